"""Reading a praxicon folder: ``load``, ``recognise`` and ``parse`` read it one way and refuse
a damaged one with the same line, naming the file and the field; and what the commands check
before any work.

Each damage is one the fuzzer or an audit found answered, hung or raised a traceback."""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from praxicon import PraxiconError, build, load, read_dataset
from praxicon.description import DescriptionError, Descriptions
from praxicon.store import read_descriptions
from praxicon_fixtures import refused as _refused, run_praxicon as _run


def _take(seed: int, arm: bool, leg: bool, seconds: float = 5.0, rate: float = 30.0):
    """A take whose arm or leg swings (the other still), every joint present."""
    from kinetology import Motion
    from kinetology.bvh_writer import star_skeleton

    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * rate)) / rate
    phase = 2 * np.pi * t / (1 + 0.05 * (seed % 3))
    channels = ("hips.rz", "arm.rx", "arm.rz", "leg.rx", "head.ry")
    noise = [0.3 * rng.standard_normal(t.size) for _ in channels]
    values = np.column_stack([
        noise[0],
        (40 * np.sin(phase) if arm else 0 * t) + noise[1],
        (25 * np.sin(phase + 0.7) if arm else 0 * t) + noise[2],
        (30 * np.sin(phase + 2) if leg else 0 * t) + noise[3],
        noise[4]])
    return Motion(values, channels, rate, star_skeleton(channels), f"take{seed}")


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    """A praxicon of two actions (m.wave, m.step) with its descriptions, and a new wave."""
    from kinetology import write_bvh

    root = tmp_path_factory.mktemp("checks")
    rows = ["action,file"]
    for name, arm, leg, seeds in (("wave", True, False, (1, 2, 3)),
                                  ("step", False, True, (4, 5, 6))):
        for seed in seeds:
            path = root / "takes" / f"{name}{seed}.bvh"
            path.parent.mkdir(exist_ok=True)
            write_bvh(_take(seed, arm, leg), path)
            rows.append(f"{name},{path}")
    (root / "m.csv").write_text("\n".join(rows) + "\n")
    result = build(read_dataset(root / "m.csv"), root / "px", progress=False,
                   log=lambda s: None)
    assert result.praxicon.descriptions is not None
    write_bvh(_take(7, True, False), root / "new.bvh")
    return root


@pytest.fixture
def px(built, tmp_path) -> Path:
    """A copy of the built praxicon folder, to damage."""
    return Path(shutil.copytree(built / "px", tmp_path / "px"))


def _edit(path: Path, change) -> None:
    data = json.loads(path.read_text())
    change(data)
    path.write_text(json.dumps(data))  # NaN and Infinity written as JSON's extensions


def _every_reader_refuses(capsys, built, folder, message) -> str:
    """load, read_descriptions, recognise and parse (API and command) refuse ``folder`` with
    one line holding ``message``; the line."""
    from praxicon import parse, recognise

    with pytest.raises(PraxiconError) as info:
        load(folder)
    said = str(info.value)
    assert message in said and "\n" not in said
    for windows in (False, True):
        with pytest.raises(DescriptionError, match=None) as again:
            read_descriptions(folder, windows=windows)
        assert str(again.value) == said
    for call in (recognise, parse):
        with pytest.raises(DescriptionError):
            call(folder, built / "new.bvh")
    for command in ("recognise", "parse"):
        assert _refused(capsys, [command, str(folder), str(built / "new.bvh")]) == said
    return said


# -- recognise and parse read the folder as load does -----------------------------------------
def _index(change):
    return lambda folder: _edit(folder / "index.json", change)


def _twice(index):
    index["actions"].append(index["actions"][0])


