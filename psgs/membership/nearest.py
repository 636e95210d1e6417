"""Distance to the language: :func:`nearest` and the :class:`Nearest` it returns.

For a PSGS and a word tuple ``w``, the distance is the least
``Σᵢ d(wᵢ, uᵢ)`` over the tuples ``u`` of L(Γ), ``d`` the edit distance
(unit insertion, deletion and substitution unless :class:`EditCosts` say
otherwise). Each component's distance to its context-free language
(:mod:`psgs.membership.error_chart`) is a lower bound; the synchronised
search (:mod:`psgs.membership.nearest_search`) raises it to the exact
distance. For a PCGS the master's word is compared with the master words a
bounded search derives. See ``docs/membership.md``.
"""

from __future__ import annotations

import gc
import math
import numbers
from collections import deque
from dataclasses import dataclass, field
from functools import cached_property

from .._foundation.text import finite
from ..analysis import usable_rules
from ..budget import Budget, check_count, check_seconds
from ..errors import BoundReached, ValidationError
from ..model import PCGS, PSGS, Terminal, Word, as_word
from ..steps import initial_configuration, pcgs_steps
from .chart import CompiledGrammar
from .costs import Edit, EditCosts, edit_costs
from .error_chart import INF, TOLERANCE, ErrorChart
from .nearest_search import DistanceSearch
from .parallel_distance import FormSearch, multiplies
from .words import coerce_words
from .witness import PCGSSchedule, PSGSSchedule, Rewrite, ScheduledMove, replay

__all__ = ["Nearest", "nearest"]

#: Each round of a component distance at least doubles its cost cap (measured: 1.5 and 3
#: no faster on Γ with 1% and 5% random edits)
_GROWTH = 2


@dataclass(frozen=True)
class Nearest:
    """The answer of :func:`nearest`: how far the words are from the language, and the nearest tuple.

    Attributes
    ----------
    distance : float or None
        The least total edit cost (an ``int`` for whole-number costs). When
        ``exact`` is false it is an upper bound (the cheapest tuple found
        before a budget ran out), or ``None`` when no tuple was found (a
        budget ran out first, no tuple is within ``max_errors``, or the
        language is empty).
    exact : bool
        Whether ``distance`` is proved least.
    lower_bound : float
        Every tuple of the language is at least this far (``distance`` when
        exact; more than ``max_errors`` when ``bound == "max_errors"``).
    words : tuple of words, or a word, or None
        A nearest tuple (PSGS) or master word (PCGS).
    edits : tuple
        Per component (PSGS) the edit script from the input word to the
        nearest word, as :class:`~psgs.membership.costs.Edit` values in
        order of position; for a PCGS one script.
    bound : str or None
        Why the answer is not exact: ``"max_errors"``, ``"max_seconds"``,
        ``"max_states"``, ``"max_symbols"`` or (PCGS) ``"max_steps"``.
    reason : str or None
        The same in words, or why there is no tuple.
    states : int
        Search states explored.
    system : PSGS or PCGS, optional
        The system asked about (to replay the witness).
    schedule : PSGSSchedule or PCGSSchedule, optional
        What the witness is replayed from.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> result = psgs.nearest(gamma, ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbxad"])
    >>> result.distance, result.exact, "".join(map(str, result.words[3]))
    (1, True, 'abcdbcad')
    >>> [str(edit) for edit in result.edits[3]]
    ['substitute x→c at 5']
    >>> result.witness.words == result.words
    True
    """

    distance: float | None
    exact: bool
    lower_bound: float
    words: tuple | None = None
    edits: tuple = ()
    bound: str | None = None
    reason: str | None = None
    states: int = 0
    system: PSGS | PCGS | None = field(default=None, repr=False, compare=False)
    schedule: object = field(default=None, repr=False, compare=False)

    @cached_property
    def witness(self):
        """The derivation of ``words`` (replayed and checked), or ``None`` without a tuple."""
        if self.schedule is None:
            return None
        return replay(self.system, self.schedule)

    def __str__(self) -> str:
        if self.distance is None:
            return f"no tuple found: {self.reason}"
        head = f"distance {_show(self.distance)}"
        if not self.exact:
            head += f" (an upper bound; at least {_show(self.lower_bound)}: {self.reason})"
        return head


