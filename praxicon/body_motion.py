"""The whole body around a generated action's actuators: where the root goes, and what the rest does.

Generation (:mod:`praxicon.generation`) makes the actuator channels from the grammar
system. This module gives everything else from the action's performances:

* **heading, travel and course** (:mod:`praxicon.heading`, re-exported here): where the
  root faces, read from its world rotation rather than one Euler channel, its velocity in
  that heading's frame (:func:`travel`), and its :func:`course` over a take, averaged over
  one period, so that a generated turn goes straight, turns and goes on as the takes do;
* **the body's own orientation**, heading removed (:func:`heading_free_angles`): the root's
  rotation turned back by its heading, as angles in the root's rotation order, continuous
  through a turn; averaged over takes on one side of ±180° (:func:`nearest_turn`);
* **typical movements** (:func:`mean_cycles`): per channel, the performances' mean cycle,
  its phase aligned to a leading generated channel, so joints the grammar does not drive
  move as they do in the takes instead of standing still;
* **a style's performances** (:func:`performances_of` with a style, :func:`style_of`: read by
  :mod:`praxicon.performance_files`, named here too).

Every function is pure: motions in, arrays out.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# RELATIVE too: the line generation's errors end with, long read from here
from .performance_files import RELATIVE, missing_style, performances_of, style_of  # noqa: F401
from .heading import _UP, Course, Travel, _moving_mean, course, course_time, global_rotation, \
    heading, mean_course, root_chain, travel, yaw_matrices

__all__ = ["Body", "Course", "Travel", "animate", "body_frame", "body_of", "channel_drift", "course",
           "cycle_starts", "euler_angles", "global_rotation", "heading", "heading_free_angles",
           "mean_course", "mean_cycles", "missing_style", "nearest_turn", "own_period",
           "performances_of", "root_chain", "style_of", "travel", "whole_cycle", "yaw_matrices"]


def body_frame(motions, root: str) -> tuple[int, float]:
    """The body axis of ``root`` and a quarter turn that set its heading-free angles, for all ``motions``.

    The axis (0, 1, 2) is the local axis that stays most horizontal over all of them:
    one axis for all, so that their headings agree (a body whose two horizontal axes are
    about as level would otherwise be read facing one way in one take and 90° off in the
    next). The offset (radians, a multiple of 90°) is added to the heading removed, chosen
    so that the middle Euler angle of the heading-free rotation is nearest 0 on average:
    far from the gimbal angle (±90°), where the other two are ill-defined.
    """
    rotations = [global_rotation(m, root) for m in motions]
    axis = int(np.argmin(sum(np.abs(r[:, _UP, :]).mean(axis=0) for r in rotations)))
    joint = motions[0].skeleton.joints[motions[0].skeleton.index(root)]
    if _rotation_channels(joint) is None:
        return axis, 0.0

    def tilt(offset):
        return sum(float(np.abs(_free(r, axis, offset, joint.rotation_order)[:, 1]).mean())
                   for r in rotations)

    return axis, min(np.radians([0.0, 90.0, 180.0, 270.0]), key=tilt)


def euler_angles(matrices, order: str) -> np.ndarray:
    """Angles (degrees, ``(frames, 3)`` in ``order``) whose product ``R_order[0] R_order[1] R_order[2]`` is each matrix; unwrapped over frames."""
    import warnings

    try:
        from scipy.spatial.transform import Rotation
    except ImportError:  # a plain install: one line naming the extra, not a traceback
        from psgs.errors import MissingDependency
        raise MissingDependency("whole-body generation needs scipy: pip install "
                                "'psgs[praxicon]'") from None

    with warnings.catch_warnings():
        # at gimbal lock scipy sets the third angle to zero and warns; that angle is as good
        # as any there (the product is the same matrix), so the warning says nothing to a user
        warnings.simplefilter("ignore", UserWarning)
        angles = Rotation.from_matrix(np.asarray(matrices, float)).as_euler(order.upper())
    return np.degrees(np.unwrap(angles, axis=0))


def heading_free_angles(motion, root: str, frame=(None, 0.0)) -> dict[str, np.ndarray] | None:
    """The root's world rotation with its heading turned away: channel -> angles (degrees).

    The root's world rotation is turned back by its heading (:func:`heading` on the
    body axis ``frame[0]``) less the offset ``frame[1]`` (:func:`body_frame`), and
    decomposed in its rotation order. None when the root does not have three rotation
    channels in that order.
    """
    joint = motion.skeleton.joints[motion.skeleton.index(root)]
    rotations = _rotation_channels(joint)
    if rotations is None:
        return None
    angles = _free(global_rotation(motion, root), frame[0], frame[1], joint.rotation_order)
    return {c: angles[:, i] for i, c in enumerate(rotations)}


def _free(world, axis, offset, order) -> np.ndarray:
    h, _ = heading(world, axis)
    return euler_angles(yaw_matrices(offset - h) @ world, order)


def _is_angle(channel: str) -> bool:
    return channel.rsplit(".", 1)[-1] in ("rx", "ry", "rz")


def _rotation_channels(joint):
    """A joint's three rotation channels in its rotation order, or None."""
    rotations = [c for c in joint.channels if c.rsplit(".", 1)[1].startswith("r")]
    if len(rotations) != 3 or any(joint.axis) or \
            "".join(c[-1].upper() for c in rotations) != joint.rotation_order.upper():
        return None
    return rotations


