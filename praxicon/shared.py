"""Kineteme sub-patterns that several actions share (the paper's Fig. 13).

A morpheme repeats, so it is read *cyclically*: ``B G R Y`` holds ``Y B G``
(across the copy boundary) as well as ``G R Y``, and a whole cycle is one
pattern whatever kineteme it starts at (written from its alphabetically first
rotation: ``G R Y B`` and ``B G R Y`` are both ``B G R Y``). For every joint,
:func:`shared_patterns` collects the cyclic sub-strings of each action's
morphemes of that joint (any of its channels), of ``min_length`` kinetemes or
more and no longer than the morpheme, and keeps those that at least
``min_actions`` actions share. A shared pattern is left out when a longer one
that contains it is shared by the same actions (it says nothing more).

Sorted by joint (in order of first appearance), then by how many actions share
it (most first), then longest first, then alphabetically: the same praxicon
gives the same list.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

from psgs.errors import ValidationError

from ._values import check_count, not_all
from .records import ActionRecord, ChannelMorpheme, JointRecord, Praxicon

__all__ = ["SharedPattern", "shared_patterns"]


@dataclass(frozen=True)
class SharedPattern:
    """A kineteme pattern of one joint, and the (action, channel) pairs whose morphemes hold it."""

    joint: str
    kinetemes: tuple[str, ...]
    actions: tuple[str, ...]
    channels: tuple[tuple[str, str], ...]

    def to_dict(self) -> dict:
        """The pattern as plain JSON values (for shared.json)."""
        return {"joint": self.joint, "kinetemes": list(self.kinetemes),
                "actions": list(self.actions), "channels": [list(c) for c in self.channels]}


def _cycle(morpheme: tuple[str, ...]) -> tuple[str, ...]:
    """One period of the repeated morpheme: ``Y B G R Y`` repeated reads ``Y B G R`` cyclically."""
    if len(morpheme) > 1 and morpheme[0] == morpheme[-1]:
        return morpheme[:-1]  # the copies' ends merge into one segment
    return morpheme


def _cyclic_substrings(morpheme: tuple[str, ...], min_length: int,
                       wholes: set) -> set[tuple[str, ...]]:
    cycle = _cycle(morpheme)
    n = len(cycle)
    doubled = cycle + cycle
    found = {doubled[i:i + k] for k in range(min_length, n) for i in range(n)}
    if n >= min_length:  # the whole cycle, once: its rotations are one pattern
        whole = min(doubled[i:i + n] for i in range(n))
        found.add(whole)
        wholes.add(whole)
    return found


def _contains(longer: tuple[str, ...], shorter: tuple[str, ...]) -> bool:
    k = len(shorter)
    return any(longer[i:i + k] == shorter for i in range(len(longer) - k + 1))


def shared_patterns(praxicon, *, min_length: int = 4, min_actions: int = 2) -> list[SharedPattern]:
    """Per joint, the kineteme sub-patterns shared by at least ``min_actions`` actions.

    Parameters
    ----------
    praxicon : Praxicon or iterable of ActionRecord
        A praxicon (:func:`praxicon.load` reads a folder), or its records.
    min_length : int
        Fewest kinetemes in a pattern (4: one full cycle ``B G R Y``).
    min_actions : int
        Fewest actions that must share it.

    Returns
    -------
    list of SharedPattern

    Raises
    ------
    ValueError
        (ValidationError) ``min_length`` or ``min_actions`` that is no whole number of at
        least 1, or records that are not ActionRecords.

    Examples
    --------
    >>> def action(name, channel, kinetemes):
    ...     joint = JointRecord("arm", ((channel, ChannelMorpheme(tuple(kinetemes))),))
    ...     return ActionRecord(name, "d", name, status="ok", actuators=("arm",),
    ...                         joints=(joint,))
    >>> records = [action("a", "arm.rx", "BGRY"), action("b", "arm.rz", "GRYBGB")]
    >>> [(p.joint, " ".join(p.kinetemes), p.actions) for p in shared_patterns(records)]
    [('arm', 'B G R Y', ('a', 'b'))]
    """
    for name, count in (("min_length", min_length), ("min_actions", min_actions)):
        # 0 or less made patterns of no kineteme or slices of the wrong end, without a word
        check_count(count, name)  # np.int64 too, as before
    records = praxicon.actions if isinstance(praxicon, Praxicon) else praxicon
    records = tuple(records) if isinstance(records, Iterable) else None
    if records is None or not all(isinstance(r, ActionRecord) for r in records):
        raise ValidationError(f"shared_patterns reads a Praxicon or its ActionRecords, "
                              f"{not_all(praxicon, records, ActionRecord)}")
    holders: dict[str, dict[tuple[str, ...], set[tuple[str, str]]]] = {}
    wholes: set[tuple[str, ...]] = set()  # patterns that are a whole cycle (read cyclically)
    for action in records:
        if not action.learnt:
            continue
        for joint in action.joints:
            for channel, morpheme in joint.morphemes:
                for sub in _cyclic_substrings(morpheme.kinetemes, min_length, wholes):
                    holders.setdefault(joint.name, {}).setdefault(sub, set()).add(
                        (action.name, channel))
    found: list[SharedPattern] = []
    for joint, patterns in holders.items():
        shared = {p: h for p, h in patterns.items()
                  if len({a for a, _ in h}) >= min_actions}
        for pattern, held in shared.items():
            actions = {a for a, _ in held}
            implied = any(other != pattern and len(other) >= len(pattern)
                          and _contains(other + other if other in wholes else other, pattern)
                          and {a for a, _ in shared[other]} == actions for other in shared)
            if not implied:
                found.append(SharedPattern(joint, pattern, tuple(sorted(actions)),
                                           tuple(sorted(held))))
    order = {j: i for i, j in enumerate(holders)}
    found.sort(key=lambda p: (order[p.joint], -len(p.actions), -len(p.kinetemes), p.kinetemes))
    return found
