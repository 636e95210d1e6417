"""Segmentation across frame rates and tempos: unwrapping, slow motion at 30 fps, displacements."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology import Motion
from kinetology.segmentation import DEFAULTS, channel_deadbands, segment, segments, unwrap


def wave(seconds, rate, period, amplitude, centre=0.0, name="arm.rz"):
    t = np.arange(int(round(seconds * rate))) / rate
    return Motion((centre + amplitude * np.sin(2 * np.pi * t / period))[:, None], (name,), rate)


def wrapped(motion):
    """The motion as a file stores it: angles folded into [-180, 180)."""
    values = (np.asarray(motion.values) + 180.0) % 360.0 - 180.0
    return Motion(values, motion.channels, motion.frame_rate)


def test_unwrap_removes_jumps_of_a_full_turn():
    angles = np.array([170.0, 179.0, -178.0, -170.0, 175.0])
    assert unwrap(angles).tolist() == [170.0, 179.0, 182.0, 190.0, 175.0]
    assert unwrap(angles, 0).tolist() == angles.tolist()


def test_an_angle_crossing_180_segments_like_the_same_angle_unwrapped():
    true = wave(4, 120, 1.0, 30, centre=175.0)  # swings across +-180 every cycle
    stored = wrapped(true)
    assert np.ptp(stored.values) > 300  # the file's fake range
    assert segment(stored).strings == segment(true).strings
    seg = segments(stored)
    assert seg.symbols(0)[:4] == ("G", "R", "Y", "B")
    # without unwrapping the jumps make wrong kinetemes
    assert segment(stored, unwrap=0).string("arm.rz") != segment(true).string("arm.rz")


def test_translations_are_never_unwrapped():
    t = np.arange(240) / 120
    values = np.stack([np.where(t < 1, 0.0, 300.0), 30 * np.sin(2 * np.pi * t)], axis=1)
    motion = Motion(values, ("root.tx", "root.rx"), 120)
    seg = segments(motion, channels=["root.tx", "root.rx"])
    assert seg.displacements[0].sum() == pytest.approx(300.0, abs=1.0)


@pytest.mark.parametrize("rate", [30, 120])
@pytest.mark.parametrize("period, amplitude", [(1.0, 30.0), (4.0, 20.0), (6.0, 10.0)])
def test_slow_and_brisk_waves_give_four_kinetemes_a_cycle_at_30_and_120_fps(rate, period,
                                                                              amplitude):
    cycles = 3
    ag = segment(wave(cycles * period, rate, period, amplitude))
    symbols = ag.string("arm.rz")
    assert symbols[:4] == ("G", "R", "Y", "B")
    assert abs(len(symbols) - 4 * cycles) <= 1


def test_the_old_fixed_dead_band_lost_slow_motion_at_30_fps():
    """Why the defaults changed: 200 deg/s^2 erased a slow raise's acceleration changes."""
    slow = wave(12, 30, 6.0, 10.0)
    old = segment(slow, smoothing=0.025, acceleration_deadband=200.0, relative_deadband=0.0)
    assert len(old.string("arm.rz")) < 4 * 2
    assert len(segment(slow).string("arm.rz")) >= 4 * 2


@settings(max_examples=30, deadline=None)
@given(period=st.floats(0.5, 1.5), amplitude=st.floats(10.0, 90.0),
       slow=st.sampled_from([1.5, 2.0, 3.0]))
def test_slowing_a_motion_down_keeps_its_kinetemes(period, amplitude, slow):
    """Tempo invariance: the same movement at 1/slow of the speed reads the same."""
    rng = np.random.default_rng(0)
    brisk = wave(2 * period, 30, period, amplitude)
    # a second harmonic so the shape is not a pure sine
    harmonic = 0.2 * amplitude * np.sin(4 * np.pi * np.arange(brisk.frames) / 30 / period + 1)
    brisk = Motion(brisk.values + harmonic[:, None] + rng.normal(0, 0.05, (brisk.frames, 1)),
                   brisk.channels, 30)
    t = np.arange(int(brisk.frames * slow)) / slow
    slowed = Motion(np.interp(t, np.arange(brisk.frames), brisk.values[:, 0])[:, None],
                    brisk.channels, 30)
    a, b = segment(slowed), segment(brisk)
    slow_string, brisk_string = a.string("arm.rz"), b.string("arm.rz")
    # equal, but for a last segment of a few frames that the ends of the two copies cut
    # differently (the slowed copy ends a fraction of a frame later in the movement)
    if len(slow_string) == len(brisk_string) + 1:
        assert a.durations["arm.rz"][-1] <= 0.15 * period * slow
        slow_string = slow_string[:-1]
    elif len(brisk_string) == len(slow_string) + 1:
        assert b.durations["arm.rz"][-1] <= 0.15 * period
        brisk_string = brisk_string[:-1]
    assert slow_string == brisk_string


def test_displacements_add_up_to_the_whole_change_and_follow_the_states():
    motion = wave(3, 120, 1.0, 30)
    seg = segments(motion)
    moves = seg.displacements[0]
    assert len(moves) == len(seg.codes[0])
    assert moves.sum() == pytest.approx(float(np.diff(motion.values[[0, -1], 0])[0]), abs=1.0)
    for code, move in zip(seg.codes[0], moves):
        assert (move > 0) == (code in (0, 1))  # B and G rise, R and Y fall


def test_channel_deadbands_follow_the_channel_with_a_floor():
    signal = np.stack([np.linspace(-100, 100, 201), np.linspace(-1, 1, 201)], axis=1)
    bands = channel_deadbands(signal, 5.0, 0.1)
    assert bands.tolist() == pytest.approx([9.5, 5.0])
    assert channel_deadbands(signal, 5.0, 0.0).tolist() == [5.0, 5.0]


def test_defaults_act_at_30_fps():
    assert DEFAULTS["smoothing"] * 30 >= 1.0  # at least one frame of smoothing
    assert DEFAULTS["unwrap"] == 360.0


def _direct_smooth(values, rate, sigma):
    frames = sigma * rate
    radius = min(max(1, int(np.ceil(3 * frames))), values.shape[0] - 1)
    offsets = np.arange(-radius, radius + 1)
    kernel = np.exp(-0.5 * (offsets / frames) ** 2)
    kernel /= kernel.sum()
    padded = np.pad(values, [(radius, radius), (0, 0)], mode="reflect", reflect_type="odd")
    return sum(w * padded[k:k + values.shape[0]] for k, w in enumerate(kernel))


@pytest.mark.parametrize("rate", [30, 120, 1000])  # direct sum, FFT, a long FFT kernel
def test_smoothing_equals_the_direct_gaussian_sum(rate):
    from kinetology.segmentation import smooth

    values = np.cumsum(np.random.default_rng(3).normal(size=(400, 3)), axis=0)
    np.testing.assert_allclose(smooth(values, rate, 0.05), _direct_smooth(values, rate, 0.05),
                               atol=1e-9)
    assert smooth(values[:, 0], rate, 0.05).shape == (400,)