def own_period(values, expected: int) -> int | None:
    """A take's own period (frames) near ``expected``, from the autocorrelation of ``values``.

    Among the lags within 0.6 to 1.5 times ``expected`` where the autocorrelation peaks
    (a local maximum inside that range), the first that correlates nearly as well (within
    10%) as the best peak: two periods correlate as well as one, so the first is the
    period. None when the take is too short for those lags or the autocorrelation has no
    peak there (a smooth take correlates best at the shortest lag, which is no period).

    >>> import numpy as np
    >>> own_period(np.sin(2 * np.pi * np.arange(200) / 26), 20)
    26
    """
    x = np.asarray(values, float)
    centred = x - x.mean()
    lags = np.arange(max(2, int(0.6 * expected)), min(int(1.5 * expected), x.size - 2) + 1)
    if not lags.size:
        return None
    auto = np.array([float(centred[:-k] @ centred[k:]) / (x.size - k) for k in lags])
    peaks = [i for i in range(1, auto.size - 1) if auto[i - 1] <= auto[i] >= auto[i + 1]]
    if not peaks:
        return None
    best = max(auto[i] for i in peaks)
    return int(lags[next(i for i in peaks if auto[i] >= best - 0.1 * abs(best))])


def nearest_turn(values, reference: float) -> np.ndarray:
    """Angles (degrees) shifted by the whole turns that bring their mean nearest ``reference``.

    Angles 360° apart are one rotation, but two takes of one pose can be read on either
    side of ±180° (a root turned back by its heading sits there): their means are only
    comparable, or worth averaging, on one side.

    >>> nearest_turn([179.0, -179.0 + 360.0], -178.0).tolist()
    [-181.0, -179.0]
    """
    x = np.asarray(values, float)
    return x - 360.0 * np.round((x.mean() - reference) / 360.0)


def cycle_starts(leader, template) -> list[int]:
    """Frames where each cycle of ``template`` (one generated period) begins in ``leader``, and where the last ends.

    The take's own period is first read from its autocorrelation (the first lag within
    0.6 to 1.5 template lengths that correlates nearly as well as the best), and the template stretched to it, so that a slower or
    faster style is matched at its own tempo; the first start is then the
    best-correlating offset within one period, each next one the best within a quarter
    period of one period on.

    Examples
    --------
    >>> import numpy as np
    >>> take = np.sin(2 * np.pi * (np.arange(100) - 5) / 25)
    >>> cycle_starts(take, np.sin(2 * np.pi * np.arange(20) / 20))
    [5, 30, 55, 80]
    """
    x = np.asarray(leader, float)
    g = np.asarray(template, float)
    n = g.size
    if x.size < n or n < 2 or not np.any(g - g.mean()):
        return []
    own = own_period(x, n)
    if own is not None:
        g = np.interp(np.linspace(0, n, own, endpoint=False), np.arange(n + 1), np.append(g, g[0]))
    g = g - g.mean()
    p = g.size
    if x.size < p:
        return []
    windows = np.lib.stride_tricks.sliding_window_view(x, p)
    score = (windows - windows.mean(axis=1, keepdims=True)) @ g
    starts = [int(np.argmax(score[:p]))]
    while True:
        lo, hi = starts[-1] + p - p // 4, starts[-1] + p + p // 4
        if hi > score.size - 1:  # the search must fit: at the take's end its edge would win
            # the last cycle ends one period on, when the take holds it
            return starts + [starts[-1] + p] if starts[-1] + p < x.size else starts
        starts.append(lo + int(np.argmax(score[lo:hi + 1])))


