"""What a new user's sweep of the kinetology command and API found: each test fails before
its fix (plot's --min-range, label files of another take, ...)."""

from __future__ import annotations

import shutil
import warnings

import numpy as np
import pytest

import kinetology

from kinetology.cli import main
from kinetology.viewer import ViewError

from kinetology_fixtures import MOCAP, needs_mocap, real_take
from test_kinetology_review_fixes import _write_bvh


def _one_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("kinetology: error:"), err
    return err[0]


# -- plot --min-range -----------------------------------------------------------------------

def _drawn(monkeypatch):
    """The figures plot would have written, instead of writing them."""
    import kinetology.plotting

    figures = []
    monkeypatch.setattr(kinetology.plotting, "save", lambda fig, path: figures.append(fig))
    return figures


def test_plot_states_draws_a_channel_below_min_range_as_still(tmp_path, monkeypatch, capsys):
    pytest.importorskip("matplotlib")
    from kinetology.plotting import STILL_COLOUR

    take, out = str(_write_bvh(tmp_path / "take.bvh")), str(tmp_path / "p.png")
    figures = _drawn(monkeypatch)
    assert main(["plot", take, "--channel", "Knee.rx", "-o", out]) == 0
    assert main(["plot", take, "--channel", "Knee.rx", "--min-range", "1000", "-o", out]) == 0
    moving, still = (fig.axes[0] for fig in figures)
    assert "states" in moving.get_title() and len(moving.get_lines()) == 4
    assert still.get_title().startswith("Knee.rx: still (moves less than min_range 1000 deg")
    assert [line.get_color() for line in still.get_lines()] == [STILL_COLOUR]


@pytest.mark.parametrize("kind, says", [
    ("reconstruction", "the codec has no setting --min-range"),
    ("view", "--kind view: --min-range does not apply"),
])
def test_plot_refuses_min_range_where_it_means_nothing(tmp_path, capsys, kind, says):
    pytest.importorskip("matplotlib")
    out = tmp_path / "p.png"
    assert main(["plot", str(_write_bvh(tmp_path / "take.bvh")), "--channel", "lknee",
                 "--kind", kind, "--min-range", "5", "-o", str(out)]) == 2
    assert says in _one_line(capsys)
    assert not out.exists()


# -- label files of another take ------------------------------------------------------------

def test_segment_refuses_labels_reaching_past_the_take_naming_the_file(tmp_path, capsys):
    take = _write_bvh(tmp_path / "take.bvh")  # 240 frames at 120 fps: 2 s
    labels = tmp_path / "other.txt"  # one label per 1/10 s: 3 s of labels
    labels.write_text(" ".join(["1"] * 10 + ["5"] * 20) + "\n")
    out = tmp_path / "spans"
    assert main(["segment", str(take), "--labels", str(labels), "-o", f"{out}/"]) == 2
    err = _one_line(capsys)
    assert f"{labels}: the labels reach 3 s, past the end of the take take.bvh (2 s" in err
    assert not out.exists()


