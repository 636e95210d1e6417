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
In ``parallel`` mode the occurrences of a nonterminal in one form all derive
the same word, so a frontier gives each nonterminal one substring class (the
others have no future) and is keyed by the set of its pairs; the multiset of
``single`` mode would count ε-occurrences that change nothing there.
See ``docs/membership.md``.
"""

from __future__ import annotations

from collections.abc import Sequence

from ..analysis import moves as system_moves, reachable, strongly_connected
from ..budget import Budget
from ..model import IDLE, PSGS
from .chart import Chart, CompiledGrammar
from .depth_first import Finish, depth_first
from .result import Acceptance
from .witness import PSGSSchedule, Rewrite, ScheduledMove

__all__: list[str] = []

#: The first round's cap on ε-occurrences per component (single mode; doubled per round).
_FIRST_CAP = 4


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


def _spine(cg: CompiledGrammar) -> frozenset[int]:
    """Nonterminals that lie on a cycle of the grammar, or can reach one (upward closed)."""
    n = len(cg.nonterminals)
    edges = [set() for _ in range(n)]
    reverse = [set() for _ in range(n)]
    for k, a in enumerate(cg.lhs):
        for s in cg.body[k]:
            if s >= 0:
                edges[a].add(s)
                reverse[s].add(a)
    cyclic = [a for component in strongly_connected(range(n), edges) for a in component
              if len(component) > 1 or a in edges[a]]
    return frozenset(reachable(reverse, cyclic))


class _ScheduleSearch:
    """Depth-first search for a synchronised schedule over span-annotated frontiers."""

    def __init__(self, system: PSGS, compiled: list[CompiledGrammar], charts: list[Chart],
                 max_states: int, budget: Budget, focus=None, substrings=None,
                 allowed=None) -> None:
        self.system = system
        # focus: per component the nonterminals tracked (None: all); see _spine_check
        self.focus = focus
        self.explored = 0
        self.compiled = compiled
        self.charts = charts
        self.max_states = max_states
        self.budget = budget
        self.parallel = system.mode == "parallel"
        self.substrings = (substrings if substrings is not None
                           else [_Substrings(c.word) for c in charts])
        moves = system_moves(system)
        self.moves = moves
        self.move_rule_ids = [
            tuple(None if r is IDLE else cg.rule_id[r] for r, cg in zip(m, compiled))
            for m in moves]
        # per move, its (component, left-hand side) entries that rewrite a tracked symbol
        self.move_entries = [
            tuple((c, compiled[c].lhs[rule]) for c, rule in enumerate(rule_ids)
                  if rule is not None and (focus is None or compiled[c].lhs[rule] in focus[c]))
            for rule_ids in self.move_rule_ids]
        # moves by (component, left-hand side) of each non-idle entry: a state looks only at
        # the moves that rewrite a nonterminal it holds, not at every move of the system
        # allowed: the moves the search may apply (None: all), e.g. one block's moves only
        self.moves_needing: dict[tuple[int, int], list[int]] = {}
        for m, rule_ids in enumerate(self.move_rule_ids):
            if allowed is not None and m not in allowed:
                continue
            for c, rule in enumerate(rule_ids):
                if rule is not None:
                    self.moves_needing.setdefault((c, compiled[c].lhs[rule]), []).append(m)

    # ---- states
    def key(self, state):
        out = []
        for c, front in enumerate(state):
            classes = self.substrings[c]
            if len(front) == 1:
                (a, i, j), = front
                out.append(((a, classes.of(i, j)),))
            elif self.parallel:
                # equal occurrences in parallel mode are rewritten alike for ever (see
                # _parallel_options): how many there are changes no step, so the set is the key
                out.append(tuple(sorted({(a, classes.of(i, j)) for a, i, j in front})))
            else:
                out.append(tuple(sorted((a, classes.of(i, j)) for a, i, j in front)))
        return tuple(out)

    def _children(self, c: int, rule: int, split: tuple[int, ...]):
        body = self.compiled[c].body[rule]
        if self.focus is not None:
            keep = self.focus[c]
            return [(s, split[t], split[t + 1]) for t, s in enumerate(body) if s in keep]
        return [(s, split[t], split[t + 1]) for t, s in enumerate(body) if s >= 0]

    def _component_options(self, c: int, front, rule: int):
        """Ways component ``c`` can apply ``rule``: (new frontier, rewrites), lazily; None if none.

        A generator, so a step with a huge number of ways (parallel mode, many
        equal occurrences) costs only the ways the search actually tries, and
        each way counts against the budget.
        """
        cg = self.compiled[c]
        a = cg.lhs[rule]
        if self.focus is not None and a not in self.focus[c]:
            return iter([(front, ())])  # an untracked occurrence: the relaxation asks nothing
        targets = [it for it in front if it[0] == a]
        if not targets:
            return None
        if not self.parallel:
            return self._single_options(c, front, rule, targets)
        return self._parallel_options(c, front, rule, a, targets)

    def _single_options(self, c: int, front, rule: int, targets):
        chart = self.charts[c]
        classes = self.substrings[c]
        tick = self.budget.tick
        seen = set()
        for it in targets:
            cls = classes.of(it[1], it[2])
            if cls in seen:
                continue  # an equal occurrence has the same futures
            seen.add(cls)
            rest = list(front)
            rest.remove(it)
            for split in chart.splits(rule, it[1], it[2]):
                tick()
                new = sorted(rest + self._children(c, rule, split), key=_item_order)
                yield tuple(new), ((it, split),)

    def _parallel_options(self, c: int, front, rule: int, a: int, targets):
        """Parallel mode: every occurrence of ``a`` takes the same split, shifted to its span.

        In parallel mode all occurrences of one nonterminal in a form derive the
        same word: from the step that made them on, every step rewrites them
        alike (each applies one rule to every occurrence of its left side), so
        their sub-forms stay equal. A derivation of the words therefore gives
        each nonterminal of a form a single substring class, and a frontier
        where one nonterminal has two classes has no future. Hence the ways to
        apply ``rule`` are the splits of one occurrence, copied to the others
        (equal substrings have the same splits, shifted), and a way whose
        children give a nonterminal a second class is dropped at once. Without
        this, ``S → S S`` in parallel mode tried every multiset of splits,
        every partition of the word's length.
        """
        chart = self.charts[c]
        classes = self.substrings[c]
        tick = self.budget.tick
        first = targets[0]
        if len(targets) > 1:
            cls = classes.of(first[1], first[2])
            if any(classes.of(i, j) != cls for _, i, j in targets[1:]):
                return  # two occurrences of a that must derive different words
        rest = [it for it in front if it[0] != a]
        known: dict[int, int] = {}  # the class each nonterminal of the rest must derive
        for s, i, j in rest:
            if s not in known:
                known[s] = classes.of(i, j)
        origin = first[1]
        for split in chart.splits(rule, first[1], first[2]):
            tick()
            children = self._children(c, rule, split)
            if not _agrees(classes, children, known):
                continue
            new = rest + children
            rewrites = [(first, split)]
            for it in targets[1:]:
                shift = it[1] - origin
                rewrites.append((it, tuple(b + shift for b in split)))
                new.extend((s, i + shift, j + shift) for s, i, j in children)
            new.sort(key=_item_order)
            yield tuple(new), tuple(rewrites)

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
        relevant = set()
        for c, table in enumerate(leftmost_of):
            for a in table:
                relevant.update(self.moves_needing.get((c, a), ()))
        move_entries = self.move_entries
        for m in sorted(relevant):
            key = None
            for c, a in move_entries[m]:
                if not state[c]:
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
            first = None if options is None else next(options, None)
            if first is None:
                return
            if first[1]:
                rewrites_somewhere = True
            per_component.append(_Replayable(first, options))
        if not rewrites_somewhere:
            return
        for combo in _lazy_product(per_component):
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
        In parallel mode the cap never binds (see :meth:`walk`): one round decides.
        """
        cap = _FIRST_CAP
        explored = 0
        while True:
            # the previous round's visited set is gone; the charts are kept
            self.budget.held = sum(chart.held for chart in self.charts)
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
                               plan=self._readable([])), explored + 1, False)
        path, explored, capped = self.walk(initial, _finished, cap, explored)
        if path is None:
            return None, explored, capped
        if path == "max_states":
            reason = f"the schedule search stopped after {explored} states"
            if capped or cap > _FIRST_CAP:  # this round or an earlier one met the cap
                reason += " (occurrences that derive ε can pile up without end here)"
            return (Acceptance("unknown", reason=reason + f" (max_states={self.max_states})",
                               bound="max_states", states=explored, system=self.system),
                    explored, capped)
        # a relaxation's yes is only a "maybe": its schedule is never read
        schedule = self._readable(path) if self.focus is None else None
        return (Acceptance("yes", states=explored, system=self.system, plan=schedule),
                explored, capped)

    def walk(self, initial, finished, cap: int, explored: int):
        """Depth-first from ``initial`` to a state ``finished`` accepts: ``(path, explored, capped)``.

        ``path`` is the list of moves found, ``None`` when every state (with
        at most ``cap`` ε-occurrences per component) was explored, or
        ``"max_states"``; ``capped`` says whether the ε cap cut a state.
        """
        visited = {self.key(initial)}
        explored += 1
        self.explored = explored
        budget = self.budget
        counts = [explored, False]  # states explored, whether the ε cap cut a state

        def expand(nxt, path):
            _, _, state, move = nxt
            # a frontier of at most cap occurrences cannot hold more than cap ε-occurrences;
            # parallel mode needs no cap: its keys are sets with one class per nonterminal
            # (see key), finitely many, however many ε-occurrences pile up
            if not self.parallel and any(
                    len(front) > cap and sum(1 for _, i, j in front if i == j) > cap
                    for front in state):
                counts[1] = True
                return None
            k = self.key(state)
            if k in visited:
                return None
            visited.add(k)
            counts[0] += 1
            self.explored = counts[0]
            # memory: a state keeps one entry per tracked occurrence (states × form size)
            budget.hold(1 + sum(len(front) for front in state))
            if finished(state):
                return Finish([*path, move])
            if counts[0] >= self.max_states:
                return Finish("max_states")
            return move, self.successors(state)

        # the clock is read per generated successor, not per new state: successors that
        # are already visited or over the ε cap cost time without adding a state
        found = depth_first(self.successors(initial), expand, budget.tick)
        return found, counts[0], counts[1]