def mean_cycles(curves, starts, period: int) -> dict[str, np.ndarray]:
    """Per channel the mean of its cycles, each resampled to ``period`` frames, closed on itself.

    ``curves`` is one dict per performance (channel -> angles), ``starts`` the matching
    cycle bounds (:func:`cycle_starts`); a cycle runs from one to the next. The mean's end is brought back to its
    start by a linear ramp, so the cycles repeat without a jump.

    Examples
    --------
    Two takes of a sine, one twice as slow, give back the sine:

    >>> import numpy as np
    >>> a = np.sin(2 * np.pi * np.arange(60) / 20)
    >>> b = np.sin(2 * np.pi * np.arange(120) / 40)
    >>> got = mean_cycles([{"c": a}, {"c": b}], [[0, 20, 40], [0, 40, 80]], 20)["c"]
    >>> bool(np.allclose(got, np.sin(2 * np.pi * np.arange(20) / 20), atol=0.02))
    True
    """
    sums: dict[str, np.ndarray] = {}
    counts: dict[str, int] = {}
    phase = np.linspace(0.0, 1.0, period + 1)
    for take, begins in zip(curves, starts):
        for channel, values in take.items():
            values = np.asarray(values, float)
            for s, e in zip(begins, begins[1:]):
                if e >= values.size or e - s < 2:
                    continue
                cycle = np.interp(s + phase * (e - s), np.arange(values.size), values)
                sums[channel] = sums.get(channel, 0.0) + cycle
                counts[channel] = counts.get(channel, 0) + 1
    out = {}
    for channel, total in sums.items():
        mean = total / counts[channel]
        mean = mean - (mean[-1] - mean[0]) * phase  # closed: the end meets the start
        out[channel] = mean[:-1]
    return out


@dataclass(frozen=True, eq=False)
class Body:
    """What an action's performances say about the channels the grammar does not drive.

    Built by :func:`body_of`. ``root`` is the joint that travels (None when the
    performances cannot tell: no skeleton, no file that reads), ``carrier`` the joint
    above it whose channels are all still in the takes (Bandai's ``joint_Root``), which
    generation turns and moves so that the root's own channels keep their generated
    values; ``curves`` per performance the channels' angles with the root's rotation
    heading-free and its horizontal position removed (the travel puts it back);
    ``centre`` their mean per channel; ``travel`` the mean of their :class:`Travel`,
    ``course`` the mean of their :class:`Course` (where the body goes over a take: a walk
    advances, a turn goes straight, turns and goes on, as the takes do); ``offset`` the
    heading (radians) the root's heading-free rotation faces (:func:`body_frame`), which
    the travel's direction adds to the turn; ``drift`` per angle channel the slow part of
    its course over a take (:func:`channel_drift`: a head turned into a turn and back), on
    the clock of ``course``.
    """

    performances: tuple = ()
    root: str | None = None
    carrier: str | None = None
    axis: int | None = None
    curves: tuple = ()
    centre: dict | None = None
    travel: Travel | None = None
    course: Course | None = None
    offset: float = 0.0
    drift: dict | None = None


def _source_take(record):
    """The take whose skeleton and channels generation writes on: the record's first
    performance, read at the path build was given (the records keep it as given)."""
    import kinetology

    try:
        return kinetology.read(record.skeleton_source)
    except FileNotFoundError:
        raise ValueError(f"{record.skeleton_source}: no such file: the skeleton of "
                         f"{record.name!r} is read from its first performance, at the path "
                         f"build was given (a relative one is relative to the folder build ran "
                         f"in: run from there, or build from absolute paths)") from None


