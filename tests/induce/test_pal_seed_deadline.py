"""max_seconds inside one string's motif search and inside the pooling's units.

A seed grown in a long string is a pass over the string for each column of each growth step
(2 million symbols: some 2.5 s a seed with either engine; 2^19 - 1 symbols of a repeating
figure, some 1.9 s): numpy's search read the clock only before each seed, and the compiled
one only between runs of strings, so a long string ran seconds to minutes past the bound.
Whenever there is a deadline, numpy's grow now reads the clock before each growth step and
each column scanned, and every compiled run reads its alarm there; the pooling's relocation
of a member (a scan and a growth over the whole string) and the joint scan of a group read it
too. The slack of 2 million symbols is one second (the passes over the string before the
first seed, its digrams counted, and a loaded machine).
"""

from __future__ import annotations

import threading
import time

import numpy as np
import pytest

from psgs.budget import Budget
from psgs.errors import BoundReached
from psgs.induce.pal import motifs
from psgs.induce.pal._alarm import alarm
from psgs.induce.pal.conf import ContentConf
from psgs.induce.pal.learner import encode
from psgs.induce.pal.pooling import relocate, vote
from psgs.induce.pal.together import locate_together
from psgs.induce.synthetic import generate

SLACK = 1.0
#: past the deadline, a pass over 2^19 symbols is about a millisecond: the slack of the
#: strings just under 2^19 symbols is for a loaded machine (the code before took 0.6 s past
#: it with numpy, 1.8 s compiled)
SHORT_SLACK = 0.35


def _engines():
    return ["numpy", pytest.param("numba", marks=pytest.mark.skipif(
        not _has_numba(), reason="the compiled engine needs numba (test extra)"))]


def _has_numba() -> bool:
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


def _long_string(n: int) -> np.ndarray:
    """A figure of 100 distinct symbols played over and over, 10% of the symbols noise:
    every seed grows to ``max_pattern`` over the whole string."""
    rng = np.random.default_rng(0)
    codes = np.tile(rng.permutation(200)[:100], n // 100 + 1)[:n]
    noise = rng.random(n) < 0.1
    codes[noise] = rng.integers(0, 200, int(noise.sum()))
    return codes


def _now() -> tuple[float, float]:
    return time.monotonic(), time.process_time()


def _since(begun: tuple[float, float]) -> float:
    """The lesser of the wall time and this process's CPU time since ``begun``: a search
    that never reads the clock runs to its end in both (its work is this process's); on a
    loaded machine the wall time stretches while the CPU time does not, and idle threads of
    the process (numba's, the alarm's) add CPU time but no wall time."""
    wall, cpu = begun
    return min(time.monotonic() - wall, time.process_time() - cpu)


@pytest.mark.parametrize("engine", _engines())
@pytest.mark.parametrize("length, seconds, slack", [
    (1 << 21, 0.2, SLACK),  # a seed grown in a long string
    ((1 << 19) - 1, 0.05, SHORT_SLACK),  # under what a compiled run once read no alarm in
], ids=["long string", "just under 2^19 symbols"])
def test_a_string_s_search_stops_at_the_deadline(engine, length, seconds, slack):
    codes = _long_string(length)
    conf = ContentConf(engine=engine)
    motifs.find_motifs([codes[:2000]], conf)  # (numba: compiled, or read from its cache)
    begun = _now()
    with pytest.raises(BoundReached, match="max_seconds"):
        motifs.find_motifs([codes], conf, Budget(seconds=seconds))
    assert _since(begun) < seconds + slack


@pytest.mark.parametrize("engine", _engines())
def test_a_deadline_not_reached_inside_a_string_changes_nothing(engine):
    strings, _ = encode(generate(seed=4, noise=0.2, strings=8, unequal_lengths=True)
                        .actiongram)
    codes = [s.codes for s in strings]
    conf = ContentConf(engine=engine)
    plain = motifs.find_motifs(codes, conf)
    bounded = motifs.find_motifs(codes, conf, Budget(seconds=1e6))
    assert sum(m is not None for m in plain) >= 3
    for a, b in zip(plain, bounded, strict=True):
        assert (a is None) == (b is None)
        if a is not None:
            assert np.array_equal(a.motif, b.motif) and np.array_equal(a.starts, b.starts)
            assert a.significance == b.significance
    # and the one-seed grow the pooling and numpy's fallback call
    seed = np.array([codes[0][0], codes[0][1]])
    starts = np.flatnonzero((codes[0][:-1] == seed[0]) & (codes[0][1:] == seed[1]))
    rate = strings[0].match_rate
    args = (codes[0], seed, starts, rate, strings[0].distinct, conf, True)
    a, b = motifs.grow(*args), motifs.grow(*args, clock=Budget(seconds=1e6))
    assert (a is None) == (b is None)
    if a is not None:
        assert np.array_equal(a.motif, b.motif) and a.significance == b.significance


@pytest.mark.parametrize("engine", _engines())
def test_a_long_string_s_single_seed_stops_too(engine):
    codes = _long_string(1 << 21)
    conf = ContentConf(engine=engine)
    seed = codes[:2].copy()
    starts = np.flatnonzero((codes[:-1] == seed[0]) & (codes[1:] == seed[1]))
    rate = float(np.sum((np.bincount(codes) / len(codes)) ** 2))
    begun = _now()
    with pytest.raises(BoundReached, match="max_seconds"):
        motifs.grow(codes, seed, starts, rate, 200, conf, seed_only=True,
                    clock=Budget(seconds=0.2))
    assert _since(begun) < 0.2 + SLACK


def _expired() -> Budget:
    clock = Budget(seconds=1e-3)
    clock.deadline -= 1.0
    return clock


def _group():
    strings, _ = encode(generate(seed=3, noise=0.1, strings=6).actiongram)
    conf = ContentConf()
    found = motifs.find_motifs([s.codes for s in strings], conf)
    i = next(i for i, m in enumerate(found) if m is not None)
    return strings, i, found[i], conf


@pytest.mark.parametrize("engine", _engines())
def test_relocating_a_member_reads_the_clock(engine):
    strings, i, motif, _ = _group()
    conf = ContentConf(engine=engine)
    pattern = tuple(motif.motif.tolist())
    assert relocate(strings[i], pattern, conf, Budget(seconds=1e6)) is not None
    with pytest.raises(BoundReached, match="max_seconds"):
        relocate(strings[i], pattern, conf, _expired())
    if engine == "numba":  # the compiled growth reads the alarm it is handed
        with pytest.raises(BoundReached, match="max_seconds"):
            relocate(strings[i], pattern, conf, stop=np.ones(1, dtype=np.uint8))


def test_the_joint_scan_of_a_group_reads_the_clock():
    strings, i, motif, conf = _group()
    windows = strings[i].copy_times(motif)
    votes = {i: vote(strings[i], windows)}
    assert votes[i] is not None
    locate_together(strings, votes, conf, Budget(seconds=1e6))
    with pytest.raises(BoundReached, match="max_seconds"):
        locate_together(strings, votes, conf, _expired())


@pytest.mark.parametrize("seconds", [threading.TIMEOUT_MAX, 1e10, 1e300, float("inf")])
def test_a_deadline_past_what_a_timer_can_wait_sets_no_timer(seconds, monkeypatch):
    failures = []
    monkeypatch.setattr(threading, "excepthook", failures.append)
    with alarm(Budget(seconds=seconds)) as flag:
        time.sleep(0.05)  # (the timer's thread died at once when it was started)
        assert flag[0] == 0
    assert failures == []
