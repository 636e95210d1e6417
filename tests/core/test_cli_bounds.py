"""Every command of the formal core that stops a derivation or a search at a bound exits 3
and names the bound on stderr, with what it found still written: ``psgs draw`` (the
derivation's bounds, and the picture's ``--max-nodes``), ``psgs derive --random``'s time
bound, ``psgs derive --enumerate``'s memory bound."""

from __future__ import annotations

import pytest

import psgs
from psgs.cli import main
from psgs.draw import parse_forest

ENDLESS = 'psgs Endless\ncomponent G start S\n  p: S -> "a" S\n'
# parallel mode doubles the form every step: 17 steps were 262,000 nodes, three minutes
DOUBLING = 'psgs Doubling\ncomponent G start S\n  p: S -> S S\n'


def run(capsys, *argv):
    status = main(list(argv))
    out, err = capsys.readouterr()
    return status, out, err


@pytest.fixture
def grammar(tmp_path):
    def write(text: str):
        path = tmp_path / "g.psgs"
        path.write_text(text, encoding="utf-8")
        return str(path)
    return write


def test_draw_of_a_derivation_that_never_ends_exits_3_naming_max_steps(grammar, tmp_path,
                                                                        capsys):
    out_svg = tmp_path / "e.svg"
    status, out, err = run(capsys, "draw", grammar(ENDLESS), "-o", str(out_svg),
                           "--max-steps", "5", "--engine", "matplotlib")
    assert status == 3  # was 0: an unfinished picture looked like a finished one
    assert out.strip() == f"{out_svg} (matplotlib)" and out_svg.read_text().startswith("<?xml")
    assert err == ("psgs: the derivation drawn (seed 0) stopped at its bound max_steps: "
                   "stopped after 5 steps (max_steps); its parse trees are unfinished\n")


def test_draw_stops_the_trees_at_max_nodes_and_says_so(grammar, tmp_path, capsys):
    path = grammar(DOUBLING)
    status, _, err = run(capsys, "draw", path, "-o", str(tmp_path / "d.svg"),
                         "--max-nodes", "40", "--engine", "matplotlib")
    assert status == 3
    assert err.startswith("psgs: the picture stopped at its bound max_nodes: drew the first "
                          "4 of 17 steps: the next would take the parse trees past 40 nodes")
    forest = parse_forest(psgs.load(path), max_nodes=40)
    # 1 + 2 + 4 + 8 + 16 nodes after four steps; the fifth would add 32
    assert len(forest.labels) == 31 and forest.bound == "max_nodes" and not forest.complete


def test_draw_of_a_terminal_derivation_within_the_nodes_exits_0(tmp_path, capsys):
    status, _, err = run(capsys, "draw", "counting", "-o", str(tmp_path / "c.svg"),
                         "--engine", "matplotlib")
    assert status == 0 and err == ""
    forest = parse_forest(psgs.load("counting"), max_nodes=10_000)
    assert forest.complete and forest.bound is None and forest.reason is None


def test_draw_names_its_time_bound(grammar, tmp_path, capsys):
    # a nanosecond has passed before the first step: the time bound, not max_steps, stops it
    status, _, err = run(capsys, "draw", grammar(ENDLESS), "-o", str(tmp_path / "t.svg"),
                         "--max-seconds", "1e-9", "--engine", "matplotlib")
    assert status == 3
    assert "stopped at its bound max_seconds: stopped after 1e-09 seconds, 0 steps" in err


def test_derive_random_has_a_time_bound_and_names_it(grammar, capsys):
    status, out, err = run(capsys, "derive", grammar(ENDLESS), "--max-seconds", "1e-9")
    assert status == 3 and out.strip() == "(S)"
    assert err == ("psgs: the derivation did not finish: stopped after 1e-09 seconds, 0 steps "
                   "(max_seconds)\n")


def test_derive_enumerate_keeps_max_symbols(capsys):
    status, _, err = run(capsys, "derive", "paper_example", "--enumerate", "--max-length",
                         "64", "--max-symbols", "100")
    assert status == 3 and "(max_symbols=100)" in err


def test_random_derivation_checks_and_keeps_max_seconds():
    gamma = psgs.load("paper_example")
    with pytest.raises(psgs.ValidationError, match="max_seconds must be a positive number"):
        psgs.random_derivation(gamma, 1, max_seconds=0)
    unbounded = psgs.random_derivation(gamma, 1, max_seconds=None)
    assert unbounded.is_terminal and unbounded.bound is None
    stopped = psgs.random_derivation(gamma, 1, max_seconds=1e-9)
    assert stopped.bound == "max_seconds" and len(stopped.steps) == 0


