"""``psgs praxicon recognise|parse``: output, exit statuses, one-line errors; and a
real-data check (marked ``mocap``)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from praxicon.recognition_cli import register_recognise
from praxicon_fixtures import SHARED, needs_mocap


def _register(subparsers) -> None:
    parser = subparsers.add_parser("praxicon")
    register_recognise(parser.add_subparsers(dest="praxicon_command", required=True))


def run(argv):
    from psgs.cli import main

    return main(["praxicon", *argv], commands={"praxicon": _register})


def _take(seed: int, arm: bool, leg: bool, seconds: float = 5.0, rate: float = 30.0):
    from kinetology import Motion
    from kinetology.bvh_writer import star_skeleton

    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * rate)) / rate
    phase = 2 * np.pi * t / (1 + 0.05 * (seed % 3))  # three tempos, learnt and new alike
    channels = ("hips.rz", "arm.rx", "arm.rz", "leg.rx", "head.ry")
    values = np.column_stack([
        0.3 * rng.standard_normal(t.size),
        (40 * np.sin(phase) if arm else 0 * t) + 0.3 * rng.standard_normal(t.size),
        (25 * np.sin(phase + 0.7) if arm else 0 * t) + 0.3 * rng.standard_normal(t.size),
        (30 * np.sin(phase + 2) if leg else 0 * t) + 0.3 * rng.standard_normal(t.size),
        0.3 * rng.standard_normal(t.size)])
    return Motion(values, channels, rate, star_skeleton(channels), f"take{seed}")


@pytest.fixture(scope="module")
def px(tmp_path_factory) -> Path:
    """A praxicon folder built from a manifest of two actions' BVH takes (its descriptions
    learnt by the build), and two new takes beside it."""
    from kinetology import write_bvh
    from praxicon import build, read_dataset

    folder = tmp_path_factory.mktemp("px")
    rows = ["action,file"]
    for name, arm, leg, seeds in (("wave", True, False, (1, 2, 3)),
                                  ("step", False, True, (4, 5, 6))):
        for seed in seeds:
            path = folder / f"{name}{seed}.bvh"
            write_bvh(_take(seed, arm, leg), path)
            rows.append(f"{name},{path}")
    (folder / "m.csv").write_text("\n".join(rows) + "\n")
    result = build(read_dataset(folder / "m.csv"), folder, progress=False, log=lambda s: None)
    assert result.praxicon.descriptions is not None
    assert result.praxicon.descriptions.names == ("m.step", "m.wave")
    for seed, arm, leg in ((7, True, False), (8, False, True)):
        write_bvh(_take(seed, arm, leg), folder / f"new{seed}.bvh")
    return folder


def test_recognise_prints_one_line_per_file(px, capsys):
    capsys.readouterr()
    assert run(["recognise", str(px), str(px / "new7.bvh"), str(px / "new8.bvh")]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert len(lines) == 2
    assert lines[0].startswith(f"{px / 'new7.bvh'}: m.wave ") and "runner-up m.step" in lines[0]
    assert lines[1].startswith(f"{px / 'new8.bvh'}: m.step ")


def test_recognise_explain(px, capsys):
    capsys.readouterr()
    assert run(["recognise", str(px), str(px / "new7.bvh"), "--explain"]) == 0
    out = capsys.readouterr().out
    assert "matched:" in out and "m.step: p=" in out


def test_recognise_plot_draws_the_explanation(px, tmp_path, capsys):
    pytest.importorskip("matplotlib")
    picture = tmp_path / "why.png"
    capsys.readouterr()
    assert run(["recognise", str(px), str(px / "new7.bvh"), "--plot", str(picture)]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == str(picture)
    assert picture.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    err = _error(capsys, ["recognise", str(px), str(px / "new7.bvh"), str(px / "new8.bvh"),
                          "--plot", str(picture)])
    assert "one FILE" in err


def test_parse_prints_the_timeline(px, capsys):
    from kinetology import Motion, read, write_bvh

    a, b = read(px / "new7.bvh"), read(px / "new8.bvh")
    joined = Motion(np.concatenate([a.values, b.values]), a.channels, a.frame_rate, a.skeleton)
    write_bvh(joined, px / "joined.bvh")
    capsys.readouterr()
    assert run(["parse", str(px), str(px / "joined.bvh")]) == 0
    rows = [line.split() for line in capsys.readouterr().out.splitlines()]
    assert [r[2] for r in rows if r[2] != "-"] == ["m.wave", "m.step"]
    assert float(rows[0][0]) == 0.0 and float(rows[-1][1]) == pytest.approx(10.0, abs=0.05)


def _error(capsys, argv) -> str:
    capsys.readouterr()
    assert run(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("psgs: error: ") and "\n" not in err and "Traceback" not in err
    return err


def test_bad_input_is_one_line_exit_2(px, tmp_path, capsys):
    from kinetology import Motion, write_bvh

    assert "no such praxicon folder" in _error(capsys, ["recognise", str(tmp_path / "none"),
                                                        str(px / "new7.bvh")])
    assert "no index.json" in _error(capsys, ["recognise", str(tmp_path), str(px / "new7.bvh")])
    assert "no such file" in _error(capsys, ["recognise", str(px), str(tmp_path / "x.bvh")])
    (tmp_path / "folder.bvh").mkdir()  # unreadable as a file: said as every command says it
    assert f"{tmp_path / 'folder.bvh'}: Is a directory" in _error(
        capsys, ["recognise", str(px), str(tmp_path / "folder.bvh")])
    one = _take(9, True, False)
    write_bvh(Motion(one.values[:1], one.channels, 30.0, one.skeleton), tmp_path / "one.bvh")
    assert "1 frame;" in _error(capsys, ["recognise", str(px), str(tmp_path / "one.bvh")])
    old = _copy(px, tmp_path / "old")
    data = json.loads((px / "descriptions.json").read_text())
    data["version"] = 0
    (old / "descriptions.json").write_text(json.dumps(data))
    assert "psgs praxicon build" in _error(capsys, ["recognise", str(old),
                                                    str(px / "new7.bvh")])
    bare = _copy(px, tmp_path / "bare")
    (bare / "descriptions.json").unlink()
    assert "psgs praxicon build" in _error(capsys, ["parse", str(bare),
                                                    str(px / "new7.bvh")])


def _copy(px: Path, to: Path) -> Path:
    """The praxicon folder's files (not the takes beside them) copied to ``to``."""
    import shutil

    shutil.copytree(px, to, ignore=shutil.ignore_patterns("*.bvh", "*.png"))
    return to


