"""Copies pooled over a group of synchronised strings (steps 4-6): the windows the members
share, each member's vote in them and the pattern voted; the groups of the synchronisation
graph (:mod:`~psgs.induce.pal.synchronisation` tests the pairs, step 3)."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ...analysis import reachable
from .conf import NO_BOUND
from .motifs import Timed, grow, locate_copies
from .statistics import log10_binom_sf, scan_threshold
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ...budget import Budget
    from .conf import ContentConf


#: The bytes a pair of synchronised strings is counted at against ``max_bytes``: each string
#: in the other's list of partners and in its report's ``synchronised_with``, 8 bytes each
PAIR_BYTES = 32


def sync_groups(candidates: list[int], partners: dict[int, list[int]]) -> list[list[int]]:
    """Connected components of the synchronisation graph, singletons left out."""
    seen: set[int] = set()
    out = []
    for i in candidates:
        if i in seen or not partners[i]:
            continue
        group = reachable(partners, [i])  # the core's one graph walk (psgs.analysis)
        seen |= group
        out.append(sorted(group))
    return out


def pooled_windows(member_intervals: list[np.ndarray], support: float) -> np.ndarray:
    """Shared copy windows of a group: the times enough members agree are in a copy.

    Cores are the maximal time ranges covered by copies of at least a share
    ``support`` of the members; each core then widens to the copies that
    overlap it (so a copy one member located more completely still counts),
    without reaching into the next core.
    """
    need = max(1, math.ceil(support * len(member_intervals) - 1e-9))
    spans = np.concatenate(member_intervals)
    times = np.concatenate((spans[:, 0], spans[:, 1]))
    steps = np.concatenate((np.ones(len(spans), dtype=np.int64),
                            -np.ones(len(spans), dtype=np.int64)))
    order = np.lexsort((steps, times))  # at equal times, ends before starts
    times, depth = times[order], np.cumsum(steps[order])
    inside = depth >= need
    before = np.concatenate(([False], inside[:-1]))
    opened, closed = times[inside & ~before], times[~inside & before]
    keep = closed > opened
    core = np.column_stack((opened[keep], closed[keep]))
    if len(core) == 0:
        return np.zeros((0, 2))
    core = _join_fragments(core, spans)
    low, high = core[:, 0].copy(), core[:, 1].copy()
    first = np.searchsorted(core[:, 1], spans[:, 0], side="right")  # first core ending after s
    last = np.searchsorted(core[:, 0], spans[:, 1], side="left") - 1  # last core starting before e
    hit = first <= last
    np.minimum.at(low, first[hit], spans[hit, 0])
    np.maximum.at(high, last[hit], spans[hit, 1])
    low[1:] = np.maximum(low[1:], core[:-1, 1])
    high[:-1] = np.minimum(high[:-1], core[1:, 0])
    return np.column_stack((low, high))


def _join_fragments(core: np.ndarray, spans: np.ndarray) -> np.ndarray:
    """Join consecutive cores that copies run across more than they stop or start between.

    Where one member repeats a shorter motif twice per copy of the others
    (and another misses its copy), coverage dips at the short motif's copy
    boundary; that instant is inside a copy for the members spanning it.
    Likewise where members' motifs cover different parts of a copy (one its
    start, another its end) and one member's copy runs across the gap between
    them. Where every member's copy ends and the next begins, nobody runs
    across and the cores stay apart.
    """
    if len(core) < 2:
        return core
    eps = 1e-9 * max(1.0, float(np.abs(core).max()))
    # the gap between consecutive cores (an instant when they touch)
    gap_start, gap_end = core[:-1, 1], core[1:, 0]
    by_start = np.argsort(spans[:, 0], kind="stable")
    first_times, last_times = spans[by_start, 0], spans[by_start, 1]
    # copies running across a whole gap start before it, at most the longest copy before
    lo = np.searchsorted(first_times, gap_start - float(np.max(spans[:, 1] - spans[:, 0]))
                         - eps, side="left")
    hi = np.searchsorted(first_times, gap_start - eps, side="left")
    width = int(np.max(hi - lo)) if len(lo) else 0
    index = np.minimum(lo[:, None] + np.arange(width), len(spans) - 1)
    spanning = np.count_nonzero((index < hi[:, None])
                                & (last_times[index] > gap_end[:, None] + eps), axis=1)
    starts, ends = np.sort(spans[:, 0]), np.sort(spans[:, 1])
    # a member whose copy ends where its next begins counts once
    stopping = np.maximum(np.searchsorted(starts, gap_end + eps, side="right")
                          - np.searchsorted(starts, gap_start - eps, side="left"),
                          np.searchsorted(ends, gap_end + eps, side="right")
                          - np.searchsorted(ends, gap_start - eps, side="left"))
    join = np.zeros(len(core), dtype=bool)  # join[k]: core k continues core k - 1
    join[np.flatnonzero((spanning >= 1) & (spanning >= stopping)) + 1] = True
    group = np.cumsum(~join) - 1
    low = np.full(group[-1] + 1, np.inf)
    high = np.full(group[-1] + 1, -np.inf)
    np.minimum.at(low, group, core[:, 0])
    np.maximum.at(high, group, core[:, 1])
    return np.column_stack((low, high))


def relocate(string: Timed, pattern: tuple[int, ...], conf: ContentConf,
             clock: Budget = NO_BOUND, stop: np.ndarray | None = None) -> np.ndarray | None:
    """Copy intervals of ``pattern`` found by scanning the string, or None if too few.

    ``clock`` is read before each column of the scans and each growth step, ``stop`` (its
    :func:`~psgs.induce.pal._alarm.alarm`) by the compiled growth; past the deadline
    :class:`~psgs.errors.BoundReached` is raised.
    """
    if len(pattern) < 2:
        return None
    codes = string.codes
    motif = np.asarray(pattern, dtype=np.int64)
    threshold = scan_threshold(len(motif), len(codes) - len(motif) + 1, string.match_rate,
                               conf)
    found = locate_copies(codes, motif, threshold, clock)
    if len(found) < conf.min_copies:
        return None
    # the pooled copies are many and reliable: let them grow the pattern further
    grown = grow(codes, motif, found, string.match_rate, string.distinct, conf, clock=clock,
                 stop=stop)
    if grown is None:
        return string.intervals(found, len(motif))
    return string.copy_times(grown)


@dataclass(frozen=True)
class Vote:
    """One member's copies in the shared windows and their column-wise plurality."""

    pattern: tuple[int, ...]
    shares: np.ndarray        # plurality share of each column
    times: object             # (copies, columns) each full copy's symbols' start and end
                              # times from its window's start: ``starts()``, ``ends()``
    bounds: np.ndarray        # (copies, 2): the symbol index range of each copy
    windows_held: np.ndarray  # which window each copy lies in
    chance: np.ndarray | None = None  # each column's plurality symbol's frequency in
    symbols: int = 2                  # the string; how many distinct symbols it has

    @property
    def spans(self) -> tuple[tuple[int, int], ...]:
        """The symbol index range of each copy, as pairs."""
        return tuple(map(tuple, self.bounds.tolist()))

    @property
    def full_copies(self) -> int:
        """How many copies have the pattern's length (those the columns are read from)."""
        return len(self.times)

    def log10_chance(self, column: int) -> float:
        """log10 of the chance that the copies agree at ``column`` as much as they do.

        The binomial tail of the plurality symbol's count, at the symbol's
        frequency in the whole string, times the number of distinct symbols
        (any of them could have been the plurality); at most 0 (0 when the
        frequencies are not known).
        """
        if self.chance is None:
            return 0.0
        copies = self.full_copies
        k = round(float(self.shares[column]) * copies)
        return min(0.0, log10_binom_sf(k, copies, float(self.chance[column]))
                   + math.log10(max(2, self.symbols)))

    @functools.cached_property
    def column_start(self) -> np.ndarray:
        """The median time offset of each column from its window's start."""
        return np.median(self.times.starts(), axis=0)

    @functools.cached_property
    def column_end(self) -> np.ndarray:
        """The median time offset of each column's end from its window's start."""
        return np.median(self.times.ends(), axis=0)


