"""The ``--frame-rate`` option as every kinetology command reads it: a rate for an AMC file
(AMC files do not state theirs), an error with any other file (a BVH file states its own
frame time), so that no command ignores it in silence.

Its own module below the commands, so that ``kinetology view`` and the other commands share
it without importing one another.
"""

from __future__ import annotations

from pathlib import Path

from .motion import MotionFormatError

__all__ = ["frame_rate_options"]


def frame_rate_options(args, path: str) -> dict:
    """``read``'s options for ``path``: ``--frame-rate`` for an AMC file; with any other file
    an error rather than silently ignored (a BVH file states its own frame time).

    Examples
    --------
    >>> from argparse import Namespace
    >>> frame_rate_options(Namespace(frame_rate=60.0), "walk.amc")
    {'frame_rate': 60.0}
    >>> frame_rate_options(Namespace(frame_rate=None), "walk.bvh")
    {}
    """
    rate = getattr(args, "frame_rate", None)
    if rate is None:
        return {}
    if Path(path).suffix.lower() != ".amc":
        raise MotionFormatError("--frame-rate applies to AMC files; a BVH file states its own "
                                "frame time", source=path)
    return {"frame_rate": rate}
