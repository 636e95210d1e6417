"""What a record's names must be, each check giving the problem as one line (``None`` when
there is none) for the reader to raise naming its file: an action's name, which names its
files, and a learnt record's channel keys, which generation looks each channel up by.
"""

from __future__ import annotations

from .jsonvalues import shown

__all__ = ["MAX_NAME_BYTES", "name_problem", "channels_problem", "component_problem",
           "lookup_problem"]

#: The axes of a channel ``JOINT.AXIS`` (``kinetology.AXES``: kept here, so that reading a
#: record does not import kinetology).
_AXES = ("tx", "ty", "tz", "rx", "ry", "rz")


#: Longest action name in bytes (UTF-8): it names the action's files, which with ``.json``
#: and a temporary suffix must stay within the 255 bytes file systems allow.
MAX_NAME_BYTES = 200


def name_problem(name) -> str | None:
    """Why ``name`` cannot name an action's files (None when it can).

    Examples
    --------
    >>> name_problem("m.wave"), name_problem("a/b")
    (None, "action name 'a/b' cannot be a file name (it holds '/')")
    >>> name_problem("x" * 300)
    'action name xxxxxxxxxxxxxxxxxxxxxxxx... is 300 bytes long; at most 200 make a file name'
    """
    if not isinstance(name, str):
        return f"action name {name!r} is not text"
    if not name.strip():
        return f"action name {name!r} is empty"
    for bad in ("/", "\\", "\0"):
        if bad in name:
            return f"action name {name!r} cannot be a file name (it holds {bad!r})"
    if name.startswith("."):
        return f"action name {name!r} cannot be a file name (it starts with '.')"
    size = len(name.encode("utf-8", "surrogatepass"))
    if size > MAX_NAME_BYTES:
        return (f"action name {name[:24]}... is {size} bytes long; at most {MAX_NAME_BYTES} "
                f"make a file name")
    return None


def channels_problem(key: str, keys, joints, needed) -> str | None:
    """What is wrong with ``keys`` (a record's JSON object ``key``, channel -> value): the
    first that is no channel ``JOINT.AXIS`` of one of ``joints`` (AXIS one of kinetology's
    axes), else the first of ``needed`` (the channels that must have one) without one;
    ``None`` when neither.

    A record's ``mean_pose`` holds every channel of its joints and ``component_names`` every
    channel of its morphemes, and their readers look a channel up with a default: a key
    renamed was a channel given nothing (a pose of 0, no component) without a word.

    Examples
    --------
    >>> channels_problem("mean_pose", ["Hips.rx", "Hipz.ry"], ["Hips"], [])
    "'mean_pose' names 'Hipz.ry', which is no channel of its joints (JOINT.AXIS: a joint of all_joints, an axis of tx ty tz rx ry rz)"
    >>> channels_problem("component_names", ["Hips.rx"], ["Hips"], ["Hips.rx", "Hips.ry"])
    "'component_names' has no value for 'Hips.ry', a channel of its morphemes"
    """
    keys, joints = list(keys), set(joints)
    for k in keys:
        joint, _, axis = k.rpartition(".")
        if axis not in _AXES or joint not in joints:
            return (f"{key!r} names {shown(k)}, which is no channel of its joints (JOINT.AXIS: "
                    f"a joint of all_joints, an axis of {' '.join(_AXES)})")
    have = set(keys)
    missing = next((c for c in needed if c not in have), None)
    if missing is not None:
        return f"{key!r} has no value for {shown(missing)}, a channel of its morphemes"
    return None


