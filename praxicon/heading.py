"""Where a root faces and where it goes: its heading, its travel, its course over a take.

A root's Euler angles are a poor measure of where a body faces (Bandai Namco's ``Hips``
turns ``Z X Y`` with ``rz`` near 90°, so its heading is mostly ``rx``, and a turn through
``rx = ±90°`` flips ``rz`` and ``ry`` by 180°). The heading (:func:`heading`) is read from the
root's world rotation instead (:func:`global_rotation`): the body axis that stays most
horizontal, its direction about the vertical (``y``), unwrapped. The root's velocity is
measured in that heading's frame (forward, sideways): :func:`travel` over a whole take,
:func:`course` along it. Used by :mod:`praxicon.body_motion`, which re-exports all of it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Course", "Travel", "course", "course_time", "global_rotation", "heading", "mean_course",
           "root_chain", "travel", "yaw_matrices"]

_UP = 1  # y is vertical in BVH and in the ASF files of the shared data


def root_chain(skeleton, root: str) -> list[int]:
    """Indices of the joints from the skeleton's top down to ``root`` (inclusive)."""
    chain = [skeleton.index(root)]
    while skeleton.joints[chain[-1]].parent is not None:
        chain.append(skeleton.joints[chain[-1]].parent)
    return chain[::-1]


def global_rotation(motion, root: str) -> np.ndarray:
    """Per frame the world rotation of joint ``root``, shape ``(frames, 3, 3)``."""
    from kinetology.kinematics import local_rotation

    out = np.broadcast_to(np.eye(3), (motion.frames, 3, 3)).copy()
    for j in root_chain(motion.skeleton, root):
        out = out @ local_rotation(motion, motion.skeleton.joints[j])
    return out


def yaw_matrices(radians) -> np.ndarray:
    """Rotations about the vertical by ``radians`` (one per frame): ``Ry``."""
    from kinetology.kinematics import axis_rotation

    return axis_rotation("Y", radians)


def heading(rotations, axis: int | None = None) -> tuple[np.ndarray, int]:
    """The unwrapped heading (radians about the vertical) of rotations, and the body axis used.

    The body axis (0, 1, 2: local x, y, z) is the one that stays most horizontal over
    the frames (unless given); the heading is its direction's angle from ``+z``
    towards ``+x``, so that ``yaw_matrices(-h) @ R`` turns the axis back onto ``+z``.

    Examples
    --------
    A body turning steadily by 90° over 10 frames:

    >>> import numpy as np
    >>> h, axis = heading(yaw_matrices(np.linspace(0, np.pi / 2, 10)))
    >>> axis, round(float(np.degrees(h[-1] - h[0])), 6)   # x and z level: the first
    (0, 90.0)
    """
    r = np.asarray(rotations, float)
    if axis is None:
        axis = int(np.argmin(np.abs(r[:, _UP, :]).mean(axis=0)))
    d = r[:, :, axis]
    return np.unwrap(np.arctan2(d[:, 0], d[:, 2])), axis




@dataclass(frozen=True)
class Travel:
    """How a root moves: mean speed in its own heading's frame and mean turning rate.

    Attributes
    ----------
    forward, sideways : float
        Mean velocity along the heading and across it (length units per second).
    turn : float
        Net change of heading over the take per second (degrees per second).
    speed : float
        Mean horizontal speed, whatever the direction (length units per second).
    """

    forward: float
    sideways: float
    turn: float
    speed: float


def _world_positions(motion, root: str) -> np.ndarray:
    from kinetology.kinematics import forward_kinematics

    return forward_kinematics(motion)[:, motion.skeleton.index(root)]


def _body_velocity(motion, root: str, axis: int | None):
    """Per frame the root's heading, world velocity, and that velocity seen from the body
    (turned back by the heading at that frame): ``(h, v, forward, sideways)``."""
    h, _ = heading(global_rotation(motion, root), axis)
    v = np.gradient(_world_positions(motion, root), axis=0) * float(motion.frame_rate)
    forward = np.cos(h) * v[:, 2] + np.sin(h) * v[:, 0]
    sideways = np.cos(h) * v[:, 0] - np.sin(h) * v[:, 2]
    return h, v, forward, sideways


def travel(motion, root: str, axis: int | None = None) -> Travel | None:
    """The root's :class:`Travel` over a motion with a skeleton (None under two frames).

    Examples
    --------
    >>> import numpy as np, kinetology
    >>> from kinetology.motion import Joint, Skeleton
    >>> sk = Skeleton((Joint("hip", None, (0, 0, 0), ("hip.tx", "hip.tz", "hip.ry"), "ZXY"),))
    >>> t = np.arange(31) / 30.0                  # one second: 90° of turn, 100 units ahead
    >>> h = np.radians(90.0 * t)
    >>> x, z = np.cumsum(100 * np.sin(h)) / 30, np.cumsum(100 * np.cos(h)) / 30
    >>> m = kinetology.Motion(np.c_[x, z, np.degrees(h)], ("hip.tx", "hip.tz", "hip.ry"), 30.0, sk)
    >>> got = travel(m, "hip")
    >>> round(got.speed), round(got.turn)
    (100, 90)
    """
    if motion.frames < 2:
        return None
    rate = float(motion.frame_rate)
    h, v, forward, sideways = _body_velocity(motion, root, axis)
    seconds = (motion.frames - 1) / rate
    return Travel(float(forward.mean()), float(sideways.mean()),
                  float(np.degrees(h[-1] - h[0]) / seconds),
                  float(np.hypot(v[:, 0], v[:, 2]).mean()))


