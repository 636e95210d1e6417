"""Forward kinematics: joint angles to 3D joint positions, vectorised over frames.

A joint's global rotation is its parent's times its local rotation
``C @ R(angles) @ C.T`` (see :class:`~kinetology.motion.Joint`); its position
is the parent's position plus the parent's global rotation applied to its
translation. The translation is the joint's offset, except along axes it has
position channels for: those give the translation itself (in BVH files with
position channels on every joint, such as Bandai Namco's, the channel values
equal the offsets; adding the two would double every bone).
"""

from __future__ import annotations

from numbers import Integral

import numpy as np

from psgs.errors import ValidationError

from .motion import Motion, MotionFormatError, check_motion, real_array

__all__ = ["axis_rotation", "rotation_matrices", "euler_angles", "local_rotation",
           "forward_kinematics", "MAX_POSITION", "positions_problem", "measurable_positions",
           "joint_angle"]

#: The farthest a joint may lie from the origin to be drawn or to have its angles measured, in
#: file units: a page, a GIF and :func:`joint_angle` measure bones by their squares, which
#: overflow past 1e154 (a file of 1e307s gave a page of NaN and Infinity that no browser reads,
#: a GIF a traceback, and ``view_invariance`` a "values must be finite" naming no take).
MAX_POSITION = 1e150


def axis_rotation(axis: str, radians) -> np.ndarray:
    """Rotations about one axis (``"X"``, ``"Y"`` or ``"Z"``), one per angle, shape ``(..., 3, 3)``.

    Examples
    --------
    >>> import numpy as np
    >>> np.round(axis_rotation("Y", np.array([np.pi / 2]))[0] @ [0.0, 0.0, 1.0], 6)
    array([1., 0., 0.])
    """
    radians = np.asarray(radians, float)
    c, s = np.cos(radians), np.sin(radians)
    out = np.zeros(radians.shape + (3, 3))
    i = "XYZ".index(axis)
    j, k = (i + 1) % 3, (i + 2) % 3
    out[..., i, i] = 1.0
    out[..., j, j] = c
    out[..., k, k] = c
    out[..., j, k] = -s
    out[..., k, j] = s
    return out


def rotation_matrices(angles_deg: dict[str, np.ndarray], order: str, frames: int) -> np.ndarray:
    """``R = R_order[0] @ R_order[1] @ R_order[2]`` per frame, from angles in degrees.

    ``angles_deg`` maps ``"X"``, ``"Y"``, ``"Z"`` to per-frame angles; a missing
    axis is zero.

    Parameters
    ----------
    angles_deg : dict of str to numpy.ndarray
        Per-frame angles (degrees) by axis, ``"X"``, ``"Y"`` or ``"Z"``.
    order : str
        The axes in the order of the product, e.g. ``"ZYX"`` for ``Rz @ Ry @ Rx``.
    frames : int
        Number of frames.

    Returns
    -------
    numpy.ndarray
        Shape ``(frames, 3, 3)``.

    Examples
    --------
    >>> import numpy as np
    >>> r = rotation_matrices({"Z": np.array([0.0, 90.0])}, "ZYX", 2)
    >>> np.round(r[1] @ [1.0, 0.0, 0.0], 6)
    array([0., 1., 0.])
    """
    result = np.broadcast_to(np.eye(3), (frames, 3, 3)).copy()
    for axis in order:
        if axis in angles_deg:
            result = result @ axis_rotation(axis, np.radians(angles_deg[axis]))
    return result


def euler_angles(matrices: np.ndarray, order: str) -> np.ndarray:
    """Angles (degrees) whose product ``R_order[0] @ R_order[1] @ R_order[2]`` is each matrix.

    The inverse of :func:`rotation_matrices` for an order of three distinct axes; shape
    ``(frames, 3)``, the columns in ``order``, each unwrapped over the frames (no jump of
    360°). The middle angle is within ±90°; where it is ±90° (gimbal lock) the first is 0.

    Examples
    --------
    >>> import numpy as np
    >>> angles = {"Z": np.array([30.0, 170.0]), "Y": np.array([-20.0, 10.0]),
    ...           "X": np.array([45.0, -175.0])}
    >>> np.round(euler_angles(rotation_matrices(angles, "ZYX", 2), "ZYX"), 6)  # -175 as 185
    array([[ 30., -20.,  45.],
           [170.,  10., 185.]])
    """
    if sorted(order) != ["X", "Y", "Z"]:
        raise ValidationError(f"rotation order {order!r} is not three distinct axes X, Y, Z")
    m = np.asarray(matrices, float)
    i, j, k = ("XYZ".index(a) for a in order)
    sign = 1.0 if (j - i) % 3 == 1 else -1.0  # XYZ, YZX, ZXY: +1; the others: -1
    middle = np.arcsin(np.clip(sign * m[:, i, k], -1.0, 1.0))
    first = np.arctan2(-sign * m[:, j, k], m[:, k, k])
    last = np.arctan2(-sign * m[:, i, j], m[:, i, i])
    locked = np.hypot(m[:, i, i], m[:, i, j]) < 1e-9  # the middle at +-90 degrees
    first[locked] = 0.0  # only the sum (or difference) of the other two is defined there
    last[locked] = np.arctan2(sign * m[locked, j, i], m[locked, j, j])
    return np.degrees(np.unwrap(np.stack([first, middle, last], axis=1), axis=0))


