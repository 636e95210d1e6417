"""An actiongram as PAL reads it: each string as integer codes with start and end times."""

from __future__ import annotations

from itertools import chain

import numpy as np

from ...actiongram import Actiongram
from .motifs import Timed

__all__: list[str] = []  # private: PAL.induce is the interface (learner re-exports encode)


def encode(actiongram: Actiongram) -> tuple[list[Timed], list[str]]:
    """Each string as integer codes over one alphabet (symbols in order of first appearance)."""
    # whole-actiongram passes: per-symbol work is the floor of PAL's cost
    lengths = [len(syms) for syms in actiongram.symbols]
    total = sum(lengths)
    codes, alphabet = _codes(actiongram.symbols, total)
    durations = np.fromiter(chain.from_iterable(actiongram.segment_durations),
                            dtype=np.float64, count=total)
    bounds = np.cumsum([0] + lengths).tolist()
    starts, ends = _times(durations, bounds, actiongram.origins)
    strings = [Timed(codes[a:b], starts[a:b], ends[a:b])
               for a, b in zip(bounds[:-1], bounds[1:])]
    return strings, alphabet


def _times(durations: np.ndarray, bounds: list[int], origins) -> tuple[np.ndarray, np.ndarray]:
    """Every segment's start and end time, as :meth:`Timed.from_codes` gives them string by
    string: strings of one length are summed as the rows of one array (a running sum along
    each row, the same additions in the same order)."""
    ends = np.empty(len(durations))
    by_length: dict[int, list[int]] = {}
    for i, (a, b) in enumerate(zip(bounds[:-1], bounds[1:])):
        by_length.setdefault(b - a, []).append(i)
    for length, rows in by_length.items():
        if length == 0:
            continue
        origin = np.asarray([float(origins[i]) for i in rows])[:, None]
        if len(by_length) == 1:  # one length: the strings are the rows as they lie
            block = ends.reshape(len(rows), length)
            np.cumsum(durations.reshape(len(rows), length), axis=1, out=block)
            block += origin  # (x + origin is origin + x: IEEE addition commutes)
            break
        index = np.asarray([bounds[i] for i in rows])[:, None] + np.arange(length)
        ends[index] = origin + np.cumsum(durations[index], axis=1)
    return ends - durations, ends


def _codes(symbols: tuple[tuple[str, ...], ...], total: int) -> tuple[np.ndarray, list[str]]:
    """Integer codes of every string's symbols, one array, numbered in order of first
    appearance."""
    if total == 0:
        return np.zeros(0, dtype=np.int64), []
    joined = "".join(map("".join, symbols))
    if len(joined) == total:  # symbols are never empty: each is one character
        # their code points, read in C, then renumbered
        points = np.frombuffer(joined.encode("utf-32-le"), dtype=np.uint32)
        if int(points.max()) < 1 << 16:  # a table lookup is quicker than a search
            present = np.bincount(points)
            ordinals = np.flatnonzero(present)
            if len(ordinals) <= 256:  # first appearances by a few scans in C; one lookup
                symbols_sorted = [chr(o) for o in ordinals.tolist()]
                first = [joined.find(sym) for sym in symbols_sorted]
                order = sorted(range(len(first)), key=first.__getitem__)
                table = np.zeros(len(present), dtype=np.int64)
                table[ordinals[order]] = np.arange(len(order))
                return table[points], [symbols_sorted[k] for k in order]
            table = np.zeros(len(present), dtype=np.int64)
            table[ordinals] = np.arange(len(ordinals))
            index = table[points]
        else:
            ordinals = np.unique(points)
            index = np.searchsorted(ordinals, points)
        symbols_sorted = [chr(o) for o in ordinals.tolist()]
    else:
        flat = list(chain.from_iterable(symbols))
        symbols_sorted = sorted(set(flat))
        lookup = {sym: k for k, sym in enumerate(symbols_sorted)}
        index = np.fromiter(map(lookup.__getitem__, flat), dtype=np.int64, count=total)
    first = np.full(len(symbols_sorted), total, dtype=np.int64)
    np.minimum.at(first, index, np.arange(total))
    order = np.argsort(first, kind="stable")
    rank = np.empty(len(symbols_sorted), dtype=np.int64)
    rank[order] = np.arange(len(symbols_sorted))
    return rank[index], [symbols_sorted[k] for k in order.tolist()]
