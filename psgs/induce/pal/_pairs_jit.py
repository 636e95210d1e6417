"""The compiled synchronisation test: :func:`psgs.induce.pal.synchronisation.synchronised` for the
pairs of a block of rows of candidates in one numba call.

Only comparisons of the copies' times and integer counts, in the numpy engine's terms, so
the pairs are the same (tests/induce/test_pal_engines.py draws touching, overlapping and
out-of-order copy lists). Without numba this module still imports (plain Python functions).
"""

from __future__ import annotations

import math

import numpy as np

from ._chance_jit import _jit
from ._counting_jit import _stable_argsort

__all__: list[str] = []  # private: the PAL parameter ``engine`` is the interface


@_jit
def _disjoint(lo, hi):
    """synchronisation._disjoint, and each interval's end at or after its start: then starts and
    ends both only grow (what the pointers of :func:`_pair` need; otherwise the general
    clustering runs, which gives the same answer)."""
    for j in range(len(lo)):
        if not hi[j] >= lo[j] or (j and not lo[j] >= hi[j - 1]):
            return False
    return True


@_jit
def _overlap_runs(lo, hi, other_lo, other_hi):
    """For intervals ``(lo, hi)`` against ``(other_lo, other_hi)`` (both disjoint, in time
    order): how many of the other's each overlaps, summed, and how many overlap any."""
    overlaps, touching = 0, 0
    before_end = ended = 0
    for j in range(len(lo)):
        while before_end < len(other_lo) and other_lo[before_end] < hi[j]:
            before_end += 1
        while ended < len(other_hi) and other_hi[ended] <= lo[j]:
            ended += 1
        run = before_end - ended
        if run > 0:
            overlaps += run
            touching += 1
    return overlaps, touching


@_jit
def _pair(a_lo, a_hi, b_lo, b_hi, a_disjoint, b_disjoint, fraction, min_copies):
    """synchronisation.synchronised on copies ``(a_lo, a_hi)`` and ``(b_lo, b_hi)``."""
    if len(a_lo) == 0 or len(b_lo) == 0:
        return False
    if a_disjoint and b_disjoint:
        # synchronisation._shared_clusters: clusters = intervals - overlaps; each interval's run of
        # the other list's is two searchsorted counts, here read off by pointers moving
        # forward (the lists are in time order, so the counts only grow)
        overlaps, touching_a = _overlap_runs(a_lo, a_hi, b_lo, b_hi)
        _, touching_b = _overlap_runs(b_lo, b_hi, a_lo, a_hi)
        both = touching_a + touching_b - overlaps
        clusters = len(a_lo) + len(b_lo) - overlaps
    else:
        # synchronisation.copy_clusters: sorted by start, then end; a cluster opens past the reach
        lo = np.concatenate((a_lo, b_lo))
        hi = np.concatenate((a_hi, b_hi))
        by_end = _stable_argsort(hi)
        order = by_end[_stable_argsort(lo[by_end])]
        both, clusters = 0, 0
        reach = -math.inf
        has_a = has_b = False
        for j in range(len(order)):
            k = order[j]
            if j == 0 or lo[k] >= reach:
                if has_a and has_b:
                    both += 1
                clusters += 1
                has_a = has_b = False
            if k < len(a_lo):
                has_a = True
            else:
                has_b = True
            reach = hi[k] if j == 0 else max(reach, hi[k])
        if has_a and has_b:
            both += 1
    return both >= min_copies and both >= fraction * clusters


@_jit
def disjoint_flags(lo, hi, bounds):
    """:func:`_disjoint` of each copy list ``(lo, hi)[bounds[i]:bounds[i + 1]]``."""
    count = len(bounds) - 1
    disjoint = np.zeros(count, dtype=np.bool_)
    for i in range(count):
        disjoint[i] = _disjoint(lo[bounds[i]:bounds[i + 1]], hi[bounds[i]:bounds[i + 1]])
    return disjoint


@_jit
def synchronised_rows(lo, hi, bounds, disjoint, first, last, fraction, min_copies, stop):
    """Which pairs (i < j) of the copy lists ``(lo, hi)[bounds[i]:bounds[i + 1]]`` (start and
    end times) are synchronised, for the rows ``i`` from ``first`` to ``last - 1`` (row ``i``
    at ``i - first``, filled right of the diagonal); ``disjoint`` from :func:`disjoint_flags`.
    A block of rows a call: the table is the block's rows by every candidate (every row at
    once would be the candidates squared). ``stop`` (a one-byte flag, see
    :func:`psgs.induce.pal._alarm.alarm`) is read before each pair: once it is set the call
    returns with the rest of the table left False, and the caller, reading the flag after
    it, keeps none of it (a block is some 2^20 pair tests, seconds for long copy lists)."""
    count = len(bounds) - 1
    out = np.zeros((last - first, count), dtype=np.bool_)
    for i in range(first, last):
        a, b = bounds[i], bounds[i + 1]
        for j in range(i + 1, count):
            if stop[0]:
                return out
            c, d = bounds[j], bounds[j + 1]
            out[i - first, j] = _pair(lo[a:b], hi[a:b], lo[c:d], hi[c:d], disjoint[i],
                                      disjoint[j], fraction, min_copies)
    return out
