"""The compiled motif search: :func:`~psgs.induce.pal.motifs.find_motif` for every string in
one numba call (the synchronisation of candidates is in :mod:`._pairs_jit`, the chance
levels in :mod:`._chance_jit`, counting and sorting in :mod:`._counting_jit`).

The search is the numpy engine's step for step (the same seeds in the same order, the same
columns added, the same copies kept), in integer arithmetic and exact float comparisons
(``k >= conserve * len(pos)``, ``-k / len(pos)``: one IEEE operation each, numba without
``fastmath`` neither reorders nor fuses). Only the chance levels are floats that could come
out differently: numba's ``lgamma`` is the C library's, CPython's ``math.lgamma`` its own.
So nothing float computed here is ever returned. Where a scan threshold is decided (a
binomial tail against ``scan_alpha``) or two seeds' significances are compared, a result
within a relative 1e-6 of the boundary marks the string *uncertain* (then the numpy engine
searches it); the two implementations differ by some 1e-12, so every other decision is the
numpy engine's. The significance kept is computed in Python from the integers returned
(:func:`~psgs.induce.pal.motifs.significance`), so every ``Motif`` is the same to the bit.

A search can be stopped inside a string: every loop over a string's seeds, its growth steps
and the columns of a scan reads ``stop``, a one-byte array that
:func:`psgs.induce.pal._alarm.alarm` sets at the deadline from a timer thread (numba reads no
clock), and a string stopped is ``STOPPED``: the caller raises the bound, nothing of it is
kept. A flag that is never set changes nothing.

Without numba this module still imports (the functions are then plain Python, which
:func:`psgs.induce.pal.motifs.search` never offers), so that the doctests collect everywhere.
"""

from __future__ import annotations

import numpy as np

from ..._foundation.engines import jit_inlined as _inlined
from ._chance_jit import _MARGIN, _jit, _log10_binom_sf, _log10_poisson_sf, _threshold
from ._counting_jit import _digrams, _grouped, _sorted

__all__: list[str] = []  # private: the PAL parameter ``engine`` is the interface

#: status of a string after the search (STOPPED: ``stop`` was set before it ended)
NONE, FOUND, UNCERTAIN, STOPPED = 0, 1, 2, 3
#: farthest column looked at beyond a damaged one while growing (motifs._BRIDGE)
_BRIDGE = 2


# -- copies ------------------------------------------------------------------------------
@_jit
def _chain(positions, count, length):
    """Sorted ``positions[:count]`` kept left to right, each ``length`` after the last
    (duplicates dropped): motifs.merge_copies and motifs.keep_apart."""
    out = np.empty(count, dtype=np.int64)
    kept = 0
    for j in range(count):
        p = positions[j]
        if kept == 0 or p >= out[kept - 1] + length:
            out[kept] = p
            kept += 1
    return out[:kept]


@_jit
def _merge(old, new, length):
    """motifs.merge_copies: both lists, earlier first, none overlapping one kept before."""
    if not (_ascending(old) and _ascending(new)):
        both = _sorted(np.concatenate((old, new)))
        return _chain(both, len(both), length)
    # both in position order already (as they always are here): merged in one pass
    both = np.empty(len(old) + len(new), dtype=np.int64)
    i = j = 0
    for k in range(len(both)):
        if j >= len(new) or (i < len(old) and old[i] <= new[j]):
            both[k] = old[i]
            i += 1
        else:
            both[k] = new[j]
            j += 1
    return _chain(both, len(both), length)


@_jit
def _ascending(values):
    for j in range(1, len(values)):
        if values[j] < values[j - 1]:
            return False
    return True


