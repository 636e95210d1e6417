"""Bad input to the praxicon: one clear line each, never a traceback, and no record lost.

Datasets read with one :class:`DatasetError`; ``build`` never raises for bad files or names;
one bad performance costs that performance only; resuming a damaged folder learns again what
it cannot trust and keeps the rest; a damaged or foreign folder reads with one
:class:`PraxiconError`, and the command line says it in one line with exit status 2.
"""

from __future__ import annotations

import json
import shutil

import pytest

from praxicon import build, read_dataset
from praxicon.cli import main
from praxicon.datasets import Action, DatasetError, Performance

from praxicon_fixtures import CHANNELS, take, write_manifest


def _files(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name != "timings.json"}


def _quiet(*args, **kwargs):
    return build(*args, progress=False, log=lambda line: None, **kwargs)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """A manifest of two learnable actions and a praxicon built from it (copy before use)."""
    root = tmp_path_factory.mktemp("built")
    (root / "data").mkdir()
    manifest = write_manifest(root / "data", {"wave": [1, 2, 3], "step": [4, 5, 6]})
    _quiet(read_dataset(manifest), root / "px")
    return manifest, root / "px"


@pytest.fixture
def px(built, tmp_path):
    manifest, folder = built
    copy = tmp_path / "px"
    shutil.copytree(folder, copy)
    return manifest, copy


# -- reading datasets: every error a DatasetError ----------------------------------------------
@pytest.mark.parametrize("name, content, message", [
    ("m.toml", "performance = [1, 2]\n", "m.toml: performance 1: a [[performance]] table "
                                         "expected, not 1"),
    ("m.toml", '[[performance]]\naction = "wave"\nfile = ["a"]\n',
     "performance 1: action and file must be text, not ['a']"),
    ("m.csv", "action,file\nwave," + "a" * 131_073 + "\n",
     "m.csv:2: field larger than field limit (131072)"),
    ("m.csv", b"action,file\nw\xe9ve,a.bvh\n", "m.csv:2:2: not UTF-8 text: byte 0xe9"),
    ("m.toml", b'[[performance]]\naction = "w\xe9ve"\n', "m.toml:2:12: not UTF-8 text"),
    ("m.csv", "action,file,start\nwave,a.bvh,inf\n", "m.csv:2: start/stop must be seconds >= 0"),
    # names that become one: one record would overwrite the other
    ("m.csv", "action,file\nwave left,a.bvh\nwave-left,b.bvh\n",
     "actions 'wave left' and 'wave-left' are both named 'm.wave-left'"),
    ("m.csv", "action,file\nbye!,a.bvh\nbye,b.bvh\n",
     "actions 'bye' and 'bye!' are both named 'm.bye'"),
    ("m.csv", "action,file\n" + "x" * 300 + ",a.bvh\n", "is 302 bytes long; at most 200"),
    # a cell past the header's would be dropped without a word; a column twice is ambiguous
    ("m.csv", "action,file\nwave,a.bvh\nwave,b.bvh,extra,more\n", "m.csv:3: 4 cells, the "
                                                                   "header has 2"),
    ("m.csv", "action,file,action\nwave,a.bvh,run\n", "m.csv:1: the header names column "
                                                        "'action' twice"),
    # a row given twice counted as two performances: one take met the minimum of two
    ("m.csv", "action,file,start\nwave,a.bvh,1\nwave,b.bvh,\nwave,a.bvh,1.0\n",
     "m.csv:4: the same performance as line 2 (action, file and span): list each once"),
    ("m.toml", '[[performance]]\naction = "w"\nfile = "a.bvh"\n' * 2,
     "m.toml: performance 2: the same performance as performance 1"),
])
def test_a_bad_manifest_is_one_dataset_error(tmp_path, name, content, message):
    path = tmp_path / name
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content)
    with pytest.raises(DatasetError) as info:
        read_dataset(path)
    assert message in str(info.value) and "\n" not in str(info.value)


@pytest.mark.parametrize("text", ["action,file\nwave,a.bvh,,\n",
                                  # a spreadsheet pads its header too, and may start with a BOM
                                  "\ufeffaction,file,,\nwave,a.bvh,,\nwave,b.bvh,,\n"])
