"""Parallel-mode distance on multiplying grammars: best-first over the sentential forms.

In ``parallel`` mode a step rewrites every occurrence of a rule's left side
alike, so the occurrences of a nonterminal in a form all derive one word; but
with edits each occurrence lines up against its own piece of the input, so
the span search of :mod:`psgs.membership.nearest_search` must choose a split
per occurrence. Where a rule multiplies its own nonterminal (``S → S S``: the
forms ``S^(2^k)``) those choices are the partitions of the input and the span
search runs out of time. Such forms are few, though: this search walks the
tuples of forms themselves, cheapest lower bound first (A*), and aligns a
word with the input only once it is terminal.

A form's lower bound is the largest of three, each never above the cost of a
word the form derives (so the first terminal tuple taken off the queue is a
nearest one):

* lengths: the form's occurrences of ``X`` derive one word, so its length is
  the terminals' count plus, per nonterminal, its number of occurrences times
  a length ``X`` derives; a word whose length is ``L`` needs ``|n - L|``
  insertions or deletions, at least the cheapest each;
* letters: an input symbol that no terminal the form can derive matches is
  deleted or substituted, an edit of its own;
* alignment, asked when the form is the cheapest left and short: the least
  cost of aligning the form's symbols with the input one after the other, a
  terminal matched, substituted or inserted, a nonterminal against the words
  it derives alone by its :class:`~psgs.membership.error_chart.ErrorChart`
  when it has few words or the input is short, else by its lengths (the chart
  of ``S → S S`` asks every span and split).

A child keeps its parent's bound when that is larger (it derives a subset of
the parent's words). A terminal tuple's bound is its exact edit distance. A
nonterminal too frequent in a form for any word but ε within the best cost
found leaves the form for a set that must derive ε (``FormSearch._children``).
"""

from __future__ import annotations

import heapq

from ..budget import Budget
from ..model import PSGS
from .chart import UNBOUNDED
from .error_chart import INF, ErrorChart
from .nearest_search import SearchSetup

__all__ = ["FormSearch", "multiplies"]

#: The alignment bound is computed for a form when its nonterminals times the input's spans
#: are at most this many; longer forms keep the length bound alone.
_CHART_CELLS = 20_000

#: Inputs up to this long align a nonterminal of many words by its error chart (the chart of
#: ``S → S S`` asks every span and split: 0.02 s at 32 symbols, 0.4 s at 100); longer ones
#: by its lengths.
_CHART_LENGTH = 32


def multiplies(compiled) -> bool:
    """Whether a rule's body holds two occurrences of nonterminals that derive its left side.

    Then the occurrences of a nonterminal can multiply without end (``S → S S``), and in
    parallel mode the span search chooses a split per occurrence.

    Examples
    --------
    >>> from psgs.model import Grammar, Rule, Nonterminal as N, Terminal as T
    >>> from psgs.membership.chart import CompiledGrammar
    >>> S, A, a = N("S"), N("A"), T("a")
    >>> doubling = Grammar("G", S, [Rule("p", S, (S, S)), Rule("q", S, (a,))])
    >>> multiplies(CompiledGrammar(doubling, {a: 0}))
    True
    >>> twice = Grammar("G", S, [Rule("p", S, (A, A)), Rule("q", A, (a, A)), Rule("r", A, (a,))])
    >>> multiplies(CompiledGrammar(twice, {a: 0}))
    False
    """
    n = len(compiled.nonterminals)
    reach = [set() for _ in range(n)]  # reach[x]: the nonterminals x derives a form with
    for a, body in zip(compiled.lhs, compiled.body):
        reach[a].update(s for s in body if s >= 0)
    changed = True
    while changed:
        changed = False
        for x in range(n):
            more = set().union(*(reach[y] for y in reach[x])) - reach[x]
            if more:
                reach[x] |= more
                changed = True
    for a, body in zip(compiled.lhs, compiled.body):
        if sum(1 for s in body if s >= 0 and (s == a or a in reach[s])) >= 2:
            return True
    return False


def _lengths(compiled, most: int, tick) -> list[int]:
    """Per nonterminal, the lengths ``≤ most`` it derives in its grammar alone, as a bitset."""
    mask = (1 << (most + 1)) - 1
    sets = [0] * len(compiled.nonterminals)
    changed = True
    while changed:
        changed = False
        for a, body in zip(compiled.lhs, compiled.body):
            tick()
            acc = 1
            for s in body:
                acc = _sumset(acc, 2 if s < 0 else sets[s], mask)
                if not acc:
                    break
            if acc | sets[a] != sets[a]:
                sets[a] |= acc
                changed = True
    return sets