def _finished(state) -> bool:
    return all(not front for front in state)


def _item_order(item):
    return (item[1], item[2], item[0])


def _agrees(classes: _Substrings, children, known: dict[int, int]) -> bool:
    """Whether ``children`` give each nonterminal one class, the class ``known`` holds for it.

    ``known`` maps the nonterminals of the rest of the frontier to the class
    they derive; each child's class is added to it on a copy, so equal
    children (``S → S S`` split in the middle) agree with each other too.
    """
    seen = dict(known)
    for s, i, j in children:
        cls = classes.of(i, j)
        if seen.setdefault(s, cls) != cls:
            return False
    return True




class _Replayable:
    """A lazy sequence of options that can be walked again (for the product of several)."""

    __slots__ = ("seen", "rest")

    def __init__(self, first, rest) -> None:
        self.seen = [first]
        self.rest = rest

    def __iter__(self):
        k = 0
        while True:
            if k < len(self.seen):
                yield self.seen[k]
                k += 1
                continue
            nxt = next(self.rest, None) if self.rest is not None else None
            if nxt is None:
                self.rest = None
                return
            self.seen.append(nxt)


def _lazy_product(factors):
    """``itertools.product(*factors)`` without listing the factors first, same order."""
    if not factors:
        yield ()
        return
    stack = [iter(factors[0])]
    picked: list = []
    while stack:
        item = next(stack[-1], None)
        if item is None:
            stack.pop()
            if picked:
                picked.pop()
            continue
        if len(stack) == len(factors):
            yield (*picked, item)
            continue
        picked.append(item)
        stack.append(iter(factors[len(stack)]))
