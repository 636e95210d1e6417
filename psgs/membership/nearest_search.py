"""PSGS distance: the synchronised schedule search of ``accepts``, weighted by edit costs.

The states are those of :mod:`psgs.membership.schedule_search`: per
component, the nonterminal occurrences still to derive, each tagged with the
span of the input word it stands for. A move applies a tuple as ``accepts``
does (one occurrence in ``single`` mode, every occurrence of the left-hand
side in ``parallel`` mode), choosing for each occurrence a split of its span
among the rule's body; but a split may now cost edits (its terminals
aligned with their spans, see :class:`~psgs.membership.error_chart.ErrorChart`).

A state's estimate ``f = g + h``: ``g`` the edits already fixed, ``h`` the
sum over its occurrences of their distance in the component grammar alone.
``h`` never overestimates (synchronisation only removes derivations) and
never drops along a move (a split costs at least its occurrence's distance),
so a search that expands only states with ``f ≤ U`` finds every tuple of
cost ``≤ U``. Rounds raise ``U`` from the sum of the components' distances
(the lower bound) to the least estimate a round cut off, by at least the least
cost (doubled while rounds explore no state) and, after a round that explored,
an eighth of ``U``; within a round a
depth-first branch and bound keeps the cheapest tuple, so the first round
that finds one returns the exact distance. When the components' nearest
words can be derived in step, the first round finds them without
backtracking.
"""

from __future__ import annotations

from ..analysis import moves as system_moves
from ..budget import Budget
from ..model import IDLE, PSGS
from .depth_first import Finish, depth_first
from .error_chart import INF, TOLERANCE, ErrorChart
from .schedule_search import _item_order, _Substrings

__all__ = ["DistanceSearch"]

#: The largest raise of the cap between two rounds, in least costs (see ``DistanceSearch.run``).
_MOST_DOUBLED = 2 ** 40

#: A round raises the cap by at least this share of it (1/8): rounds grow geometrically.
_SHARE = 8


class SearchSetup:
    """What a distance search is handed and what :func:`psgs.nearest` reads back from it:
    the system, its compiled components and error charts, the budgets, the least positive
    cost, the system's moves with their rules' ids in each compiled component, and the
    answer so far (the input words, the states explored, the cheapest tuple and the bound
    proved). :class:`DistanceSearch` and
    :class:`~psgs.membership.parallel_distance.FormSearch` build on it.
    """

    def __init__(self, system: PSGS, compiled, charts: list[ErrorChart], max_states: int,
                 budget: Budget, step: float) -> None:
        self.system = system
        self.compiled = compiled
        self.charts = charts
        self.max_states = max_states
        self.budget = budget
        self.scale = sum(chart.scale for chart in charts)  # what costs are rounded against
        self.step = step  # the least positive cost: rounds grow the bound by at least this
        self.moves = system_moves(system)
        self.move_rule_ids = [tuple(None if r is IDLE else cg.rule_id[r]
                                    for r, cg in zip(m, compiled)) for m in self.moves]
        self.words = None  # the input words, for the edit scripts of the answer
        self.explored = 0
        self.best = None  # (cost, path) of the cheapest tuple found so far
        self.proved = 0.0  # every tuple costs at least this

    def tolerance(self, value: float) -> float:
        """:meth:`ErrorChart.tolerance` over every component's word."""
        return TOLERANCE * (value + self.scale)


