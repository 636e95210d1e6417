"""Readers: every real file reads, BVH and ASF/AMC agree through forward kinematics,
malformed files give one located error."""

from __future__ import annotations

import dataclasses
import time

import numpy as np
import pytest

import kinetology
from kinetology import Motion, MotionFormatError, forward_kinematics
from kinetology.asf import parse_amc, parse_asf
from kinetology.bvh import parse_bvh
from kinetology.motion import Skeleton

from kinetology_fixtures import MOCAP, needs_mocap, real_take

SMALL_BVH = """HIERARCHY
ROOT Hips
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Yrotation Xrotation
  JOINT Knee
  {
    OFFSET 0 -10 0
    CHANNELS 3 Zrotation Yrotation Xrotation
    End Site
    {
      OFFSET 0 -10 0
    }
  }
}
MOTION
Frames: 3
Frame Time: 0.0333333
0 0 0 0 0 0 0 0 0
1 0 0 0 0 0 90 0 0
2 0 0 0 0 0 0 0 90
"""


def test_small_bvh_reads_and_forward_kinematics_rotates():
    m = parse_bvh(SMALL_BVH, "small.bvh")
    assert m.frames == 3 and m.frame_rate == 30.0
    assert m.channels[:3] == ("Hips.tx", "Hips.ty", "Hips.tz")
    assert m.channels[6:] == ("Knee.rz", "Knee.ry", "Knee.rx")
    assert not m.values.flags.writeable
    p = forward_kinematics(m)
    np.testing.assert_allclose(p[0, 2], [0, -20, 0], atol=1e-9)
    # frame 1: knee turned 90 degrees about z: the shin points along +x
    np.testing.assert_allclose(p[1, 2], [1 + 10, -10, 0], atol=1e-9)
    # frame 2: about x by 90: (0,-10,0) -> (0,0,-10)
    np.testing.assert_allclose(p[2, 2], [2, -10, -10], atol=1e-9)


@pytest.mark.parametrize("bad, message, line", [
    (SMALL_BVH.replace("2 0 0 0 0 0 0 0 90", "2 0 0 0 0 0 0 90"), "expected 9 numbers", 21),
    (SMALL_BVH.replace("1 0 0 0 0 0 90 0 0", "1 0 0 0 zero 0 90 0 0"), "not a number", 20),
    (SMALL_BVH.replace("1 0 0 0 0 0 90 0 0", "1 0 0 0 nan 0 90 0 0"), "not finite", 20),
    (SMALL_BVH.replace("2 0 0 0 0 0 0 0 90\n", ""), "header says 3 frames", 17),
    (SMALL_BVH.replace("Zrotation Yrotation Xrotation\n    End", "Zrotation Yrotation\n    End"),
     "unknown channel", 10),
    (SMALL_BVH.replace("OFFSET 0 -10 0\n    CHANNELS", "OFFSET 0 ten 0\n    CHANNELS"),
     "expected a number", 8),
    (SMALL_BVH[:SMALL_BVH.index("MOTION")], "file ends", None),
])
def test_malformed_bvh_names_file_and_line(bad, message, line):
    with pytest.raises(MotionFormatError) as info:
        parse_bvh(bad, "bad.bvh")
    text = str(info.value)
    assert message in text and text.startswith("bad.bvh:")
    assert "\n" not in text
    if line is not None:
        assert info.value.line == line, text


def test_truncated_bvh_file_in_tmp_path(tmp_path):
    path = tmp_path / "cut.bvh"
    path.write_text(SMALL_BVH[: SMALL_BVH.index("2 0 0")] + "2 0 0")
    with pytest.raises(MotionFormatError) as info:
        kinetology.read(path)
    assert str(info.value).startswith(f"{path}:21:")


SMALL_ASF = """:units
  length 1
:root
   order TX TY TZ RX RY RZ
   axis XYZ
   position 0 0 0
   orientation 0 0 0
:bonedata
  begin
     id 1
     name femur
     direction 0 -1 0
     length 10
     axis 0 0 90 XYZ
    dof rx
  end
  begin
     id 2
     name tibia
     direction 0 -1 0
     length 10
     axis 0 0 0 XYZ
    dof rx rz
  end
:hierarchy
  begin
    root femur
    femur tibia
  end
"""

