"""Performances: one :class:`~kinetology.motion.Motion` per performance of an action.

An action is learned from several performances of it, each kept apart (never joined into
one stream): takes in separate files, or labelled spans of one take. :func:`cut` takes a
time span out of a motion; :func:`performances` gathers them from files or from spans.
"""

from __future__ import annotations

from numbers import Real
from os import PathLike
from pathlib import Path
from typing import Iterable

import numpy as np

from psgs.errors import NotFound, ValidationError

from .labels import Span
from .motion import Motion, MotionFormatError, check_motion, check_number, check_rate

__all__ = ["cut", "performances", "from_files", "from_spans", "segment_performances",
           "overshoot", "OVERSHOOT"]


def cut(motion: Motion, start: float | None = None, stop: float | None = None) -> Motion:
    """The frames of ``motion`` from ``start`` to ``stop`` seconds (a new motion).

    Parameters
    ----------
    motion : Motion
        The take.
    start, stop : float, optional
        Seconds from the first frame; default the start and the end of the take. Frame ``i``
        is at ``i / frame_rate``; the cut keeps frames with ``start <= t < stop`` (rounded to
        the nearest frame), so cuts at the borders of adjacent spans share no frame.

    Returns
    -------
    Motion
        Same channels, frame rate and skeleton; ``meta["cut"]`` holds ``(start, stop)``
        in seconds of the original take.

    Raises
    ------
    ValueError
        ``start`` or ``stop`` outside the take, or ``stop <= start`` (the message gives the
        take's length).

    Examples
    --------
    >>> import numpy as np
    >>> m = Motion(np.arange(10.0)[:, None], ("knee.rx",), 10.0)
    >>> cut(m, 0.2, 0.5).column("knee.rx")
    array([2., 3., 4.])
    """
    check_motion(motion)
    check_window(start, stop)
    length = motion.duration
    begin = 0.0 if start is None else float(start)
    end = length if stop is None else float(stop)
    where = f"the take {motion.source} ({length:g} s, 0 to {length:g})"
    tolerance = 0.5 / motion.frame_rate  # half a frame: label spans are rounded to frames
    if begin < 0 or begin >= length:
        raise ValidationError(f"start {begin:g} s is outside {where}")
    if end > length + tolerance or end <= 0:
        raise ValidationError(f"stop {end:g} s is outside {where}")
    if end <= begin:
        raise ValidationError(f"stop {end:g} s is not after start {begin:g} s")
    first = int(round(begin * motion.frame_rate))
    last = min(motion.frames, int(round(end * motion.frame_rate)))
    if last <= first:
        raise ValidationError(f"{begin:g}..{end:g} s holds no frame at {motion.frame_rate:g} fps")
    offset = motion.meta.get("cut", (0.0, length))[0]
    meta = {**motion.meta, "cut": (offset + first / motion.frame_rate,
                                   offset + last / motion.frame_rate)}
    return Motion(motion.values[first:last], motion.channels, motion.frame_rate,
                  motion.skeleton, motion.source, meta)


def check_window(start, stop) -> None:
    """A :class:`ValidationError` unless ``start`` and ``stop`` are each None or a number of
    seconds: what :func:`cut` refuses without the take (the rest depends on its length), so
    that the command line refuses it before reading the take.

    Examples
    --------
    >>> check_window(1.5, None)
    >>> check_window(float("nan"), None)
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: start and stop must be numbers, not nan, None
    """
    for name, value in (("start", start), ("stop", stop)):  # float("2") and True would pass
        if value is not None and (isinstance(value, bool) or not isinstance(value, Real)):
            raise ValidationError(f"{name} must be a number of seconds, not {value!r}")
    if any(value is not None and float(value) != float(value) for value in (start, stop)):
        raise ValidationError(f"start and stop must be numbers, not {start!r}, {stop!r}")  # NaN


def from_files(paths: Iterable[str | Path], **options) -> tuple[Motion, ...]:
    """One performance per file (each file one take), read by :func:`kinetology.read`.

    Parameters
    ----------
    paths : iterable of str or Path
        Motion files (``.bvh``, ``.amc``).
    **options
        Passed to the reader (``frame_rate=`` for AMC, ...).

    Returns
    -------
    tuple of Motion

    Raises
    ------
    MotionFormatError, FileNotFoundError
        As :func:`kinetology.read`.

    Examples
    --------
    >>> from_files([])
    ()
    """
    from .readers import read

    return tuple(read(p, **options) for p in paths)


#: How far, in seconds, labels may reach past the end of their take (at least; see
#: :func:`overshoot`): the labels' own rounding, not labels of another take. CMU mocap6 labels
#: one block of 12 frames at a time and its truelabels run up to one block (0.1 s) past their
#: takes; the Bandai Namco JSON spans end within 0.05 s of theirs.
OVERSHOOT = 0.15


