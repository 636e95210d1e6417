"""The chart's static analysis (near-linear, bottom-up over strongly connected components) agrees
with the plain round-by-round fixpoints it replaced, on generated grammars."""

from __future__ import annotations

from hypothesis import given, settings

import psgs.strategies as pst
from psgs.membership.chart import UNBOUNDED, CompiledGrammar


def reference(cg: CompiledGrammar):
    """The definitions, computed the slow way (fixpoints over every rule until nothing changes)."""
    n = len(cg.nonterminals)
    rules = list(range(len(cg.rules)))
    nullable, minlen = [False] * n, [UNBOUNDED] * n
    changed = True
    while changed:
        changed = False
        for k in rules:
            a, body = cg.lhs[k], cg.body[k]
            if not nullable[a] and all(s >= 0 and nullable[s] for s in body):
                nullable[a] = changed = True
            total = sum(1 if s < 0 else minlen[s] for s in body)
            if total < minlen[a]:
                minlen[a], changed = total, True
    useful = [k for k in rules if all(s < 0 or minlen[s] < UNBOUNDED for s in cg.body[k])]
    edges = [set() for _ in range(n)]
    for k in useful:
        edges[cg.lhs[k]].update(s for s in cg.body[k] if s >= 0)

    def reach(a, graph):
        seen, todo = set(), [a]
        while todo:
            for y in graph[todo.pop()]:
                if y not in seen:
                    seen.add(y)
                    todo.append(y)
        return seen

    reaches = [reach(a, edges) for a in range(n)]
    grows = [False] * n
    changed = True
    while changed:
        changed = False
        for k in useful:
            if not grows[cg.lhs[k]] and any(s < 0 or grows[s] for s in cg.body[k]):
                grows[cg.lhs[k]] = changed = True
    pumping = [False] * n
    for k in useful:
        a, body = cg.lhs[k], cg.body[k]
        for t, s in enumerate(body):
            if s >= 0 and (s == a or a in reaches[s]) and \
                    any(o < 0 or grows[o] for u, o in enumerate(body) if u != t):
                pumping[a] = True
    unbounded = [pumping[a] or any(pumping[b] for b in reaches[a]) for a in range(n)]
    maxlen = [UNBOUNDED if unbounded[a] else 0 for a in range(n)]
    for _ in range(n + 1):
        for k in useful:
            a = cg.lhs[k]
            if not unbounded[a]:
                maxlen[a] = max(maxlen[a], sum(1 if s < 0 else maxlen[s] for s in cg.body[k]))
    unit = [set() for _ in range(n)]
    for k in useful:
        body = cg.body[k]
        for t, s in enumerate(body):
            if s >= 0 and all(o >= 0 and nullable[o] for u, o in enumerate(body) if u != t):
                unit[cg.lhs[k]].add(s)
    closure = [tuple(sorted(reach(a, unit) | {a})) for a in range(n)]

    def edge_terminals(reverse):
        sets = [set() for _ in range(n)]
        changed = True
        while changed:
            changed = False
            for k in useful:
                target = sets[cg.lhs[k]]
                for s in (cg.body[k][::-1] if reverse else cg.body[k]):
                    if s < 0:
                        changed |= ~s not in target
                        target.add(~s)
                        break
                    if not sets[s] <= target:
                        target |= sets[s]
                        changed = True
                    if not nullable[s]:
                        break
        return [frozenset(x) for x in sets]

    return nullable, minlen, maxlen, closure, edge_terminals(False), edge_terminals(True)


@settings(max_examples=100)
@given(pst.grammars(max_nonterminals=5, max_rules=9))
def test_the_near_linear_analysis_agrees_with_the_fixpoints(grammar):
    ids = {t: k for k, t in enumerate(sorted(grammar.terminals))}
    cg = CompiledGrammar(grammar, ids)
    nullable, minlen, maxlen, closure, first, last = reference(cg)
    assert cg.nullable == nullable and cg.minlen == minlen and cg.maxlen == maxlen
    assert [cg.unit_closure(a) for a in range(len(cg.nonterminals))] == closure
    assert cg.first == first and cg.last == last