def component_problem(names: dict, channels, components) -> str | None:
    """What is wrong with a record's ``component_names`` (``names``, channel -> component)
    for its system, whose components are named ``components``: the first of ``channels``
    (its morphemes') without a component name, or whose name is no component of the system;
    ``None`` when neither. Generation derives each channel's word from its component.

    Examples
    --------
    >>> component_problem({"a.rx": "a_rx", "a.ry": "a_rq"}, ["a.rx", "a.ry"], {"a_rx", "a_ry"})
    "'component_names' gives 'a.ry' the component 'a_rq', which is no component of its system (its components: a_rx, a_ry)"
    """
    for channel in channels:
        name = names.get(channel)
        if name is None:
            return (f"'component_names' has no component for {shown(channel)}, a channel of "
                    f"its morphemes")
        if name not in components:
            known = ", ".join(sorted(components)[:4]) + (", ..." if len(components) > 4 else "")
            return (f"'component_names' gives {shown(channel)} the component {shown(name)}, "
                    f"which is no component of its system (its components: {known or 'none'})")
    return None


def lookup_problem(record, components=None, skeleton=None) -> str | None:
    """Why a learnt record's ``mean_pose`` and ``component_names`` do not name what
    generation looks up in them (``None`` when they do): the one check that
    :func:`praxicon.load` (the record alone), :func:`praxicon.verify` (with its system's
    components) and generation (with the components and the skeleton it poses) make.

    Generation looks each channel of the skeleton up in ``mean_pose`` and each channel of a
    morpheme up in ``component_names``, with a default: a key renamed or dropped left a
    channel posed at 0, or derived from no component, without a word. The record alone shows
    a key that is no channel of its joints and a morpheme's channel without one
    (:func:`channels_problem`); ``components`` (the names of its parsed system's components)
    a component name that is no component (:func:`component_problem`); ``skeleton`` (the
    channels of the motion generated on, read from ``record.skeleton_source``) a
    ``mean_pose`` key that is no channel of it, or a channel of it without one, which only
    that file shows.

    Parameters
    ----------
    record : ActionRecord
        A learnt record.
    components : set of str, optional
        Its system's components' names; not checked without them (the system unparsed).
    skeleton : sequence of str, optional
        The skeleton's channels; not checked without them (the file unread).

    Returns
    -------
    str or None
        The first problem, one line naming the key, or None.

    Examples
    --------
    >>> from praxicon.records import ActionRecord, ChannelMorpheme, JointRecord
    >>> r = ActionRecord("m.a", "m", "a", status="ok", actuators=("arm",),
    ...                  joints=(JointRecord("arm", (("arm.rx", ChannelMorpheme(("B",))),)),),
    ...                  component_names=(("arm.rx", "arm_rx"),), skeleton_source="a.bvh",
    ...                  all_joints=("hips", "arm"),
    ...                  mean_pose=(("arm.rx", 1.5), ("hips.rz", 0.0)))
    >>> lookup_problem(r, {"arm_rx"}, ["hips.rz", "arm.rx"]) is None
    True
    >>> lookup_problem(r, {"arm_rx"}, ["hips.rz", "arm.rx", "arm.ry"])
    "'mean_pose' has no value for 'arm.ry', a channel of its skeleton (a.bvh)"
    >>> lookup_problem(r, {"arm_ry"})
    "'component_names' gives 'arm.rx' the component 'arm_rx', which is no component of its system (its components: arm_ry)"
    """
    needed = list(record.morphemes())
    for key, pairs in (("mean_pose", record.mean_pose),
                       ("component_names", record.component_names)):
        if problem := channels_problem(key, (c for c, _ in pairs), record.all_joints, needed):
            return problem
    if skeleton is not None:
        source = f"its skeleton ({record.skeleton_source})"
        named, known = dict(record.mean_pose), set(skeleton)
        stray = next((c for c in named if c not in known), None)
        if stray is not None:
            return f"'mean_pose' names {shown(stray)}, which is no channel of {source}"
        missing = next((c for c in skeleton if c not in named), None)
        if missing is not None:
            return f"'mean_pose' has no value for {shown(missing)}, a channel of {source}"
    if components is not None:
        return component_problem(dict(record.component_names), needed, components)
    return None