def test_segment_takes_labels_within_their_rounding_past_the_end(tmp_path, capsys):
    take = _write_bvh(tmp_path / "take.bvh", frames=228)  # 1.9 s; the labels' last block is
    labels = tmp_path / "take.txt"  # past it, and it starts a new label: no frame, left out
    labels.write_text(" ".join(["1"] * 10 + ["5"] * 9 + ["1"]) + "\n")
    out = tmp_path / "spans"
    assert main(["segment", str(take), "--labels", str(labels), "-o", f"{out}/"]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["take-ArmCircle-1.actiongram",
                                                      "take-JumpJack-1.actiongram"]


@needs_mocap
def test_every_shared_label_file_fits_its_take():
    from kinetology.labels import spans_of
    from kinetology.performances import from_spans

    pairs = [(t, t.parent.parent / "amc" / f"{t.stem}.amc")
             for t in sorted((MOCAP / "cmu-mocap6" / "truelabels").glob("*.txt"))]
    for dataset in ("bandai-namco-1", "bandai-namco-2-subset"):
        pairs += [(j, j.with_suffix(".bvh"))
                  for j in sorted((MOCAP / dataset / "data").glob("*.json"))]
    pairs = [(labels, take) for labels, take in pairs if take.is_file()]
    assert len(pairs) > 300
    for labels, take in pairs:
        motion = real_take(take)
        parts = from_spans(motion, spans_of(labels, motion.frame_rate), source=str(labels))
        assert sum(p.frames for p in parts) == motion.frames, labels


# -- the viewer ------------------------------------------------------------------------------

def _far_bvh(path, position: float = 1e300):
    """A take whose root travels ``position`` units away: finite, but its squares are not."""
    rows = "\n".join(f"{position if k % 2 else 0} 0 0 {10 * k}" for k in range(6))
    path.write_text("HIERARCHY\nROOT hip\n{ OFFSET 0 0 0\n  CHANNELS 4 Xposition Yposition "
                    "Zposition Xrotation\n  JOINT knee\n  { OFFSET 0 -10 0\n    End Site\n"
                    "    { OFFSET 0 -10 0 } } }\n"
                    f"MOTION\nFrames: 6\nFrame Time: 0.0333333\n{rows}\n")
    return path


@pytest.mark.parametrize("suffix", [".html", ".gif"])
def test_view_refuses_positions_too_far_to_draw(tmp_path, capsys, suffix):
    if suffix == ".gif":
        pytest.importorskip("matplotlib")
    take, out = _far_bvh(tmp_path / "far.bvh"), tmp_path / f"far{suffix}"
    assert main(["view", str(take), "-o", str(out)]) == 2
    assert f"{take}: joint positions reach 1e+300 units, too far to draw" in _one_line(capsys)
    assert not out.exists()  # the page held NaN and Infinity, which no browser reads
    assert main(["view", str(_far_bvh(tmp_path / "near.bvh", 1e6)), "-o", str(out)]) == 0


def _slow_leg(frames: int):
    """A knee bending at 0.1 fps, the slowest rate a motion may have."""
    from kinetology import Joint, Motion, Skeleton

    leg = Skeleton((Joint("hip", None, (0, 0, 0), ("hip.rx",)),
                    Joint("knee", 0, (0, -10, 0), ("knee.rx",)),
                    Joint("foot", 1, (0, -10, 0), end_site=True)))
    knee = 45 + 40 * np.sin(np.arange(frames) / 50)
    return Motion(np.column_stack([0 * knee, knee]), ("hip.rx", "knee.rx"), 0.1, leg, "leg")


@pytest.mark.parametrize("suffix, frames", [(".gif", 200), (".mp4", 30_000)])
def test_view_writes_one_frame_at_any_rate_and_refuses_frames_too_slow(tmp_path, capsys,
                                                                       suffix, frames):
    pytest.importorskip("matplotlib")
    if suffix == ".mp4" and shutil.which("ffmpeg") is None:
        pytest.skip("ffmpeg is not installed")
    take, out = str(_write_bvh(tmp_path / "take.bvh", frames=12)), tmp_path / f"v{suffix}"
    # one frame kept: its duration shows nothing (Pillow's OverflowError, ffmpeg's failure)
    assert main(["view", take, "-o", str(out), "--max-rate", "1e-300"]) == 0
    assert "1 frame at 1e-300 fps" in capsys.readouterr().out and out.stat().st_size > 0
    out.unlink()
    # two frames kept of a long take at 0.1 fps: each lasts longer than the format shows one
    with pytest.raises(ViewError, match=rf"v\{suffix}: .* frames a second is slower than a "
                                        rf"\{suffix} plays"):
        kinetology.view(_slow_leg(frames), out, max_frames=2, kinetemes=False)
    assert not out.exists()


def test_a_gif_of_a_fast_player_plays_in_time(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    from PIL import Image, ImageSequence

    out = tmp_path / "fast.gif"  # 24 frames at 120 fps: 0.2 s
    assert main(["view", str(_write_bvh(tmp_path / "take.bvh", frames=24)), "-o", str(out),
                 "--max-rate", "inf"]) == 0
    assert "24 frames at 120 fps" in capsys.readouterr().out
    with Image.open(out) as gif:  # a delay of 0 (8 ms, stored in hundredths) played as 100 ms
        delays = [frame.info["duration"] for frame in ImageSequence.Iterator(gif)]
    assert min(delays) >= 20 and sum(delays) == 200


# -- evaluate --min-range ------------------------------------------------------------------

def test_evaluate_min_range_leaves_the_mocap6_descriptions_their_own_threshold(monkeypatch,
                                                                              capsys):
    import kinetology.evaluation as evaluation
    from kinetology.evaluation import Performance

    t = np.arange(1440) / 120  # a knee swinging 60 degrees; an elbow 3 (still by 5, not by 2)
    elbow = np.where(t < 8, 1.5 * np.sin(2 * np.pi * t), 0.0)  # in the swings, not the wave
    take = kinetology.Motion(np.column_stack([30 * np.sin(2 * np.pi * t), elbow]),
                             ("knee.rx", "elbow.rx"), 120.0)
    performances = [Performance("t", "swing", 0, 480), Performance("t", "swing", 480, 960),
                    Performance("t", "wave", 960, 1440)]
    monkeypatch.setattr(evaluation, "mocap6_performances", lambda folder: ({"t": take},
                                                                          performances))
    reports = []
    for extra in ([], ["--min-range", "2"]):  # 2 is the default the help gives
        assert main(["evaluate", "--mocap6", "folder", *extra]) == 0
        reports.append(capsys.readouterr().out)
    assert reports[0] == reports[1], reports


@needs_mocap
def test_plot_view_draws_the_window_asked_for(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    take = MOCAP / "bandai-namco-1" / "data" / "dataset-1_bye_normal_001.bvh"  # 3.7 s
    figures = _drawn(monkeypatch)
    for window in ([], ["--start", "1", "--stop", "2"]):
        assert main(["plot", str(take), "--channel", "lknee", "--kind", "view", *window,
                     "-o", str(tmp_path / "v.png")]) == 0
    whole, part = (fig.axes[0].images[0].get_extent()[:2] for fig in figures)
    assert whole == pytest.approx((0, 3.7)) and part == pytest.approx((1, 2 + 1 / 30))


# -- extreme parameters ----------------------------------------------------------------------

@pytest.mark.parametrize("engine", ["numpy", "numba"])
def test_a_huge_relative_dead_band_warns_nothing(engine, capsys):
    pytest.importorskip("numba") if engine == "numba" else None
    from kinetology.segmentation import segments

    walk = kinetology.synthetic_motion(2, (0,), seed=0)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy's overflow warning was printed on stderr
        found = segments(walk, engine=engine, relative_deadband=1e308)
    assert all(len(codes) == 1 for codes in found.codes)  # one segment: no sign is significant


def test_a_max_error_too_fine_for_any_setting_says_why(tmp_path, capsys):
    assert main(["compress", str(_write_bvh(tmp_path / "take.bvh")), "--max-error",
                 "1e-300"]) == 2
    err = _one_line(capsys)
    assert "no setting meets max_error=1e-300" in err and "nan" not in err
    assert "no residual step that fine fits in 62 bits" in err


def test_decompress_reads_a_memoryview_and_names_a_wrong_type():
    from psgs.errors import ValidationError

    walk = kinetology.synthetic_motion(2, (0,), seed=0)
    data = kinetology.compress(walk)
    assert kinetology.decompress(memoryview(data)).frames == walk.frames  # was "bad magic"
    with pytest.raises(ValidationError, match="a compressed motion is bytes, not str"):
        kinetology.decompress(data.decode("latin-1"))


# -- an output that is an input ----------------------------------------------------------------

@pytest.mark.parametrize("command", [["segment", "{take}", "-o", "{take}"],
                                     ["compress", "{take}", "-o", "{link}"],
                                     ["decompress", "{kin}", "-o", "{kin}"],
                                     ["decompress", "{kin}", "-o", "{take}", "--against",
                                      "{take}"]])
def test_an_output_that_is_an_input_is_refused_and_the_input_kept(tmp_path, capsys, command):
    take = _write_bvh(tmp_path / "take.bvh")
    kin = tmp_path / "take.kin"
    assert main(["compress", str(take), "-o", str(kin)]) == 0
    (tmp_path / "link.bvh").symlink_to(take)
    before = take.read_bytes(), kin.read_bytes()
    capsys.readouterr()
    names = {"take": str(take), "kin": str(kin), "link": str(tmp_path / "link.bvh")}
    assert main([part.format(**names) for part in command]) == 2
    assert "which writing would destroy; give another output" in _one_line(capsys)
    assert (take.read_bytes(), kin.read_bytes()) == before
