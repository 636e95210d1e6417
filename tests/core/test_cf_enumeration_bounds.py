"""The context-free word enumeration (``context_free_words``, ``language`` of a grammar, the
filter's component words) keeps a time and a memory bound and names the one it hits, also
inside one rule's products; and it is no longer cubic in the length."""

from __future__ import annotations

import time
import tracemalloc

import pytest

from psgs import PSGS, Grammar, Nonterminal as N, Rule, Terminal as T
from psgs.enumeration import WORD_OVERHEAD, context_free_words, language

S, X = N("S"), N("X")
a, b = T("a"), T("b")


def eight_letters() -> Grammar:
    """S -> X X X X X X X X, X -> one of 20 letters: 20^8 words of length 8, all from one
    rule, so the words are built inside one step of the table."""
    letters = [Rule(f"x{k}", X, (T(c),)) for k, c in enumerate("abcdefghijklmnopqrst")]
    return Grammar("G", S, [Rule("s", S, (X,) * 8)] + letters)


def test_the_memory_bound_holds_inside_one_rule_s_products():
    # it was counted nowhere: the products grew until the time ran out (422 MB in 20 s)
    tracemalloc.start()
    try:
        start = time.monotonic()
        rows, bound = context_free_words(eight_letters(), 8, max_symbols=100_000,
                                         max_seconds=10)
        seconds = time.monotonic() - start
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert bound == ("stopped at length 8: the words kept and those being built would hold "
                     "more than 100000 symbols (max_symbols); shorter words are complete")
    assert len(rows) == 8 and rows[1] == frozenset() and seconds < 5
    assert peak < 20e6, peak


def test_the_memory_bound_counts_the_words_kept():
    # a^n b^n: lengths 0, 2, ..., 12 hold 7 words of 42 symbols, 98 with the overhead
    g = Grammar("G", S, [Rule("r1", S, (a, S, b)), Rule("r2", S, ())])
    kept = sum(n + WORD_OVERHEAD for n in range(0, 13, 2))
    rows, bound = context_free_words(g, 40, max_symbols=kept)
    assert len(rows) == 14 and "stopped at length 14" in bound and "max_symbols" in bound
    rows, bound = context_free_words(g, 12, max_symbols=kept)
    assert bound is None and len(rows) == 13


def test_language_names_the_memory_bound_of_a_grammar_and_of_the_filter():
    lang = language(eight_letters(), 8, max_symbols=100_000)
    assert not lang.complete and lang.bound == "max_symbols" and "100000 symbols" in lang.reason
    # the filter's accepts calls get what the component words leave; the system is the ε-pile
    # of docs/membership.md (single mode), whose search on (ε, c) piles up S's without end
    t = N("T")
    g1 = Grammar("G1", S, [Rule("p1", S, (S, S)), Rule("p2", S, (a,)), Rule("p3", S, ())])
    g2 = Grammar("G2", t, [Rule("q1", t, (T("c"),)), Rule("q2", t, (b,))])
    piling = PSGS((g1, g2), (("p2", "q1"), ("p3", "q2")), mode="single")
    lang = language(piling, 3, method="filter", max_symbols=2_000, max_seconds=20)
    assert lang.bound == "max_symbols" and "max_symbols=19" in lang.reason  # 2000 less words
    assert ("", "b") in lang


def test_the_time_bound_is_named_and_kept():
    dyck = Grammar("G", S, [Rule("p", S, (S, S)), Rule("q", S, (a, S, b)), Rule("r", S, ())])
    # this thread's CPU seconds: on a loaded machine the wall time between two readings of the
    # clock stretches (0.86 s seen on CI), and the process's CPU counts other threads of the
    # worker (0.84 s seen late in a suite run), though the enumeration does no more work
    start = time.thread_time()
    rows, bound = context_free_words(dyck, 60, max_seconds=0.5, max_symbols=None)
    seconds = time.thread_time() - start
    assert bound.endswith("after 0.5 seconds (max_seconds); shorter words are complete")
    assert seconds <= 1.1 * 0.5 + 0.25, seconds
    assert [len(r) for r in rows[:9]] == [1, 0, 1, 0, 2, 0, 5, 0, 14]  # Catalan numbers


def test_one_word_a_length_is_quadratic_not_cubic():
    # S -> a S | ε to length 400 took 26 s (every length's words built again at every n,
    # each split of each length tried); now about 0.15 s
    g = Grammar("G", S, [Rule("p", S, (a, S)), Rule("q", S, ())])
    rows, bound = context_free_words(g, 400, max_seconds=5)
    assert bound is None and [len(r) for r in rows] == [1] * 401
    assert rows[400] == frozenset({(a,) * 400})


@pytest.mark.parametrize("bad", [0, -1, 1.5, "10"])
def test_a_bad_memory_bound_is_refused(bad):
    from psgs import ValidationError

    with pytest.raises(ValidationError, match="max_symbols must be a whole number"):
        context_free_words(eight_letters(), 2, max_symbols=bad)