def overshoot(motion: Motion) -> float:
    """Seconds labels may reach past the end of ``motion``: :data:`OVERSHOOT`, or one label
    block of 12 frames when that is longer (a take read at a lower frame rate).

    Parameters
    ----------
    motion : Motion
        The take.

    Returns
    -------
    float

    Examples
    --------
    >>> import numpy as np
    >>> overshoot(Motion(np.zeros((4, 1)), ("knee.rx",), 120.0))
    0.15
    >>> overshoot(Motion(np.zeros((4, 1)), ("knee.rx",), 30.0))
    0.4
    """
    from .labels import FRAMES_PER_LABEL

    return max(OVERSHOOT, FRAMES_PER_LABEL / motion.frame_rate)


def from_spans(motion: Motion, spans: Iterable[Span], label: str | None = None, *,
               min_seconds: float = 0.0, source: str | None = None) -> tuple[Motion, ...]:
    """One performance per labelled span of one take.

    Spans may reach up to :func:`overshoot` seconds past the end of the take (the labels'
    rounding): they are cut at its end, and a span lying wholly in that margin, which holds
    no frame, is left out. Labels reaching further are of another take: an error.

    Parameters
    ----------
    motion : Motion
        The take the spans label.
    spans : iterable of Span
        From :func:`kinetology.labels.read_cmu_truelabels` or
        :func:`~kinetology.labels.read_bandai_json`.
    label : str, optional
        Keep only spans with this label (default: all).
    min_seconds : float
        Leave out spans shorter than this.
    source : str, optional
        The label file the spans come from, named in the error.

    Returns
    -------
    tuple of Motion
        In time order; each ``meta`` has ``"label"`` and ``"cut"``.

    Raises
    ------
    MotionFormatError
        A span reaching more than :func:`overshoot` seconds past the end of the take (the
        message names ``source``, the time reached and the take's duration).

    Examples
    --------
    >>> import numpy as np
    >>> m = Motion(np.zeros((30, 1)), ("knee.rx",), 10.0)
    >>> spans = [Span("a", 0.0, 1.0), Span("b", 1.0, 2.0), Span("a", 2.0, 3.0)]
    >>> [p.frames for p in from_spans(m, spans, "a")]
    [10, 10]
    >>> from_spans(m, [Span("a", 0.0, 4.5)], source="labels.txt")
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: labels.txt: the labels reach 4.5 s, past the end of the take <motion> (3 s; 1.2 s past it at most): labels of another take?
    """
    check_number(min_seconds, "min_seconds")  # NaN kept no span, without a word
    spans = tuple(spans)
    for span in spans:
        if not isinstance(span, Span):
            raise ValidationError(f"spans must hold Span values, not {type(span).__name__}")
    _check_reach(motion, spans, source)
    out = []
    for span in spans:
        if span.start >= motion.duration:  # in the rounding margin past the end: no frame
            continue
        if (label is None or span.label == label) and span.duration >= min_seconds:
            part = cut(motion, span.start, min(span.stop, motion.duration))
            out.append(Motion(part.values, part.channels, part.frame_rate, part.skeleton,
                              part.source, {**part.meta, "label": span.label}))
    return tuple(out)


def _check_reach(motion: Motion, spans: tuple[Span, ...], source: str | None) -> None:
    """Refuse spans reaching past the take by more than its rounding margin: they label
    another, longer take, and cutting them at this one's end would lose that unseen."""
    reach = max((span.stop for span in spans), default=0.0)
    margin = overshoot(motion)
    if reach > motion.duration + margin:
        raise MotionFormatError(
            f"the labels reach {reach:g} s, past the end of the take {Path(motion.source).name} "
            f"({motion.duration:g} s; {margin:g} s past it at most): labels of another take?",
            source=source or "the spans")


