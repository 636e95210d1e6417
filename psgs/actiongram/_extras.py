"""The optional extras of an actiongram: displacements, actuator map, skeleton.

Their validation, merging and text directives, apart from the strings themselves, which
every actiongram has; :class:`psgs.Actiongram` is the only user.
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Sequence

from ..errors import FormatError, ValidationError
from ._checks import _bad_name, _finite, _shown, _tuple_of


def _bad_displacement(value: object) -> str | None:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return f"a displacement must be a number, not {_shown(value)}"
    if not _finite(value):
        return f"a displacement must be finite, not {_shown(value)}"
    return None


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


def _merge(symbols: Sequence[str], durations: Sequence[float]) -> tuple[tuple[str, ...],
                                                                       tuple[float, ...]]:
    """Merge runs of equal neighbours into one segment, adding their durations."""
    out_symbols: list[str] = []
    out_durations: list[float] = []
    for sym, dur in zip(symbols, durations):
        if out_symbols and out_symbols[-1] == sym:
            out_durations[-1] += dur
        else:
            out_symbols.append(sym)
            out_durations.append(float(dur))
    return tuple(out_symbols), tuple(out_durations)


def _merge_displacements(symbols: Sequence[str],
                         displacements: Sequence[float]) -> tuple[float, ...]:
    """The displacements of :func:`_merge`'s segments: a merged run's changes add up."""
    out: list[float] = []
    previous = None
    for sym, disp in zip(symbols, displacements):
        if out and previous == sym:
            out[-1] += disp
        else:
            out.append(float(disp))
        previous = sym
    return tuple(out)


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


def normalise_extras(value, names: tuple[str, ...], symbols: tuple[tuple[str, ...], ...]) -> None:
    """Validate and normalise ``value``'s displacements, actuator map and skeleton in place.

    ``symbols`` are the strings before equal neighbours merge (a merged run's
    displacements add up).
    """
    displacements = (_tuple_of(value.segment_displacements, "segment_displacements")
                     or (None,) * len(names))
    if len(displacements) != len(names):
        raise ValidationError("segment_displacements must have one entry per string")
    rows: list[tuple[float, ...] | None] = []
    for name, syms, disps in zip(names, symbols, displacements):
        if disps is None:
            rows.append(None)
            continue
        if isinstance(disps, (str, bytes)) or not isinstance(disps, Iterable):
            raise FormatError(f"string {_shown(name)}: displacements must be a list of "
                              f"numbers or None, not {_shown(disps)}")
        disps = tuple(disps)
        if len(disps) != len(syms):
            raise FormatError(f"string {_shown(name)} has {len(syms)} symbols but "
                              f"{len(disps)} displacements")
        for disp in disps:
            problem = _bad_displacement(disp)
            if problem:
                raise FormatError(f"string {_shown(name)}: {problem}")
        # an empty string has nothing to displace: unknown, as the text form reads it back
        if not syms:
            rows.append(None)
        elif value.keep_repeats:
            rows.append(tuple(map(float, disps)))
        else:
            merged = _merge_displacements(syms, disps)
            if not all(map(math.isfinite, merged)):  # finite each, too large once added
                raise FormatError(f"string {_shown(name)}: its displacements overflow (equal "
                                  f"neighbours merged add up to more than a float can hold)")
            rows.append(merged)
    object.__setattr__(value, "segment_displacements", tuple(rows))
    normalise_actuators(value, names)
    normalise_skeleton(value)


def normalise_actuators(value, names: tuple[str, ...]) -> None:
    """Validate ``value.string_actuators`` (one valid name per string; () the defaults)."""
    actuators = _tuple_of(value.string_actuators, "string_actuators")
    if not actuators:
        actuators = tuple(default_actuator(n) if isinstance(n, str) else n for n in names)
    if len(actuators) != len(names):
        raise ValidationError("string_actuators must have one entry per string")
    for name, actuator in zip(names, actuators):
        problem = _bad_name(actuator)
        if problem:
            raise FormatError(f"string {_shown(name)}: actuator {_shown(actuator)}: {problem}")
    object.__setattr__(value, "string_actuators", actuators)


def normalise_skeleton(value) -> None:
    """Validate ``value.skeleton_edges``: (actuator, parent or None) pairs, no cycle."""
    edges: list[tuple[str, str | None]] = []
    parent_of: dict[str, str | None] = {}
    for edge in _tuple_of(value.skeleton_edges, "skeleton_edges"):
        if isinstance(edge, (str, bytes)) or not isinstance(edge, Iterable) \
                or len(tuple(edge)) != 2:
            raise FormatError(f"a skeleton entry must be (actuator, parent), not {_shown(edge)}")
        child, parent = tuple(edge)
        for joint in (child,) if parent is None else (child, parent):
            problem = _bad_name(joint)
            if problem:
                raise FormatError(f"skeleton: {problem}")
        if child in parent_of:
            raise FormatError(f"skeleton: {_shown(child)} is given a parent twice")
        if parent == child:
            raise FormatError(f"skeleton: {_shown(child)} is its own parent")
        parent_of[child] = parent
        edges.append((child, parent))
    rooted: set[str] = set()  # joints whose parent chain is known to end (linear time)
    for start in parent_of:  # a parent chain that comes back is not a skeleton
        chain, joint = [start], parent_of[start]
        on_chain = {start}
        while joint is not None and joint in parent_of and joint not in rooted:
            if joint in on_chain:
                raise FormatError(f"skeleton: the parents of {_shown(start)} form a cycle")
            chain.append(joint)
            on_chain.add(joint)
            joint = parent_of[joint]
        rooted.update(chain)
    object.__setattr__(value, "skeleton_edges", tuple(edges))

