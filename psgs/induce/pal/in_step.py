"""How unlikely a group of sections in step is by chance: the group's one significance.

A string's section (:mod:`~psgs.induce.pal.sections`) is weighed alone by
:func:`~psgs.induce.pal.sections.repeat_significance`, a bound over every
place its copies could lie. A second string whose section lies at the *same
times* is far stronger evidence than a second repeat anywhere: the places it
could have taken and still lain as close to the first string's copies are a
handful, not thousands. So a group of sections in step is weighed as one
event (``docs/streams.md``, "Significance of a repetition"):

- its **lead**, one member, repeats somewhere:
  :func:`~psgs.induce.pal.sections.lead_significance`, the expected number of maximal
  exact repeats as strong in its string;
- each other member repeats where the lead's copies are:
  :func:`~psgs.induce.pal.in_step_weight.in_step_significance`, ``T_j``, counting
  only the places its copies could take lying as close to the lead's copies as they do;
- and the lead and its ``m - 1`` partners could have been any of the
  ``N`` strings: ``log10(N * C(N - 1, m - 1))``.

The group's significance is the sum, at the lead that makes it strongest (members
that move with the lead or with another, one string's symbol determining the other's
beyond chance away from the lead's copies, add nothing: :class:`~psgs.induce.pal.alike.Alike`);
a member is kept only when its own ``T_j`` beats chance among the other strings, so that
no random string is carried in by the others' strength: ``T_j + log10(N - 1) <=
log10(alpha)`` read at the lead's copies, and, read again at the core below by how
much of it the string plays again at its shift
(:func:`~psgs.induce.pal.core_cover.cover_reading`), Holm's step-down over the ``M``
strings read there (the ``k``-th lightest against ``log10(M - k)``). A string is read at
the lead's copies (:func:`read_at`), not only at its own section: its longest repeat may be
a chance repeat elsewhere, as long as the section or longer. Copies in step keep the
lead's shift between them (to within the string's typical segment); a string that fails at
the lead's copies is read again where the lead and its members all are (the core: symbols
agreeing by chance around the lead's copies make them reach past the repeat the others
play), and the lead itself is read where it and its closest member both are.
"""

from __future__ import annotations

import math

import numpy as np

from .conf import NO_BOUND
from .alike import Alike
from .core_cover import cover_reading
from .in_step_weight import in_step_significance, in_step_weights
from .motifs import Timed
from .pairing import lead_segments
from .sections import Section, _cycles, lead_significance
from .shift_runs import Frame, candidates, grid_runs, long_runs
from .statistics import log10_choose

__all__: list[str] = []  # private: choice.py is the caller


def group_significance(strings: list[Timed], sections: list, intervals: dict[int, np.ndarray],
                       follows: list[float | None], group: list[int],
                       partners: dict[int, list[int]], level: float, clock=NO_BOUND
                       ) -> tuple[float, dict[int, Section]]:
    """The strongest reading of a group of sections in step: its significance and members.

    ``sections[i]`` is string ``i``'s Section, ``intervals[i]`` its copies' times,
    ``follows[i]`` its follow rate (None: its match rate), ``partners`` who is in step
    with whom, ``level`` log10 of ``alpha``. The members map to the section each is read
    at (its own, or one found at the lead's copies); members that move together count once
    (:class:`~psgs.induce.pal.alike.Alike`; weighed again so when the strongest
    reading holds such members). Returns ``(inf, {})`` when no lead
    has a partner that beats chance. ``clock`` (a :class:`~psgs.budget.Budget`) is read
    before each lead.

    Examples
    --------
    >>> from psgs.induce.pal.sections import find_section
    >>> rng = np.random.default_rng(1)
    >>> codes = []
    >>> for _ in range(2):
    ...     section = rng.integers(0, 8, 10)
    ...     codes.append(np.concatenate((rng.integers(0, 8, 5), section, rng.integers(0, 8, 3),
    ...                                  section, rng.integers(0, 8, 12))))
    >>> strings = [Timed.from_codes(c, np.ones(len(c)), 0.0) for c in codes]
    >>> rates = [s.match_rate for s in strings]
    >>> sections = [find_section(c, 2, 40, q) for c, q in zip(codes, rates)]
    >>> times = {i: s.copy_times(x) for i, (s, x) in enumerate(zip(strings, sections))}
    >>> significance, members = group_significance(strings, sections, times, [None, None],
    ...                                            [0, 1], {0: [1], 1: [0]}, -2.0)
    >>> sorted(members), significance < -2.0
    ([0, 1], True)
    """
    best = _strongest(strings, sections, intervals, follows, group, partners, level, clock)
    # members that move together count once (alike.Alike), weighed again so only
    # when the strongest reading holds such members: counting fewer members only makes a
    # reading weaker (each adds T_j + log10 of at most N - 1 <= level < 0), so the
    # strongest without any stays the strongest
    alike = Alike(strings, level)
    if best[0] <= level:
        first, *rest = best[1]
        # (asked at the copies the lead was read at and at its own, as its readings ask; a
        # string read at another's copies may lead too, and has no own)
        places = [strings[first].copy_times(best[1][first]), *(
            [intervals[first]] if first in intervals else [])]
        if any(alike.counted(first, rest, at) != rest for at in places):
            best = _strongest(strings, sections, intervals, follows, group, partners, level,
                              clock, alike)
    return best


