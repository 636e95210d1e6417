"""The kinetology command: outputs psgs reads back, and one-line errors."""

from __future__ import annotations

import numpy as np
import pytest

import psgs
from kinetology.cli import main

from kinetology_fixtures import MOCAP, needs_mocap
from test_kinetology_readers import SMALL_BVH


@pytest.fixture
def small_bvh(tmp_path):
    t = np.arange(240) / 120
    rows = "\n".join(f"0 0 0 0 0 0 {30 * np.sin(2 * np.pi * x):.4f} 0 {20 * np.cos(3 * x):.4f}"
                     for x in t)
    head = SMALL_BVH[: SMALL_BVH.index("Frames:")]
    path = tmp_path / "small.bvh"
    path.write_text(f"{head}Frames: 240\nFrame Time: 0.0083333\n{rows}\n")
    return path


def test_segment_writes_an_actiongram_psgs_loads(small_bvh, tmp_path, capsys):
    out = tmp_path / "small.actiongram"
    assert main(["segment", str(small_bvh), "-o", str(out)]) == 0
    ag = psgs.load(out)
    assert set(ag.names) == {"Knee.rz", "Knee.rx"}
    assert ag.string("Knee.rz")[:4] == ("G", "R", "Y", "B")
    assert main(["segment", str(small_bvh), "--channels", "Knee.rz"]) == 0
    text = capsys.readouterr().out
    assert "Knee.rz:" in text and "Knee.rx:" not in text


def test_compress_decompress_round_trip(small_bvh, tmp_path, capsys):
    packed = tmp_path / "small.kin"
    assert main(["compress", str(small_bvh), "-o", str(packed), "--quantum", "0.01"]) == 0
    csv = tmp_path / "small.csv"
    assert main(["decompress", str(packed), "-o", str(csv), "--against", str(small_bvh)]) == 0
    err = capsys.readouterr().err
    assert "mean absolute error" in err
    table = np.loadtxt(csv, delimiter=",", skiprows=1)
    assert table.shape == (240, 10)
    np.testing.assert_allclose(table[:, 7], 30 * np.sin(2 * np.pi * table[:, 0]), atol=0.5)


@pytest.mark.parametrize("args, fragment", [
    (["segment", "missing.amc"], "No such file"),
    (["segment", "{bad}"], "expected 9 numbers"),
    (["segment", "{small}", "--channels", "nope"], "no channel 'nope'"),
    (["segment", "{small}", "--smoothing", "-1"], "non-negative"),
    (["decompress", "{small}"], "bad magic"),
    (["evaluate"], "nothing to evaluate"),
    (["evaluate", "--mocap6", "/nonexistent"], "no cmu-mocap6 takes"),  # was StopIteration
    (["evaluate", "--mocap6", "{labels}"], "labels.txt:2:3: a label is a number from 1 to"),
])
def test_errors_are_one_line_and_exit_2(args, fragment, small_bvh, tmp_path, capsys):
    bad = tmp_path / "bad.bvh"
    bad.write_text(small_bvh.read_text().replace("0 0 0 0 0 0 0.0000 0 20.0000", "0 0 0", 1))
    (tmp_path / "amc").mkdir()
    (tmp_path / "truelabels").mkdir()
    (tmp_path / "amc" / "labels.amc").write_text(":FULLY-SPECIFIED\n:DEGREES\n1\nroot 0 0 0 "
                                                 "0 0 0\n2\nroot 0 0 0 1 0 0\n")
    (tmp_path / "truelabels" / "labels.txt").write_text("1 1\n1 0 2\n")  # 0: no action
    args = [a.format(bad=bad, small=small_bvh, labels=tmp_path) for a in args]
    assert main(args) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("kinetology: error:"), captured.err
    assert fragment in lines[0]
    assert "Traceback" not in captured.err


