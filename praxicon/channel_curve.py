"""One generated channel's curve: the quartic through its knots, corrected until it segments
to the kineteme string it was built from (:func:`channel_curve`), and every channel of a
motion so, one or several at a time (:func:`channel_curves`).
"""

from __future__ import annotations

from concurrent.futures import ThreadPoolExecutor, as_completed
from dataclasses import dataclass

import numpy as np

__all__ = ["Method", "channel_curve", "channel_curves", "SMOOTH_STEPS"]

#: Kineteme changes a smooth angle can make: one sign flips, and a velocity sign flips only
#: where the acceleration pushes it that way (a maximum is G -> R, a minimum Y -> B).
SMOOTH_STEPS = frozenset({("B", "G"), ("G", "B"), ("G", "R"), ("R", "Y"), ("Y", "R"),
                          ("Y", "B")})


def _resegment(curve, rate, params, channel) -> tuple[str, ...]:
    """The kineteme string the segmentation reads from one generated channel."""
    import kinetology

    found = kinetology.segments(kinetology.Motion(curve[:, None], (channel,), rate), **params)
    return found.symbols(0) if found.channels else ()


def _fit_lengths(knots, frames: int) -> np.ndarray:
    """Segment lengths >= 1 frame adding up to ``frames - 1`` (the last frame ends the last)."""
    lengths = np.maximum(np.diff(knots), 1)
    while lengths.sum() > frames - 1 and lengths.max() > 1:  # rounding: from the longest
        lengths[int(np.argmax(lengths))] -= 1
    lengths[-1] += max(0, frames - 1 - int(lengths.sum()))
    return lengths


# minimum segment lengths (frames) tried when the learnt durations are too short for the
# changes a morpheme makes: a quiet return to zero speed before a change of both signs
# takes a few frames at any amplitude
_MINIMUM_FRAMES = (4, 8)
_HARD_FRAMES = (10, 16, 24)  # likewise for the segments beside a change of both signs
_REACH = 1.25  # a generated channel's smoothed range is at least this many times min_range


def channel_curve(knots, sequence, steps, frames, rate, params, channel):
    """One channel's curve and how it was made: the quartic alone, or with a correction.

    The quartic, jerk-minimising reconstruction of the knots is the base. When
    segmenting it again does not give ``sequence``, the correction layer
    (:func:`praxicon.shaping.shape`) moves it, as little as it can, until it does; when
    that has no answer at the learnt durations, segments shorter than a few frames
    are lengthened (frames taken from the longest segments, so the channel keeps the
    action's period) and the correction tried again.
    """
    from kinetology.codec import reconstruct
    from kinetology.segmentation import DEFAULTS, STATES, smooth

    from .shaping import lengthened, shape

    settings = {**DEFAULTS, **params}

    codes = np.array([STATES.index(k) for k in sequence], dtype=np.int8)
    knot_values = np.concatenate(([0.0], np.cumsum(steps)))
    lengths = _fit_lengths(knots, frames)
    bounds = np.concatenate(([0], np.cumsum(lengths)))
    base = reconstruct(bounds, codes, knot_values)
    # a channel whose smoothed range is under the segmentation's min_range is "still" and has
    # no kinetemes at all: such a morpheme's displacements are scaled up to 1.25 times it
    reach = float(np.ptp(smooth(base, rate, settings["smoothing"])))
    scale = 1.0
    if reach < _REACH * settings["min_range"]:
        scale = _REACH * settings["min_range"] / max(reach, 1e-9)
        knot_values = knot_values * scale
        base = reconstruct(bounds, codes, knot_values)
    want = tuple(sequence)
    if _resegment(base, rate, params, channel) == want:
        return base, Method("quartic", 0.0, 0, scale)
    status = "no answer"
    # the segments beside a change a smooth angle cannot make (SMOOTH_STEPS) are where the
    # correction needs time: lengthened first, then every segment
    steps_made = list(zip(sequence, sequence[1:]))
    hard = np.zeros(len(sequence), bool)
    for i, step in enumerate(steps_made):
        if step not in SMOOTH_STEPS:
            hard[i] = hard[i + 1] = True
    tries = [(1, None)] + [(m, hard) for m in _HARD_FRAMES if hard.any()] + \
        [(m, None) for m in _MINIMUM_FRAMES]
    for minimum, which in tries:
        if minimum > 1:
            longer = lengthened(lengths, minimum, which)
            if longer is None or np.array_equal(longer, lengths):
                continue
            bounds = np.concatenate(([0], np.cumsum(longer)))
            base = reconstruct(bounds, codes, knot_values)
        shaped = shape(base, bounds, sequence, rate, params)
        if shaped.status == "solved" and _resegment(shaped.curve, rate, params, channel) == want:
            return shaped.curve, Method("corrected", shaped.change,
                                        minimum if minimum > 1 else 0, scale)
        status = shaped.status if shaped.status != "solved" else "re-segments otherwise"
    return reconstruct(np.concatenate(([0], np.cumsum(lengths))), codes, knot_values), \
        Method(f"failed: {status}", 0.0, 0, scale)


@dataclass(frozen=True)
class Method:
    """How one generated channel was made.

    Attributes
    ----------
    kind : str
        ``"quartic"`` (the reconstruction alone re-segments exactly), ``"corrected"``
        (the correction layer was needed) or ``"failed: REASON"``.
    change : float
        Largest change of the correction, degrees (0 for the quartic alone).
    minimum_frames : int
        When segments had to be lengthened to at least this many frames; 0 otherwise.
    scale : float
        The factor the learnt displacements were multiplied by (1: as learnt), when
        the channel would otherwise move less than the segmentation's ``min_range``.

    Examples
    --------
    >>> Method("corrected", 0.4, 10)
    Method(kind='corrected', change=0.4, minimum_frames=10, scale=1.0)
    """

    kind: str
    change: float
    minimum_frames: int
    scale: float = 1.0


def channel_curves(jobs, workers: int = 1, progress=None) -> dict:
    """``{name: (curve, Method)}`` of :func:`channel_curve` for each ``(name, arguments)`` job,
    ``workers`` channels at a time.

    The channels are independent and each answer is the same however many run at once; the
    time is the correction's linear programmes, which HiGHS solves without holding Python's
    lock, so threads share the cores. ``progress(done, total, name)`` is called as each
    channel is made (in the order they finish).

    Examples
    --------
    A rise, a turn and a fall over two seconds at 30 fps: the quartic alone segments to it.

    >>> import numpy as np
    >>> job = (np.array([0, 15, 30, 45, 60]), ("B", "G", "R", "Y"),
    ...        np.array([20.0, 20.0, -20.0, -20.0]), 61, 30.0, {}, "knee.rx")
    >>> made = channel_curves([("knee.rx", job)], workers=2)
    >>> curve, method = made["knee.rx"]
    >>> curve.shape, method.kind
    ((61,), 'quartic')
    """
    out = {}
    if workers == 1:
        for name, arguments in jobs:
            out[name] = channel_curve(*arguments)
            if progress is not None:
                progress(len(out), len(jobs), name)
        return out
    with ThreadPoolExecutor(workers) as pool:
        running = {pool.submit(channel_curve, *arguments): name for name, arguments in jobs}
        try:
            for future in as_completed(running):
                out[running[future]] = future.result()
                if progress is not None:
                    progress(len(out), len(jobs), running[future])
        except BaseException:  # an error or Ctrl-C: the channels not started are not made
            pool.shutdown(wait=False, cancel_futures=True)
            raise
    return out
