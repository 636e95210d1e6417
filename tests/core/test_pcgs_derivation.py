"""PCGS derivations: communication priority, returning vs non-returning, blocking, languages."""

from __future__ import annotations

import dataclasses

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import PCGS, Grammar, Nonterminal, Query, Rule, Terminal, ValidationError
from psgs.derivation import (Derivation, applicable_steps, apply_tuple, communication_step,
                             initial_configuration, random_derivation)
from psgs.enumeration import language

S1, S2, S3 = Nonterminal("S1"), Nonterminal("S2"), Nonterminal("S3")
X, Y, Z, B = Nonterminal("X"), Nonterminal("Y"), Nonterminal("Z"), Nonterminal("B")
a, b, c = Terminal("a"), Terminal("b"), Terminal("c")
Q1, Q2, Q3 = Query("G1"), Query("G2"), Query("G3")


def w(text: str):
    return tuple(Terminal(ch) for ch in text)


def anbncn(returning: bool = True) -> PCGS:
    """Centralised: the master counts a's while G2, G3 grow b's and c's in step; {aⁿbⁿcⁿ}."""
    g1 = Grammar("G1", S1, [Rule("m1", S1, (a, S1)), Rule("m2", S1, (a, Q2)),
                            Rule("m3", X, (Q3,)), Rule("m4", Y, ())])
    g2 = Grammar("G2", S2, [Rule("b1", S2, (b, X)), Rule("b2", X, (b, X))])
    g3 = Grammar("G3", S3, [Rule("c1", S3, (Y,)), Rule("c2", Y, (c, Y))])
    return PCGS((g1, g2, g3), returning=returning, name="anbncn")


def asks_twice(returning: bool) -> PCGS:
    """The master asks G2 again and again: returning gives aⁿ, non-returning triangular counts."""
    g1 = Grammar("G1", S1, [Rule("m1", S1, (Q2,)), Rule("m2", Z, (Q2,)), Rule("m3", Z, ())])
    g2 = Grammar("G2", S2, [Rule("g1", S2, (a, Z)), Rule("g2", Z, (a, Z))])
    return PCGS((g1, g2), returning=returning)


def test_anbncn_language():
    for returning in (True, False):
        lang = language(anbncn(returning), 12)
        assert lang.complete, lang.bound
        assert list(lang) == [w("a" * n + "b" * n + "c" * n) for n in (1, 2, 3, 4)]
    assert anbncn().centralised


def test_returning_and_non_returning_languages_differ():
    returning = language(asks_twice(True), 10)
    non_returning = language(asks_twice(False), 10)
    assert returning.complete and non_returning.complete
    assert [len(x) for x in returning] == list(range(1, 11))
    assert [len(x) for x in non_returning] == [1, 3, 6, 10]
    assert all(set(x) == {a} for x in returning.words + non_returning.words)


def test_communication_has_priority_and_returning_resets_the_sender():
    system = anbncn(True)
    config = ((a, a, Q2), (b, b, X), (Y,))
    steps = applicable_steps(system, config)
    assert len(steps) == 1 and steps[0].kind == "communicate"
    assert steps[0].after == ((a, a, b, b, X), (S2,), (Y,))
    assert steps[0].positions == ((2,), (), ())
    assert str(steps[0]) == "communicate"
    kept = applicable_steps(dataclasses.replace(system, returning=False), config)
    assert kept[0].after == ((a, a, b, b, X), (b, b, X), (Y,))
    with pytest.raises(ValidationError, match="communication has priority"):
        apply_tuple(system, config, ("m1", "b2", "c2"))
    assert apply_tuple(system, config, "communicate") == steps[0]


def test_a_rewriting_step_rewrites_every_non_terminal_component_once():
    system = anbncn()
    steps = applicable_steps(system, initial_configuration(system))
    assert [s.after for s in steps] == [((a, S1), (b, X), (Y,)), ((a, Q2), (b, X), (Y,))]
    assert all(s.kind == "rewrite" and all(len(p) == 1 for p in s.positions) for s in steps)
    with pytest.raises(ValidationError, match="G2 is not terminal and must rewrite"):
        apply_tuple(system, initial_configuration(system), ("m1", "#", "c1"))


def test_terminal_components_stay_and_others_go_on():
    system = anbncn()
    config = ((a, Y), (b,), (c, Y))  # G2 terminal: it keeps its word (not a reachable state)
    steps = applicable_steps(system, config)
    assert [s.after for s in steps] == [((a,), (b,), (c, c, Y))]
    assert steps[0].tuple[1] is None and steps[0].positions[1] == ()
    # a rule named for a terminal component is skipped and recorded as idle, like the listing
    assert apply_tuple(system, config, ("m4", "b2", "c2")) == steps[0]