def test_plot_writes_pictures(small_bvh, tmp_path):
    pytest.importorskip("matplotlib")
    for kind in ("states", "reconstruction"):
        out = tmp_path / f"{kind}.png"
        assert main(["plot", str(small_bvh), "--channel", "Knee.rz", "--kind", kind,
                     "-o", str(out)]) == 0
        assert out.stat().st_size > 1000 and out.read_bytes()[:4] == b"\x89PNG"


@needs_mocap
def test_evaluate_on_a_cmu_take(capsys):
    path = MOCAP / "cmu-subject02" / "02_01.amc"
    assert main(["evaluate", str(path), "--views", "6"]) == 0
    out = capsys.readouterr().out
    assert "compactness" in out and "reconstructivity" in out and "lknee" in out


@needs_mocap
def test_segment_a_cmu_amc_for_psgs(tmp_path):
    out = tmp_path / "walk.txt"
    assert main(["segment", str(MOCAP / "cmu-subject02" / "02_01.amc"), "-o", str(out)]) == 0
    ag = psgs.load(out, kind="actiongram")
    assert "lfemur.rx" in ag.names and ag.total_symbols > 100


@needs_mocap
def test_psgs_induce_accepts_a_segmented_cmu_take(tmp_path, capsys):
    # no skip when `psgs induce` is missing: it exists, and this is an acceptance point
    from psgs.cli import main as psgs_main

    out = tmp_path / "walk.actiongram"
    assert main(["segment", str(MOCAP / "cmu-subject02" / "02_01.amc"), "-o", str(out)]) == 0
    capsys.readouterr()
    assert psgs_main(["induce", str(out)]) == 0
    assert "component" in capsys.readouterr().out


