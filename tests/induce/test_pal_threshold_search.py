"""The scan threshold found by halving against the one found by trying each count in turn.

Beside these draws the two agreed on 934,920 cases of a grid (lengths 1 to 79 and up to 512,
1 to 10^6 windows, 53 match rates, 3 floors, 7 bounds from 10^-12 to 0.5) when the halving
was written.
"""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from psgs.induce.pal.statistics import _linear_threshold, _threshold


@settings(max_examples=250, deadline=None, derandomize=True)
@given(length=st.integers(1, 200), windows=st.integers(-2, 10**6),
       rate=st.one_of(st.floats(0, 1), st.sampled_from([0.125, 0.25, 0.5, 1 / 3])),
       fraction=st.sampled_from([0.0, 0.5, 0.9]),
       alpha=st.one_of(st.floats(1e-12, 3), st.sampled_from([0.05, 0.01, 1.0, 2.0])))
def test_the_threshold_found_by_halving_is_the_first_that_passes(length, windows, rate,
                                                                fraction, alpha):
    assert _threshold.__wrapped__(length, windows, rate, fraction, alpha) == \
        _linear_threshold(length, windows, rate, fraction, alpha)


def test_the_tail_is_a_half_or_more_up_to_the_mean_and_falls_past_it():
    # what the halving rests on, as log10_binom_sf computes it: at t <= m p the tail is at
    # least a half, and past m p each tail is above the next by more than the rounding
    from psgs.induce.pal.statistics import log10_binom_sf

    for length in range(1, 300, 7):
        for rate in (1e-6, 0.01, 0.1, 0.125, 0.25, 1 / 3, 0.5, 0.7, 0.99):
            tails = [log10_binom_sf(t, length, rate) for t in range(length + 1)]
            for t in range(1, length + 1):
                if t <= length * rate:
                    assert tails[t] >= -0.29, (length, rate, t)  # (10^-0.29 > 0.51)
                elif t < length:
                    assert tails[t + 1] < tails[t] - 1e-9, (length, rate, t)
