"""PAL: learn a parallel synchronous grammar system from an actiongram.

From the paper (SPEC §5): each string is learnt on its own from its digram
frequencies, growing rules N -> X Y; a string's structure is kept only when it
is synchronised with the structure of other strings (a string with nothing
synchronised is spurious and is not a component); the highest synchronised
level of each component is its motion pattern; the axiom has
S_i -> N_i S_i | N_i, synchronised across the components.

Ours (the paper's algorithm figure is lost), built to survive noise and
irregular repetition -- ``docs/pal.md`` gives the details and every parameter:

1. a motif per string, seeded by its most frequent digrams and grown one
   conserved column at a time, its copies located again by a tolerant scan
   after every step (damaged copies keep voting);
2. a significance screen against random strings of the same length and
   symbol frequencies;
3. synchronisation in time: two strings are in step when most clusters of
   their overlapping copies hold copies of both;
4. copies pooled over each group of synchronised strings: shared time
   windows, one copy per member and window, the pattern by plurality vote,
   copies located again with the voted pattern (not a fixed period);
5. strings too damaged to be significant alone join a group when, read in
   its windows, they repeat beyond chance; members that do not are dropped;
6. end columns not conserved across the group are trimmed.

When content finds nothing (``timing="auto"``, the default) or on request
(``timing="period"``), copies are instead time windows of the action's period,
pooled over all strings and tracked through tempo changes; a string is a
component when its symbols recur window after window (for real motion capture).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ..errors import ValidationError
from .base import Inducer, as_performances, check_choice, check_number
from .results import Induction, StringReport

__all__ = ["PAL"]

_TIMINGS = ("content", "period", "auto")


class PAL(Inducer):
    """The parallel learning algorithm (see the module docstring and ``docs/pal.md``).

    Parameters (all keyword):

    - ``min_copies`` (3): fewest copies of a motif that count as repetition.
    - ``conserve`` (0.6): share of copies that must agree on a new column.
    - ``edge_share`` (0.5): an end column of a voted pattern whose plurality symbol
      holds no more than this share of the copies is trimmed (it is not conserved).
    - ``match_fraction`` (0.5): least share of positions a copy must match.
    - ``scan_alpha`` (0.05): expected chance copies per string tolerated by the scan.
    - ``alpha`` (1e-2): chance level a string's repetition must beat to be a candidate.
    - ``sync_fraction`` (0.5): share of the merged copy clusters of two strings that
      must hold copies of both for them to be synchronised.
    - ``window_support`` (0.34): share of a group's members that must show a copy in a window.
    - ``max_pattern`` (64): longest motif, in symbols.
    - ``seeds`` (3): how many of a string's most frequent digrams are grown into motifs.
    - ``rounds`` (2): rounds of pooling; after each but the last, every member's
      copies are located again with its voted pattern.
    - ``joins_copies`` (4): a string outside every group joins one when, read in
      the group's windows, at least this many of its copies have the common
      length and half of their columns agree, beyond chance, in a share
      ``conserve`` of them.
    - ``timing`` ("auto"): how copies are located. ``"content"``: by content in
      each string, joined in time (steps 1-6); ``"period"``: by time windows of
      the action's period pooled over all strings (for real motion, where joints
      cycle through the same few states at different rates and phases);
      ``"auto"``: content, and the period mode when content finds no component.
    - ``period_quantile`` (0.9): the period mode's pooled excess self-agreement
      at each lag is this quantile over the strings (the driving joints decide).
    - ``period_agreement`` (0.6): in the period mode, least share of times at
      which a string's symbol recurs one (tracked) window later.

    >>> from psgs.induce.synthetic import generate
    >>> case = generate(seed=1, noise=0.1)
    >>> result = PAL().induce(case.actiongram)
    >>> sorted(result.components) == sorted(case.components)
    True
    """

    name = "pal"

    def __init__(self, *, min_copies: int = 3, conserve: float = 0.6, edge_share: float = 0.5,
                 match_fraction: float = 0.5, scan_alpha: float = 0.05, alpha: float = 1e-2,
                 sync_fraction: float = 0.5, window_support: float = 0.34,
                 max_pattern: int = 64, seeds: int = 3, rounds: int = 2,
                 joins_copies: int = 4, timing: str = "auto",
                 period_quantile: float = 0.9, period_agreement: float = 0.6) -> None:
        check_number("min_copies", min_copies, low=2, integer=True)
        check_number("conserve", conserve, low=0, high=1, low_open=True)
        check_number("edge_share", edge_share, low=0, high=1)
        check_number("match_fraction", match_fraction, low=0, high=1, low_open=True)
        check_number("scan_alpha", scan_alpha, low=0, low_open=True)
        check_number("alpha", alpha, low=0, high=1, low_open=True)
        check_number("sync_fraction", sync_fraction, low=0, high=1, low_open=True)
        check_number("window_support", window_support, low=0, high=1)
        check_number("max_pattern", max_pattern, low=2, integer=True)
        check_number("seeds", seeds, low=1, integer=True)
        check_number("rounds", rounds, low=1, integer=True)
        check_number("joins_copies", joins_copies, low=2, integer=True)
        check_choice("timing", timing, _TIMINGS)
        check_number("period_quantile", period_quantile, low=0, high=1)
        check_number("period_agreement", period_agreement, low=0, high=1, low_open=True)
        self.min_copies = min_copies
        self.conserve = conserve
        self.edge_share = edge_share
        self.match_fraction = match_fraction
        self.scan_alpha = scan_alpha
        self.alpha = alpha
        self.sync_fraction = sync_fraction
        self.window_support = window_support
        self.max_pattern = max_pattern
        self.seeds = seeds
        self.rounds = rounds
        self.joins_copies = joins_copies
        self.timing = timing
        self.period_quantile = period_quantile
        self.period_agreement = period_agreement

    def induce(self, performances) -> Induction:
        """Learn a PSGS from an actiongram; see :class:`~psgs.induce.Induction`.

        Parameters
        ----------
        performances : Actiongram or sequence of Actiongram
            One actiongram (a sequence holding one is the same). Several
            performances are not learnt from yet (issue 9): they are refused
            rather than joined into one stream.

        Returns
        -------
        Induction
            Synchronised: every component repeats its pattern the same number of times.

        Raises
        ------
        TypeError
            When the input is not an actiongram or a sequence of them.
        ValidationError
            For an empty sequence, performances whose actuators differ, or more
            than one performance.
        """
        takes = as_performances(performances, "PAL.induce")
        if len(takes) > 1:
            raise ValidationError(f"PAL.induce learns from one performance for now, not "
                                  f"{len(takes)} (several performances are issue 9)")
        actiongram = takes[0]
        alphabet: dict[str, int] = {}
        strings = [_Timed.build(syms, durs, origin, alphabet)
                   for syms, durs, origin in zip(actiongram.symbols,
                                                 actiongram.segment_durations,
                                                 actiongram.origins)]
        symbol_of = list(alphabet)
        motifs = [_find_motif(s.codes, self) for s in strings]
        candidates = [i for i, m in enumerate(motifs)
                      if m is not None and m.significance <= math.log10(self.alpha)]
        intervals = {i: strings[i].intervals(motifs[i].starts, len(motifs[i].motif))
                     for i in candidates}
        partners: dict[int, list[int]] = {i: [] for i in candidates}
        for a_pos, i in enumerate(candidates):
            for j in candidates[a_pos + 1:]:
                if _synchronised(intervals[i], intervals[j], self.sync_fraction, self.min_copies):
                    partners[i].append(j)
                    partners[j].append(i)
        groups = _groups(candidates, partners)

        patterns: dict[int, tuple[str, ...]] = {}
        occurrences: dict[int, tuple[tuple[float, float], ...]] = {}
        joined: dict[int, list[int]] = {}
        grouped = {i for g in groups for i in g}
        for group in groups:
            located = {i: intervals[i] for i in group}
            members = list(group)
            for round_ in range(self.rounds):
                if round_ + 1 < self.rounds:
                    windows = _pooled_windows([located[i] for i in members],
                                              self.window_support)
                    votes = {i: v for i in members
                             if (v := _vote(strings[i], windows)) is not None}
                    kept_columns = _trim(votes, self.edge_share) if votes else {}
                    # locate each member's copies again with its voted pattern
                    for i, (first, last) in kept_columns.items():
                        again = _relocate(strings[i], votes[i].pattern[first:last], self)
                        if again is not None:
                            located[i] = again
                    continue
                # every member must repeat in the shared windows itself, not only overlap
                # them in time (a random string's chance motif can); windows are redrawn
                # without the members that do not
                for _ in range(len(group)):
                    windows = _pooled_windows([located[i] for i in members],
                                              self.window_support)
                    votes = {i: v for i in members
                             if (v := _vote(strings[i], windows)) is not None
                             and _repeats_in_windows(strings[i], v, self, self.min_copies,
                                                     beyond_chance=False)}
                    if len(votes) == len(members) or len(votes) < 2:
                        break
                    members = sorted(votes)
                if len(votes) < 2:
                    votes = {}
                    break
                # strings whose own motif search fell short, read in the group's windows
                for i in range(len(strings)):
                    if i not in grouped and (v := _vote(strings[i], windows)) is not None \
                            and _repeats_in_windows(strings[i], v, self, self.joins_copies):
                        votes[i] = v
                        joined[i] = group
                        grouped.add(i)
            kept_columns = _trim(votes, self.edge_share) if votes else {}
            for i, (first, last) in kept_columns.items():
                if last <= first:
                    continue
                v = votes[i]
                length = len(v.pattern)
                patterns[i] = tuple(symbol_of[c] for c in v.pattern[first:last])
                where = []
                for a, b in v.spans:
                    if b - a == length:
                        a, b = a + first, a + last
                    where.append((float(strings[i].starts[a]), float(strings[i].ends[b - 1])))
                occurrences[i] = tuple(where)
        by_period = None
        if self.timing == "period" or (self.timing == "auto" and not patterns):
            by_period = _period_mode(strings, len(symbol_of), self)
            patterns, occurrences = {}, {}
            if by_period is not None:
                for i, codes in by_period.patterns.items():
                    patterns[i] = tuple(symbol_of[c] for c in codes)
                    occurrences[i] = by_period.occurrences[i]
                    partners[i] = [j for j in by_period.patterns if j != i]
        kept = tuple(sorted(patterns))

        reports = []
        for i, name in enumerate(actiongram.names):
            m = motifs[i]
            if i in patterns:
                status = "component"
                if i in joined:
                    partners[i] = joined[i]
            elif by_period is not None or self.timing == "period":
                status = "not in step with the period"
            elif m is None:
                status = "no repetition"
            elif i not in partners:
                status = "not significant"
            else:
                status = "not synchronised"
            reports.append(StringReport(
                name=name, status=status,
                motif=tuple(symbol_of[c] for c in m.motif) if m else (),
                copies=len(m.starts) if m else 0,
                significance=m.significance if m else 0.0,
                synchronised_with=tuple(actiongram.names[j] for j in partners.get(i, ()))))

        names = actiongram.names
        return self.build_induction(
            names, {names[i]: patterns[i] for i in kept},
            {names[i]: occurrences[i] for i in kept}, reports, synchronise=True)


@dataclass(frozen=True)
class _Timed:
    """One string as integer codes with start and end times."""

    codes: np.ndarray
    starts: np.ndarray
    ends: np.ndarray

    @classmethod
    def build(cls, symbols, durations, origin, alphabet: dict[str, int]) -> "_Timed":
        """Encode ``symbols``; new symbols join ``alphabet`` in order of first appearance."""
        for sym in dict.fromkeys(symbols):  # distinct symbols, in order of first appearance
            alphabet.setdefault(sym, len(alphabet))
        codes = np.fromiter(map(alphabet.__getitem__, symbols), dtype=np.int64,
                            count=len(symbols))
        durs = np.asarray(durations, dtype=np.float64)
        ends = origin + np.cumsum(durs)
        return cls(codes, ends - durs, ends)

    def intervals(self, copy_starts: np.ndarray, length: int) -> np.ndarray:
        """(k, 2) array: the time span of each copy of a motif of ``length`` symbols."""
        return np.column_stack((self.starts[copy_starts], self.ends[copy_starts + length - 1]))


@dataclass(frozen=True)
class _Motif:
    motif: np.ndarray
    starts: np.ndarray
    significance: float


# -- statistics -----------------------------------------------------------------
def _log10_binom_sf(k: int, m: int, p: float) -> float:
    """log10 P(X >= k) for X ~ Binomial(m, p)."""
    if k <= 0:
        return 0.0
    if k > m or p <= 0:
        return -math.inf
    if p >= 1:
        return 0.0
    lp, lq = math.log(p), math.log1p(-p)
    terms = []
    for i in range(k, m + 1):
        t = math.lgamma(m + 1) - math.lgamma(i + 1) - math.lgamma(m - i + 1) + i * lp + (m - i) * lq
        terms.append(t)
        if i > m * p and t < terms[0] - 30:
            break
    top = max(terms)
    return (top + math.log(sum(math.exp(t - top) for t in terms))) / math.log(10)


def _log10_poisson_sf(k: int, lam: float) -> float:
    """log10 P(Y >= k) for Y ~ Poisson(lam)."""
    if k <= 0:
        return 0.0
    if lam <= 0:
        return -math.inf
    terms, i = [], k
    while True:
        t = -lam + i * math.log(lam) - math.lgamma(i + 1)
        terms.append(t)
        if (i > lam and t < terms[0] - 30) or i > k + 10_000:
            break
        i += 1
    top = max(terms)
    return (top + math.log(sum(math.exp(t - top) for t in terms))) / math.log(10)


def _scan_threshold(length: int, windows: int, match_rate: float, params: PAL) -> int:
    """Fewest matching positions a window needs to count as a copy."""
    return _threshold(length, windows, match_rate, params.match_fraction, params.scan_alpha)


@functools.lru_cache(maxsize=4096)
def _threshold(length: int, windows: int, match_rate: float, match_fraction: float,
               scan_alpha: float) -> int:
    low = max(2, math.ceil(match_fraction * length))
    for t in range(low, length + 1):
        if windows * 10 ** _log10_binom_sf(t, length, match_rate) <= scan_alpha:
            return t
    return length


# -- motif finding in one string ---------------------------------------------------
def _locate(codes: np.ndarray, motif: np.ndarray, threshold: int) -> np.ndarray:
    """Non-overlapping windows agreeing with ``motif`` in >= threshold positions.

    Best agreement first, earlier first among equals; returned in position order.
    """
    n, length = len(codes), len(motif)
    width = n - length + 1
    if width <= 0:
        return np.zeros(0, dtype=np.int64)
    score = np.zeros(width, dtype=np.int32)
    for offset, sym in enumerate(motif):
        score += codes[offset:offset + width] == sym
    hits = np.flatnonzero(score >= threshold)
    if len(hits) == 0:
        return hits
    order = hits[np.lexsort((hits, -score[hits]))]
    if np.all(score[hits] == length) and (len(hits) < 2 or np.min(np.diff(hits)) >= length):
        return hits  # exact, non-overlapping copies: nothing to choose
    taken = np.zeros(n, dtype=bool)
    chosen = []
    for p in order:
        if not taken[p:p + length].any():
            taken[p:p + length] = True
            chosen.append(p)
    return np.sort(np.asarray(chosen, dtype=np.int64))


def _median_gap(starts: np.ndarray) -> int:
    """The median distance between consecutive copies (the lower middle one)."""
    gaps = np.sort(np.diff(starts))
    return int(gaps[(len(gaps) - 1) // 2])


def _merge_copies(old: np.ndarray, new: np.ndarray, length: int) -> np.ndarray:
    """Copies from both lists, earlier first, dropping any that overlaps one already kept.

    Copies located while the motif grew keep their place even when the longer
    motif no longer passes the scan (a damaged copy still shows the pattern).
    """
    both = np.unique(np.concatenate((old, new)))
    if len(both) < 2 or np.min(np.diff(both)) >= length:
        return both
    kept, last = [], None
    for p in both.tolist():
        if last is None or p >= last + length:
            kept.append(p)
            last = p
    return np.asarray(kept, dtype=np.int64)


def _find_motif(codes: np.ndarray, params: PAL) -> _Motif | None:
    """The best-supported repeated motif of one string, or None.

    Up to ``params.seeds`` of the most frequent digrams are grown in turn (a
    burst of noise can stop one seed early); the most significant motif wins,
    the earlier seed among equals.
    """
    n = len(codes)
    if n < 2 * params.min_copies:
        return None
    size = int(codes.max()) + 1
    freq = np.bincount(codes, minlength=size) / n
    distinct = int(np.count_nonzero(freq))
    match_rate = float(np.sum(freq ** 2))
    keys = codes[:-1] * size + codes[1:]
    uniq, first, counts = np.unique(keys, return_index=True, return_counts=True)
    order = np.lexsort((first, -counts))
    best: _Motif | None = None
    covered: set[int] = set()
    tried = 0
    for index in order.tolist():
        if tried >= params.seeds or counts[index] < params.min_copies:
            break
        if int(uniq[index]) in covered:
            continue  # already inside a motif grown from an earlier seed
        tried += 1
        seed = np.array([uniq[index] // size, uniq[index] % size], dtype=np.int64)
        found = _grow(codes, seed, np.flatnonzero(keys == uniq[index]), match_rate, distinct,
                      params)
        if found is None:
            continue
        covered.update((found.motif[:-1] * size + found.motif[1:]).tolist())
        if best is None or found.significance < best.significance:
            best = found
    return best


def _grow(codes: np.ndarray, motif: np.ndarray, starts: np.ndarray, match_rate: float,
          distinct: int, params: PAL) -> _Motif | None:
    """Grow ``motif`` one conserved column at a time from its copies at ``starts``."""
    n = len(codes)
    size = int(codes.max()) + 1
    while len(motif) < params.max_pattern:
        length = len(motif)
        spacing = _median_gap(starts) if len(starts) > 1 else n
        if length + 1 > spacing:
            break
        choice = None
        for side in ("right", "left"):
            pos = starts + length if side == "right" else starts - 1
            pos = pos[(pos >= 0) & (pos < n)]
            if len(pos) < params.min_copies:
                continue
            column = np.bincount(codes[pos], minlength=size)
            sym = int(np.argmax(column))
            k = int(column[sym])
            if k < params.min_copies or k < params.conserve * len(pos):
                continue
            share = k / len(pos)
            if choice is None or share > choice[0]:
                choice = (share, side, sym)
        if choice is None:
            break
        _, side, sym = choice
        grown = np.append(motif, sym) if side == "right" else np.insert(motif, 0, sym)
        kept = starts if side == "right" else starts - 1
        kept = kept[(kept >= 0) & (kept + len(grown) <= n)]
        threshold = _scan_threshold(len(grown), n - len(grown) + 1, match_rate, params)
        found = _merge_copies(kept, _locate(codes, grown, threshold), len(grown))
        if len(found) < params.min_copies:
            break
        motif, starts = grown, found

    length = len(motif)
    threshold = _scan_threshold(length, n - length + 1, match_rate, params)
    if len(starts) > 1 and _median_gap(starts) == length and starts[0] % length:
        # copies tile the string: put a copy boundary where the string starts
        shift = int(starts[0] % length)
        rotated = np.roll(motif, shift)
        found = _locate(codes, rotated, threshold)
        if len(found) >= len(starts):
            motif, starts = rotated, found
    starts = _merge_copies(starts, _locate(codes, motif, threshold), length)
    if len(starts) < params.min_copies:
        return None
    lam = (n - length + 1) * 10 ** _log10_binom_sf(threshold, length, match_rate)
    significance = length * math.log10(max(distinct, 2)) + _log10_poisson_sf(len(starts), lam)
    return _Motif(motif, starts, min(significance, 0.0))


# -- synchronisation and pooling -----------------------------------------------------
def _clusters(parts: list[np.ndarray]) -> np.ndarray:
    """Merge the intervals of several lists wherever they overlap.

    Returns a (clusters, lists) boolean array: which lists each cluster holds.
    """
    spans = np.concatenate(parts)
    tags = np.concatenate([np.full(len(iv), k) for k, iv in enumerate(parts)])
    order = np.lexsort((spans[:, 1], spans[:, 0]))
    spans, tags = spans[order], tags[order]
    reach = np.maximum.accumulate(spans[:, 1])
    opens = np.ones(len(spans), dtype=bool)
    opens[1:] = spans[1:, 0] >= reach[:-1]
    cluster = np.cumsum(opens) - 1
    held = np.zeros((int(cluster[-1]) + 1, len(parts)), dtype=bool)
    held[cluster, tags] = True
    return held


def _synchronised(a: np.ndarray, b: np.ndarray, fraction: float, min_copies: int) -> bool:
    """Whether two strings' copies cover the same time.

    Overlapping copies of both strings are merged into clusters; the strings
    are synchronised when at least ``min_copies`` clusters hold copies of both
    and those are at least ``fraction`` of all clusters. (A string whose
    period is half the other's has two copies in one cluster: still one
    shared cluster, so the period is shared in time.)
    """
    if len(a) == 0 or len(b) == 0:
        return False
    held = _clusters([a, b])
    both = int(np.count_nonzero(held.all(axis=1)))
    return both >= min_copies and both >= fraction * len(held)


def _groups(candidates: list[int], partners: dict[int, list[int]]) -> list[list[int]]:
    """Connected components of the synchronisation graph, singletons left out."""
    seen: set[int] = set()
    out = []
    for i in candidates:
        if i in seen or not partners[i]:
            continue
        stack, group = [i], []
        seen.add(i)
        while stack:
            v = stack.pop()
            group.append(v)
            for w in partners[v]:
                if w not in seen:
                    seen.add(w)
                    stack.append(w)
        out.append(sorted(group))
    return out


def _pooled_windows(member_intervals: list[np.ndarray], support: float) -> np.ndarray:
    """Shared copy windows of a group: the times enough members agree are in a copy.

    Cores are the maximal time ranges covered by copies of at least a share
    ``support`` of the members; each core then widens to the copies that
    overlap it (so a copy one member located more completely still counts),
    without reaching into the next core.
    """
    need = max(1, math.ceil(support * len(member_intervals) - 1e-9))
    spans = np.concatenate(member_intervals)
    times = np.concatenate((spans[:, 0], spans[:, 1]))
    steps = np.concatenate((np.ones(len(spans), dtype=np.int64),
                            -np.ones(len(spans), dtype=np.int64)))
    order = np.lexsort((steps, times))  # at equal times, ends before starts
    times, depth = times[order], np.cumsum(steps[order])
    inside = depth >= need
    before = np.concatenate(([False], inside[:-1]))
    opened, closed = times[inside & ~before], times[~inside & before]
    keep = closed > opened
    core = np.column_stack((opened[keep], closed[keep]))
    if len(core) == 0:
        return np.zeros((0, 2))
    core = _join_fragments(core, spans)
    low, high = core[:, 0].copy(), core[:, 1].copy()
    first = np.searchsorted(core[:, 1], spans[:, 0], side="right")  # first core ending after s
    last = np.searchsorted(core[:, 0], spans[:, 1], side="left") - 1  # last core starting before e
    hit = first <= last
    np.minimum.at(low, first[hit], spans[hit, 0])
    np.maximum.at(high, last[hit], spans[hit, 1])
    low[1:] = np.maximum(low[1:], core[:-1, 1])
    high[:-1] = np.minimum(high[:-1], core[1:, 0])
    return np.column_stack((low, high))


def _join_fragments(core: np.ndarray, spans: np.ndarray) -> np.ndarray:
    """Join touching cores that copies run across more than they stop or start at.

    Where one member repeats a shorter motif twice per copy of the others
    (and another misses its copy), coverage dips at the short motif's copy
    boundary; that instant is inside a copy for the members spanning it.
    Where every member's copy ends and the next begins (no gap between
    copies), nobody spans it and the cores stay apart.
    """
    if len(core) < 2:
        return core
    eps = 1e-9 * max(1.0, float(np.abs(core).max()))
    touching = np.flatnonzero(np.abs(core[1:, 0] - core[:-1, 1]) <= eps)
    if len(touching) == 0:
        return core
    t = core[touching, 1]
    starts, ends = np.sort(spans[:, 0]), np.sort(spans[:, 1])
    spanning = (np.searchsorted(starts, t - eps, side="left")
                - np.searchsorted(ends, t + eps, side="right"))
    # a member whose copy ends where its next begins counts once
    stopping = np.maximum(np.searchsorted(starts, t + eps, side="right")
                          - np.searchsorted(starts, t - eps, side="left"),
                          np.searchsorted(ends, t + eps, side="right")
                          - np.searchsorted(ends, t - eps, side="left"))
    join = np.zeros(len(core), dtype=bool)  # join[k]: core k continues core k - 1
    join[touching[(spanning >= 1) & (spanning >= stopping)] + 1] = True
    group = np.cumsum(~join) - 1
    low = np.full(group[-1] + 1, np.inf)
    high = np.full(group[-1] + 1, -np.inf)
    np.minimum.at(low, group, core[:, 0])
    np.maximum.at(high, group, core[:, 1])
    return np.column_stack((low, high))


def _relocate(string: _Timed, pattern: tuple[int, ...], params: PAL) -> np.ndarray | None:
    """Copy intervals of ``pattern`` found by scanning the string, or None if too few."""
    if len(pattern) < 2:
        return None
    codes = string.codes
    freq = np.bincount(codes) / len(codes)
    motif = np.asarray(pattern, dtype=np.int64)
    threshold = _scan_threshold(len(motif), len(codes) - len(motif) + 1,
                                float(np.sum(freq ** 2)), params)
    found = _locate(codes, motif, threshold)
    if len(found) < params.min_copies:
        return None
    # the pooled copies are many and reliable: let them grow the pattern further
    grown = _grow(codes, motif, found, float(np.sum(freq ** 2)), int(np.count_nonzero(freq)),
                  params)
    if grown is None:
        return string.intervals(found, len(motif))
    return string.intervals(grown.starts, len(grown.motif))


@dataclass(frozen=True)
class _Vote:
    """One member's copies in the shared windows and their column-wise plurality."""

    pattern: tuple[int, ...]
    shares: np.ndarray        # plurality share of each column
    column_start: np.ndarray  # median time offset of each column from its window's start
    column_end: np.ndarray
    spans: tuple[tuple[int, int], ...]  # symbol index range of each copy
    window_of: tuple[int, ...]          # which window each copy lies in


