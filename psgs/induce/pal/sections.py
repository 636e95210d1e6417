"""Long repeats of one string, and the one significance every candidate is ranked by.

The motif search of :mod:`~psgs.induce.pal.motifs` grows from the most
frequent digrams, so it finds what repeats *often*: a short figure played
five times beats a long section played twice. A repetition's evidence grows
with its length, its copies and its agreement alike, so this module adds a
second candidate per string, its **section**: the longest window that occurs
``min_copies`` times or more exactly and without overlap, with every such copy.

:func:`repeat_significance` is the significance both kinds of candidate are
weighed by (``docs/streams.md``, "Significance of a repetition"): the
expected number, in a random string of the same length and symbol
frequencies, of sets of ``copies`` windows of ``length`` symbols whose
copies after the first agree with the pattern in at least as many positions
as these do, counted over every set of window positions (a Bonferroni bound
over the positions).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .conf import NO_BOUND
from .motifs import Timed, keep_apart
from .statistics import log10_binom_sf, log10_choose

__all__: list[str] = []  # private: content.py is the caller

#: odd, so that it is invertible modulo 2**64 (the window hashes need its inverse)
_BASE = 0x9E3779B97F4A7C15
_INVERSE = pow(_BASE, -1, 1 << 64)


@dataclass(frozen=True)
class Section:
    """The longest exact repeat of a string: its codes, its copies' starts, its significance."""

    motif: np.ndarray
    starts: np.ndarray
    significance: float


def repeat_significance(n: int, length: int, copies: int, agreeing: int,
                        match_rate: float, follow_rate: float | None = None) -> float:
    """log10 of the expected chance repetitions as strong as this one (at most 0).

    Parameters
    ----------
    n : int
        The string's length, in symbols.
    length : int
        The pattern's length ``L``.
    copies : int
        How many copies ``c`` (non-overlapping windows of ``L`` symbols).
    agreeing : int
        In how many of the ``(c - 1) L`` positions of the copies after the
        first the symbol agrees with the pattern (``(c - 1) L`` when exact).
    match_rate : float
        The chance ``q`` that two symbols drawn from the string agree (the sum
        of its squared symbol shares).
    follow_rate : float, optional
        For exact copies: the chance ``r`` that the symbols after two equal
        symbols agree too (:func:`follow_rate`); a string whose symbols follow
        each other by rule (``B G R Y`` of motion) repeats exactly far more
        often than its symbol shares say. Without it, ``r = q``.

    Returns
    -------
    float
        ``min(0, log10(C(n - L + 1, c) * P))``: ``P = (q r^(L-1))^(c-1)`` for
        exact copies, ``P(Binomial((c - 1) L, q) >= agreeing)`` otherwise.

    Examples
    --------
    A 40-symbol section twice in 800 symbols is far less likely by chance than
    a 4-symbol figure five times:

    >>> round(repeat_significance(800, 40, 2, 40, 0.1), 1)
    -34.5
    >>> round(repeat_significance(800, 4, 5, 16, 0.1), 1)
    -3.6
    >>> round(repeat_significance(800, 40, 2, 40, 0.1, follow_rate=0.5), 1)  # by rule
    -7.3
    """
    windows = n - length + 1
    if copies < 2 or windows < copies or length < 1:
        return 0.0
    sets = log10_choose(windows, copies)
    if agreeing >= (copies - 1) * length and follow_rate is not None:
        if match_rate <= 0 or follow_rate <= 0:
            return -math.inf
        tail = (copies - 1) * (math.log10(match_rate) + (length - 1) * math.log10(follow_rate))
    else:
        tail = log10_binom_sf(agreeing, (copies - 1) * length, match_rate)
    return min(0.0, sets + tail)