def copies_in(string: Timed, windows: np.ndarray):
    """Where a string's copies lie in ``windows``, or None when no window holds a symbol.

    A copy is the run of symbols whose middle lies in a window. Returns
    ``(lo, hi, picked, full, length)``: each window's symbol index range, the
    windows holding a symbol, those holding a copy of the common length, and
    that length (the most common; the longer among equals).
    """
    middles = string.middles
    lo = np.searchsorted(middles, windows[:, 0], side="left")
    hi = np.searchsorted(middles, windows[:, 1], side="left")
    sizes = hi - lo
    picked = np.flatnonzero(sizes > 0)
    if len(picked) == 0:
        return None
    counts = np.bincount(sizes[picked])
    length = int(len(counts) - 1 - np.argmax(counts[::-1]))  # most common; longer among equals
    return lo, hi, picked, picked[sizes[picked] == length], length


def vote(string: Timed, windows: np.ndarray) -> Vote | None:
    """The plurality pattern of a string's copies in the shared windows.

    A copy is the run of symbols whose middle lies in a window. The pattern
    length is the most common copy length (the longer among equals); each
    position takes the symbol most copies of that length agree on (the one
    seen first in time among equals).
    """
    found = copies_in(string, windows)
    if found is None:
        return None
    lo, hi, picked, full, length = found
    index = lo[full][:, None] + np.arange(length)
    pattern, shares = _plurality(string.codes[index])
    return Vote(tuple(pattern), shares, _Offsets(string, index, windows[full, 0][:, None]),
                np.column_stack((lo[picked], hi[picked])), picked,
                string.symbol_counts[pattern] / len(string.codes), string.distinct)


