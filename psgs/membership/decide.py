"""PSGS membership: the fast path, the parse of each word, the spine check, the general search.

:func:`accepts_psgs` first tries the block-by-block fast path
(:mod:`psgs.membership.block_search`) where it applies; it only ever answers
yes. Otherwise each word is parsed (:mod:`psgs.membership.chart`), the
recursive parts are checked alone (a relaxation that proves most no answers
at once), and the general schedule search
(:mod:`psgs.membership.schedule_search`) decides. See ``docs/membership.md``.
"""

from __future__ import annotations

from ..analysis import usable_rules
from ..budget import Budget
from ..errors import BoundReached
from ..model import PSGS, Terminal, Word
from .block_search import lockstep_accepts, lockstep_applies
from .chart import Chart, CompiledGrammar
from .result import Acceptance
from .schedule_search import _ScheduleSearch, _spine, _Substrings

__all__ = ["accepts_psgs"]


def accepts_psgs(system: PSGS, words: tuple[Word, ...], max_states: int,
                 budget: Budget, *, fast: bool = True) -> Acceptance:
    """Decide ``words ∈ L(system)``; ``budget`` was started by the caller, before any analysis.

    ``fast=False`` skips the block-by-block fast path (the tests compare the two).

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> from psgs.model import as_word
    >>> words = tuple(as_word(w) for w in ("abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad"))
    >>> from psgs.budget import Budget
    >>> accepts_psgs(gamma, words, max_states=10_000, budget=Budget(seconds=10)).answer
    'yes'
    """
    terminal_ids: dict[Terminal, int] = {}
    for t in sorted(system.terminals):
        terminal_ids[t] = len(terminal_ids)
    for g, w in zip(system.components, words):
        if set(w) <= g.terminals:
            continue
        for k, t in enumerate(w):
            if t not in g.terminals:
                return Acceptance("no", reason=(
                    f"component {g.name}'s word is not in its context-free language "
                    f"({t} at position {k + 1} is not one of its terminals)"), system=system)
    search = None
    try:
        compiled, charts = [], []
        usable = usable_rules(system)
        for c, (g, w) in enumerate(zip(system.components, words)):
            # a rule in no tuple can never apply under 'strict': parse without it, so a word
            # that needs it is refused by the chart instead of by an endless schedule search
            cg = CompiledGrammar(g, terminal_ids, usable[c], budget)
            compiled.append(cg)
            charts.append(Chart(cg, list(map(terminal_ids.__getitem__, w)), budget))
        substrings = [_Substrings(chart.word) for chart in charts]
        if fast and lockstep_applies(compiled):
            # a yes found block by block is exact; anything else is decided below
            quick = lockstep_accepts(system, compiled, charts, substrings,
                                     max(1, max_states // 4), budget)
            if quick is not None:
                return quick
        for g, cg, chart, w in zip(system.components, compiled, charts, words):
            if not chart.derives(cg.index[g.start], 0, len(w)):
                scope = (" (under 'strict', taking only the rules that are in some tuple)"
                         if system.unsynchronised == "strict" else "")
                return Acceptance("no", reason=(
                    f"component {g.name}'s word is not in its context-free language{scope}"),
                    system=system)
        spine = _spine_check(system, compiled, charts, substrings, max_states, budget)
        if spine is not None:
            return spine
        search = _ScheduleSearch(system, compiled, charts, max_states, budget,
                                 substrings=substrings)
        return search.run()
    except BoundReached as stop:
        explored = search.explored if search is not None else 0
        if stop.bound == "max_symbols":
            reason = (f"the parse charts and the search kept {budget.held} symbols, more "
                      f"than max_symbols={budget.max_symbols} ({explored} states)")
        else:
            reason = (f"the search ran out of time after {budget.seconds:g} s "
                      f"({explored} states)")
        return Acceptance("unknown", reason=reason, bound=stop.bound, states=explored,
                          system=system)


def _spine_check(system, compiled, charts, substrings, max_states, budget) -> Acceptance | None:
    """A fast necessary condition: can the recursive parts (the spines) be scheduled alone?

    Tracking only the occurrences of spine nonterminals (an upward-closed set:
    a spine occurrence is only ever created by rewriting a spine occurrence)
    relaxes the system: a tuple asks nothing of a component whose entry
    rewrites a non-spine symbol, and a component with no spine occurrence
    left skips its entry. Every derivation projects onto a schedule of this
    relaxation, so when the relaxation has none the answer is a proved no.
    Its states are few (spines are short frontiers), whereas the full search
    would wander through the interleavings of the independent blocks.
    """
    focus = [_spine(cg) for cg in compiled]
    if all(len(f) == len(cg.nonterminals) for f, cg in zip(focus, compiled)) or \
            not any(focus):
        return None
    relaxed = _ScheduleSearch(system, compiled, charts, max(1, max_states // 4), budget,
                              focus=focus, substrings=substrings)
    result = relaxed.run()
    if result.answer == "no":
        return Acceptance("no", reason="every component parses but no schedule of the tuples "
                          "fits (even their recursive parts cannot be synchronised)",
                          states=result.states, system=system)
    return None
