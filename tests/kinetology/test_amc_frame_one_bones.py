"""An AMC file's frame 1 names its bones, and with a skeleton each must be one of the
skeleton's: a bone misspelt in frame 1 alone is named at its own line as not in the skeleton,
not as the good bone of frame 2 that differs from it (``expected bone 'nosuch', found
'lowerback'`` at frame 2's line), whichever way the frames are read.
"""

from __future__ import annotations

import shutil
from unittest import mock

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology import _frame_block
from kinetology import asf as asf_module
from kinetology.asf import parse_amc, parse_asf
from kinetology.cli import main
from kinetology.motion import MotionFormatError

from kinetology_fixtures import MOCAP
from test_kinetology_readers import SMALL_ASF

_DOFS = parse_asf(SMALL_ASF).dofs
_BONES = {"root": 6, "femur": 1, "tibia": 2}  # values per bone line


def _read(text: str, way: str):
    """``text`` read with the skeleton's dofs, the chunked way or the first way (in pieces of
    a line, or of the whole block)."""
    if way == "chunks":
        return parse_amc(text, dofs=_DOFS, source="s.amc")
    with mock.patch.object(asf_module, "read_at_once", lambda *a: None), \
            mock.patch.object(_frame_block, "CHUNK", 1 if way == "lines" else 1 << 16):
        return parse_amc(text, dofs=_DOFS, source="s.amc")


def _amc(frames: int, renamed: dict[tuple[int, int], str], indents: list[int]) -> str:
    """``frames`` frames of the three bones (bone ``b`` of frame ``f`` named
    ``renamed[(f, b)]`` when given, indented by ``indents[b]`` spaces), after two header
    lines."""
    lines = [":FULLY-SPECIFIED", ":DEGREES"]
    for f in range(frames):
        lines.append(str(f + 1))
        for b, (bone, width) in enumerate(_BONES.items()):
            name = renamed.get((f, b), bone)
            lines.append(" " * indents[b] + name + " 0" * width)
    return "\n".join(lines) + "\n"


@settings(max_examples=60, deadline=None)
@given(frames=st.integers(1, 5), bone=st.integers(0, 2),
       name=st.sampled_from(["nosuch", "femurr", "Tibia", "root2"]),
       everywhere=st.booleans(), bad_value=st.booleans(),
       indents=st.lists(st.integers(0, 3), min_size=3, max_size=3),
       way=st.sampled_from(["chunks", "lines", "pieces"]))
def test_a_bone_of_frame_one_not_in_the_skeleton_is_named_at_its_line(
        frames, bone, name, everywhere, bad_value, indents, way):
    renamed = {(f, bone): name for f in range(frames if everywhere else 1)}
    text = _amc(frames, renamed, indents)
    if bad_value:  # a value that is not a number in the last frame's last bone: named after
        text = text[:-2] + "x\n"
    with pytest.raises(MotionFormatError) as caught:
        _read(text, way)
    # frame 1's number on line 3, its bones on the lines after
    assert str(caught.value) == (f"s.amc:{4 + bone}:{indents[bone] + 1}: bone {name!r} is not "
                                 f"in the skeleton")


@pytest.mark.parametrize("way", ["chunks", "lines", "pieces"])
def test_the_same_file_unharmed_reads_alike_every_way(way):
    motion = _read(_amc(3, {}, [0, 2, 1]), way)
    assert motion.values.shape == (3, 9)


@pytest.mark.skipif(not (MOCAP / "cmu-subject02").is_dir(), reason="no shared CMU data")
@pytest.mark.parametrize("every_frame", [False, True])
def test_segment_names_the_misspelt_bone_of_a_shared_file(tmp_path, capsys, every_frame):
    source = MOCAP / "cmu-subject02"
    shutil.copy(source / "02.asf", tmp_path / "02.asf")
    text = (source / "02_01.amc").read_text()
    assert text.splitlines()[5].startswith("lowerback ")
    if every_frame:
        text = text.replace("\nlowerback ", "\nnosuch ")
    else:
        text = text.replace("\nlowerback ", "\nnosuch ", 1)
    amc = tmp_path / "02_01.amc"
    amc.write_text(text)
    assert main(["segment", str(amc), "-o", str(tmp_path / "x.ag")]) == 2
    (line,) = capsys.readouterr().err.splitlines()[-1:]
    assert line == f"kinetology: error: {amc}:6:1: bone 'nosuch' is not in the skeleton"