def _show(x) -> str:
    return f"{x:g}" if isinstance(x, float) else str(x)


def _check_budgets(max_errors, max_states, max_seconds, max_steps, max_symbols) -> None:
    if max_errors is not None:
        if isinstance(max_errors, bool) or not isinstance(max_errors, numbers.Real) or \
                not finite(max_errors) or max_errors < 0:  # NaN, inf, 10**400
            raise ValidationError(f"max_errors must be a finite number ≥ 0 or None, "
                                  f"not {max_errors!r}")
    for name, value in (("max_states", max_states), ("max_steps", max_steps),
                        ("max_symbols", max_symbols)):
        check_count(value, name)
    check_seconds(max_seconds)


def nearest(system: PSGS | PCGS, words, *, max_errors: float | None = None, costs=None,
            max_states: int = 200_000, max_seconds: float = 30.0, max_steps: int = 200,
            max_symbols: int = 10_000_000) -> Nearest:
    """The nearest word tuple of the language to ``words``, its distance and the edits.

    PSGS (both modes, both policies): ``words`` holds one word per component
    (as for :func:`psgs.accepts`); a symbol outside the system's alphabet is
    an input like any other (it is deleted or substituted). The distance is
    the least sum over components of each word's edit distance to the
    tuple's word; ``0`` exactly when :func:`psgs.accepts` says yes (when
    every cost is positive).
    ``max_errors`` bounds the search: no tuple within it gives
    ``distance=None`` with ``bound="max_errors"``. The budgets are those of
    ``accepts``; when one runs out the answer is not ``exact``: ``distance``
    is the cheapest tuple found (or ``None``) and ``lower_bound`` what was
    proved. PCGS: ``words`` is the master's word, compared with the master
    words a breadth-first search derives within ``max_steps``.

    Parameters
    ----------
    system : PSGS or PCGS
        The system.
    words : sequence of words, or a word
        One word per component (PSGS) or the master's word (PCGS).
    max_errors : float or None, default None
        The largest distance of interest.
    costs : None, mapping or EditCosts, default None
        Unit costs when ``None``; see :func:`psgs.membership.costs.edit_costs`.
    max_states, max_seconds, max_steps, max_symbols
        Budgets, as for :func:`psgs.accepts`.

    Returns
    -------
    Nearest

    Raises
    ------
    ValidationError
        Bad costs, the wrong number of words, a bad ``max_errors`` or a
        budget that is not positive.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> psgs.nearest(gamma, ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad"]).distance
    0
    >>> far = psgs.nearest(gamma, ["abcdbcad", "bcadabcd", "cdabcdab", "abcd"], max_errors=2)
    >>> far.distance, far.bound, far.lower_bound > 2
    (None, 'max_errors', True)
    """
    _check_budgets(max_errors, max_states, max_seconds, max_steps, max_symbols)
    if max_errors is not None:  # a numpy number (as edit costs are) as the Python one it is
        max_errors = int(max_errors) if isinstance(max_errors, numbers.Integral) \
            else float(max_errors)
    table = edit_costs(costs)
    budget = Budget(max_seconds, max_symbols, every=32)
    if isinstance(system, PCGS):
        return _nearest_pcgs(system, as_word(words), table, max_errors, max_steps, max_states,
                             budget)
    if not isinstance(system, PSGS):
        raise ValidationError(f"expected a PSGS or a PCGS, not {type(system).__name__}")
    tuple_of_words = coerce_words(system, words)
    collecting = gc.isenabled()
    gc.disable()  # as in accepts: the search allocates many short-lived tuples, no cycles
    try:
        return _nearest_psgs(system, tuple_of_words, table, max_errors, max_states, budget)
    finally:
        if collecting:
            gc.enable()