class CopyTimes:
    """Full copies' symbol start and end times from their windows' starts, given as arrays
    ((copies, columns) each); :class:`Vote` reads them through ``starts()`` and ``ends()``."""

    __slots__ = ("_starts", "_ends")

    def __init__(self, starts: np.ndarray, ends: np.ndarray) -> None:
        self._starts, self._ends = starts, ends

    def __len__(self) -> int:
        return len(self._starts)

    def starts(self) -> np.ndarray:
        """Each full copy's symbols' start times from its window's start."""
        return self._starts

    def ends(self) -> np.ndarray:
        """Each full copy's symbols' end times from its window's start."""
        return self._ends


class _Offsets:
    """Where each full copy's symbols start and end from its window's start, read when asked:
    most votes (every string read in a group's windows to see whether it joins) are never
    trimmed, and only trimming reads the times."""

    __slots__ = ("string", "index", "origin")

    def __init__(self, string: Timed, index: np.ndarray, origin: np.ndarray) -> None:
        self.string, self.index, self.origin = string, index, origin

    def __len__(self) -> int:
        return len(self.index)

    def starts(self) -> np.ndarray:
        return self.string.starts[self.index] - self.origin

    def ends(self) -> np.ndarray:
        return self.string.ends[self.index] - self.origin


def member_votes(strings: list[Timed], members, windows: np.ndarray,
                 clock: Budget = NO_BOUND) -> dict[int, Vote]:
    """:func:`vote` of each of ``members`` in ``windows``, in their order, those with none (no
    window holds a symbol of theirs) left out; ``clock`` read before each member.

    Examples
    --------
    >>> string = Timed.from_codes(np.array([0, 1, 2, 0, 1, 2, 3]), np.ones(7), 0.0)
    >>> other = Timed.from_codes(np.array([4, 5]), np.ones(2), 20.0)
    >>> votes = member_votes([string, other], [1, 0], np.array([[0.0, 3.0], [3.0, 6.0]]))
    >>> list(votes), votes[0].pattern
    ([0], (0, 1, 2))
    """
    out = {}
    for i in members:
        clock.check()
        if (v := vote(strings[i], windows)) is not None:
            out[i] = v
    return out


def pooled_pattern(string: Timed, vote: Vote, clock: Budget = NO_BOUND) -> tuple[int, ...]:
    """The plurality pattern over all of a member's copies, damaged boundaries included.

    ``vote.pattern`` reads only the copies of the common length; a window a
    little too short or long for a copy (its boundary set by copies that noise
    damaged) still holds that copy, and it votes here too (see
    :func:`_aligned`), ties going to the symbol seen first in time. ``clock`` is read
    between the passes over the copies (:func:`_aligned`'s a part of the copies at a time).
    """
    spans = vote.bounds
    length = len(vote.pattern)
    odd = spans[spans[:, 1] - spans[:, 0] != length]
    if len(odd) == 0:
        return vote.pattern
    full = spans[spans[:, 1] - spans[:, 0] == length]
    same = string.codes[full[:, 0][:, None] + np.arange(length)]
    rows = np.concatenate((np.flatnonzero(spans[:, 1] - spans[:, 0] == length),
                           np.flatnonzero(spans[:, 1] - spans[:, 0] != length)))
    clock.check()
    voters = np.concatenate((same, _aligned(string.codes, odd[:, 0], odd[:, 1],
                                            list(vote.pattern), clock)))
    voters = voters[np.argsort(rows, kind="stable")]  # in time order, for the ties
    return tuple(_plurality(voters[voters[:, 0] >= 0])[0])


