"""What a record's names must be, each check giving the problem as one line (``None`` when
there is none) for the reader to raise naming its file: an action's name, which names its
files, and a learnt record's channel keys, which generation looks each channel up by.
"""

from __future__ import annotations

from .jsonvalues import shown

__all__ = ["MAX_NAME_BYTES", "name_problem", "channels_problem", "component_problem"]

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