def _oriented(joint, local: np.ndarray) -> np.ndarray:
    """``local`` seen in the joint's own axes (an ASF joint's ``axis``; BVH joints have none)."""
    if not any(joint.axis):
        return local
    pre = rotation_matrices({a: np.full(1, v) for a, v in zip("XYZ", joint.axis)},
                            joint.rotation_order, 1)[0]
    return pre @ local @ pre.T


def local_rotation(motion: Motion, joint) -> np.ndarray:
    """Per frame the rotation of ``joint`` relative to its parent, shape ``(frames, 3, 3)``.

    The joint's rotation channels in its rotation order (a channel the motion lacks is
    zero), in the joint's own axes: the rotation :func:`forward_kinematics` chains.

    Examples
    --------
    >>> import numpy as np, kinetology
    >>> from kinetology.motion import Joint, Skeleton
    >>> sk = Skeleton((Joint("hip", None, (0, 0, 0), ("hip.ry",), "ZXY"),))
    >>> m = kinetology.Motion(np.array([[0.0], [90.0]]), ("hip.ry",), 30.0, sk)
    >>> np.round(local_rotation(m, sk.joints[0])[1] @ [0.0, 0.0, 1.0], 6)
    array([1., 0., 0.])
    """
    index = {c: i for i, c in enumerate(motion.channels)}
    angles = {c.rsplit(".", 1)[1][1].upper(): motion.values[:, index[c]] for c in joint.channels
              if c in index and c.rsplit(".", 1)[1].startswith("r")}
    return _oriented(joint, rotation_matrices(angles, joint.rotation_order, motion.frames))


def forward_kinematics(motion: Motion) -> np.ndarray:
    """Global joint positions, shape ``frames x joints x 3`` (skeleton order).

    Parameters
    ----------
    motion : Motion
        A motion with a skeleton (every BVH file; an AMC file read with its ASF).

    Returns
    -------
    numpy.ndarray
        Shape ``(frames, joints, 3)``, joints in ``motion.skeleton`` order (end sites
        included), in the file's length unit.

    Raises
    ------
    ValueError
        When the motion has no skeleton (an AMC read without its ASF).
    MotionFormatError
        (a ``ValueError`` too) When finite but extreme offsets or translations make a
        position overflow, instead of returning ``inf`` or ``nan``.

    Examples
    --------
    A leg of two 10-unit bones whose knee bends by 90° in the second frame:

    >>> import numpy as np
    >>> from kinetology.bvh import parse_bvh
    >>> leg = parse_bvh('''HIERARCHY
    ... ROOT hip
    ... { OFFSET 0 0 0
    ...   CHANNELS 1 Xrotation
    ...   JOINT knee
    ...   { OFFSET 0 -10 0
    ...     CHANNELS 1 Xrotation
    ...     End Site
    ...     { OFFSET 0 -10 0 } } }
    ... MOTION
    ... Frames: 2
    ... Frame Time: 0.5
    ... 0 0
    ... 0 90
    ... ''', source="leg.bvh")
    >>> positions = forward_kinematics(leg)
    >>> positions.shape
    (2, 3, 3)
    >>> np.round(positions[1, 2], 6)    # the foot: rotated about x, from -y to -z
    array([  0., -10., -10.])
    """
    check_motion(motion)
    skeleton = motion.skeleton
    if skeleton is None:
        raise ValidationError(f"{motion.source}: no skeleton, so no forward kinematics "
                         f"(read an AMC file with its ASF)")
    frames = motion.frames
    index = {name: i for i, name in enumerate(motion.channels)}
    rotations = np.empty((len(skeleton.joints), frames, 3, 3))
    positions = np.empty((frames, len(skeleton.joints), 3))
    for j, joint in enumerate(skeleton.joints):
        angles, translation = {}, np.tile(np.asarray(joint.offset, float), (frames, 1))
        for channel in joint.channels:
            axis = channel.rsplit(".", 1)[1]
            if channel not in index:
                continue
            column = motion.values[:, index[channel]]
            if axis.startswith("t"):
                translation[:, "xyz".index(axis[1])] = column
            else:
                angles[axis[1].upper()] = column
        local = _oriented(joint, rotation_matrices(angles, joint.rotation_order, frames))
        if joint.parent is None:
            rotations[j] = local
            positions[:, j] = translation
        else:
            parent_rotation = rotations[joint.parent]
            rotations[j] = parent_rotation @ local
            with np.errstate(over="ignore", invalid="ignore"):
                positions[:, j] = positions[:, joint.parent] + np.einsum(
                    "fij,fj->fi", parent_rotation, translation)
        if not np.isfinite(positions[:, j]).all():
            # finite offsets and angles can still add up past the largest float
            frame = int(np.argwhere(~np.isfinite(positions[:, j]))[0][0])
            raise MotionFormatError(f"forward kinematics overflows at joint {joint.name!r}, "
                                    f"frame {frame}: its offsets or translations are too large",
                                    source=motion.source)
    return positions


