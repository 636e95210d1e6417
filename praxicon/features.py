"""Features of a take: one fixed-length vector of numbers, computed once per take or window.

Per rotation channel of every joint but the root: its typical pose (median angle), its spread
(10-90 % range, log), its velocity energy (RMS speed, log) and the course of the take (the means
of its four quarters, relative to the median; a one-off action's shape). Per root (the joint
whose position moves): its travel and turning velocities in its own frame, mean (the drift: a
turn's heading rate, the speed of travel) and RMS of the rest (bobbing, swaying); for whole
takes also, per local axis, the largest signed turn from the take's first frame (a turn performed
and then partly undone still turned that far). The take's flight: the share of its frames in
which no point of the body is on the ground (log), and its pace: how far the body travels a
second, in its hips' heights (log), where a skeleton gives the points. And the take's tempo:
the period of its summed joint speed (log seconds).
"""

from __future__ import annotations

import math

import numpy as np

from psgs.errors import PSGSError

__all__ = ["motion_features", "feature_joint", "flight_share", "travel_pace", "FeatureError"]

_ROTATIONS = ("rx", "ry", "rz")
_TRANSLATIONS = ("tx", "ty", "tz")
_SMOOTHING = 0.05  # seconds: Gaussian smoothing before differentiating (sensor noise)
_UP = 1  # the vertical axis of a skeleton's coordinates (y, as BVH and ASF/AMC files have it)
_GROUND = 0.04  # "on the ground": within this share of the hips' height of the lowest points
_GROUND_SPAN = 1.0  # seconds over which the ground is read as level (a step is shorter)
_FLIGHT_BLOCK = 4096  # frames placed at once by the flight's forward kinematics
# added to the share before its logarithm: a share of 0 is a number too, and a frame or two
# off the ground (a brisk walk's toe-off, 1 frame in 30) is not made far from none
_FLIGHT_FLOOR = 0.1
# hips' heights a second added to the pace before its logarithm: a body standing or stepping
# on the spot drifts 0.01-0.2 a second, which the floor keeps within about 1.5 of one another
# on the log scale, where a walk is 2 to 3.5 above them
_PACE_FLOOR = 0.05
_PACE_UNIT = 0.25  # the hips are the pace's unit where at least this share of the body's height


class FeatureError(PSGSError, ValueError):
    """A motion that has no features (fewer than 3 frames)."""


def feature_joint(feature: str) -> str:
    """The joint a feature belongs to (``"*"`` for the take-wide tempo, flight and pace)."""
    channel = feature.rsplit(":", 1)[0]
    return channel.split(".", 1)[0] if "." in channel else "*"


def _joints_in_order(motion) -> list[str]:
    seen: dict[str, None] = {}
    for name in motion.channels:
        seen.setdefault(name.rpartition(".")[0], None)
    return list(seen)


def _root_joints(motion) -> list[str]:
    """The root chain: every joint (in channel order) up to the last whose position moves.

    A take may carry the body's travel on a top joint (``joint_Root``) and its bobbing on the
    next (``Hips``), or both on one: the chain's composed motion is the body's either way, so
    every take of a skeleton gets the same features. Empty when no position moves.
    """
    joints = _joints_in_order(motion)
    place = {joint: k for k, joint in enumerate(joints)}  # not joints.index per channel
    last = -1
    for c, name in enumerate(motion.channels):
        joint, _, axis = name.rpartition(".")
        if axis in _TRANSLATIONS and np.ptp(motion.values[:, c]) > 1e-6:
            last = max(last, place[joint])
    return joints[:last + 1]


def _chain_channels(motion, chain: list[str]) -> tuple[dict[str, int], dict[str, str]]:
    """What :func:`_joint_transform` reads of ``motion`` for the joints of ``chain``, found
    once: each channel's column, and each joint's rotation order (the skeleton's, of its first
    joint of that name; for a joint it lacks, the order its rotation channels are listed in).

    A chain may hold every joint of a skeleton (each with a position channel that moves): a
    search of every channel and every skeleton joint per joint of it made a chain of 4,000
    joints take 13 s (quadratic).
    """
    column = {channel: k for k, channel in enumerate(motion.channels)}
    orders: dict[str, str] = {}
    for joint in motion.skeleton.joints if motion.skeleton is not None else ():
        orders.setdefault(joint.name, joint.rotation_order)
    listed = set(chain) - orders.keys()
    if listed:
        orders.update(_listed_orders(motion.channels, listed))
    return column, orders


