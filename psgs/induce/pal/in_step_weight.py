"""How close a string's section lies to a lead's copies by chance: one string's weight or many.

:func:`in_step_significance` is the weight of one string's exact copies where a lead's
copies are (the test of a group of sections in step, :mod:`~psgs.induce.pal.in_step`).
:func:`in_step_weights` gives the weights of many rows (a string and the lead's copies it
is read at) at once, each the same to the bit: a group of strings in step tries every
member as its lead and weighs every other string at the lead's copies, so 2,000 strings
all in step are some 1.6 million weights of a few short arrays each, where numpy's cost
per call, not per symbol, decided (63 % of 10 minutes). The rows' arrays are laid end to
end and every elementwise step runs once over all of them, in the order and with the
operations of :func:`in_step_significance`; each row's sums of several terms are still
summed alone, as it sums them.
"""

from __future__ import annotations

import math

import numpy as np

from .motifs import Timed
from .sections import Section

__all__: list[str] = []  # private: in_step.py is the caller

#: the sets of windows ranked together at most (more: copy by copy), see ``_as_close``
_SETS = 1 << 12
#: rows weighed together lay end to end at most this many windows, segments and pairs of
#: copies, and about as many sets of windows (a longer row is weighed alone, by
#: in_step_significance)
_BATCH_CELLS = 1 << 20
#: the bits of a sorting key that holds a group's number and one of its sets' keys
_KEY_BITS = 62


def in_step_significance(string: Timed, section: Section, copies: np.ndarray, lead: np.ndarray,
                         follow: float | None, maximal: bool = True) -> float:
    """``log10(A * H * P * (1 - r^(c-1)))``: a section's exact copies, lying as close to
    the lead's copies as they do, by chance; ``inf`` when they do not keep the lead's shift.

    ``P = (q r^(L-1))^(c-1)``, the chance that ``c`` windows of ``L`` symbols agree
    (``q`` the match rate, ``r`` the follow rate or ``q``), and ``1 - r^(c-1)`` that the
    symbols before them do not (a repeat counted once, at its left end; 1 when a copy
    could open the string). A copy pairs with a lead copy when the two share half of the
    time they cover together; its distance to it is the time outside the shared part (how
    far its start and its end lie from the lead copy's). Of the sets of windows of ``L``
    symbols pairing copy by copy with the lead copies these pair with (a copy pairing with
    none: any window), ``A`` lie as close as these copies do: their distances summed, plus
    their **mismatch**, how far each copy's start and end lie off the lead's otherwise
    than the first copy's do (summed over the copies after the first). Copies played at the
    same times as the lead's keep its shift between them, and the symbols that agree by
    chance around a section move the edges of all its copies alike, so a repeat off the
    lead's copies by the same amount in each is nearer than one off by different amounts.
    ``H`` is what choosing that closeness after seeing it costs: the sum over the closeness
    ``d`` of the sets at ``d`` over the sets at ``d`` or nearer (the union over every set
    of the chance that it is as strong; at most ``1 + ln`` of the sets). Only copies **in
    step** are weighed: their mismatch at most, per copy after the first, the string's
    median segment under the lead's copies or an eighth of the shortest lead copy,
    whichever is more (a symbol's worth of rhythm, a note held longer at a section's end;
    exact repeats at the same times have none), since copies played at the same times keep
    the lead's shift and a repeat at a shift of its own is no repeat in step, however near
    (the sets counted are still every set pairing as the copies do, so that the test is
    chosen no more finely than before the copies were seen). ``copies`` and
    ``lead`` are (copies, 2) arrays of times; ``maximal``: the copies are a maximal run of
    agreement (the symbols before them disagree), not a part of one.

    Examples
    --------
    >>> codes = np.array([0, 1, 2, 3, 4, 5, 1, 2, 3, 4, 6, 7])
    >>> string = Timed.from_codes(codes, np.ones(12), 0.0)
    >>> section = Section(codes[1:5], np.array([1, 6]), -1.0)
    >>> same = np.array([[1.0, 5.0], [6.0, 10.0]])
    >>> round(in_step_significance(string, section, same, same, None), 2)  # one place
    -3.11
    >>> round(in_step_significance(string, section, same, same + 1, None), 2)  # more
    -2.33
    >>> in_step_significance(string, section, same, same + [[0], [1]], None)  # off the shift
    inf
    """
    length = len(section.motif)
    q, r = string.chance_rates(follow)
    if q <= 0 or r <= 0:
        return -math.inf
    c = len(copies)
    chance = (c - 1) * (math.log10(q) + (length - 1) * math.log10(r))
    n = len(string.codes)
    begins = string.starts[:n - length + 1]
    ends = string.ends[length - 1:]
    slack = 1e-9 * max(1.0, float(np.max(np.abs(copies))))
    anywhere, opens = 0.0, False
    # per copy that pairs: its offsets from its lead copy (start, end) and those of every
    # window pairing as it does
    per_copy: list[tuple[tuple[float, float], np.ndarray, np.ndarray]] = []
    for a, b in copies.tolist():
        closest = None
        for lo, hi in lead.tolist():
            shared, union = min(b, hi) - max(a, lo), max(b, hi) - min(a, lo)
            if shared > 0 and 2 * shared >= union and (closest is None
                                                       or union - shared < closest[0]):
                closest = (union - shared, lo, hi)
        if closest is None:
            anywhere += math.log10(len(begins))  # it could be any window
            opens = True
            continue
        _, lo, hi = closest
        shared = np.minimum(ends, hi) - np.maximum(begins, lo)
        union = np.maximum(ends, hi) - np.minimum(begins, lo)
        pairs = (shared > 0) & (2 * shared >= union)
        per_copy.append(((a - lo, b - hi), begins[pairs] - lo, ends[pairs] - hi))
        opens = opens or bool(pairs[0])
    left = 0.0 if opens or not maximal else math.log10(max(1e-300, 1 - r ** (c - 1)))
    # copies in step keep the lead's shift, each copy after the first to within the
    # string's typical segment or an eighth of the lead's copy (a note held longer at a
    # section's end), or they are not in step at all
    under = (string.starts < lead[:, 1].max()) & (string.ends > lead[:, 0].min())
    durations = (string.ends - string.starts)[under]
    tolerance = (c - 1) * max(float(np.median(durations)) if len(durations) else 0.0,
                              float(np.min(lead[:, 1] - lead[:, 0])) / 8)
    return anywhere + _as_close(per_copy, slack, tolerance) + chance + left