def _vote(string: _Timed, windows: np.ndarray) -> _Vote | None:
    """The plurality pattern of a string's copies in the shared windows.

    A copy is the run of symbols whose middle lies in a window. The pattern
    length is the most common copy length (the longer among equals); each
    position takes the symbol most copies of that length agree on (the one
    seen first in time among equals).
    """
    middles = (string.starts + string.ends) / 2
    lo = np.searchsorted(middles, windows[:, 0], side="left")
    hi = np.searchsorted(middles, windows[:, 1], side="left")
    sizes = hi - lo
    picked = np.flatnonzero(sizes > 0)
    if len(picked) == 0:
        return None
    counts = np.bincount(sizes[picked])
    length = int(len(counts) - 1 - np.argmax(counts[::-1]))  # most common; longer among equals
    full = picked[sizes[picked] == length]
    index = lo[full][:, None] + np.arange(length)
    same = string.codes[index]
    offsets = string.starts[index] - windows[full, 0][:, None]
    ends = string.ends[index] - windows[full, 0][:, None]
    pattern, shares = [], []
    for column in same.T:
        tally = np.bincount(column)
        top = tally.max()
        # ties go to the symbol seen first in time
        pattern.append(int(column[np.argmax(tally[column] == top)]))
        shares.append(top / len(column))
    return _Vote(tuple(pattern), np.asarray(shares), np.median(offsets, axis=0),
                 np.median(ends, axis=0),
                 tuple(zip(lo[picked].tolist(), hi[picked].tolist())),
                 tuple(picked.tolist()))


