"""The lower bounds of the parallel-mode form search: lengths, letters and alignments.

:class:`FormBounds` holds what the bounds of one component's forms read: its
error chart, the lengths and letters each nonterminal derives in its grammar
alone, and each nonterminal's cost on the input's spans. Each bound never
exceeds the cost of a word the form derives; see
:mod:`psgs.membership.parallel_distance` for how the search combines them.
The alignments run on numpy arrays, one operation per symbol of the form (the
search asks for thousands of them); numpy is imported on the first.
"""

from __future__ import annotations

from ._span_table import span_costs
from .chart import UNBOUNDED
from .error_chart import INF, ErrorChart

__all__ = ["FormBounds"]

#: The alignment bound is computed for a form when the cells it reads (a span per nonterminal
#: occurrence, a position per terminal) are at most this many; longer forms keep the length
#: bound alone.
_CHART_CELLS = 200_000

#: The highest level of :meth:`FormBounds.bound` (0 lengths and letters, 1 the alignment, 2
#: the alignment with one length for a nonterminal's occurrences), each dearer than the last.
_LEVELS = 2

#: How many lengths of a frequent nonterminal's word :meth:`FormBounds.same_length` tries.
_LENGTHS = 8

#: Inputs up to this long align a nonterminal of many words by its cost on every span from
#: the start (:func:`~psgs.membership._span_table.span_costs`: 0.04 s at 64 symbols)...
_TABLE_LENGTH = 64
#: ... inputs up to this long once the search has explored ``_LATE_STATES`` forms (0.1 s at 100
#: symbols, a small part of a search that long); longer ones by its lengths.
_LATE_TABLE_LENGTH = 128
_LATE_STATES = 64


def _lengths(compiled, most: int, tick) -> list[int]:
    """Per nonterminal, the lengths ``≤ most`` it derives in its grammar alone, as a bitset."""
    mask = (1 << (most + 1)) - 1
    sets = [0] * len(compiled.nonterminals)
    changed = True
    while changed:
        changed = False
        for a, body in zip(compiled.lhs, compiled.body):
            tick()
            acc = 1
            for s in body:
                acc = _sumset(acc, 2 if s < 0 else sets[s], mask)
                if not acc:
                    break
            if acc | sets[a] != sets[a]:
                sets[a] |= acc
                changed = True
    return sets


def _letters(compiled) -> list[int]:
    """Per nonterminal, the terminals its words can hold, as a bitset of terminal ids."""
    sets = [0] * len(compiled.nonterminals)
    changed = True
    while changed:
        changed = False
        for a, body in zip(compiled.lhs, compiled.body):
            acc = sets[a]
            for s in body:
                acc |= (1 << ~s) if s < 0 else sets[s]
            if acc != sets[a]:
                sets[a] = acc
                changed = True
    return sets


def _sumset(x: int, y: int, mask: int) -> int:
    """``{p + q : p in x, q in y}`` as bitsets, cut at ``mask``."""
    if x.bit_count() > y.bit_count():
        x, y = y, x
    out = 0
    while x:
        low = x & -x
        out |= y << (low.bit_length() - 1)
        x ^= low
    return out & mask


def _scaled(x: int, k: int, mask: int) -> int:
    """``{k p : p in x}`` as a bitset, cut at ``mask``."""
    if k == 1:
        return x & mask
    out = 0
    most = mask.bit_length()
    while x:
        low = x & -x
        p = (low.bit_length() - 1) * k
        if p >= most:
            break
        out |= 1 << p
        x ^= low
    return out