class DistanceSearch(SearchSetup):
    """Rounds of bounded depth-first search for the cheapest synchronised schedule.

    Built by :func:`psgs.nearest`, which reads the answer from ``run``.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> psgs.nearest(gamma, ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbcd"]).states > 0
    True
    """

    def __init__(self, system: PSGS, compiled, charts: list[ErrorChart], max_states: int,
                 budget: Budget, step: float) -> None:
        super().__init__(system, compiled, charts, max_states, budget, step)
        self.parallel = system.mode == "parallel"
        self.substrings = [_Substrings(ch.word) for ch in charts]
        self.cap = 0.0
        self.moves_needing: dict[tuple[int, int], list[int]] = {}
        for m, rule_ids in enumerate(self.move_rule_ids):
            for c, rule in enumerate(rule_ids):
                if rule is not None:
                    self.moves_needing.setdefault((c, compiled[c].lhs[rule]), []).append(m)

    # ------------------------------------------------------------ estimates
    def item_cost(self, c: int, item, cap: float) -> float:
        """Component ``c``'s chart cost of an occurrence ``(A, i, j)`` (``inf`` above ``cap``)."""
        a, i, j = item
        return self.charts[c].cost(a, i, j, cap)

    def key(self, state):
        """A state up to equal substrings (as in ``accepts``): equal keys have equal futures."""
        out = []
        for c, front in enumerate(state):
            classes = self.substrings[c]
            out.append(tuple(sorted((a, classes.of(i, j)) for a, i, j in front)))
        return tuple(out)

    # ------------------------------------------------------------ moves
    def _occurrence_options(self, c: int, rule: int, item, slack: float):
        """(delta, children, rewrite) per split of ``item`` costing at most its estimate + slack."""
        chart = self.charts[c]
        a, i, j = item
        base = chart.cost(a, i, j, self.cap)  # in a state within the cap, so known exactly
        splits, excess = chart.splits(rule, i, j, base + slack)
        body = self.compiled[c].body[rule]
        out = []
        for cost, bounds in splits:
            if len(bounds) == 1:
                children = []
            else:
                children = [(s, bounds[t], bounds[t + 1]) for t, s in enumerate(body) if s >= 0]
            out.append((cost - base, children, (item, bounds)))
        return out, excess - base

    def _component_options(self, c: int, front, rule: int, slack: float):
        """Sorted (delta, new front, rewrites) of one component; None when the rule cannot apply."""
        a = self.compiled[c].lhs[rule]
        targets = [it for it in front if it[0] == a]
        if not targets:
            return None, INF
        classes = self.substrings[c]
        out = []
        excess = INF
        if not self.parallel:
            seen = set()
            for it in targets:
                cls = classes.of(it[1], it[2])
                if cls in seen:
                    continue  # an equal occurrence has the same futures
                seen.add(cls)
                rest = list(front)
                rest.remove(it)
                options, ex = self._occurrence_options(c, rule, it, slack)
                excess = min(excess, ex)
                for delta, children, rw in options:
                    out.append((delta, tuple(sorted(rest + children, key=_item_order)), (rw,)))
            out.sort(key=lambda o: o[0])
            return out, excess
        rest = [it for it in front if it[0] != a]
        groups: dict[int, list] = {}
        for it in targets:
            groups.setdefault(classes.of(it[1], it[2]), []).append(it)
        slots = []  # per occurrence its options; equal occurrences choose a multiset
        for items in groups.values():
            options = []
            for it in items:
                opts, ex = self._occurrence_options(c, rule, it, slack)
                excess = min(excess, ex)
                options.append(opts)
            if not options[0]:
                return out, excess
            for k, opts in enumerate(options):
                slots.append((opts, k > 0))
        cut = [INF]
        for delta, picks in _bounded_product(slots, slack, cut):
            new = list(rest)
            rewrites = []
            for _, children, rw in picks:
                new.extend(children)
                rewrites.append(rw)
            new.sort(key=_item_order)
            out.append((delta, tuple(new), tuple(rewrites)))
        out.sort(key=lambda o: o[0])
        return out, min(excess, cut[0])

    def successors(self, state, f: float, cap: float, lowest: list):
        """Children ``(f, move, state, rewrites)`` with ``f ≤ cap``, cheapest first.

        ``lowest[0]`` is lowered to the least estimate of a child left out.
        """
        tick, hold = self.budget.tick, self.budget.hold
        leftmost_of = []
        for front in state:
            table: dict[int, int] = {}
            for a, i, _ in front:
                if a not in table or i < table[a]:
                    table[a] = i
            leftmost_of.append(table)
        relevant = set()
        for c, table in enumerate(leftmost_of):
            for a in table:
                relevant.update(self.moves_needing.get((c, a), ()))
        candidates = []
        for m in sorted(relevant):
            key = None
            for c, rule in enumerate(self.move_rule_ids[m]):
                if rule is None or not state[c]:
                    continue
                at = leftmost_of[c].get(self.compiled[c].lhs[rule])
                if at is None:
                    key = None
                    break
                key = at if key is None or at < key else key
            else:
                if key is not None:
                    candidates.append((key, m))
        candidates.sort()
        # a child's splits are summed in another order than cap - f was taken: a child
        # costing exactly the cap must not be rounded out of it (as the charts allow)
        slack = cap - f + self.tolerance(cap)
        out = []
        for order, (_, m) in enumerate(candidates):
            slots = []
            rewrites_somewhere = False
            dead = False
            for c, rule in enumerate(self.move_rule_ids[m]):
                front = state[c]
                if rule is None or not front:
                    slots.append(([(0.0, front, ())], False))
                    continue
                options, excess = self._component_options(c, front, rule, slack)
                if options is None:
                    dead = True
                    break
                if excess < INF:
                    lowest[0] = min(lowest[0], f + excess)
                if not options:
                    dead = True
                    break
                rewrites_somewhere = True
                slots.append((options, False))
            if dead or not rewrites_somewhere:
                continue
            cut = [INF]
            for delta, picks in _bounded_product(slots, slack, cut):
                # the product can be huge far from the language: each child reads the clock
                # and counts against max_symbols while the list of children is built
                tick()
                hold(1 + len(picks))
                new_state = tuple(front for _, front, _ in picks)
                if new_state != state:
                    out.append((f + delta, order, m, new_state,
                                tuple(rw for _, _, rw in picks)))
            lowest[0] = min(lowest[0], f + cut[0])
        out.sort(key=lambda o: (o[0], o[1]))
        return out

    # ------------------------------------------------------------ rounds
    def run(self, lower: float, limit: float | None):
        """Search rounds from bound ``lower``; returns ``(status, cost, path)``.

        ``status`` is ``"found"`` (exact), ``"over"`` (no tuple within
        ``limit``), ``"empty"`` (no tuple at all) or ``"max_states"``; a
        running-out clock or memory raises :class:`~psgs.errors.BoundReached`.
        """
        cap = lower if limit is None else min(lower, limit)
        self.proved = lower
        eps_cap = 4
        raise_by = self.step
        while True:
            # the previous round's visited set is gone; the charts are kept
            self.budget.held = sum(chart.held for chart in self.charts)
            explored = self.explored
            status, lowest, capped = self._round(cap, eps_cap)
            if status == "max_states":
                return "max_states", None, None
            best = self.best[0] if self.best is not None else INF
            # a tuple not reached costs at least the estimate of the state it was cut at
            self.proved = max(self.proved, min(lowest, best))
            # a round that found a tuple looks on only below it by two tolerances, and what it
            # cut then lies a tolerance under it: equal within the tolerance, so found
            if best < INF and best <= lowest + 2 * self.tolerance(best):
                return "found", best, self.best[1]
            if lowest == INF:
                return "empty", None, None
            if limit is not None and cap >= limit and not capped:
                return "over", None, None  # every state within the limit was explored
            if capped:
                eps_cap *= 2
            # The branch and bound within a round returns the cheapest tuple whatever the cap,
            # so the cap may rise by more than the least cost, and must: a round that explored
            # no state learnt only that the cap is too low (where substitutions at 1 are dwarfed
            # by insertions at 10**6, one round per least cost never ended), so the raise
            # doubles while rounds explore nothing; a round that explored raises it by an
            # eighth at least (with pairs at 1e-6 beside edits at 0.1 the states' costs take
            # so many values that one round each ran into max_states). Both stop growing at
            # 2**40 least costs, so the cap stays finite when no round ever explores (a
            # language empty in a way the analysis does not see): the time bound ends it.
            idle = self.explored == explored
            raise_by = min(raise_by * 2, self.step * _MOST_DOUBLED) if idle else self.step
            share = 0.0 if idle else min(cap / _SHARE, self.step * _MOST_DOUBLED)
            cap = max(lowest, cap + raise_by, cap + share)
            if limit is not None:
                cap = min(cap, limit)
            if best < INF:
                cap = min(cap, best)

    def _initial(self):
        return tuple(((cg.index[g.start], 0, ch.n),)
                     for g, cg, ch in zip(self.system.components, self.compiled, self.charts))

    def _round(self, cap: float, eps_cap: int):
        """Depth-first branch and bound over the states with estimate ≤ ``cap``.

        Returns ``(status, lowest, capped)``: ``lowest`` the least estimate
        of a state cut off (by the cap or by ``eps_cap``, the most occurrences
        over empty spans a component may hold), ``capped`` whether the latter
        cut anything.
        """
        self.cap = cap
        tol = self.tolerance(cap)
        initial = self._initial()
        f0 = 0.0
        for c, front in enumerate(initial):
            f0 += self.item_cost(c, front[0], cap)
        if f0 > cap + tol:
            lb = sum(self.charts[c].lower_bound(*front[0]) for c, front in enumerate(initial))
            # the initial state costs more than cap, by how much is not known: cap bounds
            # it (cap + step did not: with costs 0.7 and 1, 1.7 is followed by 2.0, and the
            # overstated bound ended a later search at a tuple that was not the cheapest)
            return "none", max(f0 if f0 < INF else cap, lb), False
        lowest = [INF]
        bound = cap
        if self.best is not None and self.best[0] - tol <= bound:
            bound = self.best[0] - 2 * tol  # only a cheaper tuple is of interest
        visited = {self.key(initial): f0}
        budget = self.budget
        # the walk's mutable facts: the cost bound (lowered by each tuple found), whether the
        # ε cap cut a state
        walk = {"bound": bound, "capped": False}

        def expand(nxt, path):
            f, _, m, state, rewrites = nxt
            if f > walk["bound"] + tol:
                return None
            if any(sum(1 for _, i, j in front if i == j) > eps_cap for front in state):
                walk["capped"] = True
                lowest[0] = min(lowest[0], f)
                return None
            k = self.key(state)
            old = visited.get(k)
            if old is not None and old <= f + tol:
                return None
            visited[k] = f
            self.explored += 1
            budget.hold(1 + sum(len(front) for front in state))
            if all(not front for front in state):
                self.best = (f, [*path, (m, rewrites)])
                if f <= self.proved + tol:
                    return Finish("found")  # no tuple is cheaper than the proved bound
                walk["bound"] = f - 2 * tol
                return None
            if self.explored >= self.max_states:
                return Finish("max_states")
            return (m, rewrites), self.successors(state, f, walk["bound"], lowest)

        status = depth_first(self.successors(initial, f0, bound, lowest), expand, budget.tick)
        if status == "found":
            return "found", INF, walk["capped"]
        if status == "max_states":
            return "max_states", lowest[0], walk["capped"]
        return "done", lowest[0], walk["capped"]


