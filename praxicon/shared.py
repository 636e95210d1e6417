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

The patterns are read length by length, and a place of a morpheme reads on only
while what it has read is shared: the work grows with the shared patterns, not
with the cube of the morphemes' lengths (two alike morphemes of 400 kinetemes
took 50 s read sub-string by sub-string, 0.1 s so). Morphemes long *and* alike
still cost the square of their length, so the places read are bounded
(``max_steps``, :data:`MAX_STEPS` by default, a few seconds): past it the
search stops with an error naming the bound and the joint it was reached at.
"""

from __future__ import annotations

import sys
from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from psgs.errors import ValidationError

from ._values import check_count, not_all
from .records import ActionRecord, ChannelMorpheme, JointRecord, Praxicon

__all__ = ["SharedPattern", "shared_patterns", "MAX_STEPS"]

#: The most places :func:`shared_patterns` reads, summed over pattern lengths (a few seconds).
MAX_STEPS = 20_000_000


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


def _least_rotation(codes: list[int]) -> int:
    """Where the lexicographically least rotation of ``codes`` starts (linear time).

    Two candidate starts ``i`` and ``j`` are compared ``k`` symbols in; the one that reads
    larger first cannot start the least rotation, nor can any start up to ``k`` past it.
    """
    n = len(codes)
    i, j, k = 0, 1, 0
    while i < n and j < n and k < n:
        a, b = codes[(i + k) % n], codes[(j + k) % n]
        if a == b:
            k += 1
            continue
        if a > b:
            i += k + 1
        else:
            j += k + 1
        if i == j:
            j += 1
        k = 0
    return min(i, j)


@dataclass(frozen=True)
class _Morpheme:
    """One channel's morpheme cycle of one joint, as codes that sort as its kinetemes do."""

    action: int  # the action's number (actions named alike are one)
    name: str
    channel: str
    codes: np.ndarray
    start: int  # where its least rotation (its whole cycle's pattern) starts


class _Joint:
    """The level-by-level search of one joint's patterns.

    A token is a place ``(morpheme, start)``; at length ``k`` it carries the dense number of
    the ``k`` kinetemes read cyclically from there. A place reads on to ``k + 1`` only while
    its ``k`` kinetemes are shared: every action holding a longer pattern holds each of its
    parts, so a pattern no part of which is shared is never read. Lengths below a morpheme's
    cycle read every place of it; the cycle's own length reads its least rotation alone (a
    whole cycle is one pattern whatever kineteme it starts at).
    """

    def __init__(self, morphemes: list[_Morpheme], alphabet: int):
        self.morphemes = morphemes
        self.lengths = np.array([len(m.codes) for m in morphemes], dtype=np.int64)
        self.offsets = np.concatenate([[0], np.cumsum(self.lengths)[:-1]]).astype(np.int64)
        self.codes = np.concatenate([m.codes for m in morphemes]).astype(np.int64)
        self.actions = np.array([m.action for m in morphemes], dtype=np.int64)
        self.alphabet = alphabet
        self.text = [_chars(m.codes) for m in morphemes]

    def symbols(self, morpheme: np.ndarray, start: np.ndarray, at: int) -> np.ndarray:
        """The kineteme ``at`` places on from each token's start, read cyclically."""
        return self.codes[self.offsets[morpheme] + (start + at) % self.lengths[morpheme]]

    def pattern(self, morpheme: int, start: int, length: int) -> str:
        text = self.text[morpheme]
        return (text + text)[start:start + length]


def _chars(codes) -> str:
    """Codes as one character each, so that slices and ``in`` run at string speed."""
    return "".join(map(chr, codes))


def _small(span: int, count: int) -> bool:
    """Whether a table of ``span`` flags costs less than sorting ``count`` keys: the levels'
    keys are dense numbers times a few kinetemes or actions, so mostly it does, and a table
    read in one pass replaces the sort each level otherwise spends most of its time in."""
    return span <= 16 * count + 4096


def _dense(keys: np.ndarray) -> np.ndarray:
    """Each key's number among the distinct keys (equal keys, equal numbers)."""
    if len(keys) and _small(int(keys.max()) + 1, len(keys)):  # keys are never negative
        seen = np.zeros(int(keys.max()) + 1, dtype=bool)
        seen[keys] = True
        return (np.cumsum(seen) - 1)[keys].astype(np.int64)  # the rank np.unique gives
    return np.unique(keys, return_inverse=True)[1].reshape(-1).astype(np.int64)


