"""The block-by-block fast path of accepts against the general schedule search.

The fast path only ever answers yes (with a schedule the derivation engine
replays); every other answer comes from the general search. So the judge is:
whenever the fast path finds a yes, the general search says yes too, and the
witness derives the words; on member tuples of Γ the fast path is what
answers (one state per block); where no derivation passes through
synchronisation points the general search still finds the yes.
"""

from __future__ import annotations

import dataclasses

import pytest
from hypothesis import HealthCheck, given, settings, strategies as st

import psgs
from psgs.budget import Budget
from psgs.membership.block_search import lockstep_accepts, lockstep_applies
from psgs.membership.chart import Chart, CompiledGrammar
from psgs.membership.decide import accepts_psgs
from psgs.membership.schedule_search import _Substrings
from psgs.model import IDLE, PSGS, Grammar, Nonterminal as N, Rule, Terminal as T, as_word
from psgs.strategies import derivable_words
from test_membership import gamma

BLOCKS = ("abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad")


def fast_path(system, words, max_states=5_000):
    words = tuple(as_word(w) for w in words)
    ids = {t: k for k, t in enumerate(sorted(system.terminals))}
    compiled = [CompiledGrammar(g, ids) for g in system.components]
    if not lockstep_applies(compiled):
        return "n/a"
    if any(t not in g.terminals for g, w in zip(system.components, words) for t in w):
        return None
    budget = Budget(seconds=10)
    charts = [Chart(cg, [ids[t] for t in w], budget) for cg, w in zip(compiled, words)]
    return lockstep_accepts(system, compiled, charts, [_Substrings(c.word) for c in charts],
                            max_states, budget)


def general(system, words):
    return accepts_psgs(system, tuple(as_word(w) for w in words), 20_000, Budget(seconds=10),
                        fast=False)


# the strategies block_systems() draws from, made once (per component number i): hypothesis
# validates a strategy and works out its properties the first time it draws from it, which for
# strategies made afresh in every example cost more than the drawing (they draw the same)
_LETTERS = st.sampled_from((T("a"), T("b")))
_WORDS = st.lists(_LETTERS, max_size=2)
_A_BODIES = {i: st.lists(st.one_of(_LETTERS, st.just(N(f"B{i}"))), max_size=3) for i in (1, 2, 3)}
_PREFIXES = {i: st.lists(st.sampled_from((T("a"), T("b"), N(f"A{i}"), N(f"B{i}"))), max_size=2)
             for i in (1, 2, 3)}


@st.composite
def block_systems(draw):
    """Small PSGS whose spines are right-linear: S → α S | α, α over a, b and finite A, B."""
    components = []
    for i in range(1, draw(st.integers(1, 3)) + 1):
        s, a, b = N(f"S{i}"), N(f"A{i}"), N(f"B{i}")
        bodies = {(s, (a,))}  # a way out of the spine
        for _ in range(draw(st.integers(1, 2))):
            bodies.add((b, tuple(draw(_WORDS))))
        for _ in range(draw(st.integers(1, 2))):
            bodies.add((a, tuple(draw(_A_BODIES[i]))))
        prefixes = _PREFIXES[i]
        for _ in range(draw(st.integers(1, 3))):
            tail = (s,) if draw(st.booleans()) else ()
            bodies.add((s, tuple(draw(prefixes)) + tail))
        rules = tuple(Rule(f"r{i}_{k}", lhs, rhs) for k, (lhs, rhs) in
                      enumerate(sorted(bodies, key=str)))
        components.append(Grammar(f"G{i}", s, rules))
    tuples = []
    for _ in range(draw(st.integers(1, 5))):
        entry = tuple(draw(st.one_of(st.none(), st.sampled_from(g.rules)))
                      for g in components)
        if any(e is not IDLE for e in entry) and entry not in tuples:
            tuples.append(entry)
    return PSGS(tuple(components), tuple(tuples),
                mode=draw(st.sampled_from(("parallel", "single"))),
                unsynchronised=draw(st.sampled_from(("free", "strict"))))


