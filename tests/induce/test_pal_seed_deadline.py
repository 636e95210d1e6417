"""max_seconds inside one string's motif search: a seed grown in a long string is cut.

A seed grown in a string of 2 million symbols takes some 2.5 s with either engine (a pass
over the string for each column of each growth step; the three seeds, some 10 s); numpy's
search read the clock only before each seed, and the compiled one only between runs of
strings, so a long string ran seconds to minutes past the bound. Now a string of
``CLOCKED_SYMBOLS`` or more reads it (numpy) or its alarm (compiled) before each growth step
and each column scanned: the stated slack is one second, which covers the passes over the
string before the first seed (its digrams counted) and a loaded machine.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from psgs.budget import Budget
from psgs.errors import BoundReached
from psgs.induce.pal import motifs
from psgs.induce.pal.conf import ContentConf
from psgs.induce.pal.learner import encode
from psgs.induce.synthetic import generate

SLACK = 1.0


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


@pytest.mark.parametrize("engine", _engines())
def test_a_seed_grown_in_a_long_string_stops_at_the_deadline(engine):
    codes = _long_string(1 << 21)
    conf = ContentConf(engine=engine)
    motifs.find_motifs([codes[:2000]], conf)  # (numba: compiled, or read from its cache)
    begun = time.monotonic()
    with pytest.raises(BoundReached, match="max_seconds"):
        motifs.find_motifs([codes], conf, Budget(seconds=0.2))
    assert time.monotonic() - begun < 0.2 + SLACK


@pytest.mark.parametrize("engine", _engines())
def test_a_deadline_not_reached_inside_a_string_changes_nothing(engine, monkeypatch):
    strings, _ = encode(generate(seed=4, noise=0.2, strings=8, unequal_lengths=True)
                        .actiongram)
    codes = [s.codes for s in strings]
    conf = ContentConf(engine=engine)
    plain = motifs.find_motifs(codes, conf)
    # every string long enough to be read inside its seeds, each a run of its own
    monkeypatch.setattr(motifs, "CLOCKED_SYMBOLS", 50)
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
    begun = time.monotonic()
    with pytest.raises(BoundReached, match="max_seconds"):
        motifs.grow(codes, seed, starts, rate, 200, conf, seed_only=True,
                    clock=Budget(seconds=0.2))
    assert time.monotonic() - begun < 0.2 + SLACK