def _strongest(strings: list[Timed], sections: list, intervals: dict[int, np.ndarray],
               follows: list[float | None], group: list[int], partners: dict[int, list[int]],
               level: float, clock, alike: Alike | None = None
               ) -> tuple[float, dict[int, Section]]:
    """:func:`group_significance`, every member's weight counted (``alike`` None) or
    only those ``alike`` counts."""
    best: tuple[float, dict[int, Section]] = (math.inf, {})
    reads = _Reads(strings, follows, [intervals[lead] for lead in group])
    for lead in group:
        clock.check()
        best = min(best, _led_by(strings, lead, sections[lead], intervals[lead], follows,
                                 partners[lead], sections, intervals, level, reads, alike),
                   key=lambda b: b[0])
        reads.done(intervals[lead])
    # a lead's own section may be a chance extension of the repeat the others play, which
    # puts the others' copies off its own: each member leads again, at the copies it was
    # read at
    for lead, section in list(best[1].items()):
        clock.check()
        if section is not sections[lead]:
            at = strings[lead].copy_times(section)
            best = min(best, _led_by(strings, lead, section, at, follows, [], sections,
                                     intervals, level, alike=alike), key=lambda b: b[0])
    if best[0] > level:
        # two partners whose copies each reach past the repeat they share, on other sides,
        # are each off the other's copies: weighed as one event where both are
        best = min(best, _paired(strings, sections, intervals, follows, group, partners,
                                 level, alike), key=lambda b: b[0])
    return best


def _paired(strings: list[Timed], sections: list, intervals: dict[int, np.ndarray],
            follows: list[float | None], group: list[int], partners: dict[int, list[int]],
            level: float, alike: Alike | None = None) -> tuple[float, dict[int, Section]]:
    """The strongest pair of partners in ``group`` read where both their sections are, as one
    event (:func:`pair_significance`), every other string read there as a member must be
    (with ``alike``: no pair that moves together, and only the members it counts weighed)."""
    best: tuple[float, dict[int, Section]] = (math.inf, {})
    for a in group:
        for b in partners[a]:
            if b <= a or b not in group or len(intervals[a]) != 2 or len(intervals[b]) != 2:
                continue
            pair = pair_reading(strings, (a, b), (intervals[a], intervals[b]), follows)
            if pair is None or pair[0] > level or pair[0] >= best[0]:
                continue
            weight, members, core = pair
            if alike is not None and alike.dependent(a, b, core):
                continue  # (one string's repeat, not two: read where the pair is)
            rest = _read_the_rest(strings, core, follows, members, level)
            counted = set(rest if alike is None else alike.counted(a, [b, *rest], core))
            for j, (again, found) in rest.items():
                members[j] = found
                weight += again if j in counted else 0.0
            best = (weight, members)
    return best


