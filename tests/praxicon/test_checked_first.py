"""What ``psgs praxicon build|draw|generate`` can tell from their arguments is said before any
work: one line, status 2 (docs/cli.md), and no folder or file made."""

from __future__ import annotations

from dataclasses import replace

from fuzz_support import praxicon_seed
from praxicon import dump
from psgs.cli import main


def _run(argv, capsys):
    status = main(["praxicon", *map(str, argv)])
    return status, capsys.readouterr()


def _one_line(captured) -> str:
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("psgs: error: "), captured.err
    return lines[0][len("psgs: error: "):]


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
