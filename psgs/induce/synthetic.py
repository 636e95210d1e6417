"""The paper's synthetic evaluation, with ground truth, and harder variants.

:func:`generate` builds one seeded actiongram: ``strings`` strings over an
``alphabet`` of letters; ``patterned`` of them each repeat a different
template (chosen among ``templates`` random templates of ``template_length``
symbols) ``copies`` times, every copy followed by ``gap`` random symbols; the
other strings are random. Noise replaces ``round(noise * n)`` symbols of each
patterned string (n its length) by random ones.

Equal neighbours: actiongrams merge adjacent equal symbols, so the generator
never produces them -- every random symbol (in random strings, in gaps, and
every noise replacement) is drawn among the letters that differ from both its
neighbours, and templates have no equal neighbours nor equal first and last
symbols. Every string therefore keeps exactly its number of segments, and a
noise replacement always changes the symbol.

Copies are synchronous across the patterned strings: copy k occupies the same
time window in every one of them. Variants (keyword arguments):

- ``durations="random"``: segment durations are random (0.5 to 1.5 time
  units); inside each copy window the template symbols of every patterned
  string share the window's time, each with its own random durations;
- ``irregular_gaps=True``: the gap after each copy has 1 to 4 symbols (the
  same time span in every patterned string), so copies are not evenly spaced;
- ``unequal_lengths=True``: every string gets 0 to 30 extra random symbols
  at its end, and random strings have 70 to 130 symbols;
- ``patterned=0``: an all-random actiongram (the right answer: no component).

:func:`success` is the paper's criterion: exactly the patterned strings are
the components and each one's pattern *is* its template, symbol for symbol
(not up to rotation: the random gap symbols mark where a copy starts).

:func:`vote_margin` measures the information ceiling of one actiongram: read
at the true copy windows, how far the true symbol leads the most frequent
wrong one at the worst template position. Where a wrong symbol outnumbers the
true one (a negative margin), no vote over the copies can recover the
template; at a tie only luck can.
"""

from __future__ import annotations

import numbers
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

from ..actiongram import Actiongram
from ..errors import ValidationError
from .conf import check_number, plain_number

__all__ = ["Synthetic", "generate", "success", "vote_margin", "PAPER_POINTS", "MAX_SYMBOLS"]

#: The paper's reported success rates (noise level -> share of actiongrams).
PAPER_POINTS = MappingProxyType({0.0: 1.0, 0.07: 1.0, 0.10: 0.96})  # read-only: shared
#: The most symbols :func:`generate` draws (letters, templates and strings together): a
#: hundred times the largest benchmark's actiongram, so a mistyped size is an error, not a
#: machine out of memory.
MAX_SYMBOLS = 100_000_000


@dataclass(frozen=True)
class Synthetic:
    """A generated actiongram with its ground truth (a value: the mappings are read-only).

    Parameters
    ----------
    actiongram : Actiongram
        The generated strings.
    components : tuple of str
        The names of the patterned strings.
    patterns : mapping of str to tuple of str
        Patterned string -> its template.
    windows : tuple of (float, float)
        The time window of each copy (the same in every patterned string).
    params : mapping, optional
        The arguments of :func:`generate` that made it.

    Examples
    --------
    >>> case = generate(seed=2)
    >>> case.windows[:2]
    ((0.0, 8.0), (10.0, 18.0))
    """

    actiongram: Actiongram
    components: tuple[str, ...]
    patterns: Mapping[str, tuple[str, ...]]
    windows: tuple[tuple[float, float], ...]
    params: Mapping[str, object] = field(default_factory=dict)

    def __post_init__(self) -> None:
        object.__setattr__(self, "components", tuple(self.components))
        object.__setattr__(self, "patterns", MappingProxyType(
            {k: tuple(v) for k, v in self.patterns.items()}))
        object.__setattr__(self, "windows", tuple(tuple(w) for w in self.windows))
        object.__setattr__(self, "params", MappingProxyType(dict(self.params)))

    def __reduce__(self):
        # read-only views do not pickle; rebuild from plain dicts
        return (type(self), (self.actiongram, self.components, dict(self.patterns),
                             self.windows, dict(self.params)))


