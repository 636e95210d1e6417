"""praxicon.verify / repair and ``psgs praxicon verify``: every file of a folder against what
its records give, checked against mutated folders."""

from __future__ import annotations

import shutil

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fuzz_support import apply, mutations_strategy, praxicon_seed
from praxicon import dump, load, repair, verify
from praxicon.records import PraxiconError

#: Files no reader of the folder reads back: written from the records alone.
DERIVED = ("actuators.csv", "shared.json", "moves.step.psgs", "moves.wave.psgs")
#: Files ``load`` reads (and checks).
READ = ("index.json", "records/moves.bow.json", "records/moves.step.json",
        "records/moves.wave.json", "descriptions.json")


@pytest.fixture(scope="module")
def seed_folder(tmp_path_factory):
    folder = tmp_path_factory.mktemp("seed") / "px"
    dump(praxicon_seed(), folder)
    return folder


def _copy(seed_folder, tmp_path):
    folder = tmp_path / "px"
    shutil.rmtree(folder, ignore_errors=True)
    shutil.copytree(seed_folder, folder)
    return folder


def _files(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes()
            for p in folder.rglob("*") if p.is_file()}


def test_the_seed_lists_every_file_it_writes(seed_folder):
    assert set(_files(seed_folder)) == set(DERIVED) | set(READ)


def test_a_whole_folder_is_intact_and_counts_its_files(seed_folder):
    found = verify(seed_folder)
    assert found.intact and found.problems == ()
    assert found.checked == len(DERIVED) + len(READ)
    (seed_folder / "timings.json").write_text('{"moves.step": 1.5, "moves.wave": 0}\n')
    try:
        assert verify(seed_folder).checked == len(DERIVED) + len(READ) + 1
        assert verify(seed_folder).intact
    finally:
        (seed_folder / "timings.json").unlink()


@settings(max_examples=60, deadline=None)
@given(name=st.sampled_from(DERIVED), mutations=mutations_strategy())
def test_a_damaged_derived_file_is_named_alone_and_repaired(seed_folder, tmp_path_factory,
                                                            name, mutations):
    folder = _copy(seed_folder, tmp_path_factory.getbasetemp())
    before = _files(folder)
    data = apply(before[name], mutations)
    (folder / name).write_bytes(data)
    found = verify(folder)
    if data == before[name]:
        assert found.intact
        return
    assert len(found.problems) == 1
    assert found.problems[0].startswith(f"{folder / name}: ")
    assert repair(folder).intact
    assert _files(folder) == before


@settings(max_examples=60, deadline=None)
@given(name=st.sampled_from(READ), mutations=mutations_strategy())
def test_a_damaged_file_load_reads_is_refused_reported_or_another_praxicon(
        seed_folder, tmp_path_factory, name, mutations):
    """No damage passes unseen: load refuses it, verify reports a file, or what the folder
    holds is another valid praxicon (a record changed into another record)."""
    folder = _copy(seed_folder, tmp_path_factory.getbasetemp())
    original = load(folder)
    data = apply(_files(folder)[name], mutations)
    (folder / name).write_bytes(data)
    try:
        found = verify(folder)
    except PraxiconError:
        return
    assert found.problems or load(folder) != original or data == _files(seed_folder)[name]


@pytest.mark.parametrize("name", DERIVED)
def test_a_missing_file_is_named(seed_folder, tmp_path, name):
    folder = _copy(seed_folder, tmp_path)
    (folder / name).unlink()
    assert verify(folder).problems == (f"{folder / name}: missing",)


def test_a_difference_names_its_line_and_column(seed_folder, tmp_path):
    folder = _copy(seed_folder, tmp_path)
    path = folder / "actuators.csv"
    lines = path.read_text().split("\n")
    lines[1] = lines[1][:-1] + "7"
    path.write_text("\n".join(lines))
    (problem,) = verify(folder).problems
    column = len(lines[1])
    assert f"actuators.csv: differs from what the records give (line 2, column {column}: " \
        in problem


def test_a_file_cut_short_says_where_it_ends(seed_folder, tmp_path):
    folder = _copy(seed_folder, tmp_path)
    path = folder / "shared.json"
    lines = path.read_bytes().split(b"\n")
    path.write_bytes(b"\n".join(lines[:3]) + b"\n")
    (problem,) = verify(folder).problems
    assert problem.endswith(f"(cut short: ends at line 3 of the {len(lines) - 1} the records "
                            f"give)")
    path.write_bytes(b"\n".join(lines[:3]))  # the third line's newline lost too
    (problem,) = verify(folder).problems
    assert "(cut short: ends at line 3 of the" in problem


def test_stray_files_are_named_and_left_by_repair(seed_folder, tmp_path):
    folder = _copy(seed_folder, tmp_path)
    strays = {folder / "records" / "moves.jump.json": "the record of no action of index.json",
              folder / "moves.jump.psgs": "the system of no learnt action of index.json",
              folder / ".index.json.4242.tmp": "a temporary file left by an interrupted write",
              folder / "records" / ".moves.step.json.7.tmp":
                  "a temporary file left by an interrupted write"}
    for path in strays:
        path.write_text("{}")
    (folder / "notes.txt").write_text("mine")  # not where a praxicon keeps its files
    expected = tuple(sorted(f"{path}: {why}" for path, why in strays.items()))
    assert verify(folder).problems == expected
    assert repair(folder).problems == expected
    assert all(path.exists() for path in strays)


