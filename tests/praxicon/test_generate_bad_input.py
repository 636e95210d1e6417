"""``psgs praxicon generate`` on bad input, one line and status 2 each: a performance it reads
that cannot be read (it was left out without a word, the motion made from the others or from
the mean pose), a record that failed with no reason stored (``not learnt: None``), and a
``--style`` word every performance's file name holds (it picked them all)."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import pytest

from fuzz_support import praxicon_seed
from praxicon import build, dump, load, read_dataset
from praxicon.body_motion import RELATIVE
from praxicon.generation import generate, generate_motion
from praxicon.records import ActionRecord
from praxicon_fixtures import refused, take


@pytest.fixture
def built(manifest, tmp_path) -> Path:
    """The manifest fixture's praxicon: moves.wave learnt from wave_1, wave_2 and wave_3."""
    out = tmp_path / "px"
    build(read_dataset(manifest), out, progress=False, log=lambda s: None)
    return out


def _no_such(file: str) -> str:
    return f"{file}: no such file" + ("" if Path(file).is_absolute() else f"; {RELATIVE}")


def _with(px, name, **changes):
    """The praxicon with one action's record changed."""
    return replace(px, actions=tuple(replace(a, **changes) if a.name == name else a
                                     for a in px.actions))


def test_a_performance_that_cannot_be_read_is_named_not_left_out(built, tmp_path, capsys):
    record = load(built)["moves.wave"]
    files = [record.performances[i].file for i in record.learnt_from]
    assert len(files) == 3 and record.skeleton_source == files[0]
    moved = Path(files[1])
    moved.rename(moved.with_name("moved-" + moved.name))  # not the skeleton's take
    out = tmp_path / "w.bvh"
    argv = ["generate", str(built), "moves.wave", "--repeat", "1", "-o", str(out)]
    assert refused(capsys, argv) == (f"action 'moves.wave': 1 of the 3 performances it was "
                                     f"learnt from cannot be read ({_no_such(files[1])})")
    # with a style too: the style's scales are read against every performance
    assert refused(capsys, argv + ["--style", "1"]).startswith("action 'moves.wave': 1 of the 3")
    assert not out.exists()
    # a damaged one: kinetology's reason, which names the file (once)
    Path(files[2]).write_text("not a motion\n")
    line = refused(capsys, argv)
    assert line.startswith(f"action 'moves.wave': 2 of the 3 performances it was learnt from "
                           f"cannot be read ({files[1]}: no such file")
    moved.with_name("moved-" + moved.name).rename(moved)
    line = refused(capsys, argv)
    assert line.startswith(f"action 'moves.wave': 1 of the 3 performances it was learnt from "
                           f"cannot be read ({files[2]}:") and line.count(files[2]) == 1
    assert "not a motion" in line or "HIERARCHY" in line, line


def test_none_of_the_performances_read_is_an_error_not_the_mean_pose(built, tmp_path):
    # the skeleton's take reads, the performances learnt from do not: every channel no
    # morpheme drives was the mean pose and the root stood still, without a word
    px = load(built)
    gone = tuple(replace(p, file=str(tmp_path / "gone" / Path(p.file).name))
                 for p in px["moves.wave"].performances)
    moved = _with(px, "moves.wave", performances=gone)
    with pytest.raises(ValueError, match=r"^action 'moves\.wave': none of the 3 performances it "
                                         r"was learnt from can be read \(.*/gone/wave_1\.bvh: "
                                         r"no such file\)$"):
        generate(moved, "moves.wave", repeat=1)
    # an action without a grammar (its performances' course) says the same
    course = _with(px, "moves.wave", performances=gone[:1] + px["moves.wave"].performances[1:],
                   actuators=())
    with pytest.raises(ValueError, match=r"^action 'moves\.wave': 1 of the 3 performances it "
                                         r"was learnt from cannot be read \(.*/gone/wave_1"):
        generate(course, "moves.wave")
    # on good input generation is as it was: the performances are read once each
    assert generate(px, "moves.wave", repeat=1).motion.frames > 0


def test_a_record_that_failed_without_a_reason_says_so(tmp_path, capsys):
    seed = praxicon_seed()
    dump(_with(seed, "moves.bow", reason=None), tmp_path / "px")
    out = tmp_path / "b.bvh"
    assert refused(capsys, ["generate", str(tmp_path / "px"), "moves.bow", "-o", str(out)]) == \
        "action 'moves.bow' was not learnt (no reason recorded)"
    assert not out.exists()
    with pytest.raises(ValueError, match=r"^action 'x' was not learnt \(no reason recorded\)$"):
        generate_motion(ActionRecord("x", "d", "x", reason=" "), 1)
    # a reason stored is given as it was
    with pytest.raises(ValueError, match=r"^action 'moves\.bow' was not learnt: 1 usable "
                                         r"performance \(at least 2 needed\)$"):
        generate_motion(seed["moves.bow"], 1)


def test_a_style_every_performance_has_is_refused(built, tmp_path, capsys):
    # wave_1.bvh, wave_2.bvh, wave_3.bvh: "wave" picks them all (a take's number picks it)
    out = tmp_path / "w.bvh"
    assert refused(capsys, ["generate", str(built), "moves.wave", "--style", "wave",
                            "-o", str(out)]) == (
        "action 'moves.wave': style 'wave' does not tell its performances apart (the file "
        "names of all 3 of its performances hold it; it has no styles)")
    assert not out.exists()


def test_an_action_built_per_style_keeps_its_own_style(tmp_path):
    from kinetology import write_bvh

    rows = ["action,file,style"]
    for seed in (1, 2, 3):
        write_bvh(take(seed), tmp_path / f"wave_normal_{seed}.bvh")
        rows.append(f"wave,wave_normal_{seed}.bvh,normal")
    (tmp_path / "m.csv").write_text("\n".join(rows) + "\n")
    build(read_dataset(tmp_path / "m.csv"), tmp_path / "px", progress=False, log=lambda s: None)
    px = load(tmp_path / "px")
    (name,) = px.names
    assert px[name].style == "normal"
    # every take holds "normal", and it is the action's own style: generated as asked
    own = generate(px, name, repeat=1, style="normal").motion
    assert own.frames == generate(px, name, repeat=1).motion.frames
    with pytest.raises(ValueError, match=rf"^action '{name}': style 'wave' does not tell its "
                                         rf"performances apart \(the file names of all 3 of its "
                                         rf"performances hold it; styles: normal\)$"):
        generate(px, name, repeat=1, style="wave")


def test_the_one_performance_an_action_was_learnt_from_is_named_as_one(built, tmp_path):
    px = load(built)
    gone = replace(px["moves.wave"].performances[0],
                   file=str(tmp_path / "gone" / "wave_1.bvh"))
    alone = _with(px, "moves.wave", performances=(gone,), learnt_from=(0,))
    with pytest.raises(ValueError, match=r"^action 'moves\.wave': the one performance it was "
                                         r"learnt from cannot be read \(.*/gone/wave_1\.bvh"):
        generate(alone, "moves.wave", repeat=1)


def test_a_failed_record_without_a_reason_says_so_in_its_repr():
    assert repr(ActionRecord("m.a", "m", "a")) == \
        "<ActionRecord 'm.a': failed (no reason recorded), 0 performances>"
