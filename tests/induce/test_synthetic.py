"""The synthetic protocol: the paper's settings exactly, ground truth, variants, the sweep."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs.induce import Induction
from psgs.induce.sweep import noise_sweep
from psgs.induce.synthetic import PAPER_POINTS, generate, success


@settings(max_examples=30, deadline=None)
@given(seed=st.integers(0, 10**6), noise=st.sampled_from([0.0, 0.07, 0.1, 0.25, 0.4]))
def test_paper_protocol_shape(seed, noise):
    case = generate(seed=seed, noise=noise)
    ag = case.actiongram
    assert len(ag) == 20
    assert all(len(s) == 100 for s in ag.symbols)  # no merging happened
    assert all(d == 1.0 for durs in ag.segment_durations for d in durs)
    assert len(set().union(*map(set, ag.symbols))) <= 20
    assert len(case.components) == 4
    assert len(set(case.patterns.values())) == 4
    for name in case.components:
        template = case.patterns[name]
        assert len(template) == 8
        string = ag.string(name)
        intact = sum(string[10 * k:10 * k + 8] == template for k in range(10))
        changed = sum(a != b for a, b in zip(string, generate(seed=seed).actiongram.string(name)))
        assert changed == round(noise * 100)
        if noise == 0:
            assert intact == 10


def test_same_seed_same_actiongram_and_noise_only_changes_symbols():
    assert generate(seed=5, noise=0.1) == generate(seed=5, noise=0.1)
    clean, noisy = generate(seed=5), generate(seed=5, noise=0.1)
    assert clean.components == noisy.components and clean.patterns == noisy.patterns


@pytest.mark.parametrize("variant", [dict(durations="random"), dict(irregular_gaps=True),
                                     dict(unequal_lengths=True)])
def test_variants_keep_copies_synchronous_in_time(variant):
    case = generate(seed=9, **variant)
    ag = case.actiongram
    for name in case.components:
        starts = ag.starts[name]
        for window_start, _ in case.windows:
            assert any(abs(t - window_start) < 1e-9 for t in starts)
    if variant.get("unequal_lengths"):
        assert len({len(s) for s in ag.symbols}) > 1
    if variant.get("durations") == "random":
        assert len({d for durs in ag.segment_durations for d in durs}) > 100


def test_all_random_variant_has_no_truth():
    case = generate(seed=1, patterned=0)
    assert case.components == () and case.patterns == {}
    assert all(a != b for s in case.actiongram.symbols for a, b in zip(s, s[1:]))


def test_success_criterion_is_exact():
    case = generate(seed=2)
    right = Induction(None, case.components, dict(case.patterns), {})
    assert success(right, case)
    first = case.components[0]
    rotated = dict(case.patterns)
    rotated[first] = rotated[first][1:] + rotated[first][:1]
    assert not success(Induction(None, case.components, rotated, {}), case)
    assert not success(Induction(None, case.components[:3],
                                 {n: case.patterns[n] for n in case.components[:3]}, {}), case)


def test_bad_arguments():
    for bad in (dict(noise=-0.1), dict(noise=1.5), dict(patterned=9), dict(durations="x")):
        with pytest.raises(ValueError):
            generate(seed=0, **bad)


def test_noise_sweep_counts_successes():
    calls = []
    rows = noise_sweep([0.0, 0.4], 3, inducers=("pal", "sequential"),
                       progress=lambda d, t: calls.append((d, t)))
    assert calls[-1] == (4, 4)
    by = {(r.inducer, r.noise): r for r in rows}
    assert by["pal", 0.0].successes == 3 and by["pal", 0.0].rate == 1.0
    assert by["sequential", 0.0].successes == 0
    assert all(r.trials == 3 for r in rows)
    assert PAPER_POINTS[0.10] == 0.96


@pytest.mark.parametrize("seed", [-1, 1.5, True, "3"])
def test_seed_must_be_a_non_negative_integer(seed):
    with pytest.raises(ValueError, match="seed must be a non-negative integer"):
        generate(seed=seed)


def test_ground_truth_is_a_read_only_value():
    import pickle

    case = generate(seed=4)
    with pytest.raises(TypeError):
        case.patterns[case.components[0]] = ("x",)
    with pytest.raises(TypeError):
        case.params["noise"] = 0.5
    again = pickle.loads(pickle.dumps(case))
    assert again == case and dict(again.patterns) == dict(case.patterns)


def test_small_alphabets_are_refused_instead_of_drawing_forever():
    # with 3 letters a noise symbol differing from itself and two distinct neighbours cannot exist
    with pytest.raises(ValueError, match="alphabet >= 4"):
        generate(seed=0, noise=0.3, alphabet=3, template_length=3)
    case = generate(seed=0, noise=0.3, alphabet=4, template_length=3)
    assert all(a != b for s in case.actiongram.symbols for a, b in zip(s, s[1:]))
    with pytest.raises(ValueError, match="gap >= 1"):
        generate(seed=0, template_length=1, gap=0)
