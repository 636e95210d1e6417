"""Parsing a recording into actions: a timeline of spans, each a learnt action or none.

Sliding windows (``window`` seconds long, every ``hop`` seconds) are scored by the actions'
window descriptions with the same score that ranks whole takes (the shared spread's distance
and the root drift's in each action's own spread); a Viterbi pass then
picks one action (or none) per window, paying ``switch`` per change, so one odd window does not
break a span and a span is never longer than the run of windows that carry it. Each window's
answer covers the ``hop`` around its centre, so spans follow the motion to within half a window.
A span then stands only where its windows fit its action: where fewer than ``support`` of them
pass the action's feature-group test (the test by which :func:`~praxicon.recognition.recognise`
answers a take "none of these"), the span is none of these, and so is a stretch of ``unfit``
seconds or more in which every window fails it.

>>> from kinetology import Motion, synthetic_motion
>>> import numpy as np
>>> a = [synthetic_motion(3, (0,), seed=1, noise=n) for n in (0.2, 0.5, 1.0)]
>>> b = [synthetic_motion(3, (2,), seed=2, noise=n) for n in (0.2, 0.5, 1.0)]
>>> px = describe_windows({"a": a, "b": b}, window=1.0, hop=0.5)
>>> joined = Motion(np.concatenate([a[0].values, b[1].values]), a[0].channels, 120.0)
>>> for span in parse(px, joined).spans:
...     print(span.start, span.stop, span.action)
0.0 7.625 a
7.625 8.625 None
8.625 15.866667 b
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from numbers import Real
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._arguments import kinds_of, real_number
# SUPPORT (the share of a span's windows passing its action's test) and UNFIT (the seconds of
# failing windows that are none of its actions): plain values that parse --help reads
from ._defaults import SUPPORT, UNFIT
from .description import (OWN_KINDS, DescriptionError, common_table, describe_table,
                          feature_rows, scores)
from ._description_json import WINDOWS
from .scoring import log_likelihoods, overflow_reason, probabilities, unscored
from .records import _count

__all__ = ["Span", "Timeline", "parse", "describe_windows", "windows",
           "learning_windows"]

_WINDOW = 2.0  # seconds: about two cycles of a gait or a wave
_HOP = 0.25  # seconds between window starts
_SWITCH = 10.0  # log-likelihood a change of action costs: about e^-10, a rare event


@dataclass(frozen=True)
class Span:
    """``start`` .. ``stop`` seconds performing ``action`` (None: no learnt action), ``score``
    the mean over the span's windows of the probability of that answer; a window that
    :func:`parse`'s check of its action's feature-group test answered none of these counts
    1 where it failed the test, 0 where it passed."""

    start: float
    stop: float
    action: str | None
    score: float


@dataclass(frozen=True)
class Timeline:
    """A recording parsed into spans, in time order, covering ``0 .. duration``; when
    :func:`parse` stopped at its ``max_seconds``, ``bound`` names it (``"max_seconds"``,
    else None), ``reason`` says where, and the spans cover ``0 ..`` :attr:`end` only.

    ``missing`` names the joints of the actions the spans name that the recording lacks (of
    the closest action when no span names one), as :attr:`Recognition.missing
    <praxicon.recognition.Recognition.missing>` does for a take: the windows were scored over
    the joints the recording has; ``unread`` those of their joints it has, read without some
    of their features (as :attr:`Recognition.unread
    <praxicon.recognition.Recognition.unread>`).
    """

    source: str
    duration: float
    spans: tuple[Span, ...]
    missing: tuple[str, ...] = ()
    unread: tuple[str, ...] = ()
    bound: str | None = None
    reason: str | None = None

    @property
    def end(self) -> float:
        """Where the spans end: ``duration``, or where parse stopped at its bound."""
        return self.duration if self.bound is None else self.spans[-1].stop

    def __repr__(self) -> str:  # a summary; text() has every span
        actions = {s.action for s in self.spans if s.action}
        missing = f", {_count(len(self.missing), 'joint')} missing" if self.missing else ""
        stopped = f", parsed to {self.end:.2f} s ({self.bound})" if self.bound else ""
        return (f"<Timeline {self.source!r}: {self.duration:.2f} s in "
                f"{_count(len(self.spans), 'span')} of {_count(len(actions), 'action')}"
                f"{missing}{stopped}>")

    def labels(self, times) -> list[str | None]:
        """The action at each of ``times``: a sequence of seconds, each from 0 to the
        recording's ``duration`` (a time outside it has no action: refused, as a NaN is), or
        to :attr:`end` where parse stopped at its bound (a time after it was not parsed).

        Raises
        ------
        DescriptionError
            ``times`` is no sequence, one of them is no real number (a text, a bool, a
            date), not finite, or outside the recording.
        """
        seconds = _seconds(times)
        if not np.isfinite(seconds).all():
            raise DescriptionError("times must be finite numbers of seconds")
        slack = 1e-9 * max(1.0, self.duration)  # a time summed from steps may pass the end
        outside = seconds[(seconds < -slack) | (seconds > self.end + slack)]
        if len(outside):
            raise DescriptionError(f"a time of {outside[0]:g} s: the recording's times are 0 to "
                                   f"{self.duration:g} s" + (
                                       "" if self.bound is None else
                                       f", parsed to {self.end:g} s ({self.bound})"))
        stops = np.array([s.stop for s in self.spans])
        index = np.minimum(np.searchsorted(stops, seconds, side="right"), len(self.spans) - 1)
        return [self.spans[i].action for i in index]

    def text(self) -> str:
        """One line per span: start, stop, action, score (the actions' column as wide as the
        longest name, 24 characters at least, so that the scores line up)."""
        width = max([24, *(len(s.action) for s in self.spans if s.action)])
        return "\n".join(f"{s.start:8.2f} {s.stop:8.2f}  {s.action or '-':{width}s} "
                         f"{s.score:.3f}" for s in self.spans)


def _seconds(times) -> np.ndarray:
    """``times`` as an array of floats, each a real number (not a bool, a text or a date); one
    too large for a float is inf (refused as not finite by the caller)."""
    if isinstance(times, np.ndarray) and times.ndim == 1 and times.dtype.kind in "fiu":
        return times.astype(float)
    if isinstance(times, (str, bytes)) or not isinstance(times, (Sequence, np.ndarray)):
        raise DescriptionError(f"times must be a sequence of seconds, not "
                               f"{type(times).__name__}")
    out = np.empty(len(times))
    for k, t in enumerate(times):  # ['1.5'] and datetime64 values were read as seconds
        if isinstance(t, (bool, np.bool_)) or not isinstance(t, Real):
            raise DescriptionError(f"times must be numbers of seconds, not {type(t).__name__} "
                                   f"(times[{k}])")
        try:
            out[k] = float(t)
        except OverflowError:  # an int of 400 digits
            out[k] = math.inf
    return out


def windows(motion, window: float = _WINDOW, hop: float = _HOP):
    """The motion cut into windows: ``(starts in seconds, motions)``; a motion shorter than
    one window is one window. ``motions`` is a read-only sequence whose windows are made as
    they are read (``list(motions)`` makes them all), so that a long recording is not held
    once per window.

    Examples
    --------
    >>> from kinetology import synthetic_motion
    >>> starts, cuts = windows(synthetic_motion(2, (0,), repetitions=3, seed=1), 1.0, 0.5)
    >>> starts[:3], cuts[0].duration
    ([0.0, 0.5, 1.0], 1.0)
    """
    from .recognition import _frames

    _frames(motion, "parsing")
    size = max(3, int(round(window * motion.frame_rate)))
    step = max(1, int(round(hop * motion.frame_rate)))
    if motion.frames <= size:
        return [0.0], (motion,)
    starts = list(range(0, motion.frames - size + 1, step))
    if starts[-1] != motion.frames - size:
        starts.append(motion.frames - size)
    return [s / motion.frame_rate for s in starts], _Windows(motion, tuple(starts), size)


class _Reported(Sequence):
    """``windows`` that call ``progress(k, total)`` as window ``k`` (from 1) is read."""

    def __init__(self, windows, progress) -> None:
        self._windows, self._progress = windows, progress

    def __len__(self) -> int:
        return len(self._windows)

    def __getitem__(self, index):
        window = self._windows[index]  # past the end: the IndexError that ends iteration
        if isinstance(index, int):
            self._progress(index % len(self) + 1, len(self))
        return window


class _Windows(Sequence):
    """The windows of one motion, each made when it is read: made at once, they held
    ``window / hop`` copies of the whole recording (8 at the defaults, 240 for 2-second windows
    a frame apart at 120 fps), while parse reads one at a time."""

    def __init__(self, motion, starts: tuple[int, ...], size: int) -> None:
        self._motion, self._starts, self._size = motion, starts, size

    def __len__(self) -> int:
        return len(self._starts)

    def __getitem__(self, index):
        from kinetology import Motion

        if isinstance(index, slice):
            return [self[i] for i in range(*index.indices(len(self)))]
        s, m = self._starts[index], self._motion
        # named by where it starts: what is said of it (a feature too large to compute, at a
        # frame of the window) is then found in the recording
        return Motion(m.values[s:s + self._size], m.channels, m.frame_rate, m.skeleton,
                      f"{m.source} (the window from {s / m.frame_rate:.2f} s)")


def learning_windows(motion, window: float = _WINDOW, hop: float = _HOP):
    """The windows of a take that :func:`describe_windows` learns from: they start every
    ``2 * hop`` seconds (a recording is parsed every ``hop``).

    Examples
    --------
    >>> from kinetology import synthetic_motion
    >>> take = synthetic_motion(2, (0,), repetitions=3, seed=1)  # 3 s
    >>> len(learning_windows(take, 1.0, 0.25)), len(windows(take, 1.0, 0.25)[1])
    (6, 10)
    """
    return windows(motion, window, 2 * hop)[1]


def describe_windows(takes: dict[str, list], *, window: float = _WINDOW, hop: float = _HOP):
    """Window descriptions of every action, learnt from the windows of its takes.

    The windows of a take start every ``2 * hop`` seconds; the descriptions' ``window`` is the
    window length, which :func:`parse` cuts recordings into: from 0.1 to 60 seconds
    (what a praxicon reads back).
    """
    real_number(hop, "hop", above=0.0)  # 0 or less was one window a frame, without a word
    if isinstance(window, bool) or not (isinstance(window, (int, float))
                                        and WINDOWS[0] <= window <= WINDOWS[1]):
        raise DescriptionError(f"a window of {window!r} seconds: windows are {WINDOWS[0]:g} to "
                               f"{WINDOWS[1]:g} seconds long")
    rows, sources = {}, {}
    for name, motions in takes.items():
        cuts = [(k, w) for k, m in enumerate(motions) for w in learning_windows(m, window, hop)]
        rows[name] = feature_rows([w for _, w in cuts], shape=False)
        # the takes that give windows numbered in order: a take's fold is its place among them
        number: dict[int, int] = {}
        sources[name] = np.array([number.setdefault(k, len(number)) for k, _ in cuts])
    order, table = common_table(rows)
    return describe_table(table, order, window=window, sources=sources)


def _viterbi(costs: np.ndarray, switch: float) -> np.ndarray:
    n, k = costs.shape
    total = costs[0].copy()
    back = np.zeros((n, k), dtype=int)
    for i in range(1, n):
        best = int(np.argmin(total))
        stay = total
        move = total[best] + switch
        back[i] = np.where(stay <= move, np.arange(k), best)
        total = np.minimum(stay, move) + costs[i]
    path = np.empty(n, dtype=int)
    path[-1] = int(np.argmin(total))
    for i in range(n - 1, 0, -1):
        path[i - 1] = back[i, path[i]]
    return path


def _runs(values: np.ndarray) -> list[tuple[int, int]]:
    """The runs of equal values: ``(first, stop)`` index pairs, in order.

    >>> _runs(np.array([3, 3, 1, 1, 1, 3]))
    [(0, 2), (2, 5), (5, 6)]
    """
    change = (np.flatnonzero(values[1:] != values[:-1]) + 1).tolist()
    return list(zip([0, *change], [*change, len(values)]))


def _supported(path: np.ndarray, passes: np.ndarray, none: int, support: float,
               stretch: int) -> np.ndarray:
    """``path`` (an action per window, ``none`` for none of these) with the windows that do
    not fit their action answered ``none``: every run of an action whose windows pass its
    feature-group test (``passes``, per window) in fewer than ``support`` of them, and in the
    other runs every stretch of ``stretch`` windows or more in a row that fail it.

    Examples
    --------
    >>> path = np.array([0, 0, 0, 0, 0, 0, 2, 1, 1, 1, 1])
    >>> passes = np.array([1, 0, 0, 0, 1, 1, 1, 0, 0, 0, 1], dtype=bool)
    >>> _supported(path, passes, 2, 0.5, 99).tolist()
    [0, 0, 0, 0, 0, 0, 2, 2, 2, 2, 2]
    >>> _supported(path, passes, 2, 0.5, 3).tolist()
    [0, 2, 2, 2, 0, 0, 2, 2, 2, 2, 2]
    """
    out = path.copy()
    for a, b in _runs(path):
        if path[a] == none:
            continue
        if passes[a:b].mean() < support:
            out[a:b] = none
            continue
        for first, stop in _runs(passes[a:b]):  # the run's stretches of failing windows
            if not passes[a + first] and stop - first >= stretch:
                out[a + first:a + stop] = none
    return out


def _stretch(unfit: float, starts, windows: int) -> int:
    """The windows in a row that last ``unfit`` seconds (at least one), each window's answer
    covering the hop between window starts (``hop`` rounded to whole frames), or
    ``windows + 1`` (never) when that is more windows than there are.

    Examples
    --------
    >>> _stretch(4.0, [0.0, 0.25, 0.5], 40), _stretch(4.0, [0.0, 0.2667], 40)
    (16, 15)
    >>> _stretch(1e308, [0.0, 1e-10], 40), _stretch(0.1, [0.0], 1)
    (41, 1)
    """
    hop = starts[1] - starts[0] if len(starts) > 1 else math.inf
    count = unfit / hop
    return windows + 1 if not count <= windows else max(1, math.ceil(count - 1e-9))


def parse(praxicon, motion, *, hop: float = _HOP, switch: float = _SWITCH,
          own=OWN_KINDS, support: float = SUPPORT, unfit: float = UNFIT,
          progress=None, max_seconds: float | None = None) -> Timeline:
    """The recording as a timeline of spans (see the module's description).

    Parameters
    ----------
    praxicon : Descriptions (window descriptions), a Praxicon or a folder
    motion : kinetology.Motion or path
    hop : float, default 0.25
        Seconds between windows.
    switch : float, default 10.0
        The cost of changing action, in log-likelihood (nats); ``math.inf``: the windows are
        one action (before the check of the spans).
    own : tuple of str, default ("drift",)
        Kinds of the root's features also scored in each action's own spread
        (:func:`~praxicon.description.scores`; ``()``: the shared spread alone): ``"drift"``,
        ``"energy"``, ``"excursion"``.
    support : float, default 0.25
        The share of a span's windows, 0 to 1, that must pass its action's feature-group test
        for the span to stand; a span below it is none of these.
    unfit : float, default 5.0
        Seconds: within a span that stands, a stretch at least this long in which every
        window fails the action's feature-group test is none of these (``math.inf``: none;
        with ``support=0`` as well, the windows' threshold alone answers none of these).
    progress : callable, optional
        Called ``progress(k, total)`` as the ``k``-th of the recording's ``total`` windows is
        read (their features are most of the time: about 4 ms a window of a 30 fps take of
        25 joints, so 0.9 s a minute at the default hop).
    max_seconds : float or None, default None
        The wall-clock bound, from the call on (``None``: none). Past it no more window is
        read (the first always is) and the windows read are parsed: the timeline up to there,
        its ``bound`` ``"max_seconds"`` and its ``reason`` saying where it stopped, as the
        library's searches report a bound in their result.

    Returns
    -------
    Timeline

    Notes
    -----
    The memory is linear in the recording and bounded by it (parse has no memory bound of its
    own): one row of numbers a window, 8 bytes a feature the recording has, written into one
    block (:func:`~praxicon.feature_table.feature_matrix`; the columns every window has are
    known once the last is read), scored a block of rows at a time. A rotation channel gives
    about four features: a window every 8 frames (30 fps, the default hop) holds half what the
    recording holds of that channel (8 bytes a frame), a window every 2 or 3 frames (10 fps)
    more. At its peak parse held 344 bytes a frame beyond a 30 fps Bandai recording's own
    1,056 (255 features a window every 8 frames: 255 bytes a frame of rows; 21.7 minutes),
    446 with a praxicon of two skeletons (491 features); it held 1,340 and 1,650 when the rows
    were a list, then a matrix, then its columns, and every window was scored at once.

    Raises
    ------
    DescriptionError
        As :func:`~praxicon.recognition.recognise` says it; a window's error names the
        recording and where the window starts (``FILE (the window from 1.25 s): ...``).
    OSError, MotionFormatError
        As :func:`~praxicon.recognition.recognise` raises them for a path.
    """
    from .recognition import _in_file, _Unscorable

    try:
        return _parsed(praxicon, motion, hop=hop, switch=switch, own=own, support=support,
                       unfit=unfit, progress=progress, max_seconds=max_seconds)
    except _Unscorable as exc:  # read from a folder: its descriptions' file named
        if isinstance(praxicon, (str, Path)):
            raise _in_file(exc, praxicon, windows=True) from None
        raise


#: the kinds of the root's features (:func:`~praxicon.features.motion_features`), which
#: ``own`` chooses among
_ROOT_KINDS = ("drift", "energy", "excursion")


def _parsed(praxicon, motion, *, hop=_HOP, switch=_SWITCH, own=OWN_KINDS, support=SUPPORT,
            unfit=UNFIT, progress=None, max_seconds=None, clock=None) -> Timeline:
    """:func:`parse`, the descriptions' numbers that cannot be scored with raised as an
    :class:`~praxicon.recognition._Unscorable`. ``clock``: the :class:`~psgs.budget.Budget`
    of ``max_seconds`` when the caller started it before (``psgs praxicon parse``'s covers
    reading the praxicon and the recording), else it starts here."""
    from psgs.budget import Budget, check_seconds
    from psgs.errors import ValidationError

    from .recognition import _descriptions, _excess, _joints_of, _motion, _score_model
    from .recognition import feature_matrix

    try:  # the clock starts first: the bound covers reading the praxicon and the motion too
        check_seconds(max_seconds, optional=True)
    except ValidationError as exc:  # praxicon's one error for a wrong argument
        raise DescriptionError(str(exc)) from None
    clock = Budget(max_seconds) if clock is None else clock

    # a hop of 0 or less was one window a frame, a NaN or negative switch cost a timeline of
    # nonsense, without a word (an infinite cost is allowed: the windows are one action,
    # whose span the check below may still cut where its windows do not fit it)
    real_number(hop, "hop", above=0.0)
    real_number(switch, "switch", least=0.0, most=math.inf)
    real_number(support, "support", least=0.0, most=1.0)
    real_number(unfit, "unfit", above=0.0, most=math.inf)
    own = kinds_of(own)
    unknown = [k for k in own if k not in _ROOT_KINDS]
    if unknown:  # scored as no kind, without a word
        raise DescriptionError(f"own: {unknown[0]!r} is no kind of the root's features (they "
                               f"are {', '.join(_ROOT_KINDS)})")
    if progress is not None and not callable(progress):
        raise DescriptionError(f"progress must be callable, not {type(progress).__name__}")
    descriptions = _descriptions(praxicon, windows=True)
    if not descriptions.spread.window:
        raise DescriptionError("parse needs window descriptions (describe_windows; "
                               "'psgs praxicon build' learns them)")
    motion = _motion(motion)
    window = descriptions.spread.window
    starts, cuts = windows(motion, window, hop)
    if progress is not None:
        cuts = _Reported(cuts, progress)
    columns, x, _ = feature_matrix(descriptions, _until(cuts, clock), shape=False,
                                   count=len(cuts))
    read = len(x)  # the windows read: a row each
    # past the bound, the windows read are parsed: where the next one's answer would begin
    # is where the timeline ends (the edge the whole recording's timeline has there)
    complete = read == len(starts)
    stop = motion.duration if complete else \
        (starts[read - 1] + starts[read]) / 2 + min(window, motion.duration) / 2
    starts = starts[:read]
    fitted = _score_model(descriptions, columns)
    if not fitted.compared.any():  # an action sharing none (another skeleton) is never chosen
        raise DescriptionError(f"{getattr(motion, 'source', '<motion>')}: the motion shares "
                               f"no joint with the praxicon's actions")
    spread = descriptions.spread
    with np.errstate(over="ignore", invalid="ignore"):  # an overflow: said just below
        shared, dist = scores(descriptions, x, columns, kinds=own, fitted=fitted)
    lost = np.flatnonzero(unscored(fitted, shared, dist))
    if len(lost):  # a window too large to score: no span of it can be told
        why = overflow_reason(fitted, x[lost[0]], [spread.features[c] for c in columns],
                              descriptions.names)
        raise DescriptionError(f"{getattr(motion, 'source', '<motion>')} (the window from "
                               f"{starts[lost[0]]:.2f} s): {why}")
    # "none of these" is one more state, at the threshold's distance: an action wins a window
    # only where it is nearer than that and nearer than every other action
    dist = np.concatenate([dist, np.full((len(dist), 1), spread.threshold * len(columns))],
                          axis=1)
    costs = -log_likelihoods(dist, spread.temperature, spread.tail)
    path = _viterbi(costs, switch)
    p = probabilities(dist, spread.temperature, spread.tail)
    # each window's part in its span's score: the probability of its answer
    value = p[np.arange(len(path)), path]
    if support > 0 or unfit < math.inf:
        none = len(descriptions.names)
        features = [spread.features[c] for c in columns]
        passes = np.ones(len(path), dtype=bool)
        answered = np.flatnonzero(path != none)  # the windows answered none need no test
        if len(answered):
            excess, _, _ = _excess(descriptions, features, x, path[answered], fitted,
                                   rows=answered)
            passes[answered] = excess <= 1.0
        checked = _supported(path, passes, none, support, _stretch(unfit, starts, len(path)))
        # a window the check answered none of these counts 1 where it failed the test and 0
        # where it passed (the probability of none of these there is that of the threshold,
        # about 0 where an action was nearer)
        value = np.where(checked != path, (~passes).astype(float), value)
        path = checked
    names = [*descriptions.names, None]
    half = min(window, motion.duration) / 2
    centres = np.array(starts) + half
    edges = np.concatenate([[0.0], (centres[1:] + centres[:-1]) / 2, [stop]])
    spans = [Span(round(float(edges[a]), 6), round(float(edges[b]), 6), names[path[a]],
                  round(float(value[a:b].mean()), 6)) for a, b in _runs(path)]
    named = {s.action for s in spans if s.action}
    if not named:  # no span names an action: the one closest over the windows, as recognise
        named = {names[int(np.argmax(np.where(fitted.compared, p[:, :-1].mean(axis=0), -1)))]}
    lacking = _lacking(descriptions, named, {spread.features[c] for c in columns})
    has = _joints_of(motion)  # a joint it has is not missing (its root may not move)
    bound = reason = None
    if not complete:
        bound, reason = "max_seconds", (f"stopped after {max_seconds:g} seconds (max_seconds): "
                                        f"parsed to {spans[-1].stop:.2f} s of "
                                        f"{motion.duration:.2f} s")
    return Timeline(getattr(motion, "source", "<motion>"), float(motion.duration), tuple(spans),
                    tuple(j for j in lacking if j not in has),
                    tuple(j for j in lacking if j in has), bound, reason)


def _until(cuts, clock):
    """The windows ``cuts``, in order, until ``clock`` has expired (the first always)."""
    for k in range(len(cuts)):
        if k and clock.expired():
            return
        yield cuts[k]


def _lacking(descriptions, actions, here) -> tuple[str, ...]:
    """The joints of ``actions``' features not among the features ``here`` (sorted)."""
    from .features import feature_joint

    return tuple(sorted({feature_joint(f) for a in descriptions.actions if a.name in actions
                         for f in a.features if f not in here} - {"*"}))
