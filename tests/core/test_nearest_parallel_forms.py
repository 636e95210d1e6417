"""Parallel-mode distance on grammars that multiply a nonterminal (``S → S S``): the form search.

In parallel mode the occurrences of a nonterminal derive one word, but with edits each lines
up against its own piece of the input, so the span search chose a split per occurrence and
ran out of time on ``S → S S | a`` (the words ``a^(2^k)``) at ``a^48`` and ``a^64``. The form
search (:mod:`psgs.membership.parallel_distance`) walks the forms themselves, cheapest lower
bound first. The property test compares its distances with the least edit distance to every
tuple of the enumerated language (``psgs.language``, the engine's own steps), where the
enumeration is complete and reaches far enough to be exact.
"""

from __future__ import annotations

import time

import pytest
from hypothesis import HealthCheck, assume, given, settings, strategies as st
from test_membership_parallel_words import DOUBLING, parallel_systems
from test_nearest import check_witness

import psgs
from psgs import PSGS, Grammar, Nonterminal as N, Rule, Terminal as T
from psgs.enumeration import language
from psgs.membership.chart import CompiledGrammar
from psgs.membership.costs import edit_costs
from psgs.membership.nearest import _edit_distance
from psgs.membership.parallel_distance import multiplies

S = N("S")
a = T("a")


def doubling_distance(n: int) -> int:
    """The distance of a^n to the words a^(2^k) (k ≥ 0): to the nearest power of two."""
    return min(abs(n - 2 ** k) for k in range(n.bit_length() + 2))


def check_answer(system, words, result, costs=None):
    """The witness derives the nearest words; the edit scripts turn the input into them."""
    check_witness(words, result, edit_costs(costs))


@pytest.mark.parametrize("n, expected", [(64, 0), (48, 16), (100, 28), (1, 0), (3, 1), (0, 1)])
def test_the_doubling_grammar_is_answered_at_once(n, expected):
    assert doubling_distance(n) == expected  # the brute force: a^100 is 28 from a^128
    # this thread's CPU seconds: a loaded machine stretches wall time, not the work done
    start = time.thread_time()
    result = psgs.nearest(DOUBLING, ["a" * n], max_seconds=5)
    seconds = time.thread_time() - start
    assert result.exact and result.distance == expected, result
    assert seconds < 1.0, seconds
    word = result.words[0]
    assert set(word) == {a} and abs(len(word) - n) == expected
    assert len(word) & (len(word) - 1) == 0  # a power of two
    check_answer(DOUBLING, (tuple(a for _ in range(n)),), result)


def test_single_mode_keeps_its_distances():
    import dataclasses

    single = dataclasses.replace(DOUBLING, mode="single")  # a⁺, context-free
    for n in (0, 3, 48):
        assert psgs.nearest(single, ["a" * n]).distance == (1 if n == 0 else 0)


def test_epsilon_doubling():
    # S → S S | a | ε, parallel: ε and a^(2^k); aaa is one edit from aa and from aaaa
    piling = PSGS((Grammar("G", S, [Rule("r1", S, (S, S)), Rule("r2", S, (a,)),
                                    Rule("r3", S, ())]),), mode="parallel")
    for n, expected in [(0, 0), (3, 1), (6, 2), (12, 4), (13, 3)]:
        result = psgs.nearest(piling, ["a" * n], max_seconds=5)
        assert result.exact and result.distance == expected, (n, result)
        check_answer(piling, (tuple(a for _ in range(n)),), result)


def test_each_occurrence_lines_up_with_its_own_piece():
    # S → S S | a | b: the S's of a form derive one word, so the words are a^(2^k) and
    # b^(2^k), not the words of a⁺ or b⁺ alone, nor their mixtures: abab is 2 from aaaa,
    # bbbb and aa, though each of its letters alone is in the component's language
    letters = PSGS((Grammar("G", S, [Rule("p", S, (S, S)), Rule("q", S, (a,)),
                                     Rule("r", S, (T("b"),))]),), mode="parallel")
    for word, expected in [("abab", 2), ("aaab", 1), ("ab", 1), ("bbbbbbbb", 0), ("bbbbbbba", 1)]:
        result = psgs.nearest(letters, [word], max_seconds=5)
        assert result.exact and result.distance == expected, (word, result)
        check_answer(letters, (tuple(T(x) for x in word),), result)


