"""Damaged and hostile codec streams: every one a MotionFormatError, checked before allocating.

Each stream below is built field by field (the layout of :mod:`kinetology.codec.stream`), so
that a header can claim what no encoder writes: durations whose int64 sum wraps (formerly a
segfault in ``np.repeat``), integers past 2^63 (OverflowError), frame counts of 2^62 or a
million frames in a 35-byte stream (ValueError, a decoding loop of a frame at a time), and an
LZMA bomb (gigabytes from a few kilobytes). The encoder's promises are here too: ``max_error``
is met or refused, never an ``assert``, and residual levels past 62 bits are refused before
the int64 cast wraps them.
"""

from __future__ import annotations

import lzma
import struct
import tracemalloc

import numpy as np
import pytest

from kinetology import Motion, MotionFormatError, compress, decompress
from kinetology.codec import entropy, residual, stream
from kinetology.codec.varint import encode as varints


def _zigzag(n: int) -> int:
    return 2 * n if n >= 0 else -2 * n - 1


def kin(frames, names=("a.rx",), durations=((1,),), displacements=None, firsts=None,
        step=0.0, residual_bytes=b"", tail=b"", preset=9 | lzma.PRESET_EXTREME):
    """A ``KIN2`` stream with these fields (state codes B G R Y ... in order)."""
    displacements = displacements or [[0] * len(d) for d in durations]
    firsts = firsts or [0] * len(names)
    body = bytearray(varints([2])) + struct.pack("<d", 120.0) + varints([frames])
    body += struct.pack("<d", 0.5) + varints([len(names)])
    for name in names:
        body += varints([len(name)]) + name.encode()
    body += varints([len(d) for d in durations]) + varints([_zigzag(f) for f in firsts])
    for d in durations:
        body += bytes([0] + [1] * (len(d) - 1)) if d else b""
    for d in durations:
        body += varints(d)
    for d in displacements:
        body += varints([_zigzag(x) for x in d])
    body += struct.pack("<d", step) + tail
    # any preset up to the decoder's 9 reads back (its dictionary is the largest)
    base = lzma.compress(bytes(body), format=lzma.FORMAT_RAW,
                         filters=[{"id": lzma.FILTER_LZMA2, "preset": preset}])
    return b"KIN2" + varints([len(base)]) + base + residual_bytes


def test_a_well_formed_stream_of_this_builder_decodes():
    motion = decompress(kin(3, durations=[[1, 1]], displacements=[[4, -2]]))
    assert motion.frames == 3 and abs(motion.values[0, 0]) < 1e-9  # the first knot: 0


@pytest.mark.parametrize("data, words", [
    # durations 4 x 2^62 sum to 2^64, which int64 wraps to 0 = frames - 1: np.repeat segfaulted
    (kin(1, durations=[[2 ** 62] * 4]), "out of range"),
    (kin(2, durations=[[2 ** 63]]), "out of range"),                       # OverflowError
    (kin(2, displacements=[[2 ** 63]]), "out of range"),                   # OverflowError
    (kin(2, firsts=[2 ** 68]), "out of range"),                            # OverflowError
    (kin(2, durations=[[1]], displacements=[[2 ** 62 - 1]], firsts=[2 ** 62 - 1]),
     "out of range"),                                                      # a sum past 2^62
    (kin(2 ** 62, names=(), durations=()), "may claim"),                   # ValueError
    (kin(10 ** 9, durations=[[10 ** 9 - 1]]), "may claim"),                # 8 GB of frames
    (kin(10 ** 6, names=(), durations=(), step=1.0, residual_bytes=b"\x00"),  # looped 15 s+
     "cannot hold"),
])
def test_hostile_headers_are_format_errors(data, words):
    with pytest.raises(MotionFormatError, match=words):
        decompress(data)


def test_an_lzma_bomb_is_refused_before_it_is_inflated():
    data = kin(2, tail=bytes(80 << 20), preset=1)  # 80 MB of zeros after the base part
    assert len(data) < 64 << 10
    tracemalloc.start()
    try:
        with pytest.raises(MotionFormatError, match="decompresses to more than"):
            decompress(data)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 16 << 20  # the dictionary is as large as the 1 MiB the body may be


