"""Every span's edit cost against every nonterminal at once: a bottom-up error-correcting chart.

The form search of :mod:`psgs.membership.parallel_distance` aligns its forms
with the input and asks, for each nonterminal occurrence, what the
nonterminal costs on every span ``(p, q)``: all of them, for every form it
refines. :class:`~psgs.membership.error_chart.ErrorChart` answers one span
at a time, top-down and pruned by a cap, which suits the span search (few
spans, small caps) but takes seconds to fill all of them on a grammar like
``S → A a S | S S``. Here they are filled in one pass, shortest spans
first, as in Aho and Peterson's minimum-distance parser:

* the rules are binarised (``X → s1 s2 s3`` becomes ``X → s1 I``,
  ``I → s2 s3``), so a span's cost is a least sum over one split point,
  read from two already known shorter spans (``min(map(add, ...))``);
* a split that gives one side the whole span and the other an empty one
  (its cheapest yield inserted, a constant), a unit rule, and an empty body
  join the span to another symbol's cost on the *same* span with a constant
  weight: these edges are closed once, by shortest paths over the symbols,
  and each span reads its cost as the least over the closure of the others'
  direct costs;
* a terminal over a span keeps one symbol (matched or substituted) and
  deletes the rest, or deletes all and is inserted.

The costs are the same minimum the chart's are (both exact), summed in
another order.
"""

from __future__ import annotations

from operator import add

from .error_chart import INF, ErrorChart

__all__ = ["span_costs"]


