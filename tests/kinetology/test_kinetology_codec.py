"""Compression by segments and reconstruction by one quartic per segment."""

from __future__ import annotations

import os

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinetology
from kinetology import Motion, MotionFormatError, compress, decompress
from kinetology.baselines import quantise_delta_compress, quantise_delta_decompress
from kinetology.codec import basis, encode_segments, reconstruct
from kinetology.synthetic import synthetic_motion

from kinetology_fixtures import MOCAP, needs_mocap

FLAGS = [tuple(bool(k >> b & 1) for b in (3, 2, 1, 0)) for k in range(16)]


def _value(coefficients, s, derivative=0):
    poly = np.polynomial.Polynomial(coefficients)
    return poly.deriv(derivative)(s) if derivative else poly(s)


@pytest.mark.parametrize("flags", FLAGS)
def test_quartic_basis_meets_its_conditions(flags):
    lv, la, rv, ra = flags
    u, w = basis(*flags)
    for y0, y1 in ((1.0, 0.0), (0.0, 1.0), (2.5, -4.0)):
        c = y0 * u + y1 * w
        assert _value(c, 0.0) == pytest.approx(y0, abs=1e-9)
        assert _value(c, 1.0) == pytest.approx(y1, abs=1e-9)
        conditions = [(lv, 0.0, 1), (rv, 1.0, 1), (la, 0.0, 2), (ra, 1.0, 2)]
        kept = [c_ for c_ in conditions if c_[0]][: 3]  # at most 5 conditions in all
        for _, at, derivative in kept:
            assert _value(c, at, derivative) == pytest.approx(0.0, abs=1e-7)
    # a constant meets every condition with zero jerk: the basis must reproduce it
    np.testing.assert_allclose(u + w, [1, 0, 0, 0, 0], atol=1e-6)


def test_jerk_minimisation_picks_the_least_jerk_quartic():
    """Cross-check one pattern (velocity zero at both ends) against a brute-force search."""
    u, w = basis(True, False, True, False)
    best = u * 0 + w  # y0 = 0, y1 = 1
    # quartics with p(0)=0, p'(0)=0, p(1)=1, p'(1)=0: c2 = 3 - c4, c3 = -2 + ... one free c4
    jerk = []
    for c4 in np.linspace(-3, 3, 601):
        c3 = -2 - 2 * c4
        c2 = 3 + c4
        s = np.linspace(0, 1, 2001)
        third = 6 * c3 + 24 * c4 * s
        jerk.append((np.trapezoid(third ** 2, s), c4))
    assert best[4] == pytest.approx(min(jerk)[1], abs=0.011)


def test_round_trip_keeps_channels_frames_and_rate():
    m = synthetic_motion(6, (0, 1, 2), seed=2)
    back = decompress(compress(m))
    assert back.channels == m.channels and back.frames == m.frames
    assert back.frame_rate == m.frame_rate
    error = np.abs(back.values - m.values).mean()
    # amplitude 30 degrees, sensor noise 0.2: a few percent of the range at most
    assert error < 1.0, error


@settings(max_examples=25, deadline=None)
@given(st.integers(0, 2 ** 31), st.integers(2, 400), st.floats(0.01, 1.0))
def test_decoded_curve_passes_through_the_stored_knots(seed, frames, quantum):
    rng = np.random.default_rng(seed)
    values = np.cumsum(rng.normal(scale=2.0, size=(frames, 2)), axis=0)
    m = Motion(values, ("a.rx", "b.ry"), 60.0)
    encoded, q = encode_segments(m, quantum=quantum)
    back = decompress(compress(m, quantum=quantum))
    assert back.values.shape == values.shape
    for c, (knots, codes, knot_values) in enumerate(encoded):
        assert knots[0] == 0 and knots[-1] == frames - 1
        np.testing.assert_allclose(back.values[knots, c], knot_values * q, atol=1e-6)
        np.testing.assert_allclose(reconstruct(knots, codes, knot_values * q),
                                   back.values[:, c], atol=1e-9)


