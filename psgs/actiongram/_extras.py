"""The optional extras of an actiongram: displacements, actuator map, skeleton.

Their normalisation and text directives, apart from the strings themselves, which every
actiongram has; :class:`psgs.Actiongram` is the only user. The checks of the displacements and
actuators are in the constructor's one list of checks, :data:`psgs.actiongram._faults.CHECKS`,
after the strings'; the skeleton's are here.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from ..errors import FormatError, ValidationError
from ._checks import _bad_name, _names_of, _refused, _shown, _tuple_of
from ._faults import ACTUATOR_CHECKS, DISPLACEMENT_CHECKS, StringFields, refuse


def default_actuator(name: str) -> str:
    """The actuator a string belongs to by default: its name before the first dot.

    Parameters
    ----------
    name : str
        A string's name, e.g. ``arm.x``.

    Returns
    -------
    str
        The part before the first dot (the whole name when there is none, or when it starts
        with a dot).

    Examples
    --------
    >>> default_actuator("arm.x"), default_actuator("body"), default_actuator(".x")
    ('arm', 'body', '.x')
    """
    if not isinstance(name, str):
        raise ValidationError(f"a string's name is a str, not {_shown(name)}")
    head = name.split(".", 1)[0]
    return head if head else name


DIRECTIVE = re.compile(r"\s*%(?:actuator|parent)\s")


def read_directive(line: str, source: str, line_no: int, owner: dict[str, str],
                    edges: list[tuple[str, str | None]]) -> None:
    """Read ``%actuator ACTUATOR: string …`` or ``%parent ACTUATOR: PARENT`` (nothing: a root)."""
    head, colon, body = line.partition(":")
    keyword, _, joint = head.strip().partition(" ")
    joint = joint.strip()
    column = len(line) - len(line.lstrip()) + 1
    if not colon:
        raise FormatError(f"expected '{keyword} ACTUATOR: …' (no ':' on this line)", source=source,
                          line=line_no, column=column)
    problem = _bad_name(joint)
    if problem:
        raise FormatError(f"{keyword}: {problem}", source=source, line=line_no, column=column)
    words = body.split()
    if keyword == "%actuator":
        for name in words:
            if name in owner:
                raise FormatError(f"string {_shown(name)} is given an actuator twice",
                                  source=source, line=line_no, column=column)
            owner[name] = joint
        return
    if len(words) > 1:
        raise FormatError(f"%parent {joint}: one parent, not {len(words)}", source=source,
                          line=line_no, column=column)
    edges.append((joint, words[0] if words else None))


def normalise_extras(value, strings: tuple[StringFields, ...]) -> None:
    """Validate and normalise ``value``'s displacements, actuator map and skeleton in place.

    ``strings`` are ``value``'s strings as given, which have passed their checks
    (:data:`~psgs.actiongram._faults.STRING_CHECKS`): their symbols before equal neighbours
    merge (a merged run's displacements add up).
    """
    displacements = (_tuple_of(value.segment_displacements, "segment_displacements")
                     or (None,) * len(strings))
    if len(displacements) != len(strings):
        raise ValidationError("segment_displacements must have one entry per string")
    if any(d is not None for d in displacements):  # (the usual actiongram has none: no checks)
        strings = tuple(s.given(d) for s, d in zip(strings, displacements))
        refuse(strings, DISPLACEMENT_CHECKS)
        displacements = tuple(s.displacement_row for s in strings)
    object.__setattr__(value, "segment_displacements", displacements)
    normalise_actuators(value, tuple(s.name for s in strings))
    normalise_skeleton(value)


def normalise_actuators(value, names: tuple[str, ...]) -> None:
    """Validate ``value.string_actuators`` (one valid name per string; () the defaults)."""
    actuators = _names_of(value.string_actuators, "string_actuators", "actuator")
    if not actuators:
        actuators = tuple(default_actuator(n) if isinstance(n, str) else n for n in names)
    if len(actuators) != len(names):
        raise ValidationError("string_actuators must have one entry per string")
    if any(_bad_name(a) is not None for a in actuators):  # the table's check, its message
        refuse(tuple(StringFields(n, (), (), actuator=a) for n, a in zip(names, actuators)),
               ACTUATOR_CHECKS)
    object.__setattr__(value, "string_actuators", actuators)


def normalise_skeleton(value) -> None:
    """Validate ``value.skeleton_edges``: (actuator, parent or None) pairs, no cycle."""
    edges: list[tuple[str, str | None]] = []
    parent_of: dict[str, str | None] = {}
    for edge in _tuple_of(value.skeleton_edges, "skeleton_edges"):
        if isinstance(edge, (str, bytes)) or not isinstance(edge, Iterable) \
                or len(tuple(edge)) != 2:
            raise _refused(f"a skeleton entry must be (actuator, parent), not {_shown(edge)}")
        child, parent = tuple(edge)
        for joint in (child,) if parent is None else (child, parent):
            problem = _bad_name(joint)
            if problem:
                raise _refused(f"skeleton: {problem}")
        if child in parent_of:
            raise _refused(f"skeleton: {_shown(child)} is given a parent twice")
        if parent == child:
            raise _refused(f"skeleton: {_shown(child)} is its own parent")
        parent_of[child] = parent
        edges.append((child, parent))
    rooted: set[str] = set()  # joints whose parent chain is known to end (linear time)
    for start in parent_of:  # a parent chain that comes back is not a skeleton
        chain, joint = [start], parent_of[start]
        on_chain = {start}
        while joint is not None and joint in parent_of and joint not in rooted:
            if joint in on_chain:
                raise _refused(f"skeleton: the parents of {_shown(start)} form a cycle")
            chain.append(joint)
            on_chain.add(joint)
            joint = parent_of[joint]
        rooted.update(chain)
    object.__setattr__(value, "skeleton_edges", tuple(edges))

