"""Bad motion and label files a fuzzer found: each one clear error at its place, never a
device read without end, a replaced byte, an overflowing rate, an empty actiongram for a
take too short to segment, frames silently lost or doubled, or a value's column left out.

Every input is a small mutation of the readers' test files, built in ``tmp_path``.
"""

from __future__ import annotations

import json
import os

import numpy as np
import pytest

import kinetology
from kinetology import Motion, MotionFormatError
from kinetology.asf import parse_amc, parse_asf
from kinetology.bvh import parse_bvh, read_bvh
from kinetology.cli import main
from kinetology.evaluation import codec_point, mocap6_performances
from kinetology.labels import read_bandai_json, read_cmu_truelabels
from psgs.errors import ValidationError

from test_kinetology_readers import SMALL_AMC, SMALL_ASF, SMALL_BVH

needs_devices = pytest.mark.skipif(not os.path.exists("/dev/null"), reason="needs /dev/null")


def _device(tmp_path, name):
    """A link named like a motion file to /dev/null: before, it read as an empty file."""
    link = tmp_path / name
    link.symlink_to("/dev/null")
    return link


def _bandai(tmp_path):
    """A Bandai Namco take: data/NAME.json and .bvh, cfg/ with the label lists."""
    (tmp_path / "cfg").mkdir(parents=True)
    (tmp_path / "cfg" / "content_label.txt").write_text("dataset-1_walk\n")
    (tmp_path / "cfg" / "style_label.txt").write_text("dataset-1_normal\n")
    (tmp_path / "data").mkdir()
    label = tmp_path / "data" / "dataset-1_walk_normal_001.json"
    label.write_text(json.dumps({"content": 0, "style": 0}))
    label.with_suffix(".bvh").write_text(SMALL_BVH)
    return label


# ---- 1. a device (or pipe) is refused before it is read, by every reader of a user's file
@needs_devices
@pytest.mark.parametrize("name, read", [
    ("take.bvh", kinetology.read),
    ("take.asf", kinetology.read_asf),
    ("t.txt", read_cmu_truelabels),
    ("label.json", read_bandai_json),
])
def test_a_device_is_refused_by_every_reader(tmp_path, name, read):
    link = _device(tmp_path, name)
    with pytest.raises(MotionFormatError, match="not a regular file") as err:
        read(link)
    assert err.value.source == str(link)


@needs_devices
def test_a_device_as_an_amc_file_or_beside_a_label_is_refused(tmp_path):
    (tmp_path / "s.asf").write_text(SMALL_ASF)
    with pytest.raises(MotionFormatError, match="not a regular file"):
        kinetology.read(_device(tmp_path, "s_1.amc"))
    label = _bandai(tmp_path / "set")
    label.with_suffix(".bvh").unlink()
    take = _device(label.parent, label.with_suffix(".bvh").name)  # it gives the duration
    with pytest.raises(MotionFormatError, match="no take dataset-1_walk_normal_001.bvh"):
        read_bandai_json(label)
    from kinetology.labels import _bvh_duration  # its header was read line by line, unbounded
    with pytest.raises(MotionFormatError, match="not a regular file"):
        _bvh_duration(take)
    cfg = label.parent.parent / "cfg" / "style_label.txt"
    cfg.unlink()
    cfg.symlink_to("/dev/null")
    with pytest.raises(MotionFormatError, match="no label list .*style_label.txt"):
        read_bandai_json(label, duration=1.0)


