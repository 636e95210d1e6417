"""``generate --style``'s errors: performances of the style that cannot be read are said so
(not "no such style" beside a list naming it), and an action built per style names its own."""

from __future__ import annotations

from fuzz_support import praxicon_seed
from praxicon import dump
from praxicon.body_motion import missing_style
from praxicon.records import ActionRecord, PerformanceRecord
from psgs.cli import main


def test_unreadable_performances_of_the_style_are_named(tmp_path, monkeypatch, capsys):
    # the seed's takes are recorded as relative paths (step_0.bvh, step_1.bvh), which do not
    # exist where the command runs: as a praxicon generated from another directory
    folder = tmp_path / "px"
    dump(praxicon_seed(), folder)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    out = tmp_path / "x.bvh"
    assert main(["praxicon", "generate", str(folder), "moves.step", "--style", "step",
                 "-o", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["psgs: error: action 'moves.step': its performances of style 'step' cannot "
                   "be read (step_0.bvh: no such file; a relative path is relative to the "
                   "folder build ran in: run from there, or build from absolute paths)"]
    assert not out.exists()


def test_an_absolute_path_is_not_said_to_be_relative(tmp_path):
    gone = tmp_path / "data" / "dataset-1_walk_sad_001.bvh"
    record = ActionRecord("d.walk", "d", "walk", performances=(
        PerformanceRecord(str(gone)), PerformanceRecord(str(tmp_path / "dataset-1_walk_x_1.bvh"))))
    assert str(missing_style(record, "sad")) == (f"action 'd.walk': its performances of style "
                                                 f"'sad' cannot be read ({gone}: no such file)")


def test_an_action_of_one_style_names_it():
    files = [f"data/dataset-2_walk_normal_00{i}.bvh" for i in (1, 2, 3)]
    record = ActionRecord("b.walk.normal", "b", "walk", "normal",
                          performances=tuple(PerformanceRecord(f) for f in files))
    assert str(missing_style(record, "sad")) == ("action 'b.walk.normal' has no performance of "
                                                 "style 'sad' (styles: normal)")


def test_why_a_style_is_missing_is_said_from_the_files_read_once(tmp_path, monkeypatch):
    """Generation has read every performance when it finds no performance of the style: why
    its files could not be read is what that reading said, each file read once."""
    import kinetology
    import pytest
    from praxicon import generate

    folder = tmp_path / "px"
    dump(praxicon_seed(), folder)
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    (elsewhere / "step_0.bvh").write_text("HIERARCHY\nROOT Hips\n{ OFFSET 0 0 0\n")  # damaged
    reads: list[str] = []
    real = kinetology.read
    monkeypatch.setattr(kinetology, "read", lambda path, *a, **k: reads.append(str(path))
                        or real(path, *a, **k))
    with pytest.raises(ValueError) as error:
        generate(folder, "moves.step", style="step")
    assert str(error.value) == ("action 'moves.step': its performances of style 'step' cannot "
                                "be read (step_0.bvh:3:15: file ends where '}' was expected)")
    assert sorted(reads) == ["step_0.bvh", "step_1.bvh"]


def test_a_style_read_but_too_short_is_said_without_reading_it_again(tmp_path, monkeypatch):
    import kinetology

    record = ActionRecord("d.walk", "d", "walk", performances=(
        PerformanceRecord(str(tmp_path / "d_walk_sad_1.bvh")),
        PerformanceRecord(str(tmp_path / "d_walk_x_1.bvh"))))
    monkeypatch.setattr(kinetology, "read", None)  # nothing is read
    assert str(missing_style(record, "sad", {})) == (
        f"action 'd.walk': its performances of style 'sad' cannot be read "
        f"({tmp_path / 'd_walk_sad_1.bvh'}: too short, or not on the channels of the other "
        f"performances)")