def _still(motions, channels) -> bool:
    return all(float(np.abs(m.column(c)).max()) < 1e-6 for m in motions for c in channels
               if c in m.channels)


def body_of(record, channels, driven, period: float | None = None,
            style: str | None = None, performances=None) -> Body:
    """The :class:`Body` of an action's performances, for a motion with ``channels``.

    ``driven`` are the channels the grammar system makes (the actuators' channels);
    ``period`` the action's period in seconds (the course is averaged over one, see
    :func:`course`); ``style`` keeps the performances of that style only
    (:func:`performances_of`); ``performances`` are the action's motions when already
    read (all of them: the style is picked by their file names), else they are read here.
    """
    if performances is None:
        performances = performances_of(record, style)
    elif style is not None:
        performances = [m for m in performances if style in style_of(m.source)]
    takes = [m for m in performances if m.skeleton is not None
             and set(channels) <= set(m.channels)]
    if not takes:
        return Body()
    skeleton = takes[0].skeleton
    roots = [j.name for j in skeleton.joints
             if f"{j.name}.tx" in channels and f"{j.name}.tz" in channels]
    if not roots:
        return Body(tuple(takes))
    root = max(roots, key=lambda r: sum(float(np.ptp(m.column(f"{r}.tx")) +
                                              np.ptp(m.column(f"{r}.tz"))) for m in takes))
    frame = body_frame(takes, root)
    axis = frame[0]
    top = skeleton.joints[root_chain(skeleton, root)[0]]
    carrier = None
    if top.name != root and {f"{top.name}.{a}" for a in ("tx", "tz", "ry")} <= set(channels) \
            and not set(top.channels) & set(driven) and _still(takes, top.channels):
        carrier = top.name
    from kinetology.segmentation import unwrap

    curves = []
    for m in takes:
        # a joint that hangs near ±180° (Bandai's legs) is written wrapped, jumping between
        # +179° and -179°: its angles are only averaged, or cycled, once made continuous
        take = {c: unwrap(m.column(c)) if _is_angle(c) else m.column(c) for c in channels}
        free = heading_free_angles(m, root, frame)
        if free is not None:
            take.update(free)
        for a in ("tx", "tz"):  # the horizontal path is the travel's
            take[f"{root}.{a}"] = np.zeros(m.frames)
        if curves:  # every take's angles on the first's side of ±180°, to be averaged
            take = {c: nearest_turn(v, float(np.mean(curves[0][c]))) if _is_angle(c) else v
                    for c, v in take.items()}
        curves.append(take)
    centre = {c: float(np.mean([np.mean(t[c]) for t in curves])) for c in channels}
    moves = [travel(m, root, axis) for m in takes]
    mean = Travel(*(float(np.mean([getattr(t, k) for t in moves]))
                    for k in ("forward", "sideways", "turn", "speed")))
    path = mean_course(course(m, root, axis, period) for m in takes)
    width = max(1, int(round((period or 0.0) * float(takes[0].frame_rate))))
    drift = {c: channel_drift([t[c] for t in curves], width) for c in channels if _is_angle(c)}
    return Body(tuple(takes), root, carrier, axis, tuple(curves), centre, mean, path,
                float(frame[1]), drift)


