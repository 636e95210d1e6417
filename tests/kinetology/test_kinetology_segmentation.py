"""Segmentation: states from the signs of velocity and acceleration, dead bands, actiongrams."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import psgs
from kinetology import Motion, segment, segments
from kinetology.segmentation import DEFAULTS, STATES, significant_sign, smooth, states
from kinetology.synthetic import synthetic_motion

from kinetology_fixtures import MOCAP, needs_mocap, real_take


def _wave(frames=480, rate=120.0, amplitude=30.0, hz=1.0, noise=0.0, seed=0):
    t = np.arange(frames) / rate
    rng = np.random.default_rng(seed)
    return t, amplitude * np.sin(2 * np.pi * hz * t) + rng.normal(scale=noise, size=frames)


def _analytic_states(velocity, acceleration):
    falling = velocity < 0
    braking = (velocity >= 0) == (acceleration < 0)
    return 2 * falling + braking


def test_state_letters_follow_the_documented_signs():
    t, x = _wave()
    code = states(x, 120.0)
    truth = _analytic_states(np.cos(2 * np.pi * t), -np.sin(2 * np.pi * t))
    # only frames right at a zero crossing may differ
    assert (code == truth).mean() > 0.97
    assert STATES == ("B", "G", "R", "Y")
    # rising and slowing down between 0 and a quarter period is G
    assert STATES[code[int(0.12 * 120)]] == "G"
    assert STATES[code[int(0.37 * 120)]] == "R"
    assert STATES[code[int(0.62 * 120)]] == "Y"
    assert STATES[code[int(0.87 * 120)]] == "B"


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(st.floats(0.3, 3.0), st.floats(1.0, 40.0), st.floats(0, 6.28)),
                min_size=1, max_size=3))
def test_states_match_analytic_derivative_signs(components):
    """Smooth sums of sinusoids: without smoothing or dead band, the states are the
    signs of the true derivatives except within a frame or two of a zero crossing."""
    rate = 120.0
    t = np.arange(600) / rate
    x = sum(a * np.sin(2 * np.pi * f * t + p) for f, a, p in components)
    v = sum(a * 2 * np.pi * f * np.cos(2 * np.pi * f * t + p) for f, a, p in components)
    acc = sum(-a * (2 * np.pi * f) ** 2 * np.sin(2 * np.pi * f * t + p) for f, a, p in components)
    code = states(x, rate, smoothing=0, velocity_deadband=0, acceleration_deadband=0,
                  relative_deadband=0)
    truth = _analytic_states(v, acc)
    # a frame may differ only where v or a changes sign within 2 frames of it
    near = np.zeros(t.size, bool)
    for signal in (v, acc):
        flips = np.flatnonzero(np.diff(np.sign(signal)) != 0)
        for k in range(-2, 3):
            near[np.clip(flips + k, 0, t.size - 1)] = True
    near[:2] = near[-2:] = True  # one-sided differences at the ends
    assert np.all((code == truth) | near)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(-50, 50), min_size=1, max_size=200), st.floats(0, 20))
def test_significant_sign_absorbs_only_small_runs(values, band):
    x = np.array(values)
    s = significant_sign(x, band)
    assert set(np.unique(s)) <= {-1, 1}
    # every run of the output contains a sample beyond the band with its sign,
    # unless nothing exceeds the band at all
    if np.abs(x).max() <= band:
        assert (s == 1).all()
        return
    starts = np.concatenate(([0], np.flatnonzero(np.diff(s)) + 1))
    for a, b in zip(starts, np.append(starts[1:], x.size)):
        assert np.any(s[a] * x[a:b] > band)
    if band == 0:
        nonzero = x != 0
        np.testing.assert_array_equal(s[nonzero], np.sign(x[nonzero]))


def test_dead_band_keeps_noise_from_splitting_segments():
    _, clean = _wave(noise=0.0)
    _, noisy = _wave(noise=0.3, seed=3)
    m_clean = Motion(clean[:, None], ("a.rx",), 120)
    m_noisy = Motion(noisy[:, None], ("a.rx",), 120)
    clean_string = "".join(segment(m_clean).string("a.rx"))
    noisy_string = "".join(segment(m_noisy).string("a.rx"))
    # noise may add or drop a symbol at an end of the recording, never inside it
    assert clean_string[1:-1] in noisy_string
    assert abs(len(noisy_string) - len(clean_string)) <= 2
    # without smoothing and dead bands the same noise shatters the signal
    raw = segment(m_noisy, smoothing=0, velocity_deadband=0, acceleration_deadband=0)
    assert len(raw.string("a.rx")) > 5 * len(segment(m_clean).string("a.rx"))


def test_still_channels_are_left_out():
    _, wave = _wave()
    rng = np.random.default_rng(1)
    still = 10 + rng.normal(scale=0.1, size=wave.size)
    m = Motion(np.column_stack([wave, still]), ("move.rx", "still.rx"), 120)
    seg = segments(m)
    assert seg.channels == ("move.rx",) and seg.still == ("still.rx",)
    assert segments(m, min_range=0).channels == ("move.rx", "still.rx")


def test_translations_are_not_segmented_by_default():
    _, wave = _wave()
    m = Motion(np.column_stack([wave, wave]), ("root.tx", "root.rx"), 120)
    assert segments(m).channels == ("root.rx",)
    assert segments(m, channels=["root.tx"]).channels == ("root.tx",)


def test_actiongram_times_are_seconds_and_reads_back(tmp_path):
    m = synthetic_motion(5, (0, 1), seed=4)
    ag = segment(m)
    for name in ag.names:
        assert sum(ag.durations[name]) == pytest.approx(m.duration, abs=1e-4)
        syms = ag.string(name)
        assert all(a != b for a, b in zip(syms, syms[1:]))
        assert set(syms) <= set(STATES)
    path = tmp_path / "synthetic.actiongram"
    path.write_text(ag.to_text())
    back = psgs.load(path)
    assert back.names == ag.names
    assert all(back.string(n) == ag.string(n) for n in ag.names)


def test_same_motion_at_30_and_120_fps_gives_the_same_string():
    strings = []
    for rate in (30.0, 120.0):
        t = np.arange(int(4 * rate)) / rate
        x = 25 * np.sin(2 * np.pi * 0.8 * t) + 10 * np.sin(2 * np.pi * 1.6 * t + 1)
        strings.append(segment(Motion(x[:, None], ("k.rx",), rate)))
    coarse, fine = strings[0].string("k.rx"), strings[1].string("k.rx")
    # the same string, but for a last segment shorter than 3 frames at 30 fps (0.1 s), which
    # the 120 fps recording resolves and the 30 fps one cannot
    if len(fine) == len(coarse) + 1:
        assert strings[1].durations["k.rx"][-1] < 0.1
        fine = fine[:-1]
    assert coarse == fine
    n = len(coarse) - 1
    np.testing.assert_allclose(strings[0].durations["k.rx"][1:n],
                               strings[1].durations["k.rx"][1:n], atol=2 / 30)


def test_bad_parameters_are_errors():
    m = synthetic_motion(2, (0,), seed=0)
    with pytest.raises(TypeError, match="unknown segmentation parameter"):
        segments(m, smoothness=1)
    with pytest.raises(ValueError, match="non-negative"):
        segments(m, smoothing=-1)
    with pytest.raises(KeyError, match="no channel"):
        segments(m, channels=["nope"])


def test_smoothing_preserves_constants_and_lines():
    line = np.linspace(0, 10, 50)[:, None]
    np.testing.assert_allclose(smooth(line, 120, 0.05), line, atol=1e-9)
    assert DEFAULTS["smoothing"] > 0


@needs_mocap
def test_real_amc_segments_into_an_actiongram_psgs_reads(tmp_path):
    m = real_take(MOCAP / "cmu-subject02" / "02_01.amc")
    ag = segment(m)
    assert "ltibia.rx" in ag.names and len(ag.names) >= 40
    # a walking knee flexes about once a step: B G R Y cycles dominate
    knee = "".join(ag.string("ltibia.rx"))
    assert knee.count("BGRY") >= 2
    path = tmp_path / "walk.txt"
    path.write_text(ag.to_text())
    assert psgs.load(path, kind="actiongram").names == ag.names


def test_shared_defaults_and_tables_are_read_only():
    from kinetology.codec import CODEC_DEFAULTS, basis
    from kinetology.evaluation import BANDAI_ANGLES, CMU_ANGLES, CMU_BVH_ANGLES
    from kinetology.plotting import STATE_COLOURS

    for table in (DEFAULTS, CODEC_DEFAULTS, CMU_ANGLES, CMU_BVH_ANGLES, BANDAI_ANGLES,
                  STATE_COLOURS):
        with pytest.raises(TypeError):
            table["smoothing"] = 1.0
    u, _ = basis(True, False, True, False)  # cached: a write would change later calls
    with pytest.raises(ValueError):
        u[0] = 1.0
