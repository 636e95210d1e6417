"""kinetology.write_bvh: real takes written and read back by kinetology and by the bvh package."""

from __future__ import annotations

import numpy as np
import pytest

import kinetology
from kinetology.bvh_writer import format_bvh, star_skeleton
from praxicon_fixtures import SHARED, needs_mocap, take


@needs_mocap()
@pytest.mark.parametrize("path", ["bandai-namco-1/data/dataset-1_bye_normal_001.bvh",
                                  "cmu-01_01-pair/01_01.bvh"])
def test_real_bvh_round_trips(path, tmp_path):
    import bvh

    original = kinetology.read(SHARED / path)
    out = kinetology.write_bvh(original, tmp_path / "copy.bvh")
    back = kinetology.read(out)
    assert back.channels == original.channels and back.frame_rate == original.frame_rate
    assert np.abs(back.values - original.values).max() < 0.01
    assert [j.name for j in back.skeleton.joints] == [j.name for j in original.skeleton.joints]
    offsets = np.array([j.offset for j in original.skeleton.joints])
    assert np.abs(np.array([j.offset for j in back.skeleton.joints]) - offsets).max() < 1e-6
    tree = bvh.Bvh(out.read_text())  # an independent reader
    assert tree.nframes == original.frames
    joint = original.skeleton.joints[1].name
    assert float(tree.frame_joint_channel(7, joint, "Zrotation")) == pytest.approx(
        original.column(f"{joint}.rz")[7], abs=0.01)


def test_skeleton_less_motion_is_written_on_a_star(tmp_path):
    motion = take(3).select(["arm.rx", "leg.rx"])  # select drops the skeleton
    assert motion.skeleton is None
    back = kinetology.read(kinetology.write_bvh(motion, tmp_path / "star.bvh"))
    assert back.skeleton.names == ("arm", "leg")
    assert np.abs(back.values - motion.values).max() < 1e-5


def test_bad_skeletons_are_value_errors():
    with pytest.raises(ValueError, match="not named joint.axis"):
        star_skeleton(["knee"])
    with pytest.raises(ValueError, match="channels differ"):
        motion = take(1)
        format_bvh(kinetology.Motion(motion.values[:, :2], motion.channels[:2], 30.0,
                                     motion.skeleton))


@needs_mocap()
def test_asf_skeleton_is_refused():
    motion = kinetology.read(SHARED / "cmu-01_01-pair" / "01_01.amc")
    with pytest.raises(ValueError, match="ASF axis pre-rotation"):
        format_bvh(motion)