def test_missing_joints_named_on_stderr(px, tmp_path, capsys):
    from kinetology import read, write_bvh

    full = read(px / "new7.bvh")
    keep = [c for c in full.channels if not c.startswith("leg.")]
    write_bvh(full.select(keep), tmp_path / "noleg.bvh")
    capsys.readouterr()
    assert run(["recognise", str(px), str(tmp_path / "noleg.bvh")]) == 0
    captured = capsys.readouterr()
    assert ": m.wave " in captured.out and "lacks: leg" in captured.err


@pytest.mark.mocap
@needs_mocap()
def test_real_turns_told_from_walks_by_their_drift():
    """Bandai dataset 2, normal style: walk and the two turns learnt from takes 1-3, takes 4-5
    ranked first by their own action; the turns' heading drift is what tells them apart.

    Learnt from three takes an action, the feature-group test answers some known takes "none
    of these" (the right turn's take 4 turns back by 190 degrees at its end); a take it does
    answer is never given another action."""
    import kinetology
    from praxicon.description import describe
    from praxicon.recognition import recognise_many

    data = SHARED / "bandai-namco-2-subset" / "data"
    contents = ("walk", "walk-turn-left", "walk-turn-right")
    takes = {c: [kinetology.read(data / f"dataset-2_{c}_normal_00{k}.bvh") for k in (1, 2, 3)]
             for c in contents}
    px = describe(takes)
    tests = [(c, kinetology.read(data / f"dataset-2_{c}_normal_00{k}.bvh"))
             for c in contents for k in (4, 5)]
    found = recognise_many(px, [m for _, m in tests])
    assert [r.ranking[0][0] for r in found] == [c for c, _ in tests]
    assert all(r.action in (None, c) for r, (c, _) in zip(found, tests))
    assert [r.action for r in found][:2] == ["walk", "walk"]
    left = px.actions[px.names.index("walk-turn-left")]
    right = px.actions[px.names.index("walk-turn-right")]
    drift = [i for i, f in enumerate(left.features) if f == "Hips.turnx:drift"]
    assert drift and left.mean[drift[0]] * right.mean[drift[0]] < 0  # opposite headings