SMALL_AMC = """:FULLY-SPECIFIED
:DEGREES
1
root 0 0 0 0 0 0
femur 0
tibia 0 0
2
root 0 0 0 0 0 0
femur 90
tibia 0 0
"""


def test_small_asf_amc_and_axis_convention():
    asf = parse_asf(SMALL_ASF, "s.asf")
    m = parse_amc(SMALL_AMC, dofs=asf.dofs, skeleton=asf.skeleton, source="s.amc")
    assert m.channels == ("root.tx", "root.ty", "root.tz", "root.rx", "root.ry", "root.rz",
                          "femur.rx", "tibia.rx", "tibia.rz")
    p = forward_kinematics(m)
    names = m.skeleton.names
    assert names == ("root", "femur", "tibia", "tibia.end")
    np.testing.assert_allclose(p[0, names.index("tibia.end")], [0, -20, 0], atol=1e-9)
    # femur's dof x is, through axis (0 0 90), the global y axis: a rotation about
    # the vertical leaves the straight leg where it is
    np.testing.assert_allclose(p[1, names.index("tibia.end")], [0, -20, 0], atol=1e-9)


@pytest.mark.parametrize("bad, message, line", [
    (SMALL_AMC.replace("tibia 0 0\n2", "tibia 0\n2"), "expected 2 numbers", 6),
    (SMALL_AMC.replace("femur 90", "femur ninety"), "not a number", 9),
    (SMALL_AMC.replace("femur 90", "femur nan"), "not finite", 9),
    (SMALL_AMC.replace("femur 90\n", ""), "expected bone 'femur'", 9),
    (SMALL_AMC.replace("tibia 0 0\n", "", 1).replace("2\nroot", "root", 1), None, None),
    (SMALL_AMC + "3\nroot 0 0 0 0 0 0\n", "truncated", 12),
])
def test_malformed_amc_names_file_and_line(bad, message, line):
    asf = parse_asf(SMALL_ASF)
    with pytest.raises(MotionFormatError) as info:
        parse_amc(bad, dofs=asf.dofs, source="bad.amc")
    text = str(info.value)
    assert text.startswith("bad.amc:") and "\n" not in text
    if message:
        assert message in text, text
    if line:
        assert info.value.line == line, text


def test_amc_without_skeleton_still_gives_angles(tmp_path):
    path = tmp_path / "07_01.amc"
    path.write_text(SMALL_AMC)
    m = kinetology.read(path)
    assert m.skeleton is None
    assert m.channels[:6] == ("root.tx", "root.ty", "root.tz", "root.rx", "root.ry", "root.rz")
    assert m.channels[6:] == ("femur.1", "tibia.1", "tibia.2")
    assert m.column("femur.1").tolist() == [0.0, 90.0]
    with pytest.raises(ValueError, match="no skeleton"):
        forward_kinematics(m)


def test_unknown_suffix_is_a_clear_error(tmp_path):
    path = tmp_path / "x.c3d"
    path.write_text("")
    with pytest.raises(MotionFormatError, match="unknown motion format"):
        kinetology.read(path)


def test_motion_is_immutable_and_validated():
    m = Motion(np.zeros((4, 2)), ("a.rx", "b.rx"), 30)
    with pytest.raises(ValueError):
        m.values[0, 0] = 1
    with pytest.raises(dataclasses.FrozenInstanceError):
        m.frame_rate = 10
    with pytest.raises(TypeError):
        m.meta["format"] = "changed"
    with pytest.raises(ValueError, match="not finite"):
        Motion(np.array([[np.nan]]), ("a.rx",), 30)
    with pytest.raises(ValueError, match="2 channel names for 3"):
        Motion(np.zeros((2, 3)), ("a", "b"), 30)


def test_large_file_reads_in_seconds(tmp_path):
    frames = 100_000
    rng = np.random.default_rng(0)
    rows = "\n".join(" ".join(f"{v:.4f}" for v in row)
                     for row in rng.normal(size=(frames, 9)) * 30)
    head = SMALL_BVH[: SMALL_BVH.index("Frames:")]
    path = tmp_path / "big.bvh"
    path.write_text(f"{head}Frames: {frames}\nFrame Time: 0.008333\n{rows}\n")
    started = time.perf_counter()
    m = kinetology.read(path)
    elapsed = time.perf_counter() - started
    assert m.frames == frames and m.frame_rate == pytest.approx(120.0, rel=1e-3)
    assert elapsed < 10, f"reading 1e5 frames took {elapsed:.1f} s"


