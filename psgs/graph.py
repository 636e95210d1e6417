"""A networkx view of a grammar system (see ``docs/export.md``).

``to_networkx(system)`` returns a :class:`networkx.MultiDiGraph` with

* a node per nonterminal *per component* (rules are per component), id
  ``(component, "nonterminal", name)``, attributes ``kind="nonterminal"``,
  ``label``, ``component``, ``start`` (True for the component's axiom);
* a node per rule, id ``(component, "rule", label)``, attributes
  ``kind="rule"``, ``label``, ``component``, ``rule`` (the
  :class:`~psgs.model.Rule`), ``text`` (``"N5 → b c"``), ``terminals``
  (the terminal texts of its right side, in order), ``queries`` (the
  components its query symbols name), ``synchronised`` (True when it
  appears in a tuple of M);

and edges, each with a ``kind`` attribute:

* ``"rewrites"``: left side -> rule (``position=None``) and rule -> each
  nonterminal of its right side (``position`` = its index in the right side;
  ``N7 -> N4 N4`` gives two parallel edges);
* ``"synchronised"``: between the rules of one tuple of M, both ways,
  ``tuple`` = the tuple's index in ``system.sync`` (PSGS only);
* ``"queries"``: from a PCGS rule holding ``?G`` to the axiom of component
  ``G`` (``position`` as above).

The kind is part of a node's id because a rule may be labelled like a
nonterminal (the paper's Γ labels ``N5: N5 -> "b" "c"``).
"""

from __future__ import annotations

import networkx as nx

from .errors import ValidationError
from .model import PCGS, PSGS, Grammar, Nonterminal, Query, Terminal

__all__ = ["to_networkx", "nonterminal_node", "rule_node"]


def nonterminal_node(component: str, name: str) -> tuple[str, str, str]:
    """The node id of nonterminal ``name`` in ``component``.

    Examples
    --------
    >>> nonterminal_node("G1", "S1")
    ('G1', 'nonterminal', 'S1')
    """
    return (component, "nonterminal", name)


def rule_node(component: str, label: str) -> tuple[str, str, str]:
    """The node id of the rule labelled ``label`` in ``component``.

    Examples
    --------
    >>> rule_node("G1", "S1a")
    ('G1', 'rule', 'S1a')
    """
    return (component, "rule", label)


def to_networkx(system: PSGS | PCGS | Grammar) -> nx.MultiDiGraph:
    """The rules and nonterminals of ``system`` as a networkx multigraph.

    Parameters
    ----------
    system : PSGS, PCGS or Grammar
        The system (or one grammar) to draw.

    Returns
    -------
    networkx.MultiDiGraph
        Nodes ``(component, "rule", label)`` and ``(component, "nonterminal", name)``; edges
        from a left-hand side to its rules, from a rule to the nonterminals it yields, and
        "synchronised with" edges between rules of a tuple.

    Raises
    ------
    ValidationError
        When ``system`` is not a PSGS, PCGS or Grammar.

    Examples
    --------
    >>> from psgs import Grammar, Nonterminal, PSGS, Rule, Terminal
    >>> S = Nonterminal("S")
    >>> g = Grammar("G", S, (Rule("p", S, (Terminal("a"), S)), Rule("q", S, ())))
    >>> graph = to_networkx(PSGS((g,), sync=[("p",)], name="As"))
    >>> sorted(graph.successors(("G", "rule", "p")))
    [('G', 'nonterminal', 'S')]
    >>> graph.nodes["G", "rule", "p"]["synchronised"]
    True
    """
    if isinstance(system, Grammar):
        components: tuple[Grammar, ...] = (system,)
        graph = nx.MultiDiGraph(name=system.name, kind="grammar")
    elif isinstance(system, PSGS):
        components = system.components
        graph = nx.MultiDiGraph(name=system.name, kind="psgs", mode=system.mode,
                                unsynchronised=system.unsynchronised)
    elif isinstance(system, PCGS):
        components = system.components
        graph = nx.MultiDiGraph(name=system.name, kind="pcgs", returning=system.returning,
                                master=system.master, centralised=system.centralised)
    else:
        raise ValidationError(f"to_networkx takes a PSGS, a PCGS or a Grammar, not "
                              f"{type(system).__name__}")
    synchronised = (set().union(*system.synchronised_rules) if isinstance(system, PSGS)
                    else set())
    starts = {g.name: g.start for g in components}
    for grammar in components:
        for nonterminal in sorted(grammar.nonterminals):
            graph.add_node(nonterminal_node(grammar.name, nonterminal.name), kind="nonterminal",
                           label=nonterminal.name, component=grammar.name,
                           start=nonterminal == grammar.start)
        for rule in grammar.rules:
            node = rule_node(grammar.name, rule.label)
            graph.add_node(node, kind="rule", label=rule.label, component=grammar.name,
                           rule=rule, text=str(rule),
                           terminals=tuple(s.name for s in rule.rhs if isinstance(s, Terminal)),
                           queries=tuple(s.component for s in rule.rhs if isinstance(s, Query)),
                           synchronised=rule in synchronised)
            graph.add_edge(nonterminal_node(grammar.name, rule.lhs.name), node, kind="rewrites",
                           position=None)
            for position, symbol in enumerate(rule.rhs):
                if isinstance(symbol, Nonterminal):
                    graph.add_edge(node, nonterminal_node(grammar.name, symbol.name),
                                   kind="rewrites", position=position)
                elif isinstance(symbol, Query) and symbol.component in starts:
                    # a grammar exported alone has no queried component to point at
                    target = nonterminal_node(symbol.component, starts[symbol.component].name)
                    graph.add_edge(node, target, kind="queries", position=position)
    if isinstance(system, PSGS):
        for index, sync_tuple in enumerate(system.sync):
            members = [rule_node(g.name, r.label)
                       for g, r in zip(system.components, sync_tuple) if r is not None]
            for a in members:
                for b in members:
                    if a != b:
                        graph.add_edge(a, b, kind="synchronised", tuple=index)
    return graph
