"""Bad input to the kinetology command and API: one line (or a note) naming what is wrong, never
a traceback or silence. Each test fails before its fix."""

from __future__ import annotations

import numpy as np
import pytest

import kinetology
from kinetology import Joint, Motion, Skeleton
from kinetology.cli import main

from test_kinetology_cli import _small_amc
from test_kinetology_review_fixes import _write_bvh


def _one_line(capsys) -> str:
    captured = capsys.readouterr()
    err = captured.err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("kinetology: error:"), captured.err
    assert captured.out == "", captured.out  # said before any output: no tail of a report
    return err[0]


# -- an empty file name ----------------------------------------------------------------------

@pytest.mark.parametrize("argv, argument", [
    (["segment", ""], "FILE"),                      # was ".: unknown motion format"
    (["compress", ""], "file"),                     # was a traceback (Path('.').with_suffix)
    (["decompress", ""], "file"),                   # was "No such file or directory", unnamed
    (["evaluate", ""], "FILE"),
    (["plot", "", "--channel", "Knee.rz", "-o", "{tmp}/a.png"], "file"),
    (["view", "", "-o", "{tmp}/a.html"], "FILE"),
    (["segment", "{take}", "--labels", "", "-o", "{tmp}/spans/"], "--labels"),
    (["decompress", "{tmp}/t.kin", "--against", ""], "--against"),
    (["evaluate", "--mocap6", ""], "--mocap6"),     # was "nothing to evaluate"
    (["segment", "{take}", "-o", ""], "-o/--output"),
    (["compress", "{take}", "-o", ""], "-o/--output"),  # was written to take.kin in silence
    (["decompress", "{tmp}/t.kin", "-o", ""], "-o/--output"),
])
def test_an_empty_file_name_is_one_line_naming_the_argument(argv, argument, tmp_path, capsys):
    take = _write_bvh(tmp_path / "take.bvh")
    assert main(["compress", str(take), "-o", str(tmp_path / "t.kin")]) == 0
    capsys.readouterr()
    argv = [a.format(tmp=tmp_path, take=take) for a in argv]
    assert main(argv) == 2
    assert _one_line(capsys) == \
        f"kinetology: error: argument {argument}: the file name is empty ('')"
    assert not (tmp_path / "take.kin").exists()


def test_the_readers_refuse_an_empty_name():
    with pytest.raises(ValueError, match="path must be a file's path, not the empty name ''"):
        kinetology.read("")  # was ".: unknown motion format '(no suffix)'": the folder


# -- view-invariance of a take too large to measure ------------------------------------------

def _leg(bone: float, source: str = "leg.bvh") -> Motion:
    skeleton = Skeleton((Joint("hip", None, (0, 0, 0), ("hip.rx",)),
                         Joint("knee", 0, (0, -bone, 0), ("knee.rx",)),
                         Joint("foot", 1, (0, -bone, 0), end_site=True)))
    knee = 45 + 40 * np.sin(np.arange(60) / 10)
    return Motion(np.column_stack([0 * knee, knee]), ("hip.rx", "knee.rx"), 30.0, skeleton,
                  source)


def test_view_invariance_of_a_take_past_the_floats_names_it():
    from kinetology.evaluation import view_invariance

    # was "values must be finite numbers", naming nothing (the bones' squares overflowed)
    with pytest.raises(kinetology.MotionFormatError,
                       match=r"^leg\.bvh: joint positions reach 2e\+307 units, too far to "
                             r"measure joint angles \(at most 1e\+150"):
        view_invariance(_leg(1e307), ("hip", "knee", "foot"), views=4)
    # bones of 1e200 overflowed only their squares' product: the angle read 90 degrees, in
    # silence; such a take is refused the same way
    with pytest.raises(kinetology.MotionFormatError, match="reach 2e"):
        view_invariance(_leg(1e200), ("hip", "knee", "foot"), views=4)
    assert view_invariance(_leg(1e6), ("hip", "knee", "foot"), views=4).agreement > 0.5


def _bandai_take(path, bone: float):
    """A take with the Bandai Namco joint names (so evaluate measures its view-invariance)
    whose leg bones are ``bone`` units long."""
    joints = [("Hips", None, (0, 0, 0)), ("Chest", "Hips", (0, 10, 0))]
    for side, x in (("L", 2), ("R", -2)):
        joints += [(f"UpperLeg_{side}", "Hips", (x, -2, 0)),
                   (f"LowerLeg_{side}", f"UpperLeg_{side}", (0, -bone, 0)),
                   (f"Foot_{side}", f"LowerLeg_{side}", (0, -bone, 0)),
                   (f"Toes_{side}", f"Foot_{side}", (0, 0, 3)),
                   (f"UpperArm_{side}", "Chest", (x, 5, 0)),
                   (f"LowerArm_{side}", f"UpperArm_{side}", (x, -8, 0)),
                   (f"Hand_{side}", f"LowerArm_{side}", (x, -8, 0))]
    index = {name: i for i, (name, _, _) in enumerate(joints)}
    t = np.arange(60) / 30
    built, channels, columns = [], [], []
    for name, parent, offset in joints:
        own = (f"{name}.rz", f"{name}.ry", f"{name}.rx")
        built.append(Joint(name, None if parent is None else index[parent], offset, own))
        channels += own
        columns += [0 * t, 0 * t, 40 * np.sin(2 * np.pi * t + len(columns))]
    kinetology.write_bvh(Motion(np.column_stack(columns), tuple(channels), 30.0,
                                Skeleton(tuple(built))), path)
    return path


