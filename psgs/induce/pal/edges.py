"""Which end columns of a group's voted patterns are conserved (step 6, and step 5's widening).

A column's conservation is pooled in time over the group's members: the mean
plurality share of the members' columns at that time and, where that mean is
low, whether the members' agreement there, counted together, is still beyond
chance (:func:`pooled_log10_chance`).
"""

from __future__ import annotations

import math

import numpy as np

from .pooling import Vote
from .statistics import log10_binom_sf

__all__: list[str] = []  # private: content.py and widening.py are the callers


def trim(votes: dict[int, Vote], edge_share: float,
         alpha: float = 0.0) -> dict[int, tuple[int, int]]:
    """Per member, the range of columns kept: end columns not conserved across the group go.

    A column's conservation is pooled in time: the mean, over the members, of
    the plurality share of the member's column at that time offset (0 where
    a member has no column). So one string's chance agreement at a column the
    others do not share is trimmed, and a column damaged in one string but
    conserved in the others is kept. With ``alpha`` > 0, a column at or below
    ``edge_share`` is still kept when the members' agreement there, counted
    together, is beyond chance at level ``alpha`` (:func:`pooled_log10_chance`,
    a member without a column there agreeing in none of its copies). Heavy
    noise lowers every member's share at once; a column the members show
    together far more often than chance is not cut for it.
    """
    # every member's columns side by side (padding never holds a time); column times
    # rise along a pattern (medians of rising offsets), so the first column ending after
    # t is the only one that can hold it first
    members = list(votes.values())
    width = max(len(v.pattern) for v in members)
    starts = np.full((len(members), width), np.inf)
    ends = np.full((len(members), width), np.inf)
    shares = np.zeros((len(members), width))
    for row, v in enumerate(members):
        starts[row, :len(v.pattern)] = v.column_start
        ends[row, :len(v.pattern)] = v.column_end
        shares[row, :len(v.pattern)] = v.shares
    rows = np.arange(len(members))
    log10_alpha = math.log10(alpha) if alpha > 0 else -math.inf
    chance = _Pooled(members) if alpha > 0 else None
    seen: dict[float, bool] = {}  # synchronous members test the same times

    def conserved(t: float) -> bool:
        if t in seen:
            return seen[t]
        count = np.count_nonzero(ends <= t, axis=1)
        column = np.minimum(count, width - 1)
        held = (count < width) & (starts[rows, column] <= t)
        keep = sum(shares[rows[held], column[held]].tolist()) / len(members) > edge_share
        if not keep and chance is not None:
            keep = chance.log10(rows[held], column[held]) <= log10_alpha
        seen[t] = keep
        return keep

    out = {}
    for i, v in votes.items():
        middles = ((v.column_start + v.column_end) / 2).tolist()
        first, last = 0, len(v.pattern)
        while first < last and not conserved(middles[first]):
            first += 1
        while last > first and not conserved(middles[last - 1]):
            last -= 1
        out[i] = (first, last)
    return out


def pooled_log10_chance(votes: list[Vote], columns: list[int | None]) -> float:
    """log10 of the chance that members agree, counted together, as often as they do.

    Member ``k`` is read at ``columns[k]`` (None: it agrees in none of its
    copies); the plurality counts of all members are added and compared with
    the binomial tail over all their copies at the mean chance of the
    plurality symbols, times the number of distinct symbols of every member
    (each chose its own plurality); at most 0. A sum, not a product of
    tails: one member's chance agreement cannot carry the others. A symbol's
    chance is its frequency in the string but no less than one over the
    string's distinct symbols: the symbols between copies are drawn from
    all of them, and a string whose pattern takes most of its length makes
    every other symbol rare overall, though not rare between copies.
    """
    held = [(k, c) for k, c in enumerate(columns) if c is not None]
    rows = np.array([k for k, _ in held], dtype=np.int64)
    cols = np.array([c for _, c in held], dtype=np.int64)
    return _Pooled(votes).log10(rows, cols)


class _Pooled:
    """The members' counts and chances as arrays, for :func:`pooled_log10_chance` at many
    columns (a member without known frequencies never agrees)."""

    def __init__(self, votes: list[Vote]) -> None:
        width = max(len(v.pattern) for v in votes)
        self.copies = sum(v.full_copies for v in votes)
        self.penalty = sum(math.log10(max(2, v.symbols)) for v in votes)
        self.several = len(votes) > 1
        self.agree = np.zeros((len(votes), width), dtype=np.int64)
        self.chance = np.full((len(votes), width), np.nan)
        for row, v in enumerate(votes):
            if v.chance is None:
                continue
            length = len(v.pattern)
            # round half to even, as Python's round of each share times the copies
            self.agree[row, :length] = np.round(v.shares * v.full_copies)
            self.chance[row, :length] = np.maximum(v.chance, 1 / max(1, v.symbols))

    def log10(self, rows: np.ndarray, columns: np.ndarray) -> float:
        """The pooled log10 chance with member ``rows[k]`` read at ``columns[k]``."""
        chance = self.chance[rows, columns]
        known = ~np.isnan(chance)
        agree = int(self.agree[rows[known], columns[known]].sum())
        if agree == 0:
            return 0.0
        p = sum(chance[known].tolist()) / int(np.count_nonzero(known))  # in member order
        if self.several and agree <= self.copies * p:
            # at or below the mean the tail is at least a half (the median is the floor or
            # the ceiling of the mean): more than the penalty of two members takes back
            return 0.0
        return min(0.0, log10_binom_sf(agree, self.copies, p) + self.penalty)
