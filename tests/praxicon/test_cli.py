"""The praxicon's command line: python -m praxicon, and psgs praxicon through the entry point."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from importlib.metadata import entry_points
from pathlib import Path

import pytest

from praxicon.cli import main

REPO = Path(__file__).resolve().parents[2]


def test_build_draw_generate(manifest, tmp_path, capsys):
    out = tmp_path / "px"
    assert main(["build", str(manifest), "-o", str(out), "--no-progress",
                 "--param", "min_copies=3"]) == 0
    captured = capsys.readouterr()
    assert captured.out.strip() == (f"praxicon: 4 actions, 2 learnt, 2 failed (0 already done) "
                                    f"-> {out}/index.json")
    assert "moves.alone: failed: 1 usable performance(s)" in captured.err
    index = json.loads((out / "index.json").read_text())
    assert index["settings"]["params"] == {"min_copies": 3}
    assert main(["build", str(manifest), "-o", str(out), "--no-progress",
                 "--param", "min_copies=3"]) == 0
    assert "(4 already done)" in capsys.readouterr().out
    assert main(["draw", str(out), "-o", str(out / "img")]) == 0
    # SVG by default: a system's graph is not rasterised
    assert (out / "img" / "actuators.svg").is_file()
    assert sorted(p.suffix for p in (out / "img" / "systems").iterdir()) == [".svg"] * len(
        list((out / "img" / "systems").iterdir()))
    drew = capsys.readouterr()
    # stdout: the pictures written; stderr: progress per action and a count, no warning
    assert all(Path(line).is_file() for line in drew.out.splitlines())
    assert "drawing 1/" in drew.err and f"drew {len(drew.out.splitlines())} pictures" in drew.err
    assert "Warning" not in drew.err
    assert main(["generate", str(out), "moves.wave", "--repeat", "2",
                 "-o", str(tmp_path / "w.bvh")]) == 0
    printed = capsys.readouterr().out
    assert "2 copies" in printed and (tmp_path / "w.bvh").is_file()
    # the round trip: the synthetic waves are smooth cycles, every channel comes back
    assert re.search(r"segmented again: (\d+) of \1 channels give back their morpheme x 2",
                     printed), printed
    # --view: the generated motion played beside a performance it was learnt from
    assert main(["generate", str(out), "moves.wave", "--repeat", "1", "-o",
                 str(tmp_path / "w1.bvh"), "--view", str(tmp_path / "w1.html")]) == 0
    last = capsys.readouterr().out.splitlines()[-1]
    assert last.startswith(f"{tmp_path / 'w1.html'}: performance (") and \
        last.endswith(") beside generated")
    page = (tmp_path / "w1.html").read_text()
    assert page.count("generated") >= 1 and "<script" in page


def test_build_that_learns_nothing_exits_1_and_still_writes_the_folder(tmp_path, capsys):
    from praxicon_fixtures import write_manifest

    data = tmp_path / "data"
    data.mkdir()
    lonely = write_manifest(data, {"wave": [1], "step": [4]})  # one take each: both fail
    out = tmp_path / "px"
    assert main(["build", str(lonely), "-o", str(out), "--no-progress"]) == 1
    captured = capsys.readouterr()
    assert "2 actions, 0 learnt, 2 failed" in captured.out
    assert captured.err.rstrip().splitlines()[-1].startswith(
        "praxicon: no action learnt: every one of the 2 failed")
    index = json.loads((out / "index.json").read_text())
    assert len(index["actions"]) == 2  # the failures are recorded all the same
    # one action learnt is a build that did something: 0
    write_manifest(data, {"wave": [1, 2, 3], "step": [4]})
    assert main(["build", str(lonely), "-o", str(out), "--no-progress"]) == 0


def test_generate_a_style(manifest, tmp_path, capsys):
    out = tmp_path / "px"
    assert main(["build", str(manifest), "-o", str(out), "--no-progress",
                 "--param", "min_copies=3"]) == 0
    capsys.readouterr()
    # the synthetic takes are wave_1, wave_2, wave_3: each number a word of the file name
    assert main(["generate", str(out), "moves.wave", "--repeat", "1", "--style", "2",
                 "-o", str(tmp_path / "w2.bvh")]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.endswith(", style 2") and (tmp_path / "w2.bvh").is_file()
    assert main(["generate", str(out), "moves.wave", "--style", "sad",
                 "-o", str(tmp_path / "sad.bvh")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    # take numbers are not named as styles: these takes have none
    assert err == ["psgs: error: action 'moves.wave' has no performance of style 'sad'"]
    assert not (tmp_path / "sad.bvh").exists()


@pytest.mark.parametrize("argv, message", [
    (["build", "nowhere", "-o", "x"], "nowhere: no such file or folder"),
    (["build", ".", "-o", "x", "--inducer", "nope"], "unknown inducer 'nope'"),
    (["build", ".", "-o", "x", "--param", "nope=1"], "has no parameter 'nope'"),
    (["build", ".", "-o", "x", "--inducer", "sequential", "--param", "max_rules=none"],
     "parameter max_rules must be an integer, not 'none'"),
    (["build", ".", "-o", "x", "--segment", "nope=1"], "--segment nope: unknown"),
    (["draw", "nowhere", "-o", "x"], "nowhere: no such praxicon folder"),
    (["generate", "nowhere", "a", "-o", "x.bvh"], "nowhere: no such praxicon folder"),
])
def test_bad_input_is_one_line(argv, message, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("psgs: error: ") and message in err[0]


def test_python_dash_m_praxicon_runs():
    done = subprocess.run([sys.executable, "-m", "praxicon", "build", "--help"], cwd=REPO,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0 and "--workers N" in done.stdout and "--scheduler" in done.stdout


def test_installed_entry_point_adds_psgs_praxicon():
    # relies on the install CI does (pip install '.[test]'): the entry point is package metadata
    (ep,) = [ep for ep in entry_points(group="psgs.commands") if ep.name == "praxicon"]
    assert ep.value == "praxicon.cli:register"
    from psgs.cli import build_parser

    assert "praxicon" in build_parser().format_help()


def test_generate_checks_every_output_before_writing_any(manifest, tmp_path, capsys,
                                                         monkeypatch):
    out = tmp_path / "px"
    assert main(["build", str(manifest), "-o", str(out), "--no-progress",
                 "--param", "min_copies=3"]) == 0
    capsys.readouterr()
    bvh, plot, page = tmp_path / "g.bvh", tmp_path / "g.png", tmp_path / "g.html"
    for options, words in [
        (["-o", str(bvh), "--view", str(tmp_path / "g.pdf")], "cannot write '.pdf'"),
        (["-o", str(tmp_path / "g.txt")], "give -o a .bvh file"),
        (["-o", str(bvh), "--plot", str(tmp_path / "g.bvh2")], "cannot write '.bvh2' pictures"),
    ]:
        assert main(["generate", str(out), "moves.wave", "--repeat", "1", *options]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and words in err[0], err
        assert sorted(p.name for p in tmp_path.glob("g.*")) == []
    # a motion the viewer cannot draw (here: its skeleton taken away) is said before the BVH
    # file and the plot are written, not after
    import praxicon.generation as generation

    real = generation.generate_motion

    def without_skeleton(*args, **kwargs):
        motion, words, methods = real(*args, **kwargs)
        return motion.select(motion.channels), words, methods

    monkeypatch.setattr(generation, "generate_motion", without_skeleton)
    assert main(["generate", str(out), "moves.wave", "--repeat", "1", "-o", str(bvh),
                 "--plot", str(plot), "--view", str(page)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no skeleton to draw" in err[0], err
    assert sorted(p.name for p in tmp_path.glob("g.*")) == []
    monkeypatch.setattr(generation, "generate_motion", real)
    assert main(["generate", str(out), "moves.wave", "--repeat", "1", "-o", str(bvh),
                 "--plot", str(plot), "--view", str(page)]) == 0
    assert sorted(p.name for p in tmp_path.glob("g.*")) == ["g.bvh", "g.html", "g.png"]


def test_generate_view_labels_panels_by_file_name(manifest, tmp_path, capsys):
    out = tmp_path / "px"
    assert main(["build", str(manifest), "-o", str(out), "--no-progress",
                 "--param", "min_copies=3"]) == 0
    page = tmp_path / "w.html"
    assert main(["generate", str(out), "moves.wave", "--repeat", "1", "-o",
                 str(tmp_path / "w.bvh"), "--view", str(page)]) == 0
    text = page.read_text()
    data = json.loads(re.search(r'<script type="application/json" class="data">(.*?)</script>',
                                text, re.S).group(1))
    # the panel's title is the file's name, short enough to sit beside the other panel
    assert [p["label"] for p in data["panels"]] == ["performance (wave_1.bvh)", "generated"]
    # the whole path is in the page's title (the browser's tab)
    first = manifest.parent / "wave_1.bvh"
    title = re.search(r"<title>(.*?)</title>", text).group(1)
    assert title == f"{first} beside generated:moves.wave"
    assert capsys.readouterr().out.splitlines()[-1] == \
        f"{page}: performance (wave_1.bvh) beside generated"


def test_generate_makes_as_many_channels_at_once_as_there_are_cores(manifest, tmp_path,
                                                                   monkeypatch):
    """The command's default --workers is the number of cores, at most 4 (as draw's);
    the motion is the same whatever the number
    (test_generate_in_threads_makes_the_same_motion)."""
    import praxicon.generation as generation
    from psgs._foundation.engines import usable_cores

    out = tmp_path / "px"
    assert main(["build", str(manifest), "-o", str(out), "--no-progress"]) == 0
    asked = []

    def fake(*args, workers=1, **kwargs):
        asked.append(workers)
        raise ValueError("stop")

    monkeypatch.setattr(generation, "generate", fake)
    for extra, wanted in (([], min(4, usable_cores())), (["--workers", "3"], 3)):
        assert main(["generate", str(out), "moves.wave", "-o", str(tmp_path / "w.bvh"),
                     *extra]) == 2
        assert asked.pop() == wanted


def test_the_build_says_when_it_describes_the_actions(manifest, tmp_path, capsys):
    """After the progress bar, learning the descriptions is announced (a silent step of
    seconds on a large praxicon); not again when a resumed build keeps them."""
    out = tmp_path / "px"
    assert main(["build", str(manifest), "-o", str(out)]) == 0
    assert "praxicon: describing the 2 learnt action(s) for recognise and parse ..." \
        in capsys.readouterr().err
    assert main(["build", str(manifest), "-o", str(out)]) == 0
    assert "describing" not in capsys.readouterr().err
    assert main(["build", str(manifest), "-o", str(tmp_path / "quiet"), "--no-progress"]) == 0
    assert "describing" not in capsys.readouterr().err


def test_build_takes_none_for_a_parameter_whose_default_is_none(manifest, tmp_path, capsys):
    # as psgs induce does: max_seconds=none is no time bound (it was refused as 'must be a
    # number or None, not 'none''), recorded as the JSON null it is
    out = tmp_path / "px"
    assert main(["build", str(manifest), "-o", str(out), "--no-progress",
                 "--param", "min_copies=3", "--param", "max_seconds=None"]) == 0
    index = json.loads((out / "index.json").read_text())
    assert index["settings"]["params"] == {"min_copies": 3, "max_seconds": None}
    assert "2 learnt" in capsys.readouterr().out
