"""psgs induce with several performances, the motion-file hint, and psgs locate."""

from __future__ import annotations

import json

from psgs.cli import main
from test_pal_performances import performance  # the synthetic waving takes


def write_takes(tmp_path, seeds, **kw):
    paths = []
    for seed in seeds:
        path = tmp_path / f"take{seed}.actiongram"
        path.write_text(performance(seed, **kw).to_text(), encoding="utf-8")
        paths.append(str(path))
    return paths


def test_induce_several_files_names_the_joints(tmp_path, capsys):
    paths = write_takes(tmp_path, range(5))
    assert main(["induce", *paths]) == 0
    out = capsys.readouterr().out
    assert "(5 performances)" in out
    # the summary: one line per joint, its channels, pattern lengths and copies
    joint_lines = [line for line in out.splitlines() if "channel(s) (" in line]
    assert [line.split(":")[0].strip() for line in joint_lines][:2] == ["arm", "hand"]
    assert all("patterns of" in line and "copies at t =" in line for line in joint_lines)
    assert not any(line.strip().startswith("other") for line in out.splitlines())
    assert "component arm" not in out  # the grammar's text only with --full
    assert main(["induce", *paths, "--full"]) == 0
    full = capsys.readouterr().out
    assert "joints: arm (" in full and "hand (" in full and "component arm" in full
    assert main(["induce", *paths, "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["performances"] == 5 and data["actuators"][:2] == ["arm", "hand"]
    assert data["verdict"] == ""


def test_induce_says_plainly_when_nothing_repeats(tmp_path, capsys):
    paths = write_takes(tmp_path, range(4), wave=False)
    assert main(["induce", *paths]) == 0
    assert "No grammar system: no synchronised repetition." in capsys.readouterr().out


def test_induce_given_motion_capture_says_to_segment_it(tmp_path, capsys):
    bvh = tmp_path / "wave.bvh"
    bvh.write_text("HIERARCHY\n", encoding="utf-8")
    assert main(["induce", str(bvh)]) != 0
    err = capsys.readouterr().err
    assert "is motion capture, not an actiongram" in err and "kinetology segment" in err
    assert err.count("\n") == 1


def test_locate_command(tmp_path, capsys):
    learn = write_takes(tmp_path, range(5))
    search = write_takes(tmp_path, (11, 12)) + write_takes(tmp_path, (21,), wave=False)
    args = ["locate", *search]
    for path in learn:
        args += ["--learn", path]
    assert main(args) == 0
    lines = capsys.readouterr().out.splitlines()
    assert lines[0].startswith("learnt from 5 performance(s): joints arm, hand")
    found = {line.split(":")[0]: line for line in lines[1:]}
    assert "score" in found[search[0]] and "score" in found[search[1]]
    assert found[search[2]].endswith("not found")


def test_locate_says_in_one_line_that_pal_has_no_such_parameter(tmp_path, capsys):
    # PAL(nosuch=1) raised the constructor's TypeError: a traceback, status 1
    learn = write_takes(tmp_path, range(2))
    args = ["locate", learn[1], "--learn", learn[0], "--param", "nosuch=1"]
    assert main(args) == 2
    err = capsys.readouterr().err
    assert err.startswith("psgs: error: inducer pal has no parameter 'nosuch'")
    assert err.count("\n") == 1


def test_locate_takes_none_for_pals_max_seconds(tmp_path, capsys):
    learn = write_takes(tmp_path, range(3))
    args = ["locate", learn[2], "--learn", learn[0], "--learn", learn[1], "--json"]
    assert main(args) == 0
    plain = capsys.readouterr().out
    assert main([*args, "--param", "max_seconds=none"]) == 0
    assert capsys.readouterr().out == plain