def _motion_files(folder):
    return sorted(p for p in folder.rglob("*") if p.suffix.lower() in (".bvh", ".amc"))


# one test per data folder, so that no single test runs long on a loaded machine
_FOLDERS = sorted(p.name for p in MOCAP.iterdir() if _motion_files(p)) if MOCAP.is_dir() \
    else ["(no data)"]


@needs_mocap
def test_the_real_data_is_all_there():
    assert len(_motion_files(MOCAP)) >= 190


@needs_mocap
@pytest.mark.parametrize("folder", _FOLDERS)
def test_every_real_file_reads(folder):
    files = _motion_files(MOCAP / folder)
    assert files
    for path in files:
        m = real_take(path)
        assert m.frames > 0 and len(m.channels) > 0
        if path.suffix == ".bvh" and "bandai" in str(path):
            assert m.frame_rate == 30.0 and all(len(j.channels) == 6
                                                for j in m.skeleton.joints if not j.end_site)
        if path.suffix == ".amc":
            assert m.frame_rate == 120.0


def _collapse_branching_bones(motion):
    """The CMU BVH conversion gives bones with several children (thorax, l/rwrist) length 0."""
    skeleton = motion.skeleton
    children = {}
    for joint in skeleton.joints:
        if joint.parent is not None:
            children.setdefault(joint.parent, []).append(joint)
    joints = []
    for joint in skeleton.joints:
        parent = joint.parent
        if parent is not None and parent != 0 and len(children[parent]) > 1:
            joint = dataclasses.replace(joint, offset=(0.0, 0.0, 0.0))
        joints.append(joint)
    return dataclasses.replace(motion, skeleton=Skeleton(tuple(joints)))


@needs_mocap
def test_bvh_and_asf_amc_agree_through_forward_kinematics():
    folder = MOCAP / "cmu-01_01-pair"
    amc = kinetology.read(folder / "01_01.amc")
    bvh = kinetology.read(folder / "01_01.bvh")
    assert amc.skeleton is not None and len(amc.skeleton.joints) == len(bvh.skeleton.joints)
    # the BVH has one extra first frame (a T pose); scale 1, axes unchanged
    assert bvh.frames == amc.frames + 1
    a = forward_kinematics(_collapse_branching_bones(amc))
    b = forward_kinematics(bvh)[1:]
    gap = np.linalg.norm(a - b, axis=2)
    assert gap.max() < 0.01, f"largest joint position gap {gap.max():.4f}"
    # without the collapse the upper body is off by the thorax length: the check can fail
    raw = np.linalg.norm(forward_kinematics(amc) - b, axis=2)
    assert raw.max() > 1.0
    # the angles of the legs are the same numbers in both files up to the axis change,
    # and the root translation is identical
    np.testing.assert_allclose(amc.values[:, :3], bvh.values[1:, :3], atol=1e-3)


from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@settings(max_examples=30, deadline=None)
@given(st.integers(1, 40), st.integers(0, 2 ** 31))
def test_bvh_values_read_back_as_written(frames, seed):
    rng = np.random.default_rng(seed)
    table = np.round(rng.uniform(-180, 180, size=(frames, 9)), 4)
    rows = "\n".join(" ".join(repr(float(v)) for v in row) for row in table)
    head = SMALL_BVH[: SMALL_BVH.index("Frames:")]
    m = parse_bvh(f"{head}Frames: {frames}\nFrame Time: 0.01\n{rows}\n", "r.bvh")
    np.testing.assert_array_equal(m.values, table)
    # forward kinematics keeps bone lengths whatever the angles
    p = forward_kinematics(m)
    np.testing.assert_allclose(np.linalg.norm(p[:, 2] - p[:, 1], axis=1), 10.0, rtol=1e-9)