def positions_problem(positions: np.ndarray, doing: str = "draw") -> str | None:
    """What keeps joint positions (frames x joints x 3) from being used for ``doing`` (None:
    nothing): a joint past :data:`MAX_POSITION`.

    Examples
    --------
    >>> import numpy as np
    >>> positions_problem(np.zeros((2, 3, 3))) is None
    True
    >>> positions_problem(np.full((2, 3, 3), 1e307), "measure joint angles")
    'joint positions reach 1e+307 units, too far to measure joint angles (at most 1e+150: lengths are measured by their squares)'
    """
    peak = float(np.max(np.abs(positions), initial=0.0))
    if not peak <= MAX_POSITION:  # NaN too
        return (f"joint positions reach {peak:.3g} units, too far to {doing} (at most "
                f"{MAX_POSITION:g}: lengths are measured by their squares)")
    return None


def measurable_positions(motion: Motion) -> np.ndarray:
    """:func:`forward_kinematics`, refused in one line naming the motion (its file) when a
    joint lies past :data:`MAX_POSITION`: the angles :func:`joint_angle` measures there
    overflow (``inf / inf``), or lose the bones to the translation (``1e307 + 10``).

    Raises
    ------
    MotionFormatError
        A joint past :data:`MAX_POSITION`, naming ``motion.source``.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Joint, Motion, Skeleton
    >>> far = Skeleton((Joint("hip", None, (0, 0, 0), ("hip.rx",)),
    ...                 Joint("foot", 0, (0, -1e200, 0), end_site=True)))
    >>> measurable_positions(Motion(np.zeros((2, 1)), ("hip.rx",), 30.0, far, "far.bvh"))
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: far.bvh: joint positions reach 1e+200 units, too far to measure joint angles (at most 1e+150: lengths are measured by their squares)
    """
    positions = forward_kinematics(motion)
    if problem := positions_problem(positions, "measure joint angles"):
        raise MotionFormatError(problem, source=motion.source)
    return positions


def joint_angle(positions: np.ndarray, a: int, b: int, c: int) -> np.ndarray:
    """The angle at joint ``b`` (degrees) between segments b->a and b->c, per frame.

    Works on 3D positions and on 2D projections alike (last axis 2 or 3).

    Parameters
    ----------
    positions : numpy.ndarray
        Shape ``(frames, joints, 2 or 3)``, e.g. from :func:`forward_kinematics`.
    a, b, c : int
        Joint indices; the angle is at ``b``.

    Returns
    -------
    numpy.ndarray
        Degrees in ``[0, 180]``, one per frame (a zero-length segment counts as 90°).

    Raises
    ------
    ValueError
        (ValidationError) Positions that are not frames x joints x 2 or 3 real numbers, or an
        index that is not an integer naming a joint.

    Examples
    --------
    >>> import numpy as np
    >>> straight_then_bent = np.array([[[0, 0, 0], [0, -1, 0], [0, -2, 0]],
    ...                                [[0, 0, 0], [0, -1, 0], [0, -1, 1]]], float)
    >>> joint_angle(straight_then_bent, 0, 1, 2)
    array([180.,  90.])
    """
    # an array of floats is read as it is (float32 positions give float32 degrees, as before);
    # integers become floats (unsigned ones would wrap around when subtracted)
    if not (isinstance(positions, np.ndarray) and positions.dtype.kind == "f"):
        positions = real_array(positions, "positions")
    if positions.ndim != 3 or positions.shape[2] not in (2, 3):
        raise ValidationError(f"positions must be frames x joints x 2 or 3, not {positions.shape}")
    for name, index in (("a", a), ("b", b), ("c", c)):
        if isinstance(index, bool) or not isinstance(index, Integral) or \
                not -positions.shape[1] <= index < positions.shape[1]:
            raise ValidationError(f"joint index {name} must be an integer below "
                                  f"{positions.shape[1]} (the joints), not {index!r}")
    u = positions[:, a] - positions[:, b]
    v = positions[:, c] - positions[:, b]
    cos = np.einsum("fi,fi->f", u, v) / np.maximum(
        np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1), 1e-12)
    return np.degrees(np.arccos(np.clip(cos, -1.0, 1.0)))
