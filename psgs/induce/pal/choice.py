"""Sections grouped in time, and the choice between them and the motif groups (step 3b).

Every string's section (:mod:`~psgs.induce.pal.sections`, its longest exact
repeat) with fewer than one chance repeat as long expected in its string is a
second candidate beside its motif; sections are synchronised in time as
motifs are (step 3), their copies pairing off at one shift
(:func:`~psgs.induce.pal.pairing.keeps_shift`), and form their own groups,
each kept only when the group as one event beats ``alpha``
(:mod:`~psgs.induce.pal.in_step`: one string's short repeat is no evidence,
several at the same times are). A string can
then be in a motif group (steps 4-6) and in a section group. Both kinds are
ranked by one significance,
:func:`~psgs.induce.pal.sections.repeat_significance` at the copies'
agreement, summed over a group's members: the groups are taken strongest
first (a motif group before a section group of equal weight), each keeping
the members no stronger group took, while two or more are left. A motif's
copies are weighed at their own agreement with the voted pattern, so many
damaged copies of a motif can outweigh a few exact ones, and a long section
twice outweighs a short figure played often.

Then every copy agreeing with its pattern in less than a share
``copy_agreement`` of its positions is dropped from the occurrences, and a
string left with fewer than ``min_copies`` copies is no component.
"""

from __future__ import annotations

import math
from bisect import bisect_left
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from .conf import NO_BOUND
from .motifs import Timed
from .in_step import group_significance
from .paired_sections import paired_groups
from .pairing import keeps_shift, spans_pair
from .pooling import PAIR_BYTES, sync_groups
from .sections import (Section, copy_agreements, find_sections, follow_rate,
                       repeat_significance)

if TYPE_CHECKING:
    from .conf import Bounds, ContentConf
    from .content import ContentResult

__all__: list[str] = []  # private: content.py is the caller

#: the statuses of a string this step dropped (see ``docs/pal.md``)
OUTWEIGHED = "its group outweighed by a stronger one"
TOO_FEW_AGREEING = "too few copies agree with the pattern"
WEAK_COPIES = "not significant at its group's copies"
CHANCE_IN_STEP = "in step with its group no more than by chance"

#: a string's section is a candidate when fewer than one repeat as long is expected by chance
#: in it (log10 of just under 1): a section is judged with the group it is in step with
SCREEN = -1e-9