def _as_close(per_copy: list[tuple[tuple[float, float], np.ndarray, np.ndarray]],
              slack: float, tolerance: float = math.inf) -> float:
    """log10 of ``A * H`` (:func:`in_step_significance`) for copies at the offsets given
    from their lead copies (start, end), each of which could have been any of the windows
    whose offsets are listed with it; ``inf`` when the copies' mismatch is over
    ``tolerance`` (not in step).

    The sets are ranked by their distance plus their mismatch while they are few (4096 or
    fewer); past that, copy by copy by the distance alone (``A`` and ``H`` the products of
    each copy's own: a ranking of its own, chosen by the sets' number alone, before the
    string is read).
    """
    if not per_copy:
        return 0.0
    sizes = [len(b) for _, b, _ in per_copy]
    if len(per_copy) > 1 and math.prod(sizes) > _SETS:
        return sum(_as_close([one], slack) for one in per_copy)
    (first_b, first_e), _, _ = per_copy[0]
    # every set's offsets: one window per copy (the sets as the rows of a grid)
    grids = np.meshgrid(*[np.arange(k) for k in sizes], indexing="ij")
    rows = [g.ravel() for g in grids]
    distance = np.zeros(len(rows[0]))
    mismatch = np.zeros(len(rows[0]))
    observed_d = observed_m = 0.0
    for k, ((db, de), begins, ends) in enumerate(per_copy):
        b, e = begins[rows[k]], ends[rows[k]]
        distance += np.abs(b) + np.abs(e)
        observed_d += abs(db) + abs(de)
        if k:
            b0, e0 = per_copy[0][1][rows[0]], per_copy[0][2][rows[0]]
            mismatch += np.abs(b - b0) + np.abs(e - e0)
            observed_m += abs(db - first_b) + abs(de - first_e)
    # (the sets' keys on a grid of ``slack``, so that float sums of the times do not part
    # equal keys)
    if observed_m > tolerance + slack:
        return math.inf  # (off the lead's shift: not in step)
    keys = np.round((mismatch + distance) / slack)
    near = max(1, int(np.count_nonzero(keys <= round((observed_m + observed_d) / slack))))
    # choosing the key after seeing it: the union over the sets of the chance each is as
    # strong, sum over the keys k of (sets at k) / (sets at k or nearer)
    _, counts = np.unique(keys, return_counts=True)
    return math.log10(near) + math.log10(float(np.sum(counts / np.cumsum(counts))))


