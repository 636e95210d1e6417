"""max_seconds inside every string's seeds and inside the pooling's units.

A string just under ``CLOCKED_SYMBOLS`` (2^19) symbols of a repeating figure takes some 1.9 s
to search with either engine; the compiled engine's run of it read no alarm (only runs of
``CLOCKED_SYMBOLS`` or more did) and numpy's grow read the clock only between seeds. Now
every run and every grow read the deadline whenever there is one. The pooling's relocation
of a member (a scan and a growth over the whole string) and the joint scan of a group read
it too.
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

#: past the deadline, a pass over 2^19 symbols is about a millisecond: the slack is for a
#: loaded machine (the code before took 0.6 s past it with numpy, 1.8 s compiled)
SLACK = 0.35


def _engines():
    return ["numpy", pytest.param("numba", marks=pytest.mark.skipif(
        not _has_numba(), reason="the compiled engine needs numba (test extra)"))]


def _has_numba() -> bool:
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


def _repeating(n: int) -> np.ndarray:
    """A figure of 100 distinct symbols over and over, 10% of them noise."""
    rng = np.random.default_rng(0)
    codes = np.tile(rng.permutation(200)[:100], n // 100 + 1)[:n]
    noise = rng.random(n) < 0.1
    codes[noise] = rng.integers(0, 200, int(noise.sum()))
    return codes


@pytest.mark.parametrize("engine", _engines())
def test_a_string_just_under_the_clocked_length_stops_at_the_deadline(engine):
    codes = _repeating(motifs.CLOCKED_SYMBOLS - 1)
    conf = ContentConf(engine=engine)
    motifs.find_motifs([codes[:2000]], conf)  # (numba: compiled, or read from its cache)
    begun = time.monotonic()
    with pytest.raises(BoundReached, match="max_seconds"):
        motifs.find_motifs([codes], conf, Budget(seconds=0.05))
    assert time.monotonic() - begun < 0.05 + SLACK


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