def pair_reading(strings: list[Timed], pair: tuple[int, int],
                 copies: tuple[np.ndarray, np.ndarray], follows: list[float | None]
                 ) -> tuple[float, dict[int, Section], np.ndarray] | None:
    """Two strings read where both of their two copies ``copies`` are, weighed as one event:
    ``(significance, {string: the repeat read}, the shared copies' times)``, or None when
    their copies share no time or either holds no exact repeat in step there.

    The significance is :func:`pair_significance` of the symbols each string has inside
    the shared copies (its own repeat reaching past them is its own, weighed in its own
    string) and the pair's choice among the strings, ``log10 C(N, 2)``.

    Examples
    --------
    >>> rng = np.random.default_rng(3)
    >>> section = [[0, 1, 2, 3, 0, 2, 1, 3, 2, 0], [3, 2, 0, 1, 3, 1, 0, 2, 0, 3]]
    >>> codes = [np.concatenate((rng.integers(0, 4, 4) + 4, s, [9, 8], s,
    ...                          rng.integers(0, 4, 12) + 4)) for s in section]
    >>> strings = [Timed.from_codes(c, np.ones(len(c)), 0.0) for c in codes]
    >>> at = np.array([[4.0, 14.0], [16.0, 26.0]])
    >>> weight, members, core = pair_reading(strings, (0, 1), (at, at), [None, None])
    >>> sorted(members), members[0].starts.tolist(), weight < -2
    ([0, 1], [4, 16], True)
    """
    core = _core(list(copies))
    if core is None:
        return None
    readings = {i: read_at(strings[i], core, follows[i]) for i in pair}
    if any(r is None for r in readings.values()):
        return None
    shared = [int(np.count_nonzero((strings[i].starts >= core[0, 0] - 1e-9)
                                   & (strings[i].ends <= core[0, 1] + 1e-9)))
              for i in pair]
    if min(shared) < 2:
        return None
    weight = (pair_significance([strings[i] for i in pair], shared,
                                [follows[i] for i in pair])
              + log10_choose(len(strings), 2))
    return weight, {i: r[1] for i, r in readings.items()}, core


def pair_significance(strings: list[Timed], lengths: list[int], follows: list[float | None]
                      ) -> float:
    """log10 of the expected number of pairs of windows at which two random strings both
    repeat themselves exactly, over ``lengths`` symbols each, at one shift.

    The shared repeat is placed once, in time: ``C(K, 2)`` ways, ``K = n - L + 1`` windows in
    the string that has the more of them; each string agrees with itself there with chance
    ``q r^(L-1)`` (its match rate, its follow rate or the match rate). No left-end term: the
    place is where both agree, not where either's repeat begins.

    Examples
    --------
    >>> codes = np.array([0, 1, 2, 3, 0, 1, 2, 3, 1, 3, 0, 2])
    >>> string = Timed.from_codes(codes, np.ones(12), 0.0)
    >>> round(pair_significance([string, string], [4, 4], [None, None]), 2)
    -3.26
    """
    places = max(log10_choose(len(s.codes) - length + 1, 2) for s, length in zip(strings, lengths))
    chance = 0.0
    for string, length, follow in zip(strings, lengths, follows):
        q, r = string.chance_rates(follow)
        if q <= 0 or r <= 0:
            return -math.inf
        chance += math.log10(q) + (length - 1) * math.log10(r)
    return places + chance