def in_step_weights(rows: list[tuple[Timed, Section, np.ndarray, np.ndarray, float | None]]
                    ) -> list[float]:
    """``[in_step_significance(*row) for row in rows]``, to the bit, computed together.

    Each row is ``(string, section, copies, lead, follow)`` as
    :func:`in_step_significance` takes them (a maximal repeat). Rows are laid end to end a
    batch at a time (``_BATCH_CELLS`` windows, segments and pairs of copies at most); a
    row longer than a batch, or one :func:`in_step_significance` answers before it reads
    the copies (a rate of 0), is weighed alone by it.

    Examples
    --------
    >>> codes = np.array([0, 1, 2, 3, 4, 5, 1, 2, 3, 4, 6, 7])
    >>> string = Timed.from_codes(codes, np.ones(12), 0.0)
    >>> section = Section(codes[1:5], np.array([1, 6]), -1.0)
    >>> same = np.array([[1.0, 5.0], [6.0, 10.0]])
    >>> rows = [(string, section, same, lead, None) for lead in (same, same + 1)]
    >>> [round(w, 2) for w in in_step_weights(rows)]
    [-3.11, -2.33]
    >>> in_step_weights(rows) == [in_step_significance(*row) for row in rows]
    True
    """
    out: list[float] = [math.nan] * len(rows)
    batch: list[int] = []
    cells = 0
    for k, (string, section, copies, lead, follow) in enumerate(rows):
        n, c, m = len(string.codes), len(copies), len(lead)
        size = c * (n - len(section.motif) + 1) + n + c * m
        q, r = string.chance_rates(follow)
        if (size > _BATCH_CELLS or q <= 0 or r <= 0 or not c or not m
                or not len(section.motif) <= n):
            out[k] = in_step_significance(string, section, copies, lead, follow)
            continue
        if cells + size > _BATCH_CELLS:
            _weigh([rows[j] for j in batch], batch, out)
            batch, cells = [], 0
        batch.append(k)
        cells += size
    if batch:
        _weigh([rows[j] for j in batch], batch, out)
    return out


def _local(sizes: np.ndarray) -> np.ndarray:
    """``0, 1, ..., sizes[k] - 1`` for every ``k``, in order."""
    return np.arange(int(sizes.sum())) - np.repeat(np.cumsum(sizes) - sizes, sizes)


