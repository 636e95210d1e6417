"""Membership for PCGS: a bounded breadth-first search over configurations.

Membership is undecidable for PCGS in general, so the search answers ``yes``
(with the derivation that reached the word), ``no`` only when it has
explored every configuration from which the master could still derive the
word, or ``unknown`` naming the budget that ran out (``max_steps``,
``max_states`` or ``max_seconds``).

Pruning by the master's word ``w`` is sound whenever the master's form is
never thrown away, i.e. unless the system is returning and some component
queries the master: then terminals in the master's form stay for good, so

* its terminal runs must occur in ``w`` in order, the first one as a prefix
  and the last one as a suffix (the symbols in between only add text), and
* its terminals plus the least yield of its nonterminals (a query may yield
  nothing) cannot exceed ``len(w)``.

Configurations are compared exactly, so the visited set never merges two
different ones; the other components are not pruned (their forms only matter
when queried, and they may block the system).
"""

from __future__ import annotations

import math
from collections import deque

from ..analysis import min_yields
from ..budget import Budget
from ..errors import BoundReached
from ..model import PCGS, Nonterminal, Query, Terminal, Word
from ..steps import initial_configuration, pcgs_steps
from .result import Acceptance
from .witness import PCGSSchedule

__all__ = ["accepts_pcgs"]


def _master_can_reset(system: PCGS) -> bool:
    if not system.returning:
        return False
    master = Query(system.master)
    return any(master in g.queries for g in system.components)


def _fits(form, word: Word, yields: dict) -> bool:
    """Can ``form`` still become ``word`` (terminals kept, other symbols replaced by text)?"""
    runs: list[list[Terminal]] = [[]]
    floor = 0
    for s in form:
        if isinstance(s, Terminal):
            runs[-1].append(s)
            floor += 1
        else:
            if isinstance(s, Nonterminal):
                floor += yields.get(s, math.inf)
            runs.append([])
    if floor > len(word):
        return False
    if len(runs) == 1:
        return tuple(runs[0]) == word
    first, last = runs[0], runs[-1]
    if tuple(word[:len(first)]) != tuple(first):
        return False
    if last and tuple(word[len(word) - len(last):]) != tuple(last):
        return False
    at = len(first)
    end = len(word) - len(last)
    for run in runs[1:-1]:
        if not run:
            continue
        found = _find(word, run, at, end)
        if found < 0:
            return False
        at = found + len(run)
    return at <= end


def _find(word: Word, run: list, start: int, end: int) -> int:
    n = len(run)
    for k in range(start, end - n + 1):
        if list(word[k:k + n]) == run:
            return k
    return -1


def accepts_pcgs(system: PCGS, word: Word, *, max_steps: int, max_states: int,
                 budget: Budget) -> Acceptance:
    """Breadth-first search for a derivation of ``word`` by the master (yes / no / unknown).

    ``budget`` was started by the caller; the search reads its clock per
    generated step and counts every configuration it keeps (in symbols).

    Examples
    --------
    >>> import psgs
    >>> copy = psgs.load("grammars/pcgs_copy.psgs")
    >>> from psgs.model import as_word
    >>> from psgs.budget import Budget
    >>> accepts_pcgs(copy, as_word("abab"), max_steps=50, max_states=10_000,
    ...              budget=Budget(seconds=10)).answer
    'yes'
    """
    try:
        return _search(system, word, max_steps, max_states, budget)
    except BoundReached as stop:
        if stop.bound == "max_symbols":
            reason = (f"the search kept {budget.held} symbols in its configurations, more than "
                      f"max_symbols={budget.max_symbols}")
        else:
            reason = f"the search ran out of time after {budget.seconds:g} s"
        return Acceptance("unknown", reason=reason, bound=stop.bound, system=system)


def _search(system: PCGS, word: Word, max_steps: int, max_states: int,
            budget: Budget) -> Acceptance:
    # every terminal of the master's word comes from some component's rules
    foreign = next((t for t in word if t not in system.terminals), None)
    if foreign is not None:
        return Acceptance("no", reason=f"{foreign} is a terminal of no component",
                          states=0, system=system)
    m = system.master_index
    prune = not _master_can_reset(system)
    yields = min_yields(system.components[m].rules, query_yield=0)
    start = initial_configuration(system)
    if prune and not _fits(start[m], word, yields):
        return Acceptance("no", reason="the master cannot derive a word of this length or shape",
                          states=1, system=system)
    parent: dict = {start: None}
    queue = deque([(start, 0)])
    cut_by_steps = False
    explored = 0
    while queue:
        configuration, depth = queue.popleft()
        explored += 1
        if depth >= max_steps:
            cut_by_steps = True
            continue
        for step in pcgs_steps(system, configuration):
            budget.tick()
            after = step.after
            if after in parent:
                continue
            master = after[m]
            if prune and not _fits(master, word, yields):
                continue
            parent[after] = step
            budget.hold(1 + sum(map(len, after)))
            if all(isinstance(s, Terminal) for s in master):
                if master == word:
                    return Acceptance("yes", states=explored, system=system,
                                      plan=_path(parent, after))
                if prune:
                    continue  # nobody can reset the master: its word is final
                # otherwise a query may send the master's word away and restart it
            if len(parent) >= max_states:
                return Acceptance(
                    "unknown", reason=f"the search stopped after {len(parent)} configurations "
                    f"(max_states={max_states})", bound="max_states", states=explored,
                    system=system)
            queue.append((after, depth + 1))
    if cut_by_steps:
        return Acceptance("unknown", reason=f"derivations longer than {max_steps} steps were not "
                          f"explored (max_steps={max_steps})", bound="max_steps", states=explored,
                          system=system)
    reason = ("every configuration from which the master could still derive the word was "
              "explored" if prune else "every reachable configuration was explored")
    return Acceptance("no", reason=reason, states=explored, system=system)


def _path(parent: dict, end) -> PCGSSchedule:
    steps = []
    node = end
    while parent[node] is not None:
        step = parent[node]
        steps.append(step)
        node = step.before
    return PCGSSchedule(tuple(reversed(steps)))