def _repeats_in_windows(string: _Timed, vote: _Vote, params: PAL, copies_needed: int,
                        beyond_chance: bool = True) -> bool:
    """Whether a string read in a group's windows repeats a pattern of its own.

    It needs at least ``copies_needed`` copies of the common length, and at
    least half of their columns (two or more) where the plurality symbol holds
    a share ``conserve`` of the copies and, when ``beyond_chance``, is more
    frequent than chance: the binomial tail of its count, at the symbol's
    frequency in the whole string, times the number of distinct symbols (any
    of them could have been the plurality), below 0.01.
    """
    length = len(vote.pattern)
    same = [a for a, b in vote.spans if b - a == length]
    if len(same) < copies_needed or length < 2:
        return False
    freq = np.bincount(string.codes) / len(string.codes)
    penalty = math.log10(max(2, int(np.count_nonzero(freq))))
    agreeing = 0
    for column, (sym, share) in enumerate(zip(vote.pattern, vote.shares.tolist())):
        k = round(share * len(same))
        if share >= params.conserve and (not beyond_chance or _log10_binom_sf(
                k, len(same), float(freq[sym])) + penalty <= -2):
            agreeing += 1
    return agreeing >= max(2, math.ceil(length / 2))


def _trim(votes: dict[int, _Vote], edge_share: float) -> dict[int, tuple[int, int]]:
    """Per member, the range of columns kept: end columns not conserved across the group go.

    A column's conservation is pooled in time: the mean, over the members, of
    the plurality share of the member's column at that time offset (0 where
    a member has no column). So one string's chance agreement at a column the
    others do not share is trimmed, and a column damaged in one string but
    conserved in the others is kept.
    """
    def pooled(t: float) -> float:
        total = 0.0
        for v in votes.values():
            hit = np.flatnonzero((v.column_start <= t) & (t < v.column_end))
            if len(hit):
                total += float(v.shares[hit[0]])
        return total / len(votes)

    out = {}
    for i, v in votes.items():
        middles = (v.column_start + v.column_end) / 2
        first, last = 0, len(v.pattern)
        while first < last and pooled(middles[first]) <= edge_share:
            first += 1
        while last > first and pooled(middles[last - 1]) <= edge_share:
            last -= 1
        out[i] = (first, last)
    return out