def _led_by(strings: list[Timed], lead: int, section: Section, lead_copies: np.ndarray,
            follows: list[float | None], partners: list[int], sections: list,
            intervals: dict[int, np.ndarray], level: float, reads: _Reads | None = None,
            alike: Alike | None = None) -> tuple[float, dict[int, Section]]:
    """:func:`group_significance` with one lead read at ``lead_copies``: every other string
    read there (its own section too when it is one of the lead's ``partners``; ``reads``
    keeps the readings other leads will ask for again; ``alike``: only the members it
    counts weighed; which members join does not depend on it)."""
    reads = _Reads(strings, follows, []) if reads is None else reads
    total = len(strings)
    # (a member's reading counts only this light or lighter: the lightest of the rest
    # need not be found; the slack keeps every reading the test below keeps, whatever the
    # float sum's rounding)
    need = level - math.log10(total - 1) + _SLACK if total > 1 else -math.inf
    joined: dict[int, Section] = {}
    weights = []
    # (the partners' own sections weighed at the lead's copies all at once)
    mates = set(partners)
    own = [j for j in range(total) if j != lead and j in mates]
    at_lead = dict(zip(own, in_step_weights([(strings[j], sections[j], intervals[j],
                                              lead_copies, follows[j]) for j in own])))
    # (only a lead of two copies reads the other strings at them: else its partners alone)
    for j in range(total) if len(lead_copies) == 2 else own:
        if j == lead:
            continue
        readings = []
        if j in at_lead:
            readings.append((at_lead[j], sections[j]))
        if len(lead_copies) == 2:
            again = reads.read(j, lead_copies, need)
            if again is not None:
                readings.append(again)
        if not readings:
            continue
        weight, found = min(readings, key=lambda r: r[0])
        if weight + math.log10(total - 1) <= level:
            joined[j] = found
            weights.append(weight)
    if joined and len(lead_copies) == 2:
        # a lead's copies may reach past the repeat the others play (symbols around its
        # copies agreeing by chance), which puts an exact member off them: every string
        # not yet in is read again where the lead and its members all are
        core = _core([lead_copies] + [_times(strings, sections, intervals, j, f)
                                      for j, f in joined.items()])
        if core is not None:
            for j, (again, found) in _read_the_rest(strings, core, follows, {lead, *joined},
                                                    level).items():
                joined[j] = found
                weights.append(again)
    if not joined:
        return math.inf, {}
    # the lead must be in step beyond chance too, read where it and the member it is most
    # in step with both are (the member's copies may reach past the lead's by chance
    # agreement, as the lead's past the member's): else a chance repeat of the others'
    # would lead them; it is reported as read there
    places = []
    for mate, found in joined.items():
        at = _times(strings, sections, intervals, mate, found)
        if len(at) == 2 and len(lead_copies) == 2:
            core = _core([at, lead_copies])
            at = at if core is None else core
        places.append(at)
    # (the lead's own section weighed at every member's copies but two at once)
    many = [at for at in places if len(at) != 2]
    weighed = iter(in_step_weights([(strings[lead], section, lead_copies, at, follows[lead])
                                    for at in many]))
    again = None
    read: dict[tuple, tuple[float, Section] | None] = {}  # (members often share their times)
    for at in places:
        if len(at) == 2:
            key = _times_key(at)
            if key not in read:
                read[key] = read_at(strings[lead], at, follows[lead], need)
            here = read[key]
        else:
            here = (next(weighed), section)
        if here is not None and (again is None or here[0] < again[0]):
            again = here
    if again is None or again[0] + math.log10(total - 1) > level:
        return math.inf, {}
    if alike is not None:  # (members that move with the lead or another add nothing)
        weight_of = dict(zip(joined, weights))
        weights = [weight_of[j] for j in alike.counted(lead, list(joined), lead_copies)]
    m = len(weights) + 1
    significance = (lead_significance(strings[lead], section, follows[lead]) + sum(weights)
                    + math.log10(total) + log10_choose(total - 1, m - 1))
    return significance, {lead: again[1], **joined}


def _times(strings: list[Timed], sections: list, intervals: dict[int, np.ndarray], j: int,
           found: Section) -> np.ndarray:
    """The times of string ``j``'s copies of ``found``: ``intervals[j]`` when it is its own
    section (they are its copies' times)."""
    return intervals[j] if found is sections[j] else strings[j].copy_times(found)