@needs_devices
def test_a_device_as_mocap6_labels_or_a_kin_file_is_one_line_exit_2(tmp_path, capsys):
    (tmp_path / "amc").mkdir()
    (tmp_path / "truelabels").mkdir()
    (tmp_path / "amc" / "13_29.amc").write_text(SMALL_AMC)
    (tmp_path / "truelabels" / "13_29.txt").symlink_to("/dev/null")
    with pytest.raises(MotionFormatError, match="not a regular file"):
        mocap6_performances(tmp_path)
    assert main(["decompress", str(_device(tmp_path, "x.kin"))]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "x.kin: not a regular file" in err, err


# ---- 2. bytes that are not UTF-8 are an error at their line and column, never replaced
@pytest.mark.parametrize("name, data, where", [
    ("j.bvh", SMALL_BVH.encode().replace(b"JOINT Knee", b"JOINT Kn\xe9e"), (6, 11)),
    ("s.asf", SMALL_ASF.encode().replace(b"name tibia", b"name t\xffbia"), (19, 12)),
    ("t.txt", b"1 1\n1 \xb2\n", (2, 3)),
    ("l.json", b'{"content": 0, "style": "\xe9"}', (1, 26)),
])
def test_bytes_that_are_not_utf8_are_located(tmp_path, name, data, where):
    path = tmp_path / name
    path.write_bytes(data)
    read = {".bvh": read_bvh, ".asf": kinetology.read_asf, ".txt": read_cmu_truelabels,
            ".json": read_bandai_json}[path.suffix]
    with pytest.raises(MotionFormatError, match="not UTF-8") as err:
        read(path)
    assert (err.value.source, err.value.line, err.value.column) == (str(path), *where)


def test_a_latin1_bone_in_an_amc_frame_is_located(tmp_path):
    (tmp_path / "s.asf").write_text(SMALL_ASF)
    amc = tmp_path / "s_1.amc"
    amc.write_bytes(SMALL_AMC.encode().replace(b"femur 90", b"f\xe9mur 90"))
    with pytest.raises(MotionFormatError, match="byte 0xe9") as err:
        kinetology.read(amc)
    assert (err.value.line, err.value.column) == (9, 2)


# ---- 3. a frame time outside 0.0001 .. 10 s is an error at its line and column
def test_a_label_beside_a_take_of_an_absurd_frame_time_is_refused(tmp_path):
    label = _bandai(tmp_path)
    take = label.with_suffix(".bvh")
    take.write_text(SMALL_BVH.replace("Frame Time: 0.0333333", "Frame Time: 1e-300"))
    with pytest.raises(MotionFormatError, match=r"'Frame Time: 1e-300' is outside 0.0001"):
        read_bandai_json(label)


@pytest.mark.parametrize("frame_time", ["1e-300", "1e-320", "0.00009", "10.5", "1e300"])
def test_a_frame_time_outside_the_range_is_located(frame_time):
    bad = SMALL_BVH.replace("Frame Time: 0.0333333", f"Frame Time:   {frame_time}")
    with pytest.raises(MotionFormatError, match=r"outside 0.0001 \.\. 10 s") as err:
        parse_bvh(bad, "ft.bvh")
    assert (err.value.line, err.value.column) == (18, 15)


@pytest.mark.parametrize("frame_time, rate", [("0.0001", 10_000.0), ("10", 0.1)])
def test_the_ends_of_the_frame_time_range_read(frame_time, rate):
    m = parse_bvh(SMALL_BVH.replace("Frame Time: 0.0333333", f"Frame Time: {frame_time}"))
    assert m.frame_rate == rate


@pytest.mark.parametrize("rate", [1e300, 20_000.0, 0.01, float("nan")])
def test_an_amc_frame_rate_outside_the_range_is_refused(rate):
    with pytest.raises(ValidationError, match="outside 0.1 .. 10000 frames a second"):
        parse_amc(SMALL_AMC, frame_rate=rate)


# ---- 4. a take too short to segment is one line and exit status 2, not an empty actiongram
def _bvh_of(tmp_path, frames):
    head = SMALL_BVH[: SMALL_BVH.index("Frames:")]
    rows = "".join(f"{k} 0 0 0 0 0 {10 * k} 0 0\n" for k in range(frames))
    path = tmp_path / f"f{frames}.bvh"
    path.write_text(f"{head}Frames: {frames}\nFrame Time: 0.0333333\n{rows}")
    return path


@pytest.mark.parametrize("command", ["segment", "compress", "evaluate"])
@pytest.mark.parametrize("frames", [0, 1, 2])
def test_too_few_frames_is_one_line_and_exit_2(tmp_path, capsys, command, frames):
    path = _bvh_of(tmp_path, frames)
    out = tmp_path / "out.kin"
    assert main([command, str(path)] + (["-o", str(out)] if command == "compress" else [])) \
        == 2
    captured = capsys.readouterr()
    assert captured.out == "" and not out.exists()
    (line,) = captured.err.splitlines()
    plural = "s" * (frames != 1)
    assert line == (f"kinetology: error: {path}: {frames} frame{plural}, but {command} needs "
                    f"at least 3 (a state is the sign of a velocity and an acceleration, and "
                    f"an acceleration takes 3 frames)")


def test_three_frames_segment_and_a_short_cut_is_refused(tmp_path, capsys):
    path = _bvh_of(tmp_path, 3)
    assert main(["segment", str(path)]) == 0
    assert "Knee.rz:" in capsys.readouterr().out
    long = _bvh_of(tmp_path, 30)
    assert main(["segment", str(long), "--start", "0.5", "--stop", "0.55"]) == 2
    err = capsys.readouterr().err
    assert f"{long}: from 0.5 s to 0.5333" in err and "1 frame, but segment needs" in err


def test_codec_point_of_no_frames_is_a_validation_error():
    with pytest.raises(ValidationError, match="0 frames"):
        codec_point(Motion(np.zeros((0, 1)), ("a.rx",), 30.0, source="empty.bvh"), 100)


# ---- 5. AMC frames numbered one after another; a bone twice is named, at its line
@pytest.mark.parametrize("old, new, line, found", [
    ("\n2\n", "\n1000000000000\n", 7, "'1000000000000'"),
    ("\n2\n", "\n1\n", 7, "'1'"),
    ("\n2\n", "\n-2\n", 7, "'-2'"),
    ("\n2\n", "\n3\n", 7, "'3'"),
    # not a frame number by its form, but a number where one belongs (it was read as a bone)
    ("\n2\n", "\n2.0\n", 7, "'2.0'"),
])
def test_amc_frame_numbers_must_follow_one_another(old, new, line, found):
    asf = parse_asf(SMALL_ASF)
    with pytest.raises(MotionFormatError, match=f"expected frame number 2, found {found}") \
            as err:
        parse_amc(SMALL_AMC.replace(old, new), dofs=asf.dofs, source="n.amc")
    assert (err.value.line, err.value.column) == (line, 1)


def test_amc_frames_may_start_at_another_number_and_pad_with_zeros():
    asf = parse_asf(SMALL_ASF)
    text = SMALL_AMC.replace("\n1\n", "\n0\n").replace("\n2\n", "\n01\n")
    assert parse_amc(text, dofs=asf.dofs).frames == 2


def test_a_bone_twice_in_the_first_amc_frame_is_named_at_its_line():
    bad = SMALL_AMC.replace("tibia 0 0\n", "tibia 0 0\n  femur 1\n", 1)
    with pytest.raises(MotionFormatError,
                       match=r"bone 'femur' appears twice in frame 1 \(first at line 5\)") as err:
        parse_amc(bad, source="d.amc")
    assert (err.value.line, err.value.column) == (7, 3)


def test_two_asf_bones_of_one_name_are_named_at_the_second():
    bad = SMALL_ASF.replace("name tibia", "name femur")
    with pytest.raises(MotionFormatError,
                       match=r"two bones are named 'femur' \(the first at line 11\)") as err:
        parse_asf(bad, "d.asf")
    assert (err.value.line, err.value.column) == (19, 11)


@pytest.mark.parametrize("link", ["root tibia", "tibia femur"])
def test_a_bone_given_a_parent_twice_or_in_a_cycle_is_named_at_its_line(link):
    bad = SMALL_ASF.replace("    femur tibia\n", f"    femur tibia\n    {link}\n")
    child = link.split()[1]
    with pytest.raises(MotionFormatError, match=rf"hierarchy gives bone '{child}' a parent "
                                                r"twice \(first at line 2[78]\)") as err:
        parse_asf(bad, "h.asf")
    assert (err.value.line, err.value.column) == (29, 5 + len(link.split()[0]) + 1)


@pytest.mark.parametrize("token", ["1_0", "\uff11\uff12", "\u0661\u0662"])
def test_a_number_float_would_take_but_no_file_means_is_not_a_number(token):
    # float() reads '1_0' as 10 and digits of other scripts as digits; a data file means neither
    with pytest.raises(MotionFormatError, match="not a number"):
        parse_bvh(SMALL_BVH.replace("0 0 0 0 0", f"0 0 {token} 0 0", 1), "n.bvh")


def test_a_form_feed_is_no_line_break_for_the_line_numbers():
    text = SMALL_BVH.replace("JOINT Knee", "JOINT Kn\x0cee", 1)
    line = next(n for n, ln in enumerate(text.split("\n"), 1) if "\x0c" in ln)
    with pytest.raises(MotionFormatError) as err:
        parse_bvh(text, "f.bvh")
    assert err.value.line == line



@pytest.mark.parametrize("brk", ["\x0c", "\u2028", "\x85"])
def test_a_label_file_breaks_lines_at_newlines_only(brk, tmp_path):
    # str.splitlines would break at these too, and the bad label be named a line too far
    from kinetology._mocap6 import _labels

    path = tmp_path / "t.txt"
    path.write_text(f"1 1{brk}1\n2 x 2\n", encoding="utf-8")
    for read in (read_cmu_truelabels, _labels):
        with pytest.raises(MotionFormatError) as err:
            read(path)
        assert (err.value.line, err.value.column) == (2, 3), read

# ---- 6. a value that is not finite (or not a number) is located at its column
@pytest.mark.parametrize("token", ["nan", "inf", "-inf", "1e999"])
def test_a_bvh_value_that_is_not_finite_names_its_column(token):
    bad = SMALL_BVH.replace("1 0 0 0 0 0 90 0 0", f"1 0 0 0 0 0 90 {token} 0")
    with pytest.raises(MotionFormatError, match="value 8 is not finite") as err:
        parse_bvh(bad, "v.bvh")
    assert (err.value.line, err.value.column) == (20, 16)


@pytest.mark.parametrize("old, new, message, line, column", [
    ("femur 90", "femur   nan", "value 1 is not finite", 9, 9),
    ("root 0 0 0 0 0 0\nfemur 90", "root 0 0 0 0 inf 0\nfemur 90", "value 5 is not finite", 8,
     14),
    ("femur 90", " femur x", "not a number: 'x'", 9, 8),
])
def test_an_amc_value_is_located_in_the_file_not_after_the_bone(old, new, message, line,
                                                                  column):
    asf = parse_asf(SMALL_ASF)
    with pytest.raises(MotionFormatError, match=message) as err:
        parse_amc(SMALL_AMC.replace(old, new), dofs=asf.dofs, source="v.amc")
    assert (err.value.line, err.value.column) == (line, column)


def test_radians_too_large_name_their_column():
    with pytest.raises(MotionFormatError, match="too large to convert") as err:
        parse_amc(":RADIANS\n1\nroot 0 0 0 0 0 0\n2\nroot 0 0 0 0 1e307 0\n", source="r.amc")
    assert (err.value.line, err.value.column) == (5, 14)


@pytest.mark.parametrize("old, new, message, column", [
    ("Frames: 3", "Frames: -5", "negative frame count -5", 9),
    ("Frames: 3", "  Frames:  many", "'Frames:' needs a number, not 'many'", 12),
])
def test_header_numbers_name_their_column(old, new, message, column):
    with pytest.raises(MotionFormatError, match=message) as err:
        parse_bvh(SMALL_BVH.replace(old, new), "h.bvh")
    assert (err.value.line, err.value.column) == (17, column)


def test_an_asf_number_that_is_not_finite_names_its_column():
    with pytest.raises(MotionFormatError, match="number 'inf' is not finite") as err:
        parse_asf(SMALL_ASF.replace("direction 0 -1 0", "direction 0 inf 0", 1), "n.asf")
    assert (err.value.line, err.value.column) == (12, 18)
