"""Extreme values for the BVH writer: what it writes reads back, in a file of sensible size.

Six decimals of 1e300 are 300 digits, and writing 343,000 such values took over 5 s; the
frame time of 3e8 frames a second is 0.00000000 to eight decimals, which reads back as no
rate at all. Both are written in exponent form (``repr``), which reads back exactly.
"""

from __future__ import annotations

import numpy as np

from kinetology import Motion
from kinetology.bvh import parse_bvh
from kinetology.bvh_writer import format_bvh


def test_huge_values_are_written_in_exponent_form():
    motion = Motion(np.array([[1e300, -1e300, 1e15], [2.5e299, 1.0, -7e20]]),
                    ("a.rx", "a.ry", "a.rz"), 30.0)
    text = format_bvh(motion)
    assert max(len(token) for token in text.split()) <= 24
    assert np.array_equal(parse_bvh(text, source="huge.bvh").values, motion.values)


def test_a_frame_time_too_short_for_eight_decimals_reads_back_its_rate():
    text = format_bvh(Motion(np.zeros((2, 1)), ("a.rx",), 3e8))
    (line,) = [line for line in text.splitlines() if line.startswith("Frame Time:")]
    assert line != "Frame Time: 0.00000000"
    assert parse_bvh(text, source="fast.bvh").frame_rate == 3e8