def _weigh(rows: list, places: list[int], out: list[float]) -> None:
    """:func:`in_step_weights` of one batch of rows, written to ``out`` at ``places``."""
    strings = [row[0] for row in rows]
    count = len(rows)
    n = np.array([len(s.codes) for s in strings], dtype=np.int64)
    lengths = np.array([len(row[1].motif) for row in rows], dtype=np.int64)
    windows = n - lengths + 1
    copies = np.concatenate([row[2] for row in rows]).reshape(-1, 2)
    leads = np.concatenate([row[3] for row in rows]).reshape(-1, 2)
    c = np.array([len(row[2]) for row in rows], dtype=np.int64)
    m = np.array([len(row[3]) for row in rows], dtype=np.int64)
    copy_row = np.repeat(np.arange(count), c)
    copy_from, lead_from = np.cumsum(c) - c, np.cumsum(m) - m

    # each copy's closest lead copy: the least time outside the shared part among the lead
    # copies it pairs with, the first among equals (every copy beside every lead copy)
    beside = m[copy_row]
    t_copy = np.repeat(np.arange(len(copies)), beside)
    t_lead = lead_from[copy_row][t_copy] + _local(beside)
    a, b = copies[t_copy, 0], copies[t_copy, 1]
    lo, hi = leads[t_lead, 0], leads[t_lead, 1]
    shared = np.minimum(b, hi) - np.maximum(a, lo)
    union = np.maximum(b, hi) - np.minimum(a, lo)
    valid = (shared > 0) & (2 * shared >= union)
    gap = np.where(valid, union - shared, np.inf)
    least = np.minimum.reduceat(gap, np.cumsum(beside) - beside)
    hit = np.flatnonzero(valid & (gap == least[t_copy]))
    lead_of = t_copy[hit]
    first = hit[np.concatenate((lead_of[:1] == lead_of[:1], lead_of[1:] != lead_of[:-1]))]
    paired, closest = t_copy[first], t_lead[first]  # (in copy order, row by row)
    entry_row = copy_row[paired]
    alone = np.bincount(copy_row, minlength=count) - np.bincount(entry_row, minlength=count)

    # every window of the row's string beside each paired copy's lead copy
    begins = np.concatenate([s.starts[:w] for s, w in zip(strings, windows.tolist())])
    ends = np.concatenate([s.ends[k - 1:] for s, k in zip(strings, lengths.tolist())])
    window_from = np.cumsum(windows) - windows
    spread = windows[entry_row]
    w_entry = np.repeat(np.arange(len(paired)), spread)
    w_local = _local(spread)
    at = window_from[entry_row][w_entry] + w_local
    lo_w, hi_w = leads[closest, 0][w_entry], leads[closest, 1][w_entry]
    wb, we = begins[at], ends[at]
    shared = np.minimum(we, hi_w) - np.maximum(wb, lo_w)
    union = np.maximum(we, hi_w) - np.minimum(wb, lo_w)
    pairs = (shared > 0) & (2 * shared >= union)
    opens = np.bincount(entry_row[w_entry[pairs & (w_local == 0)]], minlength=count) > 0
    chosen = np.flatnonzero(pairs)
    off_b, off_e = wb[chosen] - lo_w[chosen], we[chosen] - hi_w[chosen]
    sizes = np.bincount(w_entry[chosen], minlength=len(paired))
    entry_from = np.cumsum(sizes) - sizes
    seen_b = copies[paired, 0] - leads[closest, 0]
    seen_e = copies[paired, 1] - leads[closest, 1]

    # the string's segments under the lead's copies: their median sets the tolerance
    starts = np.concatenate([s.starts for s in strings])
    stops = np.concatenate([s.ends for s in strings])
    segment_row = np.repeat(np.arange(count), n)
    top = np.maximum.reduceat(leads[:, 1], lead_from)
    bottom = np.minimum.reduceat(leads[:, 0], lead_from)
    under = (starts < top[segment_row]) & (stops > bottom[segment_row])
    medians = _medians((stops - starts)[under], segment_row[under], count)

    # the sets of windows each row ranks: all its paired copies' (``_SETS`` sets at most),
    # or each copy's alone
    entries = np.bincount(entry_row, minlength=count)
    entry_from_row = np.cumsum(entries) - entries
    empty = np.bincount(entry_row[sizes == 0], minlength=count) > 0  # (as alone: an error)
    sets = _products(sizes, entry_from_row, entries, _SETS + 1)
    split = (entries > 1) & (sets > _SETS) & ~empty
    whole = np.flatnonzero((entries > 0) & ~split & ~empty)
    parted = np.flatnonzero(split[entry_row])  # (their entries, in order)
    slack = 1e-9 * np.maximum(1.0, np.maximum.reduceat(np.abs(copies).max(axis=1), copy_from))
    # (tolerance: (c - 1) * max(median, shortest / 8), as in_step_significance has it)
    eighth = np.minimum.reduceat(leads[:, 1] - leads[:, 0], lead_from) / 8
    tolerance = (c - 1) * np.where(medians >= eighth, medians, eighth)
    group_first = np.concatenate((entry_from_row[whole], parted))
    group_copies = np.concatenate((entries[whole], np.ones(len(parted), np.int64)))
    group_tolerance = np.concatenate((tolerance[whole], np.full(len(parted), np.inf)))
    group_slack = np.concatenate((slack[whole], slack[entry_row[parted]]))
    # (the groups' sets laid end to end a part at a time: ``_BATCH_CELLS`` sets at most, or
    # one group)
    reach = np.cumsum(np.concatenate((sets[whole], sizes[parted])))
    closeness: list[float] = []
    done = 0
    while done < len(group_first):
        upto = max(done + 1, int(np.searchsorted(
            reach, (reach[done - 1] if done else 0) + _BATCH_CELLS, side="right")))
        part = slice(done, upto)
        closeness += _closeness(group_first[part], group_copies[part], group_tolerance[part],
                                group_slack[part], sizes, entry_from, off_b, off_e, seen_b,
                                seen_e)
        done = upto
    close = [0.0] * count
    for row, value in zip(whole.tolist(), closeness):
        close[row] = value
    ones = iter(closeness[len(whole):])
    for row in np.flatnonzero(split).tolist():  # (a row's copies weighed alone, summed)
        close[row] = sum(next(ones) for _ in range(int(entries[row])))

    alone_list = alone.tolist()
    opened = ((alone > 0) | opens).tolist()
    counts, spans, empty_list = c.tolist(), windows.tolist(), empty.tolist()
    for row, (string, section, row_copies, lead, follow) in enumerate(rows):
        if empty_list[row]:
            out[places[row]] = in_step_significance(string, section, row_copies, lead, follow)
            continue
        q, r = string.chance_rates(follow)
        copies_row = counts[row]
        chance = (copies_row - 1) * (math.log10(q) + (len(section.motif) - 1) * math.log10(r))
        anywhere = 0.0
        for _ in range(alone_list[row]):
            anywhere += math.log10(spans[row])
        left = 0.0 if opened[row] else math.log10(max(1e-300, 1 - r ** (copies_row - 1)))
        out[places[row]] = anywhere + close[row] + chance + left