def test_a_component_that_cannot_rewrite_blocks_the_system():
    g1 = Grammar("G1", S1, [Rule("m1", S1, (a, S1)), Rule("m2", S1, (a,))])
    g2 = Grammar("G2", S2, [Rule("g1", S2, (B,))])  # B has no rule
    system = PCGS((g1, g2))
    config = apply_tuple(system, initial_configuration(system), ("m1", "g1")).after
    assert config == ((a, S1), (B,))
    assert applicable_steps(system, config) == ()
    assert random_derivation(system, 3).status == "blocked"
    lang = language(system, 5)
    assert lang.complete and list(lang) == [w("a")]  # only before G2 gets stuck


def test_circular_queries_block():
    g1 = Grammar("G1", S1, [Rule("m1", S1, (a, Q2))])
    g2 = Grammar("G2", S2, [Rule("g1", S2, (b, Q1))])
    system = PCGS((g1, g2))
    assert not system.centralised
    config = applicable_steps(system, initial_configuration(system))[0].after
    assert config == ((a, Q2), (b, Q1))
    assert applicable_steps(system, config) == ()
    with pytest.raises(ValidationError, match="blocked"):
        communication_step(system, config)
    lang = language(system, 6)
    assert lang.complete and len(lang) == 0


def test_a_component_waits_while_the_form_it_asks_for_holds_a_query():
    """G1 asks G2, which asks G3: G2 is answered first, G1 in the next communication step."""
    g1 = Grammar("G1", S1, [Rule("m1", S1, (Q2,))])
    g2 = Grammar("G2", S2, [Rule("g1", S2, (b, Q3))])
    g3 = Grammar("G3", S3, [Rule("h1", S3, (c,))])
    system = PCGS((g1, g2, g3), returning=False)
    d = random_derivation(system, 0)
    assert str(d) == "(S1, S2, S3) ⇒ (?G2, b?G3, c) ⇒ (?G2, bc, c) ⇒ (bc, bc, c)"
    assert [s.kind for s in d.steps] == ["rewrite", "communicate", "communicate"]
    assert language(system, 5).words == (w("bc"),)


def test_a_queried_master_restarts_in_returning_mode():
    """Non-centralised: G2 takes the master's word; the master then derives again from S1."""
    g1 = Grammar("G1", S1, [Rule("m1", S1, (a,)), Rule("m2", S1, (b,))])
    g2 = Grammar("G2", S2, [Rule("g1", S2, (Z,)), Rule("g2", Z, (Q1,))])
    system = PCGS((g1, g2), returning=True)
    config = ((a,), (Q1,))
    step = applicable_steps(system, config)[0]
    assert step.after == ((S1,), (a,))
    assert language(system, 3).words == (w("a"), w("b"))


def test_derivation_of_a_pcgs_ends_when_the_master_is_terminal():
    system = anbncn()
    for seed in range(10):
        d = random_derivation(system, seed, max_steps=200)
        assert d.status == "terminal" and d.is_terminal
        n = d.words.count(a)
        assert d.words == w("a" * n + "b" * n + "c" * n)
        assert all(s in applicable_steps(system, s.before) for s in d.steps)
        assert Derivation(system, d.steps) == Derivation(system, d.steps, d.configurations)


@settings(max_examples=30, deadline=None)
@given(data=st.data())
def test_random_pcgs_derivations_only_take_applicable_steps(data):
    from psgs.strategies import pcgs_systems
    system = data.draw(pcgs_systems(max_components=3, max_nonterminals=2, max_rules=4, max_rhs=2))
    d = random_derivation(system, data.draw(st.integers(0, 1000)), max_steps=20,
                          max_form_length=40)
    for step in d.steps:
        options = applicable_steps(system, step.before)
        assert step in options
        if step.kind == "communicate":
            assert options == (step,)  # communication has priority and is deterministic
            if system.returning:
                asked = {system.index(s.component) for f in step.before for s in f
                         if isinstance(s, Query)}
                for j in asked:
                    if step.after[j] != step.before[j]:
                        assert step.after[j] == (system.components[j].start,)
    if d.is_terminal:
        word = d.words
        lang = language(system, len(word), max_configurations=3_000, max_form_length=60)
        if lang.complete:
            assert word in lang.words
        else:
            assert "max_configurations" in lang.bound or "max_form_length" in lang.bound