def test_large_amc_reads_in_seconds(tmp_path):
    frames = 100_000
    asf = parse_asf(SMALL_ASF)
    rng = np.random.default_rng(1)
    values = np.round(rng.uniform(-90, 90, size=(frames, 3)), 3)
    lines = [":FULLY-SPECIFIED", ":DEGREES"]
    for k, (a, b, c) in enumerate(values, 1):
        lines += [str(k), "root 0 0 0 0 0 0", f"femur {a}", f"tibia {b} {c}"]
    path = tmp_path / "big.amc"
    path.write_text("\n".join(lines) + "\n")
    started = time.perf_counter()
    m = kinetology.read(path, asf=asf)
    elapsed = time.perf_counter() - started
    assert m.frames == frames
    np.testing.assert_array_equal(m.values[:, 6:], values)
    assert elapsed < 10, f"reading 1e5 AMC frames took {elapsed:.1f} s"


def test_absurdly_deep_hierarchies_and_empty_files_are_one_clear_error(tmp_path):
    depth = 3000  # beyond Python's recursion limit
    joints = "".join(f"JOINT j{i}\n{{\nOFFSET 0 1 0\nCHANNELS 1 Xrotation\n" for i in range(depth))
    text = (f"HIERARCHY\nROOT r\n{{\nOFFSET 0 0 0\nCHANNELS 1 Xrotation\n{joints}"
            + "}\n" * (depth + 1) + "MOTION\nFrames: 0\nFrame Time: 0.01\n")
    with pytest.raises(MotionFormatError, match="nested too deeply"):
        parse_bvh(text, "deep.bvh")
    bones = "".join(f"begin\nname b{i}\ndirection 0 1 0\nlength 1\ndof rx\nend\n"
                    for i in range(depth))
    links = "".join(f"b{i} b{i + 1}\n" for i in range(depth - 1))
    with pytest.raises(MotionFormatError, match="nested too deeply"):
        parse_asf(f":bonedata\n{bones}:hierarchy\nbegin\nroot b0\n{links}end\n", "deep.asf")
    for name in ("empty.bvh", "empty.amc"):
        path = tmp_path / name
        path.write_text("")
        with pytest.raises(MotionFormatError) as info:
            kinetology.read(path)
        assert str(info.value).startswith(f"{path}:1:"), str(info.value)


def test_radian_units_are_converted_to_degrees(tmp_path):
    asf_deg = parse_asf(SMALL_ASF)
    asf_rad = parse_asf(SMALL_ASF.replace("length 1\n", "length 1\n  angle rad\n")
                        .replace("axis 0 0 90 XYZ", f"axis 0 0 {np.pi / 2!r} XYZ"))
    assert asf_rad.skeleton.joints[1].axis == pytest.approx(asf_deg.skeleton.joints[1].axis)
    radians = SMALL_AMC.replace(":DEGREES", ":RADIANS").replace("femur 90",
                                                               f"femur {np.pi / 2!r}")
    with_asf = parse_amc(radians, dofs=asf_deg.dofs)
    without = parse_amc(radians)
    assert with_asf.column("femur.rx")[1] == pytest.approx(90.0)
    assert without.column("femur.1")[1] == pytest.approx(90.0)
    with pytest.raises(MotionFormatError, match="deg or rad"):
        parse_asf(SMALL_ASF.replace("length 1\n", "length 1\n  angle grad\n"))


@pytest.mark.parametrize("name", ["junk.bvh", "junk.amc"])
def test_binary_or_run_on_garbage_gives_one_short_line(tmp_path, name):
    path = tmp_path / name
    rng = np.random.default_rng(4)
    path.write_bytes(b"x" * 50_000 + rng.integers(0, 256, 5_000, dtype=np.uint8).tobytes())
    with pytest.raises(MotionFormatError) as info:
        kinetology.read(path)
    text = str(info.value)
    assert text.startswith(f"{path}:1:") and "\n" not in text
    assert len(text) < len(str(path)) + 220, len(text)


# ---- inputs that once crashed the readers with an undocumented exception
@pytest.mark.parametrize("frame_time", ["nan", "inf", "-inf", "0", "-1"])
def test_unreadable_frame_times_are_a_format_error(frame_time):
    bad = SMALL_BVH.replace("Frame Time: 0.0333333", f"Frame Time: {frame_time}")
    with pytest.raises(MotionFormatError, match="frame time must be a positive finite") as err:
        parse_bvh(bad, "ft.bvh")
    assert (err.value.source, err.value.line) == ("ft.bvh", 18)