@settings(max_examples=75, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(block_systems(), st.data())
def test_a_fast_yes_is_a_yes_of_the_general_search(system, data):
    members = data.draw(st.one_of(
        derivable_words(system, max_steps=12, max_form_length=16).map(lambda pair: pair[0]),
        st.tuples(*[st.text("ab", max_size=5) for _ in system.components])))
    found = fast_path(system, members)
    assert found != "n/a"  # every drawn system has right-linear spines
    if found is not None:
        assert found.answer == "yes"
        assert found.witness.words == tuple(as_word(w) for w in members)
        assert general(system, members).answer == "yes"


@pytest.mark.parametrize("mode", ["parallel", "single"])
@pytest.mark.parametrize("k", [1, 2, 7])
def test_gamma_members_are_answered_block_by_block(mode, k):
    system = dataclasses.replace(gamma(), mode=mode)
    words = [b * k for b in BLOCKS]
    found = fast_path(system, words)
    assert found is not None and found.answer == "yes"
    assert found.states <= k + 30  # one point per block, after the first blocks are searched
    assert found.witness.words == tuple(as_word(w) for w in words)
    assert [len(m.rewrites) for m in found.schedule.moves][0] == 4


@pytest.mark.parametrize("mode", ["parallel", "single"])
def test_gamma_non_members_fall_through_to_the_general_search(mode):
    system = dataclasses.replace(gamma(), mode=mode)
    short = [b * 3 for b in BLOCKS[:3]] + [BLOCKS[3] * 2]
    assert fast_path(system, short) is None
    assert psgs.accepts(system, short).answer == "no"


def test_a_derivation_that_never_synchronises_is_found_by_the_general_search():
    # G2's block B is closed by a tuple that also extends G1's spine: no derivation of
    # (aaa, bb) passes through a point where both forms are one spine occurrence
    g1 = Grammar("G1", N("S1"), (Rule("p", N("S1"), (T("a"), N("S1"))),
                                 Rule("q", N("S1"), (T("a"),))))
    g2 = Grammar("G2", N("S2"), (Rule("u", N("S2"), (N("B"), N("S2"))),
                                 Rule("v", N("S2"), (N("B"),)), Rule("w", N("B"), (T("b"),))))
    system = PSGS((g1, g2), (("p", "u"), ("p", "w"), ("q", "v")), unsynchronised="strict")
    for mode in ("parallel", "single"):
        system = dataclasses.replace(system, mode=mode)
        assert fast_path(system, ["aaa", "bb"]) is None
        result = psgs.accepts(system, ["aaa", "bb"], check_witness=True)
        assert result.answer == "yes"
        assert general(system, ["aaa", "bb"]).answer == "yes"


def test_a_component_off_the_spine_is_one_block():
    g1 = Grammar("G1", N("S1"), (Rule("p", N("S1"), (T("a"), N("S1"))),
                                 Rule("q", N("S1"), (T("a"),))))
    g2 = Grammar("G2", N("X"), (Rule("x", N("X"), (N("Y"), N("Y"))),
                                Rule("y", N("Y"), (T("b"),))))
    system = PSGS((g1, g2), ((IDLE, "x"), (IDLE, "y"), ("p", IDLE), ("q", IDLE)),
                  mode="parallel", unsynchronised="strict")
    found = fast_path(system, ["aa", "bb"])
    assert found is not None and found.witness.words == (as_word("aa"), as_word("bb"))
    # the same block closed by a tuple that also rewrites G1's spine: not block by block
    mixed = dataclasses.replace(system, sync=(("p", "x"), ("q", "y")))
    assert fast_path(mixed, ["aa", "bb"]) is None
    assert psgs.accepts(mixed, ["aa", "bb"]).answer == "yes"


def test_the_fast_paths_share_of_max_states_runs_out_into_the_general_search():
    words = [b * 40 for b in BLOCKS]
    assert fast_path(gamma(), words, max_states=5) is None
    assert psgs.accepts(gamma(), words, max_states=5_000).answer == "yes"


@pytest.mark.parametrize("budget, value", [("max_seconds", 0.001), ("max_symbols", 200)])
def test_budgets_hold_on_the_fast_path(budget, value):
    words = [b * 300 for b in BLOCKS]
    result = psgs.accepts(gamma(), words, **{budget: value})
    assert result.answer == "unknown" and result.bound == budget
    assert str(value) in result.reason or f"{value:g}" in result.reason
