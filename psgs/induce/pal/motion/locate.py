"""Find a learned action in new motion: the time spans where its pattern recurs.

:func:`locate` slides the learned pattern of every component channel over a
new actiongram, in time, at a few tempos, and scores each place by the
agreement of the kineteme states with the pattern, corrected for chance
(Cohen's kappa, per channel, then the mean over the component channels, a
channel the new actiongram lacks counting 0). Places scoring at least
``threshold`` are occurrences; overlapping ones (the cycles of a repeated
action) merge into one span.

The pattern of a channel is its morpheme (kinetemes with typical durations)
when the induction has one; otherwise the pattern's kinetemes share the
median copy duration equally, and for a bare grammar system (no times at all)
each kineteme lasts the channel's median segment duration in the new motion.
"""

from __future__ import annotations

import numbers
import re
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ....actiongram import Actiongram
from ....errors import ValidationError
from ....model import PSGS, Nonterminal
from ...conf import check_number, plain_number
from ...results import Induction
from ..period import track_windows
from .conf import MotionConf
from .cycles import cycle_evidence, joint_period, lag_scores
from .grids import agreement_counts, grid_step, kappa, sample

__all__ = ["Located", "locate"]

#: Tempos tried, relative to the learned one (slower and quicker performances).
SCALES = (0.67, 0.8, 0.9, 1.0, 1.12, 1.25, 1.5)


@dataclass(frozen=True)
class Located:
    """One span of time where the action was found.

    Parameters
    ----------
    start, stop : float
        The span, in the actiongram's time unit (seconds for kinetology's actiongrams).
    score : float
        In [-1, 1]: how well the span agrees with what was learned (1: every state agrees).

    Examples
    --------
    >>> found = Located(1.5, 3.0, 0.8)
    >>> found.stop - found.start, found.score
    (1.5, 0.8)
    """

    start: float
    stop: float
    score: float


