"""The fast segmentation engine gives exactly the answers of the plain per-channel rules.

The references below are written the straightforward way (a loop over frames per channel, the
former code's smoothing, Python's ``round``, ``Actiongram.from_strings``); the engine in
:mod:`kinetology._kinetemes` and :meth:`psgs.Actiongram.from_codes` must equal them exactly.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology import Motion
from kinetology._kinetemes import gaussian_kernel, round_half_even
from kinetology.performances import segment_performances
from kinetology.segmentation import DEFAULTS, STATES, segments, smooth, unwrap
from psgs import Actiongram
from psgs.errors import FormatError


# -- references ------------------------------------------------------------------------

def reference_smooth_direct(values, frame_rate, sigma):
    """The former code's smoothing for short kernels: np.pad, then shifted copies in pairs."""
    radius, kernel = gaussian_kernel(frame_rate, sigma, values.shape[0])
    padded = np.pad(values, [(radius, radius)] + [(0, 0)] * (values.ndim - 1), mode="reflect",
                    reflect_type="odd")
    frames = values.shape[0]
    out = kernel[radius] * padded[radius:radius + frames]
    for k in range(radius):
        out = out + (padded[k:k + frames] + padded[2 * radius - k:2 * radius - k + frames]) \
            * kernel[k]
    return out


def reference_sign(signal, band):
    """Dead-band sign, one frame at a time: runs whose peak |x| stays within the band take the
    sign of the last run that did not (the first such run's sign before it; +1 when none)."""
    runs = []  # [sign, peak, length]
    for x in signal:
        s = 1 if x >= 0 else -1
        if runs and runs[-1][0] == s:
            runs[-1][1] = max(runs[-1][1], abs(x))
            runs[-1][2] += 1
        else:
            runs.append([s, abs(x), 1])
    counting = [r[0] for r in runs if r[1] > band]
    if not counting:
        return [1] * len(signal)
    out, current = [], counting[0]
    for s, peak, length in runs:
        if peak > band:
            current = s
        out.extend([current] * length)
    return out


