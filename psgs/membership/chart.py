"""A goal-directed chart for one context-free grammar and one word.

``Chart.derives(A, i, j)`` answers whether nonterminal ``A`` derives
``word[i:j]``; ``Chart.splits(rule, i, j)`` lists the ways a rule's body can
cover ``word[i:j]``. Only the items a question needs are computed (top-down,
memoised), which keeps the work linear on grammars shaped like the induced
ones (``S → N S | N`` with blocks of bounded length), where a full Earley or
CYK chart is quadratic.

Why it terminates and is complete (ε- and unit rules included): for a span of
length ≥ 1, a derivation tree of ``A`` either splits the span among the
children of some node into strictly shorter pieces, or passes the whole span
down a chain of nodes whose other children derive ε. The chain is captured
statically by the *unit closure* of ``A`` (nonterminals ``X`` with
``A ⇒* αXβ``, ``αβ ⇒* ε``), and the children of a proper split have strictly
shorter spans, so the recursion is well founded. Empty spans use the static
nullable set. The recursion runs on an explicit stack, and so does the walk
over a rule's body, so deep right recursion (thousands of ``S → N S``) and
long bodies (a rule of thousands of symbols) do not hit Python's recursion
limit.

Length windows (each nonterminal's minimum and maximum yield, the maximum
capped at "unbounded") prune the split points: a block of fixed length has
one possible end, so the chart never tries the others.

The static analysis is near-linear in the grammar's size (least yields by
Knuth's algorithm; maximum yields, first/last terminals and the unit closure
bottom-up over the strongly connected components), so a grammar of
thousands of rules is compiled in milliseconds, and every loop of the
chart counts against the caller's :class:`~psgs.budget.Budget`.
"""

from __future__ import annotations

from collections.abc import Sequence

from ..analysis import least_sums, reachable, strongly_connected
from ..budget import Budget
from ..model import Grammar, Nonterminal, Rule, Terminal

UNBOUNDED = 1 << 60
#: How many unknown children one evaluation of an item notes before it stops looking further.
_MISSING_PER_PASS = 64
#: What the chart counts against ``max_symbols`` per memo entry and per entry of its stack: the
#: item's three ints (the error chart counts its memo entries the same way).
ITEM_SYMBOLS = 3