def test_plot_window_outside_the_motion_is_one_line(small_bvh, tmp_path, capsys):
    pytest.importorskip("matplotlib")
    out = tmp_path / "late.png"
    assert main(["plot", str(small_bvh), "--channel", "Knee.rz", "--start", "5",
                 "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no frames between 5 s and the end" in err[0], err
    assert not out.exists()


def test_view_invariance_needs_at_least_one_view():
    from kinetology.evaluation import view_invariance
    from test_kinetology_eval import _planar_leg

    with pytest.raises(ValueError, match="views must be a positive"):
        view_invariance(_planar_leg(), ("Thigh", "Shin", "Shin.end"), views=0)


# ---- --frame-rate for AMC, misspelt channels listed
def _small_amc(tmp_path):
    from test_kinetology_readers import SMALL_AMC, SMALL_ASF
    (tmp_path / "s.asf").write_text(SMALL_ASF)
    rows = "".join(f"{k}\nroot 0 0 0 0 0 0\nfemur {40 * np.sin(k / 8):.3f}\ntibia 0 0\n"
                   for k in range(1, 121))
    path = tmp_path / "s_1.amc"
    path.write_text(":FULLY-SPECIFIED\n:DEGREES\n" + rows)
    return path


def test_frame_rate_sets_an_amc_files_rate(tmp_path, capsys):
    path = _small_amc(tmp_path)
    assert main(["segment", str(path), "--frame-rate", "30"]) == 0
    out = capsys.readouterr().out
    assert "120 frames at 30 fps" in out
    ag = psgs.Actiongram.from_text(out)
    assert sum(ag.durations["femur.rx"]) == pytest.approx(120 / 30)


def test_frame_rate_with_a_bvh_file_is_an_error(small_bvh, capsys):
    assert main(["segment", str(small_bvh), "--frame-rate", "30"]) == 2
    assert "applies to AMC files" in capsys.readouterr().err


@pytest.mark.parametrize("rate", ["0", "-5", "nan", "x"])
def test_a_bad_frame_rate_is_a_usage_error(tmp_path, rate, capsys):
    with pytest.raises(SystemExit) as info:
        main(["segment", str(_small_amc(tmp_path)), "--frame-rate", rate])
    assert info.value.code == 2


def test_a_misspelt_channel_lists_the_files_channels(small_bvh, capsys):
    assert main(["segment", str(small_bvh), "--channels", "Kne.rz"]) == 2
    err = capsys.readouterr().err
    assert len(err.splitlines()) == 1
    assert "did you mean Knee.rz" in err and "Hips.tx" in err and "9 channels" in err


def test_segment_several_files_writes_one_actiongram_each_named_after_it(small_bvh, tmp_path,
                                                                         capsys):
    other = tmp_path / "other.bvh"
    other.write_text(small_bvh.read_text())
    out = tmp_path / "grams"
    assert main(["segment", str(small_bvh), str(other), "-o", f"{out}/"]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["other.actiongram", "small.actiongram"]
    ag = psgs.load(out / "other.actiongram")
    assert ag.actuator("Knee.rz") == "Knee"
    assert "other.actiongram: 2 strings" in capsys.readouterr().out
    # several files and no folder: refused, one line
    assert main(["segment", str(small_bvh), str(other)]) == 2
    assert "give -o DIR/" in capsys.readouterr().err


def test_segment_start_stop_cuts_the_take(small_bvh, tmp_path, capsys):
    out = tmp_path / "part.actiongram"
    assert main(["segment", str(small_bvh), "--start", "0.5", "--stop", "1.5", "-o",
                 str(out)]) == 0
    text = out.read_text()
    assert "from 0.5 s to 1.5 s: 120 frames" in text.splitlines()[0]
    ag = psgs.load(out)
    assert sum(ag.durations["Knee.rz"]) == pytest.approx(1.0)
    assert main(["segment", str(small_bvh), "--start", "3"]) == 2
    assert "start 3 s is outside the take" in capsys.readouterr().err


def test_segment_labels_writes_one_actiongram_per_labelled_span(small_bvh, tmp_path, capsys):
    labels = tmp_path / "small.txt"  # CMU truelabels: one label per 12 frames (1/10 s)
    labels.write_text(" ".join(["5"] * 5 + ["1"] * 10 + ["5"] * 5))
    out = tmp_path / "spans"
    assert main(["segment", str(small_bvh), "--labels", str(labels), "--label", "ArmCircle",
                 "-o", f"{out}/"]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["small-ArmCircle-1.actiongram",
                                                      "small-ArmCircle-2.actiongram"]
    second = psgs.load(out / "small-ArmCircle-2.actiongram")
    assert sum(second.durations["Knee.rz"]) == pytest.approx(0.5)
    assert main(["segment", str(small_bvh), "--labels", str(labels), "--label", "Squat",
                 "-o", str(out)]) == 2
    assert "no span labelled 'Squat'" in capsys.readouterr().err


def test_segment_labels_leaves_out_a_span_too_short_to_segment_and_says_so(small_bvh, tmp_path,
                                                                          capsys, monkeypatch):
    import kinetology.labels
    from kinetology.labels import Span

    # a label file may hold a span of a frame or two (its own rate, a cut take's end)
    spans = (Span("ArmCircle", 0.0, 0.01), Span("ArmCircle", 0.5, 1.5))
    monkeypatch.setattr(kinetology.labels, "spans_of", lambda path, rate: spans)
    out = tmp_path / "spans"
    assert main(["segment", str(small_bvh), "--labels", "any.txt", "-o", f"{out}/"]) == 0
    assert [p.name for p in out.iterdir()] == ["small-ArmCircle-1.actiongram"]
    assert "left out 1 span of fewer than 3 frames" in capsys.readouterr().err


@needs_mocap
def test_segment_labels_of_a_real_mocap6_take(tmp_path, capsys):
    folder = MOCAP / "cmu-mocap6"
    assert main(["segment", str(folder / "amc" / "13_29.amc"), "--labels",
                 str(folder / "truelabels" / "13_29.txt"), "--label", "Squat",
                 "--min-seconds", "2", "--channels", "ltibia.rx", "-o", str(tmp_path)]) == 0
    grams = sorted(tmp_path.glob("13_29-Squat-*.actiongram"))
    assert len(grams) == 1
    ag = psgs.load(grams[0])
    assert len(ag.string("ltibia.rx")) >= 8  # several squats: several knee cycles
