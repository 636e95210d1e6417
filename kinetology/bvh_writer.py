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
which BVH cannot express: writing one is a ``ValueError``; :func:`without_axes`
first gives the same motion on a skeleton BVH can hold.

Only what reads back is written; anything else is a ``ValueError`` naming the
joint: a joint name that is empty or holds white space or a brace; two joints
of one name (end sites named as they read back); an end site not named
``parent.end`` (the name a reader gives it); a channel not named
``joint.axis`` after its own joint; a rotation order other than the one the
``CHANNELS`` line implies (the reader takes it from there); a non-finite
offset; joints nested more than :data:`MAX_DEPTH` deep; a frame rate outside
:data:`~kinetology.motion.FRAME_RATE_RANGE` (0.1 to 10,000 fps, the frame times
the reader accepts). The values are
written in the order the file lists the channels, which is the skeleton's
depth-first order even when the skeleton lists its joints otherwise. Numbers
of 10^15 or more are written in exponent form, and the frame time with as
many digits as the frame rate needs to read back.
"""

from __future__ import annotations

from pathlib import Path

import math

import numpy as np

from psgs.errors import ValidationError

from .motion import FRAME_RATE_RANGE, Joint, Motion, Skeleton, as_path, check_motion

__all__ = ["write_bvh", "format_bvh", "star_skeleton", "without_axes"]

#: The deepest nesting written: kinetology's reader (and others) nest by recursion.
MAX_DEPTH = 500
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
            raise ValidationError(f"channel {name!r} is not named joint.axis (axis tx .. rz)")
        by_joint.setdefault(joint, []).append(name)
    joints = []
    for index, (joint, names) in enumerate(by_joint.items()):
        order = "".join(n[-1].upper() for n in names if n.rsplit(".", 1)[1].startswith("r"))
        order += "".join(a for a in "ZYX" if a not in order)
        joints.append(Joint(joint, None if index == 0 else 0, (0.0, 0.0, 0.0), tuple(names),
                            order))
    return Skeleton(tuple(joints), length_unit="none (angles only)")


def without_axes(motion: Motion) -> Motion:
    """The same motion on a skeleton without ASF ``axis`` pre-rotations, which BVH can hold.

    Each joint keeps its name, place and offset; a rotated joint's local rotation
    ``C @ R @ C.T`` (:class:`~kinetology.motion.Joint`) becomes three rotation channels
    ``joint.r?`` in its rotation order (:func:`~kinetology.kinematics.euler_angles`), after
    its position channels. Forward kinematics gives the same positions, so a CMU take (or a
    motion generated on its skeleton) is written as BVH on its own skeleton, bone for bone.
    A motion whose skeleton has no axes (or no skeleton) is returned as it is.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Joint, Motion, Skeleton
    >>> from kinetology.kinematics import forward_kinematics
    >>> arm = Skeleton((Joint("shoulder", None, (0, 0, 0), ("shoulder.rx",), "ZYX", (0, 0, 90)),
    ...                 Joint("hand", 0, (10, 0, 0), end_site=True)))
    >>> swing = Motion(np.array([[0.0], [45.0]]), ("shoulder.rx",), 30.0, arm)
    >>> plain = without_axes(swing)
    >>> plain.channels, plain.skeleton.joints[0].axis
    (('shoulder.rz', 'shoulder.ry', 'shoulder.rx'), (0.0, 0.0, 0.0))
    >>> bool(np.allclose(forward_kinematics(plain), forward_kinematics(swing)))
    True
    """
    from .kinematics import euler_angles, local_rotation

    skeleton = motion.skeleton
    if skeleton is None or not any(any(j.axis) for j in skeleton.joints):
        return motion
    joints, columns, names = [], [], []
    for joint in skeleton.joints:
        moved = [c for c in joint.channels if c in motion.channels]
        rotated = any(c.rsplit(".", 1)[1].startswith("r") for c in moved)
        positions = [c for c in moved if c.rsplit(".", 1)[1].startswith("t")]
        # without rotation channels the local rotation is C @ C.T, none: no channel needed
        channels = positions + ([f"{joint.name}.r{a.lower()}" for a in joint.rotation_order]
                                if rotated else [])
        columns += [motion.column(c) for c in positions]
        if rotated:
            columns += list(euler_angles(local_rotation(motion, joint),
                                         joint.rotation_order).T)
        names += channels
        joints.append(Joint(joint.name, joint.parent, joint.offset, tuple(channels),
                            joint.rotation_order, (0.0, 0.0, 0.0), joint.end_site))
    values = np.column_stack(columns) if columns else np.zeros((motion.frames, 0))
    return Motion(values, tuple(names), motion.frame_rate,
                  Skeleton(tuple(joints), skeleton.length_unit), motion.source, motion.meta)


def _number(value: float) -> str:
    if abs(value) >= 1e15:  # six decimals would be 300 digits for 1e300 (and no more exact)
        return repr(float(value))
    text = f"{value:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _frame_time(rate: float) -> str:
    """The frame time as the reader turns it back into ``rate`` (8 decimals when enough)."""
    slowest, fastest = FRAME_RATE_RANGE
    if not slowest <= rate <= fastest:  # the reader refuses its frame time
        raise ValidationError(f"frame rate {rate:g} fps is outside {slowest:g} .. {fastest:g} "
                              f"fps, the rates a BVH file is read at")
    seconds = 1.0 / rate
    for text in (f"{seconds:.8f}", repr(seconds)):
        back = 1.0 / float(text) if float(text) > 0 else math.inf
        if math.isfinite(back) and back >= 1 and abs(back - round(back)) < 0.01:  # as the reader
            back = float(round(back))
        if math.isclose(back, rate, rel_tol=1e-12):
            return text
    raise ValidationError(f"frame rate {rate!r} cannot be written as a frame time that reads back")


def _implied_order(joint: Joint) -> str:
    """The rotation order a reader gives ``joint``: its rotation channels as listed, the
    missing axes after them in Z, Y, X order."""
    order = "".join(c.rsplit(".", 1)[1][1].upper() for c in joint.channels
                    if c.rsplit(".", 1)[1].startswith("r"))
    return order + "".join(a for a in "ZYX" if a not in order) if order else "ZYX"


def _check_joint(skeleton: Skeleton, joint: Joint, seen: set[str]) -> None:
    """ValueError unless ``joint`` reads back as it is (see the module docstring)."""
    name = joint.name
    if joint.end_site:
        parent = skeleton.joints[joint.parent].name if joint.parent is not None else None
        if parent is None or name != f"{parent}.end":
            raise ValidationError(f"end site {name!r} would read back as {parent!r}.end: BVH end "
                             f"sites have no names")
    elif not name or any(ch.isspace() or ch in "{}" for ch in name):
        raise ValidationError(f"joint name {name!r} cannot be written to BVH (empty, white space "
                         f"or a brace: readers split the hierarchy into words and braces)")
    if name in seen:
        raise ValidationError(f"two joints are named {name!r}")
    seen.add(name)
    if not all(math.isfinite(v) for v in joint.offset):
        raise ValidationError(f"joint {name!r} has a non-finite offset {joint.offset}")
    for channel in joint.channels:
        owner, _, axis = channel.rpartition(".")
        if owner != name or axis not in _AXIS_NAMES:
            raise ValidationError(f"channel {channel!r} of joint {name!r} would read back as "
                             f"{name}.<axis>: channels are named after their joint")
    if any(c.rsplit(".", 1)[1].startswith("r") for c in joint.channels) and \
            joint.rotation_order != _implied_order(joint):
        raise ValidationError(f"joint {name!r}: rotation order {joint.rotation_order!r} is not the "
                         f"order of its rotation channels ({_implied_order(joint)!r}), which "
                         f"is the order a BVH file gives")


def format_bvh(motion: Motion) -> str:
    """The BVH text of ``motion`` (see the module docstring).

    Raises
    ------
    ValueError
        When a skeleton channel is missing from the motion (or the reverse), a
        joint has an ASF ``axis`` pre-rotation, or anything else would not read
        back (see the module docstring).

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Motion
    >>> text = format_bvh(Motion(np.zeros((2, 1)), ("knee.rx",), 30.0))
    >>> text.splitlines()[:5]
    ['HIERARCHY', 'ROOT knee', '{', '  OFFSET 0 0 0', '  CHANNELS 1 Xrotation']
    """
    check_motion(motion)
    skeleton = motion.skeleton or star_skeleton(motion.channels)
    listed = [c for j in skeleton.joints for c in j.channels]
    if sorted(listed) != sorted(motion.channels):
        missing = sorted(set(motion.channels) ^ set(listed))
        raise ValidationError(f"skeleton and motion channels differ ({', '.join(missing[:5])})")
    lines = ["HIERARCHY"]
    children: dict[int | None, list[int]] = {}
    seen: set[str] = set()
    for joint in skeleton.joints:  # first, as the plainest reason an ASF skeleton fails
        if any(joint.axis):
            raise ValidationError(f"joint {joint.name!r} has an ASF axis pre-rotation, which BVH "
                             f"cannot express (kinetology.bvh_writer.without_axes re-expresses "
                             f"the angles without it)")
    for index, joint in enumerate(skeleton.joints):
        _check_joint(skeleton, joint, seen)
        children.setdefault(joint.parent, []).append(index)
    roots = children.get(None, [])
    if len(roots) != 1:
        raise ValidationError(f"a BVH file has one root joint, this skeleton has {len(roots)}")

    depth = [0] * len(skeleton.joints)
    for index, joint in enumerate(skeleton.joints):  # parents come first: one pass
        depth[index] = 0 if joint.parent is None else depth[joint.parent] + 1
    if max(depth, default=0) > MAX_DEPTH:
        raise ValidationError(f"joints nested {max(depth)} deep; BVH readers (kinetology's "
                         f"included) read at most {MAX_DEPTH} levels")
    written: list[str] = []  # channels in the file's order: depth-first from the root
    stack: list[tuple[int, int, bool]] = [(roots[0], 0, True)]  # a loop: chains can be deep
    while stack:
        index, depth, opening = stack.pop()
        pad = "  " * min(depth, 40)  # indentation is cosmetic; deep chains stay linear
        if not opening:
            lines.append(pad + "}")
            continue
        joint = skeleton.joints[index]
        written.extend(joint.channels)
        if joint.end_site:
            lines.append(f"{pad}End Site")
        else:
            lines.append(f"{pad}{'ROOT' if joint.parent is None else 'JOINT'} {joint.name}")
        lines.append(pad + "{")
        lines.append(f"{pad}  OFFSET {' '.join(_number(v) for v in joint.offset)}")
        if joint.channels:
            names = " ".join(_AXIS_NAMES[c.rsplit('.', 1)[1]] for c in joint.channels)
            lines.append(f"{pad}  CHANNELS {len(joint.channels)} {names}")
        stack.append((index, depth, False))
        stack.extend((child, depth + 1, True) for child in reversed(children.get(index, [])))
    order = [motion.index(c) for c in written]
    lines += ["MOTION", f"Frames: {motion.frames}",
              f"Frame Time: {_frame_time(motion.frame_rate)}"]
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
    path = as_path(path)
    path.write_text(format_bvh(motion), encoding="utf-8")
    return path