def add_sections(strings: list[Timed], found: ContentResult, conf: ContentConf,
                 clock: Bounds = NO_BOUND) -> None:
    """Section groups formed and weighed against the motif groups; ``found`` updated.

    ``clock`` is read in the search (each string, each row of pairs, each group's lead)
    and raises :class:`~psgs.errors.BoundReached` past its deadline, or when the section
    pairs found pass its ``max_bytes`` (:data:`~psgs.induce.pal.pooling.PAIR_BYTES` a pair),
    always before the components of ``found`` change (its sections, partners and statuses
    may have).
    """
    # (not bounded by max_pattern: a section is found by a search over lengths, not grown)
    level = math.log10(conf.alpha)
    # every string's follow rate, read by the section search and by the groups' test alike
    follows = []
    for s in strings:
        clock.check()
        follows.append(follow_rate(s.codes))
    symbols = strings
    if conf.section_durations == "equal":
        # a section's copies repeat what ``codes`` holds: here the symbols with their
        # durations; every rate stays the symbols' own
        strings = [with_durations(s) for s in strings]
    sections = find_sections([s.codes for s in strings], conf.min_copies,
                             [s.match_rate for s in strings], SCREEN, follows, clock)
    found.sections = sections
    candidates = [i for i, s in enumerate(sections) if s is not None and s.significance <= SCREEN]
    intervals = {i: strings[i].copy_times(sections[i]) for i in candidates}
    partners: dict[int, list[int]] = {i: [] for i in candidates}
    table = _CopyTable.of([intervals[i] for i in candidates])
    for k, a in enumerate(candidates):
        clock.check()
        # copies that pair off, at one shift (a chance repeat inside long copies pairs with
        # them too, but lies off them by a different amount in each)
        in_step = [candidates[b] for b in in_step_row(table, k, conf.min_copies,
                                                      conf.sync_fraction)]
        clock.keep(PAIR_BYTES * len(in_step))
        partners[a].extend(in_step)
        for b in in_step:
            partners[b].append(a)
    found.section_partners = partners
    weights = {i: motif_weight(symbols[i], found.patterns[i], found.spans[i])
               for i in found.patterns}
    # a motif group's member must be significant at the copies it ended with, too
    motif_groups = [[i for i in g if weights[i] <= level] for g in found.groups]
    for i in weights:
        if weights[i] > level:
            found.dropped[i] = WEAK_COPIES
    weighed = [(sum(weights[i] for i in g), 0, k, g) for k, g in enumerate(motif_groups)]
    sectioned, readings = [], []
    for group in sync_groups(candidates, partners):
        significance, members = group_significance(strings, sections, intervals, follows,
                                                   group, partners, level, clock)
        for i in group:
            if significance > level or i not in members:
                found.dropped.setdefault(i, CHANCE_IN_STEP)
        if significance <= level:
            weighed.append((_rank(strings, members), 1, len(sectioned), sorted(members)))
            sectioned.append(sorted(members))
            readings.append(members)
    # strings no section group took may still play a section at the same times as another,
    # though each one's own longest repeat lies elsewhere: found by the pair
    grouped = {i for g in sectioned for i in g}
    pairs = paired_groups(strings, follows, level,
                          [i for i in range(len(strings)) if i not in grouped],
                          conf.min_copies, clock) if conf.section_search == "pairs" else []
    for _, members in pairs:
        weighed.append((_rank(strings, members), 1, len(sectioned), sorted(members)))
        sectioned.append(sorted(members))
        readings.append(members)
    taken: dict[int, tuple[int, int]] = {}  # string -> (kind, group) it is a component of
    beside = math.log10(max(len(strings) - 1, 1))

    def beside_section(j: int, i: int) -> bool:
        # whether motif member ``j`` stays in step with its mate ``i`` that a section group
        # took: ``j`` beats chance among the other strings, as a section group's members
        # must, and keeps that group's shift (a chance repeat inside a section's long
        # copies pairs with them too, but lies off them by a different amount in each)
        return weights[j] + beside <= level and keeps_shift(
            np.asarray(found.occurrences[j]), strings[i].copy_times(readings[taken[i][1]][i]))

    for _, kind, k, group in sorted(weighed, key=lambda w: w[:3]):
        free = [i for i in group if i not in taken]
        # a motif group keeps a lone member when the rest of it are components already
        # (taken by a stronger group, so still in step with it), or when it was one alone;
        # when a section group took them, only beside that section (``beside_section``)
        if len(free) >= 2 or (kind == 0 and free and all(
                i in free or (i in taken and (taken[i][0] == 0 or all(
                    beside_section(j, i) for j in free)))
                for i in found.groups[k])):
            taken.update((i, (kind, k)) for i in free)
    for i in list(found.patterns):
        if taken.get(i, (1,))[0] != 0:
            del found.patterns[i], found.occurrences[i], found.spans[i]
            found.joined.pop(i, None)
            if i not in taken:
                found.dropped.setdefault(i, OUTWEIGHED)
    for i, (kind, k) in taken.items():
        if kind == 1:
            s = readings[k][i]  # its own section, or the repeat read at the lead's copies
            length = len(s.motif)
            if s is not sections[i]:
                s = Section(s.motif, s.starts, repeat_significance(
                    len(strings[i].codes), length, len(s.starts), (len(s.starts) - 1) * length,
                    strings[i].match_rate, follows[i]))
                sections[i] = s
            found.patterns[i] = tuple(symbols[i].codes[s.starts[0]:s.starts[0] + length].tolist())
            found.occurrences[i] = tuple(map(tuple, strings[i].intervals(s.starts,
                                                                         length).tolist()))
            found.spans[i] = tuple((a, a + length) for a in s.starts.tolist())
            found.from_sections.add(i)
            mates = [j for j in readings[k] if j != i]  # (a string read at the lead's copies
            found.section_partners[i] = sorted(set(partners.get(i, [])) | set(mates))  # too)
    for i in {i for g in sectioned for i in g} - set(taken):
        found.dropped.setdefault(i, OUTWEIGHED)
    if symbols is not strings:  # the sections as their symbols, for the reports
        found.sections = [None if x is None else Section(
            symbols[i].codes[x.starts[0]:x.starts[0] + len(x.motif)].copy(), x.starts,
            x.significance) for i, x in enumerate(sections)]
        strings = symbols
    keep_agreeing(strings, found, conf)
    # a group that the agreement left with one member is no longer in step with anything
    left: dict[tuple[int, int], list[int]] = {}
    for i in found.patterns:  # (each is in ``taken``: the others were deleted above)
        left.setdefault(taken[i], []).append(i)
    for (kind, k), members in left.items():
        mates = [] if kind else [j for j in found.groups[k] if j != members[0]]
        left_in = [j for j in mates if j in found.patterns]
        # (a mate left in a section group keeps it only beside that section)
        if len(members) == 1 and (kind or (mates and not left_in) or not all(
                taken[j][0] == 0 or beside_section(members[0], j) for j in left_in)):
            i = members[0]
            del found.patterns[i], found.occurrences[i], found.spans[i], found.agreements[i]
            found.joined.pop(i, None)
            found.from_sections.discard(i)
            found.dropped[i] = TOO_FEW_AGREEING


