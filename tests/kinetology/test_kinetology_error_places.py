"""Every error of a motion reader names its file, line and column, and the column is that of
the word the message is about: found by reading mutated shared files and small edits of the
test files. An ASF line is indented, so column 1 (which these errors gave) is white space;
an AMC file without frames is named at the end of its last line.
"""

from __future__ import annotations

import pytest

from kinetology.asf import parse_amc, parse_asf, read_amc
from kinetology.bvh import parse_bvh
from kinetology.motion import MotionFormatError

from test_kinetology_readers import SMALL_AMC, SMALL_ASF


def _message(parse, text) -> str:
    with pytest.raises(MotionFormatError) as caught:
        parse(text, source="x")
    return str(caught.value)


def _deep_asf(depth: int) -> str:
    bones = "".join(f"  begin\n    name b{k}\n    direction 0 1 0\n    length 1\n  end\n"
                    for k in range(depth))
    chain = "".join(f"    b{k} b{k + 1}\n" for k in range(depth - 1))
    return f":bonedata\n{bones}:hierarchy\n  begin\n    root b0\n{chain}  end\n"


@pytest.mark.parametrize("old, new, error", [
    ("  length 1\n", "  length 1\n  angle grad\n", "x:3:9: angle unit must be deg or rad, not "
                                                   "'grad'"),
    ("  length 1\n", "  length 1\n  angle # in degrees\n", "x:3:8: angle unit must be deg or "
                                                           "rad, not ''"),
    ("order TX TY TZ RX RY RZ", "order TX TY TZ RX RQ RZ", "x:4:22: bad root order 'TX TY TZ "
                                                           "RX RQ RZ'"),
    ("order TX TY TZ RX RY RZ", "order TX TY TZ RX RY RX", "x:4:25: bad root order 'TX TY TZ "
                                                           "RX RY RX'"),
    ("   axis XYZ\n", "   axis\n", "x:5:8: root axis needs an order such as XYZ"),
    ("   axis XYZ\n", "   axis XYY\n", "x:5:9: bad axis order 'XYY'"),
    ("axis 0 0 90 XYZ", "axis 0 0 90 XZ", "x:14:18: bad axis order 'XZ'"),
    ("     name femur\n", "", "x:15:3: bone without a name"),
    ("  end\n  begin\n     id 2", "  end\n     id 2\n  begin\n     id 2",
     "x:17:6: 'id' outside a begin/end bone block"),
    ("name femur", "name", "x:11:10: bone name missing"),
    ("dof rx rz", "dof rx rq", "x:23:12: bad dof list 'rx rq'"),
    # at the length, the number that makes it overflow (it named the bone's begin line)
    ("direction 0 -1 0\n     length 10\n     axis 0 0 90",
     "direction 0 -1e300 0\n     length 1e300\n     axis 0 0 90",
     "x:13:13: bone 'femur': length x direction overflows"),
    # at the name of the first bone left out (no line was named)
    ("    femur tibia\n", "", "x:19:11: bones not in the hierarchy: tibia"),
])
def test_asf_errors_name_the_column_of_their_word(old, new, error):
    assert old in SMALL_ASF
    assert _message(parse_asf, SMALL_ASF.replace(old, new)) == error


def test_nesting_too_deep_names_the_joint_or_bone_where_it_stopped():
    # placed by recursion: the last joint (or hierarchy line) reached is where it went too deep
    assert _message(parse_asf, _deep_asf(1200)).endswith(
        ":10: bones nested too deeply in :hierarchy")
    message = _message(parse_asf, _deep_asf(1200))
    line = int(message.split(":")[1])
    assert _deep_asf(1200).split("\n")[line - 1].split()[1].startswith("b")  # a child's name
    bvh = ("HIERARCHY\nROOT a\n{\n" + "".join(f"JOINT j{k}\n{{\n" for k in range(1200))
           + "}\n" * 1201)
    message = _message(parse_bvh, bvh)
    assert message.endswith(":7: joints nested too deeply")
    line = int(message.split(":")[1])
    assert bvh.split("\n")[line - 1].startswith("JOINT j")  # column 7: the joint's name


def test_an_amc_file_without_frames_is_named_at_its_end():
    assert _message(parse_amc, ":FULLY-SPECIFIED\n:DEGREES\n") == "x:2:9: no frames"
    assert _message(parse_amc, "") == "x:1:1: no frames"


def test_a_key_file_names_the_column_of_its_bad_dof(tmp_path):
    (tmp_path / "SkeletonJoints.key").write_text("root tx ty tz rx ry rz\n  femur rx rq\n")
    (tmp_path / "a.amc").write_text(SMALL_AMC)
    with pytest.raises(MotionFormatError, match=r"SkeletonJoints.key:2:12: bad dof names in "
                                                r"'femur rx rq'$"):
        read_amc(tmp_path / "a.amc", asf=None)


@pytest.mark.parametrize("text, place, words", [
    ("HIERARCHY\nROOT Hips\n{ OFFSET 0 0 0\n", (3, 15), "file ends where '}' was expected"),
    ("HIERARCHY\nROOT Hips\n{ OFFSET 0 0 0\nCHANNELS 1 Xrotation\n}\nMOTION\n", (6, 7),
     "file ends before 'Frames:'"),
])
def test_a_bvh_file_that_ends_early_is_named_after_its_last_character(text, place, words):
    # the line alone left the reader to find where the text stops (a long last line)
    with pytest.raises(MotionFormatError) as error:
        parse_bvh(text, source="cut.bvh")
    assert str(error.value) == f"cut.bvh:{place[0]}:{place[1]}: {words}"