def test_empty_cells_past_the_header_pad_a_manifest_row(tmp_path, text):
    (tmp_path / "m.csv").write_text(text, encoding="utf-8")
    assert [a.content for a in read_dataset(tmp_path / "m.csv")] == ["wave"]


def test_names_that_become_one_are_refused_by_the_command_too(tmp_path, capsys):
    (tmp_path / "m.csv").write_text("action,file\nwave left,a.bvh\nwave-left,b.bvh\n")
    assert main(["build", str(tmp_path / "m.csv"), "-o", str(tmp_path / "px")]) == 2
    (line,) = capsys.readouterr().err.splitlines()
    assert line.startswith("psgs: error: ") and "rename one" in line
    assert not (tmp_path / "px").exists()  # refused before anything was learnt


def _bandai(root):
    """A Bandai-style folder of three takes of one content (the label files beside them)."""
    from kinetology import write_bvh

    (root / "cfg").mkdir(parents=True)
    (root / "data").mkdir()
    (root / "cfg" / "content_label.txt").write_text("dataset-9_wave\n")
    (root / "cfg" / "style_label.txt").write_text("dataset-9_calm\n")
    for i in (1, 2, 3):
        write_bvh(take(i, seconds=2), root / "data" / f"dataset-9_wave_calm_00{i}.bvh")
        (root / "data" / f"dataset-9_wave_calm_00{i}.json").write_text(
            '{"content": 0, "style": 0}')
    return root


def test_a_label_file_nesting_too_deeply_costs_its_take_only(tmp_path):
    root = _bandai(tmp_path / "set")
    (root / "data" / "dataset-9_wave_calm_002.json").write_text("[" * 100_000)
    (action,) = read_dataset(root)
    assert len(action.performances) == 2
    (problem,) = action.problems
    assert "dataset-9_wave_calm_002.json" in problem and "nests too deeply" in problem


def test_a_negative_frame_time_beside_a_label_is_a_format_error(tmp_path):
    from kinetology import MotionFormatError
    from kinetology.labels import read_bandai_json

    root = _bandai(tmp_path / "set")
    bvh = root / "data" / "dataset-9_wave_calm_003.bvh"
    text = bvh.read_text().splitlines()
    text = [("Frame Time: -0.0333" if line.startswith("Frame Time:") else line) for line in text]
    bvh.write_text("\n".join(text) + "\n")
    with pytest.raises(MotionFormatError, match="give no length to label"):
        read_bandai_json(bvh.with_suffix(".json"))
    (action,) = read_dataset(root)  # that take is left out, with its line
    assert len(action.performances) == 2 and "give no length" in action.problems[0]


# -- build never raises for bad input ----------------------------------------------------------
def test_a_nul_byte_in_a_path_is_an_unreadable_file(tmp_path, capsys):
    data = tmp_path / "data"
    data.mkdir()
    write_manifest(data, {"wave": [1, 2]})
    (data / "m.toml").write_text(
        "".join(f'[[performance]]\naction = "wave"\nfile = "{f}"\n'
                for f in ("wave_1.bvh", "wave_2.bvh", "wave\\u0000_3.bvh")))
    assert main(["build", str(data / "m.toml"), "-o", str(tmp_path / "px"),
                 "--no-progress"]) == 0
    captured = capsys.readouterr()
    assert "1 learnt, 0 failed" in captured.out and "Traceback" not in captured.err
    assert "unreadable file (embedded null byte)" in captured.err


def test_an_action_name_that_cannot_be_a_file_name_is_refused_not_raised(tmp_path):
    data = tmp_path / "data"
    data.mkdir()
    manifest = write_manifest(data, {"wave": [1, 2]})
    (wave,) = read_dataset(manifest)
    long = Action("x" * 300, "m", "x" * 300, performances=wave.performances)
    lines = []
    result = build([wave, long], tmp_path / "px", progress=False, log=lines.append)
    assert result.refused == ("x" * 300,) and result.learnt == ("moves.wave",)
    assert result.praxicon.names == ("moves.wave",)
    assert any("is 300 bytes long" in line for line in lines)


