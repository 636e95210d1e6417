"""The maximal runs of agreement of a string with itself at every shift of a range.

:func:`~psgs.induce.pal.in_step.read_at` reads a string at two lead copies'
times: every stretch where the symbols at ``p`` and ``p + shift`` agree, for
every shift between the segments under the first copy and those under the
second, and every position ``p`` within reach of the first copy. A
:class:`Frame` holds that range; :func:`grid_runs` finds every run, the
shifts as the rows of one array; :func:`long_runs` only those of ``floor``
symbols or more, from the pairs of equal windows of ``floor`` symbols, which
on long copies is far less work than the grid (most shifts hold no long run).
Both give runs in the same order; :func:`candidates` turns runs into the
windows ``read_at`` weighs, in the order that breaks ties among them.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .motifs import Timed
from .pairing import _pairs_with
from .sections import _window_hashes

__all__: list[str] = []  # private: in_step.py is the caller

#: the grid is filled this many cells at a time, at most
_BLOCK_CELLS = 1 << 22
#: at most this many pairs of equal windows are followed (else the grid)
_MAX_PAIRS = 1 << 20
#: the runs found are checked symbol by symbol this many symbols at a time, at most
_CHECK_SYMBOLS = 1 << 22


@dataclass(frozen=True)
class Frame:
    """What :func:`~psgs.induce.pal.in_step.read_at` looks at: the string, the lead's
    copies (their ``[[start, end], [start, end]]`` times), the indices of the segments
    under each, how far past them to look (``reach`` segments), the shifts
    ``low..top`` and the positions ``lo..lo + width``."""

    string: Timed
    lead: np.ndarray
    first: np.ndarray
    second: np.ndarray
    reach: int
    low: int
    top: int
    lo: int
    width: int

    @property
    def rows(self) -> int:
        """How many shifts the grid fills at a time (a long string's block stays small);
        the candidates' order, which breaks ties, is the blocks'."""
        return max(1, _BLOCK_CELLS // (self.width + 2))

    def his(self, shifts: np.ndarray) -> np.ndarray:
        """Per shift, the end of the positions looked at."""
        return np.minimum(len(self.string.codes) - shifts, int(self.first[-1]) + self.reach + 1)


def grid_runs(frame: Frame) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every shift's maximal runs of agreement (``begin``, ``end``, ``shift``), shifts as the
    rows of one array (a run is a row's stretch of True), in the order of the shifts and
    then of the runs."""
    codes, lo, width = frame.string.codes, frame.lo, frame.width
    n = len(codes)
    position = lo + np.arange(width)
    parts = []
    for block in range(frame.low, frame.top + 1, frame.rows):
        shifts = np.arange(block, min(frame.top, block + frame.rows - 1) + 1)
        his = frame.his(shifts)
        inside = position[None, :] < his[:, None]
        other = np.minimum(position[None, :] + shifts[:, None], n - 1)
        grid = np.zeros((len(shifts), width + 2), dtype=np.int8)
        grid[:, 1:-1] = inside & (codes[position][None, :] == codes[other])
        steps = np.diff(grid, axis=1)
        row, begin = np.nonzero(steps == 1)
        end = np.nonzero(steps == -1)[1] + lo
        parts.append((begin + lo, end, shifts[row]))
    return tuple(np.concatenate([p[k] for p in parts]) for k in range(3))


def long_runs(frame: Frame, floor: int
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """The maximal runs of agreement of ``floor`` symbols or more that :func:`grid_runs`
    finds, in its order, from the pairs of equal windows of ``floor`` symbols; None when
    those pairs are too many or a hash collision parts a run from its windows.

    Examples
    --------
    >>> codes = np.array([7, 0, 1, 2, 3, 4, 8, 0, 1, 2, 3, 4, 9, 5, 6])
    >>> string = Timed.from_codes(codes, np.ones(15), 0.0)
    >>> frame = Frame(string, np.array([[1.0, 6.0], [7.0, 12.0]]), np.arange(1, 6),
    ...               np.arange(7, 12), 10, 2, 10, 0, 13)
    >>> [x.tolist() for x in long_runs(frame, 4)]  # 0 1 2 3 4 again 6 later
    [[1], [6], [6]]
    >>> begin, end, shift = grid_runs(frame)
    >>> [(b, e, s) for b, e, s in zip(begin.tolist(), end.tolist(), shift.tolist()) if e - b >= 4]
    [(1, 6, 6)]
    """
    codes, lo, low, top = frame.string.codes, frame.lo, frame.low, frame.top
    n = len(codes)
    last = min(n - low, int(frame.first[-1]) + frame.reach + 1)  # (the widest row's end)
    stop = min(n, last + top)
    if stop - lo < floor:
        return (np.zeros(0, np.int64),) * 3
    hashes = _window_hashes(codes[lo:stop], floor)
    order = np.argsort(hashes, kind="stable")  # (positions ascending within a hash)
    ordered = hashes[order]
    begins = np.flatnonzero(np.concatenate(([True], ordered[1:] != ordered[:-1])))
    ends_ = np.concatenate((begins[1:], [len(ordered)]))
    group_end = np.repeat(ends_, ends_ - begins)
    later = group_end - np.arange(len(order)) - 1  # the windows after each in its group
    if int(later.sum()) > _MAX_PAIRS:
        return None
    left = np.repeat(np.arange(len(order)), later)
    right = _ranges(np.arange(len(order)) + 1, later)
    p, other = order[left] + lo, order[right] + lo
    shift = other - p
    # a window pair lies on the grid when its shift is looked at and both its windows lie
    # inside the positions looked at for that shift
    keep = (shift >= low) & (shift <= top)
    p, shift = p[keep], shift[keep]
    keep = p + floor <= frame.his(shift)
    p, shift = p[keep], shift[keep]
    if not len(p):
        return (np.zeros(0, np.int64),) * 3
    arranged = np.lexsort((p, shift))
    p, shift = p[arranged], shift[arranged]
    fresh = np.concatenate(([True], (shift[1:] != shift[:-1]) | (p[1:] != p[:-1] + 1)))
    starts_ = np.flatnonzero(fresh)
    begin = p[starts_]
    end = p[np.concatenate((starts_[1:], [len(p)])) - 1] + floor
    shift = shift[starts_]
    # every run checked symbol by symbol (a window's hash stands for its symbols), a batch
    # of runs at a time: the runs' symbols together may be ``floor`` times the pairs
    sizes = end - begin
    reach = np.cumsum(sizes)
    done = 0
    while done < len(sizes):
        upto = max(done + 1, int(np.searchsorted(reach, reach[done] - sizes[done] + _CHECK_SYMBOLS,
                                                 side="right")))
        part = sizes[done:upto]
        at = _ranges(begin[done:upto], part)
        if not np.array_equal(codes[at], codes[at + np.repeat(shift[done:upto], part)]):
            return None
        done = upto
    return begin, end, shift


def candidates(frame: Frame, begin: np.ndarray, end: np.ndarray, shift: np.ndarray):
    """The candidates of the runs ``(begin, end, shift)`` (in the grid's order): each
    window of a run and the run's part under the lead's copies that pair with both
    copies, as ``(lengths, starts, shifts, clipped)`` lists in the grid's order."""
    string, first, second, lo = frame.string, frame.first, frame.second, frame.lo
    starts, ends = string.starts, string.ends
    n = len(string.codes)
    (a1, b1), (a2, b2) = frame.lead.tolist()
    hi = frame.his(shift)
    # (cut by the range looked at: not maximal)
    keep = (end - begin >= 2) & ~((begin == lo) & (lo > 0)) & ~((end == hi) & (hi < n - shift))
    begin, end, shift = begin[keep], end[keep], shift[keep]
    # a run longer than the shift holds copies of the shift's length that do not
    # overlap (copies that touch, and chance agreement after the second)
    length = np.minimum(end - begin, shift)
    count = end - length - begin + 1
    at = _ranges(begin, count)
    # and the part of each run under the lead's copies: a run may reach far past them
    # (symbols around the copies agreeing by chance) or be one block played over and
    # over, where the lead's copies mark a section of it (not maximal: no left end)
    cut_at = np.maximum(np.maximum(begin, first[0]), second[0] - shift)
    cut_end = np.minimum(np.minimum(end, first[-1] + 1), second[-1] + 1 - shift)
    cut_end = np.minimum(cut_end, cut_at + shift)
    cut = ((cut_at > begin) | (cut_end < end)) & (cut_end - cut_at >= 2)
    cut_at, cut_shift = cut_at[cut], shift[cut]
    cut_length = cut_end[cut] - cut_at
    cut_pairs = (_pairs_with(starts[cut_at], ends[cut_at + cut_length - 1], a1, b1)
                 & _pairs_with(starts[cut_at + cut_shift],
                               ends[cut_at + cut_length - 1 + cut_shift], a2, b2))
    length, whole_shift = np.repeat(length, count), np.repeat(shift, count)
    pairs = (_pairs_with(starts[at], ends[at + length - 1], a1, b1)
             & _pairs_with(starts[at + whole_shift], ends[at + length - 1 + whole_shift],
                           a2, b2))
    lengths = np.concatenate((length[pairs], cut_length[cut_pairs]))
    ats = np.concatenate((at[pairs], cut_at[cut_pairs]))
    shifts = np.concatenate((whole_shift[pairs], cut_shift[cut_pairs]))
    clipped = np.concatenate((np.zeros(int(pairs.sum()), bool), np.ones(int(cut_pairs.sum()),
                                                                          bool)))
    # the grid's order: block by block of shifts, a block's whole windows before its parts
    block = (shifts - frame.low) // frame.rows
    order = np.argsort(2 * block + clipped, kind="stable")
    return (lengths[order].tolist(), ats[order].tolist(), shifts[order].tolist(),
            clipped[order].tolist())


def _ranges(begins: np.ndarray, sizes: np.ndarray) -> np.ndarray:
    """``begins[k], begins[k] + 1, ..., begins[k] + sizes[k] - 1`` for every ``k``, in order.

    Examples
    --------
    >>> _ranges(np.array([3, 10]), np.array([2, 3])).tolist()
    [3, 4, 10, 11, 12]
    """
    total = int(sizes.sum())
    return np.repeat(begins, sizes) + np.arange(total) - np.repeat(np.cumsum(sizes) - sizes, sizes)