FOLDERS = {
    "actions not a list": (_index(lambda i: i.update(actions="m.wave")),
                           "index.json: 'actions' must be a list of records"),
    "action listed twice": (_index(_twice), "index.json: action 'm.step' is listed twice"),
    "name out of the folder": (_index(lambda i: i["actions"][0].update(name="../m.step")),
                               "index.json: action 1: action name '../m.step' cannot be a "
                               "file name (it holds '/')"),
    "no actions listed": (_index(lambda i: i.update(actions=[])),
                          "takes: describes 'm.step', which index.json does not list"),
    "record missing": (lambda f: (f / "records" / "m.wave.json").unlink(),
                       "records/m.wave.json: missing"),
    "record empty": (lambda f: (f / "records" / "m.wave.json").write_text(""),
                     "records/m.wave.json:1:1: not JSON (Expecting value)"),
    "record cut": (lambda f: (f / "records" / "m.wave.json").write_text(
        (f / "records" / "m.wave.json").read_text()[:200]), "records/m.wave.json:"),
    "index cut": (lambda f: (f / "index.json").write_text((f / "index.json").read_text()[:300]),
                  "index.json:"),
}


@pytest.mark.parametrize("damage", list(FOLDERS))
def test_recognise_and_parse_refuse_what_load_refuses(built, px, capsys, damage):
    spoil, message = FOLDERS[damage]
    spoil(px)
    _every_reader_refuses(capsys, built, px, message)


def test_a_cut_index_names_its_line_and_column(built, px, capsys):
    text = (px / "index.json").read_text()
    (px / "index.json").write_text(text[:text.index('"datasets"') + 12])
    said = _every_reader_refuses(capsys, built, px, "index.json:")
    line = text[:text.index('"datasets"')].count("\n") + 1
    assert said.startswith(f"{px / 'index.json'}:{line}:") and ": not JSON (" in said


def test_the_sound_folder_is_read_by_every_reader(built, capsys):
    """The control: the undamaged folder answers."""
    status, out, err = _run(capsys, ["recognise", str(built / "px"), str(built / "new.bvh")])
    assert status == 0 and ": m.wave " in out and err == ""
    status, out, err = _run(capsys, ["parse", str(built / "px"), str(built / "new.bvh")])
    assert status == 0 and "m.wave" in out and err == ""


# -- the build never leaves descriptions of other records --------------------------------------
@pytest.mark.parametrize("after", [0, 1])  # Ctrl-C before any action is learnt, or after one
def test_an_interrupted_build_leaves_no_stale_descriptions(built, px, monkeypatch, after):
    """A resumed build that learns an action again and is interrupted before it describes the
    actions leaves a folder load reads (without descriptions), not one it refuses."""
    import praxicon.builder as builder
    from praxicon.learn import Settings

    real, calls = builder.learn_action, []

    def once(action, settings):  # learns the first action, then Ctrl-C
        calls.append(action.name)
        if len(calls) > after:
            raise KeyboardInterrupt
        return real(action, settings)

    monkeypatch.setattr(builder, "learn_action", once)
    with pytest.raises(KeyboardInterrupt):  # other settings: every action is learnt again
        build(read_dataset(built / "m.csv"), px, settings=Settings.make(min_performances=3),
              progress=False, log=lambda s: None)
    assert not (px / "descriptions.json").exists()
    assert load(px).descriptions is None


# -- a record's frame rate ---------------------------------------------------------------------
@pytest.mark.parametrize("rate", [-30, 0, 0.05, 20000, 1e308, math.inf, math.nan])
def test_a_record_frame_rate_out_of_range_names_the_file_and_field(built, px, capsys, rate):
    # 1e308 made generation loop over as many steps; inf and NaN raised tracebacks
    _edit(px / "records" / "m.wave.json", lambda d: d["record"].update(frame_rate=rate))
    said = _every_reader_refuses(capsys, built, px, "records/m.wave.json: 'frame_rate' must be "
                                                    "frames per second from 0.1 to 10000, not ")
    assert _refused(capsys, ["generate", str(px), "m.wave", "-o", str(px / "w.bvh")]) == said
    assert not (px / "w.bvh").exists()


# -- descriptions.json, every field ------------------------------------------------------------
def _set(part, where, key, value):
    """A change of ``descriptions.json``: in ``part`` (takes or windows), in the spread or in
    every action (``where``), ``key`` set to ``value`` (a callable: of the old value)."""
    def change(data):
        places = [data[part]["spread"]] if where == "spread" else data[part]["actions"]
        for place in places:
            place[key] = value(place[key]) if callable(value) else value
    return change


