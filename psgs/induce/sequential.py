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
from dataclasses import dataclass

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
        ``"rule bound reached"`` when it stops there.

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
        return self.build_induction(first.names, patterns, occurrences, reports,
                                    synchronise=False, performances=len(takes),
                                    occurrence_performance=where)


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
    seq = np.asarray(codes, dtype=np.int64)
    origin = np.arange(len(seq), dtype=np.int64)  # where each current symbol starts
    expansion: dict[int, tuple[int, int]] = {}
    length_of = {c: 1 for c in range(len(names) + len(strings) - 1)}
    next_code = len(names) + len(strings) - 1
    base = np.int64(1 << 31)
    bounded = False
    while len(seq) >= 2:
        if len(expansion) >= max_rules:
            bounded = True
            break
        keys = seq[:-1] * base + seq[1:]
        uniq, first, counts = np.unique(keys, return_index=True, return_counts=True)
        order = np.lexsort((first, -counts))
        best = uniq[order[0]]
        hits = np.flatnonzero(keys == best)
        left, right = int(best // base), int(best % base)
        if left == right:  # runs like N N N: take non-overlapping pairs left to right
            keep, last = [], -2
            for p in hits.tolist():
                if p >= last + 2:
                    keep.append(p)
                    last = p
            hits = np.asarray(keep, dtype=np.int64)
        if len(hits) < min_count:
            break
        code = next_code
        next_code += 1
        expansion[code] = (left, right)
        length_of[code] = length_of[left] + length_of[right]
        seq = seq.copy()
        seq[hits] = code
        drop = np.ones(len(seq), dtype=bool)
        drop[hits + 1] = False
        seq, origin = seq[drop], origin[drop]
    if not expansion:
        return None
    longest = max(expansion, key=lambda c: (length_of[c], int(np.sum(seq == c)), -c))

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
    for p in origin[seq == longest].tolist():
        k = int(np.searchsorted(bounds, p, side="right")) - 1
        positions.append((k, int(p) - offsets[k]))
    return pattern, tuple(positions), len(expansion), bounded
