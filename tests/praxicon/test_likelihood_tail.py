"""Heavy-tailed likelihoods: what the ranking's probabilities are, how the tail is fitted on
held-out takes, and that windows (parse's costs) stay Gaussian."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology import synthetic_motion
from praxicon.calibration import fit_likelihood
from praxicon.description import DescriptionError, Spread, describe
from praxicon.parsing import describe_windows
from praxicon.scoring import log_likelihoods, probabilities

distances = st.lists(st.floats(0.0, 1e6), min_size=2, max_size=8)


@given(distances, st.floats(0.01, 1e4), st.floats(1e-3, 1e6))
@settings(max_examples=200, deadline=None)
def test_a_tail_keeps_the_order_of_the_distances(dist, temperature, tail):
    d = np.array([dist])
    ll = log_likelihoods(d, temperature, tail)[0]
    for i in range(len(dist)):
        for j in range(len(dist)):
            if dist[i] < dist[j]:
                assert ll[i] >= ll[j]
    p = probabilities(d, temperature, tail)[0]
    assert math.isclose(p.sum(), 1.0) and (p >= 0).all()


@given(distances, st.floats(0.01, 1e4))
@settings(max_examples=100, deadline=None)
def test_an_infinite_tail_is_the_gaussian_and_a_long_one_comes_near_it(dist, temperature):
    d = np.array([dist])
    assert (log_likelihoods(d, temperature) == -0.5 * d / temperature).all()
    long = log_likelihoods(d, temperature, 1e9 * (max(dist) + 1.0))
    assert np.allclose(long, -0.5 * d / temperature, rtol=1e-6, atol=1e-6)


def _held_out(seed: int):
    """Scores of held-out takes against 3 actions, their own nearest by a ratio, at scales
    that differ takes to takes by a factor of up to 100 (near and far takes alike)."""
    rng = np.random.default_rng(seed)
    n = 120
    truth = rng.integers(0, 3, n)
    scale = 10.0 ** rng.uniform(0, 2, n)
    score = scale[:, None] * rng.uniform(2.0, 4.0, (n, 3))
    score[np.arange(n), truth] = scale * rng.uniform(0.5, 1.5, n)
    return score, truth


def _loss(score, truth, temperature, tail):
    p = probabilities(score, temperature, tail)[np.arange(len(truth)), truth]
    return float(-np.log(np.maximum(p, 1e-300)).mean())


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_a_tail_is_fitted_where_takes_lie_at_many_scales(seed):
    score, truth = _held_out(seed)
    gaussian = fit_likelihood(score, truth, False)
    assert gaussian[1] == math.inf and math.log2(gaussian[0]).is_integer()
    temperature, tail = fit_likelihood(score, truth, True)
    assert math.isfinite(tail)
    assert _loss(score, truth, temperature, tail) < _loss(score, truth, *gaussian)


@given(st.integers(0, 2 ** 32 - 1))
@settings(max_examples=25, deadline=None)
def test_a_tail_is_kept_only_where_it_fits_the_held_out_takes_better(seed):
    rng = np.random.default_rng(seed)
    score = rng.uniform(0.1, 100.0, (30, 3)) * rng.uniform(0.5, 50.0, (30, 1))
    truth = rng.integers(0, 3, 30)
    gaussian = fit_likelihood(score, truth, False)
    fitted = fit_likelihood(score, truth, True)
    assert fitted == gaussian or \
        _loss(score, truth, *fitted) < _loss(score, truth, *gaussian) - 1e-12


@pytest.fixture(scope="module")
def takes():
    return {name: [synthetic_motion(4, pattern, seed=seed, noise=0.2 + 0.2 * k, repetitions=5)
                   for k in range(4)]
            for name, pattern, seed in (("left", (0,), 1), ("both", (0, 2), 2),
                                        ("right", (2,), 3))}


def test_windows_stay_gaussian_so_parse_costs_are_distances(takes):
    assert describe_windows(takes, window=1.0).spread.tail == math.inf


def test_a_spread_keeps_its_tail_through_json(takes):
    spread = describe(takes).spread
    for tail in (spread.tail, 12.5, math.inf):
        again = Spread.from_dict(json.loads(json.dumps(_with(spread, tail).to_dict())))
        assert again.tail == tail


def _with(spread, tail):
    from dataclasses import replace
    return replace(spread, tail=tail)


@pytest.mark.parametrize("bad", [0, -1.0, "x", True, 1e400])
def test_a_tail_that_is_no_positive_number_is_refused_naming_it(takes, bad):
    data = describe(takes).spread.to_dict()
    text = json.dumps(data).replace('"tail": ' + json.dumps(data["tail"]),
                                    '"tail": ' + ("1e400" if bad == 1e400 else json.dumps(bad)))
    with pytest.raises(DescriptionError, match="tail"):
        Spread.from_dict(json.loads(text))


@pytest.mark.parametrize("field, value", [("tail", 1e-310), ("tail", 1e-200),
                                          ("temperature", 1e-310)])
def test_a_tail_or_temperature_too_small_to_score_with_is_named(takes, field, value):
    # accepted by the reader (a positive number), they made every probability NaN
    from dataclasses import replace

    from praxicon.recognition import recognise

    d = describe(takes)
    bad = replace(d, spread=replace(d.spread, **{field: value}))
    with pytest.raises(DescriptionError, match=f"the spread's {field} is {value:g}"):
        recognise(bad, synthetic_motion(4, (0,), seed=50, noise=0.3, repetitions=5))