def whole_cycle(body: Body, period: float, rate: float, most: int = 3) -> int:
    """How many periods of the morphemes make one cycle of the whole body (1, 2 or 3).

    A learnt morpheme may be half a stride: the hip swings once in it, but the left and
    right legs take turns, so the body repeats only every second one. Per multiple ``m``
    of ``period``, the performances' channels (``body.curves``) are correlated with
    themselves about ``m`` periods on (the best lag within 15%), each channel's
    correlation normalised and averaged over the channels that move; the cycle is the
    smallest multiple that correlates nearly as well (within 0.1) as the best. 1 when
    the takes are too short to tell.
    """
    steps = period * rate
    scores = []
    for m in range(1, most + 1):
        found = []
        for take in body.curves:
            moving = [np.asarray(v, float) - np.mean(v) for c, v in take.items()
                      if _is_angle(c) and np.ptp(v) > 1.0]
            if not moving:
                continue
            x = np.stack(moving)
            energy = np.maximum((x * x).sum(axis=1), 1e-12)
            lags = range(max(1, int(0.85 * m * steps)), int(1.15 * m * steps) + 1)
            best = [float(np.mean((x[:, :-k] * x[:, k:]).sum(axis=1) / energy *
                                  x.shape[1] / (x.shape[1] - k)))
                    for k in lags if k < x.shape[1] - steps / 2]
            if best:
                found.append(max(best))
        if not found:
            break
        scores.append(float(np.mean(found)))
    if not scores:
        return 1
    return next(m for m, r in enumerate(scores, 1) if r >= max(scores) - 0.1)


def channel_drift(curves, width: int, samples: int = 101) -> np.ndarray:
    """The mean slow course of one channel over its takes, each in its own time (0 to 1).

    Each take's angles averaged over ``width`` frames (one period) about each frame, less
    their mean: what stays is where the joint goes over the take (a head that turns into
    a turn and back), not each cycle's swing, which the mean cycle gives.

    >>> import numpy as np
    >>> ramp = np.linspace(-1.0, 1.0, 50) + np.sin(2 * np.pi * np.arange(50) / 10)
    >>> got = channel_drift([ramp], 10, samples=3)
    >>> bool(got[0] < -0.4 and abs(got[1]) < 0.05 and got[2] > 0.4)   # the ramp, not the sine
    True
    """
    u = np.linspace(0.0, 1.0, samples)
    out = []
    for x in curves:
        x = np.asarray(x, float)
        slow = _moving_mean(x, width) - x.mean()
        out.append(np.interp(u, np.linspace(0.0, 1.0, x.size), slow))
    return np.mean(out, axis=0)


def animate(values, channels, body: Body, driven, rate: float, period: float,
            drifting=()) -> None:
    """Fill the channels the grammar does not drive, and move the root; ``values`` in place.

    Every channel not in ``driven`` takes the performances' mean cycle, phase-aligned
    to the generated channel that moves most (the leader): generated copy ``k`` begins
    at ``k * period``, and so does each cycle laid here. The root then follows the
    performances' mean course (:class:`Course`, stretched over the generated take; their
    mean rates when there is none): on ``body.carrier`` when there is one (the
    root's channels keep their values), else on the root itself, whose rotation takes
    the turn only when no rotation channel of it is driven (a driven channel keeps its
    generated values, so the turn is left out).

    ``drifting`` are driven root rotation channels whose morpheme only rises or only
    falls: a root's Euler angle that flips by 180° as the body turns through the gimbal
    angle reads as one long rise, and generated as such it would spin the body. With a
    carrier, such a channel keeps its generated values (and kineteme string), and the
    carrier's rotation undoes it in the world: the body takes that channel's mean cycle
    instead.
    """
    if body.centre is None:
        return
    index = {c: i for i, c in enumerate(channels)}
    frames = values.shape[0]
    steps = max(2, int(round(period * rate)))
    own = {body.root, body.carrier}
    leaders = [c for c in driven if c.split(".")[0] not in own] or list(driven)
    if leaders:
        leader = max(leaders, key=lambda c: float(np.ptp(values[:, index[c]])))
        template = values[:steps, index[leader]]
        starts = [cycle_starts(m.column(leader), template) for m in body.performances]
        cycles = mean_cycles([{c: v for c, v in t.items() if c not in driven or c in drifting}
                              for t in body.curves], starts, steps)
    else:
        cycles = {}
    phase = np.arange(frames) * steps / (period * rate)
    typical = {c: np.interp(phase, np.arange(steps), cycle, period=steps)
               for c, cycle in cycles.items()}
    seconds = body.course.seconds if body.course is not None else None
    when = course_time(frames, rate, seconds)
    for c in channels:
        if c not in driven:
            values[:, index[c]] = typical.get(c, body.centre.get(c, values[0, index[c]]))
            if body.drift and c in body.drift:
                values[:, index[c]] += np.interp(when, np.linspace(0.0, 1.0, body.drift[c].size),
                                                 body.drift[c])
    _move(values, index, body, rate, driven, {c: typical[c] for c in drifting if c in typical})
    _wrap_as_written(values, channels, body.performances)