# -- the period mode: copies located by time pooled over the strings -----------------
@dataclass(frozen=True)
class _PeriodResult:
    """Components found by the period mode: pattern codes and copy times per string."""

    period: float
    patterns: dict
    occurrences: dict
    agreement: dict


def _time_grid(strings: list[_Timed], max_points: int = 1 << 14):
    """Sample every string's symbol code on one time grid (-1 outside the string).

    The step is half the lower quartile of the segment durations (so most
    segments span two points or more; the quickest flickers fall between
    points), coarser if the
    actiongram would need more than ``max_points`` points.
    """
    present = [s for s in strings if len(s.codes)]
    t0 = min(float(s.starts[0]) for s in present)
    t1 = max(float(s.ends[-1]) for s in present)
    durations = np.concatenate([s.ends - s.starts for s in present])
    step = max(float(np.quantile(durations, 0.25)) / 2, (t1 - t0) / max_points)
    times = t0 + step * (np.arange(int((t1 - t0) / step + 1e-9)) + 0.5)
    grid = np.full((len(strings), len(times)), -1, dtype=np.int64)
    for row, s in enumerate(strings):
        if len(s.codes) == 0:
            continue
        index = np.searchsorted(s.ends, times, side="right")
        inside = (times >= s.starts[0]) & (index < len(s.codes))
        grid[row, inside] = s.codes[index[inside]]
    return times, step, grid


