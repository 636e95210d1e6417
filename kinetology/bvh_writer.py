"""Writing a :class:`~kinetology.motion.Motion` as a BVH (Biovision hierarchy) file.

The inverse of :func:`kinetology.read_bvh`: the skeleton's joints in their
depth-first order, each with its ``OFFSET`` and its channels in the order the
motion lists them (``joint.tx`` -> ``Xposition``, ``joint.rz`` ->
``Zrotation``), end sites as ``End Site``, then one line per frame. Values are
written with six decimals, so every angle reads back within 0.5e-6 degrees.

A motion without a skeleton (an AMC file read without its ASF) is written on a
*star* skeleton: every joint a child of the first one, at a zero offset, so
that the angles survive (any BVH reader reads them) though forward kinematics
means nothing. ASF skeletons hold a fixed pre-rotation per bone (``axis``),
which BVH cannot express: writing one is a ``ValueError``.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .motion import Joint, Motion, Skeleton

__all__ = ["write_bvh", "format_bvh", "star_skeleton"]

_AXIS_NAMES = {"tx": "Xposition", "ty": "Yposition", "tz": "Zposition",
               "rx": "Xrotation", "ry": "Yrotation", "rz": "Zrotation"}


def star_skeleton(channels) -> Skeleton:
    """A skeleton carrying ``channels`` (``joint.axis`` names): every joint on the first one.

    Examples
    --------
    >>> star_skeleton(["root.tx", "root.rz", "knee.rx"]).names
    ('root', 'knee')
    """
    by_joint: dict[str, list[str]] = {}
    for name in channels:
        joint, _, axis = name.rpartition(".")
        if not joint or axis not in _AXIS_NAMES:
            raise ValueError(f"channel {name!r} is not named joint.axis (axis tx .. rz)")
        by_joint.setdefault(joint, []).append(name)
    joints = []
    for index, (joint, names) in enumerate(by_joint.items()):
        order = "".join(n[-1].upper() for n in names if n.rsplit(".", 1)[1].startswith("r"))
        order += "".join(a for a in "ZYX" if a not in order)
        joints.append(Joint(joint, None if index == 0 else 0, (0.0, 0.0, 0.0), tuple(names),
                            order))
    return Skeleton(tuple(joints), length_unit="none (angles only)")


def _number(value: float) -> str:
    text = f"{value:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def format_bvh(motion: Motion) -> str:
    """The BVH text of ``motion`` (see the module docstring).

    Raises
    ------
    ValueError
        When a skeleton channel is missing from the motion (or the reverse), or a
        joint has an ASF ``axis`` pre-rotation.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Motion
    >>> text = format_bvh(Motion(np.zeros((2, 1)), ("knee.rx",), 30.0))
    >>> text.splitlines()[:5]
    ['HIERARCHY', 'ROOT knee', '{', '  OFFSET 0 0 0', '  CHANNELS 1 Xrotation']
    """
    skeleton = motion.skeleton or star_skeleton(motion.channels)
    listed = [c for j in skeleton.joints for c in j.channels]
    if sorted(listed) != sorted(motion.channels):
        missing = sorted(set(motion.channels) ^ set(listed))
        raise ValueError(f"skeleton and motion channels differ ({', '.join(missing[:5])})")
    lines = ["HIERARCHY"]
    children: dict[int | None, list[int]] = {}
    for index, joint in enumerate(skeleton.joints):
        if any(joint.axis):
            raise ValueError(f"joint {joint.name!r} has an ASF axis pre-rotation, which BVH "
                             f"cannot express")
        children.setdefault(joint.parent, []).append(index)
    roots = children.get(None, [])
    if len(roots) != 1:
        raise ValueError(f"a BVH file has one root joint, this skeleton has {len(roots)}")

    def emit(index: int, depth: int) -> None:
        joint = skeleton.joints[index]
        pad = "  " * depth
        if joint.end_site:
            lines.append(f"{pad}End Site")
        else:
            lines.append(f"{pad}{'ROOT' if joint.parent is None else 'JOINT'} {joint.name}")
        lines.append(pad + "{")
        lines.append(f"{pad}  OFFSET {' '.join(_number(v) for v in joint.offset)}")
        if joint.channels:
            names = " ".join(_AXIS_NAMES[c.rsplit('.', 1)[1]] for c in joint.channels)
            lines.append(f"{pad}  CHANNELS {len(joint.channels)} {names}")
        for child in children.get(index, []):
            emit(child, depth + 1)
        lines.append(pad + "}")

    emit(roots[0], 0)
    order = [motion.index(c) for c in listed]
    lines += ["MOTION", f"Frames: {motion.frames}", f"Frame Time: {1.0 / motion.frame_rate:.8f}"]
    values = np.asarray(motion.values)[:, order]
    lines += [" ".join(_number(v) for v in row) for row in values.tolist()]
    return "\n".join(lines) + "\n"


def write_bvh(motion: Motion, path: str | Path) -> Path:
    """Write ``motion`` to ``path`` as BVH; returns the path.

    Read back by :func:`kinetology.read` to the same values within 1e-6 (the
    values are written with six decimals); see :func:`format_bvh` for errors.

    Parameters
    ----------
    motion : Motion
        The motion (without a skeleton, every joint is put on the first one).
    path : str or Path
        The file to write (overwritten).

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    ValueError
        See :func:`format_bvh`.

    Examples
    --------
    >>> import numpy as np, tempfile, pathlib
    >>> from kinetology import Motion, read
    >>> m = Motion(np.array([[1.25, -3.0], [2.0, 4.5]]), ("hip.rx", "hip.ry"), 30.0)
    >>> out = write_bvh(m, pathlib.Path(tempfile.mkdtemp()) / "m.bvh")
    >>> read(out).values.tolist()
    [[1.25, -3.0], [2.0, 4.5]]
    """
    path = Path(path)
    path.write_text(format_bvh(motion), encoding="utf-8")
    return path
