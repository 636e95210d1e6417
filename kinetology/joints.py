"""Actuators are joints: which joint each channel moves, and each joint's parent.

A channel belongs to the skeleton joint that lists it (BVH ``CHANNELS``, ASF ``dof``).
Without a skeleton (an AMC file read with no ASF) the **dot rule** applies: the actuator is
the part of the name before the first dot (``lfemur.rx`` -> ``lfemur``; a name without a dot
is its own actuator). The parents then come from the **CMU standard skeleton** (the
``:hierarchy`` every CMU ASF file shares) when every actuator is a CMU bone name, and are
unknown (an empty map) otherwise.

Parents skip joints that move no channel (CMU's ``lhipjoint``, BVH end sites): a joint's
parent is its nearest ancestor that is an actuator, so that "a skeleton neighbour" means a
neighbour that can move.
"""

from __future__ import annotations

from types import MappingProxyType
from typing import Iterable, Mapping

from psgs.errors import ValidationError

from .motion import Motion, check_motion

__all__ = ["CMU_PARENTS", "dot_actuator", "actuator_map", "skeleton_parents"]

#: Parent of each bone in the CMU ASF skeleton (the ``:hierarchy`` of every CMU subject).
CMU_PARENTS = MappingProxyType({
    "root": None, "lhipjoint": "root", "rhipjoint": "root", "lowerback": "root",
    "lfemur": "lhipjoint", "ltibia": "lfemur", "lfoot": "ltibia", "ltoes": "lfoot",
    "rfemur": "rhipjoint", "rtibia": "rfemur", "rfoot": "rtibia", "rtoes": "rfoot",
    "upperback": "lowerback", "thorax": "upperback", "lowerneck": "thorax",
    "upperneck": "lowerneck", "head": "upperneck", "lclavicle": "thorax",
    "rclavicle": "thorax", "lhumerus": "lclavicle", "lradius": "lhumerus",
    "lwrist": "lradius", "lhand": "lwrist", "lthumb": "lwrist", "lfingers": "lhand",
    "rhumerus": "rclavicle", "rradius": "rhumerus", "rwrist": "rradius", "rhand": "rwrist",
    "rthumb": "rwrist", "rfingers": "rhand",
})


def dot_actuator(channel: str) -> str:
    """The actuator of a channel by the dot rule: the name before the first dot.

    Parameters
    ----------
    channel : str
        A channel name such as ``lfemur.rx``.

    Returns
    -------
    str
        The part before the first dot (the whole name when there is none).

    Examples
    --------
    >>> dot_actuator("lfemur.rx"), dot_actuator("knee")
    ('lfemur', 'knee')
    """
    return channel.split(".", 1)[0]


def actuator_map(motion: Motion, channels: Iterable[str] | None = None) -> dict[str, str]:
    """Channel -> actuator (joint name) for ``channels`` of ``motion`` (default: all).

    The skeleton joint that lists the channel, else the dot rule.

    Parameters
    ----------
    motion : Motion
        The motion (its skeleton, when it has one, names the joints).
    channels : iterable of str, optional
        The channels to map (default: all of the motion's).

    Returns
    -------
    dict
        ``{channel: joint}`` in the order given.

    Raises
    ------
    ValueError
        (ValidationError) When ``motion`` is no Motion or ``channels`` is one string.

    Examples
    --------
    >>> import numpy as np
    >>> m = Motion(np.zeros((2, 2)), ("lfemur.rx", "lfemur.ry"), 120)
    >>> actuator_map(m)
    {'lfemur.rx': 'lfemur', 'lfemur.ry': 'lfemur'}
    """
    check_motion(motion)
    if isinstance(channels, str):  # would be mapped letter by letter
        raise ValidationError(f"channels must be a collection of names, not {channels!r}")
    owner = {}
    if motion.skeleton is not None:
        for joint in motion.skeleton.joints:
            for channel in joint.channels:
                owner[channel] = joint.name
    names = motion.channels if channels is None else tuple(channels)
    return {c: owner.get(c, dot_actuator(c)) for c in names}


def skeleton_parents(motion: Motion, actuators: Iterable[str]) -> dict[str, str | None]:
    """Actuator -> parent actuator (None for a root) from the motion's skeleton.

    Only ``actuators`` appear, and a parent is always one of them (the nearest ancestor
    that is). Without a skeleton: the CMU standard hierarchy when every actuator is a CMU
    bone, else ``{}`` (unknown).

    Parameters
    ----------
    motion : Motion
        The motion whose skeleton gives the hierarchy (or None: the fallback above).
    actuators : iterable of str
        The joints to give parents to.

    Returns
    -------
    dict
        ``{joint: parent or None}``, empty when the hierarchy is unknown.

    Raises
    ------
    ValueError
        (ValidationError) When ``actuators`` is one string.

    Examples
    --------
    >>> import numpy as np
    >>> m = Motion(np.zeros((2, 2)), ("lfemur.rx", "ltibia.rx"), 120)
    >>> skeleton_parents(m, ["lfemur", "ltibia"])
    {'lfemur': None, 'ltibia': 'lfemur'}
    """
    if isinstance(actuators, str):  # would be read letter by letter
        raise ValidationError(f"actuators must be a collection of names, not {actuators!r}")
    wanted = list(dict.fromkeys(actuators))
    parent_of: Mapping[str, str | None]
    if motion.skeleton is not None:
        joints = motion.skeleton.joints
        parent_of = {j.name: (joints[j.parent].name if j.parent is not None else None)
                     for j in joints}
    elif wanted and all(a in CMU_PARENTS for a in wanted):
        parent_of = CMU_PARENTS
    else:
        return {}
    keep = set(wanted)
    out = {}
    for name in wanted:
        up = parent_of.get(name)
        while up is not None and up not in keep:
            up = parent_of.get(up)
        out[name] = up
    return out