def _letters(count: int) -> list[str]:
    if count <= 26:
        return [chr(ord("a") + k) for k in range(count)]
    return [f"s{k}" for k in range(count)]


def _pick(rng: np.random.Generator, size: int, avoid: tuple[int, ...]) -> int:
    """A random letter differing from every code in ``avoid`` (None entries ignored)."""
    while True:  # rejection keeps every allowed letter equally likely
        k = int(rng.integers(size))
        if k not in avoid:
            return k


def _template(rng: np.random.Generator, size: int, length: int) -> list[int]:
    while True:
        out = [int(rng.integers(size))]
        for _ in range(length - 1):
            out.append(_pick(rng, size, (out[-1],)))
        if length < 2 or out[0] != out[-1]:
            return out


def _random_string(rng: np.random.Generator, size: int, length: int) -> list[int]:
    """Uniform random letters, each differing from the one before it."""
    if length <= 0:
        return []
    steps = rng.integers(1, size, size=length)
    steps[0] = rng.integers(size)
    return (np.cumsum(steps) % size).tolist()


def _split(rng: np.random.Generator, total: float, parts: int, random: bool) -> list[float]:
    if not random:
        return [total / parts] * parts
    weights = rng.uniform(0.5, 1.5, size=parts)
    return list(weights / weights.sum() * total)


