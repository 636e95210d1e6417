"""A record whose system text does not parse: ``load`` leaves the systems unparsed, so verify,
repair, resume, draw and generate each name the record (not the intact ``.psgs`` copy beside
it), and repair writes nothing from it."""

from __future__ import annotations

import json

import pytest

from fuzz_support import praxicon_seed
from praxicon import dump, repair, verify
from praxicon.pictures import draw_praxicon
from praxicon.records import PraxiconError
from praxicon.store import read_records


@pytest.fixture
def damaged(tmp_path):
    """The seed praxicon with the system of ``moves.step``'s record replaced by garbage."""
    folder = tmp_path / "px"
    dump(praxicon_seed(), folder)
    path = folder / "records" / "moves.step.json"
    stored = json.loads(path.read_text())
    stored["record"]["system"] = "garbage"
    path.write_text(json.dumps(stored))
    return folder


def _why(folder) -> str:
    return f"{folder / 'records' / 'moves.step.json'}: 'system' does not parse (line 1, column 1"


def test_verify_names_the_record_not_its_intact_system_file(damaged):
    found = verify(damaged)
    (problem,) = found.problems
    assert problem.startswith(_why(damaged))
    assert problem.endswith("the record is damaged ('psgs praxicon build DATASET... -o FOLDER' "
                            "into the folder learns the action again)")
    assert found.repairable == 0  # nothing --repair can mend: only learning it again


def test_repair_writes_nothing_from_a_damaged_record(damaged):
    psgs_file = damaged / "moves.step.psgs"
    before = {p: p.read_bytes() for p in damaged.rglob("*") if p.is_file()}
    with pytest.raises(PraxiconError, match="nothing repaired") as error:
        repair(damaged)
    assert str(error.value).startswith(_why(damaged))
    assert {p: p.read_bytes() for p in damaged.rglob("*") if p.is_file()} == before
    assert psgs_file.read_text().startswith("psgs pal")


def test_the_command_says_whole_no_more(damaged, capsys):
    from psgs.cli import main

    assert main(["praxicon", "verify", str(damaged)]) == 1
    out, err = capsys.readouterr()
    assert out.startswith(_why(damaged)) and err.endswith(": 1 problem(s)\n")
    assert main(["praxicon", "verify", "--repair", str(damaged)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"psgs: error: {_why(damaged)}") and "repaired; whole" not in err


def test_resume_learns_a_damaged_system_again(damaged):
    found, untrusted = read_records(damaged)
    assert "moves.step" not in found and untrusted["moves.step"].startswith(_why(damaged))
    assert "moves.wave" in found


def test_draw_names_the_record_before_any_picture(damaged, tmp_path):
    with pytest.raises(ValueError) as error:
        draw_praxicon(damaged, tmp_path / "img", workers=1)
    assert str(error.value).startswith(_why(damaged))
    assert not (tmp_path / "img").exists()


def test_generate_names_the_record(damaged, tmp_path, capsys):
    from psgs.cli import main

    out = tmp_path / "x.bvh"
    assert main(["praxicon", "generate", str(damaged), "moves.step", "-o", str(out)]) == 2
    assert capsys.readouterr().err.startswith(f"psgs: error: {_why(damaged)}")
    assert not out.exists()
    from praxicon import generate, load

    with pytest.raises(ValueError, match=r"^the record of 'moves.step': 'system' does not parse"):
        generate(load(damaged, descriptions=False), "moves.step")


def test_a_build_into_the_folder_learns_the_damaged_action_again(manifest, tmp_path):
    from praxicon import build, load, read_dataset

    folder = tmp_path / "px"
    build(read_dataset(manifest), folder, progress=False, log=lambda line: None)
    intact = (folder / "moves.wave.psgs").read_bytes()
    path = folder / "records" / "moves.wave.json"
    stored = json.loads(path.read_text())
    stored["record"]["system"] = "garbage"
    path.write_text(json.dumps(stored))
    said = []
    result = build(read_dataset(manifest), folder, progress=False, log=said.append)
    assert result.learnt == ("moves.wave",)  # the others' records are trusted as before
    assert f"{path}: 'system' does not parse (line 1, column 1: expected a first line 'psgs " \
           f"NAME' or 'pcgs NAME'): learnt again" in said
    assert load(folder)["moves.wave"].system.encode() == intact
    assert verify(folder).intact
