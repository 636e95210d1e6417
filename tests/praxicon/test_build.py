"""Building a praxicon: what is on disk, determinism, resume, failures, Ctrl-C, executors."""

from __future__ import annotations

import json
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

import pytest

import praxicon.builder as build_module
from praxicon import Settings, build, load, read_dataset
from praxicon.records import FORMAT_VERSION


def _files(folder):
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name != "timings.json"}


def test_build_writes_index_systems_and_matrix(manifest, tmp_path, capsys):
    result = build(read_dataset(manifest), tmp_path / "px", progress=False)
    px = load(tmp_path / "px")
    assert px == result.praxicon  # the typed round trip: the folder read back, field for field
    assert px.counts == {"actions": 4, "learnt": 2, "failed": 2}
    index = json.loads((tmp_path / "px" / "index.json").read_text())
    assert index["counts"] == px.counts and index["version"] == FORMAT_VERSION
    wave = px["moves.wave"]
    # the arm and the leg swing in step; hips and head are still
    assert wave.actuators == ("arm", "leg")
    assert set(wave.joint("arm").channels) <= {"arm.rx", "arm.rz"}
    morpheme = wave.joint("leg").morpheme("leg.rx")
    assert len(morpheme.kinetemes) == len(morpheme.durations) == len(morpheme.displacements)
    assert wave.file == "moves.wave.psgs"
    assert (tmp_path / "px" / wave.file).read_text() == wave.system
    matrix = (tmp_path / "px" / "actuators.csv").read_text().splitlines()
    assert matrix[0] == "action,hips,arm,leg,head"
    assert "moves.wave,0,1,1,0" in matrix
    assert result.failed == ("moves.alone", "moves.ghost")
    # bad input: one line each in the index and on stderr, the build went on
    err = capsys.readouterr().err
    ghost = px["moves.ghost"]
    assert ghost.status == "failed" and ghost.problems[0].endswith(
        "nowhere.bvh: unreadable file (no such file)")
    assert "moves.ghost: " + ghost.problems[0] in err
    alone = px["moves.alone"]
    assert alone.reason.startswith("1 usable performance(s); an action needs at least 2")
    assert f"moves.alone: failed: {alone.reason}" in err


def test_same_inputs_same_bytes_and_resume(manifest, tmp_path):
    actions = read_dataset(manifest)
    first = build(actions, tmp_path / "a", progress=False, log=lambda s: None)
    build(actions, tmp_path / "b", progress=False, log=lambda s: None)
    assert _files(tmp_path / "a") == _files(tmp_path / "b")
    again = build(actions, tmp_path / "a", progress=False, log=lambda s: None)
    assert again.learnt == () and again.skipped == tuple(a.name for a in actions)
    assert _files(tmp_path / "a") == _files(tmp_path / "b")
    assert first.learnt == ("moves.step", "moves.wave")
    # a file changed in place is another input: its action is learnt again
    from kinetology import write_bvh
    from praxicon_fixtures import take

    wave_take = next(p.file for a in actions if a.name == "moves.wave" for p in a.performances)
    write_bvh(take(9), wave_take)
    touched = build(actions, tmp_path / "a", progress=False, log=lambda s: None)
    assert touched.learnt == ("moves.wave",)
    # other parameters are other inputs: learnt again
    changed = build(actions, tmp_path / "a", settings=Settings.make(params={"min_copies": 4}),
                    progress=False, log=lambda s: None)
    assert changed.skipped == () and len(changed.learnt) == 2


def test_interrupted_build_leaves_a_valid_resumable_folder(manifest, tmp_path, monkeypatch):
    actions = read_dataset(manifest)
    real = build_module.learn_action
    calls = []

    def interrupted(action, settings):
        calls.append(action.name)
        if len(calls) == 3:
            raise KeyboardInterrupt
        return real(action, settings)

    monkeypatch.setattr(build_module, "learn_action", interrupted)
    with pytest.raises(KeyboardInterrupt):
        build(actions, tmp_path / "px", progress=False, log=lambda s: None)
    px = load(tmp_path / "px")  # a valid praxicon, the two finished actions in it
    assert px.names == tuple(calls[:2])
    monkeypatch.setattr(build_module, "learn_action", real)
    resumed = build(actions, tmp_path / "px", progress=False, log=lambda s: None)
    assert resumed.skipped == tuple(sorted(calls[:2]))
    build(actions, tmp_path / "fresh", progress=False, log=lambda s: None)
    assert _files(tmp_path / "px") == _files(tmp_path / "fresh")


@pytest.mark.parametrize("pool", [ThreadPoolExecutor, ProcessPoolExecutor])
def test_any_executor_gives_the_serial_praxicon(manifest, tmp_path, pool):
    actions = read_dataset(manifest)
    build(actions, tmp_path / "serial", progress=False, log=lambda s: None)
    with pool(max_workers=2) as executor:
        build(actions, tmp_path / "pool", executor=executor, progress=False, log=lambda s: None)
    assert _files(tmp_path / "serial") == _files(tmp_path / "pool")


def test_a_crashing_action_is_recorded_and_the_rest_go_on(manifest, tmp_path, monkeypatch):
    real = build_module.learn_action

    def flaky(action, settings):
        if action.name == "moves.step":
            raise MemoryError("out of memory")
        return real(action, settings)

    monkeypatch.setattr(build_module, "learn_action", flaky)
    with ThreadPoolExecutor(max_workers=2) as executor:
        result = build(read_dataset(manifest), tmp_path / "px", executor=executor,
                       progress=False, log=lambda s: None)
    records = {a["name"]: a for a in json.loads((tmp_path / "px" / "index.json").read_text())
               ["actions"]}
    assert records["moves.step"]["reason"] == "worker failed: MemoryError: out of memory"
    assert "moves.wave" in result.learnt