def generate(seed: int, noise: float = 0.0, *, strings: int = 20, alphabet: int = 20,
             patterned: int = 4, templates: int = 8, template_length: int = 8, copies: int = 10,
             gap: int = 2, durations: str = "unit", irregular_gaps: bool = False,
             unequal_lengths: bool = False) -> Synthetic:
    """One synthetic actiongram with ground truth; the same arguments give the same value.

    The defaults are the paper's protocol: 20 strings of 100 unit
    segments, 20 letters, 4 patterned strings from 4 of 8 templates of 8
    symbols repeated 10 times, each copy followed by 2 random symbols. The
    module docstring describes the variants.

    Parameters
    ----------
    seed : int
        A non-negative integer; the structure and the noise come from separate
        streams of it, so the same seed gives the same strings at every noise level.
    noise : float, optional
        Share (0 to 1) of each patterned string's symbols replaced by random ones.
    strings, alphabet, patterned, templates, template_length, copies, gap : int, optional
        The protocol's sizes (defaults: 20, 20, 4, 8, 8, 10, 2).
    durations : {"unit", "random"}, optional
        Unit segment durations, or random ones (0.5 to 1.5) within each copy window.
    irregular_gaps : bool, optional
        1 to 4 random symbols after each copy instead of ``gap``.
    unequal_lengths : bool, optional
        0 to 30 extra random symbols at the end of every string; random
        strings of 70 to 130 symbols.

    Returns
    -------
    Synthetic
        The actiongram, the patterned strings (``components``), their
        templates (``patterns``), the copy windows and the arguments.

    Raises
    ------
    ValidationError
        For a negative or non-integer seed, noise outside 0..1, a size that is not a
        whole number, more patterned strings than strings or templates, sizes for
        which no string can be drawn (fewer than 4 letters, ...), or sizes that make
        more than :data:`MAX_SYMBOLS` symbols.

    Examples
    --------
    >>> case = generate(seed=1, noise=0.1)
    >>> len(case.actiongram), case.components
    (20, ('s04', 's11', 's13', 's18'))
    >>> len(case.patterns["s04"]), generate(seed=1, noise=0.1) == case
    (8, True)
    """
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise ValidationError(f"seed must be a non-negative integer, not {seed!r}")
    check_number("noise", plain_number(noise), low=0, high=1)
    sizes = dict(strings=strings, alphabet=alphabet, patterned=patterned, templates=templates,
                 template_length=template_length, copies=copies, gap=gap)
    for name, value in sizes.items():
        check_number(name, plain_number(value), low=0, integer=True)
    for name, flag in (("irregular_gaps", irregular_gaps), ("unequal_lengths", unequal_lengths)):
        # 0 and 1 are flags too (they were read as such before the check), "yes" is not
        if not isinstance(flag, (bool, np.bool_, numbers.Integral)) or flag not in (0, 1):
            raise ValidationError(f"{name} must be True or False, not {flag!r}")
    # what the draw holds at once: the letters, the templates and every string's symbols
    symbols = (alphabet + templates * template_length + strings * max(
        copies * (template_length + (4 if irregular_gaps else gap)), 130))
    if symbols > MAX_SYMBOLS:
        raise ValidationError(f"these sizes make about {symbols:.3g} symbols, more than "
                              f"{MAX_SYMBOLS:,} (MAX_SYMBOLS)")
    if patterned > min(strings, templates):
        raise ValidationError("patterned must not exceed strings or templates")
    if durations not in ("unit", "random"):
        raise ValidationError(f"durations must be 'unit' or 'random', not {durations!r}")
    # a noise replacement must differ from the symbol and both neighbours: 4 letters at least,
    # or the draw could never end
    if alphabet < 4 or template_length < 1 or copies < 1 or gap < (0 if not irregular_gaps else 1):
        raise ValidationError("alphabet >= 4, template_length >= 1, copies >= 1, gap >= 0 "
                              "required")
    if template_length == 1 and gap == 0 and not irregular_gaps and copies > 1:
        raise ValidationError("a 1-symbol template needs gap >= 1 (back-to-back copies would "
                              "merge)")
    # separate streams: the same seed gives the same strings at every noise level
    structure_seed, noise_seed = np.random.SeedSequence(seed).spawn(2)
    rng = np.random.default_rng(structure_seed)
    noise_rng = np.random.default_rng(noise_seed)
    letters = _letters(alphabet)
    pool = [_template(rng, alphabet, template_length) for _ in range(templates)]
    chosen_strings = sorted(rng.choice(strings, size=patterned, replace=False).tolist())
    chosen_templates = rng.choice(templates, size=patterned, replace=False).tolist()
    gaps = [int(rng.integers(1, 5)) if irregular_gaps else gap for _ in range(copies)]
    random_durs = durations == "random"

    # the shared timeline: copy k's window, then its gap
    windows, gap_spans, t = [], [], 0.0
    for k in range(copies):
        width = float(template_length)
        windows.append((t, t + width))
        t += width
        gap_spans.append((t, t + gaps[k]))
        t += gaps[k]
    span = t

    names = [f"s{i + 1:02d}" for i in range(strings)]
    rows: dict[str, list[int]] = {}
    row_durations: dict[str, list[float]] = {}
    truth: dict[str, tuple[str, ...]] = {}
    for i, name in enumerate(names):
        if i in chosen_strings:
            template = pool[chosen_templates[chosen_strings.index(i)]]
            codes: list[int] = []
            durs: list[float] = []
            for k in range(copies):
                codes.extend(template)
                durs.extend(_split(rng, windows[k][1] - windows[k][0], len(template), random_durs))
                fillers = []
                for g in range(gaps[k]):
                    nxt = template[0] if (k + 1 < copies and g == gaps[k] - 1) else None
                    fillers.append(_pick(rng, alphabet, (fillers[-1] if fillers else codes[-1],
                                                         nxt)))
                codes.extend(fillers)
                if gaps[k]:
                    durs.extend(_split(rng, gap_spans[k][1] - gap_spans[k][0], gaps[k],
                                       random_durs))
            truth[name] = tuple(letters[c] for c in template)
            n_noise = round(noise * len(codes))
            for pos in sorted(noise_rng.choice(len(codes), size=n_noise, replace=False).tolist()):
                left = codes[pos - 1] if pos > 0 else None
                right = codes[pos + 1] if pos + 1 < len(codes) else None
                codes[pos] = _pick(noise_rng, alphabet, (codes[pos], left, right))
        else:
            length = int(rng.integers(70, 131)) if unequal_lengths else int(round(span))
            codes = _random_string(rng, alphabet, length)
            if random_durs:
                durs = list(rng.uniform(0.5, 1.5, size=length))
            else:
                durs = [1.0] * length
        if unequal_lengths:
            extra = int(rng.integers(0, 31))
            for _ in range(extra):
                codes.append(_pick(rng, alphabet, (codes[-1] if codes else None,)))
            durs.extend(rng.uniform(0.5, 1.5, size=extra) if random_durs else [1.0] * extra)
        rows[name] = codes
        row_durations[name] = [float(d) for d in durs]

    ag = Actiongram.from_strings({n: [letters[c] for c in rows[n]] for n in names},
                                 durations=row_durations)
    params = dict(seed=seed, noise=noise, strings=strings, alphabet=alphabet, patterned=patterned,
                  templates=templates, template_length=template_length, copies=copies, gap=gap,
                  durations=durations, irregular_gaps=irregular_gaps,
                  unequal_lengths=unequal_lengths)
    components = tuple(names[i] for i in chosen_strings)
    return Synthetic(ag, components, {n: truth[n] for n in components}, tuple(windows), params)