def locate(learned: Induction | PSGS, actiongram: Actiongram, *, threshold: float = 0.4,
           scales: tuple[float, ...] = SCALES, repeats: int | None = None,
           min_speed: float = 0.5, method: str = "auto",
           min_share: float | None = None) -> tuple[Located, ...]:
    """The time spans of ``actiongram`` where the learned action occurs.

    Parameters
    ----------
    learned : Induction or PSGS
        What an inducer learnt (its components' patterns), or a grammar system
        whose component names are the actiongram's string names made into
        identifiers (as inducers name them).
    actiongram : Actiongram
        New motion (a take not used for learning).
    threshold : float, optional
        Least chance-corrected agreement, averaged over the component
        channels, for a place to count (default 0.4).
    scales : tuple of float, optional
        Tempos tried, relative to the learned durations.
    repeats : int, optional
        Copies of the pattern in a row that a place must hold: by default 2
        for an action learnt as cycles (several copies per performance), else 1.
    min_speed : float, optional
        Where a channel moves slower than this share of its learned typical
        speed (from the morpheme's displacements), its agreement counts
        proportionally less: the same states drawn small are not the action.
    method : {"auto", "joints", "pattern"}, optional
        ``"joints"``: the evidence PAL learns by, read in the new motion: its
        cycles timed on the learned leader, each joint's repeated motion, and
        the share of it that the learned joints carry (the score; found at
        ``min_share``, default 0.4, one of them carrying at least PAL's
        ``joint_share`` of the most any joint carries, and the learned
        channels' repetition significant at PAL's ``alpha``). ``"pattern"``: the learned patterns slid over the
        new motion (``threshold``). ``"auto"`` (default): joints for an action
        learnt as cycles by joint, else pattern.
    min_share : float, optional
        For ``method="joints"``: least share of the new motion's repeated
        motion the learned joints must carry (default 0.4).

    Returns
    -------
    tuple of Located
        In time order; empty when the action is not found, and by every
        method when nothing was learnt (an induction without a component:
        no synchronised repetition) or when ``actiongram`` holds none of what
        was learnt: no string of a learned component (``method="pattern"``),
        no channel of a learned joint (``method="joints"``). A string a take
        lacks is motion that is not there (segmentation leaves out the channels
        that hardly move), so the action is not found in it, as a channel the
        take lacks counts 0 among others; comparing :func:`learned_names` with
        ``actiongram.names`` tells this case from a place that scored too low.

    Raises
    ------
    ValidationError
        With ``method="joints"``, when ``learned`` is a grammar system (it keeps no
        joints); when a scale is not finite and positive,
        ``repeats`` is below 1, or ``threshold`` (at most 1), ``min_speed`` (0 or
        more) or ``min_share`` (0 to 1) is no finite number. A tempo whose pattern is longer than the new
        motion is skipped before it is sampled (it fits nowhere).
    TypeError
        When the arguments are not of these types.

    Examples
    --------
    >>> from psgs import Actiongram
    >>> from psgs.induce import Induction
    >>> learned = Induction(None, ("a", "b"), {"a": ("x", "y"), "b": ("u", "v")},
    ...                     {"a": ((0, 2),), "b": ((0, 2),)})
    >>> new = Actiongram.from_strings({"a": "xy" * 6 + "xxxxyyyyxxxx", "b": "uv" * 6 + "u" * 12})
    >>> [(round(s.start), round(s.stop)) for s in locate(learned, new, threshold=0.6)]
    [(0, 12)]
    >>> locate(learned, Actiongram.from_strings({"q": "xy" * 6}))  # no learned string in it
    ()
    """
    if not isinstance(learned, (Induction, PSGS)):
        raise TypeError(f"locate needs an Induction or a PSGS, not {type(learned).__name__}")
    if not isinstance(actiongram, Actiongram):
        raise TypeError(f"locate needs an Actiongram, not {type(actiongram).__name__}")
    if method not in ("auto", "joints", "pattern"):
        raise ValidationError(f"method must be auto, joints or pattern, not {method!r}")
    if method == "joints" and not isinstance(learned, Induction):
        # the joints method times the learnt joints with the learner's parameters, which a
        # grammar system does not keep
        raise ValidationError("method joints reads an induction's learnt joints; a grammar "
                              "system has none (its patterns: method pattern)")
    scales = _checked_scales(scales)
    # each is read by one method only: checked for both, so a bad one is never ignored
    check_number("threshold", plain_number(threshold), high=1)  # above 1: never met
    check_number("min_speed", plain_number(min_speed), low=0)
    if min_share is not None:
        check_number("min_share", plain_number(min_share), low=0, high=1)
    if repeats is not None and (isinstance(repeats, bool)
                                or not isinstance(repeats, numbers.Integral) or repeats < 1):
        raise ValidationError(f"repeats must be a whole number of at least 1, not {repeats!r}")
    if isinstance(learned, Induction) and not learned.components:
        # nothing learnt (no synchronised repetition): found nowhere, as the joints method
        # answers an induction without actuators
        return ()
    if method == "joints" or (method == "auto" and isinstance(learned, Induction)
                              and learned.actuators and _cyclic(learned)):
        return _by_joints(learned, actiongram, min_share if min_share is not None else 0.4)
    templates = _templates(learned, actiongram)
    if not templates:
        # none of the learned strings moves in this take: not found, as the joints method
        # answers a take without the learned joints (not an error: psgs locate reads many
        # takes, and one without those channels answers "not found" like any other)
        return ()
    repeats = (2 if _cyclic(learned) else 1) if repeats is None else int(repeats)
    codes: dict[str, int] = {}
    step = grid_step((actiongram,))
    grid = sample(actiongram, codes, step)
    if repeats > grid.points:
        # more copies in a row than the new motion has sampled points: each would last less
        # than a point, so no place holds them (and the copies are not made: their number
        # is unbounded)
        return ()
    templates = {n: (syms * repeats, durs * repeats, speed)
                 for n, (syms, durs, speed) in templates.items()}
    size = len(codes) + len({s for syms, _, _ in templates.values() for s in syms})
    rows = {name: actiongram.index(name) for name in templates}
    best = np.full(grid.points, -np.inf)
    width = np.zeros(grid.points, dtype=np.int64)
    for scale in scales:
        # a template longer than the new motion fits nowhere: skip it before sampling it,
        # so that a huge tempo costs nothing (its sampled length would be unbounded)
        if max(_sampled_length(durs, scale, step) for _, durs, _ in templates.values()) \
                > grid.points:
            continue
        states = {name: _template_states(syms, durs, scale, step, codes)
                  for name, (syms, durs, _) in templates.items()}
        length = max(len(s) for s in states.values())
        if length < 2 or length > grid.points:
            continue
        total = np.zeros(grid.points - length + 1)
        for name, template in states.items():
            template = np.pad(template, (0, length - len(template)), constant_values=-1)
            curve = _kappa_curve(grid.states[rows[name]], template, size)
            typical = templates[name][2]
            if typical and min_speed > 0:  # drawn small: count in proportion
                moving = _window_sums(grid.speed[rows[name]], length) / length
                curve = curve * np.minimum(1.0, moving / (min_speed * typical * scale ** -1))
            total += curve
        score = total / len(learned_names(learned))
        better = score > best[:len(score)]
        best[:len(score)][better] = score[better]
        width[:len(score)][better] = length
    return _spans(best, width, threshold, grid.t0, step)