def _first(value):
    return lambda old: [value, *old[1:]]


DESCRIPTIONS = {
    "temperature 0": (_set("takes", "spread", "temperature", 0),
                      "takes: spread: 'temperature' must be above 0, not 0.0"),
    "temperature -1": (_set("windows", "spread", "temperature", -1),
                       "windows: spread: 'temperature' must be above 0, not -1.0"),
    "temperature inf": (_set("takes", "spread", "temperature", math.inf),
                        "takes: spread: 'temperature' must be a finite number, not inf"),
    "scale inf": (_set("takes", "spread", "scale", _first(math.inf)),
                  "takes: spread: 'scale' must be finite numbers: value 1 is inf"),
    "scale 0": (_set("windows", "spread", "scale", _first(0.0)),
                "windows: spread: 'scale' must be numbers above 0: value 1 is 0.0"),
    "noise 0": (_set("takes", "spread", "noise", _first(0.0)),
                "takes: spread: 'noise' must be numbers above 0: value 1 is 0.0"),
    "mean NaN": (_set("takes", "actions", "mean", _first(math.nan)),
                 "takes: action 'm.step': 'mean' must be finite numbers: value 1 is nan"),
    "spread negative": (_set("windows", "actions", "spread", _first(-1.0)),
                        "windows: action 'm.step': 'spread' must be numbers from 0: value 1 "
                        "is -1.0"),
    "mean cut": (_set("takes", "actions", "mean", lambda old: old[:3]),
                 "takes: action 'm.step': 'mean' has 3 values for"),
    "factors cut": (_set("windows", "spread", "factors", lambda old: [old[0][:3]]),
                    "windows: spread: row 1 of 'factors' has 3 values for"),
    "threshold NaN": (_set("takes", "spread", "threshold", math.nan),
                      "takes: spread: 'threshold' must be a finite number, not nan"),
    "limit negative": (_set("takes", "spread", "limits", lambda old: [[old[0][0], -1.0]]),
                       "takes: spread: 'limits' must be numbers above 0: value 1 is -1.0"),
    "takes 0": (_set("takes", "actions", "takes", 0),
                "takes: action 'm.step': 'takes' must be a whole number from 1, not 0"),
    "window negative": (lambda d: (_set("windows", "spread", "window", -2.0)(d),
                                   _set("windows", "actions", "window", -2.0)(d)),
                        "windows: spread: 'window' must be 0 (whole takes) or 0.1 to 60 "
                        "seconds, not -2.0"),
    "window huge": (lambda d: (_set("windows", "spread", "window", 1e300)(d),
                               _set("windows", "actions", "window", 1e300)(d)),
                    "'window' must be 0 (whole takes) or 0.1 to 60 seconds, not 1e+300"),
    "window tiny": (lambda d: (_set("windows", "spread", "window", 1e-300)(d),
                               _set("windows", "actions", "window", 1e-300)(d)),
                    "'window' must be 0 (whole takes) or 0.1 to 60 seconds, not 1e-300"),
    "window of whole takes": (lambda d: (_set("takes", "spread", "window", 2.0)(d),
                                         _set("takes", "actions", "window", 2.0)(d)),
                              "takes: spread: 'window' must be 0 (whole takes), not 2.0"),
    "action's window not the spread's": (_set("windows", "actions", "window", 1.0),
                                         "windows: action 'm.step': 'window' 1 is not the "
                                         "spread's 2"),
    "action twice": (lambda d: d["takes"]["actions"].append(d["takes"]["actions"][0]),
                     "takes: action 'm.step' is described twice"),
    "action not in the index": (lambda d: [d[p]["actions"][0].update(name="m.ghost")
                                           for p in ("takes", "windows")],
                                "takes: describes 'm.ghost', which index.json does not list "
                                "as a learnt action (learn the descriptions again: 'psgs "
                                "praxicon build"),
    # the group test reads the groups it finds a limit for: renamed, it was off unsaid
    "a limit of no feature group": (
        lambda d: d["takes"]["spread"]["limits"][0].__setitem__(0, "bogus0"),
        "takes: spread: 'limits' must be of the spread's feature groups: value 1 is 'bogus0'"),
    "a group's limit twice": (
        lambda d: d["windows"]["spread"]["limits"].append(d["windows"]["spread"]["limits"][0]),
        "windows: spread: 'limits' names"),
    "windows of an action the takes lack": (
        lambda d: d["windows"]["actions"][0].update(name="m.ghost"),
        "takes and windows describe other actions: 'm.step' is described in takes only"),
    "key of other records": (lambda d: d.update(key="0" * 64),
                             "descriptions.json: 'key' is not the key of this folder's learnt "
                             "actions: the descriptions were learnt from other records"),
    "key not text": (lambda d: d.update(key=5), "descriptions.json: 'key' must be text"),
}