def _wrap_as_written(values, channels, performances) -> None:
    """Angles written in [-180°, 180°) where every performance writes them so, ``values`` in place.

    The same rotation reads as +179° or -181°; a capture that writes its angles wrapped
    (a leg hanging near ±180° jumps between the two) is matched by generated angles written
    the same way. Segmenting unwraps them again, so the kineteme strings do not change.
    """
    for i, c in enumerate(channels):
        if _is_angle(c) and performances and all(
                c in m.channels and float(np.abs(m.column(c)).max()) <= 180.0
                for m in performances):
            values[:, i] = (values[:, i] + 180.0) % 360.0 - 180.0


def _move(values, index, body: Body, rate: float, driven, undo) -> None:
    if body.course is not None:  # the performances' course, over the generated take
        h, forward, sideways = body.course.at(values.shape[0], rate)
    else:
        h = np.radians(body.travel.turn) * np.arange(values.shape[0]) / rate
        forward, sideways = body.travel.forward, body.travel.sideways
    # the heading-free body faces body.offset: turned by h, it faces h + offset, and its
    # velocity, measured along and across its facing, is laid that way
    facing = h + body.offset
    vx = np.sin(facing) * forward + np.cos(facing) * sideways
    vz = np.cos(facing) * forward - np.sin(facing) * sideways
    path = {a: np.concatenate(([0.0], np.cumsum((v[1:] + v[:-1]) / 2) / rate))
            for a, v in (("tx", vx), ("tz", vz))}
    holder = body.carrier or body.root
    for a, p in path.items():
        values[:, index[f"{holder}.{a}"]] += p
    skeleton = body.performances[0].skeleton
    joint = skeleton.joints[skeleton.index(body.root)]
    rotations = _rotation_channels(joint)
    if body.carrier is None:
        if joint.parent is not None or rotations is None or set(rotations) & set(driven):
            return  # a turn composed under a moving parent, or over driven angles, is left out
        _set_rotation(values, index, joint, yaw_matrices(h) @ _rotation(values, index, joint))
        return
    carrier = skeleton.joints[skeleton.index(body.carrier)]
    turn = yaw_matrices(h)
    if undo and rotations is not None:  # world = yaw @ wanted: the carrier is yaw @ wanted @ own^-1
        own = _rotation(values, index, joint)
        wanted = _rotation({**{c: values[:, index[c]] for c in rotations}, **undo}, None, joint)
        turn = turn @ wanted @ np.swapaxes(own, 1, 2)
    if _rotation_channels(carrier) is None:
        values[:, index[f"{body.carrier}.ry"]] += np.degrees(h)
        return
    _set_rotation(values, index, carrier, turn)
    # the root sits where the heading alone would put it, whatever else the carrier turns
    own_t = np.stack([values[:, index[f"{body.root}.{a}"]] if f"{body.root}.{a}" in index
                      else np.zeros(len(h)) for a in ("tx", "ty", "tz")], axis=1)
    shift = np.einsum("fij,fj->fi", yaw_matrices(h) - turn, own_t)
    for i, a in enumerate(("tx", "ty", "tz")):
        if f"{body.carrier}.{a}" in index:
            values[:, index[f"{body.carrier}.{a}"]] += shift[:, i]


def _rotation(values, index, joint) -> np.ndarray:
    """A joint's local rotation per frame from its channels' values (an array, or a dict)."""
    from kinetology.kinematics import rotation_matrices

    column = (lambda c: values[c]) if index is None else (lambda c: values[:, index[c]])
    angles = {c[-1].upper(): column(c) for c in _rotation_channels(joint)}
    return rotation_matrices(angles, joint.rotation_order, len(next(iter(angles.values()))))


def _set_rotation(values, index, joint, matrices) -> None:
    angles = euler_angles(matrices, joint.rotation_order)
    for i, c in enumerate(_rotation_channels(joint)):
        values[:, index[c]] = angles[:, i]