def _letters(compiled) -> list[int]:
    """Per nonterminal, the terminals its words can hold, as a bitset of terminal ids."""
    sets = [0] * len(compiled.nonterminals)
    changed = True
    while changed:
        changed = False
        for a, body in zip(compiled.lhs, compiled.body):
            acc = sets[a]
            for s in body:
                acc |= (1 << ~s) if s < 0 else sets[s]
            if acc != sets[a]:
                sets[a] = acc
                changed = True
    return sets


def _sumset(x: int, y: int, mask: int) -> int:
    """``{p + q : p in x, q in y}`` as bitsets, cut at ``mask``."""
    if x.bit_count() > y.bit_count():
        x, y = y, x
    out = 0
    while x:
        low = x & -x
        out |= y << (low.bit_length() - 1)
        x ^= low
    return out & mask


def _scaled(x: int, k: int, mask: int) -> int:
    """``{k p : p in x}`` as a bitset, cut at ``mask``."""
    if k == 1:
        return x & mask
    out = 0
    most = mask.bit_length()
    while x:
        low = x & -x
        p = (low.bit_length() - 1) * k
        if p >= most:
            break
        out |= 1 << p
        x ^= low
    return out


class _Component:
    """What the bounds of one component's forms read: its chart, lengths and costs."""

    def __init__(self, compiled, chart: ErrorChart, tick) -> None:
        self.compiled = compiled
        self.chart = chart
        self.n = chart.n
        # lengths are kept up to 2n + 1: any longer word is n + 2 insertions away at least,
        # one bound for all of them
        self.most = 2 * self.n + 1
        self.mask = (1 << (self.most + 1)) - 1
        self.lengths = _lengths(compiled, self.most, tick)
        self.minlen, self.maxlen = compiled.minlen, compiled.maxlen
        self.letters = _letters(compiled)
        self._foreign: dict[int, float] = {}

    def foreign_bound(self, letters: int) -> float:
        """What the input symbols no terminal of ``letters`` (a bitset of ids) matches cost.

        Each is deleted or substituted, one edit of its own.
        """
        known = self._foreign.get(letters)
        if known is not None:
            return known
        chart = self.chart
        ids = [t for t in range(letters.bit_length()) if letters >> t & 1]
        total = 0.0
        for p, x in enumerate(chart.word):
            if x < 0 or not letters >> x & 1:
                total += min([chart.delete[p], *(chart.substitute(p, t) for t in ids)])
        self._foreign[letters] = total
        return total

    def length_bound(self, counts: dict[int, int], fixed: int) -> float:
        """The least cost of the length change a word of the form needs."""
        chart, n, mask = self.chart, self.n, self.mask
        reach = (1 << fixed) & mask
        longest = fixed
        for x, k in counts.items():
            if self.minlen[x] >= UNBOUNDED:
                return INF  # x derives no word
            reach = _sumset(reach, _scaled(self.lengths[x], k, mask), mask)
            longest += k * self.maxlen[x]
            if not reach and longest <= self.most:
                return INF
        best = INF
        below = reach & ((1 << (n + 1)) - 1)
        if below:
            shortfall = n - (below.bit_length() - 1)
            best = 0.0 if shortfall == 0 else shortfall * chart.min_delete
        above = reach >> n
        if above:
            excess = (above & -above).bit_length() - 1
            best = min(best, 0.0 if excess == 0 else excess * chart.min_insert)
        if longest > self.most:  # a length past what the bitsets hold
            best = min(best, (self.most + 1 - n) * chart.min_insert)
        return best

    def chart_bound(self, form, cap: float, tick) -> float:
        """The least cost of the form's symbols aligned with the input one after the other.

        Each terminal matched, substituted or inserted, any input symbol deleted,
        each nonterminal against the words it derives alone when they are few
        (the chart's rows), else by their lengths: exact on a terminal form.
        ``inf`` when above ``cap``.
        """
        chart, n = self.chart, self.n
        deleted, delete, insert, sub = chart.deleted, chart.delete, chart.insert, chart.substitute
        row = list(deleted)  # row[q]: the form so far against word[:q]
        for s in form:
            tick()
            new = [INF] * (n + 1)
            if s < 0:
                t = ~s
                new[0] = row[0] + insert[t]
                for q in range(1, n + 1):
                    new[q] = min(row[q] + insert[t], row[q - 1] + sub(q - 1, t))
            else:
                least = chart.min_yield[s]
                # a nonterminal with few words is costed by the chart's rows (one per start);
                # any other by its lengths alone on a long input (the chart of S → S S is cubic)
                few = chart.finite[s] is not None or n <= _CHART_LENGTH
                for p in range(n + 1):
                    base = row[p]
                    if base > cap:
                        continue
                    for q in range(p, n + 1):
                        if few:  # exact when not above the cap (deleting all, inserting least)
                            here = chart.cost(s, p, q, min(cap - base,
                                                           deleted[q] - deleted[p] + least))
                        else:
                            here = chart.lower_bound(s, p, q)
                        if base + here < new[q]:
                            new[q] = base + here
            for q in range(1, n + 1):  # input symbols deleted after the form so far
                if new[q - 1] + delete[q - 1] < new[q]:
                    new[q] = new[q - 1] + delete[q - 1]
            row = new
        return row[n] if row[n] <= cap + chart.tolerance(cap) else INF