# -- one bad performance costs that performance only -------------------------------------------
def test_a_stop_past_the_end_with_no_start_costs_that_performance(tmp_path):
    data = tmp_path / "data"
    data.mkdir()
    manifest = write_manifest(data, {"wave": [1, 2, 3]})
    manifest.write_text(manifest.read_text() + "wave,wave_1.bvh,,99\n")
    result = _quiet(read_dataset(manifest), tmp_path / "px")
    record = result.praxicon["moves.wave"]
    assert record.learnt and [p.used for p in record.performances] == [True] * 3 + [False]
    (problem,) = record.problems
    assert "label span 0-99 s ends after the motion" in problem


def test_a_take_with_other_channels_costs_that_take(tmp_path):
    from kinetology import Motion, write_bvh
    from kinetology.bvh_writer import star_skeleton

    data = tmp_path / "data"
    data.mkdir()
    manifest = write_manifest(data, {"wave": [1, 2, 3]})
    odd = take(4)
    fewer = CHANNELS[:-1]  # no head
    write_bvh(Motion(odd.values[:, :-1], fewer, odd.frame_rate, star_skeleton(fewer)),
              data / "odd.bvh")
    manifest.write_text(manifest.read_text() + "wave,odd.bvh,,\n")
    record = _quiet(read_dataset(manifest), tmp_path / "px").praxicon["moves.wave"]
    assert record.learnt and [p.used for p in record.performances] == [True] * 3 + [False]
    (problem,) = record.problems
    assert "odd.bvh: its 4 channels are not the 5 of the other performances" in problem


# -- resuming a damaged folder -----------------------------------------------------------------
def test_resume_learns_again_what_it_cannot_trust_and_keeps_the_rest(px, tmp_path, built):
    manifest, folder = px
    fresh = _files(built[1])
    (folder / "timings.json").write_text("[]")
    wave = folder / "records" / "moves.wave.json"
    stored = json.loads(wave.read_text())
    stored["record"]["joints"] = 5  # edited, its input key intact
    wave.write_text(json.dumps(stored))
    step = folder / "records" / "moves.step.json"
    step.write_text('{"key": "' + stored["key"] + '", "record": ' + "[" * 100_000)
    lines = []
    result = build(read_dataset(manifest), folder, progress=False, log=lines.append)
    assert result.learnt == ("moves.step", "moves.wave") and result.skipped == ()
    assert sum("learnt again" in line for line in lines) == 2
    assert _files(folder) == fresh
    assert set(json.loads((folder / "timings.json").read_text())) == {"moves.step",
                                                                     "moves.wave"}


def test_resume_keeps_untouched_records_and_rewrites_a_deleted_system(px, built):
    manifest, folder = px
    untouched = (folder / "records" / "moves.step.json").read_bytes()
    (folder / "moves.wave.psgs").unlink()
    (folder / "index.json").write_text("damaged")
    (folder / "shared.json").write_text("[")
    result = _quiet(read_dataset(manifest), folder)
    assert result.learnt == () and result.skipped == ("moves.step", "moves.wave")
    assert (folder / "records" / "moves.step.json").read_bytes() == untouched
    assert _files(folder) == _files(built[1])  # the system, the index, shared.json rewritten


# -- damaged and foreign folders: one PraxiconError, one line, exit status 2 -------------------
def _index_of_version_1(folder):
    index = json.loads((folder / "index.json").read_text())
    index["version"] = 1
    (folder / "index.json").write_text(json.dumps(index))


def _index_of_a_later_version(folder):
    index = json.loads((folder / "index.json").read_text())
    index["version"] += 1
    (folder / "index.json").write_text(json.dumps(index))


def _edit_record(change):
    def edit(folder):
        path = folder / "records" / "moves.wave.json"
        stored = json.loads(path.read_text())
        change(stored["record"])
        path.write_text(json.dumps(stored))
    return edit


