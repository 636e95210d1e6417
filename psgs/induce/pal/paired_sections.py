"""Sections that two strings play at the same times, found by the pair, not by each string.

A string's section (:mod:`~psgs.induce.pal.sections`) is its own longest repeat, and groups
in step are formed from those. Where two strings play a short section twice at the same
times, either one's longest repeat may be a chance repeat elsewhere, as long or longer (a
random string of 60 symbols over 4 letters holds an 8-symbol repeat one time in 13), and
the two are never paired, though a shared repeat at one shift is far stronger evidence than
either string's alone. So, for the strings that no section group took, every exact repeat
of two copies long enough to count is listed (:func:`exact_repeats`), the repeats of two
strings whose copies lie at the same times are paired, and each pair is weighed as one
event where both are (:func:`~psgs.induce.pal.in_step.pair_reading`: the chance of two
random strings both repeating at one shift, over every place and every pair of strings);
every other string is read there as a member of a group must be.
"""

from __future__ import annotations

import math
import numpy as np

from .conf import NO_BOUND
from .in_step import _core, _read_the_rest, pair_reading
from .motifs import Timed
from .pairing import keeps_shift
from .sections import (Section, _cycles, _longest_repeated, _repeated, _window_hashes,
                       follow_rate)
from .statistics import log10_choose

__all__: list[str] = []  # private: choice.py is the caller

#: bytes counted against ``max_bytes`` for each repeat listed (its three numbers)
REPEAT_BYTES = 24


def exact_repeats(codes: np.ndarray, low: int, clock=NO_BOUND) -> np.ndarray:
    """Every maximal run of agreement between a string and itself shifted, at a shift of
    ``low`` symbols or more, ``low`` symbols or longer: rows ``(start, start + shift,
    length)`` in order.

    ``codes[start + k] == codes[start + shift + k]`` for ``k < length``, and neither run
    can grow (the symbols before and after disagree, or the string ends). A run longer than
    its shift holds two copies apart wherever they begin in it (``x a b c a b c y``: ``a b
    c`` at 1 and 4, ``b c a`` ...); a run of twice its shift or more is a block played
    three times or more, left to the search for more copies. ``clock`` (a
    :class:`~psgs.induce.pal.conf.Bounds`) is read for each window of a group of equal
    ones and counts :data:`REPEAT_BYTES` a run.

    Examples
    --------
    >>> codes = np.array([7, 0, 1, 2, 3, 8, 0, 1, 2, 3, 9, 1, 2])
    >>> exact_repeats(codes, 3).tolist()
    [[1, 6, 4]]
    >>> exact_repeats(codes, 2).tolist()
    [[1, 6, 4], [2, 11, 2], [7, 11, 2]]
    >>> exact_repeats(np.array([5, 0, 1, 2, 0, 1, 2, 0, 6]), 3).tolist()  # a run of 5
    [[1, 4, 4]]
    """
    n = len(codes)
    if low < 1 or 2 * low > n:
        return np.empty((0, 3), dtype=np.int64)
    hashes = _window_hashes(codes, low)
    order = np.argsort(hashes, kind="stable")
    ordered = hashes[order]
    begins = np.concatenate(([0], np.flatnonzero(np.diff(ordered)) + 1))
    sizes = np.diff(np.concatenate((begins, [len(ordered)])))
    found = []
    for g in np.flatnonzero(sizes >= 2).tolist():
        clock.check()
        before = len(found)
        where = order[begins[g]:begins[g] + sizes[g]].tolist()  # ascending positions
        for k, p in enumerate(where):
            clock.check()  # (a group holds as many pairs as its windows squared)
            for q in where[k + 1:]:
                shift = q - p
                if shift < low or (p and codes[p - 1] == codes[q - 1]):
                    continue  # the copies would overlap, or the run begins further left
                if not np.array_equal(codes[p:p + low], codes[q:q + low]):
                    continue  # (a hash collision)
                length = low
                while q + length < n and codes[p + length] == codes[q + length]:
                    length += 1
                if length < 2 * shift:
                    found.append((p, q, length))
        clock.keep(REPEAT_BYTES * (len(found) - before))
    if not found:
        return np.empty((0, 3), dtype=np.int64)
    return np.array(sorted(found), dtype=np.int64)


