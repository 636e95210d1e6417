"""What ``psgs praxicon build|draw|generate`` can tell from their arguments is said before any
work: one line, status 2 (docs/cli.md), and no folder or file made."""

from __future__ import annotations

from dataclasses import replace

import pytest

from fuzz_support import praxicon_seed
from praxicon import dump, read_dataset
from praxicon.datasets import DatasetError
from praxicon.records import ActionRecord, Praxicon, Settings
from psgs.cli import main


def _run(argv, capsys):
    status = main(["praxicon", *map(str, argv)])
    return status, capsys.readouterr()


def _one_line(captured) -> str:
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("psgs: error: "), captured.err
    return lines[0][len("psgs: error: "):]


@pytest.mark.parametrize("name, text, why", [
    ("e.csv", "action,file\n", "no row under the header: one per performance"),
    ("e.csv", "action,file,start,stop\n\n", "no row under the header: one per performance"),
    ("e.toml", "", "no [[performance]] table"),
])
def test_a_manifest_without_actions_is_refused_before_the_folder(tmp_path, capsys, name, text,
                                                                 why):
    manifest = tmp_path / name
    manifest.write_text(text)
    out = tmp_path / "px"
    status, captured = _run(["build", manifest, "-o", out, "--no-progress"], capsys)
    assert status == 2
    assert _one_line(captured) == f"{manifest}: no actions in it ({why})"
    assert not out.exists() and captured.out == ""
    with pytest.raises(DatasetError, match="no actions in it"):
        read_dataset(manifest)


@pytest.mark.parametrize("value, why", [
    ("smoothing=-1", "smoothing must be a non-negative number, not -1"),
    ("smoothing=nan", "smoothing must be a non-negative number, not nan"),
    ("unwrap=maybe", "unwrap must be a number, not 'maybe'"),
    ("min_range=true", "min_range must be a number, not True"),
])
def test_a_bad_segment_value_is_refused_before_any_action(tmp_path, capsys, value, why):
    manifest = tmp_path / "m.csv"
    manifest.write_text("action,file\nwave,a.bvh\nwave,b.bvh\n")
    out = tmp_path / "px"
    status, captured = _run(["build", manifest, "-o", out, "--no-progress", "--segment", value],
                            capsys)
    assert status == 2 and _one_line(captured) == f"--segment {why}"
    assert not out.exists()


def test_an_output_that_is_a_file_is_named_as_one(tmp_path, capsys):
    afile = tmp_path / "afile"
    afile.write_text("mine")
    manifest = tmp_path / "m.csv"
    manifest.write_text("action,file\nwave,a.bvh\n")
    status, captured = _run(["build", manifest, "-o", afile], capsys)
    assert status == 2 and _one_line(captured) == f"{afile}: a file, not a praxicon folder"
    dump(praxicon_seed(), tmp_path / "px")
    status, captured = _run(["draw", tmp_path / "px", "-o", afile], capsys)
    assert status == 2 and _one_line(captured) == f"{afile}: a file, not a folder for the pictures"
    assert afile.read_text() == "mine"


def test_draw_names_the_folder_without_a_learnt_action(tmp_path, capsys):
    folder = tmp_path / "px"
    dump(Praxicon((ActionRecord("m.a", "m", "a", reason="no takes"),), Settings.make()), folder)
    status, captured = _run(["draw", folder, "-o", tmp_path / "img"], capsys)
    assert status == 2 and _one_line(captured) == f"{folder}: no learnt action to draw"
    assert not (tmp_path / "img").exists()


def test_one_picture_is_one_picture(tmp_path, capsys):
    # a learnt action without actuators has no morphemes or system to draw: the matrix alone
    seed = praxicon_seed().actions[1]
    alone = replace(seed, actuators=(), joints=(), system=None, component_names=())
    folder = tmp_path / "px"
    dump(Praxicon((alone,), Settings.make()), folder)
    status, captured = _run(["draw", folder, "-o", tmp_path / "img"], capsys)
    assert status == 0 and captured.out.splitlines() == [str(tmp_path / "img" / "actuators.svg")]
    assert f"drew 1 picture into {tmp_path / 'img'}" in captured.err


def test_view_of_an_action_on_no_skeleton_is_refused_before_any_work(tmp_path, capsys,
                                                                    monkeypatch):
    import praxicon.generation

    amc = tmp_path / "takes" / "13_29.amc"  # no ASF beside it: angles without a skeleton
    amc.parent.mkdir()
    amc.write_text(":FULLY-SPECIFIED\n:DEGREES\n1\nroot 0 0 0 0 0 0\n")
    seed = praxicon_seed()
    folder = tmp_path / "px"
    dump(replace(seed, actions=tuple(replace(a, skeleton_source=str(amc)) if a.learnt else a
                                     for a in seed.actions)), folder)

    def no_work(*args, **kwargs):
        raise AssertionError("generated before the player's skeleton was checked")

    monkeypatch.setattr(praxicon.generation, "generate", no_work)
    bvh, page = tmp_path / "gen.bvh", tmp_path / "gen.html"
    status, captured = _run(["generate", folder, "moves.step", "--repeat", "4", "-o", bvh,
                             "--view", page], capsys)
    assert status == 2
    assert _one_line(captured) == (f"{page}: no skeleton to draw: 'moves.step' is on the "
                                   f"skeleton of {amc}, an AMC file without its ASF (generate "
                                   f"it without --view)")
    assert not bvh.exists() and not page.exists()


def test_an_error_while_drawing_is_on_a_line_of_its_own(tmp_path, capsys, monkeypatch):
    # an error after the progress line started ("drawing 3/9: ...", no newline) was printed
    # at that line's end
    import praxicon.pictures

    def fails_midway(praxicon, output, *, progress, **kwargs):
        progress(0, 9, "actuators")
        raise ValueError("bad.psgs:1:1: no system")

    monkeypatch.setattr(praxicon.pictures, "draw_praxicon", fails_midway)
    dump(praxicon_seed(), tmp_path / "px")
    status, captured = _run(["draw", tmp_path / "px", "-o", tmp_path / "img"], capsys)
    assert status == 2
    assert captured.err.splitlines()[-1] == "psgs: error: bad.psgs:1:1: no system"
