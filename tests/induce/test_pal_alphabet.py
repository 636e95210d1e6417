"""PAL and locate grow gently with the alphabet: many distinct symbols cost about what few do.

Each string's own symbols are what the self-agreement and cycle kappas count (a
symbol a string lacks adds exactly 0), so a large alphabet costs little more
than a small one. The bounds are loose (a 16-fold alphabet under 8 times the
time, best of three CPU-time readings) so that a loaded machine does not fail
them, yet tight enough that a cost proportional to the alphabet does.
"""

from __future__ import annotations

import time

import numpy as np
import pytest

from psgs import Actiongram
from psgs.induce import PAL, locate


def _best_time(call, tries: int = 3) -> float:
    best = float("inf")
    for _ in range(tries):
        start = time.process_time()
        call()
        best = min(best, time.process_time() - start)
    return max(best, 1e-3)


def _content(alphabet: int, length: int = 2000, seed: int = 0) -> Actiongram:
    rng = np.random.default_rng(seed)
    names = [f"s{i}" for i in range(alphabet)]
    return Actiongram.from_strings({"a": [names[i % alphabet] for i in range(length)],
                                    "b": [names[i] for i in rng.integers(0, alphabet, length)]})


def test_pal_on_a_sixteen_fold_alphabet_costs_under_eight_times():
    PAL().induce(_content(8, 200))  # compiled kernels and imports out of the timing
    small, large = _content(125), _content(2000)
    ratio = _best_time(lambda: PAL().induce(large)) / _best_time(lambda: PAL().induce(small))
    assert ratio < 8, ratio


@pytest.fixture(scope="module")
def cycling():
    """An action learnt as cycles of three joints, and the names of its takes' strings."""
    kinetology = pytest.importorskip("kinetology")
    from kinetology.synthetic import synthetic_motion

    takes = [kinetology.segment(synthetic_motion(seed=s, repetitions=6)) for s in range(2)]
    return PAL().induce(takes), takes[0]


def _random_take(like: Actiongram, alphabet: int, length: int = 300) -> Actiongram:
    rng = np.random.default_rng(alphabet)
    names = like.names
    return Actiongram.from_strings(
        {n: [f"q{x}" for x in rng.integers(0, alphabet, length)] for n in names},
        {n: list(rng.uniform(0.05, 0.15, length)) for n in names},
        displacements={n: list(rng.uniform(-5, 5, length)) for n in names},
        actuators=dict(zip(names, like.string_actuators)))


def test_locate_on_a_sixteen_fold_alphabet_costs_under_eight_times(cycling):
    learned, like = cycling
    small, large = _random_take(like, 40), _random_take(like, 640)
    locate(learned, small)
    ratio = _best_time(lambda: locate(learned, large)) / _best_time(lambda: locate(learned, small))
    assert ratio < 8, ratio
