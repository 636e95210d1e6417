"""The pair tests of a row of section candidates, at once, against pair by pair.

The candidates' copies are tested in step pair by pair (N^2 / 2 tests); a row of them is
tested at once (``choice.in_step_row``) and must be, to the bit, ``coincide`` and
``keeps_shift`` of each pair (the oracles here).
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs.induce.pal import choice
from psgs.induce.pal.choice import _CopyTable, coincide, in_step_row
from psgs.induce.pal.pairing import keeps_shift


def _copy_lists(seed: int) -> list[np.ndarray]:
    """Candidates' copies: many near one set of times (in step, or off by a little, some
    copies dropped), some at random, a few not in time order."""
    rng = np.random.default_rng(seed)
    base = np.sort(rng.uniform(0, 100, rng.integers(1, 12)))
    lists = []
    for _ in range(rng.integers(1, 30)):
        if rng.random() < 0.5:
            starts = base + rng.choice([0, 0.5, 1, 2, -1], len(base)) * (rng.random() < 0.5)
            lengths = rng.choice([3.0, 4.0, 6.0], len(base))
            starts = starts[rng.random(len(starts)) < 0.9]
            lengths = lengths[:len(starts)]
        else:
            starts = np.sort(rng.uniform(0, 100, rng.integers(0, 12)))
            lengths = rng.uniform(0.5, 8, len(starts))
        if rng.random() < 0.05:
            starts = starts[::-1].copy()
        lists.append(np.column_stack((starts, starts + lengths)).reshape(-1, 2))
    return lists


@pytest.mark.parametrize("cells", [choice._ROW_CELLS, 8, 40])
@settings(max_examples=60, deadline=None, derandomize=True)
@given(seed=st.integers(0, 2**32 - 1), copies=st.integers(2, 3),
       fraction=st.sampled_from([0.0, 0.5, 1.0]))
def test_a_row_of_pair_tests_is_each_pair_s_own(cells, seed, copies, fraction):
    # (8 and 40 cells: pairs with many copies tested alone, the rest in blocks of a few)
    choice._ROW_CELLS, kept = cells, choice._ROW_CELLS
    try:
        lists = _copy_lists(seed)
        table = _CopyTable.of(lists)
        for k, a in enumerate(lists):
            assert in_step_row(table, k, copies, fraction) == [
                b for b in range(k + 1, len(lists))
                if coincide(a, lists[b], copies, fraction) and keeps_shift(a, lists[b])]
    finally:
        choice._ROW_CELLS = kept


def test_the_drawn_rows_hold_pairs_in_step_and_not():
    found = tested = 0
    for seed in range(40):
        lists = _copy_lists(seed)
        table = _CopyTable.of(lists)
        for k in range(len(lists)):
            found += len(in_step_row(table, k, 2, 0.5))
            tested += len(lists) - k - 1
    assert 50 < found < tested / 2, (found, tested)