@dataclass(frozen=True)
class _Keyed(Timed):
    """A string whose codes are what its sections' copies must repeat, weighed by the
    chance agreement of its symbols (``rate``, their match rate)."""

    rate: float = 0.0

    @property
    def match_rate(self) -> float:
        return self.rate


def with_durations(string: Timed) -> Timed:
    """``string`` with one code per (symbol, duration) pair, its match rate its symbols'.

    Durations are equal when they agree to a millionth of the string's longest (float
    rounding of the times aside).

    Examples
    --------
    >>> string = Timed.from_codes(np.array([0, 1, 0, 1]), np.array([1.0, 1.0, 1.0, 2.0]), 0.0)
    >>> keyed = with_durations(string)
    >>> keyed.codes.tolist(), keyed.match_rate == string.match_rate
    ([0, 1, 0, 2], True)
    """
    durations = string.ends - string.starts
    grain = 1e-6 * max(float(np.max(durations, initial=0.0)), 1e-300)
    steps = np.round(durations / grain).astype(np.int64)
    _, keys = np.unique(np.column_stack((string.codes, steps)), axis=0, return_inverse=True)
    return _Keyed(keys.ravel().astype(np.int64), string.starts, string.ends, string.match_rate)


def _rank(strings: list[Timed], members: dict[int, Section]) -> float:
    """A section group's rank among the groups: ranked as the motif groups are, by its
    members' significances summed, each weighed alone by the one rule of a motif's copies
    (the group's own significance is the test it has passed)."""
    return sum(motif_weight(strings[i], tuple(s.motif.tolist()),
                            tuple((a, a + len(s.motif)) for a in s.starts.tolist()))
               for i, s in members.items())


def coincide(a: np.ndarray, b: np.ndarray, copies: int, fraction: float = 1.0) -> bool:
    """Whether ``copies`` copies of one section pair off with copies of the other, each pair
    sharing at least half of the time the two cover together (each copy in one pair), and
    the pairs are at least ``fraction`` of the copies of each.

    Looser than this, a short chance repeat inside a long section's copies, or a few copies
    among many of the other, would count as in step with it.

    Examples
    --------
    >>> coincide(np.array([[0., 16.], [20., 36.]]), np.array([[1., 16.], [21., 35.]]), 2)
    True
    >>> coincide(np.array([[0., 16.], [20., 36.]]), np.array([[3., 9.], [23., 29.]]), 2)
    False
    """
    if min(len(a), len(b)) < max(copies, fraction * max(len(a), len(b))):
        return False  # too few copies on one side to pair off enough of the other's
    # copies of one string are disjoint and in time order, so the copies of ``b`` a copy of
    # ``a`` can share time with run from the last one starting before it to the last one
    # starting before it ends (the ones before that end before it starts)
    a_list, b_list = a.tolist(), b.tolist()
    b_starts = [start for start, _ in b_list]
    count = 0
    for a0, a1 in a_list:
        near = max(bisect_left(b_starts, a0) - 1, 0)
        while near < len(b_list) and b_list[near][0] < a1:
            if spans_pair((a0, a1), b_list[near]):
                count += 1
                break
            near += 1
    count = min(count, len(b_list))
    return count >= copies and count >= fraction * max(len(a), len(b))