@_jit
def _locate(codes, motif, threshold, stop):
    """motifs.locate_copies: the best-agreeing non-overlapping windows, in position order
    (none once ``stop`` is set: the caller reads it)."""
    n, length = len(codes), len(motif)
    width = n - length + 1
    if width <= 0:
        return np.zeros(0, dtype=np.int64)
    score = np.zeros(width, dtype=np.int64)
    for o in range(length):  # column by column: a loop over the windows that vectorises
        if stop[0]:
            return np.zeros(0, dtype=np.int64)
        sym = motif[o]
        for w in range(width):
            score[w] += codes[w + o] == sym
    # the windows that pass, grouped by level (best first), in position order within one
    per_level = np.zeros(length + 2, dtype=np.int64)
    hits = 0
    for w in range(width):
        if score[w] >= threshold:
            per_level[length - score[w] + 1] += 1
            hits += 1
    if hits == 0:
        return np.zeros(0, dtype=np.int64)
    for level in range(1, length + 2):
        per_level[level] += per_level[level - 1]
    ranked = np.empty(hits, dtype=np.int64)
    for w in range(width):
        if score[w] >= threshold:
            slot = length - score[w]
            ranked[per_level[slot]] = w
            per_level[slot] += 1
    # best first, windows of one level left to right (as the numpy engine chains them): a
    # window is kept when no kept window lies within ``length`` of it
    blocked = np.zeros(width, dtype=np.bool_)
    chosen = np.zeros(width, dtype=np.bool_)
    for j in range(hits):
        w = ranked[j]
        if blocked[w]:
            continue
        chosen[w] = True
        blocked[max(0, w - length + 1):min(width, w + length)] = True
    out = np.empty(hits, dtype=np.int64)
    kept = 0
    for w in range(width):
        if chosen[w]:
            out[kept] = w
            kept += 1
    return out[:kept]


