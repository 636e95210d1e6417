"""Language enumeration: order, uniqueness, bounds, and the two PSGS methods cross-checked."""

from __future__ import annotations

import dataclasses

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from psgs import PCGS, PSGS, Grammar, Nonterminal, Rule, Terminal, ValidationError
from psgs.analysis import min_yields
from psgs.enumeration import Language, context_free_words, language

S, A, B = Nonterminal("S"), Nonterminal("A"), Nonterminal("B")
a, b = Terminal("a"), Terminal("b")


def text(word) -> str:
    return "".join(t.name for t in word)


def brute_force_cf(grammar: Grammar, max_length: int, max_forms: int = 200_000) -> set[str]:
    """Leftmost derivations with ε-aware pruning: an independent oracle for small grammars."""
    yields = min_yields(grammar.rules)
    out, seen, todo = set(), set(), [(grammar.start,)]
    while todo:
        form = todo.pop()
        if sum(1 if isinstance(s, Terminal) else yields.get(s, 99) for s in form) > max_length:
            continue
        k = next((i for i, s in enumerate(form) if isinstance(s, Nonterminal)), None)
        if k is None:
            out.add(text(form))
            continue
        for rule in grammar.rules_by_lhs.get(form[k], ()):
            nxt = form[:k] + rule.rhs + form[k + 1:]
            if nxt not in seen and len(nxt) <= 3 * max_length + 6:
                seen.add(nxt)
                todo.append(nxt)
        assert len(seen) < max_forms
    return out


# ---------------------------------------------------------------- a grammar alone
@pytest.mark.parametrize("rules, expected", [
    # left recursion
    ([Rule("r1", S, (S, a)), Rule("r2", S, (b,))], ["b", "ba", "baa", "baaa"]),
    # a unit cycle and ε
    ([Rule("r1", S, (A,)), Rule("r2", A, (S,)), Rule("r3", A, (a, A, b)), Rule("r4", A, ())],
     ["", "ab", "aabb"]),
    # an unproductive nonterminal contributes nothing
    ([Rule("r1", S, (a,)), Rule("r2", S, (B, a)), Rule("r3", B, (B, b))], ["a"]),
])
def test_context_free_words_of_tricky_grammars(rules, expected):
    lang = language(Grammar("G", S, rules), 4)
    assert lang.complete and lang.bound is None and lang.kind == "words"
    assert [text(x) for x in lang] == expected


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_context_free_enumeration_matches_brute_force(data):
    from psgs.strategies import grammars
    g = data.draw(grammars(max_nonterminals=3, max_rules=5, max_rhs=3))
    n = data.draw(st.integers(0, 5))
    lang = language(g, n)
    assert lang.complete
    assert [text(x) for x in lang] == sorted(brute_force_cf(g, n), key=lambda s: (len(s), s))


def test_max_words_stops_honestly_and_keeps_shorter_lengths_complete():
    g = Grammar("G", S, [Rule("r1", S, (a, S)), Rule("r2", S, (b, S)), Rule("r3", S, ())])
    rows, bound = context_free_words(g, 10, max_words=40)
    assert bound and "max_words=40" in bound and "stopped at length" in bound
    assert [len(r) for r in rows] == [2 ** n for n in range(len(rows))]
    lang = language(g, 10, max_words=40)
    assert not lang.complete and lang.reason == bound and lang.bound == "max_words"
    assert len(lang) == sum(2 ** n for n in range(len(rows)))


# ---------------------------------------------------------------- the value
def test_language_is_a_sized_iterable_value_with_membership_by_text():
    g1 = Grammar("G1", Nonterminal("S1"), [Rule("p1", Nonterminal("S1"), (a, Nonterminal("S1"))),
                                           Rule("p2", Nonterminal("S1"), (a,))])
    g2 = Grammar("G2", Nonterminal("S2"), [Rule("q1", Nonterminal("S2"), (b, Nonterminal("S2"))),
                                           Rule("q2", Nonterminal("S2"), (b,))])
    system = PSGS((g1, g2), sync=[("p1", "q1"), ("p2", "q2")], unsynchronised="strict")
    lang = language(system, 6)
    assert isinstance(lang, Language) and len(lang) == 3 and lang.kind == "tuples"
    assert ("aa", "bb") in lang and ("aa", "b") not in lang and "ab" not in lang
    assert [tuple(map(text, t)) for t in lang] == [("a", "b"), ("aa", "bb"), ("aaa", "bbb")]
    with pytest.raises(dataclasses.FrozenInstanceError):
        lang.complete = False  # type: ignore[misc]