def success(induction, truth: Synthetic) -> bool:
    """The paper's criterion: exactly the patterned strings, each pattern equal to its template.

    Parameters
    ----------
    induction : Induction
        What an inducer learnt from ``truth.actiongram`` (anything with
        ``components`` and ``patterns`` will do).
    truth : Synthetic
        The generated case.

    Returns
    -------
    bool
        True when the components are exactly the patterned strings and each
        pattern is its template symbol for symbol (not up to rotation).

    Examples
    --------
    >>> from psgs.induce import PAL, Sequential
    >>> case = generate(seed=1)
    >>> success(PAL().induce(case.actiongram), case)
    True
    >>> success(Sequential().induce(case.actiongram), case)  # it keeps random strings too
    False
    """
    _require_truth(truth)
    if set(induction.components) != set(truth.components):
        return False
    return all(tuple(induction.patterns[n]) == truth.patterns[n] for n in truth.components)


def vote_margin(truth: Synthetic) -> int:
    """The information ceiling of one actiongram: the true symbol's worst lead over a wrong one.

    Every patterned string is read at the true copy windows (its symbols from
    each window's start, as many as the template has); at each template
    position the copies' symbols are counted. The margin is the least, over
    the patterned strings and positions, of the true symbol's count minus
    the count of the most frequent other symbol. Negative: a wrong symbol
    outnumbers the true one somewhere, and a plurality vote over the copies,
    however well they are located, gives a wrong pattern; 0: a tie somewhere;
    positive: every position is recoverable by a vote.

    Parameters
    ----------
    truth : Synthetic
        A generated case (any variant).

    Returns
    -------
    int
        The margin; the number of copies for an actiongram without patterned
        strings (nothing to recover).

    Examples
    --------
    >>> vote_margin(generate(seed=1))  # no noise: all 10 copies agree everywhere
    10
    >>> vote_margin(generate(seed=1, noise=0.4)) < 10
    True
    """
    _require_truth(truth)
    ag = truth.actiongram
    copies = len(truth.windows)
    worst = copies
    window_starts = np.asarray([w[0] for w in truth.windows])
    for name in truth.components:
        template = truth.patterns[name]
        symbols = ag.string(name)
        index = ag.index(name)
        starts = ag.origins[index] + np.concatenate(
            ([0.0], np.cumsum(ag.segment_durations[index])[:-1]))
        # the first symbol of each copy starts at its window (up to rounding)
        first = np.searchsorted(starts, window_starts - 1e-9)
        for offset, true in enumerate(template):
            counts: dict[str, int] = {}
            for k in first.tolist():
                if k + offset < len(symbols):
                    sym = symbols[k + offset]
                    counts[sym] = counts.get(sym, 0) + 1
            wrong = max((c for sym, c in counts.items() if sym != true), default=0)
            worst = min(worst, counts.get(true, 0) - wrong)
    return worst


def _require_truth(truth: object) -> None:
    if not isinstance(truth, Synthetic):  # an AttributeError from inside otherwise
        raise ValidationError(f"truth must be a Synthetic (from generate), not "
                              f"{type(truth).__name__}")
