"""The section search's shortcuts against brute force: the same strings, lengths and pairs."""

from __future__ import annotations

import numpy as np
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from psgs.induce.pal.choice import coincide
from psgs.induce.pal.sections import _longest_repeated, _may_repeat, _repeated

codes_lists = st.lists(st.integers(0, 3), min_size=0, max_size=40)


def _apart(codes: list[int], length: int, copies: int) -> bool:
    """The oracle: some window of ``length`` found ``copies`` times without overlap (greedy
    from the left, which is optimal for equal-length windows)."""
    seen: dict[tuple[int, ...], list[int]] = {}
    for start in range(len(codes) - length + 1):
        seen.setdefault(tuple(codes[start:start + length]), []).append(start)
    for starts in seen.values():
        kept, last = 0, -length
        for s in starts:
            if s >= last + length:
                kept, last = kept + 1, s
        if kept >= copies:
            return True
    return False


def _spread(codes: list[int], length: int, copies: int) -> bool:
    """The prefilter's own criterion: some window of ``length`` comes ``copies`` times or
    more, its first and last occurrence at least ``(copies - 1) * length`` apart."""
    seen: dict[tuple[int, ...], list[int]] = {}
    for start in range(len(codes) - length + 1):
        seen.setdefault(tuple(codes[start:start + length]), []).append(start)
    return any(len(s) >= copies and s[-1] - s[0] >= (copies - 1) * length
               for s in seen.values())


@settings(max_examples=100, deadline=None, derandomize=True)
@given(strings=st.lists(codes_lists, min_size=1, max_size=6), copies=st.integers(2, 3),
       lows=st.lists(st.integers(0, 8), min_size=6, max_size=6))
def test_may_repeat_is_the_brute_force_prefilter(strings, copies, lows):
    arrays = [np.asarray(s, dtype=np.int64) for s in strings]
    lows = lows[:len(strings)]
    expected = [i for i, (s, low) in enumerate(zip(strings, lows))
                if 2 <= low <= len(s) // copies and _spread(s, low, copies)]
    assert _may_repeat(arrays, lows, copies) == expected
    # never passes over a string that holds the copies apart a section needs
    for i, (s, low) in enumerate(zip(strings, lows)):
        if 2 <= low <= len(s) // copies and _apart(s, low, copies):
            assert i in expected


@settings(max_examples=100, deadline=None, derandomize=True)
@given(codes=codes_lists, copies=st.integers(2, 3), data=st.data())
def test_longest_repeated_is_the_longest_length_that_repeats(codes, copies, data):
    high = len(codes) // copies
    lengths = [k for k in range(1, high + 1) if _apart(codes, k, copies)]
    for k in range(1, high + 1):  # the quick exit says no exactly where no window repeats
        assert bool(_repeated(np.asarray(codes, dtype=np.int64), k, copies, first=True)) \
            == (k in lengths)
    assume(lengths)
    low = data.draw(st.sampled_from(lengths))
    answer = _longest_repeated(np.asarray(codes, dtype=np.int64), copies, low, high)
    assert answer == max(lengths)
    assert bool(_repeated(np.asarray(codes, dtype=np.int64), answer, copies, first=True))


def _coincide_oracle(a, b, copies, fraction):
    """Every copy of ``a`` against every copy of ``b``."""
    if min(len(a), len(b)) < max(copies, fraction * max(len(a), len(b))):
        return False
    paired = 0
    for a0, a1 in a:
        if any(min(a1, b1) - max(a0, b0) > 0
               and 2 * (min(a1, b1) - max(a0, b0)) >= max(a1, b1) - min(a0, b0)
               for b0, b1 in b):
            paired += 1
    count = min(paired, len(b))
    return count >= copies and count >= fraction * max(len(a), len(b))


def _copies(draw_lengths):
    """Disjoint copies in time order from (gap, length) pairs."""
    out, t = [], 0.0
    for gap, length in draw_lengths:
        t += gap
        out.append((t, t + length))
        t += length
    return np.asarray(out, dtype=np.float64).reshape(-1, 2)


spans = st.lists(st.tuples(st.floats(0, 6, allow_nan=False), st.floats(0.5, 8, allow_nan=False)),
                 min_size=0, max_size=6)


@settings(max_examples=150, deadline=None, derandomize=True)
@given(a=spans, b=spans, copies=st.integers(1, 3), fraction=st.sampled_from([0.0, 0.5, 1.0]))
def test_coincide_is_the_all_pairs_oracle(a, b, copies, fraction):
    a, b = _copies(a), _copies(b)
    assert coincide(a, b, copies, fraction) == _coincide_oracle(a.tolist(), b.tolist(),
                                                                copies, fraction)
