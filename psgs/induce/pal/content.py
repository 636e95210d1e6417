"""The content mode: copies found by content in each string, joined in time (steps 1-6)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ._alarm import alarm
from .conf import NO_BOUND
from .motifs import Motif, Timed, find_motifs
from .edges import trim
from .joining import may_join
from .pooling import (PAIR_BYTES, member_votes, pooled_pattern, pooled_windows, relocate,
                      repeats_in_windows, sync_groups, vote)
from .synchronisation import pair_blocks
from .together import locate_together
from .widening import widen

if TYPE_CHECKING:
    from ...budget import Budget
    from .conf import Bounds, ContentConf


#: the statuses of a string some stage of the pooling dropped (see ``docs/pal.md``)
DROPPED_IN_WINDOWS = "not repeated in the group's windows"
LEFT_ALONE = "group left with one member"
TRIMMED_AWAY = "pattern trimmed away"


@dataclass
class ContentResult:
    """What the content mode found, per string index (a working record, not a public value)."""

    motifs: list[Motif | None]
    candidates: list[int]
    intervals: dict[int, object]  # candidate -> (copies, 2) array of copy times
    partners: dict[int, list[int]]
    patterns: dict[int, tuple[int, ...]] = field(default_factory=dict)
    occurrences: dict[int, tuple[tuple[float, float], ...]] = field(default_factory=dict)
    joined: dict[int, list[int]] = field(default_factory=dict)
    spans: dict[int, tuple[tuple[int, int], ...]] = field(default_factory=dict)  # positions
    groups: list[list[int]] = field(default_factory=list)  # the components, group by group
    dropped: dict[int, str] = field(default_factory=dict)  # string -> the stage that dropped it
    sections: list = field(default_factory=list)  # per string: its Section or None
    section_partners: dict[int, list[int]] = field(default_factory=dict)
    from_sections: set[int] = field(default_factory=set)  # components whose pattern is a section
    agreements: dict[int, tuple[float, ...]] = field(default_factory=dict)  # per copy


def find_candidates(strings: list[Timed], conf: ContentConf, clock: Bounds = NO_BOUND
                    ) -> ContentResult:
    """Steps 1-3: a motif per string, the significance screen, synchronisation in time.

    ``clock`` is read between strings and between rows of the pairs tested; past its
    deadline it raises :class:`~psgs.errors.BoundReached` (nothing is returned), as it does
    when the pairs found pass its ``max_bytes`` (:data:`PAIR_BYTES` a pair).
    """
    motifs = find_motifs([s.codes for s in strings], conf, clock)
    candidates = [i for i, m in enumerate(motifs)
                  if m is not None and m.significance <= math.log10(conf.alpha)]
    intervals = {i: strings[i].copy_times(motifs[i]) for i in candidates}
    partners: dict[int, list[int]] = {i: [] for i in candidates}
    for rows, columns in pair_blocks([intervals[i] for i in candidates], conf, clock):
        clock.keep(PAIR_BYTES * len(rows))
        for i, j in zip(rows, columns):
            a, b = candidates[i], candidates[j]
            partners[a].append(b)
            partners[b].append(a)
    return ContentResult(motifs, candidates, intervals, partners)


def pool_groups(strings: list[Timed], found: ContentResult, conf: ContentConf,
                clock: Budget = NO_BOUND) -> ContentResult:
    """Steps 4-6 for every group of synchronised strings: pooled windows, vote, join, trim.

    ``clock`` is read before each group, each of its rounds and each member located again
    (and inside its scans and growth: the compiled growth reads an
    :func:`~psgs.induce.pal._alarm.alarm`); past its deadline it raises
    :class:`~psgs.errors.BoundReached`, ``found`` holding the patterns of the groups done
    (a group's are written once it is done).
    """
    with alarm(clock) as stop:
        return _pool_groups(strings, found, conf, clock, stop)


def _pool_groups(strings: list[Timed], found: ContentResult, conf: ContentConf,
                 clock: Budget, stop: np.ndarray) -> ContentResult:
    """:func:`pool_groups`, the compiled growth reading ``stop``."""
    intervals = found.intervals
    groups = sync_groups(found.candidates, found.partners)
    patterns, occurrences, joined = found.patterns, found.occurrences, found.joined
    dropped = found.dropped
    grouped = {i for g in groups for i in g}
    for group in groups:
        clock.check()
        located = {i: intervals[i] for i in group}
        earlier = np.zeros((0, 2))
        members = list(group)
        # the rounds before the last vote, then locate each member again with its vote; once
        # a round leaves every member where it was, every round left would repeat it
        for _ in range(conf.rounds - 1):
            clock.check()
            before = {i: located[i] for i in members}
            windows = pooled_windows([located[i] for i in members], conf.window_support)
            earlier = windows
            votes = member_votes(strings, members, windows, clock)
            kept_columns = trim(votes, conf.edge_share, conf.column_alpha) if votes else {}
            # locate each member's copies again with its voted pattern
            for i, (first, last) in kept_columns.items():
                clock.check()
                pattern = pooled_pattern(strings[i], votes[i], clock)
                again = relocate(strings[i], pattern[first:last], conf, clock, stop)
                if again is not None:
                    located[i] = again
            if all(np.array_equal(located[i], before[i]) for i in members):
                break
        # the last round: every member must repeat in the shared windows itself, not only
        # overlap them in time (a random string's chance motif can); windows are redrawn
        # without the members that do not
        for _ in range(len(group)):
            clock.check()
            windows = with_earlier(pooled_windows([located[i] for i in members],
                                                  conf.window_support), earlier)
            votes = {i: v for i, v in member_votes(strings, members, windows, clock).items()
                     if repeats_in_windows(strings[i], v, conf, conf.min_copies,
                                           beyond_chance=False)}
            for i in members:
                if i not in votes:
                    dropped[i] = DROPPED_IN_WINDOWS
            if len(votes) == len(members) or len(votes) < 2:
                break
            members = sorted(votes)
        if len(votes) < 2:  # a group left alone leaves it
            for i in votes:
                dropped[i] = LEFT_ALONE
            votes = {}
        else:
            clock.check()
            together = locate_together(strings, votes, conf, clock)
            if together is not None:
                # a copy damaged in most members passes no joint scan; its window stays
                together = with_earlier(together, windows)
                again = member_votes(strings, votes, together, clock)
                if len(again) == len(votes):
                    windows, votes = together, again
            windows, votes = widen(strings, votes, windows, conf.edge_share,
                                   conf.column_alpha, conf.max_pattern, clock)
            # strings whose own motif search fell short, read in the group's windows
            outside = [i for i in range(len(strings)) if i not in grouped]
            clock.check()
            for i in may_join(strings, outside, windows, conf.joins_copies, conf.conserve):
                clock.check()
                if (v := vote(strings[i], windows)) is not None \
                        and repeats_in_windows(strings[i], v, conf, conf.joins_copies):
                    votes[i] = v
                    joined[i] = group
                    grouped.add(i)
        kept_columns = trim(votes, conf.edge_share, conf.column_alpha) if votes else {}
        kept = []
        for i, (first, last) in kept_columns.items():
            if last <= first:
                dropped[i] = TRIMMED_AWAY
                continue
            v = votes[i]
            length = len(v.pattern)
            patterns[i] = pooled_pattern(strings[i], v, clock)[first:last]
            where, spans = [], []
            for a, b in v.spans:
                if b - a == length:
                    a, b = a + first, a + last
                where.append((float(strings[i].starts[a]), float(strings[i].ends[b - 1])))
                spans.append((int(a), int(b)))
            occurrences[i] = tuple(where)
            found.spans[i] = tuple(spans)
            kept.append(i)
        if kept:
            found.groups.append(kept)
    return found


def with_earlier(windows: np.ndarray, earlier: np.ndarray) -> np.ndarray:
    """``windows`` and every earlier window that overlaps none of them, in time order.

    Copies located again with a voted pattern miss the copies that noise
    damaged in most members (the scan needs most positions to match); the
    window the first round's copies found there still holds that copy, and
    its damaged symbols still count in the vote.
    """
    if len(earlier) == 0 or len(windows) == 0:
        return windows
    first = np.searchsorted(windows[:, 1], earlier[:, 0], side="right")
    last = np.searchsorted(windows[:, 0], earlier[:, 1], side="left")
    alone = earlier[first >= last]
    if len(alone) == 0:
        return windows
    both = np.concatenate((windows, alone))
    return both[np.argsort(both[:, 0], kind="stable")]