@dataclass(frozen=True, eq=False)
class Course:
    """Where a root goes over a take, in the take's own time from 0 (start) to 1 (end).

    Attributes
    ----------
    heading : numpy.ndarray
        Heading change since the start (radians), at evenly spaced points of the take.
    forward, sideways : numpy.ndarray
        The velocity in the heading's frame at the same points (length units per second).
    """

    heading: np.ndarray
    forward: np.ndarray
    sideways: np.ndarray
    seconds: float | None = None

    def at(self, frames: int, rate: float | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Heading (from 0), forward and sideways velocity at ``frames`` frames.

        Without ``rate`` (or without the take's ``seconds``), the course is stretched over
        the frames. With it, the frames keep the take's own clock: a shorter motion is
        the middle of the course (a turn turns at the takes' rate, not faster), a longer
        one goes on straight at the course's ends.

        >>> import numpy as np
        >>> c = Course(np.array([0.0, 0.0, 1.0, 1.0]), np.ones(4), np.zeros(4), seconds=3.0)
        >>> np.round(c.at(3, rate=1.0)[0], 3).tolist()   # 2 s of a 3 s course: its middle
        [0.0, 0.5, 1.0]
        """
        t = np.linspace(0.0, 1.0, self.heading.size)
        u = course_time(frames, rate, self.seconds)
        h, forward, sideways = (np.interp(u, t, x) for x in (self.heading, self.forward,
                                                             self.sideways))
        return h - h[0], forward, sideways


def course_time(frames: int, rate: float | None, seconds: float | None) -> np.ndarray:
    """Per generated frame, where it falls in a take of ``seconds`` (0: start, 1: end).

    Without ``rate`` or ``seconds``: the frames spread over the whole take. With them, on
    the take's own clock: a shorter motion is the take's middle, a longer one holds the
    ends (0 and 1) beyond it.

    >>> course_time(3, 1.0, 4.0).tolist(), course_time(3, 1.0, 1.0).tolist()
    ([0.25, 0.5, 0.75], [0.0, 0.5, 1.0])
    """
    u = np.linspace(0.0, 1.0, frames)
    if rate and seconds:
        length = (frames - 1) / float(rate) / seconds
        u = np.clip(0.5 - length / 2 + u * length, 0.0, 1.0)
    return u


def _moving_mean(x: np.ndarray, width: int) -> np.ndarray:
    if width < 2 or x.size < 2:
        return x
    padded = np.pad(x, (width // 2, width - 1 - width // 2), mode="edge")
    return np.convolve(padded, np.ones(width) / width, mode="valid")


def course(motion, root: str, axis: int | None = None, period: float | None = None,
           samples: int = 101) -> Course | None:
    """The root's :class:`Course` over a motion (None under two frames).

    With ``period`` (seconds), the heading and the velocity are first averaged over one
    period about each frame: what stays is where the body goes, not the sway of each step
    (a mean over exactly one cycle removes a periodic component whatever its shape).

    Examples
    --------
    A root that goes straight for a second, then turns 90° in the next:

    >>> import numpy as np, kinetology
    >>> from kinetology.motion import Joint, Skeleton
    >>> sk = Skeleton((Joint("hip", None, (0, 0, 0), ("hip.tx", "hip.tz", "hip.ry"), "ZXY"),))
    >>> h = np.radians(np.r_[np.zeros(30), np.linspace(0, 90, 31)])
    >>> x, z = np.cumsum(100 * np.sin(h)) / 30, np.cumsum(100 * np.cos(h)) / 30
    >>> m = kinetology.Motion(np.c_[x, z, np.degrees(h)], ("hip.tx", "hip.tz", "hip.ry"), 30.0, sk)
    >>> c = course(m, "hip", axis=2, samples=3)   # the body faces along its local z
    >>> np.round(np.degrees(c.heading)).tolist(), np.round(c.forward).tolist()
    ([0.0, 0.0, 90.0], [100.0, 100.0, 100.0])
    """
    if motion.frames < 2:
        return None
    rate = float(motion.frame_rate)
    h, _, forward, sideways = _body_velocity(motion, root, axis)
    width = int(round(period * rate)) if period else 1
    h, forward, sideways = (_moving_mean(x, width) for x in (h - h[0], forward, sideways))
    t = np.linspace(0.0, 1.0, motion.frames)
    u = np.linspace(0.0, 1.0, samples)
    return Course(*(np.interp(u, t, x) for x in (h - h[0], forward, sideways)),
                  seconds=(motion.frames - 1) / rate)


def mean_course(courses) -> Course:
    """The point-wise mean of several :class:`Course` values of one length.

    >>> import numpy as np
    >>> a = Course(np.array([0.0, 1.0]), np.array([100.0, 100.0]), np.zeros(2))
    >>> b = Course(np.array([0.0, 2.0]), np.array([50.0, 50.0]), np.zeros(2))
    >>> mean_course([a, b]).heading.tolist()
    [0.0, 1.5]
    """
    courses = list(courses)
    seconds = [c.seconds for c in courses]
    return Course(*(np.mean([getattr(c, k) for c in courses], axis=0)
                    for k in ("heading", "forward", "sideways")),
                  seconds=float(np.mean(seconds)) if None not in seconds else None)