def _read_the_rest(strings: list[Timed], core: np.ndarray, follows: list[float | None],
                   taken, level: float) -> dict[int, tuple[float, Section]]:
    """Every string not in ``taken`` that plays the core (two copies' times) again at its
    shift beyond chance among the other strings read, as a member must be: ``{string: (its
    significance, the repeat read)}``, in string order. Each is weighed by how much of the
    core it covers (:func:`~psgs.induce.pal.core_cover.cover_reading`).

    Holm's step-down over the ``M`` strings read: the ``k``-th lightest (from 0) joins when
    it and every lighter one weigh at most ``level - log10(M - k)``; the chance of carrying
    in any random string at this reading is at most ``alpha``, as with ``level - log10(M)``
    for each, and a member read where others passed needs less.
    """
    left = [j for j in range(len(strings)) if j not in taken]
    readings = {j: cover_reading(strings[j], core, follows[j]) for j in left}
    ranked = sorted((found[0], j) for j, found in readings.items() if found is not None)
    out: dict[int, tuple[float, Section]] = {}
    for k, (weight, j) in enumerate(ranked):
        if weight > level - math.log10(len(left) - k):
            break
        out[j] = readings[j]
    return dict(sorted(out.items()))


class _Reads:
    """:func:`read_at` of the strings at lead copies, each answer kept while a lead still
    to come reads at the same times: sections in step often lie at the very same times
    (a string's copies are its segments' times), and each lead reads every string there.
    ``leads``: the copies each lead to come reads at, in turn (:meth:`done` after each);
    answers at other times are not kept, nor at more than ``_KEPT_TIMES`` times at once."""

    def __init__(self, strings: list[Timed], follows: list[float | None],
                 leads: list[np.ndarray]) -> None:
        self.strings, self.follows = strings, follows
        self.left: dict[tuple, int] = {}  # times -> leads still to read there
        for copies in leads:
            key = _times_key(copies)
            self.left[key] = self.left.get(key, 0) + 1
        self.kept: dict[tuple, dict] = {}

    def read(self, j: int, copies: np.ndarray, need: float) -> tuple[float, Section] | None:
        """``read_at(strings[j], copies, follows[j], need)``."""
        key = _times_key(copies)
        if self.left.get(key, 0) < 2 and key not in self.kept:
            return read_at(self.strings[j], copies, self.follows[j], need)
        if key not in self.kept:
            if len(self.kept) >= _KEPT_TIMES:
                return read_at(self.strings[j], copies, self.follows[j], need)
            self.kept[key] = {}
        answers = self.kept[key]
        if (j, need) not in answers:
            answers[j, need] = read_at(self.strings[j], copies, self.follows[j], need)
        return answers[j, need]

    def done(self, copies: np.ndarray) -> None:
        """A lead reading at ``copies`` is done: their answers go with the last one."""
        key = _times_key(copies)
        if key in self.left:
            self.left[key] -= 1
            if self.left[key] <= 0:
                del self.left[key]
                self.kept.pop(key, None)


def _times_key(copies: np.ndarray) -> tuple:
    """Copies' times as a key: equal when every time is the same."""
    return copies.shape, copies.dtype.str, copies.tobytes()


#: the most lead copies' times whose readings are kept at once (each: one per string)
_KEPT_TIMES = 8


def _core(copies: list[np.ndarray]) -> np.ndarray | None:
    """Where every one of these pairs of copies is: each copy's times shared by all, or
    None when some copy shares none."""
    core = np.column_stack((np.max([c[:, 0] for c in copies if len(c) == 2], axis=0),
                            np.min([c[:, 1] for c in copies if len(c) == 2], axis=0)))
    return core if np.all(core[:, 1] > core[:, 0]) else None


#: what a caller adds to the weight it needs (its own test, a sum, may round either way)
_SLACK = 1e-9
#: grids of more shifts-by-positions than this are first searched for long runs alone
_GRID_CELLS = 1 << 16
#: the shortest runs that search looks for, tried in turn before the grid
_RUN_FLOORS = (48, 12)