def _listed_orders(channels, joints: set[str]) -> dict[str, str]:
    """Per joint of ``joints`` the axes (``"ZYX"``) of the rotation channels whose names start
    with the joint's and a ``.``, in the order of ``channels``: a joint named ``a`` takes the
    axes of the channels of a joint named ``a.b`` too.

    One pass over the channels, each looked at only where its name could end one of the
    joints' (at a ``.`` as far in as a joint's name is long).
    """
    sizes = sorted({len(joint) for joint in joints})
    out = dict.fromkeys(joints, "")
    for channel in channels:
        head, dot, axis = channel.rpartition(".")
        if not dot or axis not in _ROTATIONS:
            continue
        for size in sizes:
            if size > len(head):
                break
            if (size == len(head) or head[size] == ".") and head[:size] in out:
                out[head[:size]] += axis[1].upper()
    return out


def _joint_transform(motion, joint: str, channels: tuple[dict[str, int], dict[str, str]]):
    """Per frame the joint's rotation matrix and translation (smoothed channels), read by
    the columns and orders of :func:`_chain_channels`."""
    from kinetology.kinematics import rotation_matrices
    from kinetology.segmentation import smooth, unwrap

    rate = motion.frame_rate
    column, orders = channels
    angles = {a.upper(): smooth(unwrap(motion.values[:, column[f"{joint}.r{a}"]]
                                       .astype(float)), rate, _SMOOTHING)
              for a in "xyz" if f"{joint}.r{a}" in column}
    rot = rotation_matrices(angles, orders[joint] or "XYZ", motion.frames)
    pos = np.stack([smooth(motion.values[:, column[f"{joint}.t{a}"]].astype(float), rate,
                           _SMOOTHING)
                    if f"{joint}.t{a}" in column else np.zeros(motion.frames)
                    for a in "xyz"], axis=1)
    return rot, pos


def _chain_pose(motion, chain: list[str]) -> tuple[np.ndarray, np.ndarray]:
    """Per frame the root chain's rotation and position (smoothed), parent to child."""
    rot = np.broadcast_to(np.eye(3), (motion.frames, 3, 3)).copy()
    pos = np.zeros((motion.frames, 3))
    channels = _chain_channels(motion, chain)
    for joint in chain:  # compose parent to child: p += R t_child, R = R R_child
        r, t = _joint_transform(motion, joint, channels)
        pos = pos + np.einsum("tij,tj->ti", rot, t)
        rot = rot @ r
    return rot, pos


def root_motion(motion, chain: list[str]) -> np.ndarray:
    """Frames-1 x 6: the root chain's velocity and turning rate (deg/s) in its own frame."""
    return _root_series(*_chain_pose(motion, chain), motion.frame_rate)


def _root_series(rot: np.ndarray, pos: np.ndarray, rate: float) -> np.ndarray:
    """:func:`root_motion` from the chain's pose (:func:`_chain_pose`)."""
    velocity = np.einsum("tji,tj->ti", rot[:-1], np.diff(pos, axis=0)) * rate
    step = np.einsum("tji,tjk->tik", rot[:-1], rot[1:])  # R_t^T R_t+1: the turn in one frame
    turning = np.degrees(np.stack([step[:, 2, 1] - step[:, 1, 2], step[:, 0, 2] - step[:, 2, 0],
                                   step[:, 1, 0] - step[:, 0, 1]], axis=1) / 2) * rate
    return np.concatenate([velocity, turning], axis=1)


