"""``kinetology.read``: any supported motion file, format chosen by suffix."""

from __future__ import annotations

from pathlib import Path

from .asf import read_amc
from .bvh import read_bvh
from .motion import Motion, MotionFormatError, as_path

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

    Parameters
    ----------
    path : str or Path
        A ``.bvh`` or ``.amc`` file (the suffix in any case).
    **options
        Passed to :func:`kinetology.read_amc` (``asf=``, ``frame_rate=``) or
        :func:`kinetology.read_bvh`.

    Returns
    -------
    Motion

    Raises
    ------
    MotionFormatError
        For another suffix, a malformed file (naming ``file:line:col``), or ``frame_rate=``
        or ``asf=`` with a BVH file.
    FileNotFoundError
        When the file does not exist.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> path = Path(tempfile.mkdtemp()) / "knee.bvh"
    >>> _ = path.write_text('''HIERARCHY
    ... ROOT knee
    ... { OFFSET 0 0 0
    ...   CHANNELS 1 Xrotation
    ...   End Site
    ...   { OFFSET 0 -10 0 } }
    ... MOTION
    ... Frames: 3
    ... Frame Time: 0.0083333
    ... 0
    ... 45
    ... 90
    ... ''')
    >>> knee = read(path)
    >>> knee.channels, knee.frame_rate, knee.column("knee.rx").tolist()
    (('knee.rx',), 120.0, [0.0, 45.0, 90.0])
    >>> read(path.with_suffix(".c3d"))
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: ...knee.c3d: unknown motion format '.c3d'; expected one of .bvh, .amc
    >>> read(path, frame_rate=30)
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: ...knee.bvh: frame_rate applies to AMC files; ...
    """
    path = as_path(path)
    suffix = path.suffix.lower()
    if suffix == ".bvh":
        amc_only = sorted({"frame_rate", "asf"} & set(options))
        if amc_only:  # read_bvh's TypeError ('unexpected keyword argument') said not why
            verb = "applies" if len(amc_only) == 1 else "apply"
            raise MotionFormatError(f"{' and '.join(amc_only)} {verb} to AMC files; a BVH file "
                                    f"states its own frame time and skeleton", source=str(path))
        return read_bvh(path, **options)
    if suffix == ".amc":
        return read_amc(path, **options)
    raise MotionFormatError(f"unknown motion format {suffix or '(no suffix)'!r}; "
                            f"expected one of {', '.join(SUFFIXES)}", source=str(path))