def span_costs(chart: ErrorChart, tick) -> list[list[list[float]]]:
    """Per nonterminal ``x``, per end ``q``, per start ``p ≤ q``: ``x``'s cost on ``word[p:q]``.

    The least edit cost of the span against the words ``x`` derives in the
    chart's grammar alone (``inf`` when it derives none). ``tick`` is called
    per span and symbol, so a budget's clock is read as the table fills.

    Examples
    --------
    >>> from psgs.model import Grammar, Rule, Nonterminal as N, Terminal as T
    >>> from psgs.membership.chart import CompiledGrammar
    >>> S, a = N("S"), T("a")
    >>> g = Grammar("G", S, [Rule("p", S, (S, S)), Rule("q", S, (a,))])
    >>> cg = CompiledGrammar(g, {a: 0})
    >>> word = [0, 1, 0]                               # a x a: x is no terminal
    >>> chart = ErrorChart(cg, word, [1], [1, 1, 1], lambda p, t: 0 if word[p] == t else 1)
    >>> costs = span_costs(chart, lambda: None)[0]
    >>> costs[3][0], costs[1][0], costs[2][1], costs[0][0]   # a x a, a, x, the empty span
    (1.0, 0.0, 1.0, 1)
    """
    g = chart.g
    n = chart.n
    nts = len(g.nonterminals)
    deleted, delete, insert, sub = chart.deleted, chart.delete, chart.insert, chart.substitute
    least = chart.min_yield
    # items: the nonterminals, then one per binarised suffix of a long body; a side of a
    # binary node is ('t', terminal id) or ('i', item)
    empty: list[float] = list(least)  # an item's cost on an empty span: its least insertion
    binary: list[tuple[int, tuple, tuple]] = []  # (item, left, right)
    unary: list[tuple[int, tuple]] = []  # (item, side): the item on a span is the side on it
    nullary: list[int] = []  # items with an empty body: the span deleted

    def side(s: int) -> tuple:
        return ("t", ~s) if s < 0 else ("i", s)

    def side_empty(sd: tuple) -> float:
        return insert[sd[1]] if sd[0] == "t" else empty[sd[1]]

    for a, body in zip(g.lhs, g.body):
        if any(s >= 0 and least[s] == INF for s in body):
            continue  # a body with a nonterminal that derives nothing
        if not body:
            nullary.append(a)
        elif len(body) == 1:
            unary.append((a, side(body[0])))
        else:
            right = side(body[-1])
            for k in range(len(body) - 2, 0, -1):  # the suffixes body[k:], longest last
                item = len(empty)
                empty.append(side_empty(side(body[k])) + side_empty(right))
                binary.append((item, side(body[k]), right))
                right = ("i", item)
            binary.append((a, side(body[0]), right))
    items = len(empty)
    # same-span edges: target ≤ source + weight
    edges: list[list[tuple[int, float]]] = [[] for _ in range(items)]
    for a, sd in unary:
        if sd[0] == "i":
            edges[sd[1]].append((a, 0.0))
    for a, left, right in binary:
        if right[0] == "i":  # left empty, right the whole span
            edges[right[1]].append((a, side_empty(left)))
        if left[0] == "i":
            edges[left[1]].append((a, side_empty(right)))
    # closure[b]: (a, w) with a ≤ b + w on any span, by shortest paths (weights ≥ 0)
    closure: list[list[tuple[int, float]]] = []
    for b in range(items):
        tick()
        best = {b: 0.0}
        frontier = [b]
        while frontier:
            nxt = []
            for x in frontier:
                for a, w in edges[x]:
                    v = best[x] + w
                    if v < best.get(a, INF):
                        best[a] = v
                        nxt.append(a)
            frontier = nxt
        closure.append([(a, w) for a, w in best.items() if w < INF])
    # terminals: tables[t] rows and columns as the items'
    terminals = sorted({sd[1] for _, sd in unary if sd[0] == "t"}
                       | {sd[1] for _, l, r in binary for sd in (l, r) if sd[0] == "t"})
    # rows[x][p][q] and cols[x][q][p] (INF where q < p; an empty span its least insertion)
    rows = {("i", x): [[INF] * (n + 1) for _ in range(n + 1)] for x in range(items)}
    cols = {("i", x): [[INF] * (n + 1) for _ in range(n + 1)] for x in range(items)}
    for x in range(items):
        for p in range(n + 1):
            rows[("i", x)][p][p] = cols[("i", x)][p][p] = empty[x]
    for t in terminals:
        row_t = [[INF] * (n + 1) for _ in range(n + 1)]
        col_t = [[INF] * (n + 1) for _ in range(n + 1)]
        gain = [sub(r, t) - delete[r] for r in range(n)]
        for p in range(n + 1):
            tick()
            row_t[p][p] = col_t[p][p] = insert[t]
            keep = insert[t]  # the cheapest of inserting t, or keeping one symbol for it
            for q in range(p + 1, n + 1):
                if gain[q - 1] < keep:
                    keep = gain[q - 1]
                row_t[p][q] = col_t[q][p] = deleted[q] - deleted[p] + keep
        rows[("t", t)], cols[("t", t)] = row_t, col_t
    for length in range(1, n + 1):
        for p in range(n - length + 1):
            q = p + length
            tick()
            direct = [INF] * items
            for a in nullary:
                v = deleted[q] - deleted[p]
                if v < direct[a]:
                    direct[a] = v
            for a, sd in unary:
                if sd[0] == "t":
                    v = rows[sd][p][q]
                    if v < direct[a]:
                        direct[a] = v
            for a, left, right in binary:
                # interior splits: both sides shorter and known
                v = min(map(add, rows[left][p][p + 1:q], cols[right][q][p + 1:q]), default=INF)
                if right[0] == "t":  # left empty, the terminal on the whole span
                    v = min(v, side_empty(left) + rows[right][p][q])
                if left[0] == "t":
                    v = min(v, rows[left][p][q] + side_empty(right))
                if v < direct[a]:
                    direct[a] = v
            value = list(direct)
            for b in range(items):
                d = direct[b]
                if d < INF:
                    for a, w in closure[b]:
                        if d + w < value[a]:
                            value[a] = d + w
            for x in range(items):
                rows[("i", x)][p][q] = cols[("i", x)][q][p] = value[x]
    return [[cols[("i", x)][q][:q + 1] for q in range(n + 1)] for x in range(nts)]