class CompiledGrammar:
    """A grammar with integer symbols and its static length analysis.

    Symbols in rule bodies are ints: a nonterminal is its index (≥ 0), a
    terminal ``t`` is ``~id(t)`` (< 0) with ids from ``terminal_ids``.
    """

    def __init__(self, grammar: Grammar, terminal_ids: dict[Terminal, int],
                 rules=None, budget: Budget | None = None) -> None:
        self.grammar = grammar
        self.budget = budget if budget is not None else Budget()
        nts = sorted(grammar.nonterminals, key=lambda n: n.name)
        self.nonterminals: list[Nonterminal] = nts
        self.index = {n: k for k, n in enumerate(nts)}
        self.terminal_of = {v: k for k, v in terminal_ids.items()}
        # rules: the usable subset (None: all), e.g. under 'strict' only rules in some tuple
        self.rules: list[Rule] = list(grammar.rules if rules is None else rules)
        self.rule_id = {r: k for k, r in enumerate(self.rules)}
        self.lhs = [self.index[r.lhs] for r in self.rules]
        self.body: list[tuple[int, ...]] = []
        for r in self.rules:
            body = []
            for s in r.rhs:
                if isinstance(s, Nonterminal):
                    body.append(self.index[s])
                else:
                    body.append(~terminal_ids[s])
            self.body.append(tuple(body))
        self.by_lhs: list[list[int]] = [[] for _ in nts]
        for k, a in enumerate(self.lhs):
            self.by_lhs[a].append(k)
        self._analyse()

    def _analyse(self) -> None:
        n = len(self.nonterminals)
        tick = self.budget.tick
        least = least_sums([(a, [s for s in body if s >= 0], sum(1 for s in body if s < 0))
                            for a, body in zip(self.lhs, self.body)])
        minlen = [least.get(a, UNBOUNDED) for a in range(n)]
        nullable = [m == 0 for m in minlen]
        self.nullable = nullable
        self.minlen = minlen
        productive = [m < UNBOUNDED for m in minlen]
        useful_rules = [k for k in range(len(self.rules))
                        if all(s < 0 or productive[s] for s in self.body[k])]
        self.budget.check()
        edges: list[set[int]] = [set() for _ in range(n)]
        for k in useful_rules:
            tick()
            edges[self.lhs[k]].update(s for s in self.body[k] if s >= 0)
        # successor components first: a bottom-up pass sees each nonterminal after its parts
        self._components = strongly_connected(range(n), edges)
        self.budget.check()
        self.maxlen = self._max_lengths(useful_rules, productive, edges)
        # unit closure: A ⇒* α X β with α β ⇒* ε, over useful rules (computed per asked A)
        unit_edges: list[set[int]] = [set() for _ in range(n)]
        for k in useful_rules:
            tick()
            body = self.body[k]
            blocking = sum(1 for s in body if s < 0 or not nullable[s])
            for s in body:
                # every other symbol nullable: s is the only one that is not, or none is
                if s >= 0 and blocking - (0 if nullable[s] else 1) == 0:
                    unit_edges[self.lhs[k]].add(s)
        self._unit_edges = unit_edges
        self._unit_closure: dict[int, tuple[int, ...]] = {}
        useful = set(useful_rules)
        self.useful_by_lhs = [[k for k in ks if k in useful] for ks in self.by_lhs]
        self.first = self._edge_terminals(useful_rules, reverse=False)
        self.last = self._edge_terminals(useful_rules, reverse=True)
        # per rule, min/max yield of each suffix of the body
        self.suffix_min: list[list[int]] = []
        self.suffix_max: list[list[int]] = []
        maxlen = self.maxlen
        for body in self.body:
            tick()
            smin = [0] * (len(body) + 1)
            smax = [0] * (len(body) + 1)
            for t in range(len(body) - 1, -1, -1):
                s = body[t]
                smin[t] = smin[t + 1] + (1 if s < 0 else minlen[s])
                smax[t] = min(UNBOUNDED, smax[t + 1] + (1 if s < 0 else maxlen[s]))
            self.suffix_min.append(smin)
            self.suffix_max.append(smax)

    def unit_closure(self, a: int) -> tuple[int, ...]:
        """The nonterminals ``X`` with ``a ⇒* α X β``, ``α β ⇒* ε`` (``a`` included), sorted."""
        found = self._unit_closure.get(a)
        if found is None:
            found = tuple(sorted(reachable(self._unit_edges, [a])))
            self._unit_closure[a] = found
        return found

    def _edge_terminals(self, useful_rules: list[int], reverse: bool) -> list[frozenset[int]]:
        """Terminal ids that can begin (or, reversed, end) a non-empty yield of each nonterminal.

        A nonterminal's set is its own edge terminals plus the sets of the
        nonterminals that can stand at its edge; one bottom-up pass over the
        strongly connected components of that relation settles every set.
        """
        n = len(self.nonterminals)
        direct = [0] * n  # bitsets of terminal ids
        at_edge: list[set[int]] = [set() for _ in range(n)]
        for k in useful_rules:
            self.budget.tick()
            a = self.lhs[k]
            body = self.body[k][::-1] if reverse else self.body[k]
            for s in body:
                if s < 0:
                    direct[a] |= 1 << ~s
                    break
                at_edge[a].add(s)
                if not self.nullable[s]:
                    break
        bits = [0] * n
        for component in strongly_connected(range(n), at_edge):
            self.budget.tick()
            value = 0
            for a in component:
                value |= direct[a]
                for b in at_edge[a]:
                    value |= bits[b]  # successor components are settled; own ones are 0 yet
            for a in component:
                bits[a] = value
        cache: dict[int, frozenset[int]] = {}
        out = []
        for value in bits:
            found = cache.get(value)
            if found is None:
                found = cache[value] = frozenset(t for t in range(value.bit_length())
                                                 if value >> t & 1)
            out.append(found)
        return out

    def _max_lengths(self, useful_rules: list[int], productive: list[bool],
                     edges: list[set[int]]) -> list[int]:
        """Longest yield per nonterminal, UNBOUNDED when a pumping cycle is reachable."""
        n = len(self.nonterminals)
        tick = self.budget.tick
        reverse: list[list[int]] = [[] for _ in range(n)]
        for a in range(n):
            for s in edges[a]:
                reverse[s].append(a)
        # derives some non-empty word: a useful rule with a terminal, or with a growing symbol
        grows_directly = {self.lhs[k] for k in useful_rules if any(s < 0 for s in self.body[k])}
        can_grow = [False] * n
        for a in reachable(reverse, grows_directly):
            can_grow[a] = True
        component_of = [0] * n
        for c, component in enumerate(self._components):
            for a in component:
                component_of[a] = c
        # a rule of A pumps when A ⇒+ ...A... through one body symbol Y (Y in A's strongly
        # connected component) while another symbol of the body can yield something
        pumping = set()
        for k in useful_rules:
            tick()
            a = self.lhs[k]
            body = self.body[k]
            growing = sum(1 for s in body if s < 0 or can_grow[s])
            for s in body:
                if s >= 0 and component_of[s] == component_of[a]:
                    if growing - (1 if can_grow[s] else 0) > 0:
                        pumping.add(a)
        unbounded = [False] * n
        for a in reachable(reverse, pumping):
            unbounded[a] = True
        maxlen = [UNBOUNDED if unbounded[a] else 0 for a in range(n)]
        rules_of: list[list[int]] = [[] for _ in range(n)]
        for k in useful_rules:
            rules_of[self.lhs[k]].append(k)
        # bounded symbols, bottom-up: the longest yield is reached without pumping, so
        # |component| + 1 rounds settle a component whose parts below are settled
        for component in self._components:
            if unbounded[component[0]]:
                continue
            rules = [k for a in component for k in rules_of[a]]
            for _ in range(len(component) + 1):
                changed = False
                for k in rules:
                    tick()
                    a = self.lhs[k]
                    total = sum(1 if s < 0 else maxlen[s] for s in self.body[k])
                    if total > maxlen[a]:
                        maxlen[a] = total
                        changed = True
                if not changed:
                    break
        return maxlen