def learned_names(learned: Induction | PSGS) -> tuple[str, ...]:
    """The component names of ``learned`` (string names for an Induction)."""
    if isinstance(learned, Induction):
        return tuple(learned.components)
    return tuple(c.name for c in learned.components)


def _cyclic(learned) -> bool:
    """Whether the action was learnt as cycles (more copies than performances)."""
    if not isinstance(learned, Induction) or not learned.components:
        return False
    return len(learned.occurrences[learned.components[0]]) > learned.performances


def _templates(learned, actiongram: Actiongram) -> dict[str, tuple]:
    """Per component string of ``actiongram``: (kinetemes, durations, typical speed or None)."""
    if isinstance(learned, Induction):
        out = {}
        for name in learned.components:
            if name not in actiongram.names:
                continue
            morpheme = learned.morphemes.get(name)
            if morpheme is not None:
                speed = None
                if morpheme.displacements is not None:
                    speed = sum(abs(d) for d in morpheme.displacements) / sum(morpheme.durations)
                out[name] = (morpheme.kinetemes, morpheme.durations, speed)
                continue
            pattern = learned.patterns[name]
            spans = learned.occurrences.get(name, ())
            length = float(np.median([b - a for a, b in spans])) if spans else len(pattern)
            out[name] = (pattern, (length / len(pattern),) * len(pattern), None)
        return out
    if isinstance(learned, PSGS):
        if not learned.components:
            raise ValidationError("the system has no component: nothing to locate")
        by_identifier = {_identifier(n): n for n in actiongram.names}
        out = {}
        for grammar in learned.components:
            name = by_identifier.get(grammar.name, grammar.name)
            if name not in actiongram.names:
                continue
            pattern = _pattern_of(grammar)
            durs = actiongram.durations[name]
            typical = float(np.median(durs)) if durs else 1.0
            out[name] = (pattern, (typical,) * len(pattern), None)
        return out
    raise TypeError(f"locate needs an Induction or a PSGS, not {type(learned).__name__}")


def _identifier(name: str) -> str:
    """A string name as inducers name its component (before any suffix that keeps names
    unique): characters outside letters, digits and ``_`` become ``_``; ``c_`` before a digit."""
    ident = re.sub(r"[^A-Za-z0-9_]", "_", name)
    return "c_" + ident if not ident or ident[0].isdigit() else ident


def _pattern_of(grammar) -> tuple[str, ...]:
    """The terminal string of a component's pattern: S -> N (the 'last' rule), N expanded."""
    by_lhs: Mapping = grammar.rules_by_lhs
    start = grammar.start
    for rule in by_lhs.get(start, ()):
        if len(rule.rhs) == 1 and isinstance(rule.rhs[0], Nonterminal):
            return tuple(_expand(rule.rhs[0], by_lhs, 0))
    raise ValidationError(f"component {grammar.name!r} has no pattern rule S -> N")