class FormSearch(SearchSetup):
    """A* over the tuples of sentential forms of a parallel-mode PSGS, for :func:`psgs.nearest`.

    Built by :func:`psgs.nearest` in parallel mode when a component's grammar
    :func:`multiplies`; ``run`` answers as
    :meth:`~psgs.membership.nearest_search.DistanceSearch.run` does, with a
    path the same builder turns into the nearest words, their derivation and
    the edit scripts.

    Examples
    --------
    >>> from psgs import PSGS, Grammar, Rule, Nonterminal as N, Terminal as T
    >>> import psgs
    >>> S, a = N("S"), T("a")
    >>> doubling = PSGS((Grammar("G", S, [Rule("p", S, (S, S)), Rule("q", S, (a,))]),),
    ...                 mode="parallel")                  # the words a^(2^k)
    >>> near = psgs.nearest(doubling, ["a" * 48])
    >>> near.distance, near.exact, len(near.words[0]) in (32, 64)
    (16, True, True)
    """

    def __init__(self, system: PSGS, compiled, charts: list[ErrorChart], max_states: int,
                 budget: Budget, step: float) -> None:
        super().__init__(system, compiled, charts, max_states, budget, step)
        self.parts = [_Component(cg, ch, budget.tick) for cg, ch in zip(compiled, charts)]

    # ------------------------------------------------------------ bounds
    def _bound(self, state, cap: float, refine: bool) -> float:
        total = 0.0
        for part, (form, vanish) in zip(self.parts, state):
            if any(not part.compiled.nullable[x] for x in vanish):
                return INF  # a nonterminal that must derive the empty word cannot
            counts: dict[int, int] = {}
            fixed = 0
            letters = 0
            for s in form:
                if s < 0:
                    fixed += 1
                    letters |= 1 << ~s
                else:
                    counts[s] = counts.get(s, 0) + 1
            if not counts:
                value = part.chart_bound(form, cap - total, self.budget.tick)
            else:
                for x in counts:
                    letters |= part.letters[x]
                value = max(part.length_bound(counts, fixed), part.foreign_bound(letters))
                cells = len(form) * (part.n + 1) * (part.n + 2) // 2
                if refine and value + total <= cap and cells <= _CHART_CELLS:
                    value = max(value, part.chart_bound(form, cap - total, self.budget.tick))
            total += value
            if total > cap + self.tolerance(cap):
                return INF
        return total

    def _children(self, state, upper: float):
        """``(move, state)`` per move that rewrites: every occurrence of each entry's left side.

        A component's entry is its form and the nonterminals that must derive the empty word
        (``vanish``): a nonterminal that occurs so often in a form that any other word of it
        makes the tuple longer than ``upper`` allows leaves the form for that set (its
        occurrences derive one word, so all the empty one, wherever they stand). The set is
        still rewritten by the moves, as the forms' occurrences would be: a rule of a
        terminal there is no move within ``upper``, its body's nonterminals join the set.
        """
        for m, rule_ids in enumerate(self.move_rule_ids):
            new = []
            changed = False
            for c, (rule, (form, vanish)) in enumerate(zip(rule_ids, state)):
                if rule is None or (not vanish and all(s < 0 for s in form)):
                    new.append((form, vanish))  # idle, or a terminal form: the engine leaves it
                    continue
                cg = self.compiled[c]
                a = cg.lhs[rule]
                body = cg.body[rule]
                if a in vanish:
                    if any(s < 0 for s in body):
                        break  # as many terminals as occurrences: over upper
                    vanish = (vanish - {a}) | set(body)
                    out = tuple(s for s in form if s not in vanish)
                elif a in form:
                    out = []
                    for s in form:
                        if s == a:
                            out.extend(x for x in body if x not in vanish)
                        else:
                            out.append(s)
                    out, vanish = self._vanishing(c, tuple(out), vanish, upper)
                else:
                    break
                entry = (out, frozenset(vanish))
                changed = changed or entry != state[c]
                new.append(entry)
            else:
                if changed:
                    yield m, tuple(new)

    def _vanishing(self, c: int, form, vanish, upper: float):
        """``form`` without the nonterminals too frequent to derive a word other than ε."""
        chart = self.charts[c]
        if upper == INF or chart.min_insert <= 0:
            return form, vanish
        # k occurrences of a word of one symbol or more are k - n insertions at least
        most = chart.n + (upper + self.tolerance(upper)) / chart.min_insert
        counts: dict[int, int] = {}
        for s in form:
            if s >= 0:
                counts[s] = counts.get(s, 0) + 1
        many = {x for x, k in counts.items() if k > most}
        if not many:
            return form, vanish
        return tuple(s for s in form if s not in many), vanish | many

    # ------------------------------------------------------------ search
    def run(self, lower: float, limit: float | None):
        """A* from the start forms; returns ``(status, cost, path)`` as ``DistanceSearch.run``."""
        budget = self.budget
        start = tuple(((cg.index[g.start],), frozenset())
                      for g, cg in zip(self.system.components, self.compiled))
        cap = INF if limit is None else limit
        f0 = max(lower, self._bound(start, cap, refine=True))
        self.proved = lower
        parent = {start: None}
        if f0 == INF:  # over the limit (or no word: then no tuple is within it either)
            return ("over" if limit is not None else "empty"), None, None
        queue = [(f0, 1, 0, start, True)]
        counter = 1
        cut = False  # a state was left out as costing more than the limit
        while queue:
            f, _, _, state, refined = heapq.heappop(queue)
            self.proved = max(self.proved, f)
            upper = self.best[0] if self.best is not None else cap
            terminal = all(not vanish and all(s < 0 for s in form) for form, vanish in state)
            if terminal:
                return "found", f, self._path(parent, state)
            if not refined:  # the chart bound, asked once a state is the cheapest left
                g = max(f, self._bound(state, upper, refine=True))
                if g > f + self.tolerance(f):
                    if g <= upper + self.tolerance(upper):
                        heapq.heappush(queue, (g, 1, counter, state, True))
                        counter += 1
                    else:
                        cut = cut or self.best is None
                    continue
            self.explored += 1
            if self.explored >= self.max_states:
                self.proved = f
                return "max_states", None, None
            for m, child in self._children(state, upper):
                budget.tick()
                if child in parent:
                    continue
                upper = self.best[0] if self.best is not None else cap
                h = max(f, self._bound(child, upper, refine=False))
                if h == INF or h > upper + self.tolerance(upper):  # inf: no word, or over
                    cut = cut or self.best is None
                    continue
                parent[child] = (state, m)
                budget.hold(1 + sum(len(form) + len(vanish) for form, vanish in child))
                done = all(not vanish and all(s < 0 for s in form) for form, vanish in child)
                if done and (self.best is None or h < self.best[0]):
                    self.best = (h, self._path(parent, child))
                heapq.heappush(queue, (h, 0 if done else 1, counter, child, done))
                counter += 1
        if limit is not None and cut:
            return "over", None, None
        return "empty", None, None

    # ------------------------------------------------------------ the path
    def _path(self, parent, state):
        """The moves to ``state`` as ``DistanceSearch`` paths are: per move, per component,
        ``((A, i, j), bounds)`` for each occurrence rewritten, spans of the input words."""
        moves = []
        while parent[state] is not None:
            state, m = parent[state]
            moves.append(m)
        moves.reverse()
        per_component = [self._spans(c, moves) for c in range(len(self.compiled))]
        return [(m, tuple(rewrites[k] for rewrites in per_component))
                for k, m in enumerate(moves)]

    def _spans(self, c: int, moves) -> list[tuple]:
        """Component ``c``'s rewrites per move, each occurrence with its span of the input."""
        cg, chart = self.compiled[c], self.charts[c]
        # the derivation tree: node = [symbol, rule, children]; a child is ('n', id) or ('t', t)
        nodes = [[cg.index[self.system.components[c].start], None, None]]
        form = [0]  # node ids of the nonterminals of the form, terminals as None
        rewritten = []
        for m in moves:
            rule = self.move_rule_ids[m][c]
            if rule is None or all(x is None for x in form):
                rewritten.append([])
                continue
            a, body = cg.lhs[rule], cg.body[rule]
            ids, out = [], []
            for x in form:
                if x is None or nodes[x][0] != a:
                    out.append(x)
                    continue
                kids = []
                for s in body:
                    if s < 0:
                        kids.append(("t", ~s))
                        out.append(None)
                    else:
                        nodes.append([s, None, None])
                        kids.append(("n", len(nodes) - 1))
                        out.append(len(nodes) - 1)
                nodes[x][1], nodes[x][2] = rule, kids
                ids.append(x)
            form = out
            rewritten.append(ids)
        leaves = []  # the terminal ids of the word, in order
        leaf_of = {}  # (node, child index) -> its leaf's index
        empties = []  # nodes rewritten by an empty body, each with the leaves before it
        stack = [("n", 0, None)]
        while stack:
            kind, x, where = stack.pop()
            if kind == "t":
                leaf_of[where] = len(leaves)
                leaves.append(x)
                continue
            kids = nodes[x][2]
            if not kids:
                empties.append((x, len(leaves)))
            for k in range(len(kids) - 1, -1, -1):
                stack.append((kids[k][0], kids[k][1], (x, k)))
        leaf_span = _leaf_spans(chart, leaves)
        node_span: dict[int, tuple[int, int]] = {}
        for k, (x, before) in enumerate(empties):
            if not leaves and k == 0:  # an empty word: one ε-node deletes the whole input
                node_span[x] = (0, chart.n)
            else:  # where the leaves before it end (the input's end once it is deleted)
                at = leaf_span[before - 1][1] if before else 0
                at = chart.n if not leaves else at
                node_span[x] = (at, at)
        bounds_of: dict[int, tuple] = {}
        for x in range(len(nodes) - 1, -1, -1):  # children are made after their parents
            kids = nodes[x][2]
            if not kids:
                bounds_of[x] = (node_span[x][0],)
                continue
            bounds = []
            for k, (kind, y) in enumerate(kids):
                p, q = leaf_span[leaf_of[(x, k)]] if kind == "t" else node_span[y]
                if not bounds:
                    bounds.append(p)
                bounds.append(q)
            bounds_of[x] = tuple(bounds)
            node_span[x] = (bounds[0], bounds[-1])
        return [tuple(((nodes[x][0], *node_span[x]), bounds_of[x]) for x in ids)
                for ids in rewritten]


