"""A fast path to a yes: derive the words block by block, every component in lockstep.

It applies to a PSGS whose components all have *right-linear spines*: every
usable rule whose left side is on the spine (the nonterminals on or above a
cycle of the grammar, see :func:`psgs.membership.schedule_search._spine`) has
at most one spine symbol in its body, as its last symbol (``S → N S | N`` in
Γ and in the grammars PAL induces; ``S → a S | a`` too). Everything else in
such a body is off the spine and derives a finite language.

The search only visits *synchronisation points*: configurations where each
component's sentential form is one spine occurrence or nothing. A component
whose start symbol is off the spine (a finite language) is one block,
derived first by the block schedule described next. From a point, a
*spine move* (a move that rewrites the spine occurrence of every component it
names, terminal components skipping their entry) opens one block per
component, its non-spine symbols spanning a prefix of the occurrence's span;
then a *block schedule* (the general schedule search, restricted to the moves
that rewrite non-spine symbols only) must rewrite every block to terminals
while the new spine occurrences wait. Such a path is a derivation of the
system in either mode (it is a path of the general search), so its yes is
exact; the witness is replayed like any other. Not every derivation passes
through synchronisation points (a component may open its next block before
another closes its last), so a failure here proves nothing: the caller then
runs the general search, which decides.

Why it is fast: a block schedule depends only on the blocks' contents
(substrings, compared exactly) and on which components keep a spine
occurrence, and so do the ways a spine rule's prefix can cover a word's
next symbols; both are memoised under those keys, so on a word of repeated
blocks only the first block of each kind is searched, and the rest of the
word is read by hashing its substrings, without a chart over the whole word.
"""

from __future__ import annotations

from ..budget import Budget
from ..model import PSGS
from .chart import UNBOUNDED, Chart, CompiledGrammar
from .depth_first import Finish, depth_first
from .result import Acceptance
from .schedule_search import _item_order, _ScheduleSearch, _spine, _Substrings

__all__ = ["lockstep_accepts", "lockstep_applies"]

#: The most occurrences over empty spans a component's block may hold at once (single mode:
#: the schedule search needs no such cap in parallel mode, whose keys are finitely many).
_BLOCK_EPSILON_CAP = 16


def lockstep_applies(compiled: list[CompiledGrammar]) -> bool:
    """Whether every component's spine is right-linear.

    Examples
    --------
    >>> import psgs
    >>> from psgs.membership.chart import CompiledGrammar
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> ids = {t: k for k, t in enumerate(sorted(gamma.terminals))}
    >>> lockstep_applies([CompiledGrammar(g, ids) for g in gamma.components])
    True
    """
    for cg in compiled:
        spine = _spine(cg)
        for a, body in zip(cg.lhs, cg.body):
            if a in spine and any(s in spine for s in body[:-1]):
                return False
    return True


def lockstep_accepts(system: PSGS, compiled: list[CompiledGrammar], charts: list[Chart],
                     substrings: list[_Substrings], max_states: int,
                     budget: Budget) -> Acceptance | None:
    """A yes with its schedule when a block-by-block derivation exists; ``None`` otherwise.

    ``None`` proves nothing (see the module's text): the caller decides with
    the general search. Only call it when :func:`lockstep_applies`.

    Examples
    --------
    >>> import psgs
    >>> from psgs.budget import Budget
    >>> from psgs.membership.chart import Chart, CompiledGrammar
    >>> from psgs.membership.schedule_search import _Substrings
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> ids = {t: k for k, t in enumerate(sorted(gamma.terminals))}
    >>> words = ["abcdbcad" * 3, "bcadabcd" * 3, "cdabcdab" * 3, "abcdbcad" * 3]
    >>> compiled = [CompiledGrammar(g, ids) for g in gamma.components]
    >>> charts = [Chart(cg, [ids[psgs.Terminal(x)] for x in w]) for cg, w in zip(compiled, words)]
    >>> found = lockstep_accepts(gamma, compiled, charts, [_Substrings(c.word) for c in charts],
    ...                          10_000, Budget(seconds=10))
    >>> found.answer, len(found.witness.steps) > 0
    ('yes', True)
    """
    return _Lockstep(system, compiled, charts, substrings, max_states, budget).run()


