"""numpy's engine tests a row's pairs at once: the same pairs as the test of each pair.

:func:`psgs.induce.pal.synchronisation._pairs_each` counts, for one list against many, how
many copies each list has before and after every copy of the row's list; the oracle is
:func:`~psgs.induce.pal.synchronisation.synchronised` on every pair, which merges the two
lists' copies into clusters (:func:`~psgs.induce.pal.synchronisation.copy_clusters`).
Copies are drawn on a small grid so that ends meet starts, copies have no length, lists
overlap themselves or are empty.
"""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from psgs.induce.pal import synchronisation


@st.composite
def _copy_lists(draw):
    lists = []
    for _ in range(draw(st.integers(1, 7))):
        count = draw(st.integers(0, 5))
        if draw(st.booleans()):  # in time order, none overlapping (the usual case)
            times = sorted(draw(st.lists(st.integers(0, 24), min_size=2 * count,
                                         max_size=2 * count)))
            copies = np.array(times, dtype=float).reshape(-1, 2)
        else:  # anywhere: overlapping, out of order
            starts = draw(st.lists(st.integers(0, 20), min_size=count, max_size=count))
            lengths = draw(st.lists(st.integers(0, 5), min_size=count, max_size=count))
            copies = np.column_stack((starts, np.add(starts, lengths))).astype(float)
        lists.append(copies.reshape(-1, 2) + draw(st.sampled_from([0.0, 0.5])))
    return lists


def _each_pair(lists, fraction, copies):
    return [(i, j) for i in range(len(lists)) for j in range(i + 1, len(lists))
            if synchronisation.synchronised(lists[i], lists[j], fraction, copies)]


@settings(max_examples=150, deadline=None, derandomize=True)
@given(_copy_lists(), st.sampled_from([0.0, 0.5, 0.9, 1.0]), st.integers(1, 3))
def test_a_row_at_once_finds_the_pairs_each_pair_does(lists, fraction, copies):
    found = [(i, j) for rows, columns in synchronisation._pairs_each(lists, fraction, copies)
             for i, j in zip(rows, columns)]
    assert found == _each_pair(lists, fraction, copies)


@pytest.mark.parametrize("queries", [1, 7, 1 << 18])
def test_a_row_read_in_parts_finds_the_same_pairs(monkeypatch, queries):
    # the row's partners tested a few at a time (as many as PAIR_QUERIES allows) or all at once
    rng = np.random.default_rng(3)
    lists = [np.column_stack((s, s + 6.0)) for s in
             (np.arange(12) * 10.0 + offset for offset in rng.uniform(0, 8, 30))]
    monkeypatch.setattr(synchronisation, "PAIR_QUERIES", queries)
    found = [(i, j) for rows, columns in synchronisation._pairs_each(lists, 0.5, 3)
             for i, j in zip(rows, columns)]
    assert found == _each_pair(lists, 0.5, 3) and len(found) > 50
