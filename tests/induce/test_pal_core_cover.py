"""A string read at a group's core by how much of the core it plays again at the core's shift."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs.induce.pal.core_cover import cover_reading
from psgs.induce.pal.motifs import Timed
from psgs.induce.pal.sections import _cycles, follow_rate


def _brute(string: Timed, core: np.ndarray, follow):
    """cover_reading by hand: every segment under the core's first copy, its partner found by
    a scan for the segment starting exactly the core's shift later, the longest stretch of
    consecutive such pairs agreeing at one index shift (no longer than the shift), widened
    while the symbols keep agreeing at that shift in time, its copies pairing with the
    core's."""
    codes, starts, ends = string.codes.tolist(), string.starts.tolist(), string.ends.tolist()
    (a1, b1), (a2, b2) = core.tolist()
    first = [p for p in range(len(codes)) if starts[p] < b1 and ends[p] > a1]
    if not first or not any(starts[p] < b2 and ends[p] > a2 for p in range(len(codes))):
        return None
    shift = a2 - a1

    def partner(p):
        return next((k for k in range(len(codes)) if abs(starts[k] - starts[p] - shift) <= 1e-9),
                    None)

    best, at, step = 0, None, None
    for i, p in enumerate(first):
        c = 0
        for p2 in first[i:]:
            k = partner(p2)
            if (k is None or k <= p2 or codes[k] != codes[p2] or (k - p2) != (partner(p) - p)
                    or c == k - p2):  # (at most the shift: longer copies would overlap)
                break
            c += 1
        if c > best:
            best, at, step = c, p, partner(p) - p
    if best == 0:
        return None
    q, r = string.chance_rates(follow)
    weight = math.log10(len(first) - best + 1) + math.log10(q) + (best - 1) * math.log10(r)
    lo, hi = at, at + best

    def again(p):
        return (0 <= p < len(codes) - step and codes[p] == codes[p + step]
                and abs(starts[p + step] - starts[p] - shift) <= 1e-9)

    while hi - lo < step and again(lo - 1):
        lo -= 1
    while hi - lo < step and again(hi):
        hi += 1
    if _cycles(string.codes, (lo, lo + step), hi - lo):
        return None
    copies = ((starts[lo], ends[hi - 1]), (starts[lo + step], ends[hi - 1 + step]))
    for (a, b), (c, d) in zip(copies, core.tolist()):
        shared, union = min(b, d) - max(a, c), max(b, d) - min(a, c)
        if not (shared > 0 and 2 * shared >= union):
            return None  # (the copies must pair with the core's)
    return weight, codes[lo:hi], [lo, lo + step]


@settings(max_examples=60, deadline=None, derandomize=True)
@given(codes=st.lists(st.integers(0, 3), min_size=12, max_size=40),
       durations=st.lists(st.sampled_from([1.0, 1.0, 1.0, 2.0]), min_size=40, max_size=40),
       a=st.integers(0, 10), length=st.integers(2, 8), gap=st.integers(0, 8))
def test_cover_reading_is_the_longest_stretch_played_again_by_hand(codes, durations, a, length,
                                                                   gap):
    codes = np.array(codes)
    string = Timed.from_codes(codes, np.array(durations[:len(codes)]), 0.0)
    core = np.array([[a, a + length], [a + length + gap, a + 2 * length + gap]], dtype=float)
    got, want = cover_reading(string, core, follow_rate(codes)), _brute(string, core,
                                                                        follow_rate(codes))
    assert (got is None) == (want is None)
    if got is not None:
        assert got[0] == pytest.approx(want[0], abs=1e-12)
        assert got[1].motif.tolist() == want[1] and got[1].starts.tolist() == want[2]


def _random(rng, count: int, letters: int) -> np.ndarray:
    out: list[int] = []
    for _ in range(count):
        last = out[-1] if out else None
        choice = int(rng.integers(0, letters - (last is not None)))
        out.append(choice + (last is not None and choice >= last))
    return np.array(out)


@pytest.mark.parametrize("letters", [3, 4])
def test_random_strings_reach_a_weight_no_more_often_than_it_says(letters):
    # the weight is log10 of a bound on the chance that a random string covers the core as
    # far: read at one core, 2,000 random strings reach a weight w in at most 10^w of them
    # (measured: 3 letters 5.3 %, 1.15 %, 0.2 % at -1, -1.5, -2; 4 letters 2.95 %, 1.05 %, 0.2 %)
    rng = np.random.default_rng(letters)
    core = np.array([[10.0, 18.0], [25.0, 33.0]])
    weights = []
    for _ in range(2000):
        codes = _random(rng, 60, letters)
        got = cover_reading(Timed.from_codes(codes, np.ones(60), 0.0), core, follow_rate(codes))
        weights.append(0.0 if got is None else got[0])
    weights = np.array(weights)
    for level in (-1.0, -1.5, -2.0):
        assert np.mean(weights <= level) <= 10 ** level


def test_an_exact_member_off_the_core_by_a_symbol_pays_only_for_what_it_misses():
    # the core reaches a symbol past the section on the right (the members read so far all
    # agree there by chance); this string's copies reach a symbol past it on the left: it
    # covers 8 of the core's 9 symbols, and is reported with its own copies
    section = [0, 1, 2, 3, 1, 0, 2, 3]
    codes = np.array([2, 0] + [1] + section + [3] + [1] + section + [0, 2, 1, 0])
    # copies of ``[1] + section``: from 2 and from 12; the core is [3, 12) and [13, 22)
    string = Timed.from_codes(codes, np.ones(len(codes)), 0.0)
    weight, found = cover_reading(string, np.array([[3.0, 12.0], [13.0, 22.0]]), None)
    q = string.match_rate
    assert weight == pytest.approx(math.log10(2) + 8 * math.log10(q))
    assert found.starts.tolist() == [2, 12] and found.motif.tolist() == [1] + section


def test_a_cycle_played_through_the_core_is_no_reading():
    codes = np.array([3, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 2])
    string = Timed.from_codes(codes, np.ones(len(codes)), 0.0)
    assert cover_reading(string, np.array([[1.0, 5.0], [5.0, 9.0]]), None) is None


def test_a_string_playing_a_few_of_the_core_s_symbols_again_is_no_member():
    # three of the core's ten symbols played again at its shift: unlikely enough over many
    # letters, but its copies do not pair with the core's (half of the time they cover)
    codes = np.arange(30)
    codes[12:15] = codes[2:5]
    string = Timed.from_codes(codes, np.ones(30), 0.0)
    core = np.array([[0.0, 10.0], [10.0, 20.0]])
    assert cover_reading(string, core, None) is None
    codes[10:20] = codes[0:10]  # the whole of it: a member
    weight, found = cover_reading(Timed.from_codes(codes, np.ones(30), 0.0), core, None)
    assert found.starts.tolist() == [0, 10] and len(found.motif) == 10


def test_a_stretch_longer_than_the_shift_is_cut_to_it():
    # the core cuts through segments, so the stretch under its first copy could run past
    # the shift: the copies reported never overlap
    codes = np.array([5, 0, 1, 2, 0, 1, 2, 0, 6, 7, 5, 6])
    string = Timed.from_codes(codes, np.ones(12), 0.0)
    weight, found = cover_reading(string, np.array([[1.5, 4.5], [4.5, 7.5]]), None)
    (first, second), length = found.starts.tolist(), len(found.motif)
    assert first + length <= second and found.motif.tolist() == [0, 1, 2]