def _whole(x, costs: EditCosts):
    integral = all(float(v).is_integer() for v in _all_costs(costs))
    return int(round(x)) if integral and x is not None and x < INF else x


def _all_costs(costs: EditCosts):
    yield from (costs.insert, costs.delete, costs.substitute)
    yield from costs.insert_symbol.values()
    yield from costs.delete_symbol.values()
    yield from costs.pairs.values()


def _nearest_psgs(system: PSGS, words, costs: EditCosts, max_errors, max_states,
                  budget: Budget) -> Nearest:
    terminals = sorted(system.terminals)
    ids = {t: k for k, t in enumerate(terminals)}
    symbol_of = list(terminals)
    for w in words:
        for t in w:
            if t not in ids:  # outside the alphabet: an id no terminal of a rule has
                ids[t] = len(symbol_of)
                symbol_of.append(t)
    insert = [costs.insertion(t) for t in terminals]
    positive = [v for v in _all_costs(costs) if v > 0]
    step = min(positive) if positive else 1.0
    unit = costs.unit
    search = None
    try:
        compiled, charts = [], []
        usable = usable_rules(system)
        for c, (g, w) in enumerate(zip(system.components, words)):
            cg = CompiledGrammar(g, {t: ids[t] for t in terminals}, usable[c], budget)
            ws = [ids[t] for t in w]
            if unit:
                def sub(p, t, ws=ws):
                    return 0 if ws[p] == t else 1
            else:
                def sub(p, t, w=w):
                    return costs.substitution(w[p], symbol_of[t])
            compiled.append(cg)
            charts.append(ErrorChart(cg, ws, insert, [costs.deletion(t) for t in w], sub, budget))
        # parallel mode with a rule that multiplies its nonterminal (S → S S): the span search
        # would choose a split per occurrence, and the chart of each component alone is cubic
        # (every span of S → S S); the forms themselves are few, and bound themselves
        forms = system.mode == "parallel" and any(map(multiplies, compiled))
        lower = 0.0
        for g, cg, chart in zip(system.components, compiled, charts):
            if chart.min_yield[cg.index[g.start]] == INF:
                return Nearest(None, True, INF, reason=f"component {g.name} derives no word, "
                               "so the language is empty", system=system)
            if forms:
                continue
            d = _component_distance(chart, cg.index[g.start], step, max_errors)
            if d == INF:
                return _over(system, max_errors, lower, costs)
            lower += d
        # the components' distances, summed in another order than the search sums a tuple's
        # edits, may lie a hair over a max_errors the tuple meets (0.4 + 0.2 > 0.6)
        if max_errors is not None and lower > max_errors + TOLERANCE * (
                max_errors + sum(chart.scale for chart in charts)):
            return _over(system, max_errors, lower, costs)
        kind = FormSearch if forms else DistanceSearch
        search = kind(system, compiled, charts, max_states, budget, step)
        search.words = words
        status, cost, path = search.run(lower, max_errors)
        if status == "found":
            return _answer(search, cost, path, costs, exact=True)
        if status == "over":
            return _over(system, max_errors, search.proved, costs, search.explored)
        if status == "empty":
            return Nearest(None, True, INF, reason="no tuple of the language exists (no "
                           "schedule of the tuples derives terminal words)",
                           states=search.explored, system=system)
        reason = f"the search stopped after {search.explored} states (max_states={max_states})"
        return _partial(search, "max_states", reason, costs)
    except BoundReached as stop:
        if search is None:
            return Nearest(None, False, 0, bound=stop.bound, reason=_budget_reason(stop, budget),
                           system=system)
        return _partial(search, stop.bound, _budget_reason(stop, budget), costs)


def _budget_reason(stop: BoundReached, budget: Budget) -> str:
    if stop.bound == "max_symbols":
        return (f"the search kept {budget.held} symbols in its states, more than "
                f"max_symbols={budget.max_symbols}")
    return f"the search ran out of time after {budget.seconds:g} s"


