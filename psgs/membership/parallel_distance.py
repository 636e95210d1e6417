"""Parallel-mode distance on multiplying grammars: best-first over the sentential forms.

In ``parallel`` mode a step rewrites every occurrence of a rule's left side
alike, so the occurrences of a nonterminal in a form all derive one word; but
with edits each occurrence lines up against its own piece of the input, so
the span search of :mod:`psgs.membership.nearest_search` must choose a split
per occurrence. Where a rule multiplies its own nonterminal (``S → S S``: the
forms ``S^(2^k)``) those choices are the partitions of the input and the span
search runs out of time. Such forms are few, though: this search walks the
tuples of forms themselves, cheapest lower bound first (A*).

A state's lower bound is the sum over components of the largest of these,
each never above the cost of a word the form derives (so the first terminal
tuple taken off the queue is a nearest one); :mod:`psgs.membership._form_bounds`
computes them:

* lengths: the form's occurrences of ``X`` derive one word, so its length is
  the terminals' count plus, per nonterminal, its number of occurrences times
  a length ``X`` derives; a word whose length is ``L`` needs ``|n - L|``
  insertions or deletions, at least the cheapest each;
* letters: an input symbol that no terminal the form can derive matches is
  deleted or substituted, an edit of its own;
* alignment, asked once the state is the cheapest left: the least cost of
  aligning the form's symbols with the input one after the other, a terminal
  matched, substituted or inserted, a nonterminal against the words it
  derives alone, by its cost on every span
  (:func:`~psgs.membership._span_table.span_costs`, on inputs of up to 64
  symbols, or 128 once the search has run a while) or by its lengths;
* one length: if that does not lift the state, the alignment in which the
  occurrences of the form's most frequent nonterminal all take words of one
  length (they derive one word), the least over the lengths;
* the floor: a component's word costs at least the component's distance
  alone (:meth:`FormSearch._find_floors`, searched first when there are two
  components or more); when every component's nearest derivation alone can
  be run in step by the system's moves, that tuple is the answer at once.

A child keeps its parent's bound when that is larger (it derives a subset of
the parent's words). A terminal tuple's bound is its exact edit distance.
Among equal bounds the queue takes terminal tuples first, then the states with
the fewest nonterminal occurrences, then the newest (a plateau of equal bounds
is walked depth first). A nonterminal too frequent in a form for any word but
ε within the best cost found leaves the form for a set that must derive ε
(``FormSearch._children``).
"""

from __future__ import annotations

import copy
import heapq
import time

from ..budget import Budget
from ..errors import BoundReached
from ..model import PSGS
from ._form_bounds import _LATE_STATES, _LEVELS, FormBounds
from .error_chart import INF, ErrorChart
from .nearest_search import SearchSetup

__all__ = ["FormSearch", "multiplies"]