@pytest.mark.parametrize("text, why", [
    ("[1, 2]", "not an object of seconds per action"),
    ('{"moves.jump": 1}', "'moves.jump' is no action of index.json"),
    ('{"moves.step": -1}', "'moves.step': seconds must be a number 0 or more, not -1"),
    ('{"moves.step": true}', "'moves.step': seconds must be a number 0 or more, not True"),
    ('{"moves.step": 1,', "1:18: not JSON"),
])
def test_timings_are_checked(seed_folder, tmp_path, text, why):
    folder = _copy(seed_folder, tmp_path)
    (folder / "timings.json").write_text(text)
    (problem,) = verify(folder).problems
    assert problem.startswith(f"{folder / 'timings.json'}") and why in problem


def test_a_folder_load_refuses_is_its_error(seed_folder, tmp_path):
    folder = _copy(seed_folder, tmp_path)
    (folder / "records" / "moves.step.json").write_text("{")
    with pytest.raises(PraxiconError, match="moves.step.json:1:2: not JSON"):
        verify(folder)
    with pytest.raises(PraxiconError, match="moves.step.json:1:2: not JSON"):
        repair(folder)


def _run(argv):
    from psgs.cli import main

    return main(["praxicon", "verify", *argv])


def test_the_command_exits_0_1_2_and_repairs(seed_folder, tmp_path, capsys):
    folder = _copy(seed_folder, tmp_path)
    assert _run([str(folder)]) == 0
    assert capsys.readouterr().err.strip() == f"{folder}: whole: 9 files as its records give"
    (folder / "shared.json").unlink()
    assert _run([str(folder)]) == 1
    out, err = capsys.readouterr()
    assert out == f"{folder / 'shared.json'}: missing\n"
    assert err.endswith("1 problem(s) (1 of them --repair writes again from the records)\n")
    assert _run([str(folder), "--repair"]) == 0
    assert capsys.readouterr().err.strip() == (f"{folder}: repaired; whole: 9 files as its "
                                               f"records give")
    assert _run([str(tmp_path / "nowhere")]) == 2
    assert "no such praxicon folder" in capsys.readouterr().err


def test_a_timing_too_large_for_a_float_is_a_number(seed_folder, tmp_path):
    folder = _copy(seed_folder, tmp_path)
    (folder / "timings.json").write_text('{"moves.step": 1' + "0" * 400 + "}")
    assert verify(folder).intact  # a whole number of seconds, however large
    (folder / "timings.json").write_text('{"moves.step": -1' + "0" * 400 + "}")
    (problem,) = verify(folder).problems
    assert problem.endswith("seconds must be a number 0 or more, not -100000000000000000000"
                            "000000000000000...")


def test_a_file_grown_long_is_read_no_further_than_the_records_give(seed_folder, tmp_path):
    folder = _copy(seed_folder, tmp_path)
    path = folder / "moves.step.psgs"
    expected = path.read_bytes()
    with open(path, "ab") as handle:
        handle.truncate(1 << 40)  # a sparse terabyte: read whole, it would take the memory
    (problem,) = verify(folder).problems
    lines = expected.count(b"\n")
    assert problem == (f"{path}: differs from what the records give (longer than the records "
                       f"give: more after line {lines})")


@pytest.mark.parametrize("data, why", [
    (b"", "empty; the records give"),
    (None, "the last line's newline is missing"),
])
def test_an_empty_file_and_a_lost_last_newline_are_named(seed_folder, tmp_path, data, why):
    folder = _copy(seed_folder, tmp_path)
    path = folder / "shared.json"
    path.write_bytes(path.read_bytes()[:-1] if data is None else data)
    (problem,) = verify(folder).problems
    assert why in problem


def test_a_folder_in_a_files_place_is_named_and_repair_leaves_no_temporary_file(
        seed_folder, tmp_path):
    folder = _copy(seed_folder, tmp_path)
    (folder / "shared.json").unlink()
    (folder / "shared.json").mkdir()
    assert verify(folder).problems == (f"{folder / 'shared.json'}: not a file",)
    with pytest.raises(PraxiconError, match=r"shared\.json: cannot be written"):
        repair(folder)
    assert not list(folder.glob(".*.tmp"))


def test_learnt_actions_without_their_descriptions_are_named(seed_folder, tmp_path):
    folder = _copy(seed_folder, tmp_path)
    (folder / "descriptions.json").unlink()
    (problem,) = verify(folder).problems
    assert problem.startswith(f"{folder / 'descriptions.json'}: missing: recognise and parse "
                              f"cannot read the folder")
    assert repair(folder).problems == (problem,)  # not made up from nothing


def test_repairable_counts_the_files_repair_mends(seed_folder, tmp_path):
    folder = _copy(seed_folder, tmp_path)
    (folder / "shared.json").unlink()
    (folder / "actuators.csv").write_text("action\n")
    (folder / "moves.jump.psgs").write_text("stray")
    (folder / "timings.json").write_text("[]")
    found = verify(folder)
    assert len(found.problems) == 4 and found.repairable == 2
    assert repair(folder).repairable == 0