def _component_distance(chart: ErrorChart, start: int, step: float, max_errors) -> float:
    """One component's distance to its context-free language (``inf`` past ``max_errors``)."""
    ceiling = chart.deleted[chart.n] + chart.min_yield[start]  # delete all, insert the least
    if ceiling == INF:
        return INF
    cap = max(step, chart.lower_bound(start, 0, chart.n))
    while True:
        if max_errors is not None:
            cap = min(cap, max_errors)
        cap = min(cap, ceiling)
        d = chart.cost(start, 0, chart.n, cap)
        if d == INF and cap >= ceiling and (max_errors is None or ceiling <= max_errors):
            return ceiling  # deleting all and inserting the least costs it: summed otherwise,
            # the chart can read a hair more, over the cap it was asked for
        if d < INF or cap >= ceiling or (max_errors is not None and cap >= max_errors):
            return d
        cap = _GROWTH * cap + step


def _over(system, max_errors, proved, costs, states=0) -> Nearest:
    # proved: every tuple costs at least this; and more than max_errors, which was searched
    return Nearest(None, True, max(proved, math.nextafter(max_errors, INF)), bound="max_errors", reason=f"no tuple of the language is within "
                   f"max_errors={max_errors}", states=states, system=system)


def _partial(search: DistanceSearch, bound: str, reason: str, costs) -> Nearest:
    if search.best is None:
        return Nearest(None, False, _whole(search.proved, costs), bound=bound, reason=reason,
                       states=search.explored, system=search.system)
    cost, path = search.best
    found = _answer(search, cost, path, costs, exact=False)
    return Nearest(found.distance, False, _whole(min(search.proved, cost), costs), found.words,
                   found.edits, bound=bound, reason=reason, states=search.explored,
                   system=search.system, schedule=found.schedule)


# ------------------------------------------------------------------ the nearest tuple
def _answer(search: DistanceSearch, cost: float, path, costs: EditCosts, exact: bool) -> Nearest:
    """Rebuild the derivation trees the path chose, the nearest words, the schedule, the edits."""
    system = search.system
    n = len(system.components)
    nodes = [[] for _ in range(n)]  # per component: [symbol, i, j, rule, bounds, children]
    pending = [dict() for _ in range(n)]
    for c, (g, cg, chart) in enumerate(zip(system.components, search.compiled, search.charts)):
        nodes[c].append([cg.index[g.start], 0, chart.n, None, None, None])
        pending[c][(cg.index[g.start], 0, chart.n)] = [0]
    order = []  # per move: per component the node ids it rewrote
    for m, rewrites in path:
        taken = []
        for c, rule in enumerate(search.move_rule_ids[m]):
            ids = []
            # the occurrences a move rewrites are taken before any child is made: a child over
            # the same span (S → S S over an empty span) is no occurrence of this move
            taken_here = [pending[c][item].pop() for item, _ in rewrites[c]]
            for nid, ((a, i, j), bounds) in zip(taken_here, rewrites[c]):
                node = nodes[c][nid]
                body = search.compiled[c].body[rule]
                children = []
                if body:
                    for t, s in enumerate(body):
                        p, q = bounds[t], bounds[t + 1]
                        if s < 0:
                            children.append(("t", ~s, p, q))
                        else:
                            kid = len(nodes[c])
                            nodes[c].append([s, p, q, None, None, None])
                            pending[c].setdefault((s, p, q), []).append(kid)
                            children.append(("n", kid))
                node[3], node[4], node[5] = rule, bounds, children
                ids.append(nid)
            taken.append(ids)
        order.append((m, taken))
    words, spans, edits = [], [], []
    for c in range(n):
        word, span, script = _flatten(search, c, nodes[c], costs)
        words.append(word)
        spans.append(span)
        edits.append(script)
    moves = []
    for m, taken in order:
        per_component = []
        for c, ids in enumerate(taken):
            rws = []
            for nid in ids:
                sym, _, _, rule, _, children = nodes[c][nid]
                start, end = spans[c][nid]
                split = [start]
                for child in children:
                    split.append(split[-1] + 1 if child[0] == "t" else spans[c][child[1]][1])
                rws.append(Rewrite(search.compiled[c].nonterminals[sym], start, end,
                                   tuple(split)))
            per_component.append(tuple(rws))
        moves.append(ScheduledMove(search.moves[m], tuple(per_component)))
    words = tuple(words)
    schedule = PSGSSchedule(words, tuple(moves))
    total = sum(e.cost for script in edits for e in script)
    return Nearest(_whole(total, costs), exact, _whole(total if exact else search.proved, costs),
                   words, tuple(edits), states=search.explored, system=system, schedule=schedule)