def paired_groups(strings: list[Timed], follows: list[float | None], level: float,
                  free: list[int], copies: int, clock=NO_BOUND
                  ) -> list[tuple[float, dict[int, Section]]]:
    """Groups in step formed from pairs of the strings ``free`` repeating at the same times:
    ``(significance, {member: the repeat read})`` each, strongest first, no string in two.

    Only for two copies (``copies`` 2; an empty list otherwise): a pair is read where both
    its repeats are, and the reading of a string at copies is of two. A pair is kept when
    its significance (:func:`~psgs.induce.pal.in_step.pair_reading`) reaches ``level``; the
    strongest pairs are taken first, each with every string not yet taken that is in step
    at the pair's copies beyond chance among the other strings.

    Examples
    --------
    >>> rng = np.random.default_rng(5)
    >>> def draw(k):  # k symbols over 4 letters, no two neighbours equal
    ...     return np.cumsum(rng.integers(1, 4, k)) % 4
    >>> section = [draw(8), draw(8)]
    >>> codes = [np.concatenate((draw(6), s, draw(5) + 4, s, draw(30))) for s in section]
    >>> codes.append(draw(57))
    >>> strings = [Timed.from_codes(c, np.ones(len(c)), 0.0) for c in codes]
    >>> [sorted(members) for _, members in paired_groups(strings, [None] * 3, -2.0,
    ...                                                   [0, 1, 2], 2)]
    [[0, 1]]
    """
    if copies != 2 or len(free) < 2:
        return []
    total = len(strings)
    terms = {i: _term(strings[i], follows[i]) for i in free}
    # the longest repeat of each string: what it can bring to a pair at most
    longest = {}
    for i in free:
        clock.check()
        codes = strings[i].codes
        longest[i] = (_longest_repeated(codes, 2, 2, len(codes) // 2)
                      if len(codes) >= 4 and _repeated(codes, 2, 2, first=True) else 0)
    # a pair's significance is its places, log10 C(n - L + 1, 2) for the string that has
    # more (at least half its own: L <= n / 2), its strings' terms and log10 C(N, 2); each
    # string is given half its least places, so that two runs' bounds add up to the pair's:
    # a pair that reaches the level holds a run at least half as strong as it needs, found
    # in its own string; the other string is read where that run is
    half = {i: log10_choose(len(strings[i].codes) - len(strings[i].codes) // 2 + 1, 2) / 2
            for i in free}
    need = level - log10_choose(total, 2)
    pairs: dict[tuple[int, int], tuple[float, dict[int, Section], np.ndarray]] = {}
    joints: dict[tuple[int, int], _JointString] = {}
    for i in free:
        q, r = terms[i]
        low = _fewest(q, r, need / 2 - half[i], longest[i])
        if low is None:
            continue
        codes = strings[i].codes
        for p, p2, length in exact_repeats(codes, low, clock).tolist():
            shift, size = p2 - p, min(length, p2 - p)
            # a run longer than its shift: its first two copies and its last two
            for start in dict.fromkeys((p, p + length - size)):
                if _cycles(codes, (start, start + shift), size):
                    continue
                mine = strings[i].intervals(np.array([start, start + shift]), size)
                bound = need - (q + (size - 1) * r + half[i])
                for j in free:
                    if j == i:
                        continue
                    clock.check()
                    theirs = _agreeing(strings[j], mine, terms[j], bound - half[j])
                    if theirs is None:
                        continue
                    key = (i, j) if i < j else (j, i)
                    core = _core([mine, theirs])
                    if core is None:
                        continue
                    # the two read as one string first: the cheaper test, and the one that
                    # fails where the strings move together
                    if key not in joints:
                        joints[key] = _JointString.of(strings[key[0]], strings[key[1]])
                    if joints[key].significance(core) + log10_choose(total, 2) > level:
                        continue
                    reading = pair_reading(strings, key, (core, core), follows)
                    if reading is not None and reading[0] <= level and (
                            key not in pairs or reading[0] < pairs[key][0]):
                        pairs[key] = reading
    taken = set(range(total)) - set(free)
    groups = []
    for (i, j), (weight, members, core) in sorted(pairs.items(), key=lambda kv: kv[1][0]):
        if i in taken or j in taken:
            continue
        clock.check()
        for k, (again, found) in _read_the_rest(strings, core, follows, taken | {i, j},
                                                level).items():
            members[k] = found
            weight += again
        taken.update(members)
        groups.append((weight, members))
    return groups


class _JointString:
    """Two strings as one, a symbol a stretch of time in which neither changes (the pair of
    their symbols), with its own match and follow rates: the chance of a repeat of both at
    once read from how the two move together, not as if they were independent (voices of
    one piece move together: a repeat of one is half a repeat of the other)."""

    def __init__(self, starts, ends, codes) -> None:
        self.starts, self.ends, self.codes = starts, ends, codes
        counts = np.bincount(codes)
        self.match = float(np.sum((counts / len(codes)) ** 2))
        follow = follow_rate(codes)
        self.follow = self.match if follow is None else follow

    @classmethod
    def of(cls, a: Timed, b: Timed) -> "_JointString":
        cuts = np.unique(np.concatenate((a.starts, a.ends, b.starts, b.ends)))
        lo, hi = max(a.starts[0], b.starts[0]), min(a.ends[-1], b.ends[-1])
        cuts = cuts[(cuts >= lo) & (cuts <= hi)]
        middles = (cuts[:-1] + cuts[1:]) / 2
        at_a = np.searchsorted(a.ends, middles, side="right")
        at_b = np.searchsorted(b.ends, middles, side="right")
        keys = a.codes[np.minimum(at_a, len(a.codes) - 1)] * (int(b.codes.max()) + 1) + \
            b.codes[np.minimum(at_b, len(b.codes) - 1)]
        _, codes = np.unique(keys, return_inverse=True)
        return cls(cuts[:-1], cuts[1:], codes.astype(np.int64))

    def significance(self, core: np.ndarray) -> float:
        """log10 of the chance of an exact repeat of the joint string as long as its
        stretches inside ``core``'s first copy, at some pair of places."""
        inside = int(np.count_nonzero((self.starts >= core[0, 0] - 1e-9)
                                      & (self.ends <= core[0, 1] + 1e-9)))
        if inside < 1 or self.match <= 0 or self.follow <= 0:
            return 0.0
        places = log10_choose(max(len(self.codes) - inside + 1, 2), 2)
        return places + math.log10(self.match) + (inside - 1) * math.log10(self.follow)


def _agreeing(string: Timed, copies: np.ndarray, term: tuple[float, float],
              need: float) -> np.ndarray | None:
    """The times of the longest exact repeat of ``string`` inside the first of ``copies``
    and at their shift, when its chance (``term``: log10 of a first symbol's and each
    further one's) reaches ``need``; else None.

    A segment repeats when a segment of the same symbol begins the shift later, to within
    half the string's median segment (the times of two strings never agree to the float).
    """
    (a, b), (c, _) = copies.tolist()
    shift = c - a
    first = np.flatnonzero((string.starts >= a - 1e-9) & (string.ends <= b + 1e-9))
    if len(first) < 2:
        return None
    tolerance = float(np.median(string.ends - string.starts)) / 2
    target = string.starts[first] + shift
    at = np.clip(np.searchsorted(string.starts, target), 1, len(string.codes) - 1)
    at = np.where(np.abs(string.starts[at - 1] - target) < np.abs(string.starts[at] - target),
                  at - 1, at)
    ok = (np.abs(string.starts[at] - target) <= tolerance) & (
        string.codes[at] == string.codes[first]) & (at > first[-1])
    # runs of agreeing segments whose partners follow one another as they do
    step = np.concatenate(([False], ok[1:] & ok[:-1] & (np.diff(at) == np.diff(first))))
    if not ok.any():
        return None
    starts = np.flatnonzero(ok & ~step)
    lengths = np.array([_run_length(step, u) for u in starts.tolist()])
    best = int(np.argmax(lengths))
    length, u = int(lengths[best]), int(starts[best])
    q, r = term
    if length < 2 or q + (length - 1) * r > need:
        return None
    k0, k1 = first[u], first[u + length - 1]
    m0, m1 = at[u], at[u + length - 1]
    return np.array([[string.starts[k0], string.ends[k1]], [string.starts[m0], string.ends[m1]]])


def _run_length(step: np.ndarray, u: int) -> int:
    """How many segments from ``u`` on agree, each following the one before."""
    v = u + 1
    while v < len(step) and step[v]:
        v += 1
    return v - u


def _term(string: Timed, follow: float | None) -> tuple[float, float]:
    """log10 of a string's chance that its first symbol repeats, and each further one:
    what :func:`~psgs.induce.pal.in_step.pair_significance` adds up (0 when it cannot)."""
    q = string.match_rate
    r = q if follow is None else follow
    if q <= 0 or r <= 0:
        return 0.0, 0.0
    return math.log10(q), math.log10(r)


def _fewest(q: float, r: float, need: float, longest: int) -> int | None:
    """The fewest symbols (two at least) of a repeat whose chance ``q + (L - 1) r`` reaches
    ``need``, or None when even ``longest`` does not."""
    if longest < 2:
        return None
    if r >= 0:
        return 2 if q <= need else None
    length = max(2, math.ceil((need - q) / r + 1 - 1e-9))
    return length if length <= longest else None
