"""The networkx view: nodes, attributes and edges match the system they describe."""

from __future__ import annotations

from pathlib import Path

import networkx as nx
import pytest
from hypothesis import HealthCheck, given, settings

import psgs
import psgs.strategies as pst
from psgs import PCGS, Grammar, Nonterminal, Query, Rule, Terminal, ValidationError
from psgs.graph import nonterminal_node, rule_node, to_networkx

REPO = Path(__file__).resolve().parents[2]


def edges_of_kind(graph, kind):
    return [(u, v, d) for u, v, d in graph.edges(data=True) if d["kind"] == kind]


def test_paper_example_graph():
    system = psgs.load(REPO / "grammars" / "paper_example.psgs")
    graph = to_networkx(system)
    assert isinstance(graph, nx.MultiDiGraph)
    assert graph.graph["kind"] == "psgs" and graph.graph["name"] == "Gamma"
    rules = [n for n, d in graph.nodes(data=True) if d["kind"] == "rule"]
    nonterminals = [n for n, d in graph.nodes(data=True) if d["kind"] == "nonterminal"]
    assert len(rules) == 8 + 8 + 6 + 8
    # the rule N5 and the nonterminal N5 are two nodes
    assert rule_node("G1", "N5") in graph and nonterminal_node("G1", "N5") in graph
    assert len(nonterminals) == sum(len(g.nonterminals) for g in system.components)
    # N7 -> N4 N4: two parallel edges, positions 0 and 1
    positions = sorted(d["position"] for d in graph.get_edge_data(
        rule_node("G3", "N7"), nonterminal_node("G3", "N4")).values())
    assert positions == [0, 1]
    # the 3rd tuple (N5, N1, N4, N6) links four rules pairwise, both ways
    linked = {(u, v) for u, v, d in edges_of_kind(graph, "synchronised") if d["tuple"] == 2}
    members = [rule_node("G1", "N5"), rule_node("G2", "N1"), rule_node("G3", "N4"),
               rule_node("G4", "N6")]
    assert linked == {(x, y) for x in members for y in members if x != y}
    # N2 and N3 of G3 are in no tuple
    assert graph.nodes[rule_node("G3", "N2")]["synchronised"] is False
    assert graph.nodes[rule_node("G3", "N4")]["synchronised"] is True
    assert graph.nodes[rule_node("G1", "N5")]["terminals"] == ("b", "c")
    assert graph.nodes[nonterminal_node("G1", "S1")]["start"] is True


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(pst.psgs_systems(max_components=3))
def test_graph_holds_every_rule_symbol_and_tuple(system):
    graph = to_networkx(system)
    rewrites = edges_of_kind(graph, "rewrites")
    for g in system.components:
        for rule in g.rules:
            node = rule_node(g.name, rule.label)
            assert graph.nodes[node]["rule"] == rule
            assert graph.nodes[node]["component"] == g.name
            into = [u for u, v, d in rewrites if v == node]
            assert into == [nonterminal_node(g.name, rule.lhs.name)]
            out = sorted((d["position"], v[2]) for u, v, d in rewrites if u == node)
            assert out == [(i, s.name) for i, s in enumerate(rule.rhs)
                           if isinstance(s, Nonterminal)]
    expected_sync = sum(k * (k - 1) for k in
                        (sum(r is not None for r in t) for t in system.sync))
    assert len(edges_of_kind(graph, "synchronised")) == expected_sync
    assert graph.number_of_nodes() == sum(len(g.rules) + len(g.nonterminals)
                                          for g in system.components)


def test_pcgs_queries_point_at_the_queried_axiom():
    T = Nonterminal("T")
    g1 = Grammar("G1", Nonterminal("S"), (Rule("p", Nonterminal("S"),
                                               (Terminal("a"), Query("G2"))),))
    g2 = Grammar("G2", T, (Rule("q", T, (Terminal("b"),)),))
    graph = to_networkx(PCGS((g1, g2), returning=False))
    assert graph.graph["kind"] == "pcgs" and graph.graph["returning"] is False
    assert graph.graph["centralised"] is True
    queries = edges_of_kind(graph, "queries")
    assert [(u, v, d["position"]) for u, v, d in queries] == [
        (rule_node("G1", "p"), nonterminal_node("G2", "T"), 1)]


def test_a_pcgs_component_alone_keeps_its_queries_as_an_attribute():
    S = Nonterminal("S")
    g = Grammar("G1", S, (Rule("p", S, (Terminal("a"), Query("G2"))),))
    graph = to_networkx(g)
    assert graph.nodes[rule_node("G1", "p")]["queries"] == ("G2",)
    assert not edges_of_kind(graph, "queries")


def test_a_grammar_alone_and_bad_input():
    S = Nonterminal("S")
    graph = to_networkx(Grammar("G", S, (Rule("p", S, (S, S)), Rule("q", S, ()))))
    assert graph.graph["kind"] == "grammar"
    assert graph.number_of_edges(rule_node("G", "p"), nonterminal_node("G", "S")) == 2
    with pytest.raises(ValidationError):
        to_networkx("not a system")


def test_reachability_analysis_works_on_the_view():
    system = psgs.load(REPO / "grammars" / "idling.psgs")
    graph = to_networkx(system)
    rewrites = nx.MultiDiGraph((u, v) for u, v, d in graph.edges(data=True)
                               if d["kind"] == "rewrites")
    reachable = nx.descendants(rewrites, nonterminal_node("G1", "S"))
    assert nonterminal_node("G1", "C") in reachable
    assert not any(n[0] == "G2" for n in reachable)
