"""Which strings outside a group could join it: the vote's counts for many strings at once.

Every string outside a group is read in the group's windows to see whether
it repeats there (:func:`~psgs.induce.pal.pooling.repeats_in_windows` on its
:func:`~psgs.induce.pal.pooling.vote`). With a thousand strings that is a
thousand votes, nearly all of random strings that cannot pass: here the
counts the test starts from (the common copy length, how many copies have
it, each column's plurality count) are taken for all of them in one pass,
and only the strings that pass that first part are voted on in full. The
answer is the same; only the work is less.
"""

from __future__ import annotations

import math

import numpy as np

from .motifs import Timed
from .pooling import copies_in

__all__: list[str] = []  # private: content.py is the caller


def may_join(strings: list[Timed], rows: list[int], windows: np.ndarray, copies_needed: int,
             conserve: float) -> list[int]:
    """The ``rows`` whose vote in ``windows`` passes the counting part of the joining test.

    That part: at least ``copies_needed`` copies of the common length (two
    symbols or more), and at least half of the columns (two or more) whose
    plurality holds a share ``conserve`` of them. A row left out would fail
    :func:`~psgs.induce.pal.pooling.repeats_in_windows`; a row kept may still.
    """
    kept: list[int] = []
    reads: list[np.ndarray] = []   # per row still in question: its full copies' codes
    for i in rows:
        found = copies_in(strings[i], windows)  # the copies vote() reads
        if found is None:
            continue
        lo, _, _, full, length = found
        if len(full) < copies_needed or length < 2:
            continue
        reads.append(strings[i].codes[lo[full][:, None] + np.arange(length)])
        kept.append(i)
    if not kept:
        return []
    # every kept row's columns side by side: the plurality count of each (row, column)
    size = int(max(int(r.max()) for r in reads)) + 1
    widths = np.array([r.shape[1] for r in reads])
    first_column = np.concatenate(([0], np.cumsum(widths)[:-1]))
    keys = np.concatenate([((first_column[k] + np.arange(r.shape[1])) * size + r).ravel()
                           for k, r in enumerate(reads)])
    tally = np.bincount(keys, minlength=int(widths.sum()) * size).reshape(-1, size)
    top = tally.max(axis=1)
    out = []
    for k, i in enumerate(kept):
        copies, length = reads[k].shape
        shares = top[first_column[k]:first_column[k] + length] / copies  # as _plurality
        if np.count_nonzero(shares >= conserve) >= max(2, math.ceil(length / 2)):
            out.append(i)
    return out