def _bounded_product(slots, slack: float, excess: list):
    """Pick one option per slot with summed delta ≤ slack: yields ``(delta, picks)``.

    A slot is ``(options sorted by delta, same_as_previous)``; a slot marked
    the same as the previous one picks an option at or after the previous
    pick (equal occurrences choose a multiset). ``excess[0]`` is lowered to
    the least sum cut off.
    """
    n = len(slots)
    if n == 0:
        yield 0.0, ()
        return
    picks: list = []
    sums = [0.0]
    starts = [0]
    index = [0]
    while index:
        t = len(index) - 1
        options, _ = slots[t]
        k = index[t]
        if k >= len(options):
            index.pop()
            starts.pop()
            sums.pop()
            if picks:
                picks.pop()
            if index:
                index[-1] += 1
            continue
        total = sums[t] + options[k][0]
        if total > slack + TOLERANCE * abs(slack):
            if total < excess[0]:
                excess[0] = total
            index.pop()  # options are sorted: the later ones cost more
            starts.pop()
            sums.pop()
            if picks:
                picks.pop()
            if index:
                index[-1] += 1
            continue
        if t == n - 1:
            yield total, (*picks, options[k])
            index[t] += 1
            continue
        picks.append(options[k])
        sums.append(total)
        nxt = k if slots[t + 1][1] else 0
        starts.append(nxt)
        index.append(nxt)

