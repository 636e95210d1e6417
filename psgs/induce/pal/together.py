"""A group's copies located in all members at once (step 5c).

Each member's copies were first located in that member alone, by a scan that
needs most of the motif's positions to match. Under heavy noise a copy
damaged in most members is missed in each of them, and a window that only
some members' copies set is placed a symbol or two off. Read together, the
members give a copy ``members`` times as many positions to match: a copy
that half matches in each is still far beyond chance in all of them.

So every member's voted pattern is scored at every start, the scores of
the members' starts that fall at one time (within half the shortest
member's typical symbol) are added, and copies are taken best first,
earlier first among equals, none overlapping another in time, while the
summed score is beyond chance for all the members' positions together
(:func:`~psgs.induce.pal.statistics.chance_threshold`).
"""

from __future__ import annotations

import bisect
from typing import TYPE_CHECKING

import numpy as np

from .conf import NO_BOUND
from .motifs import Timed, match_scores
from .pooling import Vote
from .statistics import chance_threshold

if TYPE_CHECKING:
    from ...budget import Budget
    from .conf import ContentConf

__all__: list[str] = []  # private: content.py is the caller


def locate_together(strings: list[Timed], votes: dict[int, Vote],
                    conf: ContentConf, clock: Budget = NO_BOUND) -> np.ndarray | None:
    """The group's copy windows found by scanning all members at once, or None if too few.

    Returns a (copies, 2) array of time windows in time order: each from the
    earliest start to the latest end of the members' copies it holds. ``clock`` is read
    before each member and each column of its scan (:class:`~psgs.errors.BoundReached`).
    """
    members = list(votes)
    reference = strings[members[0]]
    times = reference.starts
    tolerance = 0.5 * min(float(np.median(strings[i].ends - strings[i].starts))
                          for i in members)
    total = np.zeros(len(times), dtype=np.int64)
    valid = np.ones(len(times), dtype=bool)
    first = np.full(len(times), np.inf)
    last = np.full(len(times), -np.inf)
    positions, rates = 0, []
    for i in members:
        clock.check()
        s, pattern = strings[i], np.asarray(votes[i].pattern, dtype=np.int64)
        length, n = len(pattern), len(s.codes)
        width = n - length + 1
        if width <= 0:
            return None
        score = match_scores(s.codes, pattern.tolist(), clock)
        # the member's start nearest each reference start
        at = np.clip(np.searchsorted(s.starts, times), 1, n - 1)
        nearer = np.where(np.abs(s.starts[at - 1] - times) <= np.abs(s.starts[at] - times),
                          at - 1, at) if n > 1 else np.zeros(len(times), dtype=np.int64)
        here = (np.abs(s.starts[nearer] - times) <= tolerance) & (nearer < width)
        valid &= here
        j = np.minimum(nearer, width - 1)
        total += np.where(here, score[j], 0)
        first = np.minimum(first, s.starts[j])
        last = np.maximum(last, s.ends[np.minimum(j + length - 1, n - 1)])
        positions += length
        rates.append(s.match_rate)
    # the joint copy needs only to be beyond chance: with every member's positions
    # together, a copy half damaged in each is still far beyond it
    threshold = chance_threshold(positions, int(np.count_nonzero(valid)) or 1,
                                 float(np.mean(rates)), conf)
    hits = np.flatnonzero(valid & (total >= threshold))
    # best first, earlier first among equals; a copy overlapping one kept is left out
    order = hits[np.lexsort((hits, -total[hits]))]
    kept_starts: list[float] = []
    kept_ends: list[float] = []
    for p in order.tolist():
        a, b = float(first[p]), float(last[p])
        k = bisect.bisect_left(kept_starts, a)
        if (k < len(kept_starts) and kept_starts[k] < b) or (k > 0 and kept_ends[k - 1] > a):
            continue
        kept_starts.insert(k, a)
        kept_ends.insert(k, b)
    if len(kept_starts) < conf.min_copies:
        return None
    return np.column_stack((kept_starts, kept_ends))