#: a row's pair tests are laid out at most this many copy pairs at a time (a pair of
#: strings with more is tested alone, by coincide and keeps_shift)
_ROW_CELLS = 1 << 16


@dataclass(frozen=True)
class _CopyTable:
    """Every candidate's copies end to end: their ``starts`` and ``ends``, where each
    candidate's begin (``begins``), how many each has (``sizes``), whether they start in
    time order (``ordered``, as :func:`coincide` reads them) and each one's ``copies`` as
    they came."""

    starts: np.ndarray
    ends: np.ndarray
    begins: np.ndarray
    sizes: np.ndarray
    ordered: np.ndarray
    copies: tuple

    @classmethod
    def of(cls, copies: list[np.ndarray]) -> _CopyTable:
        sizes = np.array([len(c) for c in copies], dtype=np.int64)
        flat = (np.concatenate(copies).reshape(-1, 2) if copies else np.zeros((0, 2)))
        begins = np.cumsum(sizes) - sizes
        # (falls[i]: how many of the first i copies start after the copy that follows them)
        falls = np.concatenate(([0], np.cumsum(np.diff(flat[:, 0]) < 0))).tolist()
        ordered = np.array([not size or falls[begin + size - 1] == falls[begin]
                            for begin, size in zip(begins.tolist(), sizes.tolist())], bool)
        return cls(flat[:, 0].copy(), flat[:, 1].copy(), begins, sizes, ordered, tuple(copies))


def in_step_row(table: _CopyTable, k: int, copies: int, fraction: float) -> list[int]:
    """The candidates after ``k`` whose copies are in step with candidate ``k``'s:
    ``coincide(a, b, copies, fraction) and keeps_shift(a, b)``, ``a`` the copies of ``k``
    and ``b`` of each later one, the same to the bit, tested together.

    Every copy of ``a`` beside every copy of each ``b`` (a block of candidates at a time,
    ``_ROW_CELLS`` pairs of copies at most): the pairs that share half the time they cover,
    which of them :func:`coincide`'s walk from the copy of ``b`` starting last before a
    copy of ``a`` meets, and the first copy of ``b`` each copy of ``a`` pairs with for
    :func:`~psgs.induce.pal.pairing.keeps_shift`'s offsets. A candidate whose copies do
    not start in time order (:func:`coincide` bisects their starts), or that has more
    pairs of copies with ``a`` than a block, is tested alone by the two functions.

    Examples
    --------
    >>> a = np.array([[9.0, 25.0], [27.0, 43.0]])
    >>> inside = np.array([[9.0, 17.0], [34.0, 42.0]])  # pairs with a, shifted 25 not 18
    >>> table = _CopyTable.of([a, a + 1, a * 0.5, inside])
    >>> in_step_row(table, 0, 2, 1.0)  # in step; off the copies; at a shift of its own
    [1]
    >>> [coincide(a, b, 2) for b in (a + 1, a * 0.5, inside)]
    [True, False, True]
    """
    size = int(table.sizes[k])
    later = np.arange(k + 1, len(table.sizes))
    other = table.sizes[later]
    # (as coincide: too few copies on one side to pair off enough of the other's)
    enough = ~(np.minimum(size, other) < np.maximum(copies, fraction * np.maximum(size, other)))
    alone = enough & ((size * other > _ROW_CELLS) | ~table.ordered[later])
    found = []
    for b in later[alone].tolist():
        a_copies, b_copies = table.copies[k], table.copies[b]
        if coincide(a_copies, b_copies, copies, fraction) and keeps_shift(a_copies, b_copies):
            found.append(b)
    together = later[enough & ~alone]
    cells = np.cumsum(size * table.sizes[together])
    done = 0
    while done < len(together):
        upto = max(done + 1, int(np.searchsorted(cells, cells[done] - size * int(
            table.sizes[together[done]]) + _ROW_CELLS, side="right")))
        block = together[done:upto]
        found.extend(block[_in_step_block(table, k, block, copies, fraction)].tolist())
        done = upto
    return sorted(found)


