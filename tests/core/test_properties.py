"""The project's property suite, built on psgs.strategies (both rewriting modes)."""

from __future__ import annotations

import itertools

import pytest
from hypothesis import HealthCheck, assume, given, settings, strategies as st

import psgs.strategies as pst
from psgs.enumeration import language
from psgs.membership import accepts
from psgs.model import PCGS, Query, Terminal

from test_membership import gamma

ALPHABET = ("a", "b")
MAX_TOTAL = 4
PROPERTY = settings(max_examples=40, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


def all_tuples(components: int, max_total: int):
    """Every tuple of words over ALPHABET with total length ≤ max_total."""
    words_by_length = [[tuple(w) for w in itertools.product(ALPHABET, repeat=n)]
                       for n in range(max_total + 1)]
    for lengths in itertools.product(range(max_total + 1), repeat=components):
        if sum(lengths) <= max_total:
            yield from itertools.product(*(words_by_length[n] for n in lengths))


@pytest.mark.parametrize("mode", ["parallel", "single"])
def test_accepts_agrees_with_enumeration(mode):
    """Differential: accepts vs breadth-first enumeration over configurations (independent)."""
    checked = []

    @PROPERTY
    @given(pst.psgs_systems(max_components=2, mode=mode, max_rules=4, max_rhs=2,
                            alphabet=ALPHABET))
    def check(system):
        lang = language(system, MAX_TOTAL, method="search", max_configurations=5_000)
        assume(lang.complete)
        members = {tuple(tuple(t.name for t in w) for w in ws) for ws in lang.words}
        for words in all_tuples(len(system.components), MAX_TOTAL):
            result = accepts(system, words, max_states=400)
            member = words in members
            assert result.answer == ("yes" if member else "no"), (words, result)
            if result.answer == "yes":
                assert member, (words, result.witness)
                assert result.witness.words == tuple(tuple(Terminal(x) for x in w)
                                                     for w in words)
        checked.append(len(members))

    check()
    assert len(checked) >= 20, "too few systems could be enumerated completely"
    assert any(checked), "no drawn system had a non-empty language up to the bound"


@PROPERTY
@given(st.sampled_from(["parallel", "single"]), st.data())
def test_every_derived_tuple_of_gamma_is_accepted(mode, data):
    system = gamma(mode)
    words, derivation = data.draw(pst.derivable_words(system, max_steps=26,
                                                      max_form_length=40))
    result = accepts(system, words)
    assert result.answer == "yes"
    assert result.witness.words == words


@PROPERTY
@given(st.sampled_from(["parallel", "single"]), st.data())
def test_near_misses_of_gamma_are_rejected(mode, data):
    system = gamma(mode)
    # L(Γ) is the same in both modes (D5 of docs/semantics.md), so the words are drawn from parallel-mode
    # derivations: listing every single-mode step of Γ (a product of occurrence counts over four
    # components) made this test take over a minute
    words, _ = data.draw(pst.derivable_words(gamma("parallel"), max_steps=26, max_form_length=40))
    edited = data.draw(pst.near_misses(system, words))
    # Γ's words are block repetitions: one edit leaves the language (a candidate in general)
    assert accepts(system, edited).answer == "no"


@PROPERTY
@given(st.data())
def test_projection_is_a_derivation_of_the_component(data):
    system = data.draw(pst.psgs_systems(max_components=3))
    derivation = data.draw(pst.derivations(system, max_steps=12, max_form_length=12))
    for step in derivation.steps:
        for g, rule, where, before, after in zip(system.components, step.tuple, step.positions,
                                                 step.before, step.after):
            if not where:
                assert before == after
                continue
            assert rule in g.rules
            assert all(before[k] == rule.lhs for k in where)
            if system.mode == "single":
                assert len(where) == 1
            else:
                assert list(where) == [k for k, s in enumerate(before) if s == rule.lhs]
            # rewriting the positions one after another with the rule gives the new form
            form = list(before)
            for k in sorted(where, reverse=True):
                form[k:k + 1] = list(rule.rhs)
            assert tuple(form) == after


@PROPERTY
@given(st.data())
def test_an_idle_component_never_changes(data):
    system = data.draw(pst.psgs_systems(min_components=2, max_components=3))
    derivation = data.draw(pst.derivations(system, max_steps=12, max_form_length=12))
    for step in derivation.steps:
        for rule, before, after in zip(step.tuple, step.before, step.after):
            if rule is None:
                assert before == after


@PROPERTY
@given(st.data())
def test_returning_mode_restarts_a_queried_component(data):
    system = data.draw(pst.pcgs_systems(min_components=2, returning=True))
    derivation = data.draw(pst.derivations(system, max_steps=12, max_form_length=12))
    communications = 0
    for step in derivation.steps:
        if step.kind != "communicate":
            continue
        communications += 1
        queried = {system.index(step.before[i][k].component)
                   for i, where in enumerate(step.positions) for k in where}
        for j in queried:
            assert step.after[j] == (system.components[j].start,)
            assert isinstance(step.before[j], tuple)
        for i, where in enumerate(step.positions):
            assert all(isinstance(step.before[i][k], Query) for k in where)
    assert isinstance(system, PCGS)
