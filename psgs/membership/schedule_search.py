"""PSGS membership: parse each word, then search for a synchronised schedule.

Each component's word is parsed by a goal-directed chart
(:mod:`psgs.membership.chart`); then a depth-first search looks for a
synchronised schedule over *span-annotated frontiers*: per component, the
multiset of nonterminal occurrences still in the sentential form, each tagged
with the span ``(i, j)`` of the word it must derive. A tuple rewrites, per
component, one occurrence (``single``) or every occurrence of its left-hand
side (``parallel``), choosing for each a split of its span that the chart
allows. States are memoised up to equal substrings: occurrences ``(A, i, j)``
and ``(A, i', j')`` with ``w[i:j] == w[i':j']`` have the same futures, so a
state is keyed by its multiset of (nonterminal, substring class). Substring
classes are found with a polynomial rolling hash and confirmed by comparing
the substrings, so a hash collision can cost time but never a wrong answer.
See ``docs/membership.md``.
"""

from __future__ import annotations

import itertools
import time
from collections.abc import Sequence

from ..analysis import moves as system_moves, reachable, usable_rules
from ..errors import BoundReached
from ..model import IDLE, PSGS, Terminal, Word
from .chart import Chart, CompiledGrammar
from .result import Acceptance
from .witness import PSGSSchedule, Rewrite, ScheduledMove

__all__ = ["accepts_psgs"]


class _Substrings:
    """Exact equality classes of the substrings of one word, in O(1) expected per query."""

    _MOD = (1 << 61) - 1
    _BASE = 1_000_003

    def __init__(self, word: Sequence[int]) -> None:
        self.word = list(word)
        prefix = [0]
        power = [1]
        h = 0
        for x in self.word:
            h = (h * self._BASE + x + 1) % self._MOD
            prefix.append(h)
            power.append(power[-1] * self._BASE % self._MOD)
        self.prefix = prefix
        self.power = power
        self.classes: dict[tuple[int, int], list[tuple[int, int]]] = {}
        self.cache: dict[tuple[int, int], int] = {}
        self.next_class = 0

    def of(self, i: int, j: int) -> int:
        key = (i, j)
        found = self.cache.get(key)
        if found is not None:
            return found
        length = j - i
        h = (self.prefix[j] - self.prefix[i] * self.power[length]) % self._MOD
        bucket = self.classes.setdefault((length, h), [])
        for start, cls in bucket:
            # the hash only proposes; equal substrings are confirmed
            if self.word[start:start + length] == self.word[i:j]:
                self.cache[key] = cls
                return cls
        cls = self.next_class
        self.next_class += 1
        bucket.append((i, cls))
        self.cache[key] = cls
        return cls


def accepts_psgs(system: PSGS, words: tuple[Word, ...], max_states: int,
                  max_seconds: float) -> Acceptance:
    deadline = time.monotonic() + max_seconds
    terminal_ids: dict[Terminal, int] = {}
    for t in sorted(system.terminals):
        terminal_ids[t] = len(terminal_ids)
    compiled, charts = [], []
    usable = usable_rules(system)
    for c, (g, w) in enumerate(zip(system.components, words)):
        # a rule in no tuple can never apply under 'strict': parse without it, so a word that
        # needs it is refused by the chart instead of by an endless schedule search
        cg = CompiledGrammar(g, terminal_ids, usable[c])
        for k, t in enumerate(w):
            if t not in g.terminals:
                return Acceptance("no", reason=(
                    f"component {g.name}'s word is not in its context-free language "
                    f"({t} at position {k + 1} is not one of its terminals)"), system=system)
        chart = Chart(cg, [terminal_ids[t] for t in w], deadline)
        compiled.append(cg)
        charts.append(chart)
    search = None
    try:
        for g, cg, chart, w in zip(system.components, compiled, charts, words):
            if not chart.derives(cg.index[g.start], 0, len(w)):
                scope = (" (under 'strict', taking only the rules that are in some tuple)"
                         if system.unsynchronised == "strict" else "")
                return Acceptance("no", reason=(
                    f"component {g.name}'s word is not in its context-free language{scope}"),
                    system=system)
        spine = _spine_check(system, compiled, charts, max_states, deadline)
        if spine is not None:
            return spine
        search = _ScheduleSearch(system, compiled, charts, max_states, deadline)
        return search.run()
    except BoundReached:
        explored = search.explored if search is not None else 0
        return Acceptance("unknown", reason=f"the search ran out of time after {max_seconds} s",
                          bound=f"max_seconds={max_seconds}", states=explored, system=system)


