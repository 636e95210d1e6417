"""psgs.accepts on PCGS: yes with a witness, no only when proved, unknown naming the budget."""

from __future__ import annotations

from pathlib import Path

import pytest
from hypothesis import given, settings, strategies as st

import psgs.strategies as pst
from psgs import PCGS, Grammar, Nonterminal as N, Query, Rule, Terminal as T, as_word
from psgs.enumeration import language
from psgs.membership import accepts

REPO = Path(__file__).resolve().parents[2]


def abc_in_python(returning: bool = True) -> PCGS:
    """{aⁿbⁿcⁿ}: the master writes a's, G2 writes b…c around S2, the master fetches and erases S2."""
    g1 = Grammar("G1", N("S1"), (Rule("m1", N("S1"), (T("a"), N("S1"))),
                                 Rule("m2", N("S1"), (T("a"), Query("G2"))),
                                 Rule("m3", N("S2"), ())))
    g2 = Grammar("G2", N("S2"), (Rule("c1", N("S2"), (T("b"), N("S2"), T("c"))),))
    return PCGS((g1, g2), returning=returning, name="ABC")


def abc_systems():
    systems = [abc_in_python(True), abc_in_python(False)]
    path = REPO / "grammars" / "pcgs_abc.psgs"
    if path.exists():
        from psgs.format import load
        systems.append(load(path))
    return systems


@pytest.mark.parametrize("system", abc_systems(), ids=lambda s: f"{s.name}-{s.returning}")
def test_abc_accepts_a5b5c5_with_a_witness(system):
    word = "a" * 5 + "b" * 5 + "c" * 5
    result = accepts(system, word)
    assert result.answer == "yes"
    assert result.witness.words == as_word(word)
    assert str(result.witness).startswith(f"({', '.join(g.start.name for g in system.components)})")


@pytest.mark.parametrize("system", abc_systems(), ids=lambda s: f"{s.name}-{s.returning}")
def test_abc_rejects_a5b4c5_with_a_proof(system):
    result = accepts(system, "a" * 5 + "b" * 4 + "c" * 5)
    assert result.answer == "no"
    assert "explored" in result.reason
    assert result.bound is None


def test_a_tiny_budget_gives_unknown_naming_it():
    word = "a" * 5 + "b" * 5 + "c" * 5
    states = accepts(abc_in_python(), word, max_states=3)
    assert states.answer == "unknown" and states.bound == "max_states" and not states
    steps = accepts(abc_in_python(), word, max_steps=4)
    assert steps.answer == "unknown" and steps.bound == "max_steps"
    assert "4 steps" in steps.reason


def test_unbounded_non_master_growth_is_unknown_not_no():
    # G2 grows for ever and is never asked: no finite search can prove "b" is not derived
    g1 = Grammar("G1", N("S1"), (Rule("m1", N("S1"), (N("S1"),)), Rule("m2", N("S1"), (T("a"),))))
    g2 = Grammar("G2", N("S2"), (Rule("c1", N("S2"), (T("b"), N("S2"))),))
    system = PCGS((g1, g2))
    assert accepts(system, "a").answer == "yes"
    # the configurations (S1, bᵏS2) never repeat, so the search can only run out of budget
    result = accepts(system, "b", max_states=100)
    assert result.answer == "unknown" and result.bound == "max_states"
    result = accepts(system, "aa", max_states=10_000, max_steps=50)
    assert result.answer == "unknown" and result.bound == "max_steps"
    # a word longer than anything the master can hold is refuted by the length bound alone
    g3 = Grammar("G1", N("S1"), (Rule("m2", N("S1"), (T("a"),)),))
    assert accepts(PCGS((g3, g2)), "aa").answer == "no"


def test_master_reset_by_a_query_disables_pruning_but_stays_right():
    # G2 asks the master for its form; in returning mode the master restarts
    g1 = Grammar("G1", N("S1"), (Rule("m1", N("S1"), (T("a"), N("S1"))),
                                 Rule("m2", N("S1"), (T("b"),))))
    g2 = Grammar("G2", N("S2"), (Rule("c1", N("S2"), (Query("G1"),)),))
    system = PCGS((g1, g2), returning=True)
    lang = language(system, 4, max_configurations=20_000)
    members = set(lang.words)
    assert {"".join(t.name for t in w) for w in members} >= {"b", "ab", "aab", "aaab"}
    for n in range(4):
        for word in ("a" * n + "b", "b" * (n + 1)):
            result = accepts(system, word, max_states=5_000, max_steps=30)
            if as_word(word) in members:
                # reached only by sending the terminal master away and starting again
                assert result.answer == "yes"
                assert result.witness.words == as_word(word)
            else:
                assert result.answer != "yes"


@settings(max_examples=40, deadline=None)
@given(pst.pcgs_systems(max_components=2, max_rules=3, max_rhs=2), st.data())
def test_pcgs_accepts_agrees_with_enumeration(system, data):
    lang = language(system, 3, max_configurations=3_000)
    members = set(lang.words)
    for n in range(4):
        word = tuple(data.draw(st.lists(st.sampled_from([T("a"), T("b")]), min_size=n,
                                        max_size=n)))
        result = accepts(system, word, max_states=3_000, max_steps=12)
        if result.answer == "yes":
            assert result.witness.words == word
            if lang.complete:
                assert word in members
        elif result.answer == "no" and lang.complete:
            assert word not in members
        if lang.complete and word in members:
            assert result.answer in ("yes", "unknown")


def test_a_symbol_no_component_produces_is_a_proved_no():
    # left recursion, a unit cycle and an ever-growing non-returning G2: before, "c" ran the
    # search to max_steps and answered "unknown"
    g1 = Grammar("G1", N("S"), (Rule("p1", N("S"), (N("S"), T("a"))), Rule("p2", N("S"), (N("A"),)),
                                Rule("p3", N("A"), (N("S"),)), Rule("p4", N("S"), (Query("G2"),)),
                                Rule("p5", N("S"), ())))
    g2 = Grammar("G2", N("T"), (Rule("q1", N("T"), (N("T"), T("b"))), Rule("q2", N("T"), ())))
    system = PCGS((g1, g2), returning=False)
    assert accepts(system, "bba", max_seconds=10).answer == "yes"
    result = accepts(system, "c", max_seconds=10)
    assert result.answer == "no", result
    assert "c is a terminal of no component" in result.reason
    for abc in abc_systems():
        assert accepts(abc, "aabxbcc").answer == "no"
