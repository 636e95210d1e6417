"""The sequential baseline: digram rules per string, no synchronisation.

Each string is compressed on its own, Re-Pair/Sequitur style: while some
digram occurs at least ``min_count`` times (non-overlapping), the most
frequent one (earliest first among equals) becomes a rule N -> X Y and its
occurrences are replaced by N. Every string that gets at least one rule is a
component, and its pattern is the expansion of its longest rule. Nothing
checks the strings against each other, so random strings, which nearly
always repeat some digram, become components too: this is the
overgeneralisation the paper's PAL avoids.

Several performances: an actuator's strings from all performances are
compressed together -- digrams are counted over every performance, but no
digram spans the end of one performance and the start of the next (each
boundary is a separator that occurs once, so it can never be in a rule).
Occurrences are times within their own performance; the induction's
``occurrence_performance`` says which.
"""

from __future__ import annotations

from collections.abc import Sequence
import heapq
from dataclasses import dataclass, replace

import numpy as np

from .base import Inducer, as_performances
from .conf import Conf, Number, parameter
from .results import Induction, StringReport

__all__ = ["Sequential", "SequentialConf"]


@dataclass(frozen=True)
class SequentialConf(Conf):
    """The sequential baseline's parameters (see :class:`Sequential`).

    Examples
    --------
    >>> SequentialConf(min_count=3).max_rules
    100000
    """

    min_count: int = parameter(2, Number(low=2, integer=True))
    max_rules: int = parameter(100_000, Number(low=1, integer=True))


class Sequential(Inducer):
    """Per-string digram grammar learning without synchronisation.

    Parameters
    ----------
    min_count : int, optional
        The fewest occurrences of a digram that make a rule (default 2, at least 2).
    max_rules : int, optional
        A bound on rules per string (default 100000); the string's report says
        ``"rule bound reached"`` when the bound stopped a further rule from being made (a
        string whose last rule is the ``max_rules``-th is learnt whole, and says so), and
        the Induction's ``bound`` is then ``"max_rules"``.

    Raises
    ------
    ValidationError
        For a parameter that is not an integer in its range.

    Examples
    --------
    >>> from psgs import Actiongram
    >>> result = Sequential().induce(Actiongram.from_strings({"x": "abcabcabc", "y": "pq"}))
    >>> result.components, result.report("y").status
    (('x',), 'no repetition')
    >>> two = [Actiongram.from_strings({"x": "abab"}), Actiongram.from_strings({"x": "cabx"})]
    >>> result = Sequential().induce(two)
    >>> result.patterns["x"], result.occurrence_performance["x"]
    (('a', 'b'), (0, 0, 1))
    >>> Sequential(max_rules=1).induce(Actiongram.from_strings({"x": "abcabcabc"})).reason
    'stopped making rules at max_rules=1 on 1 string'
    """

    name = "sequential"
    Conf = SequentialConf

    def induce(self, performances) -> Induction:
        """Learn each string alone (an actuator's performances together); see the module docstring.

        Parameters
        ----------
        performances : Actiongram or sequence of Actiongram
            One actiongram, or several performances with the same actuators.

        Returns
        -------
        Induction
            Unsynchronised: the system has no tuples.

        Raises
        ------
        TypeError
            When the input is not an actiongram or a sequence of them.
        ValidationError
            For an empty sequence or performances whose actuators differ.
        """
        takes = as_performances(performances, "Sequential.induce")
        conf = self.conf()
        first = takes[0]
        patterns, occurrences, where, reports = {}, {}, {}, []
        for i, name in enumerate(first.names):
            found = _repair([take.symbols[i] for take in takes], conf.min_count, conf.max_rules)
            if found is None:
                reports.append(StringReport(name=name, status="no repetition"))
                continue
            pattern, positions, rules, bounded = found
            spans = []
            for k, p in positions:
                durs = np.asarray(takes[k].segment_durations[i], dtype=np.float64)
                ends = takes[k].origins[i] + np.cumsum(durs)
                starts = ends - durs
                spans.append((float(starts[p]), float(ends[p + len(pattern) - 1])))
            patterns[name] = pattern
            occurrences[name] = tuple(spans)
            where[name] = tuple(k for k, _ in positions)
            reports.append(StringReport(
                name=name, status="rule bound reached" if bounded else "component",
                motif=pattern, copies=len(positions)))
        result = self.build_induction(first.names, patterns, occurrences, reports,
                                      synchronise=False, performances=len(takes),
                                      occurrence_performance=where)
        stopped = [r.name for r in reports if r.status == "rule bound reached"]
        if not stopped:
            return result
        return replace(result, bound="max_rules", reason=(
            f"stopped making rules at max_rules={conf.max_rules} on {len(stopped)} "
            f"string{'' if len(stopped) == 1 else 's'}"))


