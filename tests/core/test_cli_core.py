"""psgs derive / export / show: output, exit status, one-line errors."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import lark
import pytest

import psgs
from psgs.cli import main
from psgs.lark_export import LARK_OPTIONS

REPO = Path(__file__).resolve().parents[2]
GAMMA = str(REPO / "grammars" / "paper_example.psgs")
K1 = "(abcdbcad, bcadabcd, cdabcdab, abcdbcad)"
K2 = "(abcdbcadabcdbcad, bcadabcdbcadabcd, cdabcdabcdabcdab, abcdbcadabcdbcad)"


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


# ---------------------------------------------------------------- derive --enumerate
@pytest.mark.parametrize("mode", [[], ["--mode", "parallel"], ["--mode", "single"]])
def test_enumerate_gamma_to_32_prints_exactly_the_k1_tuple(capsys, mode):
    status, out, err = run(capsys, "derive", GAMMA, "--enumerate", "--max-length", "32", *mode)
    assert (status, out, err) == (0, K1 + "\n", "")


@pytest.mark.parametrize("mode", ["parallel", "single"])
def test_enumerate_gamma_to_64_adds_k2(capsys, mode):
    status, out, err = run(capsys, "derive", GAMMA, "--enumerate", "--max-length", "64",
                           "--mode", mode)
    assert (status, out.splitlines(), err) == (0, [K1, K2], "")


def test_enumerate_pcgs_prints_master_words(capsys):
    status, out, _ = run(capsys, "derive", str(REPO / "grammars" / "pcgs_returning.psgs"),
                         "--enumerate", "--max-length", "10", "--returning", "no")
    assert status == 0 and out.split() == ["a", "aaa", "aaaaaa", "aaaaaaaaaa"]


def test_multi_character_terminals_are_separated_by_spaces(capsys, tmp_path):
    path = tmp_path / "long.psgs"
    path.write_text('psgs L\ncomponent G start S\n  p: S -> "up" "down"\n  q: S -> "up"\n',
                    encoding="utf-8")
    status, out, _ = run(capsys, "derive", str(path), "--enumerate", "--max-length", "5")
    assert status == 0 and out.splitlines() == ["(up)", "(up down)"]


def test_a_bound_gives_a_note_on_stderr_and_status_3(capsys):
    status, out, err = run(capsys, "derive", str(REPO / "grammars" / "modes.psgs"),
                           "--enumerate", "--max-length", "30", "--max-configurations", "5")
    assert status == 3
    assert len(err.strip().splitlines()) == 1 and "max_configurations" in err
    assert all(line.startswith("(") for line in out.splitlines())
    # it does not claim the words up to the length bound, and says when it found none
    said = "the words above are those it found" if out else "it found no word"
    assert f"{said} before it stopped, not every word up to length 30" in err


@pytest.mark.parametrize("nearest", [[], ["--nearest"]])
def test_check_at_its_bound_names_it_on_stderr_and_status_3(capsys, nearest):
    word = " ".join("a" * 30 + "b" * 30 + "c" * 30)
    status, out, err = run(capsys, "check", *nearest, "--max-steps", "5", "pcgs_abc", word)
    assert status == 3 and out
    assert err.strip().splitlines() == [err.strip()] and "bound max_steps" in err


def test_trace_prints_a_witness_under_each_tuple(capsys):
    status, out, _ = run(capsys, "derive", GAMMA, "--enumerate", "--max-length", "32",
                         "--trace")
    lines = out.splitlines()
    assert status == 0 and lines[0] == K1 and len(lines) == 2
    assert lines[1].startswith("  (S1, S2, S3, S4) ⇒ (N13, N18, N7, N23) ⇒")
    assert lines[1].endswith("⇒ (abcdbcad, bcadabcd, cdabcdab, abcdbcad)")


def test_enumerate_needs_a_length(capsys):
    status, _, err = run(capsys, "derive", GAMMA, "--enumerate")
    assert status == 2 and "--max-length" in err


# ---------------------------------------------------------------- derive --random
def test_random_is_seeded_and_printed_in_the_paper_notation(capsys):
    first = run(capsys, "derive", GAMMA, "--random", "--seed", "5")
    again = run(capsys, "derive", GAMMA, "--seed", "5")
    assert first == again
    status, out, err = first
    assert status == 0 and err == ""
    assert out.startswith("(S1, S2, S3, S4) ⇒ ")
    final = out.strip().split(" ⇒ ")[-1]
    words = tuple(final.strip("()").split(", "))
    assert psgs.accepts(psgs.load(GAMMA), words).answer == "yes"


def test_random_trace_prints_one_step_per_line(capsys):
    status, out, _ = run(capsys, "derive", str(REPO / "grammars" / "modes.psgs"), "--random",
                         "--seed", "1", "--trace")
    lines = out.splitlines()
    assert status == 0 and lines[0] == "(S)" and lines[1].startswith("  ⇒ (AA)")
    assert all("by (" in line for line in lines[1:])


def test_random_that_hits_max_steps_says_so(capsys):
    status, out, err = run(capsys, "derive", GAMMA, "--random", "--max-steps", "2")
    assert status == 3 and "max_steps" in err and out.count(" ⇒ ") == 2


def test_random_that_hits_max_symbols_says_so(capsys, tmp_path):
    path = tmp_path / "grow.psgs"
    path.write_text('psgs Grow\ncomponent G start S\n  p: S -> "a" S\nsync\n  (p)\n',
                    encoding="utf-8")
    status, out, err = run(capsys, "derive", str(path), "--random", "--max-symbols", "10")
    # (S), (aS), (aaS), (aaaS) hold 1 + 2 + 3 + 4 = 10 symbols; one step more would pass it
    assert status == 3 and "max_symbols" in err and out.count(" ⇒ ") == 3


def test_a_blocked_derivation_says_so(capsys, tmp_path):
    path = tmp_path / "blocked.psgs"
    path.write_text('psgs B\nunsynchronised strict\ncomponent G start S\n  p: S -> A\n'
                    '  q: A -> "a"\nsync\n  (p)\n', encoding="utf-8")
    status, out, err = run(capsys, "derive", str(path))
    assert status == 1 and "blocked" in err and out.strip() == "(S) ⇒ (A)"


def test_mode_and_returning_overrides_check_the_kind(capsys):
    status, _, err = run(capsys, "derive", GAMMA, "--returning", "no")
    assert status == 2 and "--returning applies to a PCGS" in err


# ---------------------------------------------------------------- export
def test_export_to_a_directory_writes_one_loadable_file_per_component(capsys, tmp_path):
    status, out, _ = run(capsys, "export", GAMMA, "--to", "lark", "-o", str(tmp_path / "out"))
    assert status == 0
    files = sorted((tmp_path / "out").glob("*.lark"))
    assert [f.name for f in files] == ["G1.lark", "G2.lark", "G3.lark", "G4.lark"]
    assert out.split() == [str(tmp_path / "out" / f"G{i}.lark") for i in range(1, 5)]
    parser = lark.Lark(files[2].read_text(encoding="utf-8"), **LARK_OPTIONS)
    parser.parse("c d a b c d a b")


def test_export_to_stdout_holds_every_component(capsys):
    status, out, _ = run(capsys, "export", GAMMA)
    assert status == 0
    for name in ("G1", "G2", "G3", "G4"):
        assert f"// ===== {name}.lark =====" in out
    assert out.count("start: n__s") == 4


# ---------------------------------------------------------------- show
def test_show_summarises_a_psgs(capsys):
    status, out, _ = run(capsys, "show", GAMMA)
    assert status == 0
    assert out.startswith("Gamma: a PSGS with 4 components")
    assert "mode: parallel" in out and "unsynchronised: free" in out
    assert "T (4): a b c d" in out and "N (26): N1 N2 N3" in out
    assert "  N7:  N7 → N4 N4" in out
    assert "M: 8 tuples" in out and "  (N9, N14, #, N19)" in out
    assert "rules in no tuple (applied on their own): G3: N2, N3" in out


def test_show_summarises_a_pcgs(capsys):
    status, out, _ = run(capsys, "show", str(REPO / "grammars" / "pcgs_abc.psgs"))
    assert status == 0
    assert out.startswith("ABC: a PCGS with 3 components")
    assert "returning: yes" in out and "master: G1" in out and "centralised: yes" in out
    assert "p2: S1 → a ?G2" in out


def test_show_sorts_terminals_named_by_digits_that_are_no_decimals(capsys, tmp_path):
    # "²" and "①" are str.isdigit() but not int(): the natural sort raised a ValueError
    path = tmp_path / "digits.psgs"
    path.write_text('psgs D\ncomponent A start S\n  p: S -> "a10" "\u00b2" "\u2460" "a9" "7"\n',
                    encoding="utf-8")
    status, out, _ = run(capsys, "show", str(path))
    assert status == 0
    assert "T (5): 7 a9 a10 ² ①" in out


# ---------------------------------------------------------------- errors
def test_missing_file_is_one_line(capsys, tmp_path):
    status, out, err = run(capsys, "show", str(tmp_path / "nothing.psgs"))
    assert status == 2 and out == ""
    assert len(err.splitlines()) == 1 and "nothing.psgs" in err and "Traceback" not in err


@pytest.mark.parametrize("command", [["show"], ["export"], ["derive", "--enumerate",
                                                             "--max-length", "4"]])
def test_format_errors_are_one_located_line(capsys, tmp_path, command):
    path = tmp_path / "bad.psgs"
    path.write_text("psgs B\ncomponent G start S\n  p: S \"a\"\n", encoding="utf-8")
    status, out, err = run(capsys, command[0], str(path), *command[1:])
    assert status == 2 and out == ""
    assert err.strip().splitlines() == [
        f"psgs: error: {path}:3:8: missing arrow: expected '->' (or '→') after the left-hand "
        f"side, found '\"a\"'"]


def test_binary_file_through_the_installed_command(tmp_path):
    path = tmp_path / "junk.psgs"
    path.write_bytes(bytes(range(256)))
    done = subprocess.run([sys.executable, "-m", "psgs", "derive", str(path)],
                          capture_output=True, text=True)
    assert done.returncode == 2 and done.stdout == ""
    assert len(done.stderr.splitlines()) == 1 and f"{path}:" in done.stderr
    assert "Traceback" not in done.stderr


def test_the_acceptance_command_prints_one_line():
    done = subprocess.run([sys.executable, "-m", "psgs", "derive", "grammars/paper_example.psgs",
                           "--enumerate", "--max-length", "32"], capture_output=True, text=True,
                          cwd=REPO)
    assert (done.returncode, done.stdout, done.stderr) == (0, K1 + "\n", "")


def test_the_console_examples_of_the_docs_print_what_they_say(capsys):
    import re
    import shlex
    checked = 0
    for page in ("format.md", "export.md"):
        text = (REPO / "docs" / page).read_text(encoding="utf-8")
        for block in re.findall(r"```console\n(.*?)```", text, re.S):
            command, _, expected = block.partition("\n")
            argv = shlex.split(command.removeprefix("$ "))
            assert argv[0] == "psgs"
            argv = [str(REPO / a) if a.startswith("grammars/") else a for a in argv[1:]]
            status, out, _ = run(capsys, *argv)
            assert status == 0 and out == expected
            checked += 1
    assert checked >= 1


def test_a_reader_that_goes_away_ends_the_command_quietly():
    """`psgs … | head` must not print a BrokenPipe error or a traceback."""
    command = (f"{sys.executable} -m psgs derive grammars/modes.psgs --enumerate "
               f"--max-length 400 | head -1")
    done = subprocess.run(["bash", "-o", "pipefail", "-c", command], capture_output=True,
                          text=True, cwd=Path(__file__).resolve().parents[2], timeout=60)
    assert done.stdout.strip() == "(bb)"
    assert done.stderr == ""
    # 141 when head closed the pipe while psgs was still writing; 0 when psgs had written all of
    # its output into the pipe's buffer before head exited (a race the command does not control:
    # no pipe broke, and nothing may be printed either way)
    assert done.returncode in (141, 0)


# ---------------------------------------------------------------- usability
def _parsers(parser):
    """``parser`` and every subcommand parser under it."""
    import argparse
    yield parser
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in dict.fromkeys(action.choices.values()):
                yield from _parsers(sub)


def _all_parsers():
    from kinetology.cli import build_parser as kinetology_parser
    from psgs.cli import build_parser as psgs_parser
    return [*_parsers(psgs_parser()), *_parsers(kinetology_parser())]


def test_one_exit_status_table_for_both_commands_in_every_help():
    from psgs._foundation.shell import EXIT_STATUS_HELP
    parsers = _all_parsers()
    assert len(parsers) >= 12  # psgs: 7 commands + bench noise; kinetology: 5 commands
    for parser in parsers:
        assert parser.format_help().rstrip().endswith(EXIT_STATUS_HELP.splitlines()[-1]), \
            parser.prog
    # and the docs page holds the same statuses
    page = (REPO / "docs" / "cli.md").read_text(encoding="utf-8")
    for line in EXIT_STATUS_HELP.splitlines()[1:]:
        code = line.split()[0]
        if code.isdigit():
            assert f"| {code} |" in page, code


def test_every_option_of_every_subcommand_has_a_line_of_help():
    for parser in _all_parsers():
        for action in parser._actions:
            if action.help is None or not action.help.strip():
                raise AssertionError(f"{parser.prog}: {action.option_strings or action.dest} "
                                     f"has no help")


@pytest.mark.parametrize("module", ["psgs", "kinetology"])
def test_version_and_python_m(module):
    done = subprocess.run([sys.executable, "-m", module, "--version"], capture_output=True,
                          text=True, timeout=60)
    # one version lookup for every command (kinetology ships in the psgs distribution)
    expected = psgs.__version__
    assert done.returncode == 0 and done.stdout.strip() == f"{module} {expected}"
    helped = subprocess.run([sys.executable, "-m", module, "--help"], capture_output=True,
                            text=True, timeout=60)
    assert helped.returncode == 0 and "exit status" in helped.stdout and helped.stderr == ""


def test_examples_are_shipped_in_the_package_and_found_by_name(capsys, tmp_path, monkeypatch):
    from psgs.cli._types import example_names
    package = Path(psgs.__file__).parent / "grammars"
    assert "paper_example" in example_names()
    assert (REPO / "grammars").resolve() == package.resolve()  # one copy, grammars/ links it
    monkeypatch.chdir(tmp_path)  # no grammars/ here: the name finds the package's copy
    status, out, err = run(capsys, "show", "paper_example")
    assert status == 0 and "a PSGS with 4 components" in out.splitlines()[0], out
    assert run(capsys, "check", "counting.psgs", "aa", "bb")[0] == 0
    status, _, err = run(capsys, "show", "no_such_example")
    assert status == 2 and "paper_example" in err and len(err.splitlines()) == 1


def test_a_nonterminal_without_rules_is_a_warning_and_enumerate_says_no(capsys, tmp_path):
    path = tmp_path / "dead.psgs"
    path.write_text('psgs D\ncomponent G start S\n  p: S -> "a" A\n', encoding="utf-8")
    status, out, err = run(capsys, "derive", str(path), "--enumerate", "--max-length", "4")
    assert (status, out) == (1, "")
    lines = err.splitlines()
    assert "nonterminal A of component G has no rule" in lines[0]
    assert lines[1] == "psgs: no word up to length 4"
    status, out, err = run(capsys, "show", str(path))
    assert status == 0 and "has no rule" in err


def test_in_a_pcgs_a_rule_in_any_component_rewrites_a_nonterminal():
    from psgs.cli.core import rule_less_nonterminals
    text = ('pcgs P\nreturning no\nmaster G2\ncomponent G1 start S1\n  p1: S1 -> "a" A\n'
            'component G2 start S2\n  q1: S2 -> ?G1\n  q2: A -> "b"{extra}\n')
    assert rule_less_nonterminals(psgs.loads(text.format(extra=""))) == []
    dead = psgs.loads(text.format(extra=' B'))
    assert rule_less_nonterminals(dead) == [("G2", "B")]


def test_a_built_wheel_ships_the_example_grammars_and_the_metadata(tmp_path):
    import zipfile
    # the backend installed with the test extra, so no download at test time; the build
    # writes only into tmp_path (a copy of the sources), never into the checkout
    source = tmp_path / "src"
    import shutil
    shutil.copytree(REPO, source, symlinks=True,
                    ignore=shutil.ignore_patterns(".git", ".venv*", "__pycache__", "build",
                                                  "*.egg-info", ".hypothesis", "out"))
    done = subprocess.run([sys.executable, "-m", "pip", "wheel", str(source), "--no-deps",
                           "--no-build-isolation", "-q", "-w", str(tmp_path / "dist")],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    (wheel,) = (tmp_path / "dist").glob("psgs-*.whl")
    with zipfile.ZipFile(wheel) as archive:
        names = set(archive.namelist())
        metadata = archive.read(f"psgs-{psgs.__version__}.dist-info/METADATA").decode()
    shipped = {n.rsplit("/", 1)[1] for n in names if n.startswith("psgs/grammars/")}
    assert shipped == {p.name for p in (REPO / "psgs" / "grammars").glob("*.psgs")}
    assert "paper_example.psgs" in shipped and "psgs/format.lark" in names
    assert "kinetology/__main__.py" in names
    assert "License-Expression: MIT" in metadata and "Author: the psgs developers" in metadata
    # typed packages (PEP 561), the viewer's script, no placeholder address
    assert {"psgs/py.typed", "kinetology/py.typed", "praxicon/py.typed",
            "kinetology/viewer.js"} <= names
    assert "Classifier: Typing :: Typed" in metadata and "Project-URL" not in metadata
    assert "Provides-Extra: all" in metadata


@pytest.mark.parametrize("error, status, words", [(RecursionError, 2, "nests too deeply"),
                                                 (MemoryError, 3, "out of memory")])
def test_resource_limits_are_one_line_not_a_traceback(capsys, monkeypatch, error, status, words):
    import psgs.cli.core as core
    from kinetology import cli as kinetology_cli
    from kinetology._commands import segment as segment_command

    def fail(*args, **kwargs):
        raise error()
    monkeypatch.setattr(core, "run_show", fail)  # registered when main() builds the parser
    assert main(["show", "counting"]) == status
    err = capsys.readouterr().err
    assert words in err and len(err.splitlines()) == 1
    monkeypatch.setattr(segment_command, "read_motion", fail)  # where segment reads its takes
    assert kinetology_cli.main(["segment", "x.bvh"]) == status
    err = capsys.readouterr().err
    assert words in err and len(err.splitlines()) == 1


def test_draw_says_when_the_derivation_it_draws_did_not_end(tmp_path, capsys):
    # a blocked derivation's trees were drawn unfinished without a word, and a nonterminal
    # without a rule was not warned of, as show and derive warn of it
    path = tmp_path / "stuck.psgs"
    path.write_text('psgs Stuck\nmode parallel\ncomponent G start S\n  p: S -> "a" X\n',
                    encoding="utf-8")
    status, out, err = run(capsys, "draw", str(path), "-o", str(tmp_path / "s.svg"),
                           "--engine", "matplotlib")
    assert status == 0 and out.strip() == f"{tmp_path / 's.svg'} (matplotlib)"
    assert err.splitlines() == [
        f"psgs: warning: {path}: nonterminal X of component G has no rule, so a form holding "
        f"it never becomes terminal",
        "psgs: note: the derivation drawn (seed 0) is blocked; its parse trees are unfinished"]
    status, _, err = run(capsys, "draw", "paper_example", "-o", str(tmp_path / "g.svg"),
                         "--engine", "matplotlib")
    assert status == 0 and err == ""


def test_draw_derives_the_word_it_draws_once(tmp_path, capsys, monkeypatch):
    # the note on an unfinished derivation came from a second derivation of the same seed
    import psgs.derivation as derivation

    made = []
    real = derivation.random_derivation

    def counted(*args, **kwargs):
        made.append(args)
        return real(*args, **kwargs)
    monkeypatch.setattr(derivation, "random_derivation", counted)
    status, _, _ = run(capsys, "draw", "paper_example", "-o", str(tmp_path / "g.svg"),
                       "--engine", "matplotlib", "--seed", "3")
    assert status == 0 and len(made) == 1


@pytest.mark.parametrize("bounds", [{}, {"max_nodes": 20}, {"max_steps": 3}])
def test_draw_builds_the_trees_it_draws_once(tmp_path, capsys, monkeypatch, bounds):
    # the trees were built for the picture, then again for what stopped them
    import psgs.draw as draw

    built = []
    real = draw.parse_forest

    def counted(*args, **kwargs):
        built.append(real(*args, **kwargs))
        return built[-1]
    monkeypatch.setattr(draw, "parse_forest", counted)
    argv = [f"--{k.replace('_', '-')}={v}" for k, v in bounds.items()]
    status, _, err = run(capsys, "draw", "paper_example", "-o", str(tmp_path / "g.svg"),
                         "--engine", "matplotlib", "--seed", "3", *argv)
    assert len(built) == 1 and status == (3 if bounds else 0)
    assert err.startswith(f"psgs: the {'picture' if 'max_nodes' in bounds else 'derivation'}"
                          if bounds else "")
    # the picture of those trees, as the library draws them
    monkeypatch.undo()
    drawn = draw.to_svg(psgs.load(GAMMA), seed=3, engine="matplotlib",
                        **{"max_nodes": draw.MAX_NODES, **bounds})
    assert (tmp_path / "g.svg").read_text() == drawn


def test_draw_draws_the_trees_it_is_given(tmp_path):
    from psgs.derivation import random_derivation
    from psgs.draw import parse_forest, to_svg

    gamma, counting = psgs.load(GAMMA), psgs.load("counting")
    cut = parse_forest(gamma, seed=5, max_nodes=30)
    assert cut.bound == "max_nodes"
    assert to_svg(gamma, forest=cut, engine="matplotlib") == \
        to_svg(gamma, seed=5, max_nodes=30, engine="matplotlib")
    # the same components and axioms, another rule's label and terminal: not its trees either
    renamed = psgs.loads(psgs.dumps(counting).replace("p1", "r9")
                         .replace('"a"', '"zz"'))
    with pytest.raises(psgs.ValidationError, match="the parse trees of another system"):
        to_svg(renamed, forest=parse_forest(counting, seed=2), engine="matplotlib")
    assert to_svg(counting, forest=parse_forest(counting, seed=2), engine="matplotlib") == \
        to_svg(counting, seed=2, engine="matplotlib")
    refused = [
        (dict(forest=parse_forest(counting)), "the parse trees of another system"),
        (dict(forest=cut, max_nodes=30), "give forest, or the derivation and max_nodes"),
        (dict(forest=cut, derivation=random_derivation(gamma, 5)), "give forest, or"),
        (dict(forest="trees"), "forest must be a Forest, not str")]
    for options, words in refused:
        with pytest.raises(psgs.ValidationError, match=words):
            to_svg(gamma, engine="matplotlib", **options)
    with pytest.raises(psgs.ValidationError, match="a PCGS is drawn without parse trees: "
                                                   "give no forest"):
        to_svg(psgs.load("pcgs_abc"), forest=cut)


def test_draw_takes_the_derivation_it_draws():
    from psgs.derivation import random_derivation
    from psgs.draw import to_svg

    gamma = psgs.load(GAMMA)
    drawn = to_svg(gamma, derivation=random_derivation(gamma, 5), engine="matplotlib")
    assert drawn == to_svg(gamma, seed=5, engine="matplotlib")
    with pytest.raises(psgs.ValidationError, match="a PCGS is drawn without parse trees"):
        to_svg(psgs.load("pcgs_abc"), derivation=random_derivation(gamma, 5))


def test_export_and_derive_refuse_what_they_used_to_take_in_silence(capsys, tmp_path):
    afile = tmp_path / "afile"
    afile.write_text("mine")
    for argv, words in ((["export", "counting", "-o", ""], "-o needs a folder name"),
                        (["export", "counting", "-o", str(afile)],
                         "a file, not a folder for the .lark files")):
        status, out, err = run(capsys, *argv)
        assert status == 2 and not out and words in err, (argv, err)
    assert afile.read_text() == "mine"
    with pytest.raises(SystemExit) as stop:  # a usage error, as draw's --seed -1 is
        main(["derive", "counting", "--random", "--seed", "-1"])
    assert stop.value.code == 2 and "--seed: -1 is negative" in capsys.readouterr().err


@pytest.mark.parametrize("value, words", [("-1", "-1 is negative"),
                                          ("nan", "'nan' is not a finite number")])
def test_check_max_errors_is_a_usage_error_in_the_option_s_words(capsys, value, words):
    # it was the library's message, 'max_errors must be a finite number ≥ 0 or None'
    with pytest.raises(SystemExit) as stop:
        main(["check", "counting", "a a", "b b", "--nearest", "--max-errors", value])
    assert stop.value.code == 2 and f"argument --max-errors: {words}" in capsys.readouterr().err