def test_max_samples_lets_a_long_still_motion_decode():
    data = kin(4_200_001, durations=[[4_200_000]])  # past the 2^22 samples a small stream may claim
    with pytest.raises(MotionFormatError, match="max_samples"):
        decompress(data)
    assert decompress(data, max_samples=4_200_001).frames == 4_200_001


def test_zero_lanes_decode_at_once_and_escapes_past_62_bits_are_errors():
    assert entropy.decode(b"\x00", 10 ** 9, 0).shape == (10 ** 9, 0)
    with pytest.raises(entropy.EntropyError):
        entropy.decode(b"\x01\x00", 10, 0)
    escaped = varints([1, 2 ** 63]) + varints([0]) + (1 << 16).to_bytes(4, "little")
    with pytest.raises(entropy.EntropyError, match="out of range"):
        entropy.decode(escaped, 1, 1)


def test_a_level_past_62_bits_is_refused_not_wrapped():
    # 1e19 / 1.0 does not fit int64: the cast gave INT64_MIN, which passed |x| < 2^62
    with pytest.raises(ValueError, match="62 bits"):
        residual.quantise(np.array([[1e19], [0.0], [0.0]]), 1.0, 0.7)
    with pytest.raises(ValueError, match="62 bits"):
        compress(Motion(np.array([[1e19], [0.0], [0.0]]), ("a.rx",), 120.0), quantum=1e300,
                 residual_step=1.0)


def test_max_error_is_met_or_refused():
    with pytest.raises(ValueError, match="no setting meets max_error=0.2"):
        compress(Motion(np.array([[0.0], [1e308]]), ("a.rx",), 120.0), max_error=0.2)
    walk = Motion(np.cumsum(np.random.default_rng(0).normal(size=(300, 2)), axis=0),
                  ("a.rx", "b.ry"), 120.0)
    for bound in (0.05, 0.3, 2.0):
        assert compress(walk, max_error=bound).mean_error <= bound


def test_truncated_lzma_data_is_an_error():
    data = kin(3, durations=[[1, 1]])
    length = data[4]  # one varint byte: the base part is short
    with pytest.raises(MotionFormatError):
        decompress(b"KIN2" + varints([length - 3]) + data[5:5 + length - 3])


@pytest.mark.parametrize("size", [1, 100, 5_000, 70_000])
def test_the_cut_dictionary_writes_the_bytes_of_the_full_one(size):
    """The encoder's dictionary is cut to the body's size (70 ms and 670 MB a stream saved):
    raw LZMA2 bytes do not depend on it while the body fits."""
    body = np.random.default_rng(size).integers(0, 40, size, dtype=np.uint8).tobytes()
    full = lzma.compress(body, format=lzma.FORMAT_RAW, filters=stream.FILTERS)
    assert lzma.compress(body, format=lzma.FORMAT_RAW, filters=stream._filters_for(size)) == full


@pytest.mark.parametrize("knots, codes, signal, message", [
    # more codes than segments were read from their first rows without a word
    ([0, 4, 8], [1, 2, 3], np.ones(9), "codes must be one state 0..3 for each of the 2"),
    ([0, 4, 8], [1], np.ones(9), "codes must be one state 0..3 for each of the 2"),
    ([0, 4, 4], [1, 2], np.ones(5), "knots must be whole frames rising from 0"),
    ([0, 4, 8], [1, 2], np.ones(12), "signal must be one finite number for each of the 9"),
    ([0, 4, 8], [1, 2], np.r_[np.ones(8), np.nan], "signal must be one finite number"),
])
def test_fit_knots_refuses_inputs_that_do_not_fit_one_another(knots, codes, signal, message):
    from kinetology.codec.quartic import fit_knots

    with pytest.raises(ValueError, match=message):
        fit_knots(np.array(knots), np.array(codes), signal)