class _Lockstep:
    def __init__(self, system, compiled, charts, substrings, max_states, budget) -> None:
        self.system = system
        self.compiled = compiled
        self.charts = charts
        self.substrings = substrings
        self.max_states = max_states
        self.budget = budget
        self.spine = [_spine(cg) for cg in compiled]
        # per component and rule with a spine left side: (its prefix, its spine tail or None,
        # the prefix's greatest yield)
        self.shape: list[dict[int, tuple[tuple[int, ...], int | None, int]]] = []
        for cg, spine in zip(compiled, self.spine):
            shapes = {}
            for rule, (a, body) in enumerate(zip(cg.lhs, cg.body)):
                if a not in spine:
                    continue
                tail = body[-1] if body and body[-1] in spine else None
                prefix = body[:-1] if tail is not None else body
                reach = sum(1 if s < 0 else cg.maxlen[s] for s in prefix)
                shapes[rule] = (prefix, tail, min(reach, UNBOUNDED))
            self.shape.append(shapes)
        probe = _ScheduleSearch(system, compiled, charts, max_states, budget,
                                substrings=substrings)
        # a block is closed by moves that rewrite non-spine symbols only
        blockwise = {m for m, rule_ids in enumerate(probe.move_rule_ids)
                     if all(rule is None or compiled[c].lhs[rule] not in self.spine[c]
                            for c, rule in enumerate(rule_ids))}
        self.block = _ScheduleSearch(system, compiled, charts, max_states, budget,
                                     substrings=substrings, allowed=blockwise)
        self.move_rule_ids = probe.move_rule_ids
        self.spine_moves: dict[tuple, list[int]] = {}
        self.prefix_cache: list[dict] = [{} for _ in compiled]
        self.block_cache: dict[tuple, list | None] = {}
        self.explored = 0

    # ---- spine moves at a synchronisation point
    def _moves_at(self, shape: tuple) -> list[int]:
        """Moves that rewrite the spine occurrence of each component they name (cached)."""
        found = self.spine_moves.get(shape)
        if found is None:
            found = []
            for m, rule_ids in enumerate(self.move_rule_ids):
                named = False
                for c, rule in enumerate(rule_ids):
                    if rule is None or shape[c] is None:
                        continue  # idle, or a terminal component skipping its entry
                    if self.compiled[c].lhs[rule] != shape[c]:
                        break
                    named = True
                else:
                    if named:
                        found.append(m)
            self.spine_moves[shape] = found
        return found

    def _prefix_splits(self, c: int, rule: int, p: int, n: int) -> list[tuple[int, ...]]:
        """Boundaries ``(p, …, q)`` by which the rule's prefix covers ``word[p:q]``, tail fitting."""
        prefix, tail, reach = self.shape[c][rule]
        cg = self.compiled[c]
        end = min(n, p + reach)
        key = (rule, self.substrings[c].of(p, end))
        relative = self.prefix_cache[c].get(key)
        if relative is None:
            relative = [tuple(b - p for b in split)
                        for split in self._enumerate_prefix(c, prefix, p, end)]
            self.prefix_cache[c][key] = relative
        if tail is None:
            return [tuple(p + b for b in split) for split in relative if p + split[-1] == n]
        if cg.minlen[tail] >= UNBOUNDED:
            return []
        limit = n - cg.minlen[tail]
        return [tuple(p + b for b in split) for split in relative if p + split[-1] <= limit]

    def _enumerate_prefix(self, c: int, prefix, p: int, end: int) -> list[tuple[int, ...]]:
        chart = self.charts[c]
        cg = self.compiled[c]
        word = chart.word
        tick = self.budget.tick
        out = []
        stack = [(p,)]
        while stack:
            bounds = stack.pop()
            t = len(bounds) - 1
            a = bounds[-1]
            if t == len(prefix):
                out.append(bounds)
                continue
            s = prefix[t]
            if s < 0:
                if a < end and word[a] == ~s:
                    stack.append((*bounds, a + 1))
                continue
            if cg.minlen[s] >= UNBOUNDED:
                continue
            for b in range(a + cg.minlen[s], min(a + cg.maxlen[s], end) + 1):
                tick()
                if chart.derives(s, a, b):
                    stack.append((*bounds, b))
        out.sort(key=lambda split: split[-1])
        return out

    def _successors(self, sync):
        """From a synchronisation point: (next point, spine move, block key), lazily."""
        shape = tuple(front[0][0] if front else None for front in sync)
        for m in self._moves_at(shape):
            per_component = []
            for c, rule in enumerate(self.move_rule_ids[m]):
                front = sync[c]
                if rule is None or not front:
                    per_component.append([(front, None)])
                    continue
                (_, p, n), = front
                tail = self.shape[c][rule][1]
                options = []
                for split in self._prefix_splits(c, rule, p, n):
                    nxt = ((tail, split[-1], n),) if tail is not None else ()
                    options.append((nxt, (rule, split)))
                if not options:
                    break
                per_component.append(options)
            else:
                yield from self._combine(sync, m, per_component)

    def _combine(self, sync, m, per_component):
        combos = [()]
        for options in per_component:
            combos = [(*done, option) for done in combos for option in options]
        for combo in combos:
            yield tuple(nxt for nxt, _ in combo), m, tuple(way for _, way in combo), sync

    # ---- blocks
    def _block_key(self, sync, ways):
        key = []
        for c, (front, way) in enumerate(zip(sync, ways)):
            if way is None:
                key.append(None if not front else ())
                continue
            rule, split = way
            key.append((rule, tuple(b - split[0] for b in split),
                        self.substrings[c].of(split[0], split[-1])))
        return tuple(key)

    def _block_schedule(self, sync, m, ways):
        """The moves closing the blocks opened by ``ways`` (relative to each block), or None."""
        key = self._block_key(sync, ways)
        if key in self.block_cache:
            return self.block_cache[key]
        initial = []
        for c, (front, way) in enumerate(zip(sync, ways)):
            if way is None:
                initial.append(front)
                continue
            rule, split = way
            prefix, tail, _ = self.shape[c][rule]
            items = [(s, split[t], split[t + 1]) for t, s in enumerate(prefix) if s >= 0]
            if tail is not None:
                items.append((tail, split[-1], front[0][2]))
            initial.append(tuple(sorted(items, key=_item_order)))
        initial = tuple(initial)
        if all(it[0] in self.spine[c] for c, front in enumerate(initial) for it in front):
            schedule = []
        else:
            path = self._close_blocks(initial)
            schedule = None if path is None else [
                (move, tuple(tuple(((a, i - _origin(ways, c), j - _origin(ways, c)),
                                    tuple(b - _origin(ways, c) for b in split))
                                   for (a, i, j), split in rewrites)
                             for c, rewrites in enumerate(per)))
                for move, per in path]
        self.block_cache[key] = schedule
        return schedule

    def _close_blocks(self, start):
        """Block moves from ``start`` to a synchronisation point (None: none found)."""
        spine = self.spine
        path, self.explored, _ = self.block.walk(
            start, lambda state: all(it[0] in spine[c] for c, front in enumerate(state)
                                     for it in front), _BLOCK_EPSILON_CAP, self.explored)
        if path == "max_states":
            raise _OutOfStates
        return path

    # ---- the walk over synchronisation points
    def run(self) -> Acceptance | None:
        start = tuple(((cg.index[g.start], 0, chart.n),)
                      for g, cg, chart in zip(self.system.components, self.compiled,
                                              self.charts))
        # components whose start is off the spine derive their whole word as one block
        initial = tuple(front if front[0][0] in spine else ()
                        for front, spine in zip(start, self.spine))
        first: list = []
        if initial != start:
            try:
                first = self._close_blocks(start)
            except _OutOfStates:
                return None
            if first is None:
                return None
            if all(not front for front in initial):
                return Acceptance("yes", states=self.explored, system=self.system,
                                  plan=lambda: self.block._readable(first))
        visited = {initial}
        self.explored += 1
        budget = self.budget

        def expand(item, path):
            nxt, m, ways, sync = item
            if nxt in visited:
                return None
            block = self._block_schedule(sync, m, ways)
            if block is None:
                return None
            visited.add(nxt)
            self.explored += 1
            budget.hold(1 + len(nxt))
            entry = (sync, m, ways, block)
            if all(not front for front in nxt):
                return Finish([*path, entry])
            if self.explored >= self.max_states:
                return Finish(None)
            return entry, self._successors(nxt)

        try:
            found = depth_first(self._successors(initial), expand, budget.tick)
        except _OutOfStates:
            return None
        if found is None:
            return None
        # the schedule (thousands of moves on long words) is built when it is first read
        return Acceptance("yes", states=self.explored, system=self.system,
                          plan=lambda: self.block._readable(first + self._moves(found)))

    def _moves(self, found) -> list:
        """The general search's path: each spine move, then its block schedule shifted."""
        moves = []
        for sync, m, ways, block in found:
            rewrites = []
            for c, (front, way) in enumerate(zip(sync, ways)):
                if way is None:
                    rewrites.append(())
                    continue
                (a, p, n), = front
                rule, split = way
                if self.shape[c][rule][1] is not None:
                    split = (*split, n)  # the tail spans the rest of the occurrence
                rewrites.append((((a, p, n), split),))
            moves.append((m, tuple(rewrites)))
            for move, per in block:
                moves.append((move, tuple(
                    tuple(((a, i + _origin(ways, c), j + _origin(ways, c)),
                           tuple(b + _origin(ways, c) for b in split))
                          for (a, i, j), split in rw)
                    for c, rw in enumerate(per))))
        return moves


class _OutOfStates(Exception):
    """The block search used up the fast path's share of ``max_states``."""


def _origin(ways, c: int) -> int:
    way = ways[c]
    return 0 if way is None else way[1][0]
