"""``kinetology.read``: any supported motion file, format chosen by suffix."""

from __future__ import annotations

from pathlib import Path

from .asf import read_amc
from .bvh import read_bvh
from .motion import Motion, MotionFormatError

__all__ = ["read", "SUFFIXES"]

SUFFIXES = (".bvh", ".amc")


def read(path: str | Path, **options) -> Motion:
    """Read a ``.bvh`` or ``.amc`` file into a :class:`Motion`.

    An AMC file finds its ASF beside it (``01_01.amc`` -> ``01.asf``, else the
    only ``.asf`` in its folder) and reads without one too (joint angles, no
    skeleton). ``options`` go to the reader (``asf=``, ``frame_rate=`` for
    AMC, whose files do not state their rate: 120 fps, the CMU rate, by
    default). A missing file raises ``FileNotFoundError``; a malformed one
    :class:`MotionFormatError` naming ``file:line:col``.
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix == ".bvh":
        return read_bvh(path, **options)
    if suffix == ".amc":
        return read_amc(path, **options)
    raise MotionFormatError(f"unknown motion format {suffix or '(no suffix)'!r}; "
                            f"expected one of {', '.join(SUFFIXES)}", source=str(path))
