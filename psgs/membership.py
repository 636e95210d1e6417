"""Membership: is a word tuple in L(Γ)? Is a word in the language of a PCGS?

:func:`accepts` answers with an :class:`Acceptance`: ``"yes"`` (with a
witness derivation, replayed step by step with the derivation engine),
``"no"`` (with a reason) or ``"unknown"`` (naming the budget that ran out).

PSGS (sound and complete in both modes and both policies): each component's
word is parsed by a goal-directed chart (:mod:`psgs._chart`); then a
depth-first search looks for a synchronised schedule over *span-annotated
frontiers*: per component, the multiset of nonterminal occurrences still in
the sentential form, each tagged with the span ``(i, j)`` of the word it must
derive. A tuple rewrites, per component, one occurrence (``single``) or every
occurrence of its left-hand side (``parallel``), choosing for each a split of
its span that the chart allows. States are memoised up to equal substrings:
occurrences ``(A, i, j)`` and ``(A, i', j')`` with ``w[i:j] == w[i':j']`` have
the same futures, so a state is keyed by its multiset of (nonterminal,
substring class). Substring classes are found with a polynomial rolling hash
and confirmed by comparing the substrings, so a hash collision can cost time
but never a wrong answer. See ``docs/membership.md``.

PCGS (membership is undecidable in general): a breadth-first search over
configurations, pruned soundly by the master's word; see
:func:`accepts` for the budgets.
"""

from __future__ import annotations

import gc
import itertools
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any, Literal

from ._chart import Chart, CompiledGrammar
from .errors import BoundReached, ValidationError
from .model import IDLE, PCGS, PSGS, Terminal, Word, as_word

__all__ = ["Acceptance", "accepts"]

#: Words of at most this many symbols in all get their witness replayed at once.
EAGER_REPLAY_LIMIT = 2000


@dataclass(frozen=True)
class Acceptance:
    """The answer of :func:`accepts`.

    ``bool(result)`` is true only for ``answer == "yes"``. ``reason`` is a
    short sentence when the answer is ``"no"`` or ``"unknown"``; ``bound``
    names the budget that ran out (``"unknown"`` only). ``states`` counts the
    search states explored. ``witness`` is the derivation (a
    :class:`psgs.derivation.Derivation`, ``str()`` prints the paper's
    notation) when the answer is ``"yes"``: it is replayed with
    :func:`psgs.derivation.apply_tuple`, which checks every step, on first
    access (at once for short words, see :data:`EAGER_REPLAY_LIMIT`).
    """

    answer: Literal["yes", "no", "unknown"]
    reason: str | None = None
    bound: str | None = None
    states: int = 0
    system: Any = field(default=None, repr=False, compare=False)
    schedule: tuple = field(default=(), repr=False, compare=False)

    def __bool__(self) -> bool:
        return self.answer == "yes"

    @cached_property
    def witness(self):
        """The witness derivation (``None`` unless the answer is yes)."""
        if self.answer != "yes":
            return None
        return _replay(self.system, self.schedule)

    def __str__(self) -> str:
        if self.answer == "yes":
            return "yes"
        if self.answer == "no":
            return f"no: {self.reason}"
        return f"unknown: {self.reason}"


