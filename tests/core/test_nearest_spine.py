"""The backward pass over a right-linear spine against the top-down error chart.

:func:`psgs.membership.spine_costs.suffix_costs` gives every spine span's
edit cost at once; the top-down chart (its memo emptied) computes the same
costs independently, span by span. They must agree on drawn grammars,
words (with symbols outside the alphabet) and edit costs.
"""

from __future__ import annotations

from hypothesis import HealthCheck, assume, given, settings, strategies as st

import psgs
from psgs.membership.chart import CompiledGrammar
from psgs.membership.error_chart import INF, ErrorChart
from psgs.membership.spine_costs import suffix_costs
from test_membership_fastpath import block_systems

ALPHABET = ("a", "b", "x")  # x is in no grammar


def charts(grammar, word, insert, delete, substitute, alphabet=ALPHABET):
    ids = {psgs.Terminal(t): k for k, t in enumerate(alphabet)}
    cg = CompiledGrammar(grammar, ids)
    ws = [ids[psgs.Terminal(t)] for t in word]

    def sub(p, t):
        return 0.0 if ws[p] == t else substitute

    return cg, ErrorChart(cg, ws, [insert] * len(alphabet), [delete] * len(ws), sub)


@settings(max_examples=60, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])
@given(block_systems(), st.text("abx", max_size=7), st.sampled_from((1.0, 0.5, 2.0)),
       st.sampled_from((1.0, 0.7, 3.0)), st.sampled_from((1.0, 1.5, 0.25)))
def test_suffix_costs_equal_the_top_down_chart(system, word, insert, delete, substitute):
    grammar = system.components[0]
    cg, chart = charts(grammar, word, insert, delete, substitute)
    found = suffix_costs(chart)
    # None: no cycle at all (a finite language), or a rule prefix with too many words
    assume(found is not None)
    chart.memo.clear()
    chart._split_cache.clear()
    n = len(word)
    for (a, i, j), value in found.items():
        assert j == n
        expected = chart.cost(a, i, j, cap=1e9)
        assert (value == INF and expected == INF) or abs(value - expected) < 1e-9, (a, i)


def test_gamma_costs_every_suffix_in_one_pass():
    gamma = psgs.load("grammars/paper_example.psgs")
    word = "abcdbcad" * 2 + "abxdbcd" + "abcdbcadd"   # a substitution, a deletion, an insertion
    cg, chart = charts(gamma.components[0], word, 1.0, 1.0, 1.0, alphabet="abcdx")
    found = suffix_costs(chart)
    start = cg.index[psgs.Nonterminal("S1")]
    assert found[(start, 0, len(word))] == 3
    chart.memo.clear()
    chart._split_cache.clear()
    for i in range(0, len(word) + 1, 3):
        assert found[(start, i, len(word))] == chart.cost(start, i, len(word), cap=1e9)
