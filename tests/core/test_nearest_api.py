"""psgs.nearest: validation, budgets, symbols outside the alphabet, max_errors, PCGS, the CLI."""

from __future__ import annotations

import math
from pathlib import Path

import pytest

import psgs
from psgs.cli import main
from psgs.membership.costs import apply_edits

REPO = Path(__file__).resolve().parents[2]
GAMMA = str(REPO / "grammars" / "paper_example.psgs")
BLOCKS = ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad"]


@pytest.fixture(scope="module")
def gamma():
    return psgs.load(GAMMA)


@pytest.mark.parametrize("kwargs, message", [
    ({"costs": {"insert": -1}}, "insert cost must be a finite number ≥ 0"),
    ({"costs": {"delete": math.inf}}, "delete cost must be a finite number ≥ 0"),
    ({"costs": {"substitute": "one"}}, "substitute cost must be a number"),
    ({"costs": {"swap": 1}}, "unknown key 'swap'"),
    ({"costs": {"pairs": {("a", "b"): -2}}}, "substitution cost of"),
    ({"max_errors": -1}, "max_errors must be a finite number ≥ 0"),
    ({"max_errors": math.nan}, "max_errors must be a finite number ≥ 0"),
    ({"max_states": 0}, "max_states must be a whole number ≥ 1"),
    ({"max_seconds": 0}, "max_seconds must be a positive number"),
    ({"max_symbols": -5}, "max_symbols must be a whole number ≥ 1"),
])
def test_bad_input_is_one_clear_line(gamma, kwargs, message):
    with pytest.raises(psgs.ValidationError) as caught:
        psgs.nearest(gamma, BLOCKS, **kwargs)
    assert message in str(caught.value) and "\n" not in str(caught.value)


def test_the_wrong_number_of_words(gamma):
    with pytest.raises(psgs.ValidationError, match="4 components but 3 words"):
        psgs.nearest(gamma, BLOCKS[:3])


def test_a_symbol_outside_the_alphabet_is_substituted_or_deleted(gamma):
    words = list(BLOCKS)
    words[1] = "bcadXabcd"  # X is no terminal of Γ
    result = psgs.nearest(gamma, [list(w) for w in words])
    assert result.exact and result.distance == 1
    assert [e.op for e in result.edits[1]] == ["delete"]
    assert apply_edits(tuple(psgs.Terminal(x) for x in words[1]), result.edits[1]) == \
        result.words[1]


def test_costs_change_the_choice(gamma):
    words = list(BLOCKS)
    words[0] = "abcdbcd"  # the 'a' before the last 'd' is missing
    assert psgs.nearest(gamma, words).distance == 1
    dear = psgs.nearest(gamma, words, costs={"insert": 5})
    # inserting costs 5; deleting all 7 symbols and inserting a block costs far more
    assert dear.exact and dear.distance == 5


def test_max_errors_answers_more_than(gamma):
    words = list(BLOCKS)
    words[2] = "cdab"
    far = psgs.nearest(gamma, words, max_errors=3)
    assert far.distance is None and far.bound == "max_errors" and far.lower_bound > 3
    near = psgs.nearest(gamma, words, max_errors=4)
    assert near.exact and near.distance == 4


def test_a_budget_that_runs_out_says_which(gamma):
    words = [b * 20 for b in BLOCKS]
    words[0] = words[0][:50] + "dd" + words[0][52:]
    words[3] = words[3][3:]
    result = psgs.nearest(gamma, words, max_states=3)
    assert not result.exact and result.bound == "max_states"
    assert result.distance is None or result.distance >= result.lower_bound
    tight = psgs.nearest(gamma, words, max_symbols=5)
    assert not tight.exact and tight.bound == "max_symbols"


def test_distance_zero_for_members_in_both_modes(gamma):
    import dataclasses

    for mode in ("parallel", "single"):
        system = dataclasses.replace(gamma, mode=mode)
        result = psgs.nearest(system, [b * 3 for b in BLOCKS])
        assert result.exact and result.distance == 0 and result.edits == ((),) * 4
        assert result.witness.words == result.words


def test_pcgs_master_word():
    copy = psgs.load(REPO / "grammars" / "pcgs_copy.psgs")
    assert psgs.nearest(copy, "abab").distance == 0
    near = psgs.nearest(copy, "abxb", max_states=2_000)
    assert near.distance == 1 and not near.exact and near.bound == "max_states"
    assert near.witness.words == near.words


def test_cli_nearest(capsys):
    status = main(["check", GAMMA, *BLOCKS[:3], "abcdbxad", "--nearest"])
    out = capsys.readouterr().out
    assert status == 1 and out.startswith("distance 1\n")
    assert "  edit    = = = = = ~ = =" in out and "  nearest a b c d b c a d" in out
    assert main(["check", GAMMA, *BLOCKS, "--nearest"]) == 0
    assert main(["check", GAMMA, *BLOCKS[:3], "ab", "--nearest", "--max-errors", "2"]) == 1
    assert "within max_errors=2" in capsys.readouterr().out
    with pytest.raises(SystemExit) as stop:  # a usage error, in the option's words
        main(["check", GAMMA, *BLOCKS[:3], "ab", "--nearest", "--max-errors", "-2"])
    assert stop.value.code == 2 and "--max-errors: -2 is negative" in capsys.readouterr().err
    assert main(["check", GAMMA, *BLOCKS[:3], "--nearest"]) == 2


def test_a_time_budget_stops_a_long_search(gamma, monkeypatch):
    """The clock is read while the chart and the search work, not only at the end.

    The budget's clock is replaced by one that moves 0.1 s at every reading, so the
    answer does not depend on how fast this machine is: a search that reads its clock
    more than three times on the way must stop at a 0.3 s budget and say so.
    """
    import itertools
    import random
    import time
    import types

    import psgs.budget

    readings = itertools.count()
    monkeypatch.setattr(psgs.budget, "time", types.SimpleNamespace(
        monotonic=lambda: 0.1 * next(readings)))
    # 19,200 symbols with 480 substitutions: an exact answer takes many clock readings
    rng = random.Random(3)
    words = []
    for block in BLOCKS:
        w = list(block * 600)
        for _ in range(120):
            w[rng.randrange(len(w))] = rng.choice("abcd")
        words.append("".join(w))
    # this thread's CPU seconds: a loaded machine stretches wall time, not the work done
    start = time.thread_time()
    result = psgs.nearest(gamma, words, max_seconds=0.3)
    took = time.thread_time() - start
    assert not result.exact and result.bound == "max_seconds" and "0.3 s" in result.reason
    assert took < 3.0


def test_memory_is_bounded_by_max_symbols_for_a_far_word(gamma):
    """Far from the language the chart's caps and rows grow: what it keeps is counted too."""
    result = psgs.nearest(gamma, ["x" * 400] * 4, max_symbols=20_000, max_seconds=20)
    assert not result.exact and result.bound == "max_symbols"
    assert "max_symbols=20000" in result.reason
