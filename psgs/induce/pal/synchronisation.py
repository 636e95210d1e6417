"""Which strings' copies cover the same time: the synchronisation test of two strings
(:func:`synchronised`) and of every pair of many (:func:`pair_blocks`), by numpy's array
passes or numba's compiled loops (the same pairs).
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import TYPE_CHECKING

import numpy as np

from ..._foundation.engines import select
from ...errors import BoundReached
from ._alarm import alarm
from .conf import NO_BOUND

if TYPE_CHECKING:
    from ...budget import Budget
    from .conf import ContentConf


def copy_clusters(parts: list[np.ndarray]) -> np.ndarray:
    """Merge the intervals of several lists wherever they overlap.

    Returns a (clusters, lists) boolean array: which lists each cluster holds.
    """
    spans = np.concatenate(parts)
    tags = np.concatenate([np.full(len(iv), k) for k, iv in enumerate(parts)])
    order = np.lexsort((spans[:, 1], spans[:, 0]))
    spans, tags = spans[order], tags[order]
    reach = np.maximum.accumulate(spans[:, 1])
    opens = np.ones(len(spans), dtype=bool)
    opens[1:] = spans[1:, 0] >= reach[:-1]
    cluster = np.cumsum(opens) - 1
    held = np.zeros((int(cluster[-1]) + 1, len(parts)), dtype=bool)
    held[cluster, tags] = True
    return held


def synchronised(a: np.ndarray, b: np.ndarray, fraction: float, min_copies: int) -> bool:
    """Whether two strings' copies cover the same time.

    Overlapping copies of both strings are merged into clusters; the strings
    are synchronised when at least ``min_copies`` clusters hold copies of both
    and those are at least ``fraction`` of all clusters. (A string whose
    period is half the other's has two copies in one cluster: still one
    shared cluster, so the period is shared in time.)
    """
    if len(a) == 0 or len(b) == 0:
        return False
    return _synchronised(a, b, _disjoint(a) and _disjoint(b), fraction, min_copies)


def _synchronised(a: np.ndarray, b: np.ndarray, disjoint: bool, fraction: float,
                  min_copies: int) -> bool:
    """:func:`synchronised` of two lists of copies (neither empty), ``disjoint`` when both
    are :func:`_disjoint` (known beforehand: a row of pair tests reads each list's once)."""
    if disjoint:
        both, clusters = _shared_clusters(a, b)
    else:
        held = copy_clusters([a, b])
        both, clusters = int(np.count_nonzero(held.all(axis=1))), len(held)
    return both >= min_copies and both >= fraction * clusters


def synchronised_pairs(lists: list[np.ndarray], conf: ContentConf, clock: Budget = NO_BOUND
                       ) -> list[tuple[int, int]]:
    """The pairs ``(i, j)``, ``i < j`` in order, of copy interval lists that are
    :func:`synchronised`, by the engine ``conf.engine`` chooses (the same pairs): the pairs
    of :func:`pair_blocks` in one list.

    Examples
    --------
    >>> from psgs.induce.pal.conf import ContentConf
    >>> copies = np.array([[0.0, 1.0], [5.0, 6.0], [10.0, 11.0]])
    >>> synchronised_pairs([copies, copies + 0.2, copies + 2.5], ContentConf(engine="numpy"))
    [(0, 1)]
    """
    return [(i, j) for rows, columns in pair_blocks(lists, conf, clock)
            for i, j in zip(rows, columns)]


def pair_blocks(lists: list[np.ndarray], conf: ContentConf, clock: Budget = NO_BOUND
                ) -> Iterator[tuple[list[int], list[int]]]:
    """The pairs of :func:`synchronised_pairs`, a block of rows at a time: for each block,
    the ``i`` and the ``j`` of its pairs as two lists (the pairs in order over the blocks).

    The caller keeps what it needs of each block as it comes: the pairs are up to the
    lists squared, and a list of them all would be held beside what the caller makes of
    them. ``clock`` is read before each ``i`` (the compiled engine: before each block of
    rows, when it has a deadline) and raises :class:`~psgs.errors.BoundReached` past it.

    Examples
    --------
    >>> from psgs.induce.pal.conf import ContentConf
    >>> copies = np.array([[0.0, 1.0], [5.0, 6.0], [10.0, 11.0]])
    >>> list(pair_blocks([copies, copies + 0.2, copies + 0.4], ContentConf(engine="numpy")))
    [([0, 0], [1, 2]), ([1], [2])]
    """
    blocks = select(conf.engine, numpy=_pairs_each, numba=lambda: _pairs_compiled)
    return blocks(lists, conf.sync_fraction, conf.min_copies, clock)


#: numpy's engine reads the clock before each this many pair tests of a row (some 30 µs a
#: test: a row of 100,000 candidates would be 3 s between two readings)
PAIRS_CLOCKED = 1 << 10


def _pairs_each(lists: list[np.ndarray], fraction: float, copies: int,
                clock: Budget = NO_BOUND) -> Iterator[tuple[list[int], list[int]]]:
    """numpy's engine: :func:`synchronised` on every pair, a row a block, the clock read
    before each :data:`PAIRS_CLOCKED` pairs of a row (fewer where the copies are many:
    :data:`PAIR_QUERIES`).

    The pairs of disjoint lists (the usual case) are tested a part of a row at once
    (:func:`_row_synchronised`); the others one by one (:func:`copy_clusters`).
    """
    count = len(lists)
    # each list's disjointness, once (not once a pair: a third of the tests' time)
    disjoint = [bool(len(iv)) and _disjoint(iv) for iv in lists]
    held = np.cumsum([0] + [len(iv) for iv in lists])  # copies of the lists before each
    for i in range(count):
        partners: list[int] = []
        a = lists[i]
        step = max(1, min(PAIRS_CLOCKED, PAIR_QUERIES // max(len(a), 1)))
        first = i + 1
        while True:  # (the clock read before each part, and once in a row of none)
            clock.check()
            if not len(a) or first >= count:
                last = first + step
            else:
                # a part's partners hold at most PAIR_QUERIES copies too (one partner at least)
                last = max(first + 1, min(first + step, count, int(np.searchsorted(
                    held, held[first] + PAIR_QUERIES, side="right")) - 1))
                together = _row_synchronised(a, lists[first:last], fraction, copies) \
                    if disjoint[i] else None
                partners += [j for j in range(first, last) if len(lists[j]) and (
                    together[j - first] if disjoint[i] and disjoint[j]
                    else _synchronised(a, lists[j], False, fraction, copies))]
            first = last
            if first >= max(count, i + 2):
                break
        if partners:
            yield [i] * len(partners), partners


#: numpy's engine tests a part of a row at once whose counts (the row's copies times the
#: partners) and whose partners' copies are each at most about this many: some 15 MB of
#: working arrays (measured with tracemalloc on rows of 10 to 3,000 copies against partners
#: of 1,000 to 3,000 copies each)
PAIR_QUERIES = 1 << 18


def _row_synchronised(a: np.ndarray, lists: list[np.ndarray], fraction: float,
                      copies: int) -> np.ndarray:
    """Per list of ``lists``: :func:`_synchronised` of ``a`` and it, when both are disjoint
    (else meaningless): :func:`_shared_clusters` of every pair at once.

    With ``a``'s copies in order, "list j's starts before ``a``'s k-th end" is the number of
    j's starts that fewer than k + 1 of ``a``'s ends are at or before: each start is placed
    among ``a``'s ends once (one search of them all), and a running count per list reads off
    every k. The floats are compared as :func:`_shared_clusters` compares them.

    Examples
    --------
    >>> a = np.array([[0.0, 1.0], [5.0, 6.0], [10.0, 11.0]])
    >>> _row_synchronised(a, [a + 0.2, a + 2.5, a[:1]], 0.5, 2).tolist()
    [True, False, False]
    """
    sizes = np.array([len(iv) for iv in lists], dtype=np.int64)
    b = (np.concatenate([np.asarray(iv, dtype=np.float64).reshape(-1, 2) for iv in lists])
         if len(lists) else np.zeros((0, 2)))
    owner = np.repeat(np.arange(len(lists), dtype=np.int64), sizes)
    m = len(a)

    def before(placed: np.ndarray) -> np.ndarray:
        # lists x copies of a: how many of a list's placed values have a place at most k
        held = np.bincount(owner * (m + 1) + placed, minlength=len(lists) * (m + 1))
        return np.cumsum(held.reshape(len(lists), m + 1), axis=1)[:, :m]

    # per copy k of a and list j: j's copies starting before k ends, less those ending by
    # its start: the run of j's copies k overlaps
    runs_a = (before(np.searchsorted(a[:, 1], b[:, 0], side="right"))
              - before(np.searchsorted(a[:, 0], b[:, 1], side="left")))
    overlaps = np.maximum(runs_a, 0).sum(axis=1)
    touching = np.count_nonzero(runs_a > 0, axis=1)
    # per copy of the lists, the run of a's copies it overlaps
    runs_b = (np.searchsorted(a[:, 0], b[:, 1], side="left")
              - np.searchsorted(a[:, 1], b[:, 0], side="right"))
    touching += np.bincount(owner, weights=runs_b > 0, minlength=len(lists)).astype(np.int64)
    both = touching - overlaps
    clusters = m + sizes - overlaps
    return (both >= copies) & (both >= fraction * clusters)


#: The compiled engine tests the pairs of a block of rows a call, about this many: its table
#: of the block's pairs is that many bytes (a row at least), where one table of every pair
#: would be the lists squared (100 MB at 10,000 candidates)
PAIRS_PER_CALL = 1 << 20


#: The compiled engine hands its pairs on at most this many at a time
PAIRS_HANDED = 1 << 16


def _pairs_compiled(lists: list[np.ndarray], fraction: float, copies: int,
                    clock: Budget = NO_BOUND) -> Iterator[tuple[list[int], list[int]]]:
    """The compiled engine: a call per block of rows, the clock read between them and an
    :func:`~psgs.induce.pal._alarm.alarm` of it before each pair inside them."""
    from . import _pairs_jit as jit

    bounds = np.zeros(len(lists) + 1, dtype=np.int64)
    np.cumsum([len(iv) for iv in lists], out=bounds[1:])
    spans = np.concatenate(lists).astype(np.float64).reshape(-1, 2) if lists \
        else np.zeros((0, 2))
    lo, hi = np.ascontiguousarray(spans[:, 0]), np.ascontiguousarray(spans[:, 1])
    disjoint = jit.disjoint_flags(lo, hi, bounds)
    count = len(lists)
    rows = max(1, PAIRS_PER_CALL // max(count, 1))
    with alarm(clock) as stop:
        for first in range(0, count, rows):
            clock.check()
            last = min(first + rows, count)
            # (the block's table is let go before the next block's is made)
            table = jit.synchronised_rows(lo, hi, bounds, disjoint, first, last,
                                          float(fraction), int(copies), stop)
            if stop[0]:  # the deadline came inside the block: its table is not whole
                raise BoundReached("max_seconds")
            at, partners = np.nonzero(table)
            del table
            # as Python ints a pair takes some 70 bytes: handed on a part of the block at a
            # time
            for part in range(0, len(at), PAIRS_HANDED):
                yield ((at[part:part + PAIRS_HANDED] + first).tolist(),
                       partners[part:part + PAIRS_HANDED].tolist())


def _disjoint(spans: np.ndarray) -> bool:
    """Whether intervals, in time order, neither overlap nor come out of order."""
    return bool(np.all(spans[1:, 0] >= spans[:-1, 1]))


def _shared_clusters(a: np.ndarray, b: np.ndarray) -> tuple[int, int]:
    """What :func:`copy_clusters` finds for two lists of disjoint intervals, without sorting.

    Each interval overlaps a run of the other list's; overlaps only join the
    two lists, and on a line they form paths, so a cluster of k intervals has
    k - 1 overlaps: clusters = intervals - overlaps, and the clusters holding
    both lists = intervals that overlap something - overlaps.
    """
    runs_a = (np.searchsorted(b[:, 0], a[:, 1], side="left")
              - np.searchsorted(b[:, 1], a[:, 0], side="right"))
    runs_b = (np.searchsorted(a[:, 0], b[:, 1], side="left")
              - np.searchsorted(a[:, 1], b[:, 0], side="right"))
    overlaps = int(np.maximum(runs_a, 0).sum())
    touching = int(np.count_nonzero(runs_a > 0) + np.count_nonzero(runs_b > 0))
    return touching - overlaps, len(a) + len(b) - overlaps
