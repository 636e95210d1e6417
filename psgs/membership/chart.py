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
nullable set. The recursion runs on an explicit stack, so deep right
recursion (thousands of ``S → N S``) does not hit Python's recursion limit.

Length windows (each nonterminal's minimum and maximum yield, the maximum
capped at "unbounded") prune the split points: a block of fixed length has
one possible end, so the chart never tries the others.
"""

from __future__ import annotations

import time
from collections.abc import Sequence

from ..analysis import reachable
from ..errors import BoundReached
from ..model import Grammar, Nonterminal, Rule, Terminal

UNBOUNDED = 1 << 60


class CompiledGrammar:
    """A grammar with integer symbols and its static length analysis.

    Symbols in rule bodies are ints: a nonterminal is its index (≥ 0), a
    terminal ``t`` is ``~id(t)`` (< 0) with ids from ``terminal_ids``.
    """

    def __init__(self, grammar: Grammar, terminal_ids: dict[Terminal, int],
                 rules=None) -> None:
        self.grammar = grammar
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
        nullable = [False] * n
        minlen = [UNBOUNDED] * n
        changed = True
        while changed:
            changed = False
            for k, a in enumerate(self.lhs):
                body = self.body[k]
                if not nullable[a] and all(s >= 0 and nullable[s] for s in body):
                    nullable[a] = changed = True
                total = sum(1 if s < 0 else minlen[s] for s in body)
                if total < minlen[a]:
                    minlen[a] = total
                    changed = True
        self.nullable = nullable
        self.minlen = minlen
        productive = [m < UNBOUNDED for m in minlen]
        useful_rules = [k for k in range(len(self.rules))
                        if all(s < 0 or productive[s] for s in self.body[k])]
        self.maxlen = self._max_lengths(useful_rules, productive)
        # unit closure: A ⇒* α X β with α β ⇒* ε, over useful rules
        unit_edges: list[set[int]] = [set() for _ in range(n)]
        for k in useful_rules:
            body = self.body[k]
            for t, s in enumerate(body):
                if s >= 0 and all(o >= 0 and nullable[o] for u, o in enumerate(body) if u != t):
                    unit_edges[self.lhs[k]].add(s)
        self.unit_closure = [tuple(sorted(reachable(unit_edges, [a]))) for a in range(n)]
        self.useful_by_lhs = [[k for k in ks if k in set(useful_rules)] for ks in self.by_lhs]
        self.first = self._edge_terminals(useful_rules, reverse=False)
        self.last = self._edge_terminals(useful_rules, reverse=True)
        # per rule, min/max yield of each suffix of the body
        self.suffix_min: list[list[int]] = []
        self.suffix_max: list[list[int]] = []
        for body in self.body:
            smin = [0] * (len(body) + 1)
            smax = [0] * (len(body) + 1)
            for t in range(len(body) - 1, -1, -1):
                s = body[t]
                smin[t] = smin[t + 1] + (1 if s < 0 else minlen[s])
                smax[t] = min(UNBOUNDED, smax[t + 1] + (1 if s < 0 else self.maxlen[s]))
            self.suffix_min.append(smin)
            self.suffix_max.append(smax)

    def _edge_terminals(self, useful_rules: list[int], reverse: bool) -> list[frozenset[int]]:
        """Terminal ids that can begin (or, reversed, end) a non-empty yield of each nonterminal."""
        sets: list[set[int]] = [set() for _ in self.nonterminals]
        changed = True
        while changed:
            changed = False
            for k in useful_rules:
                target = sets[self.lhs[k]]
                body = self.body[k][::-1] if reverse else self.body[k]
                for s in body:
                    if s < 0:
                        if ~s not in target:
                            target.add(~s)
                            changed = True
                        break
                    if not sets[s] <= target:
                        target |= sets[s]
                        changed = True
                    if not self.nullable[s]:
                        break
        return [frozenset(x) for x in sets]

    def _max_lengths(self, useful_rules: list[int], productive: list[bool]) -> list[int]:
        """Longest yield per nonterminal, UNBOUNDED when a pumping cycle is reachable."""
        n = len(self.nonterminals)
        can_grow = [False] * n  # derives some non-empty word
        changed = True
        while changed:
            changed = False
            for k in useful_rules:
                a = self.lhs[k]
                if not can_grow[a] and any(s < 0 or can_grow[s] for s in self.body[k]):
                    can_grow[a] = changed = True
        edges: list[set[int]] = [set() for _ in range(n)]
        for k in useful_rules:
            for s in self.body[k]:
                if s >= 0:
                    edges[self.lhs[k]].add(s)
        reach = [reachable(edges, [a], strict=True) for a in range(n)]
        # a rule of A pumps when A ⇒+ ...A... through one body symbol Y (A ∈ reach[Y] or Y = A)
        # while another symbol of the body can yield something
        pumping = [False] * n
        for k in useful_rules:
            a = self.lhs[k]
            body = self.body[k]
            for t, s in enumerate(body):
                if s >= 0 and (s == a or a in reach[s]):
                    if any(o < 0 or can_grow[o] for u, o in enumerate(body) if u != t):
                        pumping[a] = True
        unbounded = [pumping[a] or any(pumping[b] for b in reach[a]) for a in range(n)]
        maxlen = [0 if productive[a] else 0 for a in range(n)]
        for a in range(n):
            if unbounded[a]:
                maxlen[a] = UNBOUNDED
        # bounded symbols: the longest yield is reached without pumping, so n+1 rounds settle it
        for _ in range(n + 1):
            changed = False
            for k in useful_rules:
                a = self.lhs[k]
                if unbounded[a]:
                    continue
                total = sum(1 if s < 0 else maxlen[s] for s in self.body[k])
                if total > maxlen[a]:
                    maxlen[a] = total
                    changed = True
            if not changed:
                break
        return maxlen


class Chart:
    """Which nonterminals derive which spans of one word (computed on demand)."""

    def __init__(self, compiled: CompiledGrammar, word: Sequence[int],
                 deadline: float | None = None) -> None:
        self.g = compiled
        self.word = list(word)
        self.n = len(self.word)
        self.memo: dict[tuple[int, int, int], bool] = {}
        self.deadline = deadline
        self._split_cache: dict[tuple[int, int, int], tuple[tuple[int, ...], ...]] = {}

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
        return cached

    # ---------------------------------------------------------- machinery
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
        bounds = [i]

        def walk(t: int, p: int):
            s = body[t]
            if t == r - 1:
                ends = (j,)
            elif s < 0:
                ends = (p + 1,)
            else:
                lo = max(p + g.minlen[s], j - smax[t + 1])
                hi = min(p + g.maxlen[s], j - smin[t + 1])
                ends = range(lo, hi + 1)
            for q in ends:
                if q < p or q > j:
                    continue
                rest = j - q
                if rest < smin[t + 1] or rest > smax[t + 1]:
                    continue
                if proper and s >= 0 and q - p == span:
                    continue
                ok = self._symbol_ok(s, p, q, missing)
                if not ok:
                    continue
                bounds.append(q)
                if t == r - 1:
                    yield tuple(bounds)
                else:
                    yield from walk(t + 1, q)
                bounds.pop()

        yield from walk(0, i)

    def _evaluate(self, key: tuple[int, int, int], missing: list) -> bool | None:
        a, i, j = key
        g = self.g
        for x in g.unit_closure[a]:
            for rule in g.useful_by_lhs[x]:
                for _ in self._enumerate(rule, i, j, proper=True, missing=missing):
                    return True
        return None if missing else False

    def _resolve(self, root: tuple[int, int, int]) -> None:
        stack = [root]
        memo = self.memo
        counter = 0
        while stack:
            key = stack[-1]
            if key in memo:
                stack.pop()
                continue
            counter += 1
            if self.deadline is not None and counter % 2048 == 0 and \
                    time.monotonic() > self.deadline:
                raise BoundReached("max_seconds")
            missing: list = []
            value = self._evaluate(key, missing)
            if value is None:
                stack.extend(missing)
            else:
                memo[key] = value
                stack.pop()