def lead_significance(string: Timed, section: Section, follow: float | None) -> float:
    """log10 of the expected number of maximal exact repeats as strong as ``section``.

    ``[C(K - 1, c) (1 - r^(c-1)) + C(K - 1, c - 1)] * P``: ``C(K, c)``, ``K = n - c (L - 1)``,
    is the number of ways to place ``c`` windows of ``L`` symbols apart in ``n``, ``P =
    (q r^(L-1))^(c-1)`` the chance that they agree; a repeat is counted once, at its left
    end, where the symbols before its copies do not all agree (chance ``1 - r^(c-1)``) or
    its first copy opens the string.

    Examples
    --------
    >>> codes = np.array([0, 1, 2, 3, 4, 5, 1, 2, 3, 4, 6, 7])
    >>> string = Timed.from_codes(codes, np.ones(12), 0.0)
    >>> round(lead_significance(string, Section(codes[1:5], np.array([1, 6]), -1.0), None), 2)
    -2.3
    """
    n, length, copies = len(string.codes), len(section.motif), len(section.starts)
    q, r = string.chance_rates(follow)
    if q <= 0 or r <= 0:
        return -math.inf
    # c windows of L symbols apart in n symbols: C(n - c (L - 1), c) sets, of which
    # C(n - c (L - 1) - 1, c - 1) open the string
    sets = n - copies * (length - 1)
    inner = log10_choose(sets - 1, copies) + math.log10(max(1e-300, 1 - r ** (copies - 1)))
    edge = log10_choose(sets - 1, copies - 1)
    top = max(inner, edge)
    sets = top + math.log10(10 ** (inner - top) + 10 ** (edge - top))
    return sets + (copies - 1) * (math.log10(q) + (length - 1) * math.log10(r))


