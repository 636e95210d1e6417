"""write_bvh writes only what reads back, values under the right channels, or refuses clearly."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology import Motion, read
from kinetology.bvh import parse_bvh
from kinetology.bvh_writer import MAX_DEPTH, format_bvh, write_bvh
from kinetology.motion import Joint, Skeleton

from kinetology_fixtures import MOCAP, needs_mocap


def _motion(joints, values, rate=30.0):
    channels = tuple(c for j in joints for c in j.channels)
    return Motion(np.asarray(values, dtype=float).reshape(-1, len(channels)), channels, rate,
                  Skeleton(tuple(joints)))


def _back(motion):
    return parse_bvh(format_bvh(motion), source="back.bvh")


def test_a_skeleton_listed_breadth_first_keeps_each_value_under_its_channel():
    # root, a(root), b(root), c(a): the file is depth-first (root a c b); main wrote the
    # values in the skeleton's order, so b read back 3 and c 2
    joints = [Joint("root", None, (0, 0, 0), ("root.rx",), "XZY"),
              Joint("a", 0, (1, 0, 0), ("a.rx",), "XZY"),
              Joint("b", 0, (0, 1, 0), ("b.rx",), "XZY"),
              Joint("c", 1, (0, 0, 1), ("c.rx",), "XZY")]
    back = _back(_motion(joints, [[0, 1, 2, 3]]))
    assert {c: back.column(c)[0] for c in back.channels} == \
        {"root.rx": 0, "a.rx": 1, "b.rx": 2, "c.rx": 3}


@st.composite
def skeletons(draw):
    count = draw(st.integers(1, 8))
    parents = [None] + [draw(st.integers(0, i - 1)) for i in range(1, count)]
    joints = []
    for i, parent in enumerate(parents):
        axes = draw(st.permutations(["rx", "ry", "rz"]))[:draw(st.integers(0, 3))]
        if i == 0 and draw(st.booleans()):
            axes = ["tx", "ty", "tz"] + axes
        channels = tuple(f"j{i}.{a}" for a in axes)
        order = "".join(a[1].upper() for a in axes if a.startswith("r"))
        order += "".join(a for a in "ZYX" if a not in order)
        joints.append(Joint(f"j{i}", parent, (float(i), -1.5, 0.25), channels, order))
    return joints


@settings(max_examples=80)
@given(skeletons(), st.integers(1, 4), st.sampled_from([30.0, 120.0, 7.3, 9999.7, 0.1, 0.37]),
       st.integers(0, 1000))
def test_whatever_order_the_skeleton_lists_the_file_reads_back(joints, frames, rate, seed):
    # the rates run to both ends of FRAME_RATE_RANGE, the fastest needing more than 8 decimals
    width = sum(len(j.channels) for j in joints)
    if width == 0:
        joints[0] = Joint("j0", None, (0, 0, 0), ("j0.rx",), "XZY")
        width = 1
    values = np.round(np.random.default_rng(seed).uniform(-1e3, 1e3, (frames, width)), 6)
    values[0, 0] = 1e300  # exponent form, not 300 digits
    motion = _motion(joints, values, rate)
    back = _back(motion)
    assert sorted(back.channels) == sorted(motion.channels)
    for c in motion.channels:
        assert np.allclose(back.column(c), motion.column(c), rtol=1e-15, atol=1e-6)
    assert back.frame_rate == pytest.approx(rate, rel=1e-12)
    original = {j.name: j for j in joints}
    for joint in back.skeleton.joints:
        if joint.name in original:
            mine = original[joint.name]
            parent = back.skeleton.joints[joint.parent].name if joint.parent is not None else None
            theirs = joints[mine.parent].name if mine.parent is not None else None
            assert (parent, joint.offset, joint.rotation_order) == \
                (theirs, mine.offset, mine.rotation_order)


@pytest.mark.parametrize("joint, words", [
    (Joint("left arm", 0, (0, 0, 0), ("left arm.rx",), "XZY"), "cannot be written"),
    (Joint("a{b", 0, (0, 0, 0), ("a{b.rx",), "XZY"), "cannot be written"),
    (Joint("root.end", 0, (0, 0, 0), ("root.end.rx",), "XZY"), "two joints"),  # + end site
    (Joint("", 0, (0, 0, 0), (".rx",), "XZY"), "cannot be written"),
    (Joint("root", 0, (0, 0, 0), ("root.ry",), "YZX"), "two joints"),
    (Joint("k", 0, (float("nan"), 0, 0), ("k.rx",), "XZY"), "non-finite"),
    (Joint("k", 0, (0, 0, 0), ("k.rx", "k.ry", "k.rz"), "ZYX"), "rotation order"),
    (Joint("k", 0, (0, 0, 0), ("other.rx",), "XZY"), "named after"),
    (Joint("tip", 0, (0, 0, 0), (), "ZYX", end_site=True), "end site"),
])
def test_what_would_not_read_back_is_refused(joint, words):
    root = Joint("root", None, (0, 0, 0), ("root.rx",), "XZY")
    tip = [Joint("root.end", 0, (0, 1, 0), (), "ZYX", end_site=True)]
    motion = _motion([root, joint] + tip, np.zeros((2, 1 + len(joint.channels))))
    with pytest.raises(ValueError, match=words):
        format_bvh(motion)


def test_a_deep_chain_writes_as_deep_as_it_reads(tmp_path):
    def chain(n):
        joints = [Joint(f"j{i}", None if i == 0 else i - 1, (0, 1, 0), (f"j{i}.rx",), "XZY")
                  for i in range(n)]
        return _motion(joints, np.arange(float(n)))
    path = write_bvh(chain(MAX_DEPTH + 1), tmp_path / "deep.bvh")
    assert read(path).column(f"j{MAX_DEPTH}.rx").tolist() == [float(MAX_DEPTH)]
    with pytest.raises(ValueError, match="nested 3000 deep"):
        format_bvh(chain(3001))


@settings(max_examples=30, deadline=None)
@given(st.sampled_from(["XYZ", "XZY", "YXZ", "YZX", "ZXY", "ZYX"]),
       st.lists(st.floats(-180, 180), min_size=9, max_size=9))
def test_euler_angles_give_back_every_rotation(order, values):
    from kinetology.kinematics import euler_angles, rotation_matrices

    angles = np.array(values).reshape(3, 3)  # three frames; gimbal lock included
    angles[:, 1] = np.clip(angles[:, 1], -90, 90)
    angles[0, 1] = 90.0
    matrices = rotation_matrices({a: angles[:, i] for i, a in enumerate(order)}, order, 3)
    found = euler_angles(matrices, order)
    again = rotation_matrices({a: found[:, i] for i, a in enumerate(order)}, order, 3)
    assert np.abs(again - matrices).max() < 1e-9


@needs_mocap
def test_an_asf_take_is_written_on_its_own_skeleton(tmp_path):
    from kinetology.bvh_writer import without_axes
    from kinetology.kinematics import forward_kinematics

    amc = read(MOCAP / "cmu-01_01-pair" / "01_01.amc")
    amc = Motion(amc.values[:240], amc.channels, amc.frame_rate, amc.skeleton, amc.source)
    with pytest.raises(ValueError, match="without_axes"):
        format_bvh(amc)
    plain = without_axes(amc)
    assert not any(any(j.axis) for j in plain.skeleton.joints)
    assert plain.skeleton.names == amc.skeleton.names
    assert np.abs(forward_kinematics(plain) - forward_kinematics(amc)).max() < 1e-9
    back = read(write_bvh(plain, tmp_path / "01_01.bvh"))
    assert np.allclose([j.offset for j in back.skeleton.joints],
                       [j.offset for j in amc.skeleton.joints], atol=1e-6)  # six decimals
    assert np.abs(forward_kinematics(back) - forward_kinematics(amc)).max() < 1e-4
    assert without_axes(back) is back  # nothing to do on a BVH skeleton
