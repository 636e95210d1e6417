"""Counting and sorting for the compiled motif search: digrams grouped, symbols counted,
integers sorted (by hand: numba's ``np.sort`` and ``np.argsort`` take seconds each to compile,
and a sort of integers, or a stable one, has only one answer)."""

from __future__ import annotations

import numpy as np

from ._chance_jit import _jit

__all__: list[str] = []  # private: the PAL parameter ``engine`` is the interface


@_jit
def _stable_argsort(keys):
    """The order of ``keys`` (ascending, equal keys in index order), as
    ``np.argsort(keys, kind="stable")``: a bottom-up merge sort of the indices."""
    n = len(keys)
    order = np.arange(n)
    spare = np.empty(n, dtype=np.int64)
    width = 1
    while width < n:
        for lo in range(0, n, 2 * width):
            mid, hi = min(lo + width, n), min(lo + 2 * width, n)
            i, j = lo, mid
            for k in range(lo, hi):
                if j >= hi or (i < mid and keys[order[i]] <= keys[order[j]]):
                    spare[k] = order[i]
                    i += 1
                else:
                    spare[k] = order[j]
                    j += 1
        order, spare = spare, order
        width *= 2
    return order


@_jit
def _sorted(values):
    """``np.sort(values)`` (of integers: any correct sort gives the same array)."""
    return values[_stable_argsort(values)]


@_jit
def _digrams(keys, bins):
    """The digram keys grouped: positions by key (in position order within a key), where
    each key's group begins (one bound past the last) and its count."""
    m = len(keys)
    if bins <= 4 * m + 4096:  # counting: a small alphabet
        order = np.empty(m, dtype=np.int64)
        count = np.zeros(bins, dtype=np.int64)
        for j in range(m):
            count[keys[j]] += 1
        groups = 0
        for k in range(bins):
            if count[k]:
                groups += 1
        begin = np.empty(groups + 1, dtype=np.int64)
        at = np.empty(bins, dtype=np.int64)
        g, total = 0, 0
        for k in range(bins):
            if count[k]:
                begin[g] = total
                at[k] = total
                total += count[k]
                g += 1
        begin[groups] = m
        for j in range(m):
            order[at[keys[j]]] = j
            at[keys[j]] += 1
        return order, begin, _runs(begin)
    # sorting, a large alphabet: equal keys keep their order (position order)
    order = _stable_argsort(keys)
    return _grouped(keys, order)


@_jit
def _grouped(keys, order):
    """``(order, begin, runs)`` of keys sorted by ``order``: where each group of equal keys
    begins (and, last, their count), and :func:`_runs` of that."""
    m = len(order)
    groups = 0
    for j in range(m):
        if j == 0 or keys[order[j]] != keys[order[j - 1]]:
            groups += 1
    begin = np.empty(groups + 1, dtype=np.int64)
    g = 0
    for j in range(m):
        if j == 0 or keys[order[j]] != keys[order[j - 1]]:
            begin[g] = j
            g += 1
    begin[groups] = m
    return order, begin, _runs(begin)


@_jit
def _runs(begin):
    counts = np.empty(len(begin) - 1, dtype=np.int64)
    for g in range(len(counts)):
        counts[g] = begin[g + 1] - begin[g]
    return counts


@_jit
def symbol_counts(codes, bounds, width):
    """How often each code occurs in each string ``codes[bounds[i]:bounds[i + 1]]``:
    a (strings, width) array."""
    counts = np.zeros((len(bounds) - 1, width), dtype=np.int64)
    for i in range(len(bounds) - 1):
        for j in range(bounds[i], bounds[i + 1]):
            counts[i, codes[j]] += 1
    return counts