@pytest.mark.parametrize("damage", list(DESCRIPTIONS))
def test_damaged_descriptions_name_the_file_and_the_field(built, px, capsys, damage):
    change, message = DESCRIPTIONS[damage]
    _edit(px / "descriptions.json", change)
    said = _every_reader_refuses(capsys, built, px, message)
    assert said.startswith(f"{px / 'descriptions.json'}: ")


def test_descriptions_read_from_a_dict_are_checked_too(built):
    """``Descriptions.from_dict`` (what ``Praxicon.from_json`` reads) is checked the same way:
    a factors row of the wrong length was a reshape ValueError in parse."""
    data = json.loads((built / "px" / "descriptions.json").read_text())["windows"]
    data["spread"]["factors"] = [[1.0, 1.0, 1.0]]
    with pytest.raises(DescriptionError, match="spread: row 1 of 'factors' has 3 values for"):
        Descriptions.from_dict(data)


# -- parse names the joints the recording lacks ------------------------------------------------
def test_parse_names_the_joints_it_lacks_as_recognise_does(built, tmp_path, capsys):
    from kinetology import read, write_bvh
    from praxicon import parse

    full = read(built / "new.bvh")
    write_bvh(full.select([c for c in full.channels if not c.startswith("leg.")]),
              tmp_path / "noleg.bvh")
    timeline = parse(built / "px", tmp_path / "noleg.bvh")
    assert timeline.missing == ("leg",) and "1 joint missing" in repr(timeline)
    assert parse(built / "px", full).missing == ()
    said = {}
    for command in ("recognise", "parse"):
        status, out, err = _run(capsys, [command, str(built / "px"), str(tmp_path / "noleg.bvh")])
        assert status == 0 and "m.wave" in out
        said[command] = err
    assert said["parse"] == said["recognise"] == \
        f"{tmp_path / 'noleg.bvh'}: recognised without the joints it lacks: leg\n"


# -- outputs' folders, checked before any work -------------------------------------------------
@pytest.mark.parametrize("where", ["missing", "a file"])
def test_a_plot_into_no_folder_is_refused_before_any_answer(built, tmp_path, capsys, where):
    folder = tmp_path / "nowhere"
    if where == "a file":
        folder.write_text("x")
    plot = folder / "x.png"
    expected = (f"{plot}: no folder {folder} to write the picture into" if where == "missing"
                else f"{plot}: {folder} is not a folder")
    for command in ("recognise", "parse"):
        assert _refused(capsys, [command, str(built / "px"), str(built / "new.bvh"),
                                 "--plot", str(plot)]) == expected
    assert _refused(capsys, ["generate", str(built / "px"), "m.wave", "-o",
                             str(tmp_path / "w.bvh"), "--plot", str(plot)]) == expected
    assert _refused(capsys, ["generate", str(built / "px"), "m.wave", "-o",
                             str(folder / "w.bvh")]).startswith(f"{folder / 'w.bvh'}: ")
    assert not (tmp_path / "w.bvh").exists()
