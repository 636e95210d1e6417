"""One string as timed codes, and the motif search within it (step 1 of the content mode)."""

from __future__ import annotations

import functools
from contextlib import nullcontext
import math
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..._foundation.engines import select, usable_cores
from ...errors import BoundReached
from ._alarm import alarm
from .conf import NO_BOUND
from .statistics import log10_binom_sf, log10_poisson_sf, scan_threshold

if TYPE_CHECKING:
    from ...budget import Budget
    from .conf import ContentConf


#: farthest column looked at beyond a damaged one while growing
_BRIDGE = 2


@dataclass(frozen=True)
class Timed:
    """One string as integer codes with start and end times."""

    codes: np.ndarray
    starts: np.ndarray
    ends: np.ndarray

    @classmethod
    def build(cls, symbols, durations, origin, alphabet: dict[str, int]) -> "Timed":
        """Encode ``symbols``; new symbols join ``alphabet`` in order of first appearance."""
        for sym in dict.fromkeys(symbols):  # distinct symbols, in order of first appearance
            alphabet.setdefault(sym, len(alphabet))
        codes = np.fromiter(map(alphabet.__getitem__, symbols), dtype=np.int64,
                            count=len(symbols))
        return cls.from_codes(codes, np.asarray(durations, dtype=np.float64), origin)

    @classmethod
    def from_codes(cls, codes: np.ndarray, durations: np.ndarray, origin: float) -> "Timed":
        """A string of integer ``codes`` whose segments last ``durations``, from ``origin``."""
        ends = origin + np.cumsum(durations)
        return cls(codes, ends - durations, ends)

    @functools.cached_property
    def middles(self) -> np.ndarray:
        """The middle time of each segment (read by every vote in a group's windows)."""
        return (self.starts + self.ends) / 2

    @functools.cached_property
    def symbol_counts(self) -> np.ndarray:
        """How often each code occurs (``np.bincount`` of the codes)."""
        return np.bincount(self.codes)

    @functools.cached_property
    def distinct(self) -> int:
        """How many distinct codes the string has."""
        return int(np.count_nonzero(self.symbol_counts))

    @functools.cached_property
    def match_rate(self) -> float:
        """The chance that two of its symbols drawn at random agree (sum of squared
        frequencies), the rate the scan threshold is set at."""
        return float(np.sum((self.symbol_counts / len(self.codes)) ** 2))

    def chance_rates(self, follow: float | None) -> tuple[float, float]:
        """``(q, r)``: the chance that a repeat's first symbol agrees with its copy's by chance
        (:attr:`match_rate`) and that each further one does (``follow``, the string's follow
        rate; ``q`` without one), which the weights of repeats in step multiply."""
        return self.match_rate, self.match_rate if follow is None else follow

    def intervals(self, copy_starts: np.ndarray, length: int) -> np.ndarray:
        """(k, 2) array: the time span of each copy of a motif of ``length`` symbols."""
        return np.column_stack((self.starts[copy_starts], self.ends[copy_starts + length - 1]))

    def copy_times(self, found) -> np.ndarray:
        """:meth:`intervals` of a repeat found in this string (a :class:`Motif` or a
        section: its copies' ``starts`` and its ``motif``)."""
        return self.intervals(found.starts, len(found.motif))


@dataclass(frozen=True)
class Motif:
    """A repeated pattern found in one string: its symbol codes, where its copies start, and
    how unlikely that many copies are by chance (``significance``: log10 of the chance, at
    most 0; lower is stronger)."""

    motif: np.ndarray
    starts: np.ndarray
    significance: float


# -- motif finding in one string ---------------------------------------------------
def match_scores(codes: np.ndarray, motif, clock: Budget = NO_BOUND) -> np.ndarray:
    """How many positions of ``motif`` the window starting at each index agrees with
    (``len(codes) - len(motif) + 1`` windows, at least one symbol long); ``clock`` read
    before each column (a pass over the string)."""
    width = len(codes) - len(motif) + 1
    score = np.zeros(width, dtype=np.int32)
    for offset, sym in enumerate(motif):
        clock.check()
        score += codes[offset:offset + width] == sym
    return score


