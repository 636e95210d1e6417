"""Fixes from a user review of the kinetology command: errors modulo 360°, one-line refusals
before any output, and the byte a truncated .kin file ends at."""

from __future__ import annotations

import numpy as np
import pytest

import kinetology
from kinetology import Motion
from kinetology.cli import main

from test_kinetology_readers import SMALL_BVH


def _crossing(frames: int = 240) -> Motion:
    """A hip turning around ±180° (the file's angle jumps from +179 to -179) and a root
    translation: the decoder returns the angle unwrapped."""
    t = np.arange(frames) / 120
    turn = (180 + 15 * np.sin(2 * np.pi * t) + 180) % 360 - 180
    return Motion(np.column_stack([10 * t, turn]), ("root.tx", "hip.rz"), 120.0,
                  source="crossing.bvh")


def _write_bvh(path, frames: int = 240):
    t = np.arange(frames) / 120
    rows = "\n".join(f"0 0 0 0 0 0 {30 * np.sin(2 * np.pi * x):.4f} 0 {20 * np.cos(3 * x):.4f}"
                     for x in t)
    head = SMALL_BVH[: SMALL_BVH.index("Frames:")]
    path.write_text(f"{head}Frames: {frames}\nFrame Time: 0.0083333\n{rows}\n")
    return path


# -- 1. errors modulo 360° ------------------------------------------------------------------

def test_codec_point_compares_rotations_modulo_360_as_compress_reports():
    from kinetology.evaluation import codec_point

    motion = _crossing()
    point = codec_point(motion, original_size=10_000)
    data = kinetology.compress(motion)
    assert point["mae_angles"] == pytest.approx(data.mean_error)
    assert point["mae"] == pytest.approx(data.mean_error_all)
    assert point["max_error"] < 5  # not the 360° between +179 and the decoded -181


def test_absolute_errors_wrap_rotations_but_not_translations():
    from kinetology.codec import absolute_errors

    a = Motion(np.array([[-179.0, 1.0]]), ("neck.rz", "root.tx"), 120)
    b = Motion(np.array([[181.5, 361.0]]), ("neck.rz", "root.tx"), 120)
    np.testing.assert_allclose(absolute_errors(a, b), [[0.5, 360.0]])


def test_reconstruction_plot_title_and_curve_are_modulo_360():
    pytest.importorskip("matplotlib")
    from kinetology.plotting import plot_reconstruction

    motion = _crossing()
    decoded = kinetology.decompress(kinetology.compress(motion))
    fig = plot_reconstruction(motion, decoded, "hip.rz")
    error = float(fig.axes[0].get_title().split("mean |error| ")[1].split()[0])
    assert error == pytest.approx(kinetology.codec.mean_errors(motion, decoded)[0], abs=1e-3)
    original, shown = (line.get_ydata() for line in fig.axes[0].get_lines())
    assert np.abs(original - shown).max() < 5  # drawn on the original's turn
    import matplotlib.pyplot as plt
    plt.close(fig)


# -- 2. a picture format matplotlib does not write ------------------------------------------

@pytest.mark.parametrize("kind", ["states", "reconstruction", "view"])
@pytest.mark.parametrize("name", ["p.txt", "p.xyz", "p"])
def test_plot_refuses_an_unknown_suffix_in_one_line_before_reading(tmp_path, capsys, kind,
                                                                   name):
    pytest.importorskip("matplotlib")
    # the input does not exist: the output's suffix is refused before any work
    argv = ["plot", str(tmp_path / "missing.bvh"), "--channel", "lknee", "--kind", kind,
            "-o", str(tmp_path / name)]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err
    assert str(tmp_path / name) in err and ".png, .svg, .pdf" in err
    assert not (tmp_path / name).exists()


# -- 8. a truncated .kin file ---------------------------------------------------------------

