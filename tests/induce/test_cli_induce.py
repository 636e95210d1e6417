"""psgs induce / synth / bench noise."""

from __future__ import annotations

import csv
import json

import pytest

import psgs
from psgs.cli import main


def test_induce_example_explains_itself(capsys):
    assert main(["induce", "--example"]) == 0
    out = capsys.readouterr().out
    assert "Hidden in it: 4 strings" in out
    assert out.count("[the hidden template]") == 4
    assert "found exactly the hidden patterns" in out
    assert "component s" not in out  # a summary: the grammar's text only with --full
    assert "Grammar system: 4 component(s)" in out and "--full prints it" in out
    assert main(["induce", "--example", "--full"]) == 0
    full = capsys.readouterr().out
    assert "component s" in full and "--full prints it" not in full


def test_induce_without_file_uses_the_example(capsys):
    assert main(["induce"]) == 0
    assert "Example:" in capsys.readouterr().out


def test_synth_then_induce_json_and_output(tmp_path, capsys):
    ag_path = tmp_path / "ag.txt"
    assert main(["synth", "--noise", "0.05", "--seed", "3", "-o", str(ag_path)]) == 0
    text = ag_path.read_text()
    truth = {line.split()[2].rstrip(":"): tuple(line.split()[3:])
             for line in text.splitlines() if line.startswith("# truth")}
    assert len(truth) == 4
    out_path = tmp_path / "out.psgs"
    assert main(["induce", str(ag_path), "--json", "-o", str(out_path)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert {k: tuple(v) for k, v in data["patterns"].items()} == truth
    system = psgs.loads(out_path.read_text())
    assert system.component_names == tuple(data["components"])
    assert data["system"] == out_path.read_text()


def test_induce_sequential_with_params(tmp_path, capsys):
    path = tmp_path / "a.txt"
    path.write_text("x: a b c a b c a b c\ny: p q r s t u v\n")
    assert main(["induce", str(path), "--inducer", "sequential", "--param", "min_count=3"]) == 0
    out = capsys.readouterr().out
    assert "1 component(s)" in out and "x: a b c" in out


@pytest.mark.parametrize("argv, words", [
    (["induce", "{bad}"], "bad.txt:2:7: unknown duration syntax"),
    (["induce", "{bad}", "--inducer", "nope"], "unknown inducer 'nope'"),
    (["induce", "{bad}", "--param", "alpha"], "write KEY=VALUE"),
    (["induce", "--example", "--param", "alpha=7"], "alpha must be <= 1"),
    (["induce", "--example", "--param", "colour=red"],
     "inducer pal has no parameter 'colour' (its parameters: min_copies,"),
    (["induce", "--example", "--inducer", "sequential", "--param", "min_count=x"],
     "parameter min_count must be an integer"),
    (["induce", "{missing}"], "No such file"),
    (["induce", "--example", "-o", "{missing}/x.psgs"], "not a file in an existing directory"),
    (["induce", "--example", "-o", "{folder}"], "not a file in an existing directory"),
    # an empty name wrote nothing, without a word
    (["induce", "--example", "-o", ""], "-o needs a file name"),
    # the last one was read, the others dropped without a word
    (["induce", "--events", "{table}", "--events", "{table}"],
     "give --events once (one table holds every stream), not 2 times"),
])
def test_bad_input_is_one_line_and_status_2(tmp_path, capsys, argv, words):
    bad = tmp_path / "bad.txt"
    bad.write_text("x: a b\ny: a b@z\n")
    table = tmp_path / "t.csv"
    table.write_text("stream,onset,duration,symbol\nx,0,1,a\n")
    argv = [a.format(bad=bad, missing=tmp_path / "missing.txt", folder=tmp_path, table=table)
            for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and words in err and "Traceback" not in err


def test_no_component_is_said_plainly(tmp_path, capsys):
    path = tmp_path / "r.txt"
    assert main(["synth", "--patterned", "0", "-o", str(path)]) == 0
    assert main(["induce", str(path)]) == 0
    assert "No grammar system" in capsys.readouterr().out


def test_bench_noise_writes_csv(tmp_path, capsys):
    out = tmp_path / "n.csv"
    assert main(["bench", "noise", "--trials", "2", "--levels", "0:0.1:0.1", "--jobs", "1",
                 "--csv", str(out)]) == 0
    captured = capsys.readouterr()
    assert "2/4 cells" in captured.err or "4/4 cells" in captured.err
    rows = list(csv.DictReader(out.open()))
    assert len(rows) == 4
    pal = [r for r in rows if r["inducer"] == "pal"]
    assert [r["successes"] for r in pal] == ["2", "2"]
    assert "100.00%" in captured.out


def test_bench_noise_plot(tmp_path, capsys):
    pytest.importorskip("matplotlib", reason="matplotlib (the plot extra) is not installed")
    png = tmp_path / "n.png"
    assert main(["bench", "noise", "--trials", "1", "--levels", "0", "--inducer", "pal",
                 "--jobs", "1", "--plot", str(png)]) == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_bad_levels_are_rejected(capsys):
    with pytest.raises(SystemExit) as info:
        main(["bench", "noise", "--levels", "0.5:0.1:0.1"])
    assert info.value.code == 2


@pytest.mark.parametrize("argv", [
    ["synth", "--seed", "-1"],
    ["bench", "noise", "--seed", "-3"],
    ["bench", "noise", "--levels", "5"],
    ["bench", "noise", "--levels", "nan"],
    ["bench", "noise", "--levels", "0:nan:0.1"],
    ["bench", "noise", "--levels", "0:1:5e-324"],  # an OverflowError's traceback (status 1)
    ["bench", "noise", "--levels", "0:1:1e-300"],  # 1e300 levels: counted without end
    ["bench", "noise", "--levels", "0:1:1e-5"],
])
def test_bad_seeds_and_levels_are_usage_errors(capsys, argv):
    with pytest.raises(SystemExit) as info:
        main(argv)
    assert info.value.code == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and "error: argument --" in err


def test_a_component_kept_at_a_bound_is_not_also_called_dropped(tmp_path, capsys):
    path = tmp_path / "a.txt"
    path.write_text("x: a b c a b c a b c a b c\n")
    # max_rules is a budget: the learner stopped before its pattern (a b c), so status 3
    assert main(["induce", str(path), "--inducer", "sequential", "--param", "max_rules=1"]) == 3
    captured = capsys.readouterr()
    out = captured.out
    assert "1 component(s)" in out and "note: x: rule bound reached" in out
    assert "x: a b   (" in out  # what it had found is still printed
    assert "dropped" not in out
    assert captured.err == ("psgs: sequential stopped at its bound max_rules=1 on 1 string "
                            "(x): its pattern is what the rules made by then give\n")


def test_an_induction_within_its_budget_exits_0_and_names_no_bound(tmp_path, capsys):
    path = tmp_path / "a.txt"
    path.write_text("x: a b c a b c a b c a b c\n")
    for extra in ([], ["--json"]):
        assert main(["induce", str(path), "--inducer", "sequential", *extra]) == 0
        assert capsys.readouterr().err == ""
    # --json prints the object whole, and names the bound on stderr as the summary does
    assert main(["induce", str(path), "--inducer", "sequential", "--param", "max_rules=1",
                 "--json"]) == 3
    captured = capsys.readouterr()
    assert json.loads(captured.out)["patterns"] == {"x": ["a", "b"]}
    assert "at its bound max_rules=1" in captured.err and captured.err.count("\n") == 1


def test_a_bound_that_stopped_no_rule_is_not_named_and_exits_0(tmp_path, capsys):
    path = tmp_path / "a.txt"
    path.write_text("x: a b a b\n")
    # one rule (a b) is all this string has: max_rules=1 cut nothing off
    assert main(["induce", str(path), "--inducer", "sequential", "--param", "max_rules=1"]) == 0
    captured = capsys.readouterr()
    assert captured.err == "" and "x: a b   (2 copies at" in captured.out


@pytest.mark.parametrize("flag", ["--csv", "--plot"])
def test_bench_noise_checks_its_output_path_before_running(tmp_path, capsys, flag):
    target = tmp_path / "no-such-dir" / "out.x"
    assert main(["bench", "noise", "--trials", "1", "--levels", "0", flag, str(target)]) == 2
    captured = capsys.readouterr()
    assert "not a file in an existing directory" in captured.err and "cells" not in captured.err


def test_bench_noise_refuses_an_inducer_given_twice_before_running(capsys):
    # each inducer's column is the same trials with the same parameters: a repeat is a slip
    argv = ["bench", "noise", "--trials", "1", "--levels", "0", "--jobs", "1",
            "--inducer", "sequential", "--inducer", "pal", "--inducer", "sequential"]
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == "" and "cells" not in captured.err
    assert captured.err == ("psgs: error: --inducer sequential is given twice: give each "
                            "inducer once\n")


def test_several_performances_are_counted_whole(tmp_path, capsys):
    # the summary line counts every performance's strings and symbols, not the first one's
    first, second = tmp_path / "a.txt", tmp_path / "b.txt"
    first.write_text("x: a b c a b c a b c\n")
    second.write_text("x: a b c a b c\ny: p q p q p q\n")
    for order in ((first, second), (second, first)):
        assert main(["induce", *map(str, order)]) == 0
        line = capsys.readouterr().out.splitlines()[0]
        assert "of 2 strings, 21 symbols (2 performances)" in line, line


def test_the_bound_is_read_from_the_induction_not_from_a_status_text(tmp_path, capsys,
                                                                     monkeypatch):
    from dataclasses import replace

    from psgs.induce import Sequential

    path = tmp_path / "a.txt"
    path.write_text("x: a b c a b c a b c a b c\ny: p q\n")
    learn = Sequential.induce

    def reworded(self, performances):  # the same Induction, its caveat in other words
        result = learn(self, performances)
        return replace(result, reports=tuple(
            replace(r, status="stopped early") if r.status != "component" and
            r.name in result.components else r for r in result.reports))

    monkeypatch.setattr(Sequential, "induce", reworded)
    assert main(["induce", str(path), "--inducer", "sequential", "--param", "max_rules=1"]) == 3
    assert capsys.readouterr().err == ("psgs: sequential stopped at its bound max_rules=1 on 1 "
                                       "string (x): its pattern is what the rules made by then "
                                       "give\n")

    def unbounded(self, performances):  # the status text alone names no bound
        return replace(learn(self, performances), bound=None, reason=None)

    monkeypatch.setattr(Sequential, "induce", unbounded)
    assert main(["induce", str(path), "--inducer", "sequential", "--param", "max_rules=1"]) == 0
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("text", ["none", "None", "NONE"])
def test_none_is_the_default_of_a_parameter_whose_default_is_none(tmp_path, capsys, text):
    path = tmp_path / "a.txt"
    path.write_text("x: a b c a b c a b c a b c\ny: a b c a b c a b c a b c\n")

    def learnt(*extra):
        assert main(["induce", str(path), "--json", *extra]) == 0
        captured = capsys.readouterr()
        assert captured.err == ""
        return {k: v for k, v in json.loads(captured.out).items() if k != "seconds"}

    # max_seconds's own message says it takes a number or None: the text None was refused
    assert learnt("--param", f"max_seconds={text}") == learnt()


def test_none_for_a_parameter_that_takes_no_none_is_its_own_message(tmp_path, capsys):
    path = tmp_path / "a.txt"
    path.write_text("x: a b c a b c\n")
    assert main(["induce", str(path), "--inducer", "sequential", "--param",
                 "max_rules=None"]) == 2
    assert capsys.readouterr().err == ("psgs: error: parameter max_rules must be an integer, "
                                       "not 'None'\n")
    assert main(["induce", str(path), "--param", "max_seconds=soon"]) == 2
    assert capsys.readouterr().err == ("psgs: error: parameter max_seconds must be a number or "
                                       "None, not 'soon'\n")