def test_evaluate_names_a_take_too_large_to_measure_before_its_report(tmp_path, capsys):
    take = _bandai_take(tmp_path / "far.bvh", 1e200)
    assert main(["evaluate", str(take), "--views", "4"]) == 2
    line = _one_line(capsys)  # was "values must be finite numbers" after half the report
    assert line.startswith(f"kinetology: error: {take}: joint positions reach ")
    assert line.endswith("e+200 units, too far to measure joint angles (at most 1e+150: "
                         "lengths are measured by their squares)")
    assert main(["evaluate", str(_bandai_take(tmp_path / "near.bvh", 10)), "--views", "4"]) == 0
    assert "view-invariance (2D state = 3D state, 4 views): lknee" in capsys.readouterr().out


# -- an unwrap period of no angle ------------------------------------------------------------

def test_an_unwrap_period_below_a_degree_is_refused(tmp_path, capsys):
    from kinetology.segmentation import states

    motion = kinetology.synthetic_motion(joints=2, patterned=(0,), repetitions=2)
    for period in (1e-300, 0.5):  # 1e-300 folded every movement: "no channel left to segment"
        with pytest.raises(ValueError, match="unwrap must be 0 .off. or a period of at least 1 "
                                             "degree"):
            kinetology.segments(motion, unwrap=period)
        with pytest.raises(ValueError, match="at least 1 degree"):
            states(motion.values, motion.frame_rate, unwrap=period)
    for period in (0, 1, 2 * np.pi, 180, 360):  # off, and the periods of angles
        assert kinetology.segments(motion, unwrap=period).channels
    take = _write_bvh(tmp_path / "take.bvh")
    assert main(["segment", str(take), "--unwrap", "1e-300"]) == 2
    assert "unwrap must be 0 (off) or a period of at least 1 degree, not 1e-300" \
        in _one_line(capsys)
    with pytest.raises(SystemExit):
        main(["segment", "--help"])
    assert "(0: off; else at least 1:" in " ".join(capsys.readouterr().out.split())


# -- decompress --against at another frame rate ----------------------------------------------

def test_decompress_against_a_take_at_another_rate_says_so(tmp_path, capsys):
    amc, packed, csv = _small_amc(tmp_path), tmp_path / "s.kin", tmp_path / "s.csv"
    assert main(["compress", str(amc), "--frame-rate", "60", "-o", str(packed)]) == 0
    capsys.readouterr()
    # the AMC read at its default 120 fps: the same 120 frames, compared one to one, with a note
    assert main(["decompress", str(packed), "--against", str(amc), "-o", str(csv)]) == 0
    err = capsys.readouterr().err.splitlines()
    assert err[0] == (f"kinetology: note: {amc} is at 120 fps, {packed} at 60 fps: their 120 "
                      f"frames are compared one to one; an AMC file states no rate: "
                      f"--frame-rate 60 reads it at the compressed one")
    assert err[1].startswith("mean absolute error") and len(err) == 2
    assert main(["decompress", str(packed), "--against", str(amc), "--frame-rate", "60",
                 "-o", str(csv)]) == 0
    assert "note" not in capsys.readouterr().err  # at the same rate: as before
    # another frame count: an error, as before, now with both rates
    take = _write_bvh(tmp_path / "take.bvh", frames=240)
    assert main(["decompress", str(packed), "--against", str(take)]) == 2
    assert _one_line(capsys).endswith(f"{packed}: {take} has shape (240, 9) at 120 fps, the "
                                      f"decoded motion (120, 9) at 60 fps")


# -- labels of a shorter take ----------------------------------------------------------------

def test_segment_notes_labels_that_end_well_before_the_take(tmp_path, capsys):
    take = _write_bvh(tmp_path / "take.bvh")  # 2 s at 120 fps
    short, whole = tmp_path / "short.txt", tmp_path / "whole.txt"
    short.write_text(" ".join(["5"] * 5 + ["1"] * 3))  # CMU truelabels: 0.8 s of labels
    whole.write_text(" ".join(["5"] * 5 + ["1"] * 15))  # 2 s
    assert main(["segment", str(take), "--labels", str(short), "-o", f"{tmp_path}/a/"]) == 0
    captured = capsys.readouterr()
    assert captured.err == (f"kinetology: note: the labels in {short} end at 0.8 s, 1.2 s "
                            f"before the end of {take} (2 s): the rest is in no span and not "
                            f"segmented (labels of a shorter take?)\n")
    assert captured.out.count(".actiongram") == 2  # the spans labelled: cut as before
    assert main(["segment", str(take), "--labels", str(whole), "-o", f"{tmp_path}/b/"]) == 0
    assert capsys.readouterr().err == ""