def _action_counts(ids: np.ndarray, actions: np.ndarray, size: int) -> np.ndarray:
    """How many distinct actions hold each number in ``0 .. size - 1``."""
    width = actions.max(initial=0) + 1  # an (id, action) pair as one number
    if _small(size * int(width), len(ids)):
        held = np.zeros(size * int(width), dtype=bool)
        held[ids * width + actions] = True
        return np.bincount(np.flatnonzero(held) // width, minlength=size)
    pairs = np.unique(ids * width + actions)
    return np.bincount(pairs // width, minlength=size)


def shared_patterns(praxicon, *, min_length: int = 4, min_actions: int = 2,
                    max_steps: int = MAX_STEPS) -> list[SharedPattern]:
    """Per joint, the kineteme sub-patterns shared by at least ``min_actions`` actions.

    Parameters
    ----------
    praxicon : Praxicon or iterable of ActionRecord
        A praxicon (:func:`praxicon.load` reads a folder), or its records.
    min_length : int
        Fewest kinetemes in a pattern (4: one full cycle ``B G R Y``).
    min_actions : int
        Fewest actions that must share it.
    max_steps : int
        The most places read, summed over the pattern lengths (:data:`MAX_STEPS`).

    Returns
    -------
    list of SharedPattern

    Raises
    ------
    ValueError
        (ValidationError) ``min_length``, ``min_actions`` or ``max_steps`` that is no whole
        number of at least 1, records that are not ActionRecords, or morphemes too long and
        alike to compare within ``max_steps`` (the message names the joint and the bound).

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
    for name, count in (("min_length", min_length), ("min_actions", min_actions),
                        ("max_steps", max_steps)):
        # 0 or less made patterns of no kineteme or slices of the wrong end, without a word
        check_count(count, name)  # np.int64 too, as before
    records = praxicon.actions if isinstance(praxicon, Praxicon) else praxicon
    records = tuple(records) if isinstance(records, Iterable) else None
    if records is None or not all(isinstance(r, ActionRecord) for r in records):
        raise ValidationError(f"shared_patterns reads a Praxicon or its ActionRecords, "
                              f"{not_all(praxicon, records, ActionRecord)}")
    numbers: dict[str, int] = {}  # actions named alike count as one
    cycles: dict[str, list[tuple[str, str, tuple[str, ...]]]] = {}  # joints, as first met
    for action in records:
        if not action.learnt:
            continue
        for joint in action.joints:
            for channel, morpheme in joint.morphemes:
                cycle = _cycle(morpheme.kinetemes)
                if len(cycle) >= min_length:
                    numbers.setdefault(action.name, len(numbers))
                    cycles.setdefault(joint.name, []).append((action.name, channel, cycle))
    joints = {name: _coded(items, numbers, name) for name, items in cycles.items()}
    # every whole cycle, of any joint: a pattern another joint holds whole is read around its
    # end in this joint too, as the definition has always read it (one set of whole cycles)
    wholes: dict[int, set[tuple[str, ...]]] = {}
    for joint, alphabet in joints.values():
        for m in joint.morphemes:
            rotated = np.roll(m.codes, -m.start)
            wholes.setdefault(len(rotated), set()).add(tuple(alphabet[c] for c in rotated))
    steps, found = max_steps, []
    for name, (joint, alphabet) in joints.items():
        code = {k: chr(i) for i, k in enumerate(alphabet)}
        here = {length: {"".join(code[k] for k in w) for w in ws if all(k in code for k in w)}
                for length, ws in wholes.items()}
        patterns, steps = _maximal(joint, name, min_length, min_actions, here, steps,
                                   max_steps)
        for text, actions, held in patterns:
            found.append(SharedPattern(name, tuple(alphabet[ord(c)] for c in text),
                                       actions, held))
    order = {j: i for i, j in enumerate(joints)}
    found.sort(key=lambda p: (order[p.joint], -len(p.actions), -len(p.kinetemes), p.kinetemes))
    return found


def _coded(items, numbers, joint: str) -> tuple[_Joint, list[str]]:
    """One joint's morpheme cycles as codes numbered in the kinetemes' order, and that order."""
    distinct: set[str] = set()
    for _, _, cycle in items:
        distinct.update(cycle)
    if len(distinct) > sys.maxunicode + 1:  # a code is one character of the patterns' text
        # counted before the sort, which is most of the time a refused joint would cost
        raise ValidationError(f"shared_patterns: joint {joint!r} has {len(distinct):,} distinct "
                              f"kinetemes, more than the {sys.maxunicode + 1:,} it can compare")
    alphabet = sorted(distinct)
    code = {k: i for i, k in enumerate(alphabet)}
    morphemes = []
    for action, channel, cycle in items:
        codes = [code[k] for k in cycle]
        morphemes.append(_Morpheme(numbers[action], action, channel,
                                   np.array(codes, dtype=np.int64), _least_rotation(codes)))
    return _Joint(morphemes, len(alphabet)), alphabet


@dataclass(frozen=True)
class _Level:
    """The tokens read at one pattern length, numbered by the kinetemes they read."""

    length: int
    places: np.ndarray  # each token's morpheme
    starts: np.ndarray  # where in it the token starts
    ids: np.ndarray  # each token's pattern number (equal kinetemes, equal numbers)
    counts: np.ndarray  # per number, how many actions hold it
    dropped: np.ndarray  # per number, not reported: shared by too few, or held in a longer one
    at: np.ndarray  # per place of the joint, the number of the token starting there (-1: none)


def _maximal(joint: _Joint, name: str, min_length: int, min_actions: int,
             wholes: dict[int, set[str]], steps: int, max_steps: int):
    """The joint's shared patterns that no longer one shared by the same actions holds, and
    the steps left of ``steps`` (of the ``max_steps`` every joint shares).

    A pattern held inside a longer one by the same actions is held, by those actions, inside
    one a kineteme longer (its one-kineteme extension within the longer one is held by every
    action holding the longer, and by no action not holding the pattern) -- unless the longer
    one is a whole cycle read around its end; those are few and are checked one by one.
    """
    places = np.repeat(np.arange(len(joint.morphemes)), joint.lengths)
    starts = np.concatenate([np.arange(n) for n in joint.lengths])
    ids = joint.codes.copy()
    for at in range(1, min_length):
        ids = _dense(ids * joint.alphabet + joint.symbols(places, starts, at))
    whole_start = np.array([m.start for m in joint.morphemes], dtype=np.int64)
    length, before, shorter, candidates, whole_held = min_length, None, None, [], []
    while len(ids):
        steps -= len(ids)
        if steps < 0:
            raise ValidationError(
                f"shared_patterns: the morphemes are too long and alike to compare within "
                f"{max_steps:,} steps (max_steps; reached at joint {name!r})")
        lengths = joint.lengths[places]
        # a morpheme as long as the pattern is read once, from its least rotation
        keep = (lengths > length) | ((lengths == length) & (starts == whole_start[places]))
        places, starts, ids = places[keep], starts[keep], _dense(ids[keep])
        counts = _action_counts(ids, joint.actions[places], int(ids.max(initial=-1)) + 1)
        shared = counts[ids] >= min_actions
        if before is not None:  # an extension held by as many actions implies its two parts
            grown = counts[ids[shared]]
            suffix = joint.offsets[places[shared]] + (starts[shared] + 1) % joint.lengths[
                places[shared]]
            for part in (shorter[keep][shared], before.at[suffix]):
                ok = part >= 0  # always so (a shared pattern's parts are shared); kept safe
                part, same = part[ok], grown[ok]
                before.dropped[part[same == before.counts[part]]] = True
            candidates.extend(_held(joint, before, ~before.dropped))
        at = np.full(len(joint.codes), -1, dtype=np.int64)
        at[joint.offsets[places] + starts] = ids
        level = _Level(length, places, starts, ids, counts, counts < min_actions, at)
        if wholes.get(length):
            whole_held.extend(h for h in _held(joint, level, counts >= min_actions)
                              if h[0] in wholes[length])
        places, starts, shorter = places[shared], starts[shared], ids[shared]
        ids = shorter * joint.alphabet + joint.symbols(places, starts, length)
        before, length = level, length + 1
    if before is not None:
        candidates.extend(_held(joint, before, ~before.dropped))
    by_actions: dict[tuple[str, ...], list[str]] = {}
    for text, actions, _ in whole_held:
        by_actions.setdefault(actions, []).append(text)
    return [(text, actions, held) for text, actions, held in candidates
            if not any(len(w) >= len(text) and w != text and text in w + w
                       for w in by_actions.get(actions, ()))], steps


def _held(joint: _Joint, level: _Level, wanted: np.ndarray):
    """``(text, actions, (action, channel) pairs)`` of the level's numbers marked ``wanted``."""
    take = wanted[level.ids]
    if not take.any():
        return []
    ids, places, starts = level.ids[take], level.places[take], level.starts[take]
    chosen, first = np.unique(ids, return_index=True)
    pairs = np.unique(np.stack([ids, places], axis=1), axis=0)
    holders: dict[int, set[tuple[str, str]]] = {}
    for number, place in pairs.tolist():
        m = joint.morphemes[place]
        holders.setdefault(number, set()).add((m.name, m.channel))
    out = []
    for number, index in zip(chosen.tolist(), first.tolist()):
        place, start = int(places[index]), int(starts[index])
        held = holders[number]
        out.append((joint.pattern(place, start, level.length),
                    tuple(sorted({a for a, _ in held})), tuple(sorted(held))))
    return out