def read_at(string: Timed, lead: np.ndarray, follow: float | None, need: float | None = None
            ) -> tuple[float, Section] | None:
    """The exact repeat of ``string`` at two lead copies' times that is least likely by
    chance (:func:`in_step_significance`), or None.

    Every maximal run of agreeing symbols between a window at the first copy and one at
    the second (all shifts between the segments under them), and each run's part under
    the two copies where the run reaches past them, that pairs with both copies, does not
    overlap itself, is no cycle and keeps the lead's shift; None when none is in step.
    Among equally unlikely ones, the first in the grid's order: block by block of shifts
    (a block's shifts in order, their runs in order, each run's windows before the parts
    of the block's runs under the lead's copies).

    The runs of every shift are found at once (shifts as the rows of one array), and
    the candidates weighed from the least bound on their weight up (the bound is their
    chance agreement, which only the length sets: the other terms of
    :func:`in_step_significance` are counts, at least one, and the symbols before the
    copies disagree with chance ``1 - r`` at the least); the search stops at the first
    bound no lighter than the best weight found: the same repeat as weighing every
    candidate in that order. On long copies (a grid of more than
    ``_GRID_CELLS`` shifts by positions) the runs of 48, then 12, symbols or more are
    found first from equal windows (:mod:`~psgs.induce.pal.shift_runs`) and weighed alone;
    their best is the answer when every shorter run's least bound is heavier, as it is
    when the copies share a long repeat (a movement's section played twice: 23 s to under
    1 s on a quartet of 8,000 to 12,000 notes a voice). With ``need`` (log10), a
    caller that keeps only readings that light says so: the answer is the same when it
    is that light and None otherwise, on long copies only the runs whose least bound
    reaches ``need`` are looked for, and no candidate whose least bound is heavier than
    ``need`` is weighed (none at all when the longest run's is).

    Examples
    --------
    >>> codes = np.array([5, 1, 2, 3, 4, 6, 1, 2, 3, 4, 7, 0, 6, 5])
    >>> string = Timed.from_codes(codes, np.ones(14), 0.0)
    >>> weight, found = read_at(string, np.array([[1.0, 5.0], [6.0, 10.0]]), None)
    >>> found.motif.tolist(), found.starts.tolist()
    ([1, 2, 3, 4], [1, 6])
    """
    frame = _frame_of(string, lead)
    if frame is None:
        return None
    best = _read_runs(frame, follow, need)
    return best if need is None or (best is not None and best[0] <= need) else None


def _frame_of(string: Timed, lead: np.ndarray) -> Frame | None:
    """What :func:`read_at` looks at, or None when a copy overlaps no segment or there is
    no shift or position to look at: every shift that takes a segment under the first
    copy to one under the second, and every position within ``reach`` segments of the
    first copy (as many as lie under both copies)."""
    n = len(string.codes)
    segments = lead_segments(string, lead)
    if segments is None:
        return None
    first, second = segments
    reach = len(first) + len(second)
    low, top = max(1, int(second[0] - first[-1])), int(second[-1] - first[0])
    lo = max(0, int(first[0]) - reach)
    width = max(0, min(n - low, int(first[-1]) + reach + 1) - lo)
    if top < low or width < 2:
        return None
    return Frame(string, lead, first, second, reach, low, top, lo, width)


