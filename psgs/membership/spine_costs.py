"""Edit costs of every suffix of a word against a right-linear spine, in one backward pass.

When every rule whose left side is on the spine (the nonterminals on or
above a cycle) is right-linear on it — at most one spine symbol, last in the
body — and the rest of each such body is a few words (its symbols are
terminals or off-spine nonterminals with few words), the component's
language from a spine nonterminal is that of a finite automaton: one state
per spine nonterminal and a path of states per word of each rule's prefix.
The edit distance from a word to a regular language is then the textbook
dynamic programme over (position, state), run backwards from the end: a
state at position ``i`` deletes ``word[i]``, matches or substitutes it
along a transition, or inserts a transition's terminal (staying at ``i``;
within one position these moves are a shortest-path problem, solved with
Dijkstra since costs are ≥ 0). That gives, for every spine nonterminal ``X``
and every ``i``, the exact cost of ``X`` on ``word[i:n]`` in O(n · |states|)
— every span a spine occurrence can have, since a right-linear spine's
occurrences all end where the word ends — where the top-down chart would
try a number of block ends that grows with the errors allowed.
"""

from __future__ import annotations

import heapq
import math

from .schedule_search import _spine

__all__ = ["suffix_costs"]

INF = math.inf
#: A rule prefix with more words than this is not expanded (the chart decides alone).
_MAX_WORDS = 64


def suffix_costs(chart) -> dict[tuple[int, int, int], float] | None:
    """``{(X, i, n): cost}`` for every spine nonterminal ``X`` and start ``i``; None if it does not apply.

    ``chart`` is a :class:`psgs.membership.error_chart.ErrorChart` (its word,
    costs, budget and few-word languages are used).

    Examples
    --------
    >>> from psgs.model import Grammar, Rule, Nonterminal as N, Terminal as T
    >>> from psgs.membership.chart import CompiledGrammar
    >>> from psgs.membership.error_chart import ErrorChart
    >>> g = Grammar("G", N("S"), (Rule("p", N("S"), (T("a"), N("S"))), Rule("q", N("S"), (T("a"),))))
    >>> cg = CompiledGrammar(g, {T("a"): 0})
    >>> word = [0, 1, 0]                     # a x a: one edit from aaa (or aa)
    >>> chart = ErrorChart(cg, word, [1], [1, 1, 1], lambda p, t: 0 if word[p] == t else 1)
    >>> s = cg.index[N("S")]
    >>> costs = suffix_costs(chart)
    >>> costs[(s, 0, 3)], costs[(s, 1, 3)], costs[(s, 2, 3)], costs[(s, 3, 3)]
    (1.0, 1.0, 0.0, 1.0)
    """
    g = chart.g
    spine = sorted(_spine(g))
    if not spine:
        return None
    node_of = {a: k for k, a in enumerate(spine)}
    steps: list[list[tuple[int, int]]] = [[] for _ in spine]   # (terminal, target)
    units: list[list[int]] = [[] for _ in spine]               # zero-cost moves
    final: list[int] = []
    for a in spine:
        for rule in g.useful_by_lhs[a]:
            body = g.body[rule]
            tail = body[-1] if body and body[-1] in node_of else None
            prefix = body[:-1] if tail is not None else body
            words: list[tuple[int, ...]] = [()]
            for s in prefix:
                options = ((~s,),) if s < 0 else (None if s in node_of else chart.finite[s])
                if options is None:
                    return None  # not right-linear on the spine, or too many words
                words = [u + o for u in words for o in options]
                if len(words) > _MAX_WORDS:
                    return None
            for u in words:
                at = node_of[a]
                for t in u:
                    steps.append([])
                    units.append([])
                    steps[at].append((t, len(steps) - 1))
                    at = len(steps) - 1
                if tail is None:
                    final.append(at)
                else:
                    units[at].append(node_of[tail])
    size = len(steps)
    insert = chart.insert
    # within one position: the state's cost is at most an insertion (or unit move) plus the
    # cost of where it leads, so costs flow backwards along these edges
    back: list[list[tuple[int, float]]] = [[] for _ in range(size)]
    for q in range(size):
        for t, r in steps[q]:
            back[r].append((q, insert[t]))
        for r in units[q]:
            back[r].append((q, 0.0))
    delete, sub = chart.delete, chart.substitute  # sub(i, t) reads word[i] itself
    tick = chart.budget.tick
    n = chart.n
    base = [INF] * size
    for q in final:
        base[q] = 0.0
    out: dict[tuple[int, int, int], float] = {}
    i = n
    while True:
        tick()
        layer = _settle(base, back)
        for a, k in node_of.items():
            out[(a, i, n)] = layer[k]
        chart._hold(3 * len(spine))
        if i == 0:
            return out
        i -= 1
        d = delete[i]
        base = [layer[q] + d for q in range(size)]
        for q in range(size):
            for t, r in steps[q]:
                v = layer[r]
                if v < INF:
                    v += sub(i, t)
                    if v < base[q]:
                        base[q] = v


def _settle(base: list[float], back: list[list[tuple[int, float]]]) -> list[float]:
    """Least costs from ``base`` through the zero-input moves (Dijkstra, costs ≥ 0)."""
    best = list(base)
    heap = [(v, q) for q, v in enumerate(base) if v < INF]
    heapq.heapify(heap)
    while heap:
        v, q = heapq.heappop(heap)
        if v > best[q]:
            continue
        for p, w in back[q]:
            x = v + w
            if x < best[p]:
                best[p] = x
                heapq.heappush(heap, (x, p))
    return best