def _repair(strings: Sequence[tuple[str, ...]], min_count: int, max_rules: int):
    """Re-Pair one actuator's strings (one per performance), no digram across two of them.

    Returns (pattern, occurrences as (performance, start position), rules,
    bounded), or None when no digram repeats.
    """
    alphabet: dict[str, int] = {}
    for syms in strings:
        for s in syms:
            alphabet.setdefault(s, len(alphabet))
    names = list(alphabet)
    # between two performances a separator code of its own: it occurs once, so never in a rule
    codes: list[int] = []
    offsets: list[int] = []
    for k, syms in enumerate(strings):
        if k:
            codes.append(len(names) + k - 1)
        offsets.append(len(codes))
        codes.extend(alphabet[s] for s in syms)
    if len(codes) < 2:
        return None
    expansion, length_of, final, bounded = _pair_rules(codes, len(names) + len(strings) - 1,
                                                       min_count, max_rules)
    if not expansion:
        return None
    held = {}  # how often each code stands in the final sequence
    for c in final.values():
        held[c] = held.get(c, 0) + 1
    longest = max(expansion, key=lambda c: (length_of[c], held.get(c, 0), -c))

    def spell(c: int) -> list[int]:
        out, stack = [], [c]
        while stack:
            v = stack.pop()
            if v in expansion:
                a, b = expansion[v]
                stack.extend((b, a))
            else:
                out.append(v)
        return out

    pattern = tuple(names[c] for c in spell(longest))
    bounds = np.asarray(offsets, dtype=np.int64)
    positions = []
    for p in sorted(p for p, c in final.items() if c == longest):
        k = int(np.searchsorted(bounds, p, side="right")) - 1
        positions.append((k, int(p) - offsets[k]))
    return pattern, tuple(positions), len(expansion), bounded


def _pair_rules(codes: list[int], first_new: int, min_count: int, max_rules: int):
    """Re-Pair on ``codes``: ``(expansion, length_of, final, bounded)``.

    Each round makes the most frequent digram (the most places it starts at, overlapping ones
    of a run ``N N N`` too; among equals the one starting first) a rule, replacing its
    occurrences left to right (a run's overlapping ones skipped), until that digram starts at
    fewer than ``min_count`` places left after the skipping, or ``max_rules`` rules are made
    and another would be (``bounded`` says so; not when the last rule the bound allows is the
    last one there is).
    ``final`` maps each place left (its original position) to its code.

    The digrams' places are kept up to date as pairs are replaced -- only the neighbours of a
    replaced pair change -- and the most frequent is read from a heap, so a round costs what
    it replaces, not a count over the whole sequence (that was quadratic: a random string of
    10**5 symbols took 12 s, 10**6 did not finish).
    """
    n = len(codes)
    if n < 2:  # no digram at all
        return {}, {}, dict(enumerate(codes)), False
    sym = list(codes)
    nxt = list(range(1, n)) + [-1]
    prv = [-1] + list(range(n - 1))
    places: dict[tuple[int, int], set[int]] = {}  # digram -> the places it starts at
    firsts: dict[tuple[int, int], list[int]] = {}  # digram -> a heap of its places (lazy)
    ranking: list = []  # (-count, first place, digram), lazy: checked when popped

    def first(key):
        heap, held = firsts[key], places[key]
        while heap[0] not in held:
            heapq.heappop(heap)
        return heap[0]

    def add(p):
        key = (sym[p], sym[nxt[p]])
        places.setdefault(key, set()).add(p)
        heapq.heappush(firsts.setdefault(key, []), p)
        return key

    def remove(p):
        key = (sym[p], sym[nxt[p]])
        places[key].discard(p)
        return key

    for p in range(n - 1):
        add(p)
    for key in places:
        heapq.heappush(ranking, (-len(places[key]), first(key), key))
    expansion: dict[int, tuple[int, int]] = {}
    length_of: dict[int, int] = {}
    code, alive, bounded = first_new, n, False
    while alive >= 2 and ranking:
        count, at, key = heapq.heappop(ranking)
        held = places.get(key)
        if not held or -count != len(held) or first(key) != at:
            continue  # an entry of an older count or first place
        hits = sorted(held)
        if key[0] == key[1]:  # a run N N N: non-overlapping pairs, left to right
            keep = []
            for p in hits:
                if not keep or nxt[keep[-1]] != p:
                    keep.append(p)
            hits = keep
        if len(hits) < min_count:
            break
        if len(expansion) >= max_rules:
            # checked here, with the next rule in hand: a string whose compression ends at
            # its max_rules-th rule anyway is not one the bound stopped
            bounded = True
            break
        expansion[code] = key
        length_of[code] = length_of.get(key[0], 1) + length_of.get(key[1], 1)
        touched = set()
        for p in hits:
            q = nxt[p]
            if prv[p] >= 0:
                touched.add(remove(prv[p]))
            remove(p)
            if nxt[q] >= 0:
                touched.add(remove(q))
            sym[p] = code
            nxt[p] = nxt[q]
            if nxt[q] >= 0:
                prv[nxt[q]] = p
            alive -= 1
            if prv[p] >= 0:
                touched.add(add(prv[p]))
            if nxt[p] >= 0:
                touched.add(add(p))
        touched.add(key)
        for k in touched:
            if places[k]:
                heapq.heappush(ranking, (-len(places[k]), first(k), k))
        code += 1
    final, p = {}, 0
    while p >= 0:
        final[p] = sym[p]
        p = nxt[p]
    return expansion, length_of, final, bounded
