"""max_seconds inside the units of work PAL's loops once ran to their end between two readings
of the clock.

Each case here is one such unit made long, a deadline well inside it, and the time to the
raise held to a slack: the compiled synchronisation's block of some 2^20 pair tests (it read
the clock only between blocks: 1,024 candidates of 1,000 copies were one block of 3 s), a row
of numpy's pair tests (8,000 partners of 3,000 copies: 1.3 s), the widening of a large group
(1,000 members by 30 columns: 2.4 s, no reading at all), the passes over a long string
before its first seed (4 million symbols of a large alphabet: the digrams sorted, about a
second, and no seed to read the clock before), and one long string's section search (a
section of 200,000 symbols twice in a million: some 30 probes of its lengths, 3.4 s, read
only before the string). The slack is for a loaded machine: the cut units take a few
hundredths of a second past the deadline here. What reads the clock in parts reads the same
answer as whole.
"""

from __future__ import annotations

import time

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs.budget import Budget
from psgs.errors import BoundReached
from psgs.induce.pal import motifs, pooling, synchronisation
from psgs.induce.pal.conf import ContentConf

SLACK = 0.5


def _has_numba() -> bool:
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


NEEDS_NUMBA = pytest.mark.skipif(not _has_numba(),
                                 reason="the compiled engine needs numba (test extra)")
ENGINES = ["numpy", pytest.param("numba", marks=NEEDS_NUMBA)]


def _copies(count: int, offset: float = 0.0) -> np.ndarray:
    """``count`` disjoint copies of 6 time units, 10 apart, from ``offset``."""
    starts = np.arange(count) * 10.0 + offset
    return np.column_stack((starts, starts + 6.0))


def _raises_within(run, seconds: float) -> float:
    """The seconds ``run(Budget(seconds))`` took to raise the bound: the lesser of the wall
    time and this process's CPU time. A unit that never reads the clock runs to its end in
    both (its work is this process's); on a loaded machine the wall time stretches while the
    CPU time does not, and idle threads of the process (numba's, a timer's) add CPU time but
    no wall time."""
    begun, used = time.monotonic(), time.process_time()
    with pytest.raises(BoundReached, match="max_seconds"):
        run(Budget(seconds=seconds))
    return min(time.monotonic() - begun, time.process_time() - used)


@NEEDS_NUMBA
def test_a_compiled_block_of_pair_tests_stops_at_the_deadline():
    # 1,024 candidates are one block (2^20 pairs); a pair of 1,000 copies each is some 2,000
    # steps: 3 s for the block (the same array many times: the lists' memory is one's)
    lists = [_copies(1000, offset) for offset in (0.0, 1.5, 3.0, 4.5)] * 256
    assert len(lists) ** 2 == synchronisation.PAIRS_PER_CALL  # one block
    list(synchronisation._pairs_compiled(lists[:4], 0.5, 3))  # (compiled, or read from the cache)
    took = _raises_within(lambda clock: list(synchronisation._pairs_compiled(lists, 0.5, 3, clock)),
                          0.1)
    assert took < 0.1 + SLACK


def test_a_row_of_numpy_s_pair_tests_reads_the_clock():
    # row 0 tests 8,000 partners of 3,000 copies, some 160 µs each: 1.3 s
    lists = [_copies(3000)] + [_copies(3000, 1.5)] * 8000
    took = _raises_within(
        lambda clock: next(synchronisation._pairs_each(lists, 0.5, 3, clock)), 0.05)
    assert took < 0.05 + SLACK


def test_numpy_s_rows_read_a_part_at_a_time_are_the_same_pairs(monkeypatch):
    rng = np.random.default_rng(1)
    lists = [_copies(12, float(offset)) for offset in rng.uniform(0, 8, 40)]
    whole = list(synchronisation._pairs_each(lists, 0.5, 3))
    monkeypatch.setattr(synchronisation, "PAIRS_CLOCKED", 3)
    assert list(synchronisation._pairs_each(lists, 0.5, 3, Budget(seconds=1e6))) == whole
    assert sum(len(rows) for rows, _ in whole) > 100


def _widening_case(members: int):
    """``members`` strings (the protocol's 4 patterned strings of 40-symbol templates, over
    and over) voted in the true copy windows cut short by 15 columns a side."""
    from psgs.induce.pal.learner import encode
    from psgs.induce.synthetic import generate

    case = generate(seed=3, template_length=40, copies=10)
    strings, _ = encode(case.actiongram)
    patterned = [strings[case.actiongram.names.index(n)] for n in case.components]
    many = (patterned * members)[:members]
    true = np.asarray(case.windows, dtype=float)
    short = true + np.array([15.0, -15.0])
    return many, pooling.member_votes(many, range(members), short), short, true


def test_widening_a_large_group_reads_the_clock():
    from psgs.induce.pal.widening import widen

    # 1,000 members widened by 30 columns: 30,000 votes, 2.4 s
    strings, votes, short, true = _widening_case(1000)
    took = _raises_within(lambda clock: widen(strings, votes, short, 0.5, 1e-3, 64, clock),
                          0.1)
    assert took < 0.1 + SLACK
    # a deadline not reached: the same windows and votes as without one
    few, votes, short, true = _widening_case(8)
    windows, plain = widen(few, votes, short, 0.5, 1e-3, 64)
    again, bounded = widen(few, votes, short, 0.5, 1e-3, 64, Budget(seconds=1e6))
    assert np.array_equal(windows, true) and np.array_equal(again, windows)
    assert [v.pattern for v in plain.values()] == [v.pattern for v in bounded.values()]


