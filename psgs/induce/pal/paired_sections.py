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
from .sections import (Section, _cycles, _longest_repeated, _repeated, follow_rate,
                       prefix_hashes, window_hash)
from .statistics import log10_choose

__all__: list[str] = []  # private: choice.py is the caller

#: bytes counted against ``max_bytes`` for each repeat listed (its three numbers)
REPEAT_BYTES = 24
#: bytes counted for each pair of strings tested or kept (a joint string's numbers, a reading)
JOINT_BYTES = 512


def exact_repeats(codes: np.ndarray, low: int, clock=NO_BOUND, hashed=None) -> np.ndarray:
    """Every maximal run of agreement between a string and itself shifted, at a shift of
    ``low`` symbols or more, ``low`` symbols or longer: rows ``(start, start + shift,
    length)`` in order.

    ``codes[start + k] == codes[start + shift + k]`` for ``k < length``, and neither run
    can grow (the symbols before and after disagree, or the string ends). A run longer than
    its shift holds two copies apart wherever they begin in it (``x a b c a b c y``: ``a b
    c`` at 1 and 4, ``b c a`` ...); a run of twice its shift or more is a block played
    three times or more, left to the search for more copies. ``clock`` (a
    :class:`~psgs.induce.pal.conf.Bounds`) is read for each window of a group of equal
    ones (its runs with the later ones are found at once, each run's length by halving
    on prefix hashes, then checked symbol by symbol) and counts :data:`REPEAT_BYTES` a run
    before it is kept. ``hashed``: the string's
    :func:`~psgs.induce.pal.sections.prefix_hashes`, when the caller has them.

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
    prefix, powers = prefix_hashes(codes) if hashed is None else hashed
    hashes = window_hash(prefix, powers, np.arange(n - low + 1), low)
    order = np.argsort(hashes, kind="stable")
    ordered = hashes[order]
    begins = np.concatenate(([0], np.flatnonzero(np.diff(ordered)) + 1))
    sizes = np.diff(np.concatenate((begins, [len(ordered)])))
    found = []
    for g in np.flatnonzero(sizes >= 2).tolist():
        where = order[begins[g]:begins[g] + sizes[g]]  # ascending positions
        for k in range(len(where) - 1):
            clock.check()  # (a group holds as many pairs as its windows squared)
            p, q = int(where[k]), where[k + 1:]
            # the copies apart, and where the run begins (the symbols before disagree)
            q = q[q - p >= low]
            if p:
                q = q[codes[q - 1] != codes[p - 1]]
            q = q[np.all(codes[q[:, None] + np.arange(low)] == codes[p:p + low], axis=1)] \
                if len(q) else q  # (a hash collision)
            if not len(q):
                continue
            # each run's length, up to twice its shift (longer is a block played three
            # times or more): the longest agreeing prefix, by halving on prefix hashes
            shift = q - p
            lo, hi = np.full(len(q), low), np.minimum(n - q, 2 * shift)
            while np.any(lo < hi):
                mid = (lo + hi + 1) // 2
                same = (window_hash(prefix, powers, p, mid)
                        == window_hash(prefix, powers, q, mid))
                lo, hi = np.where(same, mid, lo), np.where(same, hi, mid - 1)
            kept = lo < 2 * shift
            rows = np.column_stack((np.full(np.count_nonzero(kept), p), q[kept], lo[kept]))
            rows = rows[[_exact(codes, *row) for row in rows.tolist()]]
            clock.keep(REPEAT_BYTES * len(rows))
            found.append(rows)
    if not found:
        return np.empty((0, 3), dtype=np.int64)
    out = np.concatenate(found).astype(np.int64)
    return out[np.lexsort(out.T[::-1])]


def _exact(codes: np.ndarray, p: int, q: int, length: int) -> bool:
    """Whether the run of ``length`` at ``p`` and ``q`` agrees and ends there (the hashes
    said so; a collision would not)."""
    return bool(np.array_equal(codes[p:p + length], codes[q:q + length])
                and (q + length == len(codes) or codes[p + length] != codes[q + length]))


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
    tolerance = {i: float(np.median(strings[i].ends - strings[i].starts)) / 2 for i in free}
    pairs: dict[tuple[int, int], tuple[float, dict[int, Section], np.ndarray]] = {}
    joints: dict[tuple[int, int], _JointString] = {}
    for i in free:
        q, r = terms[i]
        low = _fewest(q, r, need / 2 - half[i], longest[i])
        if low is None:
            continue
        codes = strings[i].codes
        hashed = prefix_hashes(codes)
        for p, p2, length in exact_repeats(codes, low, clock, hashed).tolist():
            shift, size = p2 - p, min(length, p2 - p)
            # a run longer than its shift: its first two copies and its last two
            for start in dict.fromkeys((p, p + length - size)):
                clock.check()
                if _cycle(codes, hashed, start, start + shift, size):
                    continue
                mine = strings[i].intervals(np.array([start, start + shift]), size)
                bound = need - (q + (size - 1) * r + half[i])
                for j in free:
                    if j == i:
                        continue
                    clock.check()
                    for theirs in _agreeing(strings[j], mine, terms[j], bound - half[j],
                                            tolerance[j]):
                        key = (i, j) if i < j else (j, i)
                        core = _core([mine, theirs])
                        if core is None:
                            continue
                        # the two read as one string first: the cheaper test, and the one
                        # that fails where the strings move together
                        if key not in joints:
                            clock.keep(JOINT_BYTES)
                            joints[key] = _JointString.of(strings[key[0]], strings[key[1]])
                        if joints[key].significance(core) + log10_choose(total, 2) > level:
                            continue
                        reading = pair_reading(strings, key, (core, core), follows)
                        if reading is not None and reading[0] <= level and (
                                key not in pairs or reading[0] < pairs[key][0]):
                            if key not in pairs:
                                clock.keep(JOINT_BYTES)
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
    one piece move together: a repeat of one is half a repeat of the other). It keeps the
    two strings and three numbers, not the joint string (one is kept per pair tested)."""

    def __init__(self, a: Timed, b: Timed, size: int, match: float, follow: float) -> None:
        self.a, self.b, self.size, self.match, self.follow = a, b, size, match, follow

    @classmethod
    def of(cls, a: Timed, b: Timed) -> "_JointString":
        cuts = _cuts(a, b, max(a.starts[0], b.starts[0]), min(a.ends[-1], b.ends[-1]))
        middles = (cuts[:-1] + cuts[1:]) / 2
        at_a = np.searchsorted(a.ends, middles, side="right")
        at_b = np.searchsorted(b.ends, middles, side="right")
        keys = a.codes[np.minimum(at_a, len(a.codes) - 1)] * (int(b.codes.max()) + 1) + \
            b.codes[np.minimum(at_b, len(b.codes) - 1)]
        _, codes = np.unique(keys, return_inverse=True)
        counts = np.bincount(codes)
        match = float(np.sum((counts / max(len(codes), 1)) ** 2))
        follow = follow_rate(codes.astype(np.int64))
        return cls(a, b, len(codes), match, match if follow is None else follow)

    def significance(self, core: np.ndarray) -> float:
        """log10 of the chance of an exact repeat of the joint string as long as its
        stretches inside ``core``'s first copy, at some pair of places."""
        lo = max(self.a.starts[0], self.b.starts[0], core[0, 0] - 1e-9)
        hi = min(self.a.ends[-1], self.b.ends[-1], core[0, 1] + 1e-9)
        inside = len(_cuts(self.a, self.b, lo, hi)) - 1
        if inside < 1 or self.match <= 0 or self.follow <= 0:
            return 0.0
        places = log10_choose(max(self.size - inside + 1, 2), 2)
        return places + math.log10(self.match) + (inside - 1) * math.log10(self.follow)