def accepts(system: PSGS | PCGS, words, *, max_states: int = 200_000,
            max_seconds: float = 30.0, max_steps: int = 200,
            check_witness: bool | None = None) -> Acceptance:
    """Decide whether ``words`` is in the language of ``system``.

    PSGS: ``words`` holds one word per component; a word is a ``str`` of
    one-character terminals or a sequence of terminal names or
    :class:`~psgs.model.Terminal`. A one-component system also takes a
    single word. The answer is ``"yes"``/``"no"`` unless a budget runs out:
    ``max_states`` search states (default 200,000) or ``max_seconds`` of
    wall-clock time (default 30), giving ``"unknown"`` with the budget named.

    PCGS: ``words`` is the master's word. ``"yes"`` comes with a witness;
    ``"no"`` only when the search proved it (every configuration from which
    the master could still derive the word was explored); otherwise
    ``"unknown"`` naming ``max_steps`` (derivation length, default 200),
    ``max_states`` or ``max_seconds``.

    ``check_witness`` replays the witness (a yes answer) with the derivation
    engine before returning; ``None`` (default) does so when the words are at
    most :data:`EAGER_REPLAY_LIMIT` symbols long in all, and leaves it to the
    first access of ``.witness`` otherwise.

    >>> from psgs.model import Grammar, Rule, PSGS, Nonterminal as N, Terminal as T
    >>> g = Grammar("G", N("S"), (Rule("p", N("S"), (T("a"), N("S"))), Rule("q", N("S"), (T("a"),))))
    >>> h = Grammar("H", N("R"), (Rule("u", N("R"), (T("b"), N("R"))), Rule("v", N("R"), (T("b"),))))
    >>> system = PSGS((g, h), (("p", "u"), ("q", "v")), unsynchronised="strict")
    >>> accepts(system, ["aaa", "bbb"]).answer, accepts(system, ["aaa", "bb"]).answer
    ('yes', 'no')
    """
    for name, value in (("max_states", max_states), ("max_steps", max_steps)):
        if not isinstance(value, int) or value < 1:
            raise ValidationError(f"{name} must be a positive integer, not {value!r}")
    if not isinstance(max_seconds, (int, float)) or max_seconds <= 0:
        raise ValidationError(f"max_seconds must be a positive number, not {max_seconds!r}")
    if isinstance(system, PCGS):
        from ._pcgs_membership import accepts_pcgs
        result = accepts_pcgs(system, as_word(words), max_steps=max_steps,
                              max_states=max_states, max_seconds=max_seconds)
        total = len(words)
    elif isinstance(system, PSGS):
        tuple_of_words = _coerce_words(system, words)
        # The search keeps a deep stack and a large visited set alive while allocating many
        # short-lived tuples: the cyclic collector's full passes over them made the run grow
        # faster than linearly (measured: k = 2000 Γ repetitions 6.9 s with it, 2.2 s
        # without). Nothing here makes reference cycles, so it is paused and then restored.
        collecting = gc.isenabled()
        gc.disable()
        try:
            result = _accepts_psgs(system, tuple_of_words, max_states, max_seconds)
        finally:
            if collecting:
                gc.enable()
        total = sum(len(w) for w in tuple_of_words)
    else:
        raise ValidationError(f"expected a PSGS or a PCGS, not {type(system).__name__}")
    if result.answer == "yes":
        if check_witness or (check_witness is None and total <= EAGER_REPLAY_LIMIT):
            result.witness  # noqa: B018 -- replaying checks every step
    return result


# ---------------------------------------------------------------- PSGS
def _coerce_words(system: PSGS, words) -> tuple[Word, ...]:
    n = len(system.components)
    if isinstance(words, str):
        if n != 1:
            raise ValidationError(f"give one word per component ({n}), not one string")
        words = (words,)
    try:
        words = tuple(words)
    except TypeError:
        raise ValidationError(f"words must be a sequence of words, not {words!r}") from None
    if n == 1 and words and all(isinstance(w, Terminal) for w in words):
        words = (words,)
    if len(words) != n:
        raise ValidationError(f"the system has {n} components but {len(words)} words were given")
    return tuple(as_word(w) for w in words)


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