def _spine(cg: CompiledGrammar) -> frozenset[int]:
    """Nonterminals that lie on a cycle of the grammar, or can reach one (upward closed)."""
    n = len(cg.nonterminals)
    edges = [set() for _ in range(n)]
    for k, a in enumerate(cg.lhs):
        edges[a].update(s for s in cg.body[k] if s >= 0)
    reach = [reachable(edges, [a], strict=True) for a in range(n)]
    cyclic = {a for a in range(n) if a in reach[a]}
    return frozenset(a for a in range(n) if a in cyclic or reach[a] & cyclic)


def _spine_check(system, compiled, charts, max_states, deadline) -> Acceptance | None:
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
    relaxed = _ScheduleSearch(system, compiled, charts, max(1, max_states // 4), deadline,
                              focus=focus)
    result = relaxed.run()
    if result.answer == "no":
        return Acceptance("no", reason="every component parses but no schedule of the tuples "
                          "fits (even their recursive parts cannot be synchronised)",
                          states=result.states, system=system)
    return None


class _ScheduleSearch:
    """Depth-first search for a synchronised schedule over span-annotated frontiers."""

    def __init__(self, system: PSGS, compiled: list[CompiledGrammar], charts: list[Chart],
                 max_states: int, deadline: float, focus=None) -> None:
        self.system = system
        # focus: per component the nonterminals tracked (None: all); see _spine_check
        self.focus = focus
        self.explored = 0
        self.compiled = compiled
        self.charts = charts
        self.max_states = max_states
        self.deadline = deadline
        self.parallel = system.mode == "parallel"
        self.substrings = [_Substrings(c.word) for c in charts]
        moves = system_moves(system)
        self.moves = moves
        self.move_rule_ids = [
            tuple(None if r is IDLE else cg.rule_id[r] for r, cg in zip(m, compiled))
            for m in moves]

    # ---- states
    def key(self, state):
        out = []
        for c, front in enumerate(state):
            classes = self.substrings[c]
            out.append(tuple(sorted((a, classes.of(i, j)) for a, i, j in front)))
        return tuple(out)

    def _children(self, c: int, rule: int, split: tuple[int, ...]):
        body = self.compiled[c].body[rule]
        if self.focus is not None:
            keep = self.focus[c]
            return [(s, split[t], split[t + 1]) for t, s in enumerate(body) if s in keep]
        return [(s, split[t], split[t + 1]) for t, s in enumerate(body) if s >= 0]

    def _component_options(self, c: int, front, rule: int):
        """Ways component ``c`` can apply ``rule``: (new frontier, rewrites), or None."""
        cg = self.compiled[c]
        chart = self.charts[c]
        a = cg.lhs[rule]
        if self.focus is not None and a not in self.focus[c]:
            return [(front, ())]  # an untracked occurrence: the relaxation asks nothing of it
        targets = [it for it in front if it[0] == a]
        if not targets:
            return None
        classes = self.substrings[c]
        options = []
        if not self.parallel:
            seen = set()
            for it in targets:
                cls = classes.of(it[1], it[2])
                if cls in seen:
                    continue  # an equal occurrence has the same futures
                seen.add(cls)
                rest = list(front)
                rest.remove(it)
                for split in chart.splits(rule, it[1], it[2]):
                    new = sorted(rest + self._children(c, rule, split), key=_item_order)
                    options.append((tuple(new), ((it, split),)))
            return options
        rest = [it for it in front if it[0] != a]
        groups: dict[int, list] = {}
        for it in targets:
            groups.setdefault(classes.of(it[1], it[2]), []).append(it)
        per_group = []
        for items in groups.values():
            splits = [chart.splits(rule, it[1], it[2]) for it in items]
            if not splits[0]:
                return []  # an occurrence the rule cannot cover kills the step
            # equal occurrences have the same splits (shifted): choose a multiset of them
            choices = []
            for combo in itertools.combinations_with_replacement(range(len(splits[0])),
                                                                 len(items)):
                choices.append(tuple((it, sp[k]) for it, sp, k in zip(items, splits, combo)))
            per_group.append(choices)
        for combo in itertools.product(*per_group):
            rewrites = tuple(rw for group in combo for rw in group)
            new = list(rest)
            for it, split in rewrites:
                new.extend(self._children(c, rule, split))
            new.sort(key=_item_order)
            options.append((tuple(new), rewrites))
        return options

    def successors(self, state):
        """Successor states, lazily, moves whose leftmost target comes first.

        The order is only a heuristic (it finds block-by-block schedules
        without backtracking); every applicable move is still generated.
        """
        leftmost_of = []
        for front in state:
            table: dict[int, int] = {}
            for a, i, _ in front:
                if a not in table or i < table[a]:
                    table[a] = i
            leftmost_of.append(table)
        candidates = []
        for m, rule_ids in enumerate(self.move_rule_ids):
            key = None
            for c, rule in enumerate(rule_ids):
                if rule is None or not state[c]:
                    continue
                a = self.compiled[c].lhs[rule]
                if self.focus is not None and a not in self.focus[c]:
                    continue
                at = leftmost_of[c].get(a)
                if at is None:
                    key = None
                    break
                key = at if key is None or at < key else key
            else:
                if key is not None:
                    candidates.append((key, m))
        candidates.sort()
        for _, m in candidates:
            yield from self._move_successors(state, m)

    def _move_successors(self, state, m: int):
        per_component = []
        rewrites_somewhere = False
        for c, rule in enumerate(self.move_rule_ids[m]):
            front = state[c]
            if rule is None or not front:
                per_component.append(((front, ()),))
                continue
            options = self._component_options(c, front, rule)
            if not options:
                return
            if options[0][1]:
                rewrites_somewhere = True
            per_component.append(options)
        if not rewrites_somewhere:
            return
        for combo in itertools.product(*per_component):
            new_state = tuple(f for f, _ in combo)
            if new_state != state:
                yield (0, m, new_state, (m, tuple(rw for _, rw in combo)))

    def _readable(self, path) -> PSGSSchedule:
        """The schedule with symbols instead of ints, and the words, for the replay."""
        moves = []
        for m, rewrites in path:
            per_component = []
            for c, rw in enumerate(rewrites):
                nts = self.compiled[c].nonterminals
                per_component.append(tuple(Rewrite(nts[a], i, j, split)
                                           for (a, i, j), split in rw))
            moves.append(ScheduledMove(self.moves[m], tuple(per_component)))
        words = tuple(tuple(self.compiled[c].terminal_of[x] for x in chart.word)
                      for c, chart in enumerate(self.charts))
        return PSGSSchedule(words, tuple(moves))

    def run(self) -> Acceptance:
        """Search with a cap on ε-occurrences per component, doubled until it does not bind.

        Occurrences with non-empty spans are disjoint, so at most ``len(w)``
        per component; only occurrences that must derive ε can pile up (e.g.
        ``S → S B``, ``B → ε``). Capping them makes each round finite; a round
        that never met the cap has explored everything, so its "no" is proved.
        """
        cap = 4
        explored = 0
        while True:
            result, explored, capped = self._run_capped(cap, explored)
            if result is not None:
                return result
            if not capped:
                return Acceptance(
                    "no", reason="every component parses but no schedule of the tuples fits",
                    states=explored, system=self.system)
            cap *= 2

    def _run_capped(self, cap: int, explored: int):
        initial = tuple(((cg.index[g.start], 0, chart.n),)
                        if self.focus is None or cg.index[g.start] in self.focus[c] else ()
                        for c, (g, cg, chart) in enumerate(zip(self.system.components,
                                                               self.compiled, self.charts)))
        if all(not front for front in initial):  # only in a relaxation with nothing to track
            return (Acceptance("yes", states=explored + 1, system=self.system,
                               schedule=self._readable([])), explored + 1, False)
        visited = {self.key(initial)}
        stack = [iter(self.successors(initial))]
        path: list = []
        explored += 1
        capped = False
        generated = 0
        while stack:
            nxt = next(stack[-1], None)
            # the clock is read per generated successor, not per new state: successors that
            # are already visited or over the ε cap cost time without adding a state
            generated += 1
            if generated % 1024 == 0 and time.monotonic() > self.deadline:
                self.explored = explored
                raise BoundReached("max_seconds")
            if nxt is None:
                stack.pop()
                if path:
                    path.pop()
                continue
            _, _, state, move = nxt
            if any(sum(1 for _, i, j in front if i == j) > cap for front in state):
                capped = True
                continue
            k = self.key(state)
            if k in visited:
                continue
            visited.add(k)
            explored += 1
            path.append(move)
            if all(not front for front in state):
                return (Acceptance("yes", states=explored, system=self.system,
                                   schedule=self._readable(path)), explored, capped)
            if explored >= self.max_states:
                reason = f"the schedule search stopped after {explored} states"
                if capped:
                    reason += " (occurrences that derive ε can pile up without end here)"
                return (Acceptance("unknown", reason=reason, bound=f"max_states={self.max_states}",
                                   states=explored, system=self.system), explored, capped)
            if explored % 256 == 0 and time.monotonic() > self.deadline:
                self.explored = explored
                raise BoundReached("max_seconds")
            stack.append(iter(self.successors(state)))
        return None, explored, capped


def _item_order(item):
    return (item[1], item[2], item[0])


