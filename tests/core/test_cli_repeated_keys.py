"""A ``K=V`` option given twice with one key (``--param seeds=3 --param seeds=5``) is a usage
error naming the key, not the last value taken in silence."""

from __future__ import annotations

import argparse

import pytest

from psgs._foundation.shell import key_values
from psgs.cli import build_parser, main
from psgs.errors import ValidationError

# every command with a repeatable K=V option, each option given twice with the key "seeds"
CASES = {
    ("induce", "--param"): ["induce", "--example"],
    ("locate", "--param"): ["locate", "a.actiongram", "--learn", "b.actiongram"],
    ("praxicon build", "--param"): ["praxicon", "build", "d", "-o", "px"],
    ("praxicon build", "--segment"): ["praxicon", "build", "d", "-o", "px"],
}


def _key_value_options(parser: argparse.ArgumentParser, path: str = ""):
    """(command, option) of every option whose metavar is K=V, through every subcommand."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _key_value_options(sub, f"{path} {name}".strip())
        elif action.metavar == "K=V":
            yield path, max(action.option_strings, key=len)


def test_every_key_value_option_is_covered_here():
    # a new K=V option without a case below would not be checked
    assert set(_key_value_options(build_parser())) == set(CASES)


@pytest.mark.parametrize("command, option", sorted(CASES))
def test_a_key_given_twice_is_one_line_naming_it(command, option, capsys):
    argv = CASES[command, option] + [option, "seeds=3", option, " seeds = 5"]
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err == (f"psgs: error: {option} seeds is given twice (seeds=3, then "
                            f"seeds=5): give each key once\n")


def test_different_keys_and_one_key_once_are_still_read():
    assert key_values(["a=1", "b=x", "c = 2.5"]) == {"a": 1, "b": "x", "c": 2.5}
    with pytest.raises(ValidationError, match="--segment a is given twice"):
        key_values(["a=1", "b=2", "a=1"], "--segment")  # the same value twice too


def test_induce_still_takes_its_parameters_once_each(capsys):
    assert main(["induce", "--example", "--inducer", "sequential", "--param", "min_count=3",
                 "--param", "max_rules=100000"]) == 0
    assert "sequential:" in capsys.readouterr().out