def test_bad_arguments_are_named():
    g = Grammar("G", S, [Rule("r1", S, (a,))])
    system = PSGS((g,), sync=[("r1",)])
    with pytest.raises(ValidationError, match="max_length must be"):
        language(system, -1)
    with pytest.raises(ValidationError, match="method must be"):
        language(system, 3, method="magic")
    with pytest.raises(ValidationError, match="max_configurations must be"):
        language(system, 3, max_configurations=0)
    with pytest.raises(ValidationError, match="filter' needs a PSGS"):
        language(PCGS((g,)), 3, method="filter")
    with pytest.raises(ValidationError, match="expected a PSGS, a PCGS or a Grammar"):
        language("S -> a", 3)


# ---------------------------------------------------------------- search vs filter
def _small_systems():
    from psgs.strategies import psgs_systems
    return psgs_systems(max_components=2, max_nonterminals=2, max_rules=4, max_rhs=2,
                        max_tuples=3)


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(system=_small_systems(), max_length=st.integers(0, 5))
def test_search_and_filter_agree(system, max_length):
    search = language(system, max_length, method="search", max_configurations=5_000,
                      max_form_length=40, max_seconds=5)
    filtered = language(system, max_length, method="filter", max_states=20_000, max_seconds=5)
    if search.complete and filtered.complete:
        assert search.words == filtered.words
    else:  # whatever each found is a subset of the other's complete answer, and bounds are named
        assert search.bound or filtered.bound
        if filtered.complete:
            assert set(search.words) <= set(filtered.words)
        if search.complete:
            assert set(filtered.words) <= set(search.words)


def test_methods_agree_on_the_two_readings_of_S_to_AA():
    g = Grammar("G", S, [Rule("r1", S, (A, A)), Rule("r2", A, (a, A)), Rule("r3", A, (b,))])
    for mode in ("parallel", "single"):
        system = PSGS((g,), sync=[], mode=mode)
        search = language(system, 8, method="search")
        filtered = language(system, 8, method="filter")
        assert search.complete and filtered.complete
        assert search.words == filtered.words
    assert len(language(PSGS((g,), mode="parallel"), 8)) == 4
    assert len(language(PSGS((g,), mode="single"), 8)) == sum(k + 1 for k in range(7))


def test_default_method_is_search_in_parallel_and_filter_in_single_mode():
    g = Grammar("G", S, [Rule("r1", S, (a,))])
    assert language(PSGS((g,), mode="parallel"), 2).method == "search"
    assert language(PSGS((g,), mode="single"), 2).method == "filter"


def test_filter_stops_at_max_candidates_and_says_so():
    g = Grammar("G", S, [Rule("r1", S, (a, S)), Rule("r2", S, (b, S)), Rule("r3", S, ())])
    system = PSGS((g, dataclasses.replace(g, name="H")), mode="single")
    lang = language(system, 4, method="filter", max_candidates=10)
    assert not lang.complete
    assert lang.bound == "max_candidates"
    assert lang.reason == "stopped after 10 candidate tuples (max_candidates)"
    assert lang.explored == 10


def test_max_seconds_stops_a_long_search_and_says_so():
    g = Grammar("G", S, [Rule("r1", S, (S, S)), Rule("r2", S, ())])
    lang = language(PSGS((g,), mode="single"), 3, method="search", max_seconds=0.05,
                    max_configurations=10**9, max_form_length=10**6)
    assert not lang.complete and lang.bound == "max_seconds"
    assert lang.reason == "stopped after 0.05 seconds (max_seconds)"
    with pytest.raises(ValidationError, match="max_seconds must be"):
        language(PSGS((g,)), 3, max_seconds=0)