def test_a_member_s_pooled_pattern_reads_its_copies_a_part_at_a_time(monkeypatch):
    from psgs.induce.pal.motifs import Timed

    # a figure of 64 symbols 2,000 times, 10% noise; every third window one symbol long, so
    # 667 copies are read again at the pattern's length (more than one part of 2^20 symbols)
    rng = np.random.default_rng(0)
    figure = np.concatenate((rng.permutation(100)[:64], [100, 101]))
    codes = np.tile(figure, 2000)
    noise = rng.random(len(codes)) < 0.1
    codes[noise] = rng.integers(0, 102, int(noise.sum()))
    string = Timed.from_codes(codes, np.ones(len(codes)), 0.0)
    starts = np.arange(2000) * 66.0
    windows = np.column_stack((starts, starts + 64.0))
    windows[::3, 1] += 1.0
    v = pooling.vote(string, windows)
    parts = pooling.pooled_pattern(string, v, Budget(seconds=1e6))
    monkeypatch.setattr(pooling, "ALIGNED_SYMBOLS", 1 << 40)  # every copy in one part
    assert pooling.pooled_pattern(string, v) == parts
    assert parts == tuple(figure[:64].tolist())
    expired = Budget(seconds=1e-3)
    expired.deadline -= 1.0
    with pytest.raises(BoundReached, match="max_seconds"):
        pooling.pooled_pattern(string, v, expired)


@pytest.mark.parametrize("engine", ENGINES)
def test_the_passes_before_a_long_string_s_first_seed_read_the_clock(engine):
    # 4 million symbols of 100,000: each digram about once, so no seed, and the digrams are
    # sorted, not counted (compiled: 0.5-0.9 s, once without reading the clock)
    codes = np.random.default_rng(0).integers(0, 100_000, 4_000_000)
    conf = ContentConf(engine=engine)
    motifs.find_motifs([codes[:3000]], conf)  # (numba: compiled, or read from the cache)
    assert motifs.find_motifs([codes], conf) == [None]  # no seed: only the passes read it
    took = _raises_within(lambda clock: motifs.find_motifs([codes], conf, clock), 0.05)
    if engine == "numba":
        assert took < 0.05 + SLACK
    # (numpy's search is now mostly one sort of the 4 million digrams, 0.3-0.6 s of CPU
    # whole and more on a loaded machine: that it raises at all is what shows the clock read)


@settings(max_examples=200)
@given(st.lists(st.integers(0, 40), min_size=1, max_size=300), st.sampled_from([41, 10**7]))
def test_the_digram_counts_are_np_unique_s(values, bins):
    keys = np.asarray(values, dtype=np.int64)
    # (bins 41: counted; 10**7: sorted with each key's position beside it)
    got = motifs._digram_counts(keys, bins)
    for mine, oracle in zip(got, np.unique(keys, return_index=True, return_counts=True),
                            strict=True):
        assert np.array_equal(mine, oracle)


@NEEDS_NUMBA
@settings(max_examples=200)
@given(st.lists(st.integers(0, 2**40), min_size=1, max_size=300),
       st.sampled_from([2**40 + 1, 2**62]))
def test_the_compiled_radix_groups_are_the_merge_sort_s(values, bins):
    from psgs.induce.pal._counting_jit import _digrams
    from psgs.induce.pal._motifs_jit import _digram_groups

    keys = np.asarray(values, dtype=np.int64)
    # (repeated keys: a few distinct values drawn often)
    keys = np.concatenate((keys, keys[: len(keys) // 2]))
    got = _digram_groups(keys, bins, np.zeros(1, dtype=np.uint8))
    for mine, oracle in zip(got, _digrams(keys, bins), strict=True):
        assert np.array_equal(mine, oracle)
    # a flag set stops it
    stopped = _digram_groups(keys, bins, np.ones(1, dtype=np.uint8))
    assert len(stopped[2]) == 0


def _long_section(symbols: int, half: int) -> np.ndarray:
    """``symbols`` random symbols of 50, the last ``2 * half`` a section of ``half`` twice."""
    rng = np.random.default_rng(0)
    section = rng.integers(0, 50, half)
    return np.concatenate((rng.integers(0, 50, symbols - 2 * half), section, section))


def test_one_long_string_s_section_search_reads_the_clock_between_its_lengths():
    from psgs.induce.pal.sections import find_section, find_sections, follow_rate

    # a section of 200,000 symbols twice in 10^6: the lengths probed double to it and halve
    # back, some 30 probes of 0.1 s each after 0.2 s of passes over the string (3.4 s, with
    # no reading between them): the deadline falls among the probes
    codes = _long_section(1_000_000, 200_000)
    rate = float(np.sum((np.bincount(codes) / len(codes)) ** 2))
    took = _raises_within(lambda clock: find_sections([codes], 2, [rate], -1e-9,
                                                      [follow_rate(codes)], clock), 1.0)
    assert took < 1.0 + SLACK
    # a deadline not reached: the same section as without one
    short = _long_section(3000, 400)
    plain = find_section(short, 2, 3000, rate)
    bounded = find_section(short, 2, 3000, rate, clock=Budget(seconds=1e6))
    assert len(plain.motif) == 400 and plain.starts.tolist() == [2200, 2600]
    assert np.array_equal(bounded.motif, plain.motif)
    assert np.array_equal(bounded.starts, plain.starts)