def test_constant_channel_decodes_within_half_a_quantum():
    m = Motion(np.full((50, 1), 12.34), ("c.rx",), 120)
    back = decompress(compress(m, quantum=0.1))
    assert np.abs(back.values - 12.34).max() <= 0.05 + 1e-9


def test_finer_settings_cost_bytes_and_buy_accuracy():
    m = synthetic_motion(6, (0, 1, 2), noise=0.05, seed=5)
    coarse = compress(m, smoothing=0.06, quantum=0.5)
    fine = compress(m, smoothing=0.01, quantum=0.01)
    err = [np.abs(decompress(d).values - m.values).mean() for d in (coarse, fine)]
    assert len(fine) > len(coarse) and err[1] < err[0]


@pytest.mark.parametrize("mangle, message", [
    (lambda d: b"XXXX" + d[4:], "magic"),
    (lambda d: d[:-20], "corrupt|ends"),
    (lambda d: b"", "magic"),
])
def test_corrupt_data_is_one_clear_error(mangle, message):
    data = compress(synthetic_motion(2, (0,), seed=1))
    with pytest.raises(MotionFormatError, match=message):
        decompress(mangle(data))


def test_quantise_delta_peer_error_is_rounding_only():
    m = synthetic_motion(4, (0,), seed=3)
    for step in (0.1, 1.0):
        back = quantise_delta_decompress(quantise_delta_compress(m, step))
        error = np.abs(back.values - m.values)
        assert error.max() <= step / 2 + 1e-9
        assert error.mean() == pytest.approx(step / 4, rel=0.15)


@needs_mocap
def test_beats_the_papers_size_and_error_at_once_on_a_cmu_file():
    path = MOCAP / "cmu-mocap6" / "amc" / "13_30.amc"
    m = kinetology.read(path)
    data = compress(m)
    back = decompress(data)
    percent = 100 * len(data) / os.path.getsize(path)
    error = np.abs(back.values - m.values).mean()
    assert percent < 3.698 and error < 0.823, (percent, error)


def _packed(frames, names, durations):
    """A KIN1 stream with one segment per channel (state B) and the given durations."""
    import lzma
    import struct

    from kinetology.codec import _FILTERS, _MAGIC, _varints

    body = _varints([1]) + struct.pack("<d", 120.0) + _varints([frames])
    body += struct.pack("<d", 0.5) + _varints([len(names)])
    for name in names:
        body += _varints([len(name)]) + name.encode()
    body += _varints([1] * len(names)) + _varints([0] * len(names)) + bytes(len(names))
    body += _varints(durations) + _varints([0] * len(names))
    return _MAGIC + lzma.compress(body, format=lzma.FORMAT_RAW, filters=_FILTERS)


def test_crafted_streams_are_one_clear_error_not_a_traceback():
    assert decompress(_packed(3, ["a"], [2])).frames == 3  # the helper itself is valid
    huge = 2 ** 40  # consistent durations, 8 TiB of decoded values
    with pytest.raises(MotionFormatError, match="do not fit in memory"):
        decompress(_packed(huge, ["a"], [huge - 1]))
    with pytest.raises(MotionFormatError, match="do not add up"):
        decompress(_packed(huge, ["a"], [5]))
    with pytest.raises(MotionFormatError, match="distinct"):
        decompress(_packed(3, ["a", "a"], [2, 2]))


def test_empty_motion_round_trips_and_tiny_quantum_is_refused():
    empty = Motion(np.zeros((0, 2)), ("a.rx", "b.rx"), 30)
    back = decompress(compress(empty))
    assert back.values.shape == (0, 2) and back.channels == empty.channels
    m = synthetic_motion(2, (0,), seed=1)
    with pytest.raises(ValueError, match="too small"):
        compress(m, quantum=1e-300)
