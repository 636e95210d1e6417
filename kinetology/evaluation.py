"""The paper's five kinetological principles, measured.

* compactness and reconstructivity: :func:`codec_point` (size of
  :func:`kinetology.compress` output as a share of the original file, and the
  mean absolute error of :func:`kinetology.decompress`);
* view-invariance: :func:`view_invariance` (a 3D joint angle against the 2D
  angle seen from a circle of viewpoints);
* reproducibility: :func:`reproducibility` (per joint angle, the share of
  performances of one action whose description is the most common one);
* selectivity: :func:`selectivity` (how many joint angles get different
  descriptions in different actions, and whether a performance's nearest
  neighbour, by descriptions, is a performance of the same action).

A performance's *description* of one channel (:func:`describe`) is ``still``
when the channel moves less than ``min_range`` degrees during it; otherwise
its most frequent *cycle*: the segment states from the start of one ``B``
segment (a rise getting under way) to the start of the next, e.g. ``BGRY`` for
a plain swing, ``BGBGRY`` for a rise with a pause in it. ``irregular`` when no
complete cycle occurs.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass
from numbers import Integral
from types import MappingProxyType

import numpy as np

from psgs.errors import ValidationError

from .codec import absolute_errors, compress, decompress, mean_errors
from .kinematics import joint_angle, measurable_positions
from ._mocap6 import MOCAP6_ACTIONS, Performance, mocap6_performances  # public from here
from .motion import Motion, check_number, check_rate
from .segmentation import DEFAULTS, STATES, smooth, states, unwrap

__all__ = ["codec_point", "CMU_ANGLES", "CMU_BVH_ANGLES", "BANDAI_ANGLES", "angle_table",
           "ViewInvariance", "view_invariance",
           "MOCAP6_ACTIONS", "Performance", "mocap6_performances", "describe",
           "reproducibility", "selectivity", "MAX_VIEWS"]

#: The most viewpoints :func:`view_invariance` takes (one every 0.1 degree).
MAX_VIEWS = 3600


def codec_point(motion: Motion, original_size: int, **params) -> dict:
    """Compress and decompress ``motion``; size (bytes, % of ``original_size``) and error.

    ``mae`` is the mean absolute error over all channels and frames (root
    translations included, in file units), ``mae_angles`` over angle
    channels only (over all channels when there is none), ``max_error`` the
    largest absolute error; rotation channels are compared modulo 360°
    (:func:`kinetology.codec.mean_errors`).

    Parameters
    ----------
    motion : Motion
        The motion to compress.
    original_size : int
        Size of the file it was read from, bytes (the denominator of ``percent``).
    **params
        Passed to :func:`kinetology.compress`.

    Returns
    -------
    dict
        ``bytes``, ``percent``, ``mae``, ``mae_angles`` and ``max_error``.

    Raises
    ------
    ValidationError
        For a motion without frames (no error to measure), or an ``original_size`` that is not
        a positive number.

    Examples
    --------
    >>> import kinetology
    >>> walk = kinetology.synthetic_motion(3, seed=0)
    >>> point = codec_point(walk, original_size=walk.values.nbytes)
    >>> sorted(point)
    ['bytes', 'mae', 'mae_angles', 'max_error', 'percent']
    >>> point["percent"] < 100 and point["mae"] <= point["max_error"]
    True
    """
    if not motion.frames:  # no error to average, nor a largest one
        raise ValidationError(f"{motion.source}: 0 frames, no reconstruction error to measure")
    check_number(original_size, "original_size", positive=True)  # the percent's denominator
    data = compress(motion, **params)
    decoded = decompress(data)
    # rotation channels modulo 360°, as compress reports: the decoder returns unwrapped angles
    # (181° for a file's -179°), the same angle, not an error of 360°
    error = absolute_errors(motion, decoded)
    angles, every = mean_errors(motion, decoded)
    return {"bytes": len(data), "percent": 100.0 * len(data) / original_size,
            "mae": every, "mae_angles": angles, "max_error": float(error.max())}


#: Joint angles of the CMU (ASF) skeleton as (end, vertex, end) joint triples.
CMU_ANGLES = MappingProxyType({
    "lknee": ("lfemur", "ltibia", "lfoot"), "rknee": ("rfemur", "rtibia", "rfoot"),
    "lhip": ("upperback", "lfemur", "ltibia"), "rhip": ("upperback", "rfemur", "rtibia"),
    "lelbow": ("lhumerus", "lradius", "lwrist"), "relbow": ("rhumerus", "rradius", "rwrist"),
    "lshoulder": ("lowerback", "lhumerus", "lradius"),
    "rshoulder": ("lowerback", "rhumerus", "rradius"),
    "lankle": ("ltibia", "lfoot", "ltoes"), "rankle": ("rtibia", "rfoot", "rtoes"),
})


def _mirror(table: dict, left: str, right: str) -> MappingProxyType:
    """Add the right-side angles of a table written for the left side."""
    out = {}
    for name, triple in table.items():
        out[name] = triple
        if name.startswith("l"):
            out["r" + name[1:]] = tuple(j.replace(left, right) if left in j else j
                                        for j in triple)
    return MappingProxyType(out)


#: The same angles for the CMU BVH conversion's joint names.
CMU_BVH_ANGLES = _mirror({
    "lknee": ("LeftUpLeg", "LeftLeg", "LeftFoot"), "lhip": ("Spine", "LeftUpLeg", "LeftLeg"),
    "lelbow": ("LeftArm", "LeftForeArm", "LeftHand"),
    "lshoulder": ("Hips", "LeftArm", "LeftForeArm"),
    "lankle": ("LeftLeg", "LeftFoot", "LeftToeBase")}, "Left", "Right")

#: The same angles for the Bandai Namco dataset's joint names.
BANDAI_ANGLES = _mirror({
    "lknee": ("UpperLeg_L", "LowerLeg_L", "Foot_L"), "lhip": ("Chest", "UpperLeg_L", "LowerLeg_L"),
    "lelbow": ("UpperArm_L", "LowerArm_L", "Hand_L"),
    "lshoulder": ("Hips", "UpperArm_L", "LowerArm_L"),
    "lankle": ("LowerLeg_L", "Foot_L", "Toes_L")}, "_L", "_R")


def angle_table(skeleton) -> MappingProxyType:
    """The first of CMU_ANGLES, CMU_BVH_ANGLES, BANDAI_ANGLES whose joints the skeleton has.

    Empty when there is no skeleton or none fits.

    Parameters
    ----------
    skeleton : Skeleton or None
        The skeleton of a motion.

    Returns
    -------
    types.MappingProxyType
        Angle name (``"lknee"``, ...) to the (end, vertex, end) joint names.

    Examples
    --------
    >>> dict(angle_table(None))
    {}
    >>> from kinetology import Joint, Skeleton
    >>> names = sorted({j for triple in CMU_ANGLES.values() for j in triple})
    >>> cmu_like = Skeleton(tuple(Joint(n, None, (0, 0, 0)) for n in names))
    >>> angle_table(cmu_like)["lknee"]
    ('lfemur', 'ltibia', 'lfoot')
    """
    if skeleton is None:
        return MappingProxyType({})
    names = set(skeleton.names)
    for table in (CMU_ANGLES, CMU_BVH_ANGLES, BANDAI_ANGLES):
        if all(j in names for triple in table.values() for j in triple):
            return table
    return MappingProxyType({})


@dataclass(frozen=True, eq=False)
class ViewInvariance:
    """States of one joint angle in 3D and seen from ``azimuths`` (degrees).

    What :func:`view_invariance` returns. State codes index
    :data:`kinetology.STATES` (``0`` is ``B``, ...).

    Parameters
    ----------
    azimuths : numpy.ndarray
        The viewpoints, degrees.
    states_3d : numpy.ndarray
        The state code of the 3D angle per frame.
    states_2d : numpy.ndarray
        The state code of the 2D angle, views x frames.
    angle_3d : numpy.ndarray
        The 3D angle, degrees, per frame.

    Examples
    --------
    >>> import numpy as np
    >>> result = ViewInvariance(np.array([0.0, 90.0]), np.array([0, 1]),
    ...                         np.array([[0, 1], [0, 0]]), np.array([10.0, 20.0]))
    >>> result.agreement_per_view, result.agreement
    (array([1. , 0.5]), 0.75)
    """

    azimuths: np.ndarray
    states_3d: np.ndarray   # frames
    states_2d: np.ndarray   # views x frames
    angle_3d: np.ndarray    # degrees, frames

    @property
    def agreement_per_view(self) -> np.ndarray:
        """Per viewpoint, the fraction of frames whose 2D state is the 3D state."""
        return (self.states_2d == self.states_3d[None, :]).mean(axis=1)

    @property
    def agreement(self) -> float:
        """Fraction of (view, frame) pairs whose 2D state is the 3D state."""
        return float(self.agreement_per_view.mean())


def view_invariance(motion: Motion, triple: tuple[str, str, str], *, views: int = 36,
                    elevation: float = 0.0, up_axis: int = 1, **params) -> ViewInvariance:
    """Segment a joint angle in 3D and in orthographic 2D views around the body.

    The cameras stand on a circle around the vertical axis (``up_axis``,
    ``y`` in CMU data), ``views`` of them evenly spaced, looking at the body
    from ``elevation`` degrees above the horizon. The 2D angle is the angle
    between the projected bones. ``params`` are segmentation parameters.

    Parameters
    ----------
    motion : Motion
        A motion with a skeleton.
    triple : tuple of str
        Joint names (end, vertex, end): the angle is at the middle joint.
    views : int, default 36
        Number of viewpoints, evenly spaced around the vertical axis.
    elevation : float, default 0.0
        Height of the cameras above the horizon, degrees.
    up_axis : int, default 1
        Index of the vertical axis in the skeleton's coordinates (1: ``y``).
    **params
        Segmentation parameters (:data:`kinetology.segmentation.DEFAULTS`); ``min_range`` is
        ignored.

    Returns
    -------
    ViewInvariance

    Raises
    ------
    ValueError
        When ``views`` is not a positive whole number, ``triple`` not three joints, ``up_axis``
        no axis (0, 1, 2, or -1 for 2), the motion no skeleton or a joint past 1e150 units.
    KeyError
        When a joint of ``triple`` is not in the skeleton.

    Examples
    --------
    A knee bending in the body's y-z plane is seen fully from the front and the back and
    edge-on from the sides:

    >>> import numpy as np
    >>> from kinetology import Joint, Motion, Skeleton
    >>> leg = Skeleton((Joint("hip", None, (0, 0, 0), ("hip.rx",)),
    ...                 Joint("knee", 0, (0, -10, 0), ("knee.rx",)),
    ...                 Joint("foot", 1, (0, -10, 0), end_site=True)))
    >>> t = np.arange(240) / 120
    >>> knee = 45 + 40 * np.sin(2 * np.pi * t)          # two knee bends in two seconds
    >>> bend = Motion(np.column_stack([0 * t, knee]), ("hip.rx", "knee.rx"), 120.0, leg)
    >>> result = view_invariance(bend, ("hip", "knee", "foot"), views=4)
    >>> result.azimuths
    array([  0.,  90., 180., 270.])
    >>> result.agreement_per_view.round(2)
    array([1.  , 0.25, 1.  , 0.25])
    """
    # each view is a frames-long row of states: 10**9 views asked for gigabytes
    if isinstance(views, bool) or not isinstance(views, Integral) or not 1 <= views <= MAX_VIEWS:
        raise ValidationError(f"views must be a positive whole number, at most {MAX_VIEWS}, "
                              f"not {views!r}")
    given = triple  # a generator is read once, here
    triple = tuple(triple) if isinstance(triple, Iterable) and not isinstance(triple, str) else ()
    if len(triple) != 3:
        raise ValidationError(f"triple must name three joints, not {given!r}")
    if isinstance(up_axis, (bool, np.bool_)) or not isinstance(up_axis, Integral) \
            or up_axis not in (0, 1, 2, -1):  # -2, -3: up horizontal; True an index of no axis
        raise ValidationError(f"up_axis must be 0, 1 or 2, not {up_axis!r}")
    up_axis = up_axis % 3
    positions = measurable_positions(motion)  # a take of 1e307s: one line naming it
    index = [motion.skeleton.index(name) for name in triple]
    angle3 = joint_angle(positions, *index)
    p = {k: v for k, v in {**DEFAULTS, **params}.items() if k != "min_range"}
    s3 = states(angle3, motion.frame_rate, **p)
    horizontal = [a for a in range(3) if a != up_axis]
    azimuths = np.arange(views) * 360.0 / views
    s2 = np.empty((views, motion.frames), dtype=np.int8)
    e = np.radians(elevation)
    for v, azimuth in enumerate(np.radians(azimuths)):
        right = np.zeros(3)
        right[horizontal[0]], right[horizontal[1]] = -np.sin(azimuth), np.cos(azimuth)
        forward = np.zeros(3)
        forward[horizontal[0]], forward[horizontal[1]] = np.cos(azimuth), np.sin(azimuth)
        up = np.zeros(3)
        up[up_axis] = 1.0
        screen_up = np.cos(e) * up - np.sin(e) * forward
        projected = np.stack([positions @ right, positions @ screen_up], axis=-1)
        s2[v] = states(joint_angle(projected, *index), motion.frame_rate, **p)
    return ViewInvariance(azimuths, s3, s2, angle3)


def describe(codes: np.ndarray, signal: np.ndarray, *, min_range: float = 5.0) -> str:
    """A channel's description during one performance (see the module docstring).

    ``codes`` are the per-frame state codes and ``signal`` the (smoothed)
    angle over the performance's frames.

    Parameters
    ----------
    codes : numpy.ndarray
        State codes per frame (indices into :data:`kinetology.STATES`).
    signal : numpy.ndarray
        The angle per frame, degrees.
    min_range : float, default 5.0
        A channel moving less than this (degrees) is ``still``.

    Returns
    -------
    str
        ``"still"``, ``"irregular"`` or the most frequent cycle, e.g. ``"BGRY"``.

    Raises
    ------
    ValidationError
        When ``codes`` and ``signal`` are not one channel each, of one length.

    Examples
    --------
    >>> import numpy as np
    >>> swing = 30 * np.sin(np.linspace(0, 6 * np.pi, 300))
    >>> codes = np.array([0, 1, 2, 3] * 3).repeat(25)     # B G R Y, three times over
    >>> describe(codes, swing)
    'BGRY'
    >>> describe(codes, 0.05 * swing)                   # a 3° range: below min_range
    'still'
    >>> describe(codes[:75], swing[:75])
    'irregular'
    """
    codes, signal = np.asarray(codes), np.asarray(signal)
    if codes.ndim != 1 or codes.shape != signal.shape:  # a 2-D pair read as "still"
        raise ValidationError(f"codes and signal must be one channel each, of one length, not "
                              f"{codes.shape} and {signal.shape}")
    if signal.size == 0 or np.ptp(signal) < min_range:
        return "still"
    starts = np.concatenate(([0], np.flatnonzero(codes[1:] != codes[:-1]) + 1))
    letters = "".join(STATES[c] for c in codes[starts])
    cycle_starts = [i for i, ch in enumerate(letters) if ch == "B"]
    words = [letters[a:b] for a, b in zip(cycle_starts, cycle_starts[1:])]
    if not words:
        return "irregular"
    return Counter(words).most_common(1)[0][0]


def _descriptions(motions, performances, channels, min_range, params):
    table = {}
    for take, motion in motions.items():
        # unwrapped here, as states() does, so that 'still' is judged on the same signal
        values = unwrap(motion.values[:, [motion.index(c) for c in channels]],
                        params.get("unwrap", DEFAULTS["unwrap"]))
        smoothed = smooth(values, motion.frame_rate, params.get("smoothing",
                                                                DEFAULTS["smoothing"]))
        # checked here, where the take is known: states() refuses the same values naming none
        check_rate(smoothed, motion.frame_rate, motion.source)
        code = states(values, motion.frame_rate, **params)
        for k, perf in enumerate(performances):
            if perf.take == take:
                table[k] = tuple(describe(code[perf.start:perf.stop, c],
                                          smoothed[perf.start:perf.stop, c],
                                          min_range=min_range)
                                 for c in range(len(channels)))
    return [table[k] for k in range(len(performances))]


def reproducibility(motions, performances, channels, *, min_range: float = 5.0, **params):
    """Per action and channel: (share of performances with the modal description, it).

    Parameters
    ----------
    motions : dict of str to Motion
        The takes, by name.
    performances : list of Performance
        Labelled stretches of the takes.
    channels : sequence of str
        The channels to describe.
    min_range : float, default 5.0
        Passed to :func:`describe`.
    **params
        Segmentation parameters (:data:`kinetology.segmentation.DEFAULTS`).

    Returns
    -------
    dict
        ``{action: {channel: (fraction, description, count)}}`` for actions with at least
        two performances; ``count`` is the number of performances.

    Examples
    --------
    >>> import kinetology
    >>> from kinetology.evaluation import Performance
    >>> takes = {"a": kinetology.synthetic_motion(3, (0, 1), seed=0),
    ...          "b": kinetology.synthetic_motion(3, (0, 1), seed=1)}
    >>> performances = [Performance("a", "swing", 0, 480), Performance("a", "swing", 480, 960),
    ...                 Performance("b", "wave", 0, 480), Performance("b", "wave", 480, 960)]
    >>> table = reproducibility(takes, performances, ["j0.rx", "j1.rx"])
    >>> table["swing"]["j0.rx"]
    (1.0, 'BGRY', 2)
    """
    p = {k: v for k, v in {**DEFAULTS, **params}.items() if k != "min_range"}
    described = _descriptions(motions, performances, channels, min_range, p)
    by_action: dict[str, list] = {}
    for perf, desc in zip(performances, described):
        by_action.setdefault(perf.action, []).append(desc)
    out = {}
    for action, rows in by_action.items():
        if len(rows) < 2:
            continue
        out[action] = {}
        for c, channel in enumerate(channels):
            word, count = Counter(r[c] for r in rows).most_common(1)[0]
            out[action][channel] = (count / len(rows), word, len(rows))
    return out


def selectivity(motions, performances, channels, *, min_range: float = 5.0, **params) -> dict:
    """How differently different actions are described.

    ``pairwise[(a, b)]``: share of channels whose modal descriptions differ
    between actions ``a`` and ``b``; ``nearest_neighbour_accuracy``: share of
    performances whose nearest other performance (Hamming distance between
    description vectors, ties to the earlier one) is of the same action,
    with ``chance`` the accuracy of always guessing the commonest action.

    Parameters
    ----------
    motions : dict of str to Motion
        The takes, by name.
    performances : list of Performance
        Labelled stretches of the takes.
    channels : sequence of str
        The channels to describe.
    min_range : float, default 5.0
        Passed to :func:`describe`.
    **params
        Segmentation parameters (:data:`kinetology.segmentation.DEFAULTS`).

    Returns
    -------
    dict
        ``pairwise``, ``modal`` (action to its modal description per channel),
        ``nearest_neighbour_accuracy``, ``chance`` and ``performances`` (their number).

    Examples
    --------
    >>> import kinetology
    >>> from kinetology.evaluation import Performance
    >>> takes = {"a": kinetology.synthetic_motion(3, (0, 1), seed=0),
    ...          "b": kinetology.synthetic_motion(3, (0, 1), seed=1)}
    >>> performances = [Performance("a", "swing", 0, 480), Performance("a", "swing", 480, 960),
    ...                 Performance("b", "wave", 0, 480), Performance("b", "wave", 480, 960)]
    >>> result = selectivity(takes, performances, ["j0.rx", "j1.rx", "j2.rx"])
    >>> sorted(result)
    ['chance', 'modal', 'nearest_neighbour_accuracy', 'pairwise', 'performances']
    >>> result["chance"], result["performances"]
    (0.5, 4)
    >>> 0 <= result["pairwise"]["swing", "wave"] <= 1
    True
    """
    p = {k: v for k, v in {**DEFAULTS, **params}.items() if k != "min_range"}
    described = _descriptions(motions, performances, channels, min_range, p)
    actions = sorted({perf.action for perf in performances})
    modal = {}
    for action in actions:
        rows = [d for perf, d in zip(performances, described) if perf.action == action]
        modal[action] = tuple(Counter(r[c] for r in rows).most_common(1)[0][0]
                              for c in range(len(channels)))
    pairwise = {(a, b): float(np.mean([x != y for x, y in zip(modal[a], modal[b])]))
                for i, a in enumerate(actions) for b in actions[i + 1:]}
    matrix = np.array([[x for x in d] for d in described], dtype=object)
    hits = 0
    for i in range(len(described)):
        distance = [(np.sum(matrix[i] != matrix[j]), j) for j in range(len(described)) if j != i]
        if distance:
            hits += performances[min(distance)[1]].action == performances[i].action
    counts = Counter(perf.action for perf in performances)
    return {"pairwise": pairwise, "modal": modal,
            "nearest_neighbour_accuracy": hits / max(1, len(described)),
            # no performance, no commonest action: chance is 0, as the accuracy is
            "chance": max(counts.values(), default=0) / max(1, len(performances)),
            "performances": len(performances)}
