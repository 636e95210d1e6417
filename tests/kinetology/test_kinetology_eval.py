"""The five principles measured: view-invariance, reproducibility, selectivity; synthetic motion."""

from __future__ import annotations

import numpy as np
import pytest

from kinetology.bvh import parse_bvh
from kinetology.evaluation import (CMU_ANGLES, describe, mocap6_performances, reproducibility,
                                   selectivity, view_invariance)
from kinetology.segmentation import STATES
from kinetology.synthetic import synthetic_motion

from kinetology_fixtures import MOCAP, needs_mocap, real_take


def _planar_leg(frames=360, rate=120.0):
    """A hip-knee-ankle chain whose knee bends about x: all motion in the y-z plane."""
    t = np.arange(frames) / rate
    knee = 40 + 35 * np.sin(2 * np.pi * 1.0 * t)
    rows = "\n".join(f"0 0 0 0 0 0 0 0 0 0 0 {k:.5f}" for k in knee)
    text = f"""HIERARCHY
ROOT Hip
{{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation
  JOINT Thigh
  {{
    OFFSET 0 0 0
    CHANNELS 3 Zrotation Yrotation Xrotation
    JOINT Shin
    {{
      OFFSET 0 -10 0
      CHANNELS 3 Zrotation Yrotation Xrotation
      End Site
      {{
        OFFSET 0 -10 0
      }}
    }}
  }}
}}
MOTION
Frames: {frames}
Frame Time: {1 / rate}
{rows}
"""
    return parse_bvh(text, "leg.bvh")


def test_planar_motion_seen_side_on_agrees_with_3d_and_end_on_does_not():
    m = _planar_leg()
    result = view_invariance(m, ("Thigh", "Shin", "Shin.end"), views=8)
    per_view = dict(zip(result.azimuths.tolist(), result.agreement_per_view.tolist()))
    # cameras at azimuth 0 and 180 look along x, perpendicular to the plane of motion
    assert per_view[0.0] > 0.97 and per_view[180.0] > 0.97
    # at 90 degrees the leg is seen end-on (along z): the projected angle is degenerate
    assert per_view[90.0] < per_view[0.0]
    # the 3D angle is the knee angle: 180 minus the flexion
    t = np.arange(m.frames) / m.frame_rate
    np.testing.assert_allclose(result.angle_3d, 180 - (40 + 35 * np.sin(2 * np.pi * t)),
                               atol=1e-3)


def test_describe_cycles_and_stillness():
    codes = np.repeat([0, 1, 2, 3] * 4 + [0], 10)  # B G R Y repeated
    assert describe(codes, np.linspace(0, 30, codes.size)) == "BGRY"
    assert describe(codes, np.full(codes.size, 5.0)) == "still"
    assert describe(np.repeat([1, 2], 10), np.linspace(0, 30, 20)) == "irregular"
    assert STATES[0] == "B"


def test_synthetic_motion_is_seeded_and_patterned_joints_repeat():
    a = synthetic_motion(5, (1, 3), jitter=0.0, noise=0.0, seed=7)
    b = synthetic_motion(5, (1, 3), jitter=0.0, noise=0.0, seed=7)
    c = synthetic_motion(5, (1, 3), jitter=0.0, noise=0.0, seed=8)
    np.testing.assert_array_equal(a.values, b.values)
    assert not np.allclose(a.values, c.values)
    lag = int(round(1.0 * a.frame_rate))  # one period at jitter 0
    for c_, name in enumerate(a.channels):
        gap = np.abs(a.values[lag:, c_] - a.values[:-lag, c_]).mean()
        if name in a.meta["patterned"]:
            assert gap < 1e-6
        else:
            assert gap > 1.0
    with pytest.raises(ValueError):
        synthetic_motion(3, (5,))


@needs_mocap
def test_view_invariance_of_a_real_walk():
    m = real_take(MOCAP / "cmu-subject02" / "02_01.amc")
    knee = view_invariance(m, CMU_ANGLES["lknee"], views=12)
    assert knee.states_2d.shape == (12, m.frames)
    assert knee.agreement > 0.75
    # the best views (side on) agree almost everywhere, the worst much less
    assert knee.agreement_per_view.max() > 0.95
    assert knee.agreement_per_view.min() < knee.agreement_per_view.max() - 0.2


@needs_mocap
def test_reproducibility_and_selectivity_on_mocap6():
    motions, perfs = mocap6_performances(MOCAP / "cmu-mocap6")
    assert len(motions) == 5  # 14_06.amc is absent from the data
    assert all(p.stop > p.start for p in perfs)
    actions = {p.action for p in perfs}
    assert {"JumpJack", "Jog", "Squat", "ArmCircle"} <= actions
    channels = ["lfemur.rx", "rfemur.rx", "ltibia.rx", "rtibia.rx", "lhumerus.rx",
                "rhumerus.rx", "lowerback.rx", "lradius.rx"]
    table = reproducibility(motions, perfs, channels)
    for action, row in table.items():
        for channel, (fraction, word, count) in row.items():
            assert count >= 2 and 1 / count <= fraction <= 1
    # the knees of a squat are described the same way in most performances
    assert table["Squat"]["ltibia.rx"][0] >= 0.6
    sel = selectivity(motions, perfs, channels)
    assert sel["nearest_neighbour_accuracy"] > sel["chance"]
    assert max(sel["pairwise"].values()) > 0.3


@needs_mocap
def test_view_invariance_agrees_between_the_bvh_and_amc_of_one_take():
    from kinetology.evaluation import angle_table

    folder = MOCAP / "cmu-01_01-pair"
    amc, bvh = real_take(folder / "01_01.amc"), real_take(folder / "01_01.bvh")
    a_table, b_table = angle_table(amc.skeleton), angle_table(bvh.skeleton)
    assert a_table is CMU_ANGLES and set(b_table) == set(a_table)
    for angle in ("lknee", "relbow"):
        a = view_invariance(amc, a_table[angle], views=8).agreement
        b = view_invariance(bvh, b_table[angle], views=8).agreement
        assert abs(a - b) < 0.03, (angle, a, b)


@needs_mocap
def test_bandai_skeleton_has_an_angle_table():
    from kinetology.evaluation import BANDAI_ANGLES, angle_table

    m = real_take(MOCAP / "bandai-namco-1" / "data" / "dataset-1_walk_normal_001.bvh")
    assert angle_table(m.skeleton) is BANDAI_ANGLES
    knee = view_invariance(m, BANDAI_ANGLES["lknee"], views=8)
    assert knee.agreement > 0.7