def _tempo(speed: np.ndarray, frame_rate: float) -> float:
    """Period (seconds) of the summed joint speed: the first autocorrelation peak in 0.25-4 s."""
    x = speed - speed.mean()
    n = len(x)
    lo, hi = int(0.25 * frame_rate), min(int(4.0 * frame_rate), n // 2)
    if hi <= lo + 2 or not np.any(x):
        return float(n / frame_rate)
    spectrum = np.fft.rfft(x, 2 * n)
    ac = np.fft.irfft(spectrum * np.conj(spectrum))[:n]
    ac = ac / ac[0]
    seg = ac[lo:hi]
    peaks = np.flatnonzero((seg[1:-1] > seg[:-2]) & (seg[1:-1] >= seg[2:]) & (seg[1:-1] > 0.1))
    lag = lo + 1 + peaks[0] if len(peaks) else n
    return float(lag / frame_rate)


def _excursions(turning: np.ndarray, frame_rate: float) -> np.ndarray:
    """Per axis the turn furthest from the first frame's, with its sign (degrees).

    The mean turning rate is the net turn over the take: a take that turns right a quarter
    turn and then back left further has the mean rate of a left turn, though it performed the
    right turn; how far it got from where it started says it did.

    Examples
    --------
    >>> rate = np.array([[-10.0], [-10.0], [5.0], [5.0], [5.0]])  # deg/s, at 1 frame/s
    >>> _excursions(rate, 1.0).tolist()
    [-20.0]
    """
    angle = np.concatenate([np.zeros((1, turning.shape[1])),
                            np.cumsum(turning, axis=0) / frame_rate])
    far = np.abs(angle).argmax(axis=0)
    return angle[far, np.arange(turning.shape[1])]


def _root_features(motion, chain: list[str], pose, *,
                   course: bool = True) -> list[tuple[str, float]]:
    """The root's travel and turning in its own frame, whichever way the body faces.

    The root chain's velocity and angular velocity are expressed in its own frame (so a walk
    to the north and one to the south, or a turn started facing east, give the same numbers):
    per local axis the mean (the drift: a turn's heading rate, the travel speed) and the RMS
    of the rest (bobbing, swaying). Rotation orders are the skeleton's, else the order of each
    joint's rotation channels in the motion. Named after the chain's last joint. With
    ``course`` also each axis's turn excursion (:func:`_excursions`): like the quarter means it
    reads the course of a whole take, which a window of a recording cut anywhere does not have.
    """
    series = _root_series(*pose, motion.frame_rate)  # pose: the chain's (_chain_pose)
    out = []
    for k, kind in enumerate(("travel", "turn")):
        part = series[:, 3 * k:3 * k + 3]
        mean = part.mean(axis=0)
        sway = np.sqrt(((part - mean) ** 2).mean(axis=0))
        for i, a in enumerate("xyz"):
            out.append((f"{chain[-1]}.{kind}{a}:drift", float(mean[i])))
            out.append((f"{chain[-1]}.{kind}{a}:energy", math.log1p(float(sway[i]))))
    if course:
        for a, value in zip("xyz", _excursions(series[:, 3:], motion.frame_rate)):
            out.append((f"{chain[-1]}.turn{a}:excursion", float(value)))
    return out


def flight_share(motion, chain: list[str]) -> float | None:
    """The share of a take's frames in which no point of the body is on the ground.

    A run leaves the ground between steps and a walk never does: on the shared data the walks
    and turns keep to it (0-3 % of their frames off it, a brisk walk's toe-off), most styles'
    runs fly 33-53 % of theirs, an exhausted run 4-18 %, and an elderly run, which shuffles,
    hardly ever (under 1 %). A take that flies is no walk even when every learnt action is one.

    Parameters
    ----------
    motion : kinetology.Motion
        A take with a skeleton whose vertical axis is y (as BVH and ASF/AMC files have it).
    chain : list of str
        The root chain (its last joint, the hips, gives the body's height).

    Returns
    -------
    float or None
        The share, 0 to 1; None without a skeleton holding the chain's last joint, without a
        point of the body that moves up and down, or where the skeleton's offsets are too
        large to place the points (a float overflow).

    Notes
    -----
    The ground is where the body's lowest point is, read locally: per second of the take
    (``_GROUND_SPAN``) the frame at the 2nd percentile of the frames' lowest points (the third
    lowest at least, so that a glitch of a frame or two does not set it), interpolated from
    such frame to such frame (and on, before the first and after the last, as to the nearest
    such frame half a second away or more; level where there is none), so that a floor that
    tilts or a height that drifts over a long take is not read as flight (CMU subject 02's
    second walk rises 1.6 units in 2.5 s, 4 % of its hips' height being 0.68). A frame flies
    when its lowest point is higher than ``_GROUND`` of the hips' height (its median over the
    take, above the ground) over the ground. Points whose height never changes are not the
    body: a top joint fixed at the origin, or one carrying the travel along the floor. The
    points are placed a block of ``_FLIGHT_BLOCK`` frames at a time, so a long take's joint
    positions are never all held at once.

    Examples
    --------
    A body of a hip and a foot that hops in the second of four frames:

    >>> from kinetology.bvh import parse_bvh
    >>> hop = parse_bvh('''HIERARCHY
    ... ROOT Hips
    ... { OFFSET 0 0 0
    ...   CHANNELS 3 Xposition Yposition Zposition
    ...   JOINT foot
    ...   { OFFSET 0 -10 0
    ...     CHANNELS 1 Xrotation
    ...     End Site
    ...     { OFFSET 0 -1 0 } } }
    ... MOTION
    ... Frames: 4
    ... Frame Time: 0.1
    ... 0 11 0 0
    ... 0 13 0 0
    ... 0 11 0 0
    ... 0 11 0 0
    ... ''')
    >>> flight_share(hop, ["Hips"])
    0.25
    """
    read = _ground(motion, chain)
    return None if read is None else _flight(read)


def _flight(read: tuple[np.ndarray, np.ndarray, float, float]) -> float:
    """The share of frames off the ground, from :func:`_ground`'s reading."""
    lowest, ground, hips, _ = read
    return float(np.mean(lowest > ground + _GROUND * max(hips, 0.0)))


def _ground(motion, chain: list[str]) -> tuple[np.ndarray, np.ndarray, float, float] | None:
    """Per frame the body's lowest point and the ground under it, the hips' height above the
    ground and the body's (the highest point's; medians over the take), as
    :func:`flight_share` reads them; None where it gives none."""
    from kinetology import Motion, MotionFormatError
    from kinetology.kinematics import forward_kinematics

    skeleton = motion.skeleton
    if skeleton is None or not chain or chain[-1] not in skeleton.names or not motion.frames:
        return None
    hip = skeleton.index(chain[-1])
    heights = []
    for start in range(0, motion.frames, _FLIGHT_BLOCK):
        block = Motion(motion.values[start:start + _FLIGHT_BLOCK], motion.channels,
                       motion.frame_rate, skeleton, motion.source)
        try:
            heights.append(forward_kinematics(block)[:, :, _UP])
        except MotionFormatError:
            return None
    height = np.concatenate(heights)  # a motion has a frame at least (checked above)
    with np.errstate(over="ignore", invalid="ignore"):
        reach = height.max(axis=0) - height.min(axis=0)
        body = reach > 1e-9 * max(1.0, float(np.abs(height).max()))
    if not body.any():
        return None
    lowest = height[:, body].min(axis=1)
    span = max(1, int(round(_GROUND_SPAN * motion.frame_rate)))
    edges = list(range(0, len(lowest), span)) + [len(lowest)]
    if len(edges) > 2 and edges[-1] - edges[-2] < span / 2:
        del edges[-2]  # a last piece under half a second is read with the one before
    # per piece its frame at the 2nd percentile of the lowest points (the third lowest at
    # least, so that a frame or two of glitch do not set the ground), placed at that frame's
    # time (not the piece's middle: on a rising floor a piece's low is at its start)
    at = np.array([a + int(np.argsort(lowest[a:b], kind="stable")[
        min(b - a - 1, max(2, int(0.02 * (b - a))))]) for a, b in zip(edges[:-1], edges[1:])])
    frames = np.arange(len(lowest))
    ground = np.interp(frames, at, lowest[at])
    # before the first such frame and after the last the floor goes on as it does to the
    # nearest such frame half a second or more away (two frames side by side would stretch
    # a step's jitter over a second); level where there is none
    for ends, near, others in ((frames < at[0], at[0], at[1:]),
                               (frames > at[-1], at[-1], at[:-1])):
        far = others[np.abs(others - near) >= span / 2]
        if ends.any() and len(far):
            other = far[0] if near == at[0] else far[-1]
            slope = (lowest[other] - lowest[near]) / (other - near)
            ground[ends] = lowest[near] + slope * (frames[ends] - near)
    hips = float(np.median(height[:, hip] - ground))
    with np.errstate(over="ignore", invalid="ignore"):
        tallest = float(np.median(height[:, body].max(axis=1) - ground))
    return lowest, ground, hips, tallest


def travel_pace(motion, chain: list[str]) -> float | None:
    """How fast the body travels over the ground: hips' heights a second.

    A gait goes somewhere and an action performed in place does not, whatever its steps: on
    the shared data the walks and turns travel 0.4-2.3 hips' heights a second, the runs
    1.4-4.6, the dashes 2.8-5.1, and the bows, waves, guides, calls and punches 0.01-0.2
    (stepping on the spot, swaying; a kick or a slash that steps into it 0.2-0.6). Measured in
    the body's own size, the pace reads the same in centimetres or inches and on a child's body
    or a giant's.

    Parameters
    ----------
    motion : kinetology.Motion
        A take with a skeleton whose vertical axis is y.
    chain : list of str
        The root chain (its composed position is where the body is; its last joint's height
        above the ground, the hips', is the unit).

    Returns
    -------
    float or None
        The mean horizontal distance the root chain covers in a second (in a take shorter than
        a second, from its first frame to its last), over the hips' median height above the
        ground (read as :func:`flight_share` reads it); None where that gives none, where the
        chain's last joint is not a quarter of the body's height above the ground (a top joint
        that carries the travel along the floor is no unit) or where the positions overflow.

    Examples
    --------
    A body of a hip and a swinging foot that travels 2 units a second, its hip 11 units above the
    foot's lowest point:

    >>> from kinetology.bvh import parse_bvh
    >>> text = "\\n".join(f"0 11 {0.1 * k:.1f} 0 {10 * (k % 2)}" for k in range(40))
    >>> walk = parse_bvh('''HIERARCHY
    ... ROOT Hips
    ... { OFFSET 0 0 0
    ...   CHANNELS 4 Xposition Yposition Zposition Xrotation
    ...   JOINT foot
    ...   { OFFSET 0 -10 0
    ...     CHANNELS 1 Xrotation
    ...     End Site
    ...     { OFFSET 0 -1 0 } } }
    ... MOTION
    ... Frames: 40
    ... Frame Time: 0.05
    ... ''' + text)
    >>> round(travel_pace(walk, ["Hips"]), 3)
    0.182
    """
    read = _ground(motion, chain)
    return None if read is None else _pace(motion, read, _chain_pose(motion, chain)[1])


def _pace(motion, read, pos: np.ndarray) -> float | None:
    """:func:`travel_pace` from :func:`_ground`'s reading and the root chain's positions."""
    hips, tallest = read[2], read[3]
    # the unit is the chain's last joint's height: where that is no good share of the body's
    # (a chain that ends at a top joint carrying the travel along the floor) there is none
    if not hips > _PACE_UNIT * tallest:
        return None
    with np.errstate(over="ignore", invalid="ignore"):
        flat = np.delete(pos, _UP, axis=1) / hips  # in hips' heights before any square
        span = max(1, int(round(motion.frame_rate)))  # a second: a step's sway averages out
        if motion.frames > span:
            pace = (np.linalg.norm(flat[span:] - flat[:-span], axis=1).mean()
                    * motion.frame_rate / span)
        else:
            pace = (np.linalg.norm(flat[-1] - flat[0]) * motion.frame_rate
                    / max(1, motion.frames - 1))
    return float(pace) if np.isfinite(pace) else None


def share_of_flight(value: float) -> float:
    """The share of frames off the ground a ``flight`` feature's value stands for (the
    feature is ``log(share + 0.1)``), clipped at 0; NaN stays NaN.

    A mean of such values reads back as a typical share, not the mean share: a geometric
    mean shifted by 0.1, below the mean (shares 0 and 0.5 read back as 0.145).

    >>> round(share_of_flight(math.log(0.35 + 0.1)), 6)
    0.35
    >>> round(share_of_flight((math.log(0.1) + math.log(0.6)) / 2), 3)
    0.145
    """
    share = math.exp(value) - _FLIGHT_FLOOR
    return 0.0 if share < 0 else share  # a NaN compares false: it stays NaN


def pace_of(value: float) -> float:
    """The pace (hips' heights a second) a ``pace`` feature's value stands for (the feature
    is ``log(pace + 0.05)``), clipped at 0; NaN stays NaN. A mean of such values reads back
    as a typical pace, below the mean pace (as :func:`share_of_flight`'s).

    >>> round(pace_of(math.log(1.2 + 0.05)), 6)
    1.2
    """
    pace = math.exp(value) - _PACE_FLOOR
    return 0.0 if pace < 0 else pace  # a NaN compares false: it stays NaN


def motion_features(motion, *, shape: bool = True) -> tuple[tuple[str, ...], np.ndarray]:
    """The feature vector of a whole motion: names and values (see the module's description).

    Parameters
    ----------
    motion : kinetology.Motion
        At least 3 frames.
    shape : bool, default True
        Include the four quarter means per channel (the course of a one-off action) and the
        root's turn excursions; windows of a recording leave them out (a window's quarters and
        how far it turns depend on where it starts).

    Returns
    -------
    names : tuple of str
        ``channel:kind`` (kinds pose and posec: the median's sine and cosine, spread, energy,
        shape0..3; the root's ``travel*``/``turn*`` drift and energy, and ``turn*`` excursion),
        ``flight`` and ``pace`` (with a skeleton and a root that moves; :func:`flight_share`,
        as ``log(share + 0.1)``, and :func:`travel_pace`, as ``log(pace + 0.05)``) and
        ``tempo``.
    values : numpy.ndarray

    Raises
    ------
    FeatureError
        When the motion has fewer than 3 frames, or a feature is not finite (a value of the
        motion too large to compute with: an energy's square past the float range), naming
        the motion's source and the feature.

    Examples
    --------
    >>> from kinetology import synthetic_motion
    >>> names, values = motion_features(synthetic_motion(2, (0,), seed=1))
    >>> names[:3], len(names) == len(values)
    (('j0.rx:pose', 'j0.rx:posec', 'j0.rx:spread'), True)
    """
    if motion.frames < 3:
        raise FeatureError(f"{motion.source}: {motion.frames} frames; a description needs "
                               f"at least 3")
    # a motion's values are finite, but one too large (a position of 1e300) overflows a square
    # or a sum of its features: silenced here, the feature it made refused below, so that no
    # NaN reaches a description or a score
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        names, values = _features(motion, shape)
    # finite but past _LARGEST_FEATURE is refused too: descriptions and distances square the
    # features, and such a square (or a sum of them, or a spread over takes) is not finite
    with np.errstate(invalid="ignore"):
        bad = np.flatnonzero(~(np.abs(values) <= _LARGEST_FEATURE))
    if len(bad):
        # the largest value is where to look in the file (frames counted from 0, as the
        # motion's own checks count them)
        frame, column = np.unravel_index(np.abs(motion.values).argmax(), motion.values.shape)
        value = values[bad[0]]
        said = "not finite" if not np.isfinite(value) else "too large to square"
        raise FeatureError(f"{motion.source}: feature {names[bad[0]]} is {said} "
                           f"({value:g}): a value of the motion is too large to compute "
                           f"with (its largest: {motion.values[frame, column]:g}, "
                           f"{motion.channels[column]} at frame {frame})")
    return names, values


#: The largest feature a description takes: its square, summed over a thousand features or
#: taken as a spread over takes, stays finite (doubles reach 1.8e308)
_LARGEST_FEATURE = 1e150


def _features(motion, shape: bool) -> tuple[tuple[str, ...], np.ndarray]:
    """:func:`motion_features` of a motion of 3 frames or more, non-finite values and all."""
    from kinetology.segmentation import smooth, unwrap

    rate = motion.frame_rate
    roots = _root_joints(motion)
    in_roots = set(roots)  # not the list searched per channel: quadratic in a long chain
    columns = [c for c, channel in enumerate(motion.channels)
               if channel.rpartition(".")[2] in _ROTATIONS
               and channel.rpartition(".")[0] not in in_roots]
    x = smooth(unwrap(motion.values[:, columns].astype(float)), rate, _SMOOTHING)
    speed = np.abs(np.gradient(x, axis=0)) * rate
    median = np.median(x, axis=0)
    low, high = np.percentile(x, [10, 90], axis=0)
    # an angle is a point on a circle: its typical value as sine and cosine (in degrees of arc
    # near 0), so a take read as 179 and one read as -181 have the same pose
    radians = np.radians(median)
    table = [("pose", np.degrees(np.sin(radians))), ("posec", np.degrees(np.cos(radians))),
             ("spread", np.log1p(high - low)),
             ("energy", np.log1p(np.sqrt(np.mean(speed ** 2, axis=0))))]
    if shape:
        # three frames split in four leave a quarter empty (a NaN feature): each quarter is
        # then a frame, the last one twice
        quarters = np.array_split(x, 4) if len(x) >= 4 else [x[[min(i, len(x) - 1)]]
                                                             for i in range(4)]
        table += [(f"shape{i}", q.mean(axis=0) - median) for i, q in enumerate(quarters)]
    names: list[str] = []
    values: list[float] = []
    for k, c in enumerate(columns):
        for kind, column in table:
            names.append(f"{motion.channels[c]}:{kind}")
            values.append(float(column[k]))
    if roots:
        pose = _chain_pose(motion, roots)  # the travel's features and the pace read it both
        for name, value in _root_features(motion, roots, pose, course=shape):
            names.append(name)
            values.append(value)
        read = _ground(motion, roots)
        if read is not None:
            names.append("flight")
            values.append(math.log(_flight(read) + _FLIGHT_FLOOR))
            pace = _pace(motion, read, pose[1])
            if pace is not None:
                names.append("pace")
                values.append(math.log(pace + _PACE_FLOOR))
    if columns:
        names.append("tempo")
        values.append(math.log(_tempo(speed.sum(axis=1), rate)))
    return tuple(names), np.array(values, dtype=float)
