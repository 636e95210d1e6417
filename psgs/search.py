"""Breadth-first search over configurations, the one loop behind ``language(method="search")``.

A PSGS and a PCGS differ only in their successors (:mod:`psgs.steps`), in
what a finished configuration yields (a terminal tuple; the master's word)
and in how a configuration is pruned; the loop, its visited set and its
budgets are the same. Pruning is sound: terminals never disappear from a
form (for a PCGS: unless the master can be reset) and each nonterminal still
costs at least its least terminal yield (:func:`psgs.analysis.min_yields`).
"""

from __future__ import annotations

import math
from collections import deque

from .analysis import min_yields, moves, usable_rules
from .budget import Budget
from .errors import BoundReached
from .model import PCGS, PSGS, Nonterminal, Terminal
from .steps import initial_configuration, is_terminal_form, pcgs_steps, psgs_successors

__all__ = ["psgs_search", "pcgs_search", "SearchResult"]

INFINITE = math.inf


class SearchResult:
    """What a search found: the words, the configurations it kept, the bound it hit.

    ``bound`` is the name of the budget that stopped the search or left
    configurations out (``None`` when complete); ``reason`` says it in words.
    """

    __slots__ = ("found", "explored", "bound", "reason")

    def __init__(self, found: set, explored: int, bound: str | None,
                 reason: str | None) -> None:
        self.found = found
        self.explored = explored
        self.bound = bound
        self.reason = reason


def budget_sentence(bound: str, budget: Budget) -> str:
    """The sentence a result gives when ``max_seconds`` or ``max_symbols`` stopped it."""
    if bound == "max_symbols":
        return (f"stopped when the kept configurations held {budget.held} symbols "
                f"(max_symbols={budget.max_symbols})")
    return f"stopped after {budget.seconds:g} seconds (max_seconds)"


def _form_bound(max_form_length: int) -> str:
    return (f"left out configurations with a form longer than {max_form_length} symbols "
            f"(max_form_length)")


def _breadth_first(start, successors, key, hopeless, finished, max_configurations: int,
                   max_form_length: int, clock: Budget) -> SearchResult:
    """The loop: visit configurations by depth, each once, within the budgets.

    ``key(c)`` identifies a configuration in the visited set; ``hopeless(c, k)``
    prunes it; ``finished(c, found)`` records what a configuration yields and
    says whether its successors may be skipped.
    """
    found: set = set()
    bound = reason = None
    too_long = False
    start_key = key(start)
    seen = {start_key}
    queue = deque([] if hopeless(start, start_key) else [start])
    tick, hold = clock.tick, clock.hold
    try:
        hold(1 + sum(map(len, start)))
        while queue:
            clock.check()
            configuration = queue.popleft()
            if finished(configuration, found):
                continue
            for after in successors(configuration):
                tick()  # per successor: one configuration can have thousands
                k = key(after)
                if k in seen or hopeless(after, k):
                    continue
                if any(len(f) > max_form_length for f in after):
                    too_long = True
                    continue
                if len(seen) >= max_configurations:
                    bound = "max_configurations"
                    reason = f"stopped after {len(seen)} configurations (max_configurations)"
                    queue.clear()
                    break
                seen.add(k)
                hold(1 + sum(map(len, after)))  # memory: configurations × form size
                queue.append(after)
    except BoundReached as stop:
        bound, reason = stop.bound, budget_sentence(stop.bound, clock)
    if too_long:
        bound = bound or "max_form_length"
        reason = "; ".join(filter(None, [reason, _form_bound(max_form_length)]))
    return SearchResult(found, len(seen), bound, reason)


class _Codes:
    """Small integers for a system's symbols, looked up by object identity.

    Hashing a configuration of dataclass symbols calls Python code per
    symbol; keying the visited set by integer codes keeps that in C. Equal
    symbols get equal codes (the table is built by equality once), so the
    keys identify configurations exactly.
    """

    def __init__(self, system) -> None:
        by_value: dict = {}
        self.by_id: dict[int, int] = {}
        self.objects: list = []
        for g in system.components:
            self.note(g.start, by_value)
            for r in g.rules:
                self.note(r.lhs, by_value)
                for sym in r.rhs:
                    self.note(sym, by_value)
        self._by_value = by_value

    def note(self, sym, by_value=None) -> None:
        by_value = self._by_value if by_value is None else by_value
        code = by_value.setdefault(sym, len(by_value))
        if code == len(self.objects):
            self.objects.append(sym)
        self.by_id[id(sym)] = code

    def key(self, configuration) -> tuple:
        get = self.by_id.__getitem__
        try:
            return tuple(tuple(map(get, map(id, f))) for f in configuration)
        except KeyError:  # a symbol object not from the system's rules: learn it
            for f in configuration:
                for sym in f:
                    self.note(sym)
            return self.key(configuration)


