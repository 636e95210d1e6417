"""The sequential baseline: digram rules per string, no synchronisation.

Each string is compressed on its own, Re-Pair/Sequitur style: while some
digram occurs at least ``min_count`` times (non-overlapping), the most
frequent one (earliest first among equals) becomes a rule N -> X Y and its
occurrences are replaced by N. Every string that gets at least one rule is a
component, and its pattern is the expansion of its longest rule. Nothing
checks the strings against each other, so random strings, which nearly
always repeat some digram, become components too: this is the
overgeneralisation the paper's PAL avoids.
"""

from __future__ import annotations

import numpy as np

from ..actiongram import Actiongram
from .base import Induction, Inducer, StringReport, build_system, check_number, component_name

__all__ = ["Sequential"]


class Sequential(Inducer):
    """Per-string digram grammar learning without synchronisation.

    Parameters: ``min_count`` (2), the fewest occurrences of a digram that
    make a rule; ``max_rules`` (100000), a bound on rules per string (the
    string's report says ``"rule bound reached"`` when it stops there).
    """

    name = "sequential"

    def __init__(self, *, min_count: int = 2, max_rules: int = 100_000) -> None:
        check_number("min_count", min_count, low=2, integer=True)
        check_number("max_rules", max_rules, low=1, integer=True)
        self.min_count = min_count
        self.max_rules = max_rules

    def induce(self, actiongram: Actiongram) -> Induction:
        """Learn each string alone; see the module docstring."""
        if not isinstance(actiongram, Actiongram):
            raise TypeError(f"Sequential.induce needs an Actiongram, not "
                            f"{type(actiongram).__name__}")
        patterns, occurrences, reports = {}, {}, []
        for name, syms, durs, origin in zip(actiongram.names, actiongram.symbols,
                                            actiongram.segment_durations, actiongram.origins):
            found = _repair(syms, self.min_count, self.max_rules)
            if found is None:
                reports.append(StringReport(name=name, status="no repetition"))
                continue
            pattern, positions, rules, bounded = found
            ends = origin + np.cumsum(np.asarray(durs, dtype=np.float64))
            starts = ends - np.asarray(durs, dtype=np.float64)
            patterns[name] = pattern
            occurrences[name] = tuple((float(starts[p]), float(ends[p + len(pattern) - 1]))
                                      for p in positions)
            reports.append(StringReport(
                name=name, status="rule bound reached" if bounded else "component",
                motif=pattern, copies=len(positions)))
        kept = tuple(n for n in actiongram.names if n in patterns)
        taken: set[str] = set()
        comp_names = {n: component_name(n, taken) for n in kept}
        system = (build_system([(comp_names[n], patterns[n]) for n in kept], synchronise=False,
                               name="sequential") if kept else None)
        return Induction(system=system, components=kept,
                         patterns={n: patterns[n] for n in kept},
                         occurrences={n: occurrences[n] for n in kept}, reports=tuple(reports),
                         component_names=comp_names, inducer=self.name, params=self.get_params())


def _repair(symbols: tuple[str, ...], min_count: int, max_rules: int):
    """Re-Pair one string: (pattern, start positions of its occurrences, rules, bounded) or None."""
    if len(symbols) < 2:
        return None
    alphabet: dict[str, int] = {}
    seq = np.fromiter((alphabet.setdefault(s, len(alphabet)) for s in symbols), dtype=np.int64,
                      count=len(symbols))
    names = list(alphabet)
    origin = np.arange(len(seq), dtype=np.int64)  # where each current symbol starts
    expansion: dict[int, tuple[int, int]] = {}
    length_of = {c: 1 for c in range(len(names))}
    next_code = len(names)
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
    positions = tuple(int(p) for p in origin[seq == longest])
    return pattern, positions, len(expansion), bounded
