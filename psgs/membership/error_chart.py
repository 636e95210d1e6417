"""An error-correcting chart: the edit distance from a span of a word to a nonterminal's language.

``ErrorChart.cost(A, i, j, cap)`` is the least edit cost of turning
``word[i:j]`` into some word that ``A`` derives in the component grammar
alone (Aho and Peterson's minimum-distance measure, computed top-down and
memoised), or ``inf`` when that cost exceeds ``cap``. ``splits(rule, i, j,
cap)`` lists the ways a rule's body can cover the span within ``cap``, with
their costs: what the synchronised search of :mod:`psgs.membership.nearest_search`
builds its moves from, the chart's costs serving as its admissible estimates.

Edit distance splits along a derivation tree: an optimal alignment of a
word with ``u = u_1 … u_r`` (the yields of a rule's body) cuts the word
into consecutive pieces aligned with each ``u_t``. So the cost of ``A`` on a
span is the least, over rules and splits of the span among the body, of the
children's costs; a terminal over a span costs its cheapest alignment (keep
one symbol, matched or substituted, delete the rest; or delete all and
insert it), a body over an empty span costs the cheapest insertion of a
yield (Knuth's least sums), an empty body over a span deletes it.

Why it terminates: a split in which one nonterminal child takes the whole
span leaves its siblings empty spans, whose cost is static; such chains are
folded into a weighted *unit closure* (Dijkstra over the rules, once per
nonterminal), and every other split gives its nonterminal children strictly
shorter spans, so the recursion is well founded. It runs on an explicit
stack. ``cap`` prunes: a span whose length alone forces more insertions or
deletions than the cap allows is never looked at, so for a fixed cap the
work stays near the spans a good alignment uses.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable, Sequence

from ..analysis import least_sums
from ..budget import Budget
from .chart import UNBOUNDED, CompiledGrammar
from .spine_costs import suffix_costs

__all__ = ["ErrorChart"]

INF = math.inf
#: How far apart two sums of the same edit costs may lie and be equal, relative to the largest
#: sum they were read from (a cost and the prefix sums of the word's deletions): each is rounded
#: in the order it was summed (0.4 + 0.2 is 0.6 and one unit in the last place). A few such
#: units: any wider and a cost that differs from another by less was taken for it (1e6 + 2e-6
#: for 1e6 + 1e-6); relative all the way down, so costs of 1e-10 are told apart as costs of 1
TOLERANCE = 1e-15
#: A walk over a body this short stops at its first unknown child (resolved first, nominal
#: ends first, so its value prunes the rest); a longer body notes many per pass.
_LONG_BODY = 8
#: How far along a span's edge a known neighbour is looked for.
_NEIGHBOURS = 8
#: A bounded nonterminal with at most this many words is costed against its words directly.
_FINITE_WORDS = 16
#: A row of edit distances reaches this far past the longest word (more on demand).
_ROW_MARGIN = 8


class ErrorChart:
    """Edit costs of the spans of one word against one compiled grammar (computed on demand).

    ``word`` holds symbol ids: a terminal of the system is its id in the
    compiled grammar, any other input symbol an id no terminal has.
    ``insert[t]`` is the cost of inserting terminal ``t``, ``delete[p]`` of
    deleting the symbol at position ``p``, ``substitute(p, t)`` of replacing it
    by ``t`` (0 when it is ``t``).

    Examples
    --------
    ``S → a S | a`` against ``a x a`` (``x`` is id 1, no terminal): one substitution or deletion.

    >>> from psgs.model import Grammar, Rule, Nonterminal as N, Terminal as T
    >>> from psgs.membership.chart import CompiledGrammar
    >>> g = Grammar("G", N("S"), (Rule("p", N("S"), (T("a"), N("S"))), Rule("q", N("S"), (T("a"),))))
    >>> cg = CompiledGrammar(g, {T("a"): 0})
    >>> word = [0, 1, 0]
    >>> chart = ErrorChart(cg, word, [1], [1, 1, 1], lambda p, t: 0 if word[p] == t else 1)
    >>> chart.cost(cg.index[N("S")], 0, 3, cap=5), chart.cost(cg.index[N("S")], 0, 0, cap=5)
    (1.0, 1)
    """

    def __init__(self, compiled: CompiledGrammar, word: Sequence[int], insert: Sequence[float],
                 delete: Sequence[float], substitute: Callable[[int, int], float],
                 budget: Budget | None = None) -> None:
        g = self.g = compiled
        self.word = list(word)
        self.n = len(self.word)
        self.insert = insert
        self.delete = list(delete)
        self.substitute = substitute
        self.budget = budget if budget is not None else Budget()
        prefix = [0.0]
        for d in self.delete:
            prefix.append(prefix[-1] + d)
        self.deleted = prefix  # deleted[j] - deleted[i]: deleting word[i:j]
        self.scale = prefix[-1]  # what a difference of prefix sums is rounded against
        terminal_ids = {~s for body in g.body for s in body if s < 0}
        self.min_insert = min((insert[t] for t in terminal_ids), default=INF)
        # dropping one symbol from a span's edge saves at most its deletion and costs at most
        # one insertion: what bounds a span's cost by a neighbouring span's
        self.max_insert = max((insert[t] for t in terminal_ids), default=0.0)
        self._by_end: dict[tuple[int, int], dict[int, float]] = {}
        self._by_start: dict[tuple[int, int], dict[int, float]] = {}
        self.min_delete = min(self.delete, default=INF)
        rules = [(g.lhs[k], [s for s in body if s >= 0], sum(insert[~s] for s in body if s < 0))
                 for k, body in enumerate(g.body)]
        least = least_sums(rules)
        self.min_yield = [least.get(a, INF) for a in range(len(g.nonterminals))]
        # per rule, the least insertion cost of each suffix of its body
        self.suffix_insert = []
        for body in g.body:
            acc = [0.0] * (len(body) + 1)
            for t in range(len(body) - 1, -1, -1):
                s = body[t]
                acc[t] = acc[t + 1] + (insert[~s] if s < 0 else self.min_yield[s])
            self.suffix_insert.append(acc)
        self._closure: dict[int, list[tuple[float, int]]] = {}
        self.finite = self._finite_languages()
        self.finite_lists = [None if ws is None else [list(u) for u in ws] for ws in self.finite]
        self._rows: dict[tuple[int, int], list[float]] = {}
        self.memo: dict[tuple[int, int, int], tuple[float, bool]] = {}
        # what the chart keeps, in symbols (memo entries, row cells, cached splits): counted
        # against the search's max_symbols, so a word far from the language (large caps,
        # long rows) cannot grow the chart without bound
        self.held = 0
        self._split_cache: dict[tuple[int, int, int], tuple[float, list, float]] = {}
        # a right-linear spine: the exact cost of every span a spine occurrence can have, at
        # once and in linear time, instead of top-down with a number of ends that grows with
        # the cap
        spine = suffix_costs(self)
        if spine is not None:
            self.memo.update((key, (value, True)) for key, value in spine.items())

    def _hold(self, symbols: int) -> None:
        self.held += symbols
        self.budget.hold(symbols)

    # ---------------------------------------------------------- bounds
    def _length_bound(self, smin: int, smax: int, length: int) -> float:
        if length < smin:
            return (smin - length) * self.min_insert
        if length > smax:
            return (length - smax) * self.min_delete
        return 0.0

    def lower_bound(self, a: int, i: int, j: int) -> float:
        """A cheap lower bound of ``cost(a, i, j)`` from lengths alone."""
        if i == j:
            return self.min_yield[a]
        return self._length_bound(self.g.minlen[a], self.g.maxlen[a], j - i)

    def terminal_cost(self, t: int, i: int, j: int) -> float:
        """The cost of aligning ``word[i:j]`` with the one terminal ``t``."""
        if i == j:
            return self.insert[t]
        dels = self.deleted[j] - self.deleted[i]
        best = dels + self.insert[t]
        sub = self.substitute
        delete = self.delete
        for r in range(i, j):
            c = dels - delete[r] + sub(r, t)
            if c < best:
                best = c
        return best

    def closure(self, a: int) -> list[tuple[float, int]]:
        """``(u, x)``: ``a ⇒* α x β`` with ``α β`` inserted at least cost ``u``, sorted by ``u``."""
        found = self._closure.get(a)
        if found is not None:
            return found
        g = self.g
        best = {a: 0.0}
        heap = [(0.0, a)]
        out = []
        while heap:
            u, x = heapq.heappop(heap)
            if u > best.get(x, INF):
                continue
            out.append((u, x))
            for k in g.useful_by_lhs[x]:
                self.budget.tick()
                body = g.body[k]
                total = self.suffix_insert[k][0]
                for s in body:
                    if s >= 0:
                        v = u + total - self.min_yield[s]
                        if v < best.get(s, INF):
                            best[s] = v
                            heapq.heappush(heap, (v, s))
        self._closure[a] = out
        return out

    def _finite_languages(self) -> list:
        """Per nonterminal its few words (tuples of terminal ids), or None when there are many.

        A nonterminal of bounded yield whose language has at most
        ``_FINITE_WORDS`` words is costed by comparing the span with its
        words directly (:meth:`_row`), not through its derivation trees:
        the blocks of the induced grammars are such, and one row of edit
        distances gives every end of a span at once.
        """
        g = self.g
        langs: list = [None] * len(g.nonterminals)
        for component in g._components:  # successor components first
            if any(g.maxlen[a] >= UNBOUNDED or g.minlen[a] >= UNBOUNDED for a in component):
                continue
            current = {a: set() for a in component}
            ok = True
            changed = True
            while changed and ok:
                changed = False
                for a in component:
                    for k in g.useful_by_lhs[a]:
                        self.budget.tick()
                        words = [()]
                        for sym in g.body[k]:
                            if sym < 0:
                                options = ((~sym,),)
                            elif sym in current:
                                options = tuple(current[sym])
                            else:
                                options = langs[sym]
                            if options is None:
                                ok = False
                                break
                            words = [w + o for w in words for o in options]
                            if len(words) > _FINITE_WORDS:
                                ok = False
                                break
                        if not ok:
                            break
                        for w in words:
                            if w not in current[a]:
                                current[a].add(w)
                                changed = True
                        if len(current[a]) > _FINITE_WORDS:
                            ok = False
                            break
                    if not ok:
                        break
            if ok:
                for a in component:
                    langs[a] = tuple(sorted(current[a]))
        return langs

    def _row(self, a: int, i: int, j: int) -> float:
        """``cost(a, i, j)`` for a nonterminal with few words: edit distances from ``i`` on."""
        row = self._rows.get((a, i))
        if row is None:
            # the common case, a block read without error, needs no row
            span = self.word[i:j]
            for u in self.finite_lists[a]:
                if u == span:
                    return 0.0
        if row is None or j - i >= len(row):
            # a longer row on demand: at least twice as long, so a row is built a few times
            upto = min(self.n, max(j, i + self.g.maxlen[a] + _ROW_MARGIN,
                                   i + 2 * len(row) if row is not None else 0))
            row = self._edit_row(self.finite[a], i, upto)
            self._rows[(a, i)] = row
            self._hold(len(row))
        return row[j - i]

    def _edit_row(self, words, i: int, upto: int) -> list[float]:
        """Least edit distance from ``word[i:j]`` to one of ``words``, for every ``j ≤ upto``."""
        delete = self.delete
        insert = self.insert
        sub = self.substitute
        span = upto - i
        first = [0.0] * (span + 1)
        for k in range(span):
            first[k + 1] = first[k] + delete[i + k]
        best = [INF] * (span + 1)
        for u in words:
            self.budget.tick()
            prev = first
            for t in u:
                cost_t = insert[t]
                row = [prev[0] + cost_t]
                for k in range(span):
                    p = i + k
                    v = prev[k] + sub(p, t)
                    x = prev[k + 1] + cost_t
                    if x < v:
                        v = x
                    x = row[k] + delete[p]
                    if x < v:
                        v = x
                    row.append(v)
                prev = row
            for k in range(span + 1):
                if prev[k] < best[k]:
                    best[k] = prev[k]
        return best

    # ---------------------------------------------------------- queries
    def tolerance(self, value: float) -> float:
        """How far a sum of costs near ``value`` may lie from another of the same costs
        summed otherwise (:data:`TOLERANCE` of it and of the word's deletions)."""
        return TOLERANCE * (value + self.scale)

    def cost(self, a: int, i: int, j: int, cap: float) -> float:
        """The least cost of ``a`` on ``word[i:j]`` when it is at most ``cap``, else ``inf``.

        ``cap`` is widened by :meth:`tolerance`: the walk prunes a child against
        ``cap`` less what its siblings cost, and that difference can round a
        hair below the child's own cost (``7.6 - 5.0 < 2.6``), so a value equal
        to ``cap`` read as above it.
        """
        cap += self.tolerance(cap)
        if i == j:
            v = self.min_yield[a]
            return v if v <= cap else INF
        if self.lower_bound(a, i, j) > cap:
            return INF
        if self.finite[a] is not None:
            v = self._row(a, i, j)
            return v if v <= cap else INF
        key = (a, i, j)
        entry = self.memo.get(key)
        if entry is None or (not entry[1] and entry[0] < cap):
            self._resolve(key, cap)
            entry = self.memo[key]
        value, exact = entry
        return value if exact and value <= cap else INF

    def splits(self, rule: int, i: int, j: int, cap: float) -> tuple[list, float]:
        """Every split of ``word[i:j]`` among ``rule``'s body costing at most ``cap``.

        Returns ``(splits, excess)``: the splits as ``(cost, boundaries)``
        sorted by cost (boundaries ``i = m0 ≤ … ≤ mr = j``; ``(i,)`` for an
        empty body), and a lower bound of the cost of every split left out
        (``inf`` when none was).
        """
        key = (rule, i, j)
        cached = self._split_cache.get(key)
        if cached is not None and cached[0] >= cap:
            used, found, excess = cached
            kept = [s for s in found if s[0] <= cap]
            if len(kept) < len(found):
                excess = min(excess, found[len(kept)][0])
            return kept, excess
        found = []
        excess = [INF]
        for total, bounds in self._walk(rule, i, j, cap, proper=False, missing=None,
                                        excess=excess):
            found.append((total, bounds))
        found.sort()
        self._split_cache[key] = (cap, found, excess[0])
        self._hold(1 + sum(len(b) for _, b in found))
        return found, excess[0]

    # ---------------------------------------------------------- machinery
    def _child(self, s: int, p: int, q: int, need: float, missing: list | None):
        """Cost of body symbol ``s`` on ``word[p:q]``: ``(value, known)``.

        A child that costs more than ``need`` gives ``(lower bound, None)``:
        the caller prunes it (a bound just above ``need`` cannot be added to
        other costs without rounding it away, so pruning is said, not summed).
        """
        if s < 0:
            return self.terminal_cost(~s, p, q), True
        if p == q:
            return self.min_yield[s], True
        lb = self._length_bound(self.g.minlen[s], self.g.maxlen[s], q - p)
        if lb > need:
            return lb, None
        if self.finite[s] is not None:
            v = self._row(s, p, q)
            return (v, True) if v <= need else (v, None)
        if missing is None:
            self.cost(s, p, q, need)
            v, exact = self.memo[(s, p, q)]
            return v, (True if exact else None)
        entry = self.memo.get((s, p, q))
        if entry is not None:
            v, exact = entry
            if exact:
                return v, True
            if v >= need:
                return v, None
            lb = max(lb, v)
        near = self._neighbour_bound(s, p, q, need)
        if near > need:
            return near, None
        missing.append((s, p, q, need))
        return max(lb, near), False

    def _neighbour_bound(self, s: int, p: int, q: int, need: float) -> float:
        """A lower bound of ``cost(s, p, q)`` from spans of ``s`` that differ at one edge.

        Moving a span's edge by ``k`` symbols changes its cost by at most ``k``
        insertions one way and the deletion of those symbols the other way,
        so a known neighbour bounds an unknown span before it is computed
        (a misaligned span next to a well-aligned one is then pruned unseen).
        """
        best = 0.0
        mx = self.max_insert
        deleted = self.deleted
        reach = _NEIGHBOURS
        starts = self._by_end.get((s, q))
        if starts:
            for x in range(max(0, p - reach), min(q, p + reach) + 1):
                v = starts.get(x)
                if v is not None:
                    b = v - (x - p) * mx if x > p else v - (deleted[p] - deleted[x])
                    if b > best:
                        best = b
        ends = self._by_start.get((s, p))
        if ends:
            for y in range(max(p, q - reach), min(self.n, q + reach) + 1):
                v = ends.get(y)
                if v is not None:
                    b = v - (q - y) * mx if y < q else v - (deleted[y] - deleted[q])
                    if b > best:
                        best = b
        return best

    def _walk(self, rule: int, i: int, j: int, cap: float, proper: bool, missing: list | None,
              excess: list):
        """Yield ``(cost, boundaries)`` of the splits within ``cap`` whose children are known.

        With ``missing`` given, children not computed yet are noted there (with
        the cost up to which they are needed) and their split is not yielded.
        ``excess[0]`` is lowered to the least lower bound of a pruned branch.
        """
        g = self.g
        body = g.body[rule]
        r = len(body)
        span = j - i
        if r == 0:
            c = self.deleted[j] - self.deleted[i]
            if c <= cap:
                yield c, (i,)
            elif c < excess[0]:
                excess[0] = c
            return
        smin = g.suffix_min[rule]
        smax = g.suffix_max[rule]
        sins = self.suffix_insert[rule]
        tick = self.budget.tick
        mi, md = self.min_insert, self.min_delete
        minlen, maxlen = g.minlen, g.maxlen

        def rest_bound(t: int, remaining: int) -> float:
            if remaining == 0:
                return sins[t]
            return self._length_bound(smin[t], smax[t], remaining)

        def ends(t: int, p: int, acc: float):
            if t == r - 1:
                return (j,)
            slack = cap - acc
            s = body[t]
            lo, hi = (1, 1) if s < 0 else (minlen[s], maxlen[s])
            lo2, hi2 = smin[t + 1], smax[t + 1]
            # the child's length and the rest's length may each stray from their windows
            # only as far as the slack pays for insertions or deletions
            ins_room = slack / mi if mi > 0 else UNBOUNDED
            del_room = slack / md if md > 0 else UNBOUNDED
            first = max(p, p + lo - math.floor(ins_room) if lo < UNBOUNDED else p,
                        j - min(UNBOUNDED, hi2 + math.floor(del_room)))
            last = min(j, p + min(UNBOUNDED, hi + math.floor(del_room)),
                       j - max(0, lo2 - math.floor(ins_room)))
            if (first > p or last < j) and cap < excess[0]:
                excess[0] = cap  # the ends left out cost more than cap
            found = range(max(first, p), last + 1)
            if missing is None or len(found) <= 1:
                return found
            # the cheapest-looking ends first: the child's cost when it is cheap to know (a
            # terminal, a few-word block), else its length bound, plus the rest's length
            # bound. Resolving the well-aligned child first lets its value prune the others
            # (a misaligned suffix is cut one block later by its aligned neighbour's bound)
            if s < 0:
                return sorted(found, key=lambda q: self.terminal_cost(~s, p, q)
                              + self._length_bound(lo2, hi2, j - q))
            if self.finite[s] is not None:
                if q_last := (found[-1] if found[-1] > p else 0):
                    self._row(s, p, q_last)  # the farthest end first: one row serves them all
                return sorted(found, key=lambda q: (self._row(s, p, q) if q > p
                                                    else self.min_yield[s])
                              + self._length_bound(lo2, hi2, j - q))
            return sorted(found, key=lambda q: self._length_bound(lo, hi, q - p)
                          + self._length_bound(lo2, hi2, j - q))

        bounds = [i]
        accs = [0.0]
        knowns = [True]
        levels = [iter(ends(0, i, 0.0))]
        while levels:
            t = len(levels) - 1
            p = bounds[t]
            acc = accs[t]
            s = body[t]
            for q in levels[t]:
                tick()
                if proper and s >= 0 and q - p == span:
                    continue
                rest = rest_bound(t + 1, j - q)
                need = cap - acc - rest
                if need < 0:
                    if acc + rest < excess[0]:
                        excess[0] = acc + rest
                    continue
                value, known = self._child(s, p, q, need, missing)
                total = acc + value
                if known is None:  # more than need: the branch costs more than cap
                    if min(total + rest, cap) < excess[0]:
                        excess[0] = min(total + rest, cap)
                    continue
                if total + rest > cap:
                    if total + rest < excess[0]:
                        excess[0] = total + rest
                    continue
                known = known and knowns[t]
                if missing and r <= _LONG_BODY:
                    return  # resolve this child first: its value prunes the other ends
                if t == r - 1:
                    if known:
                        yield total, (*bounds, q)
                    continue
                bounds.append(q)
                accs.append(total)
                knowns.append(known)
                levels.append(iter(ends(t + 1, q, total)))
                break
            else:
                levels.pop()
                bounds.pop()
                accs.pop()
                knowns.pop()

    def _evaluate(self, a: int, i: int, j: int, cap: float, missing: list) -> float:
        best = INF
        g = self.g
        span = j - i
        for u, x in self.closure(a):
            bound = min(cap, best)
            if u > bound:
                break
            if u + self._length_bound(g.minlen[x], g.maxlen[x], span) > bound:
                continue
            for rule in g.useful_by_lhs[x]:
                # only a cheaper split matters once one is known (ties are pruned)
                bound = cap if best == INF else min(cap, best - self.tolerance(best))
                excess = [INF]
                for total, _ in self._walk(rule, i, j, bound - u, True, missing, excess):
                    if u + total < best:
                        best = u + total
                if missing and len(g.body[rule]) <= _LONG_BODY:
                    return best
        return best

    def _resolve(self, root: tuple[int, int, int], cap: float) -> None:
        stack = [(*root, cap)]
        memo = self.memo
        tick = self.budget.tick
        while stack:
            a, i, j, need = stack[-1]
            entry = memo.get((a, i, j))
            if entry is not None and (entry[1] or entry[0] >= need):
                stack.pop()
                continue
            tick()
            missing: list = []
            value = self._evaluate(a, i, j, need, missing)
            if missing:
                stack.extend(missing)
                continue
            stack.pop()
            if value <= need:
                memo[(a, i, j)] = (value, True)
            else:
                value = max(need, entry[0]) if entry else need
                memo[(a, i, j)] = (value, False)
            self._by_end.setdefault((a, j), {})[i] = value
            self._by_start.setdefault((a, i), {})[j] = value
            self._hold(3)
