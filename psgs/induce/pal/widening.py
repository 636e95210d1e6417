"""A group's shared windows widened by the conserved columns just beyond them (step 5b).

Every member's motif search can stop one column or more short of the whole
pattern: at high noise a column's plurality, read in one string, falls below
``conserve`` although the column is there in every member. When every
member's own search stops at the same place, the pooled windows are too
short too, and no later step can give the column back. Pooled over the
group, the column still stands out: beyond a true pattern lie the symbols
between copies, which agree only by chance.

So the windows are widened one column at a time, at the start or the end,
for as long as the widened vote keeps the new column in every member
(:func:`~psgs.induce.pal.pooling.trim`'s pooled share, the rule that trims
unconserved end columns, here deciding whether to add one).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .conf import NO_BOUND
from .motifs import Timed
from .edges import trim
from .pooling import Vote, member_votes

if TYPE_CHECKING:
    from ...budget import Budget

__all__: list[str] = []  # private: content.py is the caller


def widen(strings: list[Timed], votes: dict[int, Vote], windows: np.ndarray,
          edge_share: float, alpha: float, longest: int, clock: Budget = NO_BOUND
          ) -> tuple[np.ndarray, dict[int, Vote]]:
    """``windows`` and ``votes`` widened while the column beyond is conserved in the group.

    ``votes`` are the members' votes in ``windows``; a widening is kept only
    when it lengthens every member's pattern by exactly one column and
    :func:`trim` (with ``edge_share`` and ``alpha``) keeps that column in every member.
    Patterns grow to
    ``longest`` columns at most. ``clock`` is read before each column tried and each
    member's vote (:class:`~psgs.errors.BoundReached`): a group of thousands of members
    widened by tens of columns is as many votes.
    """
    for side in ("start", "end"):
        while max(len(v.pattern) for v in votes.values()) < longest:
            clock.check()
            wider = _one_column(strings, list(votes), windows, side)
            if wider is None:
                break
            again = member_votes(strings, votes, wider, clock)
            if len(again) < len(votes) or any(len(v.pattern) != len(votes[i].pattern) + 1
                                              for i, v in again.items()):
                break
            kept = trim(again, edge_share, alpha)
            if side == "start" and any(first > 0 for first, _ in kept.values()):
                break
            if side == "end" and any(last < len(again[i].pattern)
                                     for i, (_, last) in kept.items()):
                break
            windows, votes = wider, again
    return windows, votes


def _one_column(strings: list[Timed], members: list[int], windows: np.ndarray,
                side: str) -> np.ndarray | None:
    """The windows, each reaching one more symbol of every member at ``side``, or None.

    A window takes the symbols whose middle lies in it (as :func:`vote`
    reads it). At the start it moves back to the earliest start of the
    members' symbols just before it, or, where that would take in a second
    symbol of some member, to the earliest of those symbols' middles; at the
    end likewise (to the latest end, or half way to the next symbols'
    middles). It never reaches into the window beside it; a window that
    cannot take in one more symbol of every member, and no other, stays as it
    is. None when none widens.
    """
    count = len(windows)
    near_edge = np.full(count, np.inf if side == "start" else -np.inf)  # a symbol's own edge
    near_mid = near_edge.copy()   # the middle the window must reach past
    far_mid = -near_edge          # the middle of the symbol beyond, which must stay out
    blocked = np.zeros(count, dtype=bool)
    for i in members:
        s = strings[i]
        middles = s.middles
        last = len(middles) - 1
        if side == "start":
            at = np.searchsorted(middles, windows[:, 0], side="left") - 1  # the symbol before
            blocked |= at < 0
            at = np.maximum(at, 0)
            near_edge = np.minimum(near_edge, s.starts[at])
            near_mid = np.minimum(near_mid, middles[at])
            far_mid = np.maximum(far_mid, np.where(at > 0, middles[np.maximum(at - 1, 0)],
                                                   -np.inf))
        else:
            at = np.searchsorted(middles, windows[:, 1], side="left")  # the symbol after
            blocked |= at > last
            at = np.minimum(at, last)
            near_edge = np.maximum(near_edge, s.ends[at])
            near_mid = np.maximum(near_mid, middles[at])
            far_mid = np.minimum(far_mid, np.where(at < last, middles[np.minimum(at + 1, last)],
                                                   np.inf))
    out = windows.copy()
    if side == "start":  # a window holds the middles >= its start
        edge = np.where(near_edge > far_mid, near_edge, near_mid)
        ok = ~blocked & (near_mid > far_mid)
        ok[1:] &= edge[1:] >= windows[:-1, 1]
        out[ok, 0] = edge[ok]
    else:  # ... and < its end
        edge = np.where(near_edge <= far_mid, near_edge, (near_mid + far_mid) / 2)
        ok = ~blocked & (near_mid < far_mid)
        ok[:-1] &= edge[:-1] <= windows[1:, 0]
        out[ok, 1] = edge[ok]
    return out if ok.any() else None