def _products(sizes: np.ndarray, first: np.ndarray, count: np.ndarray, cap: int) -> np.ndarray:
    """Per group, the product of ``sizes[first:first + count]`` or ``cap`` when it reaches
    ``cap`` (a group of none: 1)."""
    out = np.ones(len(first), dtype=np.int64)
    order = np.argsort(-count, kind="stable")  # (the groups with a k-th entry: a prefix)
    ranked_first, ranked_count = first[order], count[order]
    running = np.ones(len(first), dtype=np.int64)
    for k in range(int(count.max(initial=0))):
        live = int(np.count_nonzero(ranked_count > k))
        running[:live] = np.minimum(running[:live] * sizes[ranked_first[:live] + k], cap)
    out[order] = running
    return out


def _medians(values: np.ndarray, row: np.ndarray, count: int) -> np.ndarray:
    """Each row's ``np.median`` of its ``values`` (0.0 for a row with none): the middle
    value, or the mean of the middle two, of the row's values sorted."""
    order = np.lexsort((values, row))
    ordered = values[order]
    sizes = np.bincount(row, minlength=count)
    begins = np.cumsum(sizes) - sizes
    out = np.zeros(count)
    odd = sizes % 2 == 1
    out[odd] = ordered[begins[odd] + sizes[odd] // 2]
    even = np.flatnonzero((sizes > 0) & ~odd)
    middle = begins[even] + sizes[even] // 2
    # (np.median's mean of the middle two: their sum, halved)
    out[even] = (ordered[middle - 1] + ordered[middle]) / 2
    return out


def _closeness(first: np.ndarray, copies: np.ndarray, tolerance: np.ndarray,
               slack: np.ndarray, sizes: np.ndarray, entry_from: np.ndarray,
               off_b: np.ndarray, off_e: np.ndarray, seen_b: np.ndarray, seen_e: np.ndarray
               ) -> list[float]:
    """``_as_close`` of many groups at once: group ``g`` ranks the sets of one window per
    copy of its ``copies[g]`` paired copies from entry ``first[g]`` on (entry ``e`` holds
    ``sizes[e]`` windows' offsets from ``entry_from[e]`` in ``off_b``, ``off_e``; its own
    offsets are ``seen_b[e]``, ``seen_e[e]``)."""
    groups = len(first)
    if not groups:
        return []
    # groups with more copies first, so that the sets with a k-th copy are a prefix
    order = np.argsort(-copies, kind="stable")
    first, copies, tolerance, slack = first[order], copies[order], tolerance[order], slack[order]
    # each group's sets: the product of its copies' sizes, the last copy varying fastest
    # (a copy's stride: the product of the sizes after it)
    products_arr = np.ones(groups, dtype=np.int64)
    upto = np.ones(len(sizes), dtype=np.int64)
    for k in range(int(copies.max())):
        live = int(np.count_nonzero(copies > k))
        entry = first[:live] + k
        products_arr[:live] *= sizes[entry]
        upto[entry] = products_arr[:live]
    stride = np.ones(len(sizes), dtype=np.int64)
    for k in range(int(copies.max())):
        live = int(np.count_nonzero(copies > k))
        entry = first[:live] + k
        stride[entry] = products_arr[:live] // upto[entry]
    set_group = np.repeat(np.arange(groups), products_arr)
    set_local = _local(products_arr)
    total = len(set_group)
    distance = np.zeros(total)
    mismatch = np.zeros(total)
    seen_d = np.zeros(groups)
    seen_m = np.zeros(groups)
    b0 = e0 = first_b = first_e = None
    for k in range(int(copies.max())):
        live = int(np.count_nonzero(copies > k))  # (groups with a k-th copy: a prefix)
        reach = int(products_arr[:live].sum())
        entry = first[set_group[:reach]] + k
        digit = (set_local[:reach] // stride[entry]) % sizes[entry]
        where = entry_from[entry] + digit
        b, e = off_b[where], off_e[where]
        distance[:reach] += np.abs(b) + np.abs(e)
        own = first[:live] + k
        db, de = seen_b[own], seen_e[own]
        seen_d[:live] += np.abs(db) + np.abs(de)
        if k:
            mismatch[:reach] += np.abs(b - b0[:reach]) + np.abs(e - e0[:reach])
            seen_m[:live] += np.abs(db - first_b[:live]) + np.abs(de - first_e[:live])
        else:
            b0, e0, first_b, first_e = b, e, db, de
    off_shift = seen_m > tolerance + slack  # (off the lead's shift: not in step)
    keys = np.round((mismatch + distance) / slack[set_group])
    seen = np.round((seen_m + seen_d) / slack)
    near = np.bincount(set_group[keys <= seen[set_group]], minlength=groups)
    # each group's keys, in order, counted: sum over the keys of (sets at k) / (sets at k
    # or nearer), each group's sum summed alone as np.unique's counts are. (The keys are
    # whole numbers of at least 0: below 2^shift, a group's number shifted past them and
    # the key side by side are one integer that sorts as the pair does.)
    shift = _KEY_BITS - groups.bit_length()
    if 0 <= float(keys.min()) and float(keys.max()) < 2.0 ** shift:
        paired = np.sort((set_group << shift) | keys.astype(np.int64))
        fresh = np.flatnonzero(np.concatenate(([True], paired[1:] != paired[:-1])))
        key_group = paired[fresh] >> shift
    else:
        arranged = np.lexsort((keys, set_group))
        k_sorted, g_sorted = keys[arranged], set_group[arranged]
        fresh = np.flatnonzero(np.concatenate(([True], (k_sorted[1:] != k_sorted[:-1])
                                               | (g_sorted[1:] != g_sorted[:-1]))))
        key_group = g_sorted[fresh]
    counts = np.diff(np.concatenate((fresh, [total])))
    running = np.cumsum(counts)
    group_start = np.flatnonzero(np.concatenate(([True], key_group[1:] != key_group[:-1])))
    before = np.repeat(running[group_start] - counts[group_start],
                       np.diff(np.concatenate((group_start, [len(counts)]))))
    shares = counts / (running - before)
    # (one key: its share alone, 1; two: 1 + the second's, in any order; more: np.sum's)
    per_group = np.diff(np.concatenate((group_start, [len(counts)])))
    summed = np.ones(groups)
    two = np.flatnonzero(per_group == 2)
    summed[two] = shares[group_start[two]] + shares[group_start[two] + 1]
    for g in np.flatnonzero(per_group > 2).tolist():
        begin = int(group_start[g])
        summed[g] = np.sum(shares[begin:begin + int(per_group[g])])
    log10 = math.log10
    values = [math.inf if off else log10(near) + log10(share) for off, near, share in
              zip(off_shift.tolist(), np.maximum(near, 1).tolist(), summed.tolist())]
    out = [0.0] * groups
    for g, value in zip(order.tolist(), values):
        out[g] = value
    return out