def performances(*sources, spans: Iterable[Span] | None = None, label: str | None = None,
                 min_seconds: float = 0.0) -> tuple[Motion, ...]:
    """Performances from files (one take each) or from the labelled spans of one take.

    ``performances("a.bvh", "b.bvh")`` reads each file as one performance (a
    :class:`Motion` is taken as it is). ``performances("take.amc", spans=spans,
    label="Squat")`` cuts the spans labelled ``Squat`` out of the one take.

    Parameters
    ----------
    *sources : str, Path or Motion
        The takes.
    spans : iterable of Span, optional
        Labelled spans of the one take (see :func:`from_spans`).
    label : str, optional
        With ``spans``: only spans with this label.
    min_seconds : float
        With ``spans``: leave out shorter spans.

    Returns
    -------
    tuple of Motion

    Raises
    ------
    ValueError
        ``spans`` with more than one source, or a span outside the take.

    Examples
    --------
    >>> import numpy as np
    >>> m = Motion(np.zeros((30, 1)), ("knee.rx",), 10.0)
    >>> len(performances(m, m)), len(performances(m, spans=[Span("a", 0.5, 2.0)]))
    (2, 1)
    """
    from .readers import read

    for source in sources:
        if not isinstance(source, (Motion, str, PathLike)):
            raise ValidationError(f"a performance is a Motion or a file's path, not "
                                  f"{type(source).__name__}")
    motions = [s if isinstance(s, Motion) else read(s) for s in sources]
    if spans is None:
        return tuple(motions)
    if len(motions) != 1:
        raise ValidationError(f"spans label one take; got {len(motions)} sources")
    return from_spans(motions[0], spans, label, min_seconds=min_seconds)


def segment_performances(motions, channels=None, *, engine: str = "auto", **params) -> tuple:
    """One :class:`psgs.Actiongram` per performance, all with the same strings.

    A channel still in one take may move in another; a learner compares the performances
    string by string, so every actiongram gets every channel that moves (at least
    ``min_range``) in *any* of the performances, in the first motion's channel order.

    Parameters
    ----------
    motions : sequence of Motion
        The performances (same channel names; a channel missing from one is an error).
    channels : sequence of str, optional
        Channels to consider (default: every angle channel).
    engine : {"auto", "numpy", "numba"}, default "auto"
        The implementation, as for :func:`kinetology.segments` (the same output with each).
    **params
        Segmentation parameters, as for :func:`kinetology.segment`.

    Returns
    -------
    tuple of psgs.Actiongram

    Raises
    ------
    KeyError
        A channel of the union is missing from one of the motions (named).
    ValueError
        An unknown ``engine`` (or a bad segmentation parameter, as for ``segment``).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(120) / 30
    >>> a = Motion(np.stack([20 * np.sin(2 * np.pi * t), 0 * t], 1), ("arm.rx", "leg.rx"), 30)
    >>> b = Motion(np.stack([20 * np.sin(2 * np.pi * t), 5 * t], 1), ("arm.rx", "leg.rx"), 30)
    >>> [ag.names for ag in segment_performances([a, b])]
    [('arm.rx', 'leg.rx'), ('arm.rx', 'leg.rx')]
    """
    from ._engines import select
    from .segmentation import _check, _segmentation, _smoothed

    if isinstance(motions, Motion) or not isinstance(motions, Iterable):
        raise ValidationError(f"motions must be a sequence of Motion values, not "
                              f"{type(motions).__name__}")
    motions = tuple(motions)
    for motion in motions:
        if not isinstance(motion, Motion):
            raise ValidationError(f"motions must hold Motion values, not {type(motion).__name__}")
    if not motions:
        return ()
    use = select(engine, sum(m.values.size for m in motions))
    p = _check(params)
    # each take smoothed once: the channels that move anywhere are then segmented from the
    # same smoothed values (a channel's segments do not depend on the other channels)
    smoothed = [_smoothed(motion, channels, p, use) for motion in motions]
    # the check segments() makes, naming the take: values whose velocities overflow read as
    # still segments, and several files wrote what one file was refused for
    for motion, (_, values) in zip(motions, smoothed):
        check_rate(values, motion.frame_rate, motion.source)
    moving: set[str] = set()
    for motion, (names, values) in zip(motions, smoothed):
        if motion.frames:
            moving.update(n for n, r in zip(names, use.row_ranges(values))
                          if r >= p["min_range"])
    order = list(motions[0].channels if channels is None else channels)
    union = [c for c in order if c in moving]
    out = []
    for motion, (names, values) in zip(motions, smoothed):
        present = set(motion.channels)
        lacking = [n for n in union if n not in present] if channels is None else []
        if lacking:  # no channel was asked for: the takes differ, no name was misspelt
            more = f" and {len(lacking) - 3} more" if len(lacking) > 3 else ""
            raise NotFound(f"the motions have different channels: {motion.source} lacks "
                           f"{', '.join(lacking[:3])}{more} of {motions[0].source} (performances "
                           f"of one action need the same channels)")
        for name in union:
            motion.index(name)  # KeyError naming a channel this take lacks
        rows = {n: i for i, n in enumerate(names)}
        picked = values[[rows[n] for n in union]] if all(n in rows for n in union) else \
            _smoothed(motion, union, p, use)[1]
        kept = np.full(len(union), motion.frames > 0)  # an empty take keeps none, as before
        out.append(_segmentation(motion, union, picked, kept, p, use).to_actiongram())
    return tuple(out)