#: The share of the time left that each component's search alone may take (its floor).
_FLOOR_SHARE = 0.25
#: The most positions (one per component's trail) tried to take the trails in step.
_SYNC_CELLS = 100_000


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
        self.parts = [FormBounds(cg, ch, budget.tick, budget.hold)
                      for cg, ch in zip(compiled, charts)]
        # per component, what its word costs at least in any tuple (its distance alone)
        self.floors = [0.0] * len(compiled)
        self.starts = [cg.index[g.start] for g, cg in zip(system.components, compiled)]
        self.paths = True  # build the path of a tuple found (the floors' searches do not)
        self.synchronised = None  # moves that derive the components' nearest words in step

    # ------------------------------------------------------------ bounds
    def _bound(self, state, cap: float, level: int) -> float:
        """The sum of the components' bounds (:meth:`FormBounds.bound` at ``level``), each at
        least its floor; ``inf`` past ``cap``."""
        total = 0.0
        late = self.explored >= _LATE_STATES
        for part, floor, (form, vanish) in zip(self.parts, self.floors, state):
            if any(not part.compiled.nullable[x] for x in vanish):
                return INF  # a nonterminal that must derive the empty word cannot
            value = part.bound(form, cap - total, level, late, self.budget.tick)
            total += value if value > floor else floor
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
        if len(self.compiled) > 1:
            status = self._find_floors(limit)
            if status is not None:
                return status, None, None
            lower = max(lower, sum(self.floors))
            if self.synchronised is not None:  # the components' nearest words, in step
                self.proved = lower
                return "found", lower, self._moves_path(self.synchronised)
        return self._search(lower, limit)

    def _find_floors(self, limit: float | None) -> str | None:
        """Each component's distance alone, its floor in every tuple; a status when that decides.

        A derivation of the system, read in one component, is a derivation of that
        component's grammar alone in parallel mode (each step rewrites every occurrence of
        its rule's left side, or nothing), so the component's word costs at least its
        distance to the words its grammar derives alone so. Each is searched as this
        search does, on that component, within ``_FLOOR_SHARE`` of the time left and
        ``max_states``: when it runs out first, what it proved is the floor. (Without
        tuples under ``free`` every rule is a move alone and the components are
        independent: their trails are a nearest tuple, so each may take all the time
        left.) Without floors a component whose bounds are loose (its start alone
        derives a word near its input, in its grammar) let the search take every form
        of the other components within that slack, paired with each of its own.
        """
        budget = self.budget
        independent = not self.system.sync and self.system.unsynchronised == "free"
        trails = []
        for c in range(len(self.compiled)):
            alone = copy.copy(self)
            alone.compiled, alone.charts = [self.compiled[c]], [self.charts[c]]
            alone.parts, alone.floors = [self.parts[c]], [0.0]
            alone.starts = [self.starts[c]]
            alone.move_rule_ids = [(k,) for k in range(len(self.compiled[c].rules))]
            alone.scale = self.charts[c].scale
            alone.best, alone.explored, alone.proved, alone.paths = None, 0, 0.0, False
            deadline = budget.deadline
            left = budget.left()
            if left is not None and not independent:
                budget.deadline = min(deadline, time.monotonic() + left * _FLOOR_SHARE)
            try:
                status, cost, trail = alone._search(0.0, limit)
            except BoundReached as stop:
                if stop.bound != "max_seconds" or budget.deadline == deadline:
                    # every tuple costs at least the floors so far and what this one proved
                    self.proved = max(self.proved, sum(self.floors) + alone.proved)
                    raise
                status, cost, trail = "max_seconds", None, None
            finally:
                budget.deadline = deadline
                self.explored += alone.explored
            if status in ("over", "empty"):  # no tuple within the limit, or none at all
                self.proved = max(self.proved, alone.proved)
                return status
            self.floors[c] = cost if status == "found" else alone.proved
            trails.append(trail if status == "found" else None)
        self.proved = max(self.proved, sum(self.floors))
        if all(trails) and (limit is None or sum(self.floors) <= limit + self.tolerance(limit)):
            moves = self._synchronise(trails)
            if moves is not None:
                self.synchronised = moves
        return None

    def _synchronise(self, trails) -> list[int] | None:
        """The system's moves that take every component along its trail at once, or ``None``.

        ``trails[c]`` is component ``c``'s nearest derivation alone, as ``(state, move)``
        pairs of its own search. A move of the system advances each component it names by
        the next rule of its trail (a component at the end of its trail, terminal, skips
        its entry); a move that names another rule for a component not at its end is left
        out (it rewrites off the trail, or does not apply). The tuple the moves derive
        costs the sum of the floors, so it is a nearest one; ``None`` when no order of the
        system's moves takes every trail to its end (then the search decides), or when the
        positions to try exceed ``_SYNC_CELLS``.
        """
        tick = self.budget.tick
        ends = tuple(len(trail) for trail in trails)
        rules = [[m for _, m in trail] for trail in trails]  # alone, move k is rule k
        start = (0,) * len(trails)
        seen = {start: None}
        stack = [start]
        while stack:
            at = stack.pop()
            if at == ends:
                moves = []
                while seen[at] is not None:
                    at, m = seen[at]
                    moves.append(m)
                return moves[::-1]
            for m, rule_ids in enumerate(self.move_rule_ids):
                tick()
                new = list(at)
                for c, rule in enumerate(rule_ids):
                    if rule is None or at[c] == ends[c]:
                        continue  # idle, or terminal: the engine skips its entry
                    if rule != rules[c][at[c]]:
                        break
                    new[c] += 1
                else:
                    new = tuple(new)
                    if new != at and new not in seen:
                        if len(seen) >= _SYNC_CELLS:
                            return None
                        seen[new] = (at, m)
                        stack.append(new)
        return None

    def _search(self, lower: float, limit: float | None):
        """A* from the start forms; ``run``'s answer (a trail when ``paths`` is off)."""
        budget = self.budget
        start = tuple(((x,), frozenset()) for x in self.starts)
        cap = INF if limit is None else limit
        f0 = max(lower, self._bound(start, cap, _LEVELS))
        self.proved = lower
        parent = {start: None}
        if f0 == INF:  # over the limit (or no word: then no tuple is within it either)
            return ("over" if limit is not None else "empty"), None, None
        # ties: terminal tuples first, then the fewest nonterminal occurrences (the nearest to
        # a word, and a doubling nullable that keeps the bound no longer wins), then the
        # newest, so that a plateau of equal bounds is walked depth first
        queue = [(f0, _open(start), 0, start, _LEVELS)]
        counter = 1
        cut = False  # a state was left out as costing more than the limit
        while queue:
            f, rank, _, state, level = heapq.heappop(queue)
            self.proved = max(self.proved, f)
            upper = self.best[0] if self.best is not None else cap
            if rank == 0:  # a terminal tuple
                return "found", f, self._path(parent, state)
            g = f
            while level < _LEVELS and g <= f + self.tolerance(f):
                # the dearer bounds, asked once a state is the cheapest left
                level += 1
                g = max(f, self._bound(state, upper, level))
            if g > f + self.tolerance(f):
                if g <= upper + self.tolerance(upper):
                    heapq.heappush(queue, (g, rank, -counter, state, level))
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
                h = max(f, self._bound(child, upper, 0))
                if h == INF or h > upper + self.tolerance(upper):  # inf: no word, or over
                    cut = cut or self.best is None
                    continue
                parent[child] = (state, m)
                budget.hold(1 + sum(len(form) + len(vanish) for form, vanish in child))
                done = all(not vanish and all(s < 0 for s in form) for form, vanish in child)
                if done and (self.best is None or h < self.best[0]):
                    self.best = (h, self._path(parent, child))
                heapq.heappush(queue, (h, _open(child), -counter, child,
                                       _LEVELS if done else 0))
                counter += 1
        if limit is not None and cut:
            return "over", None, None
        return "empty", None, None

    # ------------------------------------------------------------ the path
    def _path(self, parent, state):
        """The moves to ``state`` as ``DistanceSearch`` paths are: per move, per component,
        ``((A, i, j), bounds)`` for each occurrence rewritten, spans of the input words.

        When the search builds no paths (a component's floor), the states before each
        move and the moves: ``[(state, move), ...]``.
        """
        trail = []
        while parent[state] is not None:
            state, m = parent[state]
            trail.append((state, m))
        trail.reverse()
        if not self.paths:
            return trail
        return self._moves_path([m for _, m in trail])

    def _moves_path(self, moves):
        """The path of :meth:`_path` for the system's ``moves`` from the start forms."""
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


def _open(state) -> int:
    """How many nonterminal occurrences a state's forms hold (0: a terminal tuple)."""
    return sum(sum(1 for s in form if s >= 0) + len(vanish) for form, vanish in state)


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