def _self_agreement(grid: np.ndarray, size: int) -> tuple[np.ndarray, np.ndarray]:
    """Per string and lag (in grid points): share of times whose symbol recurs one lag later.

    Also each string's chance rate, the sum of its squared symbol time shares
    (what a string whose symbols were drawn independently would reach).
    Computed with FFTs of one indicator per symbol.
    """
    n = grid.shape[1]
    nfft = 1 << max(1, (2 * n - 1).bit_length())
    valid = grid >= 0

    def correlate(indicator):
        spectrum = np.fft.rfft(indicator.astype(np.float64), nfft, axis=1)
        return np.fft.irfft(spectrum * spectrum.conj(), nfft, axis=1)[:, :n]

    pairs = np.round(correlate(valid))
    same = np.zeros_like(pairs)
    chance = np.zeros(grid.shape[0])
    counted = np.maximum(valid.sum(axis=1), 1)
    for sym in range(size):
        indicator = grid == sym
        if indicator.any():
            same += np.round(correlate(indicator))
            chance += (indicator.sum(axis=1) / counted) ** 2
    return same / np.maximum(pairs, 1), chance


def _candidate_periods(excess: np.ndarray, params: PAL, most: int = 4) -> list[int]:
    """Lags (grid points) at which the strings that repeat recur: candidates for the action's period.

    Pooled over the strings as the upper ``period_quantile`` of their excess
    agreement (agreement minus chance) at each lag, so the few joints that
    drive an action decide and the many still or jittering ones do not
    dilute them. Lags are searched from the end of the first decline (a
    symbol agrees with itself a moment later) to a length leaving
    ``min_copies`` copies. The candidates are the peaks of that curve: first
    the shortest within 15% of the highest (a peak at twice the period is as
    high), then the others, highest first, at most ``most``.
    """
    n = excess.shape[1]
    longest = n // params.min_copies + 1
    if longest < 3:
        return []
    pooled = np.quantile(excess[:, :longest], params.period_quantile, axis=0)
    rises = np.flatnonzero(np.diff(pooled) > 0)
    if len(rises) == 0:
        return []
    first = max(int(rises[0]), 2)
    if first >= longest:
        return []
    top = float(pooled[first:].max())
    if top <= 0:
        return []
    peaks = [lag for lag in range(first, longest)
             if pooled[lag] > 0 and pooled[lag] >= pooled[lag - 1]
             and (lag + 1 >= longest or pooled[lag] >= pooled[lag + 1])]
    shortest = [lag for lag in peaks if pooled[lag] >= 0.85 * top][:1]
    others = sorted((lag for lag in peaks if lag not in shortest), key=lambda l: (-pooled[l], l))
    return (shortest + others)[:most]