def _expand(symbol, by_lhs, depth: int) -> list[str]:
    if not isinstance(symbol, Nonterminal):
        return [symbol.name]
    if depth > 200:
        raise ValidationError("a pattern rule nests more than 200 deep")
    rules = by_lhs.get(symbol, ())
    if not rules:
        return []
    return [t for s in rules[0].rhs for t in _expand(s, by_lhs, depth + 1)]


def _checked_scales(scales) -> tuple[float, ...]:
    """``scales`` as finite positive floats, or a :class:`ValidationError` naming the bad one."""
    try:
        values = tuple(scales)
    except TypeError:
        raise ValidationError(f"scales must be a sequence of numbers, not {scales!r}") from None
    if not values:
        raise ValidationError("scales must hold at least one tempo")
    out = []
    for value in values:
        if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
            raise ValidationError(f"a scale must be a number, not {value!r}")
        if not np.isfinite(value) or value <= 0:
            raise ValidationError(f"a scale must be finite and positive, not {value!r}")
        out.append(float(value))
    return tuple(out)


def _sampled_length(durations, scale: float, step: float) -> float:
    """How many grid points the pattern covers at tempo ``scale`` (as a float: may be huge)."""
    return float(np.sum(np.asarray(durations, dtype=float))) * scale / step


def _template_states(symbols, durations, scale: float, step: float,
                     codes: dict[str, int]) -> np.ndarray:
    """The pattern sampled every ``step`` seconds at tempo ``scale`` (state codes)."""
    ends = np.cumsum(np.asarray(durations, dtype=float) * scale)
    count = max(1, int(round(ends[-1] / step)))
    times = step * (np.arange(count) + 0.5)
    index = np.minimum(np.searchsorted(ends, times, side="right"), len(symbols) - 1)
    symbol_codes = np.array([codes.setdefault(s, len(codes)) for s in symbols], dtype=np.int64)
    return symbol_codes[index]


def _kappa_curve(row: np.ndarray, template: np.ndarray, size: int) -> np.ndarray:
    """Chance-corrected agreement of ``template`` with ``row`` at every offset (FFT)."""
    n, m = len(row), len(template)
    places = n - m + 1
    valid_t = template >= 0
    agree = np.zeros(places)
    chance = np.zeros(places)
    counted = np.maximum(_window_sums((row >= 0).astype(float), m), 1.0)
    for sym in np.unique(template[valid_t]).tolist():
        indicator = (row == sym).astype(float)
        mask = (template == sym).astype(float)
        agree += _correlate(indicator, mask)[:places]
        chance += (mask.sum() / max(valid_t.sum(), 1)) * _window_sums(indicator, m) / counted
    observed = agree / max(valid_t.sum(), 1)
    room = 1 - chance
    return np.where(room > 1e-9, (observed - chance) / np.maximum(room, 1e-9), 0.0)


def _correlate(signal: np.ndarray, kernel: np.ndarray) -> np.ndarray:
    size = 1 << int(len(signal) + len(kernel)).bit_length()
    out = np.fft.irfft(np.fft.rfft(signal, size) * np.conj(np.fft.rfft(kernel, size)), size)
    return np.round(out[:len(signal)], 9)


def _window_sums(values: np.ndarray, m: int) -> np.ndarray:
    total = np.concatenate(([0.0], np.cumsum(values)))
    return total[m:] - total[:-m]


def _spans(score: np.ndarray, width: np.ndarray, threshold: float, t0: float,
           step: float) -> tuple[Located, ...]:
    """Places at or above ``threshold``, overlapping ones merged, in seconds."""
    hits = np.flatnonzero(score >= threshold)
    out: list[list[float]] = []
    for a in hits.tolist():
        b = a + int(width[a])
        if out and a <= out[-1][1]:
            out[-1][1] = max(out[-1][1], b)
            out[-1][2] = max(out[-1][2], float(score[a]))
        else:
            out.append([a, b, float(score[a])])
    return tuple(Located(t0 + a * step, t0 + b * step, round(s, 6)) for a, b, s in out)