def locate_copies(codes: np.ndarray, motif: np.ndarray, threshold: int,
                  clock: Budget = NO_BOUND) -> np.ndarray:
    """Non-overlapping windows agreeing with ``motif`` in >= threshold positions.

    Best agreement first, earlier first among equals; returned in position order.
    ``clock`` is read before each column of the scan.
    """
    n, length = len(codes), len(motif)
    width = n - length + 1
    if width <= 0:
        return np.zeros(0, dtype=np.int64)
    score = match_scores(codes, motif, clock)
    hits = np.flatnonzero(score >= threshold)
    if len(hits) == 0:
        return hits
    if np.all(score[hits] == length) and (len(hits) < 2 or np.min(np.diff(hits)) >= length):
        return hits  # exact, non-overlapping copies: nothing to choose
    # best first, earlier first among equals: level by level, a window is kept when it
    # overlaps no window kept at a higher level nor the one kept just before it
    levels = score[hits]
    chosen = np.zeros(0, dtype=np.int64)
    for level in range(int(levels.max()), threshold - 1, -1):
        here = hits[levels == level]
        if len(here) == 0:
            continue
        if len(chosen):
            at = np.searchsorted(chosen, here)
            right = chosen[np.minimum(at, len(chosen) - 1)]
            left = chosen[np.maximum(at - 1, 0)]
            free = ((at >= len(chosen)) | (right - here >= length)) \
                & ((at == 0) | (here - left >= length))
            here = here[free]
        if len(here) > 1 and np.min(np.diff(here)) < length:
            here = here[keep_apart(here, length)]
        chosen = np.sort(np.concatenate((chosen, here)))
    return chosen