def follow_rate(codes: np.ndarray) -> float | None:
    """The chance that, after two equal symbols, the next two agree too, or None.

    Models of a random string are weighed by the Bayesian information criterion
    (``-2 ln L + m ln(n - 1)``, ``m`` free parameters, ``n - 1`` steps; ``k`` below counts
    the letters followed by something). Three of them are **letter models**: each letter
    ``a`` equals the one before it with chance ``rho_a``, and otherwise is ``b`` with chance
    ``p_b / (1 - p_a)``, ``p`` the string's symbol shares; their rate is
    ``sum_a (p_a^2 / q) (rho_a^2 + (1 - rho_a)^2 sum_(b != a) p_b^2 / (1 - p_a)^2)``,
    ``q = sum p_a^2`` the match rate. They differ in ``rho_a``:

    - the **neighbour model** (``m = k``): one rate ``rho``, the string's share of equal
      neighbours. An actiongram merges equal neighbours, so ``rho`` is 0 unless it keeps
      repeats; over ``k`` equally used letters without equal neighbours the rate is then
      ``1 / (k - 1)``, not ``1 / k``: a repeat is that much cheaper than independent symbols
      say.
    - the **sticky model** (``m = k``): ``rho_a = theta + (1 - theta) p_a``, ``theta``
      (at least ``-min_a p_a / (1 - p_a)``) of greatest likelihood: symbols drawn
      independently by their shares (``theta = 0``, rate ``q``) that stay on a letter, or
      leave it, more than that. Over uneven letters with repeats kept one ``rho`` for all
      letters makes the rate far too low, and repeats of the common letter's runs too rare
      (the last example, symbols drawn independently: the neighbour model says 0.30).
    - **each letter's own** (``m = 2 k - 1``): ``rho_a = n_aa / n_a``, ``n_a`` how often
      ``a`` is followed by anything (letters each with its own persistence); ``rho`` for a
      letter only at the end.

    The fourth is the **chain**, ``m = k (k - 1)``: a first-order Markov chain of the
    digrams, for strings whose symbols follow each other by rule (``B G R Y`` of motion),
    which repeat exactly far more often; its rate is estimated without bias from the digram
    counts ``n_ab`` as ``(sum n_ab^2 - (n - 1)) / (sum n_a^2 - (n - 1))`` (not where every
    ``n_a`` is at most 1: ``0 / 0``). Ties go to the model named first. Without equal
    neighbours only the neighbour model and the chain are weighed: each letter's own rates
    are then all 0, the neighbour model's fit with more parameters, and the sticky model
    fits no better than the neighbour model (with ``c = min_a p_a``, ``theta`` at least
    ``-c / (1 - c)``, it gives a move ``(1 - theta) p_b <= p_b / (1 - c) <= p_b / (1 - p_a)``).
    None for a string of one symbol or under three symbols long (the match rate then stands
    for it).

    Examples
    --------
    >>> follow_rate(np.array([0, 1, 2, 3] * 10))  # each symbol has one successor
    1.0
    >>> letters = np.random.default_rng(0).integers(0, 3, 400)
    >>> no_equal = np.cumsum(letters + 1) % 4  # never equal to the one before
    >>> round(follow_rate(no_equal), 2)  # four letters: about 1 / 3, not 1 / 4
    0.34
    >>> uneven = np.random.default_rng(2).choice(8, 200, p=[0.7] + [0.3 / 7] * 7)
    >>> match = float(np.sum((np.bincount(uneven) / 200) ** 2))  # q
    >>> round(follow_rate(uneven), 2), round(match, 2)  # repeats kept: independent, r = q
    (0.52, 0.52)
    """
    if len(codes) < 3:
        return None
    size = int(codes.max()) + 1
    digrams = codes[:-1] * size + codes[1:]
    if size * size <= 4 * len(codes):
        counts = np.bincount(digrams, minlength=size * size)
        keys = np.flatnonzero(counts)
        pairs = counts[keys]
    else:  # (by sorting: a long alphabet would make size ** 2 bins)
        keys, pairs = np.unique(digrams, return_counts=True)
    firsts = np.bincount(codes[:-1], minlength=size)
    steps = len(codes) - 1
    rows = firsts[firsts > 0]
    symbols = len(rows)
    shares = np.bincount(codes, minlength=size) / len(codes)
    if symbols < 2 or shares.max() >= 1:
        return None
    chained = float(np.sum(pairs * np.log(pairs / firsts[keys // size])))
    same = keys // size == keys % size
    rho = float(pairs[same].sum()) / steps
    left, right = keys // size, keys % size
    with np.errstate(divide="ignore"):
        moves = np.where(same, math.log(rho) if rho > 0 else 0.0,
                         math.log1p(-rho) + np.log(shares[right]) - np.log1p(-shares[left]))
    neighbours = float(np.sum(pairs * moves))
    if rho > 0:
        return _with_repeats(_Digrams(pairs, left, right, same, firsts, shares, steps),
                             symbols, rho, chained, neighbours)
    extra = symbols * (symbols - 1) - symbols  # the chain's parameters beyond (shares, rho)
    if chained - neighbours > extra / 2 * math.log(steps):
        chain = _chain_rate(pairs, firsts, steps)
        if chain is not None:
            return chain
    match = float(np.sum(shares ** 2))
    used = shares[shares > 0]
    others = (match - used ** 2) / (1 - used) ** 2
    return float(np.sum(used ** 2 / match * (rho ** 2 + (1 - rho) ** 2 * others)))


def _chain_rate(pairs: np.ndarray, firsts: np.ndarray, steps: int) -> float | None:
    """The chain's rate from the digram counts, or None where every letter is followed at
    most once (``0 / 0``)."""
    below = float(np.sum(firsts.astype(np.float64) ** 2)) - steps
    if below <= 0:
        return None
    return max(0.0, float(np.sum(pairs.astype(np.float64) ** 2) - steps) / below)


@dataclass(frozen=True)
class _Digrams:
    """A string's digram counts ``pairs`` of ``left`` then ``right`` (``same`` where they are
    equal), how often each letter is followed by anything, its symbol shares, its steps."""

    pairs: np.ndarray
    left: np.ndarray
    right: np.ndarray
    same: np.ndarray
    firsts: np.ndarray
    shares: np.ndarray
    steps: int


def _with_repeats(d: _Digrams, symbols: int, rho: float, chained: float,
                  neighbours: float) -> float:
    """:func:`follow_rate` of a string with equal neighbours (``rho > 0``): the model the
    criterion prefers of the four, given the neighbour model's and the chain's log
    likelihoods."""
    stays = np.bincount(d.left[d.same], weights=d.pairs[d.same], minlength=len(d.shares))
    own = np.where(d.firsts > 0, stays / np.maximum(d.firsts, 1), rho)
    theta, sticky = _sticky(d, stays)
    with np.errstate(divide="ignore"):
        move = np.log(d.shares[d.right]) - np.log1p(-d.shares[d.left])
        own_fit = float(np.sum(d.pairs * np.where(d.same, np.log(own[d.left]),
                                                  np.log1p(-own[d.left]) + move)))
    penalty = math.log(d.steps) / 2
    fits = [(neighbours - symbols * penalty, np.full(len(d.shares), rho)),
            (sticky - symbols * penalty, theta + (1 - theta) * d.shares),
            (own_fit - (2 * symbols - 1) * penalty, own)]
    best = max(range(3), key=lambda i: (fits[i][0], -i))
    if chained - symbols * (symbols - 1) * penalty > fits[best][0]:
        chain = _chain_rate(d.pairs, d.firsts, d.steps)
        if chain is not None:
            return chain
    used = d.shares > 0
    p, stay = d.shares[used], fits[best][1][used]
    match = float(np.sum(p ** 2))
    others = (match - p ** 2) / (1 - p) ** 2
    return float(np.sum(p ** 2 / match * (stay ** 2 + (1 - stay) ** 2 * others)))


def _sticky(d: _Digrams, stays: np.ndarray) -> tuple[float, float]:
    """The sticky model's ``theta`` and log likelihood: ``theta`` maximises
    ``sum_a n_aa ln(theta + (1 - theta) p_a) + sum_(a != b) n_ab ln((1 - theta) p_b)``, a
    concave function, found where its slope is 0 by Newton's steps from 0 (independent
    symbols) kept inside the interval known to hold it, halved where a step leaves it (to
    ``theta``'s least value, where the slope is negative all along)."""
    used = d.shares > 0
    lo, hi, theta = -float(np.min(d.shares[used] / (1 - d.shares[used]))), 1.0, 0.0
    held = stays > 0
    n, p = stays[held], d.shares[held]
    leaving = float(d.pairs[~d.same].sum())
    for _ in range(100):
        lean = (1 - p) / (p + theta * (1 - p))  # d/dtheta of ln(theta + (1 - theta) p_a)
        slope = float(np.sum(n * lean)) - leaving / (1 - theta)
        if slope > 0:
            lo = theta
        else:
            hi = theta
        step = theta + slope / (float(np.sum(n * lean ** 2)) + leaving / (1 - theta) ** 2)
        if not lo < step < hi:
            step = (lo + hi) / 2
        done = abs(step - theta) < 1e-13
        theta = step
        if done:
            break
    fit = (float(np.sum(n * np.log(theta + (1 - theta) * p))) + leaving * math.log1p(-theta)
           + float(np.sum(d.pairs[~d.same] * np.log(d.shares[d.right[~d.same]]))))
    return theta, fit


def copy_agreements(codes: np.ndarray, pattern, starts) -> list[float]:
    """The share of the pattern's positions each copy starting at ``starts`` agrees with.

    Examples
    --------
    >>> copy_agreements(np.array([1, 2, 3, 1, 2, 4]), [1, 2, 3], [0, 3])
    [1.0, 0.6666666666666666]
    """
    pattern = np.asarray(pattern)
    starts = np.asarray(starts, dtype=np.int64)
    index = starts[:, None] + np.arange(len(pattern))
    inside = index < len(codes)
    agree = inside & (codes[np.minimum(index, len(codes) - 1)] == pattern)
    return (np.count_nonzero(agree, axis=1) / len(pattern)).tolist()


def find_sections(strings: list[np.ndarray], copies: int, match_rates: list[float],
                  level: float, follows: list[float | None] | None = None,
                  clock=NO_BOUND) -> list[Section | None]:
    """:func:`find_section` of every string (unbounded in length), strings that cannot hold a
    section reaching ``level`` passed over in one pass over all of them; ``clock`` (a
    :class:`~psgs.budget.Budget`) read before that pass's hashes of each length, before each
    string searched and between the lengths each string's search probes.

    Examples
    --------
    >>> rng = np.random.default_rng(0)
    >>> section = rng.integers(0, 9, 12)
    >>> strings = [np.concatenate((section, rng.integers(0, 9, 5), section)),
    ...            rng.integers(0, 9, 29)]
    >>> [None if s is None else len(s.motif) for s in find_sections(strings, 2, [0.11] * 2, -2)]
    [12, None]
    """
    out: list[Section | None] = [None] * len(strings)
    # (``follows``: every string's :func:`follow_rate`, when the caller has them already)
    follows = [(follow_rate(c) if follows is None else follows[i]) if len(c) >= 2 * copies
               else None for i, c in enumerate(strings)]
    lows = [_shortest(len(c), copies, q, f, level, len(c) // copies)
            if len(c) >= 2 * copies else 0 for c, q, f in zip(strings, match_rates, follows)]
    for i in _may_repeat(strings, lows, copies, clock):
        clock.check()
        out[i] = find_section(strings[i], copies, len(strings[i]), match_rates[i], level,
                              follows[i], lows[i], clock)
    return out


def _may_repeat(strings: list[np.ndarray], lows: list[int], copies: int,
                clock=NO_BOUND) -> list[int]:
    """The strings where some window of ``lows[i]`` symbols comes ``copies`` times, spread
    over ``(copies - 1) lows[i]`` symbols at least (what a section needs; hashes of every
    string of one length compared at once, ``clock`` read before each length)."""
    by_length: dict[int, list[int]] = {}
    for i, (codes, low) in enumerate(zip(strings, lows)):
        if 2 <= low <= len(codes) // copies:
            by_length.setdefault(low, []).append(i)
    out: list[int] = []
    for length, rows in by_length.items():
        clock.check()
        flat = np.concatenate([strings[i] for i in rows])
        bounds = np.cumsum([0] + [len(strings[i]) for i in rows])
        hashes = _window_hashes(flat, length)
        owner = np.repeat(np.arange(len(rows)), np.diff(bounds))[:len(hashes)]
        valid = np.arange(len(hashes)) + length <= bounds[owner + 1]
        where = np.flatnonzero(valid)
        with np.errstate(over="ignore"):
            keys = hashes[where] + owner[where].astype(np.uint64) * np.uint64(_INVERSE)
        # most windows come once: the keys alone sorted (cheaper than ordering positions)
        # name the few that come ``copies`` times, and only their windows are ordered
        ordered = np.sort(keys)
        begins = np.concatenate(([0], np.flatnonzero(np.diff(ordered)) + 1))
        sizes = np.diff(np.concatenate((begins, [len(ordered)])))
        common = ordered[begins[sizes >= copies]]
        if not len(common):
            continue
        at = np.minimum(np.searchsorted(common, keys), len(common) - 1)
        chosen = np.flatnonzero(common[at] == keys)
        order = chosen[np.argsort(keys[chosen])]  # (any order within a group: only its extent is read)
        ordered = keys[order]
        begins = np.concatenate(([0], np.flatnonzero(np.diff(ordered)) + 1))
        sizes = np.diff(np.concatenate((begins, [len(ordered)])))
        positions = where[order]
        spread = np.maximum.reduceat(positions, begins) - np.minimum.reduceat(positions, begins)
        hit = begins[(sizes >= copies) & (spread >= (copies - 1) * length)]
        out.extend(rows[k] for k in np.unique(owner[positions[hit]]).tolist())
    return sorted(out)


def find_section(codes: np.ndarray, copies: int, longest: int, match_rate: float,
                 level: float = 0.0, follow: float | None = None,
                 low: int | None = None, clock=NO_BOUND) -> Section | None:
    """The longest window of ``codes`` found ``copies`` times or more, exact and apart.

    Among windows of that length the one with the most copies wins, the
    earliest among equals; its copies are all its non-overlapping occurrences,
    taken from the left. At most ``longest`` symbols; None when no window of
    two symbols or more repeats so, when none is long enough for its
    significance to reach ``level`` (log10; 0 looks at every length), or when
    the longest is a cycle (its copies are parts of one block played over and
    over, :func:`_cycles`). ``follow`` and ``low``: the string's
    :func:`follow_rate` and the shortest length worth a look, when known. ``clock`` (a
    :class:`~psgs.budget.Budget`) is read before each probe of a length (each hashes and
    sorts the whole string: a long string's search is many such passes) and raises
    :class:`~psgs.errors.BoundReached` past its deadline.

    Examples
    --------
    >>> codes = np.array([5, 0, 1, 2, 3, 6, 0, 1, 2, 3, 7])
    >>> found = find_section(codes, 2, 64, 0.2)
    >>> found.motif.tolist(), found.starts.tolist()
    ([0, 1, 2, 3], [1, 6])
    >>> find_section(codes, 2, 64, 0.2, level=-6.0) is None  # 4 symbols twice: about 1e-1.2
    True
    """
    n = len(codes)
    high = min(longest, n // copies)
    if low is None:  # (find_sections hands both in)
        follow = follow_rate(codes)
        low = _shortest(n, copies, match_rate, follow, level, high)
    if low > high:
        return None
    clock.check()
    if not _repeated(codes, low, copies, first=True):
        return None
    low = _longest_repeated(codes, copies, low, high, clock)
    clock.check()
    starts = _repeated(codes, low, copies)
    motif = codes[starts[0]:starts[0] + low].copy()
    if _cycles(codes, starts, low):
        # a cycle (a block played over and over) is what the digram search and the
        # period mode are for; as a section it would only be that block's copies again
        return None
    agreeing = (len(starts) - 1) * low
    return Section(motif, starts, repeat_significance(n, low, len(starts), agreeing,
                                                      match_rate, follow))


def _longest_repeated(codes: np.ndarray, copies: int, low: int, high: int,
                      clock=NO_BOUND) -> int:
    """The longest length in ``[low, high]`` whose some window comes ``copies`` times apart,
    ``low`` known to; ``clock`` read before each probe.

    A window with ``copies`` copies apart gives each of its prefixes as many, so the
    lengths that repeat are the ones up to the answer. The search doubles from ``low``
    before it halves: a string's longest repeat is most often far shorter than ``high``
    (half the string), and each probe hashes and sorts the whole string.
    """
    step = max(1, low)
    while low < high:
        clock.check()
        probe = min(high, low + step)
        if _repeated(codes, probe, copies, first=True):
            low, step = probe, 2 * step
        else:
            high = probe - 1
            break
    while low < high:
        clock.check()
        middle = (low + high + 1) // 2
        if _repeated(codes, middle, copies, first=True):
            low = middle
        else:
            high = middle - 1
    return low


def _cycles(codes: np.ndarray, starts, length: int) -> bool:
    """Whether the copies of ``length`` symbols at ``starts`` are parts of one cycle: their
    window repeats itself at a shift ``p`` of half its length or less (``x y z x y z``) and
    so does the whole stretch from the first copy's start to the last one's end (one block
    played over and over). A window that repeats itself but whose copies lie apart, other
    symbols between them, is a section as any other."""
    first, last = int(starts[0]), int(starts[-1]) + length
    motif = codes[first:first + length]
    stretch = codes[first:last]

    def repeats_at(p: int) -> bool:
        return bool(np.array_equal(motif[p:], motif[:-p])
                    and np.array_equal(stretch[p:], stretch[:-p]))

    # the short shifts one by one (a block of a few symbols played over and over is found
    # at once); the longer ones only where their first few symbols agree: most do not, and
    # a long window has many shifts to try
    if any(repeats_at(p) for p in range(1, min(8, length // 2) + 1)):
        return True
    shifts = np.arange(9, length // 2 + 1)
    for j in range(min(8, length - length // 2)):
        shifts = shifts[motif[shifts + j] == motif[j]]
    return any(repeats_at(p) for p in shifts.tolist())


def _shortest(n: int, copies: int, match_rate: float, follow: float, level: float,
              high: int) -> int:
    """The fewest symbols (two at least) whose exact copies can reach ``level``."""
    length = 2
    while length <= high and repeat_significance(n, length, copies, (copies - 1) * length,
                                                 match_rate, follow) > level:
        length += 1
    return length


def _repeated(codes: np.ndarray, length: int, copies: int, first: bool = False):
    """The starts of the window of ``length`` with the most copies apart (at least
    ``copies``; the earliest among equals), or None; with ``first``, only whether one
    exists (True or None)."""
    hashes = _window_hashes(codes, length)
    if first:
        # (most probes find no window coming ``copies`` times: the hashes alone say so)
        ordered = np.sort(hashes)
        if not np.any(ordered[copies - 1:] == ordered[:len(ordered) - copies + 1]):
            return None
    order = np.argsort(hashes, kind="stable")
    ordered = hashes[order]
    cuts = np.flatnonzero(np.diff(ordered)) + 1
    begins = np.concatenate(([0], cuts))
    sizes = np.diff(np.concatenate((begins, [len(ordered)])))
    # a group's copies apart span at least (copies - 1) * length: from its first to its last
    spread = np.maximum.reduceat(order, begins) - np.minimum.reduceat(order, begins)
    possible = np.flatnonzero((sizes >= copies) & (spread >= (copies - 1) * length))
    best, best_key = None, None
    for g in possible.tolist():
        where = order[begins[g]:begins[g] + sizes[g]]  # ascending: a stable sort of positions
        kept = where[keep_apart(where, length)].tolist()
        if len(kept) < copies:
            continue
        reference = codes[kept[0]:kept[0] + length]
        kept = [p for p in kept if np.array_equal(codes[p:p + length], reference)]
        if len(kept) < copies:
            continue  # (a hash collision)
        if first:
            return True
        key = (-len(kept), kept[0])
        if best_key is None or key < best_key:
            best, best_key = np.asarray(kept, dtype=np.int64), key
    return best


def _window_hashes(codes: np.ndarray, length: int) -> np.ndarray:
    """A 64-bit polynomial hash of every window of ``length`` symbols (wrapping arithmetic)."""
    prefix, powers = prefix_hashes(codes)
    with np.errstate(over="ignore"):
        # the sum of code_j BASE**-j over each window, times BASE**(its last j)
        return (prefix[length:] - prefix[:-length]) * powers[length - 1:len(codes)]


def prefix_hashes(codes: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Prefix sums of ``(code + 1) * BASE**-j`` and the powers ``BASE**j`` (wrapping 64-bit
    arithmetic): the hash of any window, :func:`window_hash`, in two operations."""
    n = len(codes)
    with np.errstate(over="ignore"):
        steps = np.full(n + 1, _INVERSE, dtype=np.uint64)
        steps[0] = 1
        inverse_powers = np.cumprod(steps, dtype=np.uint64)[:n]  # BASE**-j
        weighted = (codes.astype(np.uint64) + np.uint64(1)) * inverse_powers
        prefix = np.concatenate(([np.uint64(0)], np.cumsum(weighted, out=weighted)))
        steps[:] = _BASE
        steps[0] = 1
        return prefix, np.cumprod(steps, dtype=np.uint64)


def window_hash(prefix: np.ndarray, powers: np.ndarray, start, length) -> np.ndarray:
    """The hash of the windows of ``length`` symbols at ``start`` from
    :func:`prefix_hashes` (equal windows, equal hashes, wherever they are; the hashes of
    :func:`_window_hashes` times ``BASE**(length - 1)``)."""
    with np.errstate(over="ignore"):
        return (prefix[start + length] - prefix[start]) * powers[start]
