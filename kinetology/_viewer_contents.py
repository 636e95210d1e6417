"""What a panel of :func:`kinetology.view` shows of its motion besides the joints' positions:
its title, the frames kept (every ``step``-th), the state each joint is in at each of them
(its kineteme, ``B G R Y``, or ``-`` when it does not move), and the joints ringed as
actuators.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Iterable

import numpy as np

from .motion import Motion

__all__ = ["titled", "frame_step", "joint_states", "actuator_problem", "actuator_flags"]


def titled(motions: Iterable) -> dict:
    """Panels titled by file name; a name that repeats (a/walk.bvh, b/walk.bvh) gets its
    position added, so that every motion keeps its panel."""
    motions = list(motions)
    names = [Path(m.source).name if isinstance(m, Motion) else str(i)
             for i, m in enumerate(motions)]
    return {(name if names.count(name) == 1 else f"{name} ({i + 1})"): m
            for i, (name, m) in enumerate(zip(names, motions))}


def frame_step(motion: Motion, max_rate: float, max_frames: int) -> int:
    """The smallest step between kept frames that keeps at most ``max_rate`` frames a second
    and at most ``max_frames`` frames."""
    by_rate = math.ceil(motion.frame_rate / max_rate - 1e-9)
    by_count = math.ceil(motion.frames / max_frames)
    return max(1, by_rate, by_count)


def joint_states(motion: Motion, step: int, params: dict) -> tuple[str, ...]:
    """Per joint, the state letter of its widest moving rotation channel at each kept frame."""
    from .segmentation import STATES, segments, unwrap

    found = segments(motion, engine="numpy", **params)
    letters = np.array([*STATES])
    codes = {c: np.repeat(found.codes[i], np.diff(found.borders[i]))[::step]
             for i, c in enumerate(found.channels)}
    kept = math.ceil(motion.frames / step)
    out = []
    for joint in motion.skeleton.joints:
        moving = [c for c in joint.channels if c in codes]
        if not moving:
            out.append("-" * kept)
            continue
        widest = max(moving, key=lambda c: float(np.ptp(unwrap(motion.column(c)))))
        out.append("".join(letters[codes[widest]]))
    return tuple(out)


def actuator_problem(motion: Motion, names: Iterable[str] | None) -> str | None:
    """The first of ``names`` that is neither a joint nor a channel of ``motion``, in words
    for the caller's :class:`~kinetology.viewer.ViewError` (None: every one is)."""
    joints = motion.skeleton.names
    for name in names or ():
        if name not in joints and name not in motion.channels:
            return f"no joint or channel {name!r} to highlight (joints: {', '.join(joints)})"
    return None


def actuator_flags(motion: Motion, names: Iterable[str] | None) -> tuple[bool, ...]:
    """Per joint, whether it is one of ``names``, or lists a channel among them (a channel
    stands for the joint that lists it); ``names`` as :func:`actuator_problem` accepts."""
    joints = motion.skeleton.names
    chosen = set()
    for name in names or ():
        if name in joints:
            chosen.add(name)
        elif name in motion.channels:  # a channel stands for the joint that lists it
            chosen.update(j.name for j in motion.skeleton.joints if name in j.channels)
    return tuple(j in chosen for j in joints)