def _by_joints(learned: Induction, actiongram: Actiongram, min_share: float
               ) -> tuple[Located, ...]:
    """One span over the cycles of the learned leader, when the learned joints carry the
    repetition of the new motion (see :func:`locate`, ``method="joints"``)."""
    # the parameters the action was learnt with: its cycles are timed the same way here
    conf = MotionConf.of(learned.inducer, learned.params)
    codes: dict[str, int] = {}
    grid = sample(actiongram, codes, grid_step((actiongram,)))
    size = max(len(codes), 1)
    rows = {a: tuple(actiongram.index(c) for c in actiongram.channels(a))
            for a in actiongram.actuators}
    mine = tuple(r for a in learned.actuators for r in rows.get(a, ()))
    if not mine:
        return ()
    scored = lag_scores(grid, size, conf)
    lag = joint_period(scored, mine, conf)  # the learned joints' period in this motion
    if not lag or grid.points < conf.min_copies * lag:
        return ()
    segments = np.array([[len(x) for x in actiongram.symbols]], dtype=float)
    paths = np.array([grid.speed.sum(axis=1) * grid.step])
    repeated, log_p = cycle_evidence([grid], [scored], [lag], size, paths, segments)
    carried = {a: float(repeated[list(r)].sum()) for a, r in rows.items() if r}
    total = sum(carried.values())
    if total <= 0:
        return ()
    share = sum(carried.get(a, 0.0) for a in learned.actuators) / total
    top = max(carried.values())
    ours = max(carried.get(a, 0.0) for a in learned.actuators)
    # the action: its joints carry much of the repetition, one of them as a leader would
    # (at joint_share of the most), beyond chance (Bonferroni over the learned channels)
    significant = float(min(log_p[list(mine)])) + np.log10(len(mine)) <= np.log10(conf.alpha)
    if share < min_share or ours < conf.joint_share * top or not significant:
        return ()
    starts = track_windows(grid.states[list(mine)], lag)
    if len(starts) == 0:
        return ()
    # spot: only the cycles where the learned joints repeat themselves (a cycle agreeing,
    # beyond chance, with the one before or after it), consecutive ones one span; the
    # rest of the recording performs something else
    kept = _repeating(grid.states[list(mine)], starts, lag, size)
    t0, step = grid.t0, grid.step
    spans: list[list[int]] = []
    for k in np.flatnonzero(kept).tolist():
        if spans and spans[-1][1] == k - 1:
            spans[-1][1] = k
        else:
            spans.append([k, k])
    return tuple(Located(t0 + float(starts[a]) * step, t0 + float(starts[b] + lag) * step,
                         round(share, 6)) for a, b in spans)


#: Least chance-corrected agreement of a cycle with a neighbouring one for it to be
#: part of the action (the learned joints' states, cycle against cycle).
CYCLE_KAPPA = 0.3


def _repeating(states: np.ndarray, starts: np.ndarray, lag: int, size: int) -> np.ndarray:
    """Per tracked cycle: whether it is a cycle of the action.

    Each cycle's ``states`` are compared with the next one's (kappa). A cycle
    is kept when it agrees at :data:`CYCLE_KAPPA` with both neighbours (the
    recording's ends count as agreeing), or at twice that with one: a cycle
    that straddles the start or end of the action agrees only weakly with its
    one neighbour inside it, and keeping it would make the span longer than
    what is performed.
    """
    windows = states[:, starts[:, None] + np.arange(lag)]          # (rows, cycles, lag)
    count = windows.shape[1]
    if count < 2:
        return np.zeros(count, dtype=bool)
    pairs = np.swapaxes(windows, 0, 1)                            # (cycles, rows, lag)
    observed, chance, _ = agreement_counts(pairs[:-1].reshape(count - 1, -1),
                                           pairs[1:].reshape(count - 1, -1), size)
    score = kappa(observed, chance)                               # cycle k with k + 1
    before = np.concatenate([[np.inf], score])                    # cycle k with k - 1
    after = np.concatenate([score, [np.inf]])
    both = (before >= CYCLE_KAPPA) & (after >= CYCLE_KAPPA)
    strong = (np.where(np.isinf(before), -np.inf, before) >= 2 * CYCLE_KAPPA) \
        | (np.where(np.isinf(after), -np.inf, after) >= 2 * CYCLE_KAPPA)
    return both | strong