def reference_segments(motion, channels=None, **params):
    """(channels, borders, codes, displacements) by loops, from the public smoothing."""
    p = {**DEFAULTS, **params}
    if channels is None:
        channels = [c for c in motion.channels if c.rsplit(".", 1)[-1] not in ("tx", "ty", "tz")]
    kept, out = [], []
    for name in channels:
        x = motion.column(name).astype(float)
        rotation = name.rsplit(".", 1)[-1] not in ("tx", "ty", "tz")
        if p["unwrap"] > 0 and rotation and x.size > 1 and \
                np.abs(np.diff(x)).max() > p["unwrap"] / 2:
            x = unwrap(x, p["unwrap"])
        s = smooth(x, motion.frame_rate, p["smoothing"])
        if not motion.frames or np.ptp(s) < p["min_range"]:
            continue
        n, rate = s.size, motion.frame_rate
        if n < 3:
            v = a = np.zeros(n)
        else:
            v = np.gradient(s) * rate
            a = np.gradient(v) * rate
        signs = []
        for signal, floor in ((v, p["velocity_deadband"]), (a, p["acceleration_deadband"])):
            band = floor
            if p["relative_deadband"] > 0:
                step = max(1, n // 8192)
                band = max(floor, p["relative_deadband"] * np.percentile(np.abs(signal[::step]),
                                                                         95))
            signs.append(reference_sign(signal, band))
        code = [2 * (sv < 0) + ((sv > 0) == (sa < 0)) for sv, sa in zip(*signs)]
        borders, codes, moves = [], [], []
        for t in range(n):
            if t == 0 or code[t] != code[t - 1]:
                if borders:
                    moves.append(s[t] - s[borders[-1]])
                borders.append(t)
                codes.append(code[t])
        moves.append(s[n - 1] - s[borders[-1]])
        kept.append(name)
        out.append((borders + [n], codes, moves))
    return kept, out


def reference_actiongram(found):
    """The former ``Segmentation.to_actiongram``: Python's round, then from_strings."""
    digits = 6 + max(0, int(np.ceil(np.log10(found.frame_rate))) - 4)
    strings = {n: found.symbols(c) for c, n in enumerate(found.channels)}
    durations = {n: tuple(round(float(d), digits) for d in found.durations(c))
                 for c, n in enumerate(found.channels)}
    moves = {n: tuple(round(float(x), 3) for x in found.displacements[c])
             for c, n in enumerate(found.channels)}
    return Actiongram.from_strings(strings, durations, displacements=moves,
                                   actuators=dict(found.actuators) or None,
                                   skeleton=dict(found.skeleton) or None)


# -- strategies ------------------------------------------------------------------------

@st.composite
def motions(draw, max_frames=90):
    frames = draw(st.integers(1, max_frames))
    count = draw(st.integers(1, 4))
    rate = draw(st.sampled_from([10.0, 30.0, 60.0, 120.0]))
    seed = draw(st.integers(0, 2 ** 16))
    rng = np.random.default_rng(seed)
    columns = []
    for _ in range(count):
        kind = draw(st.sampled_from(["walk", "wrap", "constant", "sine", "steps"]))
        if kind == "walk":
            column = np.cumsum(rng.normal(scale=draw(st.sampled_from([0.1, 2.0, 20.0])),
                                          size=frames))
        elif kind == "wrap":  # an angle turning through +-180 deg, as a file stores it
            column = (np.cumsum(rng.normal(8.0, 3.0, size=frames)) + 180) % 360 - 180
        elif kind == "constant":
            column = np.full(frames, draw(st.sampled_from([0.0, -179.5, 42.0])))
        elif kind == "sine":
            column = 40 * np.sin(np.arange(frames) / rate * 2 * np.pi * rng.uniform(0.2, 3))
        else:  # integer steps: exact zeros in the derivatives, ties in the percentiles
            column = np.round(np.cumsum(rng.integers(-1, 2, size=frames)) * 3.0)
        columns.append(column)
    names = tuple(f"j{i}.{axis}" for i, axis in
                  zip(range(count), draw(st.lists(st.sampled_from(["rx", "ry", "rz", "tx"]),
                                                  min_size=count, max_size=count))))
    return Motion(np.column_stack(columns), names, rate)


deadbands = st.fixed_dictionaries({
    "smoothing": st.sampled_from([0.0, 0.01, 0.05, 0.2]),
    "velocity_deadband": st.sampled_from([0.0, 0.5, 2.0, 50.0, 1e9]),
    "acceleration_deadband": st.sampled_from([0.0, 10.0, 500.0, 1e9]),
    "relative_deadband": st.sampled_from([0.0, 0.05, 0.5, 1.0]),
    "min_range": st.sampled_from([0.0, 2.0]),
    "unwrap": st.sampled_from([0.0, 360.0]),
})


# -- the engine against the references -------------------------------------------------

@settings(max_examples=150)
@given(motions(), deadbands)
def test_segments_equal_the_per_frame_reference_exactly(motion, params):
    found = segments(motion, **params)
    channels, expected = reference_segments(motion, **params)
    assert found.channels == tuple(channels)
    for c, (borders, codes, moves) in enumerate(expected):
        assert found.borders[c].tolist() == borders
        assert found.codes[c].tolist() == codes
        assert found.displacements[c].tolist() == moves  # exactly, not approximately


@settings(max_examples=60)
@given(motions(), deadbands)
def test_to_actiongram_equals_the_former_construction(motion, params):
    found = segments(motion, **params)
    fast, slow = found.to_actiongram(), reference_actiongram(found)
    assert fast == slow
    assert fast.to_text() == slow.to_text() and fast.to_json() == slow.to_json()


def test_long_takes_equal_the_reference_too():
    """Several channel groups and the banded product (120 fps) on 40,000 frames."""
    rng = np.random.default_rng(5)
    values = np.cumsum(rng.normal(size=(40_000, 5)), axis=0)
    values[:, 1] = (values[:, 1] * 30 + 180) % 360 - 180  # wraps
    values[:, 2] = 7.0
    motion = Motion(values, ("a.rx", "b.ry", "c.rz", "d.rx", "e.ry"), 120.0)
    found = segments(motion)
    channels, expected = reference_segments(motion)
    assert found.channels == tuple(channels) and len(channels) == 4
    for c, (borders, codes, moves) in enumerate(expected):
        assert found.borders[c].tolist() == borders
        assert found.codes[c].tolist() == codes
        assert found.displacements[c].tolist() == moves


@settings(max_examples=80)
@given(st.integers(2, 400), st.integers(1, 7), st.sampled_from([10.0, 30.0, 50.0, 120.0, 240.0]),
       st.sampled_from([0.01, 0.05, 0.2]), st.integers(0, 1000))
def test_every_kernel_smooths_as_plain_shifted_copies(frames, count, rate, sigma, seed):
    """One summation order for every kernel length, channel count and block: the result is
    the plain shifted-copies sum to the bit (formerly long kernels went through BLAS, whose
    order depends on the CPU and the matrix shape)."""
    values = np.cumsum(np.random.default_rng(seed).normal(size=(frames, count)), axis=0)
    assert np.array_equal(smooth(values, rate, sigma),
                          reference_smooth_direct(values, rate, sigma))


@settings(max_examples=40)
@given(st.integers(2, 3000), st.integers(1, 9), st.integers(0, 1000))
def test_long_kernels_are_a_convolution_and_each_channel_its_own(frames, count, seed):
    values = np.cumsum(np.random.default_rng(seed).normal(size=(frames, count)), axis=0)
    out = smooth(values, 120.0, 0.05)
    radius, kernel = gaussian_kernel(120.0, 0.05, frames)
    padded = np.pad(values, [(radius, radius), (0, 0)], mode="reflect", reflect_type="odd")
    for c in range(count):
        exact = np.convolve(padded[:, c], kernel, mode="valid")
        assert np.allclose(out[:, c], exact, rtol=0, atol=1e-12 * (1 + np.abs(values).max()))
        # a channel's smoothing does not depend on the channels beside it
        assert np.array_equal(out[:, c], smooth(values[:, c], 120.0, 0.05))


@pytest.mark.parametrize("rate, sigma, frames", [(120.0, 0.05, 1000), (30.0, 0.05, 1000),
                                                 (120.0, 0.025, 1000), (7.3, 0.31, 5)])
def test_the_kernel_is_the_correctly_rounded_gaussian(rate, sigma, frames):
    """Each weight is the float nearest exp(-k^2 / 2 s^2) / sum, computed independently
    with exact rationals and a Taylor series (no libm, whose last bit varies by CPU)."""
    from fractions import Fraction
    radius, kernel = gaussian_kernel(rate, sigma, frames)
    spread = Fraction(sigma * rate)

    def exp_neg(x):  # exp(-x) for a rational x >= 0 to far beyond double precision
        halvings = 0
        while x > Fraction(1, 4):
            x, halvings = x / 2, halvings + 1
        term, total = Fraction(1), Fraction(1)
        for n in range(1, 40):
            term = term * -x / n
            total += term
            total = Fraction(total.numerator * 10 ** 60 // total.denominator, 10 ** 60)
        for _ in range(halvings):
            total = total * total
            total = Fraction(total.numerator * 10 ** 60 // total.denominator, 10 ** 60)
        return total

    weights = [exp_neg(Fraction(k * k) / (2 * spread * spread))
               for k in range(-radius, radius + 1)]
    total = sum(weights)
    expected = [float(w / total) for w in weights]
    assert kernel.tolist() == expected
    assert not kernel.flags.writeable


# -- rounding --------------------------------------------------------------------------

@settings(max_examples=150)
@given(st.lists(st.one_of(st.floats(allow_nan=True, allow_infinity=True),
                          st.floats(-1e4, 1e4),
                          st.integers(-10 ** 7, 10 ** 7).map(lambda k: k / 2000),  # halves
                          st.integers(-10 ** 9, 10 ** 9).map(lambda k: k * 5e-7)),
                min_size=1, max_size=40),
       st.sampled_from([0, 3, 6, 7, 9, 23]))
def test_round_half_even_is_pythons_round_bit_for_bit(values, digits):
    expected = [round(v, digits) for v in values]
    got = round_half_even(np.array(values), digits).tolist()
    for e, g in zip(expected, got):
        assert (math.isnan(e) and math.isnan(g)) or (e == g and math.copysign(1, e)
                                                      == math.copysign(1, g)), (e, g)


# -- Actiongram.from_codes against from_strings ----------------------------------------

numbers = st.one_of(st.floats(0.001, 100.0), st.integers(1, 5), st.just(0.0), st.just(-1.0),
                    st.just(float("nan")), st.just(float("inf")), st.just(1e308),
                    st.just(True))


@st.composite
def coded(draw):
    alphabet = draw(st.sampled_from(["BGRY", "ab", ("x", "x"), ("a", "b c")]))
    names = draw(st.lists(st.sampled_from(["knee.rx", "hip.ry", "bad name", "", "x"]),
                          min_size=0, max_size=3, unique=True))
    codes, durations, moves = {}, {}, {}
    for name in names:
        size = draw(st.integers(0, 6))
        codes[name] = draw(st.lists(st.integers(0, len(alphabet) - 1), min_size=size,
                                    max_size=size))
        if draw(st.booleans()):
            extra = draw(st.integers(0, 1)) if draw(st.integers(0, 9)) == 0 else 0
            durations[name] = draw(st.lists(numbers, min_size=size + extra,
                                            max_size=size + extra))
        if draw(st.booleans()):
            moves[name] = draw(st.lists(st.one_of(st.floats(-90, 90), st.just(float("nan"))),
                                        min_size=size, max_size=size))
    actuators = {n: draw(st.sampled_from(["knee", "hip", "bad joint"]))
                 for n in names if draw(st.booleans())}
    skeleton = draw(st.sampled_from([None, {"knee": "hip", "hip": None},
                                     {"knee": "hip", "hip": "knee"}]))
    return alphabet, codes, durations, moves, actuators, skeleton


def _outcome(build):
    try:
        return build()
    except (FormatError, ValueError) as exc:
        return type(exc), str(exc)


@settings(max_examples=200)
@given(coded(), st.booleans())
def test_from_codes_is_from_strings_of_the_decoded_symbols(case, as_arrays):
    alphabet, codes, durations, moves, actuators, skeleton = case
    strings = {n: [alphabet[k] for k in row] for n, row in codes.items()}
    wrap = (lambda rows: {n: np.array(r) for n, r in rows.items()}) if as_arrays else dict
    fast = _outcome(lambda: Actiongram.from_codes(
        wrap(codes) if codes and all(codes.values()) else codes, alphabet,
        wrap(durations) if as_arrays and all(not isinstance(x, bool) for r in durations.values()
                                             for x in r) else durations,
        displacements=moves or None, actuators=actuators or None, skeleton=skeleton))
    slow = _outcome(lambda: Actiongram.from_strings(
        strings, durations, displacements=moves or None, actuators=actuators or None,
        skeleton=skeleton))
    if isinstance(fast, tuple) and "alphabet:" in fast[1]:
        # a symbol that cannot be one is named as such, even when no code uses it
        assert fast[0] is FormatError and any(" " in sym for sym in alphabet)
        return
    assert fast == slow


def test_from_codes_rejects_codes_outside_the_alphabet():
    with pytest.raises(ValueError, match="index the alphabet"):
        Actiongram.from_codes({"knee": [0, 4]}, "BGRY")
    with pytest.raises(ValueError, match="1-D array of integers"):
        Actiongram.from_codes({"knee": [0.5]}, "BGRY")


# -- performances ----------------------------------------------------------------------

@settings(max_examples=30)
@given(st.lists(motions(max_frames=60), min_size=1, max_size=3), deadbands)
def test_segment_performances_equals_segmenting_the_union(takes, params):
    names = takes[0].channels
    takes = [Motion(np.resize(t.values, (t.frames, len(names))), names, t.frame_rate)
             for t in takes]
    moving = set()
    for take in takes:
        moving.update(segments(take, **params).channels)
    union = [c for c in names if c in moving]
    expected = [segments(t, union, **{**params, "min_range": 0.0}).to_actiongram()
                for t in takes]
    assert list(segment_performances(takes, **params)) == expected