def _accepts_psgs(system: PSGS, words: tuple[Word, ...], max_states: int,
                  max_seconds: float) -> Acceptance:
    deadline = time.monotonic() + max_seconds
    terminal_ids: dict[Terminal, int] = {}
    for t in sorted(system.terminals):
        terminal_ids[t] = len(terminal_ids)
    compiled, charts = [], []
    for c, (g, w) in enumerate(zip(system.components, words)):
        usable = None
        if system.unsynchronised == "strict":
            # a rule in no tuple can never apply under 'strict': parse without it, so a word
            # that needs it is refused by the chart instead of by an endless schedule search
            in_tuples = {m[c] for m in system.sync if m[c] is not IDLE}
            usable = [r for r in g.rules if r in in_tuples]
        cg = CompiledGrammar(g, terminal_ids, usable)
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
    reach = []
    for a in range(n):
        seen, todo = set(), [a]
        while todo:
            for y in edges[todo.pop()]:
                if y not in seen:
                    seen.add(y)
                    todo.append(y)
        reach.append(seen)
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
        moves = list(system.sync)
        if system.unsynchronised == "free":
            n = len(system.components)
            for c, rules in enumerate(system.unsynchronised_rules):
                for rule in rules:
                    moves.append(tuple(rule if k == c else IDLE for k in range(n)))
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

    def _readable(self, path):
        """The schedule with symbols instead of ints, and the words, for the replay."""
        moves = []
        for m, rewrites in path:
            per_component = []
            for c, rw in enumerate(rewrites):
                nts = self.compiled[c].nonterminals
                per_component.append(tuple(((nts[a], i, j), split) for (a, i, j), split in rw))
            moves.append((self.moves[m], tuple(per_component)))
        words = tuple(tuple(self.compiled[c].terminal_of[x] for x in chart.word)
                      for c, chart in enumerate(self.charts))
        return words, tuple(moves)

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


def _replay(system: PSGS, schedule) -> Any:
    """Turn a schedule into a Derivation, checking each step with the derivation engine."""
    from .derivation import Derivation, apply_tuple, initial_configuration

    if schedule[0] == "pcgs":
        return _replay_pcgs(system, schedule[1])
    words, moves = schedule
    configuration = initial_configuration(system)
    # per component, the span each symbol of the form must derive (None for terminals)
    spans = [[(0, len(w))] for w in words]
    steps = []
    for entries, rewrites in moves:
        positions = []
        for c, rw in enumerate(rewrites):
            where = []
            form = configuration[c]
            for (symbol, i, j), _split in rw:
                for k, sp in enumerate(spans[c]):
                    if k not in where and sp == (i, j) and form[k] == symbol:
                        where.append(k)
                        break
                else:  # pragma: no cover - would be a bug in the search
                    raise ValidationError("witness replay lost track of an occurrence")
            positions.append(tuple(sorted(where)) if where else None)
        step = apply_tuple(system, configuration, entries, positions)
        for c, rw in enumerate(rewrites):
            if not rw:
                continue
            split_at = {}
            for ((symbol, i, j), split), k in zip(rw, _positions_in_order(rw, spans[c],
                                                                          configuration[c])):
                split_at[k] = split
            rhs = entries[c].rhs
            new_spans = []
            for k, sp in enumerate(spans[c]):
                if k in split_at:
                    split = split_at[k]
                    new_spans.extend(None if isinstance(sym, Terminal) else (split[t], split[t + 1])
                                     for t, sym in enumerate(rhs))
                else:
                    new_spans.append(sp)
            spans[c] = new_spans
        steps.append(step)
        configuration = step.after
    derivation = Derivation(system, tuple(steps))
    if derivation.words != words:  # pragma: no cover - would be a bug in the search
        raise ValidationError("the witness does not derive the words it was found for")
    return derivation


def _positions_in_order(rewrites, spans, form):
    taken = []
    for (symbol, i, j), _split in rewrites:
        for k, sp in enumerate(spans):
            if k not in taken and sp == (i, j) and form[k] == symbol:
                taken.append(k)
                break
    return taken


def _replay_pcgs(system: PCGS, found_steps) -> Any:
    from .derivation import Derivation, apply_tuple, initial_configuration

    configuration = initial_configuration(system)
    steps = []
    for found in found_steps:
        if found.kind == "communicate":
            step = apply_tuple(system, configuration, "communicate")
        else:
            step = apply_tuple(system, configuration, found.tuple,
                               [p or None for p in found.positions])
        if step.after != found.after:  # pragma: no cover - would be a bug
            raise ValidationError("the PCGS witness does not replay")
        steps.append(step)
        configuration = step.after
    return Derivation(system, tuple(steps))
