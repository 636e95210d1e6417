"""The kinetology command refuses before it works: option values before any file is read, a
take too large to code or difference in one line naming it (evaluate: before the first line of
its report, a cmu-mocap6 take too; compress --max-error: no quantum, not the one it tried); its
counts read "1 string", not "1 strings"; and a --mocap6 folder of one action says selectivity
needs two, without numpy's warnings."""

from __future__ import annotations

import re

import numpy as np
import pytest

import psgs
from kinetology import Motion
from kinetology.cli import main

from kinetology_fixtures import MOCAP, needs_mocap
from test_kinetology_readers import SMALL_BVH
from test_kinetology_review_fixes import _write_bvh


def _one_line(capsys) -> tuple[str, str]:
    """The one error line and what went to stdout."""
    captured = capsys.readouterr()
    err = captured.err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("kinetology: error:"), captured.err
    return err[0], captured.out


def _bvh(path, row: str, frames: int = 240):
    """A take of SMALL_BVH's skeleton whose every frame is ``row``."""
    head = SMALL_BVH[: SMALL_BVH.index("Frames:")]
    path.write_text(f"{head}Frames: {frames}\nFrame Time: 0.0083333\n"
                    + f"{row}\n" * frames)
    return path


@pytest.fixture
def far(tmp_path):
    """The root 1e307 units away, the knee moving: too large for the codec's 62-bit knots."""
    t = np.arange(240) / 120
    head = SMALL_BVH[: SMALL_BVH.index("Frames:")]
    rows = "\n".join(f"1e307 0 0 0 0 0 {30 * np.sin(2 * np.pi * x):.4f} 0 0" for x in t)
    path = tmp_path / "far.bvh"
    path.write_text(f"{head}Frames: 240\nFrame Time: 0.0083333\n{rows}\n")
    return path


# -- a take too large: one line naming it -----------------------------------------------------

def test_compress_names_the_take_whose_knots_need_more_than_62_bits(far, tmp_path, capsys):
    assert main(["compress", str(far), "-o", str(tmp_path / "far.kin")]) == 2
    err, _ = _one_line(capsys)
    assert f"error: {far}: quantum 0.5 is too small for channel 'Hips.tx'" in err
    assert not (tmp_path / "far.kin").exists()


def test_compress_names_the_take_whose_residuals_need_more_than_62_bits(tmp_path, capsys):
    take = _write_bvh(tmp_path / "take.bvh")
    assert main(["compress", str(take), "-o", str(tmp_path / "t.kin"), "--residual-step",
                 "1e-300"]) == 2
    assert f"error: {take}: residual step 1e-300 is too small" in _one_line(capsys)[0]


def test_evaluate_refuses_a_take_too_large_to_code_before_its_report(far, tmp_path, capsys):
    good = _write_bvh(tmp_path / "good.bvh")
    assert main(["evaluate", str(good), str(far), "--views", "1"]) == 2
    err, out = _one_line(capsys)
    assert out == ""  # good.bvh's report was printed before the error
    assert f"error: {far}: quantum 0.5 is too small for channel 'Hips.tx'" in err


def test_a_take_too_large_to_difference_is_named_by_every_command(tmp_path, capsys):
    good = _write_bvh(tmp_path / "good.bvh")
    huge = _bvh(tmp_path / "huge.bvh", " ".join(["1e307"] * 9))
    runs = {"segment": ["segment", str(huge)],
            "segment several": ["segment", str(good), str(huge), "-o", f"{tmp_path}/grams/"],
            "evaluate": ["evaluate", str(good), str(huge)]}
    for name, args in runs.items():
        assert main(args) == 2, name
        err, out = _one_line(capsys)
        assert f"error: {huge}: frame rate 120 fps is too high to difference" in err, name
        assert out == "", name  # nothing reported, nothing written
    # several files wrote an actiongram of still segments for the take one file refused
    assert not (tmp_path / "grams").exists()


