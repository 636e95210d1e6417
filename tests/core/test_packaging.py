"""The distribution's metadata: the ``all`` extra is every feature extra, and the extras named in
messages exist. (What the built wheel holds is checked in test_cli_core.py, which builds it.)"""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
PROJECT = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]
EXTRAS = PROJECT["optional-dependencies"]
FEATURES = ("fast", "plot", "praxicon", "dask")  # what a user installs; not test, bench, docs


def test_all_is_the_union_of_the_feature_extras():
    union = {r for name in FEATURES for r in EXTRAS[name]}
    assert set(EXTRAS["all"]) == union and len(EXTRAS["all"]) == len(union)
    assert set(EXTRAS) == {*FEATURES, "all", "test", "bench", "docs"}  # a new one is placed


def test_every_extra_a_message_names_exists():
    named = set()
    for path in [*REPO.glob("psgs/**/*.py"), *REPO.glob("kinetology/**/*.py"),
                 *REPO.glob("praxicon/**/*.py"), REPO / "README.md", *REPO.glob("docs/*.md")]:
        named |= set(re.findall(r"psgs\[([a-z,]+)\]", path.read_text(encoding="utf-8")))
    used = {e for group in named for e in group.split(",")}
    assert used and used <= set(EXTRAS), used - set(EXTRAS)


def test_no_placeholder_address_and_the_package_says_it_is_typed():
    assert "urls" not in PROJECT  # no public home yet: no address rather than a false one
    assert "Typing :: Typed" in PROJECT["classifiers"]
    for package in ("psgs", "kinetology", "praxicon"):
        assert (REPO / package / "py.typed").is_file()


def test_every_command_reading_a_grammar_finds_the_shipped_examples_by_name(tmp_path, capsys):
    from psgs.cli import main

    pytest.importorskip("matplotlib", reason="psgs draw without Graphviz draws with matplotlib")
    commands = {"show": [], "derive": ["--seed", "1"], "export": ["-o", str(tmp_path / "lark")],
                "check": ["a", "b", "c", "d"],
                "draw": ["-o", str(tmp_path / "x.svg"), "--engine", "matplotlib"]}
    for command, rest in commands.items():
        status = main([command, "paper_example", *rest])
        err = capsys.readouterr().err
        assert status in (0, 1) and "No such file" not in err, (command, err)
    assert (tmp_path / "x.svg").read_text().startswith("<?xml")