def test_parse_forest_refuses_a_bad_max_nodes():
    with pytest.raises(psgs.ValidationError, match="max_nodes must be a whole number"):
        parse_forest(psgs.load("counting"), max_nodes=0)


def test_a_derivation_s_status_does_not_list_every_step(monkeypatch):
    # single mode: one tuple applies at 300 x 300 choices of occurrences; the status asks
    # whether one applies
    import psgs.derivation as derivation

    body = " ".join(["A"] * 300)
    system = psgs.loads(f'psgs Wide\nmode single\ncomponent G1 start S\n  a: S -> {body}\n'
                        f'  b: A -> "a"\ncomponent G2 start T\n  c: T -> {body.replace("A", "B")}'
                        f'\n  d: B -> "b"\nsync\n  (a, c)\n  (b, d)\n')
    opened = psgs.random_derivation(system, 0, max_steps=1)

    def listed(*args):
        raise AssertionError("every step listed")
    monkeypatch.setattr(derivation, "applicable_steps", listed)
    assert opened.status == "open"


# the ε-pile system of docs/membership.md: single mode, (ε, c) is not a member and S → S S piles
# up S's over the empty word without end
PILING = ('psgs Piling\nmode single\ncomponent G1 start S\n  p1: S -> S S\n  p2: S -> "a"\n'
          '  p3: S -> \ncomponent G2 start T\n  q1: T -> "c"\n  q2: T -> "b"\n'
          'sync\n  (p2, q1)\n  (p3, q2)\n')


@pytest.mark.parametrize("nearest", [[], ["--nearest"]])
def test_check_takes_a_memory_bound_and_names_it(grammar, capsys, nearest):
    # ε-occurrences pile up: without --max-symbols only the library's default bound held it
    status, out, err = run(capsys, "check", grammar(PILING), "", "c", "--max-symbols", "20000",
                           *nearest)
    assert status == 3 and out
    assert err.startswith("psgs: the search stopped at its bound max_symbols: ")
    assert "max_symbols=20000" in err and err.count("\n") == 1


def test_enumerate_trace_names_the_bound_that_kept_a_witness_back(capsys, monkeypatch):
    # each witness was a search of its own 30 s, outside --max-seconds, and one that ran out
    # was a line of stdout only, with status 0
    import types

    import psgs.membership as membership

    asked = []

    def unknown(system, words, **budgets):
        asked.append(budgets)
        return types.SimpleNamespace(answer="unknown", witness=None, bound="max_states",
                                     reason="stopped after 2 states (max_states)")
    monkeypatch.setattr(membership, "accepts", unknown)
    status, out, err = run(capsys, "derive", "paper_example", "--enumerate", "--max-length",
                           "32", "--trace", "--max-seconds", "20")
    assert status == 3
    assert "(no derivation found: stopped after 2 states (max_states))" in out
    assert err == ("psgs: no derivation was found for 1 of the words above within the bounds "
                   "(max_states); they are in the language all the same\n")
    assert 0 < asked[0]["max_seconds"] <= 20 and asked[0]["max_symbols"] == 10_000_000


def test_enumerate_trace_searches_no_witness_once_the_time_is_out(capsys, monkeypatch):
    # past the bound each witness still got a millisecond, and thousands of words took
    # seconds each over --max-seconds, with status 0
    import psgs.budget as budget
    import psgs.membership as membership

    def never(*args, **kwargs):
        raise AssertionError("a witness was searched past the bound")
    monkeypatch.setattr(membership, "accepts", never)
    monkeypatch.setattr(budget.Budget, "expired", lambda self: self.deadline is not None)
    status, out, err = run(capsys, "derive", "paper_example", "--enumerate", "--max-length",
                           "32", "--trace", "--max-seconds", "20")
    assert status == 3
    assert "(no derivation searched: stopped at max_seconds)" in out
    assert "(max_seconds)" in err


def test_draw_of_a_derivation_that_ended_says_when_max_nodes_cut_its_trees(tmp_path, capsys):
    # the derivation ends in 9 steps; the picture of it did not, and the status said 0
    status, out, err = run(capsys, "draw", "paper_example", "-o", str(tmp_path / "g.svg"),
                           "--max-nodes", "3", "--engine", "matplotlib")
    assert status == 3 and out
    assert err.startswith("psgs: the picture stopped at its bound max_nodes: ")
    status, out, err = run(capsys, "draw", "paper_example", "-o", str(tmp_path / "h.svg"),
                           "--engine", "matplotlib")
    assert status == 0 and err == ""