def psgs_search(system: PSGS, max_length: int, max_configurations: int,
                max_form_length: int, clock: Budget) -> SearchResult:
    """The terminal tuples of total length ≤ ``max_length`` reachable in ``system``."""
    codes = _Codes(system)
    yields = [min_yields(rules) for rules in usable_rules(system)]

    def weight_table(y) -> list:
        return [1 if isinstance(sym, Terminal) else y.get(sym, INFINITE) for sym in codes.objects]

    weights = [weight_table(y) for y in yields]

    def hopeless(configuration, key) -> bool:
        nonlocal weights
        if len(weights[0]) != len(codes.objects):  # new symbols were learnt
            weights = [weight_table(y) for y in yields]
        total = 0
        for codes_of_form, weight in zip(key, weights):
            total += sum(map(weight.__getitem__, codes_of_form))
        return total > max_length

    eager = _eager_rules(system)
    system_moves = moves(system)

    def successors(configuration):
        if eager:
            forced = _forced_rewrites(configuration, eager)
            if forced is not None:
                return forced
        return (after for _, _, after in psgs_successors(system, configuration, system_moves))

    def finished(configuration, found) -> bool:
        if all(is_terminal_form(f) for f in configuration):
            found.add(configuration)
            return True
        return False

    return _breadth_first(initial_configuration(system), successors, codes.key, hopeless,
                          finished, max_configurations, max_form_length, clock)


def _eager_rules(system: PSGS) -> list[dict] | None:
    """Per component, the nonterminals all of whose rules are unsynchronised, with those rules.

    Only in ``single`` mode under ``free``. Such an occurrence must be
    rewritten some time by one of these rules applied alone, and that step
    commutes with every other step (no tuple touches the occurrence, and
    making a component terminal sooner only lets tuples skip it), so the
    search may rewrite it first: one branch per rule instead of every
    interleaving. Not sound in ``parallel`` mode, where a step rewrites
    occurrences that later steps create.
    """
    if system.mode != "single" or system.unsynchronised != "free":
        return None
    out = []
    for g, synced in zip(system.components, system.synchronised_rules):
        synced_lhs = {r.lhs for r in synced}
        table = {a: rules for a, rules in g.rules_by_lhs.items() if a not in synced_lhs}
        out.append(table)
    return out if any(out) else None


def _forced_rewrites(configuration, eager) -> list | None:
    for i, (form, table) in enumerate(zip(configuration, eager)):
        for k, sym in enumerate(form):
            rules = table.get(sym)
            if rules:
                head, tail = form[:k], form[k + 1:]
                return [configuration[:i] + (head + r.rhs + tail,) + configuration[i + 1:]
                        for r in rules if r.rhs != (sym,)]
    return None


def pcgs_search(system: PCGS, max_length: int, max_configurations: int,
                max_form_length: int, clock: Budget) -> SearchResult:
    """The master's terminal words of length ≤ ``max_length`` reachable in ``system``."""
    master = system.master_index
    master_queried = any(q.component == system.master for g in system.components
                         for q in g.queries)
    # Terminals never leave a form except when it is sent away in returning mode.
    can_prune = not (system.returning and master_queried)
    yields = min_yields(system.components[master].rules, query_yield=0)

    def hopeless(configuration, _key) -> bool:
        if not can_prune:
            return False
        total = 0
        for s in configuration[master]:
            if s.__class__ is Terminal:
                total += 1
            elif s.__class__ is Nonterminal:
                total += yields.get(s, INFINITE)
        return total > max_length

    def finished(configuration, found) -> bool:
        form = configuration[master]
        if not is_terminal_form(form):
            return False
        if len(form) <= max_length:
            found.add(form)
        return can_prune  # nobody can reset the master, so its word never changes again

    def successors(configuration):
        return (step.after for step in pcgs_steps(system, configuration))

    return _breadth_first(initial_configuration(system), successors, lambda c: c, hopeless,
                          finished, max_configurations, max_form_length, clock)