def _plurality(copies: np.ndarray) -> tuple[list[int], np.ndarray]:
    """Column-wise plurality symbol of ``copies`` and its share (rows in time order; ties:
    first seen)."""
    rows, length = copies.shape
    size = int(copies.max()) + 1
    tally = np.bincount((np.arange(length) * size + copies).ravel(),
                        minlength=length * size).reshape(length, size)
    top = tally.max(axis=1)
    # per column, the first row whose symbol has the top count
    first = np.argmax(tally[np.arange(length), copies] == top, axis=0)
    return copies[first, np.arange(length)].tolist(), top / rows


#: :func:`_aligned` reads the copies a part at a time, each part's table of reads some this
#: many symbols (copies x (2 * reach + 1) starts x the pattern's length: read whole, 21,645
#: copies of 64 symbols peaked at 865 MB)
ALIGNED_SYMBOLS = 1 << 20


def _aligned(codes: np.ndarray, lo: np.ndarray, hi: np.ndarray, pattern: list[int],
             clock: Budget = NO_BOUND) -> np.ndarray:
    """:func:`_aligned_part` of the copies a part at a time (each copy's read is its own),
    ``clock`` read before each part."""
    part = max(1, ALIGNED_SYMBOLS // ((2 * max(1, len(pattern) // 4) + 1) * len(pattern)))
    if len(lo) <= part:
        return _aligned_part(codes, lo, hi, pattern)
    out = []
    for first in range(0, len(lo), part):
        clock.check()
        out.append(_aligned_part(codes, lo[first:first + part], hi[first:first + part],
                                 pattern))
    return np.concatenate(out)


def _aligned_part(codes: np.ndarray, lo: np.ndarray, hi: np.ndarray, pattern: list[int]
                  ) -> np.ndarray:
    """Copies of another length than the pattern's, read at the pattern's length.

    A window a little too short or too long for a copy (its boundary set by
    damaged copies) still holds that copy: it is read at the pattern's length
    from the start, within ``length // 4`` symbols (one at least) of the
    window's own, that covers the window's symbols and agrees best with
    ``pattern``, when that start is unique and agrees in half the columns.
    Rows of -1 stand for copies left out (so rows match ``lo``).
    """
    length = len(pattern)
    out = np.full((len(lo), length), -1, dtype=np.int64)
    reach = max(1, length // 4)
    near = np.abs((hi - lo) - length) <= reach
    shifts = np.arange(-reach, reach + 1)
    starts = lo[:, None] + shifts[None, :]
    size = (hi - lo)[:, None]
    # the read covers the window (short copies) or lies within it (long ones)
    fits = np.where(size < length, (starts <= lo[:, None]) & (starts + length >= hi[:, None]),
                    (starts >= lo[:, None]) & (starts + length <= hi[:, None]))
    fits &= (starts >= 0) & (starts + length <= len(codes)) & near[:, None]
    index = np.clip(starts, 0, max(0, len(codes) - length))[:, :, None] + np.arange(length)
    score = np.where(fits, (codes[index] == np.asarray(pattern)).sum(axis=2), -1)
    best = score.max(axis=1)
    unique = (score == best[:, None]).sum(axis=1) == 1
    ok = unique & (2 * best >= length)
    choice = np.argmax(score, axis=1)
    out[ok] = codes[index[np.flatnonzero(ok), choice[ok]]]
    return out


def repeats_in_windows(string: Timed, vote: Vote, conf: ContentConf, copies_needed: int,
                        beyond_chance: bool = True) -> bool:
    """Whether a string read in a group's windows repeats a pattern of its own.

    It needs at least ``copies_needed`` copies of the common length, and at
    least half of their columns (two or more) where the plurality symbol holds
    a share ``conserve`` of the copies and, when ``beyond_chance``, is more
    frequent than chance: the binomial tail of its count, at the symbol's
    frequency in the whole string, times the number of distinct symbols (any
    of them could have been the plurality), below 0.01.
    """
    length = len(vote.pattern)
    copies = vote.full_copies
    if copies < copies_needed or length < 2 or np.count_nonzero(
            vote.shares >= conf.conserve) < max(2, math.ceil(length / 2)):
        return False
    agreeing = 0
    for column, share in enumerate(vote.shares.tolist()):
        if share >= conf.conserve and (not beyond_chance or vote.log10_chance(column) <= -2):
            agreeing += 1
    return agreeing >= max(2, math.ceil(length / 2))