def test_a_truncated_kin_file_names_the_byte_it_ends_at(tmp_path):
    from kinetology import MotionFormatError

    data = bytes(kinetology.compress(kinetology.synthetic_motion(3, seed=0)))
    for cut in (len(data) // 2, len(data) - 1):
        with pytest.raises(MotionFormatError, match=rf"at byte {cut} of the file"):
            kinetology.decompress(data[:cut], source="cut.kin")


# -- 3, 4, 6, 9. segment: refusals before any work, nothing half written -------------------

def _one_line(capsys) -> str:
    captured = capsys.readouterr()
    err = captured.err.strip()
    assert len(err.splitlines()) == 1 and "Traceback" not in err, err
    assert captured.out == "", captured.out
    return err


@pytest.mark.parametrize("extra", [["--min-range", "1e9"], ["--channels", ""],
                                   ["--channels", ",,"],
                                   ["--channels", "Knee.rx", "--min-range", "1e9"]])
def test_segment_refuses_to_write_an_actiongram_without_strings(tmp_path, capsys, extra):
    out = tmp_path / "still.actiongram"
    assert main(["segment", str(_write_bvh(tmp_path / "take.bvh")), *extra,
                 "-o", str(out)]) == 2
    err = _one_line(capsys)
    assert "no channel" in err
    assert not out.exists()


def test_segment_of_several_files_wants_a_folder_named_as_one(tmp_path, capsys):
    one, two = _write_bvh(tmp_path / "one.bvh"), _write_bvh(tmp_path / "two.bvh")
    out = tmp_path / "k" / "two.actiongram"
    assert main(["segment", str(one), str(two), "-o", str(out)]) == 2
    assert f"give -o {out}/" in _one_line(capsys)
    assert not (tmp_path / "k").exists()
    assert main(["segment", str(one), str(two), "-o", f"{out}/"]) == 0
    assert (out / "one.actiongram").is_file()


def test_segment_labels_want_a_folder_named_as_one(tmp_path, capsys):
    labels = tmp_path / "take.txt"  # CMU mocap6 truelabels: one label per 1/10 s
    labels.write_text(" ".join(["1"] * 20) + "\n")
    out = tmp_path / "spans"
    assert main(["segment", str(_write_bvh(tmp_path / "take.bvh")), "--labels", str(labels),
                 "-o", str(out)]) == 2
    assert f"give -o {out}/" in _one_line(capsys)
    assert not out.exists()


@pytest.mark.parametrize("extra", [["--label", "Squat"], ["--min-seconds", "5"],
                                   ["--label", "Squat", "--min-seconds", "0"]])
def test_segment_span_options_without_labels_are_an_error(tmp_path, capsys, extra):
    assert main(["segment", str(_write_bvh(tmp_path / "take.bvh")), *extra]) == 2
    err = _one_line(capsys)
    assert "--labels" in err and extra[0] in err


def test_segment_of_takes_with_different_skeletons_says_so(tmp_path, capsys):
    from kinetology.performances import segment_performances

    take = _write_bvh(tmp_path / "take.bvh")
    other = tmp_path / "other.bvh"
    other.write_text(take.read_text().replace("Knee", "Elbow"))
    assert main(["segment", str(take), str(other), "-o", f"{tmp_path / 'mix'}/"]) == 2
    err = _one_line(capsys)
    assert "different channels" in err and "did you mean" not in err
    with pytest.raises(KeyError, match="different channels"):
        segment_performances([kinetology.read(take), kinetology.read(other)])


# -- 5, 9. --frame-rate and frame_rate= with a BVH file, or not positive --------------------

@pytest.mark.parametrize("rate", ["0", "-3"])
def test_view_refuses_a_frame_rate_that_is_not_positive(tmp_path, capsys, rate):
    with pytest.raises(SystemExit) as exit_:
        main(["view", str(_write_bvh(tmp_path / "take.bvh")), "-o", str(tmp_path / "v.html"),
              "--frame-rate", rate])
    assert exit_.value.code == 2


def test_view_refuses_a_frame_rate_with_a_bvh_file(tmp_path, capsys):
    out = tmp_path / "v.html"
    assert main(["view", str(_write_bvh(tmp_path / "take.bvh")), "-o", str(out),
                 "--frame-rate", "5"]) == 2
    assert "--frame-rate applies to AMC files" in _one_line(capsys)
    assert not out.exists()


def test_read_of_a_bvh_file_with_a_frame_rate_is_a_clear_error(tmp_path):
    from kinetology import MotionFormatError

    with pytest.raises(MotionFormatError, match="frame_rate applies to AMC files"):
        kinetology.read(_write_bvh(tmp_path / "take.bvh"), frame_rate=30)


# -- 7. evaluate and decompress --against: checked before any output -----------------------

@pytest.mark.parametrize("views", ["0", "100000000"])
def test_evaluate_checks_views_before_the_report(tmp_path, capsys, views):
    assert main(["evaluate", str(_write_bvh(tmp_path / "take.bvh")), "--views", views]) == 2
    assert "--views" in _one_line(capsys)


def test_evaluate_reads_every_file_before_the_report(tmp_path, capsys):
    assert main(["evaluate", str(_write_bvh(tmp_path / "take.bvh")),
                 str(tmp_path / "missing.bvh")]) == 2
    assert "missing.bvh" in _one_line(capsys)


def test_decompress_against_another_motion_writes_no_csv(tmp_path, capsys):
    packed = tmp_path / "take.kin"
    assert main(["compress", str(_write_bvh(tmp_path / "take.bvh")), "-o", str(packed)]) == 0
    capsys.readouterr()
    other = _write_bvh(tmp_path / "other.bvh", frames=100)
    assert main(["decompress", str(packed), "--against", str(other)]) == 2
    assert "shape" in _one_line(capsys)


@pytest.mark.parametrize("option, value", [("--unwrap", "180"), ("--relative-deadband", "0.1")])
def test_segmentation_only_settings_reach_no_codec_traceback(tmp_path, capsys, option, value):
    # (an unwrap period is 0 or at least 1 degree: 180, the period of an axis)
    take = str(_write_bvh(tmp_path / "take.bvh"))
    assert main(["evaluate", take, option, value]) == 0
    assert "reconstructivity" in capsys.readouterr().out
    pytest.importorskip("matplotlib")
    assert main(["plot", take, "--channel", "Knee.rx", "--kind", "reconstruction", option,
                 value, "-o", str(tmp_path / "p.png")]) == 2
    assert f"no setting {option}" in _one_line(capsys)