def _cuts(a: Timed, b: Timed, lo: float, hi: float) -> np.ndarray:
    """The times from ``lo`` to ``hi`` at which either string's segments begin or end."""
    parts = []
    for string in (a, b):
        for times in (string.starts, string.ends):
            parts.append(times[np.searchsorted(times, lo, side="left"):
                               np.searchsorted(times, hi, side="right")])
    return np.unique(np.concatenate(parts))


def _cycle(codes: np.ndarray, hashed, first: int, second: int, size: int) -> bool:
    """:func:`~psgs.induce.pal.sections._cycles` of the copies of ``size`` at ``first`` and
    ``second``: every shift of half the window or less tried at once on the prefix hashes
    ``hashed`` (:func:`~psgs.induce.pal.sections.prefix_hashes`), the one found checked by
    the symbols."""
    prefix, powers = hashed
    span = second + size - first
    shifts = np.arange(1, size // 2 + 1)
    if not len(shifts):
        return False
    window = window_hash(prefix, powers, first, size - shifts) == \
        window_hash(prefix, powers, first + shifts, size - shifts)
    stretch = window_hash(prefix, powers, first, span - shifts) == \
        window_hash(prefix, powers, first + shifts, span - shifts)
    found = shifts[window & stretch]
    if not len(found):
        return False
    return _cycles(codes, np.array([first, second]), size) if not np.array_equal(
        codes[first + found[0]:second + size], codes[first:second + size - found[0]]) else True


def _agreeing(string: Timed, copies: np.ndarray, term: tuple[float, float],
              need: float, tolerance: float) -> list[np.ndarray]:
    """The times of the exact repeats of ``string`` inside the first of ``copies`` and at
    their shift whose chance (``term``: log10 of a first symbol's and each further one's)
    reaches ``need``: the one of the most segments and the one covering the most time (a
    few long segments can cover more of the other string's symbols), one or both.

    A segment repeats when a segment of the same symbol begins the shift later, to within
    ``tolerance`` (half the string's median segment: the times of two strings never agree
    to the float).
    """
    (a, b), (c, _) = copies.tolist()
    shift = c - a
    first = np.flatnonzero((string.starts >= a - 1e-9) & (string.ends <= b + 1e-9))
    if len(first) < 2:
        return []
    target = string.starts[first] + shift
    at = np.clip(np.searchsorted(string.starts, target), 1, len(string.codes) - 1)
    at = np.where(np.abs(string.starts[at - 1] - target) < np.abs(string.starts[at] - target),
                  at - 1, at)
    ok = (np.abs(string.starts[at] - target) <= tolerance) & (
        string.codes[at] == string.codes[first]) & (at > first[-1])
    # runs of agreeing segments whose partners follow one another as they do
    step = np.concatenate(([False], ok[1:] & ok[:-1] & (np.diff(at) == np.diff(first))))
    begins = np.flatnonzero(ok & ~step)
    if not len(begins):
        return []
    lengths = np.bincount(np.cumsum(ok & ~step)[ok])[1:]
    ends = begins + lengths - 1
    covered = string.ends[first[ends]] - string.starts[first[begins]]
    q, r = term
    out = []
    for best in dict.fromkeys((int(np.argmax(lengths)), int(np.argmax(covered)))):
        length, u, v = int(lengths[best]), int(begins[best]), int(ends[best])
        if length >= 2 and q + (length - 1) * r <= need:
            out.append(np.array([[string.starts[first[u]], string.ends[first[v]]],
                                 [string.starts[at[u]], string.ends[at[v]]]]))
    return out


def _term(string: Timed, follow: float | None) -> tuple[float, float]:
    """log10 of a string's chance that its first symbol repeats, and each further one:
    what :func:`~psgs.induce.pal.in_step.pair_significance` adds up (0 when it cannot)."""
    q, r = string.chance_rates(follow)
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