def _flatten(search: DistanceSearch, c: int, nodes, costs: EditCosts):
    """The word a component's tree yields, each node's span in it, and the edit script."""
    chart = search.charts[c]
    terminal_of = search.compiled[c].terminal_of
    original = search.words[c]
    word: list[Terminal] = []
    spans: dict[int, tuple[int, int]] = {}
    script: list[Edit] = []
    stack = [("enter", 0)]
    while stack:
        kind, x = stack.pop()
        if kind == "exit":
            spans[x] = (spans[x][0], len(word))
            continue
        if kind == "leaf":
            t, p, q = x
            word.append(terminal_of[t])
            script.extend(_leaf_edits(chart, original, terminal_of[t], t, p, q, costs))
            continue
        sym, i, j, rule, bounds, children = nodes[x]
        spans[x] = (len(word), None)
        stack.append(("exit", x))
        if not children:
            # an empty body over a span: its symbols are deleted
            script.extend(Edit("delete", p, original[p], None, costs.deletion(original[p]))
                          for p in range(i, j))
        for child in reversed(children or []):
            if child[0] == "t":
                stack.append(("leaf", child[1:]))
            else:
                stack.append(("enter", child[1]))
    return tuple(word), spans, tuple(script)


def _leaf_edits(chart: ErrorChart, original, terminal: Terminal, t: int, p: int, q: int,
                costs: EditCosts):
    """The cheapest edits turning ``original[p:q]`` into the one terminal (cost = terminal_cost)."""
    if p == q:
        return [Edit("insert", p, None, terminal, costs.insertion(terminal))]
    target = chart.terminal_cost(t, p, q)
    dels = chart.deleted[q] - chart.deleted[p]
    for r in range(p, q):
        here = chart.substitute(r, t)
        if abs(dels - chart.delete[r] + here - target) <= chart.tolerance(target):
            out = [Edit("delete", k, original[k], None, chart.delete[k]) for k in range(p, r)]
            if here or original[r] != terminal:
                out.append(Edit("substitute", r, original[r], terminal, here))
            out += [Edit("delete", k, original[k], None, chart.delete[k])
                    for k in range(r + 1, q)]
            return out
    return [Edit("insert", p, None, terminal, costs.insertion(terminal))] + \
        [Edit("delete", k, original[k], None, chart.delete[k]) for k in range(p, q)]


# ------------------------------------------------------------------ PCGS
def _edit_distance(a: Word, b: Word, costs: EditCosts) -> float:
    prev = [0.0]
    for t in b:
        prev.append(prev[-1] + costs.insertion(t))
    for x in a:
        row = [prev[0] + costs.deletion(x)]
        for k, t in enumerate(b):
            row.append(min(prev[k] + costs.substitution(x, t), prev[k + 1] + costs.deletion(x),
                           row[k] + costs.insertion(t)))
        prev = row
    return prev[-1]


