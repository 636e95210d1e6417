"""docs/kinetology.md: its Python examples run and print what their comments say, and its
console example shows what the command writes."""

from __future__ import annotations

import ast
import re

from kinetology.cli import main

from kinetology_fixtures import REPO, needs_mocap

PAGE = REPO / "docs" / "kinetology.md"


def _blocks(kind: str) -> list[str]:
    return re.findall(rf"```{kind}\n(.*?)```", PAGE.read_text(), flags=re.S)


def _expected(comment: str):
    """A comment's claim: a Python literal, or text with ``...`` standing for anything."""
    try:
        return ast.literal_eval(comment)
    except (ValueError, SyntaxError):
        if "..." in comment:
            return re.compile(".*".join(re.escape(part) for part in comment.split("...")))
        return None


@needs_mocap
def test_python_examples_run_and_print_what_they_claim(monkeypatch, capsys):
    monkeypatch.chdir(REPO)  # the examples name the data as ../shared/...
    namespace: dict = {}
    checked = 0
    for block in _blocks("python"):
        exec(compile(block, str(PAGE), "exec"), namespace)
        for line in block.splitlines():
            match = re.match(r"print\((.*)\)\s+#\s+(.*)$", line)
            if not match or (expected := _expected(match.group(2))) is None:
                continue
            value = eval(match.group(1), namespace)
            if isinstance(expected, re.Pattern):
                assert expected.fullmatch(str(value)), (line, str(value))
            else:
                assert value == expected, (line, value)
            checked += 1
    capsys.readouterr()
    assert checked >= 3  # the walk's repr, its first channels, the knee's first states


@needs_mocap
def test_console_segment_example_matches_the_command(tmp_path):
    block = next(b for b in _blocks("console") if "$ cut -c1-100 walk.actiongram" in b)
    shown = block.split("$ cut -c1-100 walk.actiongram\n", 1)[1].splitlines()
    out = tmp_path / "walk.actiongram"
    assert main(["segment", str(REPO.parent / "shared/data/mocap/cmu-subject02/02_01.amc"),
                 "--channels", "lfemur.rx", "ltibia.rx", "-o", str(out)]) == 0
    assert [line[:100] for line in out.read_text().splitlines()] == shown


def test_page_names_only_committed_scripts():
    scripts = set(re.findall(r"python (benchmarks/\w+\.py)", PAGE.read_text()))
    assert scripts >= {"benchmarks/compression.py", "benchmarks/kinetology_eval.py"}
    for script in scripts:
        assert (REPO / script).is_file(), script