def test_a_rotation_alternating_at_the_floats_limit_is_refused_without_numpy_warnings(
        tmp_path, capsys):
    """Unwrapping +-1e308 overflowed before the rate was checked: numpy's RuntimeWarnings,
    then a line saying the values went 'up to nan'."""
    import warnings

    head = SMALL_BVH[: SMALL_BVH.index("Frames:")]
    rows = [" ".join(["0"] * 8 + [f"{(-1) ** k * 1e308:g}"]) for k in range(240)]
    path = tmp_path / "wild.bvh"
    path.write_text(f"{head}Frames: 240\nFrame Time: 0.0083333\n" + "\n".join(rows) + "\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        for args in (["segment", str(path)], ["evaluate", str(path)]):
            assert main(args) == 2, args
            err, out = _one_line(capsys)
            assert f"error: {path}: frame rate 120 fps is too high to difference values up " \
                   f"to 1e+308" in err, args
        values = np.array([(-1) ** k * 1e308 for k in range(240)])
        with pytest.raises(psgs.ValidationError, match="values up to 1e\\+308"):
            __import__("kinetology").states(values, 120.0)


def _mocap6(folder, takes: dict):
    """A cmu-mocap6 folder: per take, its AMC root rows (``tx ty tz rx ry rz``) and labels."""
    (folder / "amc").mkdir(parents=True)
    (folder / "truelabels").mkdir()
    for name, (rows, labels) in takes.items():
        frames = "".join(f"{i}\nroot 0 0 0 {row}\n" for i, row in enumerate(rows, 1))
        (folder / "amc" / f"{name}.amc").write_text(f":FULLY-SPECIFIED\n:DEGREES\n{frames}")
        (folder / "truelabels" / f"{name}.txt").write_text(" ".join(map(str, labels)))
    return folder


def _swing(frames: int = 300, ry: str = "0") -> list[str]:
    """``rx ry rz`` rows of a root swinging 30 degrees about x once a second at 120 fps."""
    return [f"{30 * np.sin(2 * np.pi * i / 120):.4f} {ry} 0" for i in range(frames)]


def test_evaluate_mocap6_names_the_take_too_large_to_difference(tmp_path, capsys):
    from kinetology.evaluation import mocap6_performances, reproducibility

    # b.amc's ry is 1e307 throughout: still, but its accelerations overflow at 120 fps
    folder = _mocap6(tmp_path / "mocap6", {"a": (_swing(), [1] * 25),
                                          "b": (_swing(ry="1e307"), [2] * 25)})
    huge = folder / "amc" / "b.amc"
    good = _write_bvh(tmp_path / "good.bvh")
    for files in ([], [str(good)]):
        assert main(["evaluate", *files, "--mocap6", str(folder)]) == 2
        err, out = _one_line(capsys)
        assert err == (f"kinetology: error: {huge}: frame rate 120 fps is too high to "
                       f"difference values up to 1e+307: their velocities and accelerations "
                       f"overflow")  # it named no file
        assert out == ""  # good.bvh's report was not begun
    takes, performances = mocap6_performances(folder)
    with pytest.raises(ValueError, match=f"^{re.escape(str(huge))}: frame rate 120 fps"):
        reproducibility(takes, performances, ["root.rx", "root.ry"])


@pytest.mark.parametrize("labels, here", [
    ([1] * 25, "1 performance here, of JumpJack"),
    ([1] * 25 + [2] * 5 + [1] * 20, "2 performances here, all of JumpJack"),
    ([1] * 10, "no performance here: no run of one label lasts 2 s"),  # was a traceback
])
def test_evaluate_mocap6_of_one_action_says_selectivity_needs_two(labels, here, tmp_path,
                                                                   capsys, recwarn):
    folder = _mocap6(tmp_path, {"a": (_swing(12 * len(labels)), labels)})
    assert main(["evaluate", "--mocap6", str(folder)]) == 0
    captured = capsys.readouterr()
    assert captured.err == ""
    # one action has nothing to be told apart from: its pairs' mean read "nan%", with numpy's
    # "Mean of empty slice" on stderr, and one performance's nearest other "0.0%"
    assert captured.out.endswith(f"selectivity: n/a, needs performances of two actions or "
                                 f"more ({here})\n"), captured.out
    assert "nan" not in captured.out
    assert not [w for w in recwarn if issubclass(w.category, RuntimeWarning)], \
        [str(w.message) for w in recwarn]
    if len(labels) != 50:  # reproducibility compares an action's performances: none has two
        assert "mean over channels\n  no action has two performances or more\n" in captured.out


def test_selectivity_of_no_performance_is_no_error():
    from kinetology.evaluation import selectivity

    walk = Motion(np.zeros((240, 1)), ("knee.rx",), 120.0)
    result = selectivity({"a": walk}, [], ["knee.rx"])  # max() of no action's count raised
    assert (result["nearest_neighbour_accuracy"], result["chance"], result["pairwise"]) == \
        (0.0, 0.0, {})


def test_compress_max_error_says_no_quantum_can_code_the_take(far, tmp_path, capsys):
    assert main(["compress", str(far), "-o", str(tmp_path / "far.kin"), "--max-error",
                 "0.5"]) == 2
    err, _ = _one_line(capsys)
    # it said "quantum 0.5 is too small", a setting rate control chose, not the user
    assert err == (f"kinetology: error: {far}: no setting meets max_error=0.5: no quantum fine "
                   f"enough to meet it can code the take (channel 'Hips.tx' would need knot "
                   f"values of more than 62 bits)")
    assert not (tmp_path / "far.kin").exists()


def test_compress_max_error_codes_a_take_the_finest_quantum_cannot_on_a_coarser_one():
    from kinetology.codec import compress

    # 5e18 needs more than 62 bits in quanta of 0.5 degrees, not of 2: the residual layer's
    # base codes it (the finest rung's refusal ended rate control before it was tried)
    t = np.arange(240) / 120
    values = np.zeros((240, 9))
    values[:, 0] = 5e18
    values[:, 6] = 30 * np.sin(2 * np.pi * t)
    far = Motion(values, ("Hips.tx", "Hips.ty", "Hips.tz", "Hips.rz", "Hips.ry", "Hips.rx",
                          "Knee.rz", "Knee.ry", "Knee.rx"), 120.0, source="far.bvh")
    assert compress(far, max_error=0.5).mean_error <= 0.5


def test_plot_names_a_take_too_large_to_difference(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    huge = _bvh(tmp_path / "huge.bvh", " ".join(["1e307"] * 9))
    assert main(["plot", str(huge), "--channel", "Knee.rz", "-o", str(tmp_path / "k.png")]) == 2
    assert f"error: {huge}: frame rate 120 fps" in _one_line(capsys)[0]


# -- option values before any file is read ----------------------------------------------------

_UNWRAP = ("unwrap must be 0 (off) or a period of at least 1 degree, not 0.5: a step of more "
           "than half the period between two frames is taken for a wrap and folded back")


@pytest.mark.parametrize("args, message", [
    (["segment", "{take}", "--unwrap", "0.5"], _UNWRAP),
    (["segment", "{take}", "--smoothing", "-1"], "smoothing must be a non-negative number, not "
                                                 "-1.0"),
    (["segment", "{take}", "{other}", "-o", "{dir}/", "--min-range", "nan"],
     "min_range must be a non-negative number, not nan"),
    (["segment", "{take}", "--start", "nan"], "start and stop must be numbers, not nan, None"),
    (["segment", "{take}", "--labels", "{labels}", "-o", "{dir}/", "--unwrap", "0.5"], _UNWRAP),
    (["segment", "{take}", "--labels", "{labels}", "-o", "{dir}/", "--min-seconds", "-1"],
     "min_seconds must be a non-negative number, not -1.0"),
    (["compress", "{take}", "--quantum", "0"], "quantum must be positive, not 0.0"),
    (["compress", "{take}", "--residual-step", "1", "--hysteresis", "0.2"],
     "hysteresis must be at least 0.5, not 0.2"),
    (["compress", "{take}", "--max-error", "nan"],
     "max_error must be a positive number of degrees, not nan"),
    (["compress", "{take}", "--max-error", "1", "--quantum", "1"],
     "--max-error chooses the settings itself; drop --quantum"),
    (["plot", "{take}", "--channel", "Knee.rz", "-o", "{dir}/k.png", "--unwrap", "0.5"], _UNWRAP),
    (["plot", "{take}", "--channel", "lknee", "--kind", "view", "-o", "{dir}/k.png",
      "--velocity-deadband", "-2"], "velocity_deadband must be a non-negative number, not -2.0"),
    (["plot", "{take}", "--channel", "Knee.rz", "--kind", "reconstruction", "-o",
      "{dir}/k.png", "--smoothing", "inf"], "smoothing must be a non-negative number, not inf"),
    (["view", "{take}", "-o", "{dir}/v.html", "--max-rate", "0"],
     "kinetology.view: max_rate must be a positive number (inf: no cap), not 0.0"),
    (["view", "{take}", "-o", "{dir}/v.html", "--max-frames", "0"],
     "kinetology.view: max_frames must be a whole number of at least 1 (inf: no cap), not 0"),
    (["evaluate", "{take}", "--unwrap", "0.5"], _UNWRAP),
])
def test_an_option_value_is_refused_before_any_file_is_read(args, message, tmp_path, capsys,
                                                             monkeypatch):
    import kinetology.readers

    take = _write_bvh(tmp_path / "take.bvh")
    other = _write_bvh(tmp_path / "other.bvh")
    labels = tmp_path / "take.txt"
    labels.write_text(" ".join(["1"] * 20))
    filled = [a.format(take=take, other=other, labels=labels, dir=tmp_path) for a in args]
    # the same words with the take read (the messages are the work's own)
    assert main(filled) == 2
    assert _one_line(capsys)[0] == f"kinetology: error: {message}"

    def no_reading(*_args, **_kwargs):
        raise AssertionError("a file was read before the options were checked")

    monkeypatch.setattr(kinetology.readers, "read", no_reading)
    assert main(filled) == 2  # not read at all
    assert _one_line(capsys)[0] == f"kinetology: error: {message}"
    monkeypatch.undo()
    # a missing file: the option's error, not the file's
    missing = [a.replace(str(take), str(tmp_path / "missing.bvh")) for a in filled]
    assert main(missing) == 2
    assert _one_line(capsys)[0] == f"kinetology: error: {message}"


# -- counts: singular for one -----------------------------------------------------------------

def test_segment_counts_one_string_as_one(tmp_path, capsys):
    take = _write_bvh(tmp_path / "take.bvh")
    labels = tmp_path / "take.txt"  # CMU truelabels: one label per 12 frames (1/10 s)
    labels.write_text(" ".join(["5"] * 5 + ["1"] * 10 + ["5"] * 5))
    assert main(["segment", str(take), "--channels", "Knee.rz", "--labels", str(labels),
                 "-o", f"{tmp_path}/spans/"]) == 0
    out = capsys.readouterr().out
    assert "take-JumpJack-1.actiongram: JumpJack 0.5-1.5 s, 1 string\n" in out
    assert "strings" not in out
    other = _write_bvh(tmp_path / "other.bvh")
    assert main(["segment", str(take), str(other), "--channels", "Knee.rz", "-o",
                 f"{tmp_path}/grams/"]) == 0
    out = capsys.readouterr().out
    kinetemes = psgs.load(tmp_path / "grams" / "other.actiongram").total_symbols
    assert f"other.actiongram: 1 string, {kinetemes} kinetemes\n" in out


def test_evaluate_counts_one_channel_and_one_moving_channel_as_one(tmp_path, capsys):
    head = "HIERARCHY\nROOT Knee\n{\n  OFFSET 0 0 0\n  CHANNELS 1 Zrotation\n  End Site\n  {\n" \
           "    OFFSET 0 -10 0\n  }\n}\nMOTION\n"
    t = np.arange(240) / 120
    rows = "\n".join(f"{30 * np.sin(2 * np.pi * x):.4f}" for x in t)
    knee = tmp_path / "knee.bvh"
    knee.write_text(f"{head}Frames: 240\nFrame Time: 0.0083333\n{rows}\n")
    assert main(["evaluate", str(knee)]) == 0
    out = capsys.readouterr().out
    assert f"{knee}: 240 frames, 1 channel at 120 fps\n" in out
    assert " in 1 moving channel (0 still)" in out


@needs_mocap
def test_evaluate_counts_one_view_as_one(capsys):
    take = MOCAP / "bandai-namco-1" / "data" / "dataset-1_walk_normal_001.bvh"
    assert main(["evaluate", str(take), "--views", "1"]) == 0
    assert "view-invariance (2D state = 3D state, 1 view): lknee " in capsys.readouterr().out


def test_evaluate_mocap6_counts_one_performance_as_one(tmp_path, capsys):
    (tmp_path / "amc").mkdir()
    (tmp_path / "truelabels").mkdir()
    t = np.arange(300) / 120
    frames = "".join(f"{i}\nroot 0 0 0 {30 * np.sin(2 * np.pi * x):.4f} 0 0\n"
                     for i, x in enumerate(t, 1))
    (tmp_path / "amc" / "a.amc").write_text(f":FULLY-SPECIFIED\n:DEGREES\n{frames}")
    (tmp_path / "truelabels" / "a.txt").write_text(" ".join(["1"] * 25))  # 2.5 s of JumpJack
    assert main(["evaluate", "--mocap6", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert f"reproducibility ({tmp_path}, 1 performance): mean over channels" in out


def test_decompress_note_counts_one_frame_as_one(tmp_path, capsys):
    from kinetology.codec import compress

    packed = tmp_path / "one.kin"
    packed.write_bytes(compress(Motion(np.zeros((1, 9)), tuple(
        f"{joint}.{axis}" for joint, axes in (("Hips", ("tx", "ty", "tz", "rz", "ry", "rx")),
                                               ("Knee", ("rz", "ry", "rx"))) for axis in axes),
        60.0)))
    original = _bvh(tmp_path / "one.bvh", " ".join(["0"] * 9), frames=1)
    assert main(["decompress", str(packed), "--against", str(original), "-o",
                 str(tmp_path / "one.csv")]) == 0
    assert "at 60 fps: their 1 frame is compared one to one" in capsys.readouterr().err


def test_reader_and_stream_errors_count_one_as_one(tmp_path, capsys):
    from kinetology.asf import parse_asf
    from kinetology.bvh import parse_bvh
    from kinetology.codec import decompress, stream
    from kinetology.motion import MotionFormatError

    head = SMALL_BVH[: SMALL_BVH.index("Frames:")]
    with pytest.raises(MotionFormatError, match="header says 1 frame but 2 frame lines follow"):
        parse_bvh(f"{head}Frames: 1\nFrame Time: 0.01\n{'0 ' * 9}\n{'0 ' * 9}\n", "two.bvh")
    with pytest.raises(MotionFormatError, match="header says 2 frames but 1 frame line follows"):
        parse_bvh(f"{head}Frames: 2\nFrame Time: 0.01\n{'0 ' * 9}\n", "one.bvh")
    with pytest.raises(MotionFormatError, match="expected 1 number, found 0"):
        parse_asf(":root\n  order TX TY TZ RX RY RZ\n  axis XYZ\n  position 0 0 0\n"
                  "  orientation 0 0 0\n:bonedata\n  begin\n    id 1\n    name a\n"
                  "    direction 0 1 0\n    length\n    axis 0 0 0 XYZ\n  end\n", "a.asf")
    take = _write_bvh(tmp_path / "take.bvh")
    assert main(["segment", str(take), "--channels", "Knee.rx", "nope"]) == 2
    assert "; its 9 channels: " in _one_line(capsys)[0]
    knee = Motion(np.zeros((3, 1)), ("knee.rx",), 120.0, source="knee.bvh")
    with pytest.raises(psgs.errors.NotFound, match="; its 1 channel: knee.rx"):
        knee.index("nope")
    assert repr(knee.select(["knee.rx"])) == "Motion('knee.bvh', 3 frames x 1 channel at 120 fps)"
    # a stream of two frames whose one segment lasts two frame steps
    layout = stream.Layout(120.0, 2, 0.5, ("knee.rx",), (np.zeros(1, np.int8),),
                           (np.array([2]),), (0,), (np.array([0]),))
    with pytest.raises(MotionFormatError, match=r"durations do not add up to 1 frame \("):
        decompress(stream.write(layout), source="bad.kin")