def test_a_doubling_nullable_beside_another_component():
    # G1's S1 → S1 S1 doubles for free while G0 is still far: the forms S1^(2^k) all derive ε
    # at the same cost, and the search made one for each k until a budget ran out (so did the
    # span search). Once S1 occurs too often for any other word, it leaves the form.
    s0, s1, b = N("S0"), N("S1"), T("b")
    g0 = Grammar("G0", s0, [Rule("d0", s0, (s0, s0)), Rule("a0", s0, (a,)), Rule("b0", s0, (b,))])
    g1 = Grammar("G1", s1, [Rule("d1", s1, (s1, s1)), Rule("e1", s1, ()), Rule("b1", s1, (b,))])
    system = PSGS((g0, g1), mode="parallel")
    # the words: (x^(2^k), ε or b^(2^j)) for x = a, b; the oracle over those up to length 16
    firsts = [(x,) * 2 ** k for x in (a, b) for k in range(5)]
    seconds = [()] + [(b,) * 2 ** k for k in range(5)]
    for words in (["ab", "zz"], ["abab", "z"], ["aab", "bbb"], ["bbbbbbbbz", "zbzb"]):
        given = tuple(tuple(T(x) for x in w) for w in words)
        table = edit_costs(None)
        expected = min(_edit_distance(given[0], u, table) for u in firsts) + \
            min(_edit_distance(given[1], u, table) for u in seconds)
        start = time.thread_time()
        result = psgs.nearest(system, words, max_seconds=5)
        assert time.thread_time() - start < 1.0
        assert result.exact and result.distance == expected, (words, result)
        check_answer(system, given, result)


def test_max_errors():
    far = psgs.nearest(DOUBLING, ["a" * 48], max_errors=10)
    assert far.distance is None and far.bound == "max_errors" and far.lower_bound > 10
    within = psgs.nearest(DOUBLING, ["a" * 48], max_errors=16)
    assert within.exact and within.distance == 16


def test_budgets_name_the_bound_they_hit():
    # S → S S | a | b over a word of alternating letters: every power of a letter is far
    letters = PSGS((Grammar("G", S, [Rule("p", S, (S, S)), Rule("q", S, (a,)),
                                     Rule("r", S, (T("b"),)), Rule("s", S, (T("b"), S))]),),
                   mode="parallel")
    word = ["ab" * 12]
    states = psgs.nearest(letters, word, max_states=3)
    assert not states.exact and states.bound == "max_states", states
    assert "max_states=3" in states.reason
    symbols = psgs.nearest(letters, word, max_symbols=40)
    assert not symbols.exact and symbols.bound == "max_symbols", symbols
    start = time.thread_time()
    seconds = psgs.nearest(letters, ["ab" * 400], max_seconds=0.2)
    assert time.thread_time() - start < 1.5
    assert not seconds.exact and seconds.bound == "max_seconds", seconds


# ------------------------------------------------------------------ property: vs enumeration
INPUT = (a, T("b"), T("z"))  # z is in no system: it is deleted or substituted
#: The longest total length enumerated (as in test_membership_parallel_words)
LONGEST = {1: 8, 2: 6}
PROPERTY = settings(max_examples=80, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


def test_parallel_distances_agree_with_enumeration():
    checked = []
    enumerated: dict = {}

    @PROPERTY
    @given(parallel_systems(), st.data())
    def check(system, data):
        longest = LONGEST[len(system.components)]
        words = tuple(tuple(data.draw(st.lists(st.sampled_from(INPUT), max_size=4)))
                      for _ in system.components)
        costs = data.draw(st.sampled_from([None, None, {"insert": 2, "delete": 1,
                                                        "substitute": 1.5}]))
        table = edit_costs(costs)
        lang = enumerated.get(system)
        if lang is None:  # hypothesis draws a system many times over, with other inputs
            lang = enumerated[system] = language(system, longest, method="search",
                                                 max_configurations=4_000, max_form_length=64)
        assume(lang.complete)  # where the enumeration is complete it is exact
        expected = min((sum(_edit_distance(w, u, table) for w, u in zip(words, member))
                        for member in lang.words), default=None)
        # a tuple longer than the enumeration bound needs at least this many insertions
        floor = (longest + 1 - sum(map(len, words))) * table.insert
        assume(expected is not None and expected <= floor)
        result = psgs.nearest(system, words, costs=costs, max_states=20_000, max_seconds=5)
        assert result.exact and result.distance == pytest.approx(expected), (words, result)
        check_answer(system, words, result, costs)
        ids = {t: k for k, t in enumerate(sorted(system.terminals))}
        checked.append((expected, any(multiplies(CompiledGrammar(g, ids))
                                      for g in system.components)))

    check()
    # enough drawn systems multiplied a nonterminal (the form search), with edits to make
    forms = [d for d, multiplying in checked if multiplying]
    assert len(forms) >= 25 and sum(1 for d in forms if d > 0) >= 10, checked
