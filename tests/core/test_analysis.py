"""psgs.analysis: the grammar facts every search shares, cross-checked against plain definitions."""

from __future__ import annotations

import math

import networkx as nx
from hypothesis import given, settings
from hypothesis import strategies as st

import psgs.strategies as pst
from psgs import IDLE, PSGS, Grammar, Nonterminal as N, Rule, Terminal as T
from psgs.analysis import (least_sums, min_yields, moves, reachable, strongly_connected,
                           usable_rules)
from psgs.model import Query


def _fixpoint_yields(rules, query_yield=math.inf):
    """The definition: iterate 'least over rules of the sum over the body' until it settles."""
    best = {}
    for r in rules:
        best.setdefault(r.lhs, math.inf)
        for s in r.rhs:
            if isinstance(s, N):
                best.setdefault(s, math.inf)
    changed = True
    while changed:
        changed = False
        for r in rules:
            value = sum((1 if isinstance(s, T) else query_yield if isinstance(s, Query)
                         else best[s]) for s in r.rhs)
            if value < best[r.lhs]:
                best[r.lhs] = value
                changed = True
    return best


@settings(max_examples=75)
@given(st.one_of(pst.grammars(max_nonterminals=4, max_rules=7),
                 pst.grammars(max_nonterminals=3, max_rules=5, queries=("G2",))),
       st.sampled_from([0, math.inf]))
def test_min_yields_is_the_least_fixpoint(grammar, query_yield):
    assert min_yields(grammar.rules, query_yield=query_yield) == \
        _fixpoint_yields(grammar.rules, query_yield)


def test_min_yields_is_near_linear_on_a_long_chain():
    # N0 -> a N1, ..., N{k-1} -> a N{k}, Nk -> a, listed so that a round-by-round fixpoint
    # settles one nonterminal per round (quadratic); Knuth's algorithm settles each once
    k = 3000
    rules = [Rule(f"r{i}", N(f"N{i}"), (T("a"), N(f"N{i + 1}"))) for i in range(k)]
    rules.append(Rule("last", N(f"N{k}"), (T("a"),)))
    yields = min_yields(rules)
    assert yields[N("N0")] == k + 1 and yields[N(f"N{k}")] == 1


def test_least_sums_leaves_out_what_cannot_be_had():
    assert least_sums([("a", ["b"], 1), ("b", ["a"], 1), ("c", [], 2), ("d", ["c", "c"], 0)]) \
        == {"c": 2, "d": 4}


graphs = st.dictionaries(st.integers(0, 8), st.lists(st.integers(0, 8), max_size=4), max_size=9)


@settings(max_examples=150)
@given(graphs, st.lists(st.integers(0, 8), max_size=3), st.booleans())
def test_reachable_agrees_with_networkx(graph, sources, strict):
    g = nx.DiGraph()
    g.add_nodes_from(range(9))
    g.add_edges_from((u, v) for u, vs in graph.items() for v in vs)
    expected = set()
    for s in sources:
        if strict:  # reached by at least one edge: a successor and everything below it
            for v in g.successors(s):
                expected |= {v} | nx.descendants(g, v)
        else:
            expected |= {s} | nx.descendants(g, s)
    assert reachable(graph, sources, strict=strict) == expected


@settings(max_examples=150)
@given(graphs)
def test_strongly_connected_agrees_with_networkx_in_dependency_order(graph):
    nodes = list(range(9))
    components = strongly_connected(nodes, graph)
    g = nx.DiGraph()
    g.add_nodes_from(nodes)
    g.add_edges_from((u, v) for u, vs in graph.items() for v in vs)
    assert sorted(map(frozenset, components), key=sorted) == \
        sorted(map(frozenset, nx.strongly_connected_components(g)), key=sorted)
    where = {v: k for k, comp in enumerate(components) for v in comp}
    assert all(where[v] <= where[u] for u, vs in graph.items() for v in vs)


def test_strongly_connected_handles_a_deep_chain_without_recursion():
    k = 20_000
    graph = {i: [i + 1] for i in range(k)}
    assert len(strongly_connected(list(range(k + 1)), graph)) == k + 1


def _two():
    S, R = N("S"), N("R")
    g = Grammar("G", S, [Rule("p", S, (T("a"), S)), Rule("q", S, (T("a"),)),
                         Rule("x", S, (T("c"),))])
    h = Grammar("H", R, [Rule("u", R, (T("b"), R)), Rule("v", R, (T("b"),))])
    return g, h


def test_moves_are_the_tuples_then_each_free_rule_alone():
    g, h = _two()
    free = PSGS((g, h), [("p", "u"), ("q", "v")])
    p, q, x = g.rules
    u, v = h.rules
    assert moves(free) == ((p, u), (q, v), (x, IDLE))
    strict = PSGS((g, h), [("p", "u"), ("q", "v")], unsynchronised="strict")
    assert moves(strict) == ((p, u), (q, v))


def test_usable_rules_drop_the_rules_in_no_tuple_only_under_strict():
    g, h = _two()
    assert usable_rules(PSGS((g, h), [("p", "u")])) == (g.rules, h.rules)
    strict = PSGS((g, h), [("p", "u"), ("q", "#")], unsynchronised="strict")
    assert usable_rules(strict) == ((g.rules[0], g.rules[1]), (h.rules[0],))