def median_gap(starts: np.ndarray) -> int:
    """The median distance between consecutive copies (the lower middle one)."""
    gaps = np.sort(np.diff(starts))
    return int(gaps[(len(gaps) - 1) // 2])


def merge_copies(old: np.ndarray, new: np.ndarray, length: int) -> np.ndarray:
    """Copies from both lists, earlier first, dropping any that overlaps one already kept.

    Copies located while the motif grew keep their place even when the longer
    motif no longer passes the scan (a damaged copy still shows the pattern).
    """
    both = np.sort(np.concatenate((old, new)))
    if len(both) > 1:
        both = both[np.concatenate(([True], both[1:] != both[:-1]))]
    if len(both) < 2 or np.min(np.diff(both)) >= length:
        return both
    return both[keep_apart(both, length)]


def keep_apart(positions: np.ndarray, length: int) -> list[int]:
    """Indices of the sorted ``positions`` kept left to right, each ``length`` after the last."""
    following = np.searchsorted(positions, positions + length).tolist()
    kept, at, end = [], 0, len(positions)
    while at < end:
        kept.append(at)
        at = following[at]
    return kept


#: What :func:`grow` gets from an engine that leaves the motif to numpy's loop.
_UNDECIDED = object()


@dataclass(frozen=True)
class Search:
    """The motif search by one engine, as a table of the same functions (the same motifs).

    ``find_all(strings, conf, clock)``: :func:`find_motif` of every string, ``clock`` read
    between strings (or runs of them);
    ``grow(codes, motif, starts, match_rate, distinct, conf, seed_only)``: one motif grown,
    or ``_UNDECIDED`` to leave it to numpy's loop. :func:`search` picks the table.
    """

    find_all: Callable
    grow: Callable


def search(conf: ContentConf) -> Search:
    """The table of the engine ``conf.engine`` chooses (numba's only when it runs)."""
    return select(conf.engine, numpy=NUMPY_SEARCH, numba=lambda: COMPILED_SEARCH)


def find_motifs(strings: list[np.ndarray], conf: ContentConf, clock: Budget = NO_BOUND
                ) -> list[Motif | None]:
    """:func:`find_motif` of every string, by the engine ``conf.engine`` chooses.

    The compiled engine searches every string in one call; a string where it meets a chance
    level too close to a boundary to decide in its own floats (see
    :mod:`psgs.induce.pal._motifs_jit`) is searched here again. ``clock`` raises
    :class:`~psgs.errors.BoundReached` past its deadline, also inside a string's seeds
    (numpy: before each growth step and each column of a scan; compiled: the call's loops
    read an :func:`~psgs.induce.pal._alarm.alarm`), so that a seed grown in a long string
    is no unit the bound waits for.
    """
    return search(conf).find_all(strings, conf, clock)


def _find_each(strings: list[np.ndarray], conf: ContentConf, clock: Budget = NO_BOUND
               ) -> list[Motif | None]:
    """numpy's engine: each string searched on its own."""
    return [find_motif(codes, conf, clock) for codes in strings]


def _find_all_compiled(strings: list[np.ndarray], conf: ContentConf, clock: Budget = NO_BOUND
                       ) -> list[Motif | None]:
    """The compiled engine: every string in one call (see :func:`find_motifs`), stopped at
    ``clock``'s deadline inside the call (:class:`~psgs.errors.BoundReached`): its loops read
    an alarm between strings and seeds and at each growth step and column, since how long a
    string takes depends on what repeats in it, not only on its length (a seed grown in
    2^19 - 1 symbols of a repeating pattern: 1.9 s, a pass over the string for each column of
    each growth step). A flag never set changes nothing."""
    clock.check()
    from . import _motifs_jit as jit

    count = len(strings)
    bounds = np.zeros(count + 1, dtype=np.int64)
    np.cumsum([len(c) for c in strings], out=bounds[1:])
    flat = np.concatenate(strings) if count else np.zeros(0, dtype=np.int64)
    sizes, distinct, rates = _symbol_statistics(flat, bounds, conf.min_copies)
    stats = np.zeros((4, count))  # match rate, its log and log1p(-), log10 distinct
    for i in np.flatnonzero(distinct).tolist():
        rate = float(rates[i])
        stats[:, i] = (rate, math.log(rate), math.log1p(-rate) if rate < 1 else -math.inf,
                       math.log10(max(int(distinct[i]), 2)))
    with alarm(clock) as stop:
        found = _search_all(jit, flat.astype(np.int64, copy=False), bounds, sizes, stats, conf,
                            stop)
    status, lengths, copies, thresholds, motifs, starts = found
    if np.any(status == jit.STOPPED):
        raise BoundReached("max_seconds")
    out: list[Motif | None] = []
    for i, (state, length, k, threshold, start) in enumerate(zip(
            status.tolist(), lengths.tolist(), copies.tolist(), thresholds.tolist(),
            bounds[:-1].tolist())):
        if state == jit.UNCERTAIN:
            out.append(find_motif(strings[i], conf, clock))
        elif state == jit.FOUND:
            out.append(Motif(motifs[i, :length].copy(), starts[start:start + k].copy(),
                             significance(len(strings[i]), length, threshold, k,
                                          float(stats[0, i]), int(distinct[i]))))
        else:
            out.append(None)
    return out


#: from this many symbols on, the compiled search runs in two threads (two runs of strings
#: of about equal size; each string's search is the same wherever it runs); below, one
_THREADED_SYMBOLS = 1 << 18


def _search_all(jit, flat, bounds, sizes, stats, conf, stop):
    """The compiled search of every string, in one thread or two (the same arrays out);
    ``stop``: the flag its loops read (see :mod:`psgs.induce.pal._motifs_jit`)."""
    count = len(bounds) - 1
    out = (np.zeros(count, dtype=np.int64), np.zeros(count, dtype=np.int64),
           np.zeros(count, dtype=np.int64), np.zeros(count, dtype=np.int64),
           np.zeros((count, conf.max_pattern), dtype=np.int64),
           np.zeros(len(flat), dtype=np.int64))
    args = (sizes, stats[0], stats[1], stats[2], stats[3], conf.min_copies, conf.seeds,
            float(conf.conserve), float(conf.match_fraction), float(conf.scan_alpha),
            conf.max_pattern, stop) + out
    middle = int(np.searchsorted(bounds, len(flat) / 2))
    if len(flat) < _THREADED_SYMBOLS or usable_cores() < 2 or not 0 < middle < count:
        jit.search_strings(flat, bounds, 0, count, *args)
        return out
    with ThreadPoolExecutor(2) as pool:  # the kernel releases the GIL (nogil)
        runs = [pool.submit(jit.search_strings, flat, bounds, a, b, *args)
                for a, b in ((0, middle), (middle, count))]
        for run in runs:
            run.result()
    return out


def _symbol_statistics(flat: np.ndarray, bounds: np.ndarray, min_copies: int
                       ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per string, what :func:`find_motif` reads off its symbol counts: the alphabet size
    (largest code + 1), the distinct symbols and the match rate (the sum of squared symbol
    shares); zeros for a string too short to search.

    The match rates are summed as numpy sums each string's shares, row by row of one
    array per (length, size) (a sum along a row is the sum of the row alone, in the same
    pairwise order); tests/induce/test_pal_engines.py checks it against the string's own.
    """
    count = len(bounds) - 1
    lengths = np.diff(bounds)
    sizes = np.zeros(count, dtype=np.int64)
    distinct = np.zeros(count, dtype=np.int64)
    rates = np.zeros(count)
    searched = np.flatnonzero(lengths >= 2 * min_copies)
    if len(searched) == 0:
        return sizes, distinct, rates
    width = int(flat.max()) + 1
    if count * width > 4 * len(flat) + 4096:  # a long alphabet: string by string
        for i in searched.tolist():
            codes = flat[bounds[i]:bounds[i + 1]]
            size = int(codes.max()) + 1
            freq = np.bincount(codes, minlength=size) / len(codes)
            sizes[i], distinct[i] = size, np.count_nonzero(freq)
            rates[i] = np.sum(freq ** 2)
        return sizes, distinct, rates
    from ._counting_jit import symbol_counts  # (only the compiled engine comes here)

    counts = symbol_counts(flat, bounds, width)
    sizes[searched] = width - np.argmax(counts[searched, ::-1] > 0, axis=1)
    distinct[searched] = np.count_nonzero(counts[searched], axis=1)
    keys = lengths[searched] * (width + 1) + sizes[searched]
    for key in np.unique(keys).tolist():
        rows = searched[keys == key]
        n, size = int(lengths[rows[0]]), int(sizes[rows[0]])
        rates[rows] = np.sum((counts[rows, :size] / n) ** 2, axis=1)
    return sizes, distinct, rates


def find_motif(codes: np.ndarray, conf: ContentConf, clock: Budget = NO_BOUND
               ) -> Motif | None:
    """The best-supported repeated motif of one string, or None.

    Up to ``conf.seeds`` of the most frequent digrams are grown in turn (a
    burst of noise can stop one seed early); the most significant motif wins,
    the earlier seed among equals. ``clock`` is read before each seed and inside each seed's
    growth too (see :func:`grow`), and between the passes over the string before its first
    seed (its symbols and digrams counted).
    """
    n = len(codes)
    if n < 2 * conf.min_copies:
        return None
    size = int(codes.max()) + 1
    freq = np.bincount(codes, minlength=size) / n
    distinct = int(np.count_nonzero(freq))
    match_rate = float(np.sum(freq ** 2))
    clock.check()
    keys = codes[:-1] * size + codes[1:]
    uniq, first, counts = _digram_counts(keys, size * size, clock)
    # only a digram seen min_copies times is a seed: the others are left out of the sort
    # (their order, after every seed, is never read)
    seeded = np.flatnonzero(counts >= conf.min_copies)
    uniq, first, counts = uniq[seeded], first[seeded], counts[seeded]
    clock.check()
    order = np.lexsort((first, -counts))
    best: Motif | None = None
    covered: set[int] = set()
    tried = 0
    for index in order.tolist():
        if tried >= conf.seeds or counts[index] < conf.min_copies:
            break
        if int(uniq[index]) in covered:
            continue  # already inside a motif grown from an earlier seed
        tried += 1
        clock.check()
        seed = np.array([uniq[index] // size, uniq[index] % size], dtype=np.int64)
        found = grow(codes, seed, np.flatnonzero(keys == uniq[index]), match_rate, distinct,
                     conf, seed_only=True, clock=clock)
        if found is None:
            continue
        covered.update((found.motif[:-1] * size + found.motif[1:]).tolist())
        if best is None or found.significance < best.significance:
            best = found
    return best


def _digram_counts(keys: np.ndarray, bins: int, clock: Budget = NO_BOUND
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The distinct digram keys (``0 <= key < bins``), where each first occurs, and how often
    (as ``np.unique``); ``clock`` read between the passes over them.

    Examples
    --------
    >>> _digram_counts(np.array([5, 2, 5, 7, 2, 5]), 10**12)  # sorted: a large alphabet
    (array([2, 5, 7]), array([1, 0, 3]), array([2, 3, 1]))
    >>> _digram_counts(np.array([5, 2, 5, 7, 2, 5]), 8)  # counted
    (array([2, 5, 7]), array([1, 0, 3]), array([2, 3, 1]))
    """
    m = len(keys)
    if bins > 4 * m + 4096:  # a large alphabet: sorting is cheaper than counting
        if bins * max(m, 1) > 1 << 62:  # no room for the position beside the key
            return np.unique(keys, return_index=True, return_counts=True)
        # each key with its position below it, sorted: the keys in order, each key's
        # positions in position order (np.unique's stable sort of the keys alone is some
        # ten times slower, and one call)
        both = np.sort(keys.astype(np.int64, copy=False) * m + np.arange(m))
        clock.check()
        ordered = both // m
        opens = np.flatnonzero(np.concatenate(([True], ordered[1:] != ordered[:-1])))
        clock.check()
        return ordered[opens], both[opens] % m, np.diff(np.append(opens, m))
    counts = np.bincount(keys, minlength=bins)
    uniq = np.flatnonzero(counts)
    clock.check()
    first = np.full(bins, m, dtype=np.int64)
    np.minimum.at(first, keys, np.arange(m))
    return uniq, first[uniq], counts[uniq]


def grow(codes: np.ndarray, motif: np.ndarray, starts: np.ndarray, match_rate: float,
          distinct: int, conf: ContentConf, seed_only: bool = False,
          clock: Budget = NO_BOUND, stop: np.ndarray | None = None) -> Motif | None:
    """Grow ``motif`` one conserved column at a time from its copies at ``starts``.

    ``seed_only``: ``motif`` is a digram and ``starts`` all its occurrences.
    With ``conf.engine`` compiled, the compiled loop grows it (the same motif). ``clock`` is
    read before each growth step and each column of a scan, and raises
    :class:`~psgs.errors.BoundReached` past its deadline; the compiled loop reads ``stop``
    instead, an :func:`~psgs.induce.pal._alarm.alarm` of ``clock`` (one is set for the call
    when it is None and ``clock`` has a deadline).
    """
    n = len(codes)
    if n and match_rate > 0:
        decided = search(conf).grow(codes, motif, starts, match_rate, distinct, conf, seed_only,
                                    clock, stop)
        if decided is not _UNDECIDED:
            return decided
    size = int(codes.max()) + 1
    grown_from = motif
    while len(motif) < conf.max_pattern:
        clock.check()
        length = len(motif)
        spacing = median_gap(starts) if len(starts) > 1 else n
        if length + 1 > spacing:
            break
        choice = None
        for side in ("right", "left"):
            # a column that noise damaged in many copies can be bridged when the
            # column beyond it is conserved (its plurality still held by min_copies)
            added: list[int] = []
            for d in range(1, min(_BRIDGE, spacing - length, conf.max_pattern - length)
                           + 1):
                pos = starts + length + d - 1 if side == "right" else starts - d
                pos = pos[(pos >= 0) & (pos < n)]
                if len(pos) < conf.min_copies:
                    break
                column = np.bincount(codes[pos], minlength=size)
                sym = int(np.argmax(column))
                k = int(column[sym])
                if k < conf.min_copies:
                    break
                added.append(sym)
                if k >= conf.conserve * len(pos):
                    rank = (d, -k / len(pos))
                    if choice is None or rank < choice[0]:
                        choice = (rank, side, added)
                    break
        if choice is None:
            break
        (d, _), side, added = choice
        if side == "right":
            grown, kept = np.concatenate((motif, added)), starts
        else:
            grown, kept = np.concatenate((added[::-1], motif)), starts - d
        grown = grown.astype(np.int64)
        kept = kept[(kept >= 0) & (kept + len(grown) <= n)]
        threshold = scan_threshold(len(grown), n - len(grown) + 1, match_rate, conf)
        found = merge_copies(kept, locate_copies(codes, grown, threshold, clock), len(grown))
        if len(found) < conf.min_copies:
            break
        motif, starts = grown, found

    length = len(motif)
    threshold = scan_threshold(length, n - length + 1, match_rate, conf)
    if len(starts) > 1 and median_gap(starts) == length and starts[0] % length:
        # copies tile the string: put a copy boundary where the string starts
        shift = int(starts[0] % length)
        rotated = np.roll(motif, shift)
        found = locate_copies(codes, rotated, threshold, clock)
        if len(found) >= len(starts):
            motif, starts = rotated, found
    if not (seed_only and len(motif) == 2 and motif[0] != motif[1] and threshold >= 2
            and motif is grown_from):
        # (a digram that did not grow: its exact occurrences are ``starts`` already)
        starts = merge_copies(starts, locate_copies(codes, motif, threshold, clock), length)
    if len(starts) < conf.min_copies:
        return None
    return Motif(motif, starts, significance(n, length, threshold, len(starts), match_rate,
                                             distinct))


def significance(n: int, length: int, threshold: int, copies: int, match_rate: float,
                 distinct: int) -> float:
    """log10 of the chance of ``copies`` copies of a motif of ``length`` symbols (at most 0).

    The expected chance copies of any motif of that length among a string's
    ``distinct`` symbols (each window matching ``threshold`` positions or more,
    a position by chance with probability ``match_rate``), and the Poisson tail
    of that many copies. Both engines call this, so that motifs are the same to the bit.
    """
    lam = (n - length + 1) * 10 ** log10_binom_sf(threshold, length, match_rate)
    value = length * math.log10(max(distinct, 2)) + log10_poisson_sf(copies, lam)
    return min(value, 0.0)


def _numpy_leaves_it(*_args) -> object:
    """numpy's engine grows every motif in :func:`grow`'s own loop."""
    return _UNDECIDED


def _grow_compiled(codes: np.ndarray, motif, starts, match_rate: float, distinct: int,
                   conf: ContentConf, seed_only: bool, clock: Budget = NO_BOUND,
                   stop: np.ndarray | None = None):
    """The compiled loop's motif, None, or ``_UNDECIDED`` (a chance level too close to call
    in the compiled floats: numpy's loop decides); stopped when ``stop`` is set (without
    one, an alarm at ``clock``'s deadline)."""
    from . import _motifs_jit as jit

    n = len(codes)
    motif = np.asarray(motif, dtype=np.int64)
    size = int(codes.max()) + 1
    # (the scratch the compiled search keeps per string: its thresholds by length, a column)
    thresholds = np.full(max(conf.max_pattern, len(motif)) + 1, -2, dtype=np.int64)
    with (alarm(clock) if stop is None else nullcontext(stop)) as stop:
        state, grown, found, threshold = jit.grow_motif(
            codes.astype(np.int64, copy=False), motif, np.asarray(starts, dtype=np.int64),
            size, thresholds, match_rate, math.log(match_rate),
            math.log1p(-match_rate) if match_rate < 1 else -math.inf, conf.min_copies,
            float(conf.conserve), float(conf.match_fraction), float(conf.scan_alpha),
            conf.max_pattern, np.zeros(size, dtype=np.int64), bool(seed_only), stop)
    if state == jit.STOPPED:
        raise BoundReached("max_seconds")
    if state == jit.FOUND:
        return Motif(grown, found, significance(n, len(grown), threshold, len(found),
                                                match_rate, distinct))
    if state == jit.NONE:
        return None
    return _UNDECIDED


#: The two engines' tables (numba's compiled module is imported by its functions, on use).
NUMPY_SEARCH = Search(find_all=_find_each, grow=_numpy_leaves_it)
COMPILED_SEARCH = Search(find_all=_find_all_compiled, grow=_grow_compiled)
