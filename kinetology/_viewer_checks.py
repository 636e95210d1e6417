"""The argument checks of :func:`kinetology.view` and :class:`kinetology.Player`, and the
pace a GIF or MP4 can play at (``kinetology view`` checks its options here before it reads a
file; the animation writer reads the formats' limits).

Each returns the problem in words, for the caller's :class:`~kinetology.viewer.ViewError`, or
None. What worked before the checks keeps working: an infinite ``max_rate`` or ``max_frames``
(no cap), a whole-number float where a count is asked (``100.0``), numpy bools for the flags.
"""

from __future__ import annotations

import math
from numbers import Real

import numpy as np

from .motion import is_whole, shown

#: The longest a GIF shows a frame, seconds: its delay is a 16-bit count of hundredths.
GIF_LONGEST = 655.35
#: The shortest frame a GIF plays as stored, seconds: browsers show a delay under 2 hundredths
#: as 10 hundredths (a 120 fps player, stored with a delay of 0, ran at a tenth of its speed).
GIF_SHORTEST = 0.02
#: The fewest frames a second ffmpeg writes an MP4 at (measured: 1e-5 fps wrote, 1e-6 failed).
MP4_SLOWEST = 1e-5


def slowest_rate(suffix: str) -> float:
    """The fewest frames a second a ``.gif`` or ``.mp4`` plays at.

    >>> round(slowest_rate(".gif"), 6), slowest_rate(".mp4")
    (0.001526, 1e-05)
    """
    return 1 / GIF_LONGEST if suffix == ".gif" else MP4_SLOWEST


def pace_problem(frame_rate: float, ticks: int, suffix: str) -> str | None:
    """What is wrong with writing ``ticks`` frames at ``frame_rate`` as ``suffix`` (None:
    nothing): more than one frame slower than the format plays (Pillow raised an
    OverflowError for a GIF, ffmpeg failed on an MP4, each with a traceback). A single
    frame's duration shows nothing: it is written at the slowest rate the format holds.

    Examples
    --------
    >>> pace_problem(30.0, 90, ".gif") is None, pace_problem(1e-3, 1, ".gif") is None
    (True, True)
    >>> pace_problem(1e-3, 2, ".gif")[:44]
    '0.001 frames a second is slower than a .gif '
    """
    slowest = slowest_rate(suffix)
    if frame_rate >= slowest or ticks == 1:
        return None
    return (f"{frame_rate:g} frames a second is slower than a {suffix} plays (at least "
            f"{slowest:.3g}): keep more frames (a larger max rate or max frames) or write .html")


def view_problem(max_rate, max_frames, kinetemes, follow) -> str | None:
    """What is wrong with view's options, naming the one option (None: nothing)."""
    # a string or a bool would pass for a number (or fail in a comparison), NaN every test
    if isinstance(max_rate, (bool, np.bool_)) or not isinstance(max_rate, Real) or \
            not max_rate > 0:
        return f"max_rate must be a positive number (inf: no cap), not {shown(max_rate)}"
    # 1.5 kept 2 frames: a count of frames is a whole number (or inf: no cap)
    if not (is_whole(max_frames) or (isinstance(max_frames, Real) and max_frames == math.inf)) \
            or max_frames < 1:
        return f"max_frames must be a whole number of at least 1 (inf: no cap), not " \
               f"{shown(max_frames)}"
    for name, value in (("kinetemes", kinetemes), ("follow", follow)):
        if not isinstance(value, (bool, np.bool_)):  # "no" was true
            return f"{name} must be True or False, not {shown(value)}"
    return None


def panels_problem(panels, panel_type) -> str | None:
    """What is wrong with a player's panels: one or more ``panel_type`` values (None: nothing)."""
    if not (isinstance(panels, tuple) and panels
            and all(isinstance(p, panel_type) for p in panels)):
        return f"a player needs one or more Panel values, not {shown(panels)}"
    return None


def tick_problem(tick) -> str | None:
    """What is wrong with a slider step: a whole number from 0 (None: nothing)."""
    if not is_whole(tick) or tick < 0:  # -1 was frame -1
        return f"tick must be a whole number from 0, not {shown(tick)}"
    return None