DAMAGE = {
    "index not a praxicon": (lambda f: (f / "index.json").write_text(
        '{"format": "psgs-praxicon", "actions": 5}'), "index.json: a praxicon of format "
                                                     "version None; this psgs reads version 3"),
    "index of another version": (_index_of_version_1, "rebuild it with 'psgs praxicon build "
                                                      "DATASET... -o FOLDER'"),
    "index of a later version": (_index_of_a_later_version, "a later psgs wrote it; upgrade "
                                                            "psgs to read it"),
    "index nests too deeply": (lambda f: (f / "index.json").write_text("[" * 100_000),
                               "index.json: nests too deeply"),
    "index not JSON": (lambda f: (f / "index.json").write_text("{"),
                       "index.json:1:2: not JSON"),
    "index of a wrong format": (lambda f: (f / "index.json").write_text('{"format": 1}'),
                                "not a praxicon index"),
    "record missing": (lambda f: (f / "records" / "moves.wave.json").unlink(),
                       "records/moves.wave.json: missing"),
    "record nests too deeply": (lambda f: (f / "records" / "moves.wave.json").write_text(
        "[" * 100_000), "moves.wave.json: nests too deeply"),
    "record without its key": (lambda f: (f / "records" / "moves.wave.json").write_text("{}"),
                               "not a praxicon record file"),
    "record's joints not an object": (_edit_record(lambda r: r.update(joints=5)),
                                      "'joints' must be a JSON object, not 5"),
    "record of another action": (_edit_record(lambda r: r.update(name="moves.step")),
                                 "holds the record of 'moves.step'"),
    "morpheme durations cut": (_edit_record(lambda r: r["joints"]["arm"]["morphemes"][
        r["joints"]["arm"]["channels"][0]].update(durations=[0.5])), "'durations' has 1 values"),
    "record's status unknown": (_edit_record(lambda r: r.update(status="maybe")),
                                "'status' must be 'ok' or 'failed'"),
    # generation indexed the performances with these: an IndexError traceback
    "learnt from a performance it does not list": (_edit_record(lambda r: r.update(
        learnt_from=[0, 9])), "'learnt_from' must be indices of its 3 performances"),
    "learnt from performances that are gone": (_edit_record(lambda r: r.update(
        performances=[])), "'learnt_from' must be indices of its 0 performances"),
    # generation divided by them (a warning) or ran a kineteme backwards, and wrote a file
    "morpheme durations of 0 s": (_edit_record(lambda r: r["joints"]["arm"]["morphemes"][
        r["joints"]["arm"]["channels"][0]].update(durations=[0.0] * len(r["joints"]["arm"][
            "morphemes"][r["joints"]["arm"]["channels"][0]]["kinetemes"]))),
        "'durations' must be numbers above 0 and finite: value 1 is 0.0"),
    "a performance starting before its take": (_edit_record(lambda r: r["performances"][0]
                                                            .update(start=-5)),
                                               "performance 1: 'start' must be at least 0"),
    "a performance stopping before its start": (_edit_record(lambda r: r["performances"][0]
                                                             .update(start=2, stop=1)),
                                                "'stop' must be after its start 2, not 1"),
}


@pytest.mark.parametrize("damage", list(DAMAGE))
def test_a_damaged_folder_is_one_error(px, capsys, damage):
    from praxicon import PraxiconError, load

    _, folder = px
    spoil, message = DAMAGE[damage]
    spoil(folder)
    with pytest.raises(PraxiconError) as info:
        load(folder)
    assert message in str(info.value) and "\n" not in str(info.value)
    for argv in (["draw", str(folder), "-o", str(folder / "img")],
                 ["generate", str(folder), "moves.wave", "-o", str(folder / "w.bvh")]):
        assert main(argv) == 2
        (line,) = capsys.readouterr().err.splitlines()
        assert line == f"psgs: error: {info.value}"


@pytest.mark.parametrize("what, message", [
    ("missing", "nowhere: no such praxicon folder"),
    ("empty folder", "not a praxicon folder (no index.json; build one with 'psgs praxicon "
                     "build DATASET... -o FOLDER')"),
    ("a file", "not a praxicon folder (a file; a praxicon is a folder with index.json)"),
])
def test_a_path_that_is_not_a_praxicon_is_one_line_exit_2(tmp_path, capsys, what, message):
    path = tmp_path / "nowhere"
    if what == "empty folder":
        path.mkdir()
    elif what == "a file":
        path.write_text("x")
    for argv in (["draw", str(path), "-o", str(tmp_path / "img")],
                 ["generate", str(path), "a", "-o", str(tmp_path / "a.bvh")]):
        assert main(argv) == 2
        (line,) = capsys.readouterr().err.splitlines()
        assert line.startswith("psgs: error: ") and line.endswith(message)