def _read_runs(frame: Frame, follow: float | None, need: float | None
               ) -> tuple[float, Section] | None:
    """:func:`read_at`'s search: the lightest candidate, or (with ``need``) possibly None
    when none is as light as ``need``."""
    string, n = frame.string, len(frame.string.codes)
    q, r = string.chance_rates(follow)
    if frame.width * (frame.top - frame.low + 1) <= _GRID_CELLS or q <= 0 or not 0 < r < 1:
        runs = grid_runs(frame)
        # (with ``need``: no candidate is longer than the longest run, and none weighs less
        # than its length's bound, so a longest run whose bound is heavier keeps none)
        if (need is not None and q > 0 and 0 < r < 1 and len(runs[0])
                and _bound(q, r, int(np.max(runs[1] - runs[0]))) > need):
            return None
        return _lightest(frame, candidates(frame, *runs), follow, need=need)
    # (a candidate weighed in one pass keeps its weight in the next: a string that plays
    # one short block over and over gives the same cycles to every pass)
    weighed: dict = {}
    if need is not None:
        # a candidate of ``length`` symbols weighs at least its bound (the chance agreement
        # and the least left-end term): only runs as long as the first whose bound reaches
        # ``need`` can be kept, and among them the lightest is the lightest of all
        floor = 2
        while _bound(q, r, floor) > need and floor <= n:
            floor += 1
        runs = long_runs(frame, floor)
        if runs is not None:
            return _lightest(frame, candidates(frame, *runs), follow, weighed, need)
    # long copies: the grid of every shift by every position is most of the cost, and
    # only long runs can be the lightest. The runs of ``floor`` symbols or more, found
    # from equal windows, are weighed first; when every shorter run's least bound is
    # heavier than the best of them, the grid could not give another answer (the
    # search stops at the first bound no lighter than the best, and the longer runs'
    # candidates keep their order among themselves)
    for floor in _RUN_FLOORS:
        runs = long_runs(frame, floor)
        if runs is None:
            break  # (too many equal windows, or a hash collision: the grid decides)
        best = _lightest(frame, candidates(frame, *runs), follow, weighed)
        # (with windows of two symbols every run is found: the grid's answer, None too)
        if floor <= 2 or (best is not None and _bound(q, r, floor - 1) > best[0]):
            return best
    return _lightest(frame, candidates(frame, *grid_runs(frame)), follow, weighed)


def _bound(q: float, r: float, length: int, inner: bool = False) -> float:
    """The least weight a candidate of ``length`` symbols can have (``q`` the match rate,
    ``r`` the follow rate): :func:`in_step_significance`'s chance term at two copies, and its
    least left-end term unless the candidate is a run's ``inner`` part (no left end)."""
    if q <= 0 or r <= 0:
        return -math.inf
    return ((math.log10(q) + (length - 1) * math.log10(r))
            + (0.0 if inner else math.log10(max(1e-300, 1 - r))))


def _lightest(frame: Frame, found, follow: float | None, weighed: dict | None = None,
              need: float | None = None) -> tuple[float, Section] | None:
    """The lightest candidate in step (:func:`in_step_significance`), the first among
    equals, weighed from the least bound on their weight up; ``weighed`` keeps each
    candidate's weight (inf: a cycle, or not in step) for another pass. With ``need``, the
    candidates whose bound is heavier than it are not weighed: the answer is the same when
    it is that light, and may be None or heavier otherwise."""
    lengths, ats, shifted, clipped = found
    weighed = {} if weighed is None else weighed
    if not lengths:
        return None
    string, lead = frame.string, frame.lead
    codes, starts, ends = string.codes, string.starts, string.ends
    q, r = string.chance_rates(follow)
    bounds = {key: _bound(q, r, *key) for key in set(zip(lengths, clipped))}
    best, best_order = None, -1
    for bound, order in sorted((bounds[key], k) for k, key in enumerate(zip(lengths, clipped))):
        if need is not None and bound > need:
            break  # (every candidate left is heavier than the caller keeps)
        if best is not None and bound >= best[0]:
            if bound > best[0]:
                break  # (every candidate left is at least as heavy)
            if order > best_order:
                continue  # (at most as light as the best, and after it)
        length, s, shift = lengths[order], ats[order], shifted[order]
        key = (length, s, shift, clipped[order])
        if key in weighed:
            weight, section = weighed[key]
        elif _cycles(codes, (s, s + shift), length):
            weight, section = weighed.setdefault(key, (math.inf, None))
        else:
            motif = codes[s:s + length].copy()
            where = np.array([[starts[s], ends[s + length - 1]],
                              [starts[s + shift], ends[s + length - 1 + shift]]])
            section = Section(motif, np.array([s, s + shift], dtype=np.int64), 0.0)
            weight = in_step_significance(string, section, where, lead, follow,
                                          maximal=not clipped[order])
            weighed[key] = (weight, section)
        if weight < math.inf and (best is None or weight < best[0]
                                  or (weight == best[0] and order < best_order)):
            best, best_order = (weight, section), order
    return best  # (None when no candidate keeps the lead's shift)