def _alignment(a: Word, b: Word, costs: EditCosts) -> tuple[Edit, ...]:
    rows = [[0.0] * (len(b) + 1) for _ in range(len(a) + 1)]
    for k, t in enumerate(b):
        rows[0][k + 1] = rows[0][k] + costs.insertion(t)
    for i, x in enumerate(a):
        rows[i + 1][0] = rows[i][0] + costs.deletion(x)
        for k, t in enumerate(b):
            rows[i + 1][k + 1] = min(rows[i][k] + costs.substitution(x, t),
                                     rows[i][k + 1] + costs.deletion(x),
                                     rows[i + 1][k] + costs.insertion(t))
    out = []
    i, k = len(a), len(b)
    while i or k:
        here = rows[i][k]
        if i and k and here == rows[i - 1][k - 1] + costs.substitution(a[i - 1], b[k - 1]):
            if a[i - 1] != b[k - 1]:
                out.append(Edit("substitute", i - 1, a[i - 1], b[k - 1],
                                costs.substitution(a[i - 1], b[k - 1])))
            i, k = i - 1, k - 1
        elif i and here == rows[i - 1][k] + costs.deletion(a[i - 1]):
            out.append(Edit("delete", i - 1, a[i - 1], None, costs.deletion(a[i - 1])))
            i -= 1
        else:
            out.append(Edit("insert", i, None, b[k - 1], costs.insertion(b[k - 1])))
            k -= 1
    return tuple(reversed(out))


def _nearest_pcgs(system: PCGS, word: Word, costs: EditCosts, max_errors, max_steps: int,
                  max_states: int, budget: Budget) -> Nearest:
    """Breadth-first over configurations; every terminal master word is compared with ``word``.

    Exact when the distance is 0 or every reachable configuration was explored.
    """
    m = system.master_index
    start = initial_configuration(system)
    parent: dict = {start: None}
    queue = deque([(start, 0)])
    best = None  # (distance, master word, configuration)
    cut = None
    explored = 0
    try:
        while queue:
            configuration, depth = queue.popleft()
            explored += 1
            if depth >= max_steps:
                cut = cut or "max_steps"
                continue
            for step in pcgs_steps(system, configuration):
                budget.tick()
                after = step.after
                if after in parent:
                    continue
                parent[after] = step
                budget.hold(1 + sum(map(len, after)))
                master = after[m]
                if all(isinstance(s, Terminal) for s in master):
                    d = _edit_distance(word, master, costs)
                    if best is None or d < best[0]:
                        best = (d, master, after)
                        if d == 0:
                            queue.clear()
                            break
                if len(parent) >= max_states:
                    raise BoundReached("max_states")
                queue.append((after, depth + 1))
    except BoundReached as stop:
        cut = stop.bound
    exact = best is not None and (best[0] == 0 or cut is None)
    if best is None or (max_errors is not None and best[0] > max_errors):
        if cut is None:
            reason = ("the master derives no word" if best is None else
                      f"no master word is within max_errors={max_errors}")
            return Nearest(None, True, INF if best is None else best[0],
                           bound=None if best is None else "max_errors", reason=reason,
                           states=explored, system=system)
        return Nearest(None, False, 0, bound=cut, reason=_pcgs_reason(cut, budget, max_steps,
                       max_states), states=explored, system=system)
    steps = []
    node = best[2]
    while parent[node] is not None:
        steps.append(parent[node])
        node = parent[node].before
    schedule = PCGSSchedule(tuple(reversed(steps)))
    distance = _whole(best[0], costs)
    return Nearest(distance, exact, distance if exact else 0, best[1],
                   _alignment(word, best[1], costs), bound=None if exact else cut,
                   reason=None if exact else _pcgs_reason(cut, budget, max_steps, max_states),
                   states=explored, system=system, schedule=schedule)


def _pcgs_reason(cut: str, budget: Budget, max_steps: int, max_states: int) -> str:
    if cut == "max_steps":
        return f"derivations longer than {max_steps} steps were not explored"
    if cut == "max_states":
        return f"the search stopped at {max_states} configurations"
    if cut == "max_symbols":
        return f"the search kept more than max_symbols={budget.max_symbols} symbols"
    return f"the search ran out of time after {budget.seconds:g} s"