def _window_agreement(grid: np.ndarray, a: int, b: int, length: int) -> float:
    """Mean over rows of the share of points of windows at ``a`` and ``b`` with equal symbols."""
    n = grid.shape[1]
    span = min(length, n - b)
    left, right = grid[:, a:a + span], grid[:, b:b + span]
    valid = (left >= 0) & (right >= 0)
    counts = valid.sum(axis=1)
    share = ((left == right) & valid).sum(axis=1) / np.maximum(counts, 1)
    return float(share[counts > 0].mean()) if np.any(counts > 0) else 0.0


def _track_windows(grid: np.ndarray, lag: int) -> np.ndarray:
    """Start points of consecutive copy windows of ``lag`` points, following tempo changes.

    The phase is where the fewest segments of the given rows run across a
    window boundary, among the phases that lose no whole window; each next window starts within 20% of ``lag`` after the
    previous one, where the rows agree best with it (nearest to ``lag``
    among equals), so a repetition that slows or speeds up stays in step.
    """
    n = grid.shape[1]
    if n < 2 * lag:
        return np.zeros(0, dtype=np.int64)
    # phases that keep as many whole windows as the string holds
    crossing = np.zeros(min(lag, n - (n // lag) * lag + 1))
    for phase in range(len(crossing)):
        cuts = np.arange(max(phase, 1), n, lag)
        crossing[phase] = np.count_nonzero((grid[:, cuts - 1] == grid[:, cuts])
                                           & (grid[:, cuts] >= 0)) / len(cuts)
    starts = [int(np.argmin(crossing))]
    slack = max(1, lag // 5)
    # at most 41 tried lengths per window bounds the cost on long, finely sampled input
    tried = np.unique(np.round(np.linspace(lag - slack, lag + slack, min(2 * slack + 1, 41))))
    candidates = sorted(tried.astype(int).tolist(), key=lambda l: (abs(l - lag), l))
    while True:
        here = starts[-1]
        options = [l for l in candidates if here + l + lag <= n]
        if not options:
            break
        scores = [_window_agreement(grid, here, here + l, lag) for l in options]
        starts.append(here + options[int(np.argmax(scores))])
    return np.asarray(starts, dtype=np.int64)


def _period_mode(strings: list[_Timed], size: int, params: PAL) -> _PeriodResult | None:
    """Components whose symbols recur with the action's period, read in tracked windows.

    For real motion: joints cycle through the same few states at different
    rates and phases, so copies found by content in each string do not
    cluster; here the copies are time windows shared by all strings. A string
    is a component when, window after window, its symbols at the same time
    offset agree in a share ``period_agreement`` of the times, beyond chance
    (binomial tail on its segments, at its chance rate, times the number of
    strings, below ``alpha``); at least two are needed (synchronisation). Its
    pattern is the plurality symbol at each time offset, runs shorter than
    two grid points dropped.
    """
    if sum(len(s.codes) > 0 for s in strings) < 2:
        return None
    times, step, grid = _time_grid(strings)
    if grid.shape[1] < 2 * params.min_copies:
        return None
    agreement, chance = _self_agreement(grid, size)
    lags = _candidate_periods(agreement - chance[:, None], params)
    best = None
    for lag in lags:
        found = _read_period(strings, size, times, step, grid, agreement, chance, lag,
                             len(lags), params)
        if found is not None and (best is None or len(found.patterns) > len(best.patterns)):
            best = found
    return best


def _read_period(strings, size, times, step, grid, agreement, chance, lag, tried,
                 params: PAL) -> _PeriodResult | None:
    """The components of one candidate period (see :func:`_period_mode`)."""
    drivers = np.flatnonzero(agreement[:, lag] >= params.period_agreement)
    if len(drivers) < 2:
        return None
    starts = _track_windows(grid[drivers], lag)
    if len(starts) < params.min_copies:
        return None
    windows = grid[:, starts[:, None] + np.arange(lag)]   # (strings, copies, lag)
    penalty = math.log10(len(strings) * tried)
    patterns, occurrences, agreed = {}, {}, {}
    for row, s in enumerate(strings):
        copies = windows[row]
        valid = (copies[:-1] >= 0) & (copies[1:] >= 0)
        if valid.sum() == 0:
            continue
        share = float(((copies[:-1] == copies[1:]) & valid).sum() / valid.sum())
        if share < params.period_agreement:
            continue
        low = times[starts[0]] - step / 2
        high = times[starts[-1] + lag - 1] + step / 2
        segments = int(np.count_nonzero((s.ends > low) & (s.starts < high)))
        if _log10_binom_sf(round(share * segments), segments, float(chance[row])) + penalty \
                > math.log10(params.alpha):
            continue
        pattern = _plurality_runs(copies, size)
        if len(pattern) < 2:
            continue
        patterns[row] = pattern
        agreed[row] = share
        occurrences[row] = tuple((float(times[a] - step / 2), float(times[a + lag - 1] + step / 2))
                                 for a in starts.tolist())
    if len(patterns) < 2:
        return None
    return _PeriodResult(float(lag * step), patterns, occurrences, agreed)


def _plurality_runs(copies: np.ndarray, size: int) -> tuple[int, ...]:
    """The symbols of the column-wise plurality of ``copies``, runs under two points dropped."""
    column = []
    for values in copies.T:
        values = values[values >= 0]
        if len(values) == 0:
            column.append(-1)
            continue
        tally = np.bincount(values, minlength=size)
        column.append(int(column[-1]) if column and column[-1] >= 0
                      and tally[column[-1]] == tally.max() else int(np.argmax(tally)))
    runs: list[list[int]] = []
    for sym in column:
        if runs and runs[-1][0] == sym:
            runs[-1][1] += 1
        else:
            runs.append([sym, 1])
    kept = [sym for sym, width in runs if sym >= 0 and width >= 2] or \
        [sym for sym, _ in runs if sym >= 0]
    out: list[int] = []
    for sym in kept:
        if not out or out[-1] != sym:
            out.append(sym)
    return tuple(out)