class FormBounds:
    """What the bounds of one component's forms read: its chart, lengths and costs."""

    def __init__(self, compiled, chart: ErrorChart, tick, hold) -> None:
        self.compiled = compiled
        self.chart = chart
        self.n = chart.n
        # lengths are kept up to 2n + 1: any longer word is n + 2 insertions away at least,
        # one bound for all of them
        self.most = 2 * self.n + 1
        self.mask = (1 << (self.most + 1)) - 1
        self.lengths = _lengths(compiled, self.most, tick)
        self.minlen, self.maxlen = compiled.minlen, compiled.maxlen
        self.letters = _letters(compiled)
        self._foreign: dict[int, float] = {}
        self._columns: dict[int, list[list[float]]] = {}
        self._table: list | None = None  # span_costs, once an alignment asks for it
        self._arrays: dict | None = None  # the arrays _aligned reads, made on its first call
        self._integral: bool | None = None  # whether every cost is whole (asked once)
        self._hold = hold

    def bound(self, form, cap: float, level: int, late: bool, tick) -> float:
        """A lower bound of what a word ``form`` derives costs; ``inf`` when above ``cap``.

        A terminal form: its edit distance. Otherwise the largest of the lengths' and the
        letters' bounds (``level`` 0) and, when the form reads at most ``_CHART_CELLS``
        cells, of its alignment (``level`` 1; by every span's cost when the input is at
        most ``_TABLE_LENGTH`` long, or ``_LATE_TABLE_LENGTH`` once the search is
        ``late``) or of the alignment that gives its most frequent nonterminal's
        occurrences words of one length (``level`` 2, :meth:`same_length`).
        """
        counts: dict[int, int] = {}
        fixed = 0
        letters = 0
        for s in form:
            if s < 0:
                fixed += 1
                letters |= 1 << ~s
            else:
                counts[s] = counts.get(s, 0) + 1
        if not counts:
            return self.chart_bound(form, cap, True, tick)
        for x in counts:
            letters |= self.letters[x]
        value = max(self.length_bound(counts, fixed), self.foreign_bound(letters))
        n = self.n
        cells = sum(counts.values()) * (n + 1) * (n + 2) // 2 + fixed * (n + 1)
        if level == 0 or value > cap or cells > _CHART_CELLS:
            return value
        exact = n <= _TABLE_LENGTH or (late and n <= _LATE_TABLE_LENGTH)
        x = max(counts, key=counts.get)
        if level == 1 or counts[x] == 1:
            return max(value, self.chart_bound(form, cap, exact, tick))
        return max(value, self.same_length(form, counts, fixed, x, cap, exact, tick))

    def same_length(self, form, counts, fixed: int, x: int, cap: float, exact: bool,
                    tick) -> float:
        """The alignment with every occurrence of ``x`` given words of one length: a bound.

        The occurrences of ``x`` derive one word, so one length ``l``: each costs at
        least its chart cost on its span and the insertions or deletions that take the
        span's length to ``l``. The bound is the least over ``l`` of that alignment, for
        the ``_LENGTHS`` lengths ``x`` derives whose words the lengths alone make
        cheapest, and of the lengths' bound for the rest; at least the alignment without
        the constraint (computed with them, in one pass).
        """
        chart, n = self.chart, self.n
        k = counts[x]
        least = most = fixed
        for y, m in counts.items():
            if y != x:
                least += m * self.minlen[y]
                most += m * self.maxlen[y]

        def length_cost(length: int) -> float:
            low, high = least + k * length, most + k * length
            if low > n:
                return (low - n) * chart.min_insert
            if high < n and most < UNBOUNDED:
                return (n - high) * chart.min_delete
            return 0.0

        options = []  # (cost by lengths, length)
        lengths = self.lengths[x]
        while lengths:
            low = lengths & -lengths
            options.append((length_cost(low.bit_length() - 1), low.bit_length() - 1))
            lengths ^= low
        options.sort()
        rest = [cost for cost, _ in options[_LENGTHS:]]
        if self.maxlen[x] > self.most:  # longer words than the bitsets hold
            rest.append(length_cost(self.most + 1))
        floor = min(rest, default=INF)
        # the first row is the alignment without the constraint (its length None)
        tried = [None, *(length for _, length in options[:_LENGTHS])]
        values = self._aligned(form, cap, exact, tick, (x, tried))
        aligned = float(values[0])
        return max(aligned, min(floor, float(values[1:].min(initial=INF))))

    def foreign_bound(self, letters: int) -> float:
        """What the input symbols no terminal of ``letters`` (a bitset of ids) matches cost.

        Each is deleted or substituted, one edit of its own.
        """
        known = self._foreign.get(letters)
        if known is not None:
            return known
        chart = self.chart
        ids = [t for t in range(letters.bit_length()) if letters >> t & 1]
        total = 0.0
        for p, x in enumerate(chart.word):
            if x < 0 or not letters >> x & 1:
                total += min([chart.delete[p], *(chart.substitute(p, t) for t in ids)])
        self._foreign[letters] = total
        return total

    def length_bound(self, counts: dict[int, int], fixed: int) -> float:
        """The least cost of the length change a word of the form needs."""
        chart, n, mask = self.chart, self.n, self.mask
        reach = (1 << fixed) & mask
        longest = fixed
        for x, k in counts.items():
            if self.minlen[x] >= UNBOUNDED:
                return INF  # x derives no word
            reach = _sumset(reach, _scaled(self.lengths[x], k, mask), mask)
            longest += k * self.maxlen[x]
            if not reach and longest <= self.most:
                return INF
        best = INF
        below = reach & ((1 << (n + 1)) - 1)
        if below:
            shortfall = n - (below.bit_length() - 1)
            best = 0.0 if shortfall == 0 else shortfall * chart.min_delete
        above = reach >> n
        if above:
            excess = (above & -above).bit_length() - 1
            best = min(best, 0.0 if excess == 0 else excess * chart.min_insert)
        if longest > self.most:  # a length past what the bitsets hold
            best = min(best, (self.most + 1 - n) * chart.min_insert)
        return best

    def columns(self, x: int, exact: bool, tick) -> list[list[float]]:
        """Per end ``q``, what ``x`` costs on each span ``(p, q)``, ``p ≤ q``: a lower bound.

        ``exact``: every nonterminal's cost on every span, from
        :func:`~psgs.membership._span_table.span_costs` (built once); else a nonterminal of
        few words by the chart's rows (exact, one per start) and any other by its lengths.
        """
        if exact:
            if self._table is None:
                n = self.n
                self._hold(2 * (len(self.compiled.nonterminals) + sum(
                    max(0, len(body) - 2) for body in self.compiled.body)) * (n + 1) ** 2)
                self._table = span_costs(self.chart, tick)
            return self._table[x]
        known = self._columns.get(x)
        if known is not None:
            return known
        chart = self.chart
        deleted, least, n = chart.deleted, chart.min_yield[x], self.n
        few = chart.finite[x] is not None
        cols = []
        for q in range(n + 1):
            col = []
            for p in range(q + 1):
                tick()
                value = INF
                if few:  # capped by deleting the span and inserting the least word: exact
                    value = chart.cost(x, p, q, deleted[q] - deleted[p] + least)
                if value == INF:
                    value = chart.lower_bound(x, p, q)
                col.append(value)
            cols.append(col)
        self._columns[x] = cols
        return cols

    def chart_bound(self, form, cap: float, exact: bool, tick) -> float:
        """The least cost of the form's symbols aligned with the input one after the other.

        Each terminal matched, substituted or inserted, any input symbol deleted,
        each nonterminal against the words it derives alone (:meth:`columns`):
        exact on a terminal form, a lower bound on any other. By arrays, which sum
        in another order than the edit script does, unless the form is terminal and a
        cost is not whole (then by the script's order: its value is the distance).
        ``inf`` when above ``cap``.
        """
        if self._integral is None:  # whole costs sum exactly in any order
            chart = self.chart
            self._integral = all(float(v).is_integer() and abs(v) < 2 ** 40 for v in (
                *chart.insert, *chart.delete,
                *(chart.substitute(p, t) for p in range(self.n)
                  for t in range(len(chart.insert)))))
        if self._integral or any(s >= 0 for s in form):
            return self._aligned(form, cap, exact, tick)
        chart, n = self.chart, self.n
        delete, insert, sub = chart.delete, chart.insert, chart.substitute
        row = list(chart.deleted)  # row[q]: the form so far against word[:q]
        tolerance = chart.tolerance(cap)
        for s in form:
            tick()
            t = ~s
            cost = insert[t]
            new = [row[0] + cost]
            for q in range(1, n + 1):
                a, b = row[q] + cost, row[q - 1] + sub(q - 1, t)
                new.append(a if a < b else b)
            for q in range(1, n + 1):  # input symbols deleted after the form so far
                if new[q - 1] + delete[q - 1] < new[q]:
                    new[q] = new[q - 1] + delete[q - 1]
            row = new
            if min(row) > cap + tolerance:
                return INF  # every later symbol only adds
        return row[n] if row[n] <= cap + tolerance else INF

    def _aligned(self, form, cap: float, exact: bool, tick, fixed=None):
        """:meth:`chart_bound` of a form with a nonterminal, one array operation per symbol.

        ``fixed``: ``(x, lengths)``, one alignment per length ``l`` at once, in which each
        occurrence of ``x`` also costs at least the length change from its span to ``l``
        (:meth:`same_length`); then an array of their values (``inf`` above ``cap``).
        """
        import numpy as np  # only here: the form search is the one user in psgs.membership

        chart, n = self.chart, self.n
        if self._arrays is None:
            self._arrays = {"deleted": np.array(chart.deleted, dtype=float)}
        arrays = self._arrays
        deleted = arrays["deleted"]
        limit = cap + chart.tolerance(cap)
        # row[..., q]: the form so far against word[:q], one row per length tried
        row = deleted if fixed is None else np.tile(deleted, (len(fixed[1]), 1))
        for s in form:
            tick()
            if s < 0:
                kept = arrays.get(s)
                if kept is None:  # keeping input symbol q - 1 for the terminal
                    kept = arrays[s] = np.array([chart.substitute(p, ~s) for p in range(n)],
                                                dtype=float)
                new = row + chart.insert[~s]  # inserted after the form on word[:q]
                np.minimum(new[..., 1:], row[..., :-1] + kept, out=new[..., 1:])
            else:
                if fixed is not None and fixed[0] == s:
                    costs = self._fixed_costs(np, s, exact, fixed[1], tick)
                else:
                    costs = self._costs(np, s, exact, tick)
                # new[..., q]: the least over p of row[..., p] + costs[..., p, q]
                new = (row[..., :, None] + costs).min(axis=-2)
            # input symbols deleted after the form so far: new[q] = min over p ≤ q of
            # new[p] + deleted[q] - deleted[p]
            row = np.minimum.accumulate(new - deleted, axis=-1) + deleted
            if row.min() > limit:
                return INF if fixed is None else np.full(len(fixed[1]), INF)
        if fixed is not None:
            values = row[:, -1]
            return np.where(values <= limit, values, INF)
        value = float(row[-1])
        return value if value <= limit else INF

    def _costs(self, np, x: int, exact: bool, tick):
        """``costs[p, q]``: ``x`` on ``word[p:q]`` (:meth:`columns`), ``inf`` below the diagonal."""
        key = (x, exact or self.chart.finite[x] is not None)
        costs = self._arrays.get(key)
        if costs is None:
            costs = np.full((self.n + 1, self.n + 1), INF)
            for q, col in enumerate(self.columns(x, exact, tick)):
                costs[:q + 1, q] = col
            self._arrays[key] = costs
            self._hold((self.n + 1) ** 2)
        return costs

    def _fixed_costs(self, np, x: int, exact: bool, lengths, tick):
        """Per length ``l``: :meth:`_costs` of ``x``, each span at least the change to ``l``."""
        arrays = self._arrays
        base = self._costs(np, x, exact, tick)
        stack_key = (x, exact, tuple(lengths))
        if arrays.get("stack", (None,))[0] == stack_key:  # the stack of the call under way
            return arrays["stack"][1]
        stack = []
        for length in lengths:
            if length is None:
                stack.append(base)
                continue
            spans = arrays.get("spans")
            if spans is None:  # spans[p, q] = q - p
                ends = np.arange(self.n + 1)
                spans = arrays["spans"] = ends[None, :] - ends[:, None]
            chart = self.chart
            over = spans - length
            change = np.zeros(over.shape)  # no 0 × inf: a grammar without terminals
            change[over > 0] = over[over > 0] * chart.min_delete
            change[over < 0] = -over[over < 0] * chart.min_insert
            costs = np.maximum(base, change)
            stack.append(costs)
        arrays["stack"] = (stack_key, np.stack(stack))
        return arrays["stack"][1]
