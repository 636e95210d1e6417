"""Extreme values for the BVH writer: what it writes reads back, in a file of sensible size.

Six decimals of 1e300 are 300 digits, and writing 343,000 such values took over 5 s; the
frame time of 9999.7 frames a second is 0.00010000 to eight decimals, which reads back as
10,000. Both are written in exponent form (``repr``), which reads back exactly. A rate the
reader refuses (3e8 fps, beyond FRAME_RATE_RANGE) is not written at all.
"""

from __future__ import annotations

import numpy as np
import pytest

from kinetology import Motion
from psgs.errors import ValidationError
from kinetology.bvh import parse_bvh
from kinetology.bvh_writer import format_bvh


def test_huge_values_are_written_in_exponent_form():
    motion = Motion(np.array([[1e300, -1e300, 1e15], [2.5e299, 1.0, -7e20]]),
                    ("a.rx", "a.ry", "a.rz"), 30.0)
    text = format_bvh(motion)
    assert max(len(token) for token in text.split()) <= 24
    assert np.array_equal(parse_bvh(text, source="huge.bvh").values, motion.values)


def test_a_frame_time_too_short_for_eight_decimals_reads_back_its_rate():
    text = format_bvh(Motion(np.zeros((2, 1)), ("a.rx",), 9999.7))
    (line,) = [line for line in text.splitlines() if line.startswith("Frame Time:")]
    assert line != "Frame Time: 0.00010000"
    assert parse_bvh(text, source="fast.bvh").frame_rate == 9999.7


@pytest.mark.parametrize("rate", [3e8, 10_000.5, 0.09])
def test_a_rate_the_reader_refuses_is_not_written(rate):
    with pytest.raises(ValidationError, match="outside 0.1 .. 10000 fps"):
        format_bvh(Motion(np.zeros((2, 1)), ("a.rx",), rate))