def test_folder_round_trip_equals_in_memory(px):
    """build -> descriptions.json -> load gives the very descriptions learnt in memory from
    the same takes, and the same answers from the folder, the loaded value and memory."""
    import kinetology
    from praxicon import load
    from praxicon.description import describe
    from praxicon.store import read_descriptions
    from praxicon.parsing import describe_windows
    from praxicon.recognition import recognise_many

    loaded = load(px)
    takes = {a.name: [kinetology.read(p.file) for p in a.performances if p.used]
             for a in loaded.actions if a.learnt}
    memory = describe(takes)
    assert read_descriptions(px) == memory == loaded.descriptions
    assert read_descriptions(px, windows=True) == describe_windows(takes)
    assert loaded.window_descriptions == describe_windows(takes)
    new = [kinetology.read(px / f"new{s}.bvh") for s in (7, 8)]
    assert recognise_many(px, new) == recognise_many(loaded, new) == recognise_many(memory, new)


def test_resumed_build_keeps_its_descriptions(px):
    """A build that learns no action again reuses the descriptions (same file, same value)."""
    from praxicon import build, load, read_dataset

    before = (px / "descriptions.json").read_bytes()
    result = build(read_dataset(px / "m.csv"), px, progress=False, log=lambda s: None)
    assert result.learnt == () and (px / "descriptions.json").read_bytes() == before
    assert result.praxicon == load(px)


def test_plot_without_matplotlib_names_the_extra_before_any_answer(px, monkeypatch, capsys):
    # None in sys.modules makes `import matplotlib` fail, as after a plain `pip install .`
    import sys

    monkeypatch.setitem(sys.modules, "matplotlib", None)
    for argv in (["recognise", str(px), str(px / "new7.bvh"), "--plot", "x.png"],
                 ["parse", str(px), str(px / "new7.bvh"), "--plot", "x.png"]):
        err = _error(capsys, argv)
        assert "pip install 'psgs[praxicon]'" in err
    capsys.readouterr()
    assert run(["recognise", str(px), str(px / "new7.bvh"), "--plot", "x.png"]) == 2
    assert capsys.readouterr().out == ""  # no answer printed before the error


def test_joints_lacked_by_numbered_channels_are_said_to_be_an_amc_without_its_asf():
    # an AMC file read without its ASF names its channels bone.1, bone.2: its joints are
    # there, under names no action was learnt with, and the line says what to do
    import numpy as np

    from kinetology import Motion
    from praxicon.recognition_cli import _lacking

    values = np.zeros((3, 2))
    numbered = Motion(values, ("root.rx", "lowerback.1"), 120.0, source="copy.amc")
    named = Motion(values, ("root.rx", "lowerback.rx"), 120.0, source="walk.amc")
    assert _lacking("copy.amc", numbered, ("lowerback",)).endswith(
        "(its channels are numbered, not named: an AMC file read without its ASF; put the "
        ".asf file beside it)")
    assert _lacking("walk.amc", named, ("head",)) == \
        "walk.amc: recognised without the joints it lacks: head"