@_jit
def _median_gap(starts):
    gaps = np.empty(len(starts) - 1, dtype=np.int64)
    for j in range(len(gaps)):
        gaps[j] = starts[j + 1] - starts[j]
    gaps = _sorted(gaps)
    return gaps[(len(gaps) - 1) // 2]


# -- growing one seed -----------------------------------------------------------------------
@_jit
def grow_motif(codes, seed, starts, size, thresholds, p, lp, lq, min_copies, conserve,
               match_fraction, scan_alpha, max_pattern, column, seed_only, stop):
    """motifs.grow of one motif: (status, motif, starts, threshold); STOPPED when ``stop`` is
    set. ``thresholds`` holds the string's scan thresholds by length, computed on first
    need (-2 everywhere at first; an entry a length up to ``max(max_pattern, len(seed))``);
    ``column`` is ``size`` zeros, scratch left zeros: :func:`_search` passes its string's
    to every seed.

    Python (``motifs._grow_compiled``) and :func:`_search` call this one function: a
    compiled wrapper that made the scratch compiled all of the growth again (0.9 s of a
    cold start)."""
    n = len(codes)
    motif = seed.copy()
    grown_any = False
    added = np.empty(_BRIDGE, dtype=np.int64)
    best_added = np.empty(_BRIDGE, dtype=np.int64)
    while len(motif) < max_pattern:
        if stop[0]:
            return STOPPED, motif, starts, -1
        length = len(motif)
        spacing = _median_gap(starts) if len(starts) > 1 else n
        if length + 1 > spacing:
            break
        have = False
        best_d, best_ratio, best_right = 0, 0.0, True
        for right in (True, False):
            reach = min(_BRIDGE, spacing - length, max_pattern - length)
            for d in range(1, reach + 1):
                valid = 0
                for s in starts:
                    q = s + length + d - 1 if right else s - d
                    if 0 <= q < n:
                        valid += 1
                        column[codes[q]] += 1
                sym, k = -1, 0
                for s in starts:  # the most frequent symbol, the lowest code among equals
                    q = s + length + d - 1 if right else s - d
                    if 0 <= q < n:
                        c = codes[q]
                        if column[c] > k or (column[c] == k and c < sym):
                            sym, k = c, column[c]
                for s in starts:
                    q = s + length + d - 1 if right else s - d
                    if 0 <= q < n:
                        column[codes[q]] = 0
                if valid < min_copies or k < min_copies:
                    break
                added[d - 1] = sym
                if k >= conserve * valid:
                    ratio = -k / valid
                    if not have or d < best_d or (d == best_d and ratio < best_ratio):
                        have, best_d, best_ratio, best_right = True, d, ratio, right
                        for j in range(d):
                            best_added[j] = added[j]
                    break
        if not have:
            break
        d = best_d
        grown = np.empty(length + d, dtype=np.int64)
        shift = 0 if best_right else d  # (plain loops: array expressions are slow to compile)
        for j in range(d):
            if best_right:
                grown[length + j] = best_added[j]
            else:
                grown[j] = best_added[d - 1 - j]
        for j in range(length):
            grown[shift + j] = motif[j]
        glen = length + d
        kept = np.empty(len(starts), dtype=np.int64)
        count = 0
        for s in starts:
            if s - shift >= 0 and s - shift + glen <= n:
                kept[count] = s - shift
                count += 1
        kept = kept[:count]
        threshold = _threshold_of(thresholds, glen, n, p, lp, lq, match_fraction, scan_alpha)
        if threshold < 0:
            return UNCERTAIN, motif, starts, -1
        located = _locate(codes, grown, threshold, stop)
        if stop[0]:
            return STOPPED, motif, starts, -1
        found = _merge(kept, located, glen)
        if len(found) < min_copies:
            break
        motif, starts, grown_any = grown, found, True
    length = len(motif)
    threshold = _threshold_of(thresholds, length, n, p, lp, lq, match_fraction, scan_alpha)
    if threshold < 0:
        return UNCERTAIN, motif, starts, -1
    rotated_any = False
    if len(starts) > 1 and _median_gap(starts) == length and starts[0] % length:
        shift = starts[0] % length
        rotated = np.empty(length, dtype=np.int64)
        for j in range(length):
            rotated[j] = motif[(j - shift) % length]
        found = _locate(codes, rotated, threshold, stop)
        if stop[0]:
            return STOPPED, motif, starts, -1
        if len(found) >= len(starts):
            motif, starts, rotated_any = rotated, found, True
    if not (seed_only and length == 2 and motif[0] != motif[1] and threshold >= 2
            and not grown_any and not rotated_any):
        located = _locate(codes, motif, threshold, stop)
        if stop[0]:
            return STOPPED, motif, starts, -1
        starts = _merge(starts, located, length)
    if len(starts) < min_copies:
        return NONE, motif, starts, threshold
    return FOUND, motif, starts, threshold


@_jit
def _threshold_of(cache, length, n, p, lp, lq, match_fraction, scan_alpha):
    """The scan threshold of ``length`` in this string, computed once (-2: not yet)."""
    if cache[length] == -2:
        cache[length] = _threshold(length, n - length + 1, p, lp, lq, match_fraction,
                                   scan_alpha)
    return cache[length]


@_jit
def _significance(n, length, threshold, copies, p, lp, lq, log_distinct):
    """About motifs.significance (only compared between seeds)."""
    lam = (n - length + 1) * 10.0 ** _log10_binom_sf(threshold, length, p, lp, lq)
    return min(length * log_distinct + _log10_poisson_sf(copies, lam), 0.0)


@_inlined  # (into search_strings: compiled on its own, 1.5-2 s more)
def _search(codes, size, p, lp, lq, log_distinct, min_copies, seeds, conserve,
            match_fraction, scan_alpha, max_pattern, motif_out, starts_out, stop):
    """motifs.find_motif on one string: (status, length, copies, threshold)."""
    n = len(codes)
    if n < 2 * min_copies:
        return NONE, 0, 0, 0
    keys = np.empty(n - 1, dtype=np.int64)
    for j in range(n - 1):
        keys[j] = codes[j] * size + codes[j + 1]
    if stop[0]:
        return STOPPED, 0, 0, 0
    order, begin, counts = _digram_groups(keys, size * size, stop)
    if stop[0]:
        return STOPPED, 0, 0, 0
    first = np.empty(len(counts), dtype=np.int64)
    for g in range(len(counts)):
        first[g] = order[begin[g]]
    taken = np.zeros(len(counts), dtype=np.bool_)
    thresholds = np.full(max_pattern + 1, -2, dtype=np.int64)
    column = np.zeros(size, dtype=np.int64)
    # (a run-time True: a literal one would compile grow_motif a second time)
    as_seed = seeds > 0
    covered = np.empty(seeds * max_pattern, dtype=np.int64)
    n_covered = 0
    tried = 0
    status = NONE
    best_len, best_copies, best_threshold, best_sig = 0, 0, 0, 0.0
    while True:
        if stop[0]:  # (a pass over the digrams below, as many as the string's symbols)
            return STOPPED, 0, 0, 0
        # the next seed: most frequent first, the earlier first occurrence among equals
        gi = -1
        for g in range(len(counts)):
            if not taken[g] and (gi < 0 or counts[g] > counts[gi]
                                 or (counts[g] == counts[gi] and first[g] < first[gi])):
                gi = g
        if gi < 0 or tried >= seeds or counts[gi] < min_copies:
            break
        taken[gi] = True
        key = keys[order[begin[gi]]]
        inside = False
        for c in range(n_covered):
            if covered[c] == key:
                inside = True
                break
        if inside:
            continue
        tried += 1
        seed = np.empty(2, dtype=np.int64)
        seed[0], seed[1] = key // size, key % size
        starts = order[begin[gi]:begin[gi + 1]].copy()  # in position order
        got, motif, where, threshold = grow_motif(codes, seed, starts, size, thresholds, p, lp,
                                                  lq, min_copies, conserve, match_fraction,
                                                  scan_alpha, max_pattern, column, as_seed,
                                                  stop)
        if got == UNCERTAIN or got == STOPPED:
            return got, 0, 0, 0
        if got == NONE:
            continue
        for j in range(len(motif) - 1):
            covered[n_covered] = motif[j] * size + motif[j + 1]
            n_covered += 1
        length, copies = len(motif), len(where)
        if status == FOUND and length == best_len and copies == best_copies \
                and threshold == best_threshold:
            continue  # the same significance exactly: the earlier seed stays
        sig = _significance(n, length, threshold, copies, p, lp, lq, log_distinct)
        if status == FOUND:
            if abs(sig - best_sig) <= _MARGIN * (1.0 + abs(sig) + abs(best_sig)):
                if not (sig == 0.0 and best_sig == 0.0 and _clear(n, length, threshold,
                                                                  copies, p, lp, lq,
                                                                  log_distinct)):
                    return UNCERTAIN, 0, 0, 0
                continue  # both clearly insignificant (0): the earlier seed stays
            if sig >= best_sig:
                continue
        status = FOUND
        best_len, best_copies, best_threshold, best_sig = length, copies, threshold, sig
        # element loops: an array assigned to a slice compiles a shape check whose error
        # message (string formatting) took 1.7 s of the engine's 15 s of compilation
        for j in range(length):
            motif_out[j] = motif[j]
        for j in range(copies):
            starts_out[j] = where[j]
    return status, best_len, best_copies, best_threshold


#: the bits of the keys' digit each pass of :func:`_digram_groups`'s radix sort places
_DIGIT = 16


@_jit
def _digram_groups(keys, bins, stop):
    """``_counting_jit._digrams(keys, bins)`` (positions by key, each key's in position
    order; where each key's group begins; its count), reading ``stop`` in its passes.

    A small alphabet's keys are counted there (three passes); a large one's are sorted
    here by a stable radix sort, a pass a :data:`_DIGIT`-bit digit from the lowest (3
    passes for keys below 2^48, where the merge sort there takes a pass a doubling: 24 for
    10^7 keys, seconds that read no flag). A stable sort has one answer, so the groups are
    the same. Once ``stop`` is set the arrays returned are not whole (the caller reads it).
    """
    m = len(keys)
    if bins <= 4 * m + 4096:
        return _digrams(keys, bins)
    order = np.arange(m)
    spare = np.empty(m, dtype=np.int64)
    at = np.empty(1 << _DIGIT, dtype=np.int64)
    mask = (1 << _DIGIT) - 1
    shift = 0
    while shift < 63 and (bins - 1) >> shift:  # (a shift of 64 bits is no shift in C)
        if stop[0]:
            return order, np.zeros(1, dtype=np.int64), np.zeros(0, dtype=np.int64)
        at[:] = 0
        for j in range(m):
            at[(keys[j] >> shift) & mask] += 1
        total = 0
        for d in range(len(at)):  # each digit's first place
            count = at[d]
            at[d] = total
            total += count
        for j in range(m):
            if not j & mask and stop[0]:  # (a scattered pass: 0.3 s at 10^7 keys)
                return order, np.zeros(1, dtype=np.int64), np.zeros(0, dtype=np.int64)
            k = order[j]
            d = (keys[k] >> shift) & mask
            spare[at[d]] = k
            at[d] += 1
        order, spare = spare, order
        shift += _DIGIT
    return _grouped(keys, order)


@_jit
def _clear(n, length, threshold, copies, p, lp, lq, log_distinct):
    """Whether a significance is clearly at least 0 (so that it is exactly 0 once clipped)."""
    lam = (n - length + 1) * 10.0 ** _log10_binom_sf(threshold, length, p, lp, lq)
    return length * log_distinct + _log10_poisson_sf(copies, lam) > _MARGIN


def find_motifs(codes, bounds, sizes, p, lp, lq, log_distinct, min_copies, seeds, conserve,
                match_fraction, scan_alpha, max_pattern):
    """The motif search of every string ``codes[bounds[i]:bounds[i + 1]]`` (never stopped):
    :func:`search_strings` called from Python (compiled, this wrapper compiled all of the
    search a second time, 2 s, in the first test that called it).

    Returns ``status`` (NONE, FOUND, UNCERTAIN), the motif's ``length``, its number of
    ``copies`` and the ``threshold`` of each string, the motifs as rows of ``motifs`` and the
    copy starts of string i from ``bounds[i]`` in ``starts``.
    """
    strings = len(bounds) - 1
    out = (np.zeros(strings, dtype=np.int64), np.zeros(strings, dtype=np.int64),
           np.zeros(strings, dtype=np.int64), np.zeros(strings, dtype=np.int64),
           np.zeros((strings, max_pattern), dtype=np.int64),
           np.zeros(len(codes), dtype=np.int64))
    search_strings(codes, bounds, 0, strings, sizes, p, lp, lq, log_distinct, min_copies,
                   seeds, conserve, match_fraction, scan_alpha, max_pattern,
                   np.zeros(1, dtype=np.uint8), *out)
    return out


@_jit
def search_strings(codes, bounds, first, last, sizes, p, lp, lq, log_distinct, min_copies,
                   seeds, conserve, match_fraction, scan_alpha, max_pattern, stop, status,
                   length, copies, threshold, motifs, starts):
    """:func:`find_motifs` of strings ``first`` to ``last - 1``, written into the arrays
    given (so that threads can search disjoint runs of strings side by side); once ``stop``
    is set, every string not searched to its end is STOPPED."""
    for i in range(first, last):
        if stop[0]:
            status[i] = STOPPED
            continue
        a, b = bounds[i], bounds[i + 1]
        status[i], length[i], copies[i], threshold[i] = _search(
            codes[a:b], sizes[i], p[i], lp[i], lq[i], log_distinct[i], min_copies, seeds,
            conserve, match_fraction, scan_alpha, max_pattern, motifs[i], starts[a:b], stop)