class Chart:
    """Which nonterminals derive which spans of one word (computed on demand).

    What it keeps counts against the budget's ``max_symbols``
    (:meth:`~psgs.budget.Budget.hold`): :data:`ITEM_SYMBOLS` per memo entry,
    the boundaries of each cached split (both kept, in ``held``) and, while a
    question is resolved, :data:`ITEM_SYMBOLS` per entry of the resolution
    stack. On a grammar as ambiguous as ``S → S S | a`` the chart is CYK's,
    quadratic in the word's length, so a long word stops at the memory bound,
    named, instead of growing until the clock runs out.
    """

    def __init__(self, compiled: CompiledGrammar, word: Sequence[int],
                 budget: Budget | None = None) -> None:
        self.g = compiled
        self.word = list(word)
        self.n = len(self.word)
        self.memo: dict[tuple[int, int, int], bool] = {}
        self.budget = budget if budget is not None else Budget()
        self._split_cache: dict[tuple[int, int, int], tuple[tuple[int, ...], ...]] = {}
        # what the chart keeps, in symbols: a search that starts its count afresh (a new
        # round) starts it from the charts' held, as the chart outlives the round
        self.held = 0

    # ---------------------------------------------------------- queries
    def derives(self, a: int, i: int, j: int) -> bool:
        """True when nonterminal ``a`` derives ``word[i:j]``."""
        g = self.g
        length = j - i
        if length == 0:
            return g.nullable[a]
        if length < g.minlen[a] or length > g.maxlen[a]:
            return False
        if self.word[i] not in g.first[a] or self.word[j - 1] not in g.last[a]:
            return False
        key = (a, i, j)
        value = self.memo.get(key)
        if value is None:
            self._resolve(key)
            value = self.memo[key]
        return value

    def splits(self, rule: int, i: int, j: int) -> tuple[tuple[int, ...], ...]:
        """Every boundary tuple ``(i = m0 ≤ m1 ≤ … ≤ mr = j)`` by which ``rule`` covers ``word[i:j]``."""
        key = (rule, i, j)
        cached = self._split_cache.get(key)
        if cached is None:
            cached = tuple(self._enumerate(rule, i, j, proper=False, missing=None))
            self._split_cache[key] = cached
            # up to L + 1 splits of a span of length L under a two-symbol body, kept
            self._hold(1 + sum(map(len, cached)))
        return cached

    # ---------------------------------------------------------- machinery
    def _hold(self, symbols: int) -> None:
        self.held += symbols
        self.budget.hold(symbols)

    def _symbol_ok(self, s: int, p: int, q: int, missing: list | None) -> bool | None:
        if s < 0:
            return q == p + 1 and self.word[p] == ~s
        if q == p:
            return self.g.nullable[s]
        g = self.g
        if q - p < g.minlen[s] or q - p > g.maxlen[s]:
            return False
        word = self.word
        if word[p] not in g.first[s] or word[q - 1] not in g.last[s]:
            return False
        if missing is None:
            return self.derives(s, p, q)
        value = self.memo.get((s, p, q))
        if value is None:
            missing.append((s, p, q))
        return value

    def _enumerate(self, rule: int, i: int, j: int, proper: bool, missing: list | None):
        """Yield boundary tuples; with ``missing`` given, unknown children are noted, not computed."""
        g = self.g
        body = g.body[rule]
        r = len(body)
        smin = g.suffix_min[rule]
        smax = g.suffix_max[rule]
        span = j - i
        if r == 0:
            if span == 0:
                yield (i,)
            return
        if not (smin[0] <= span <= smax[0]):
            return
        tick = self.budget.tick
        minlen, maxlen = g.minlen, g.maxlen
        if r <= 2:
            # the bodies of most grammars (and all of the induced ones) have one or two
            # symbols: the same walk as below, in the same order, without its stacks
            yield from self._enumerate_short(body, i, j, proper, missing)
            return

        def ends(t: int, p: int):
            s = body[t]
            if t == r - 1:
                return (j,)
            if s < 0:
                return (p + 1,)
            return range(max(p + minlen[s], j - smax[t + 1]),
                         min(p + maxlen[s], j - smin[t + 1]) + 1)

        # a depth-first walk over the body on an explicit stack (a body may be thousands of
        # symbols long): bounds[t] is where symbol t starts, levels[t] its candidate ends,
        # doubts[t] how many children before t are not known yet. When noting what is
        # missing, the walk goes on past an unknown child (up to _MISSING_PER_PASS of them),
        # so one pass asks for many children: a long body whose children are resolved one
        # per pass would cost a quadratic number of steps
        bounds = [i]
        doubts = [0]
        levels = [iter(ends(0, i))]
        while levels:
            t = len(levels) - 1
            p = bounds[t]
            s = body[t]
            for q in levels[t]:
                tick()
                if q < p or q > j:
                    continue
                rest = j - q
                if rest < smin[t + 1] or rest > smax[t + 1]:
                    continue
                if proper and s >= 0 and q - p == span:
                    continue
                ok = self._symbol_ok(s, p, q, missing)
                if ok is None:  # unknown yet, and noted in missing
                    if len(missing) > _MISSING_PER_PASS:
                        continue
                    doubt = doubts[t] + 1
                elif ok:
                    doubt = doubts[t]
                else:
                    continue
                if t == r - 1:
                    if not doubt:
                        yield (*bounds, q)
                    continue
                bounds.append(q)
                doubts.append(doubt)
                levels.append(iter(ends(t + 1, q)))
                break
            else:
                levels.pop()
                bounds.pop()
                doubts.pop()

    def _enumerate_short(self, body, i: int, j: int, proper: bool, missing: list | None):
        """:meth:`_enumerate` for a body of one or two symbols (length window already checked)."""
        g = self.g
        span = j - i
        symbol_ok = self._symbol_ok
        tick = self.budget.tick
        if len(body) == 1:
            s = body[0]
            tick()
            if proper and s >= 0:
                return
            ok = symbol_ok(s, i, j, missing)
            if ok:
                yield (i, j)
            return
        s, last = body
        if last < 0:
            low = high = 1
        else:
            low, high = g.minlen[last], g.maxlen[last]
        if s < 0:
            candidates = (i + 1,)
        else:
            candidates = range(max(i + g.minlen[s], j - high), min(i + g.maxlen[s], j - low) + 1)
        for q in candidates:
            tick()
            if q < i or q > j:
                continue
            rest = j - q
            if rest < low or rest > high:
                continue
            if proper and s >= 0 and q - i == span:
                continue
            ok = symbol_ok(s, i, q, missing)
            if ok is None:  # unknown yet, and noted in missing
                if len(missing) > _MISSING_PER_PASS:
                    continue
                doubt = True
            elif ok:
                doubt = False
            else:
                continue
            tick()
            if proper and last >= 0 and rest == span:
                continue
            ok = symbol_ok(last, q, j, missing)
            if ok is None:
                continue
            if ok and not doubt:
                yield (i, q, j)

    def _evaluate(self, key: tuple[int, int, int], missing: list) -> bool | None:
        a, i, j = key
        g = self.g
        for x in g.unit_closure(a):
            for rule in g.useful_by_lhs[x]:
                for _ in self._enumerate(rule, i, j, proper=True, missing=missing):
                    return True
        return None if missing else False

    def _resolve(self, root: tuple[int, int, int]) -> None:
        stack = [root]
        memo = self.memo
        budget = self.budget
        tick = budget.tick
        hold = self._hold
        # the stack holds each item's unknown children until they are resolved, the same
        # child once per item that asked for it, so it can outgrow the memo: its highest size
        # is counted while it lives
        counted = 1
        budget.hold(ITEM_SYMBOLS)
        while stack:
            key = stack[-1]
            if key in memo:
                stack.pop()
                continue
            tick()
            missing: list = []
            value = self._evaluate(key, missing)
            if value is None:
                stack.extend(missing)
                if len(stack) > counted:
                    budget.hold(ITEM_SYMBOLS * (len(stack) - counted))
                    counted = len(stack)
            else:
                memo[key] = value
                hold(ITEM_SYMBOLS)
                stack.pop()
        budget.held -= ITEM_SYMBOLS * counted  # the stack is gone; the memo stays counted