def _in_step_block(table: _CopyTable, k: int, block: np.ndarray, copies: int,
                   fraction: float) -> np.ndarray:
    """:func:`in_step_row` of the candidates ``block`` (copies in time order): a mask."""
    first = int(table.begins[k])
    size = int(table.sizes[k])
    a0 = table.starts[first:first + size][:, None]
    a1 = table.ends[first:first + size][:, None]
    sizes = table.sizes[block]
    owner = np.repeat(np.arange(len(block)), sizes)
    local = np.arange(int(sizes.sum())) - np.repeat(np.cumsum(sizes) - sizes, sizes)
    at = table.begins[block][owner] + local
    b0, b1 = table.starts[at][None, :], table.ends[at][None, :]
    shared = np.minimum(a1, b1) - np.maximum(a0, b0)
    union = np.maximum(a1, b1) - np.minimum(a0, b0)
    pairs = (shared > 0) & (2 * shared >= union)
    edges = np.cumsum(sizes) - sizes
    # coincide: from the copy of b starting last before the copy of a (bisect_left - 1, or
    # the first) on, while they start before it ends; a copy of a counts once
    before = np.add.reduceat((b0 < a0).astype(np.int64), edges, axis=1)
    near = np.maximum(before - 1, 0)[:, owner]
    walked = pairs & (local[None, :] >= near) & (b0 < a1)
    count = np.add.reduceat(walked.astype(np.int64), edges, axis=1).astype(bool).sum(axis=0)
    count = np.minimum(count, sizes)
    met = (count >= copies) & (count >= fraction * np.maximum(size, sizes))
    # keeps_shift: each copy of a's first partner among b's copies, its offsets and the
    # shorter copy's length; two partners at least, every offset within half the median
    ranked = np.where(pairs, local[None, :], np.iinfo(np.int64).max)
    partner = np.minimum.reduceat(ranked, edges, axis=1)
    has = partner < np.iinfo(np.int64).max  # (copies of a, candidates)
    index = table.begins[block][None, :] + np.where(has, partner, 0)
    c, d = table.starts[index], table.ends[index]
    start_off, end_off = a0 - c, a1 - d
    lengths = np.minimum(a1 - a0, d - c)
    paired = has.sum(axis=0)
    spread_start = (np.where(has, start_off, -np.inf).max(axis=0)
                    - np.where(has, start_off, np.inf).min(axis=0))
    spread_end = (np.where(has, end_off, -np.inf).max(axis=0)
                  - np.where(has, end_off, np.inf).min(axis=0))
    ordered = np.sort(np.where(has, lengths, np.inf), axis=0)
    column = np.arange(len(block))
    upper = ordered[np.minimum(paired // 2, size - 1), column]
    lower = ordered[np.maximum(paired // 2 - 1, 0), column]
    # (np.median: the middle value, or the middle two's sum halved)
    median = np.where(paired % 2 == 1, upper, (lower + upper) / 2)
    keeps = (paired >= 2) & (spread_start <= median / 2) & (spread_end <= median / 2)
    return met & keeps


def motif_weight(string: Timed, pattern: tuple[int, ...],
                 spans: tuple[tuple[int, int], ...]) -> float:
    """:func:`repeat_significance` of a motif group member, its copies read at ``spans``."""
    matches = [round(a * len(pattern)) for a in
               copy_agreements(string.codes, pattern, [a for a, _ in spans])]
    agreeing = sum(matches) - max(matches)  # the best copy stands for the pattern
    return repeat_significance(len(string.codes), len(pattern), len(spans), agreeing,
                               string.match_rate)


def keep_agreeing(strings: list[Timed], found: ContentResult, conf: ContentConf) -> None:
    """Each component's per-copy agreement; copies under ``copy_agreement`` dropped."""
    for i in list(found.patterns):
        shares = copy_agreements(strings[i].codes, found.patterns[i],
                                 [a for a, _ in found.spans[i]])
        keep = np.asarray(shares) >= conf.copy_agreement
        if np.count_nonzero(keep) < min(conf.min_copies, len(shares)):
            del found.patterns[i], found.occurrences[i], found.spans[i]
            found.joined.pop(i, None)
            found.dropped[i] = TOO_FEW_AGREEING
            continue
        found.occurrences[i] = tuple(o for o, k in zip(found.occurrences[i], keep) if k)
        found.spans[i] = tuple(s for s, k in zip(found.spans[i], keep) if k)
        found.agreements[i] = tuple(a for a, k in zip(shares, keep) if k)