def _leaf_spans(chart: ErrorChart, leaves) -> list[tuple[int, int]]:
    """Per terminal of the word, the input span an optimal alignment gives it.

    A leaf keeps the input symbol it is matched or substituted with (none when
    inserted) and the deleted symbols after it; the first leaf also those
    before it. Each leaf then costs at most its part of the alignment, so the
    leaves' costs sum to the edit distance.
    """
    n, m = chart.n, len(leaves)
    delete, insert, sub = chart.delete, chart.insert, chart.substitute
    rows = [list(chart.deleted)]
    for k in range(m):
        t = leaves[k]
        prev = rows[-1]
        row = [prev[0] + insert[t]]
        for q in range(1, n + 1):
            row.append(min(prev[q] + insert[t], prev[q - 1] + sub(q - 1, t),
                           row[q - 1] + delete[q - 1]))
        rows.append(row)
    # trace back: per leaf the input position it keeps (None: inserted)
    kept: list = [None] * m
    k, q = m, n
    while k > 0:
        here = rows[k][q]
        if q > 0 and here == rows[k][q - 1] + delete[q - 1]:
            q -= 1
        elif q > 0 and here == rows[k - 1][q - 1] + sub(q - 1, leaves[k - 1]):
            kept[k - 1] = q - 1
            k, q = k - 1, q - 1
        else:
            k -= 1
    out = []
    start = 0
    for k in range(m):
        if k + 1 == m:
            end = n  # the last leaf keeps the deletions after it
        elif kept[k + 1] is not None:
            end = kept[k + 1]  # the next leaf starts at the symbol it keeps
        else:  # the next leaf is inserted: this one ends after its own symbol
            end = kept[k] + 1 if kept[k] is not None else start
        out.append((start, end))
        start = end
    return out