@pytest.mark.parametrize("frame_time, rate", [("10", 0.1), ("2.5", 0.4), ("1.5", 1 / 1.5)])
def test_slow_frame_rates_are_kept_not_rounded_to_zero(frame_time, rate):
    m = parse_bvh(SMALL_BVH.replace("Frame Time: 0.0333333", f"Frame Time: {frame_time}"))
    assert m.frame_rate == pytest.approx(rate)


def test_two_joints_of_one_name_are_located():
    bad = SMALL_BVH.replace("JOINT Knee", "JOINT Hips")
    with pytest.raises(MotionFormatError, match="two joints are named 'Hips'") as err:
        parse_bvh(bad, "dup.bvh")
    assert (err.value.line, err.value.column) == (6, 9)


def test_a_blank_line_inside_an_amc_frame_is_located():
    with pytest.raises(MotionFormatError, match="found an empty line") as err:
        parse_amc("1\n\nroot 0 0 0 0 0 0\n", source="blank.amc")
    assert (err.value.source, err.value.line) == ("blank.amc", 2)


def test_radian_values_too_large_for_degrees_are_located():
    with pytest.raises(MotionFormatError, match="too large to convert") as err:
        parse_amc(":RADIANS\n1\nroot 0 0 0 0 0 0\n2\nroot 0 0 0 0 1e307 0\n", source="r.amc")
    assert err.value.line == 5


def test_a_bare_root_axis_line_is_located():
    bad = SMALL_ASF.replace("axis XYZ", "axis", 1)
    assert bad != SMALL_ASF
    with pytest.raises(MotionFormatError, match="root axis needs an order") as err:
        parse_asf(bad, "axis.asf")
    assert err.value.line == bad.splitlines().index("   axis") + 1


def test_a_byte_order_mark_is_skipped(tmp_path):
    (tmp_path / "bom.bvh").write_bytes(b"\xef\xbb\xbf" + SMALL_BVH.encode())
    assert kinetology.read(tmp_path / "bom.bvh").frames == 3
    (tmp_path / "s.asf").write_bytes(b"\xef\xbb\xbf" + SMALL_ASF.encode())
    (tmp_path / "s_1.amc").write_bytes(b"\xef\xbb\xbf" + SMALL_AMC.encode())
    assert kinetology.read(tmp_path / "s_1.amc").channels[-1] == "tibia.rz"


def test_forward_kinematics_that_overflows_is_an_error_not_inf():
    huge = SMALL_BVH.replace("OFFSET 0 -10 0", "OFFSET 0 -1e308 0")
    with pytest.raises(MotionFormatError, match="overflows at joint"):
        forward_kinematics(parse_bvh(huge))


def test_asf_bone_vector_that_overflows_is_located():
    bad = SMALL_ASF.replace("length 10", "length 1e308", 1).replace("direction 0 -1 0",
                                                                   "direction 0 -10 0", 1)
    with pytest.raises(MotionFormatError, match="overflows") as err:
        parse_asf(bad, "big.asf")
    assert err.value.line is not None


def test_segmenting_a_motion_sampled_at_megahertz_keeps_every_segment():
    # one-frame segments at 3 MHz: durations rounded to the microsecond were 0 (a FormatError)
    from kinetology.segmentation import segments
    values = 30 * np.sin(np.arange(400) * 0.5)[:, None]
    m = Motion(values, ("j.rx",), 3e6)
    seg = segments(m, smoothing=0.0)
    ag = kinetology.segment(m, smoothing=0.0)
    assert len(ag.string("j.rx")) == seg.segment_count
    assert sum(ag.durations["j.rx"]) == pytest.approx(m.duration, rel=1e-3)


def test_one_long_hierarchy_line_reads_in_linear_time():
    # 12,000 sibling joints on one line: list.pop(0) per token made this 7 s
    n = 12_000
    joints = " ".join(f"JOINT j{i} {{ OFFSET 0 0 0 CHANNELS 1 Xrotation End Site {{ OFFSET 0 0 0 }} }}"
                      for i in range(1, n))
    text = (f"HIERARCHY\nROOT j0 {{ OFFSET 0 0 0 CHANNELS 1 Xrotation {joints} }}\n"
            f"MOTION\nFrames: 1\nFrame Time: 0.01\n{' '.join(['0'] * n)}\n")
    start = time.perf_counter()
    m = parse_bvh(text)
    assert len(m.channels) == n
    assert time.perf_counter() - start < 3.0
