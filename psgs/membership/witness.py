"""The witness of a yes: the schedule a search found, and its replay as a derivation.

A schedule is a small typed value: for a PSGS the words and one
:class:`ScheduledMove` per step (the tuple applied and, per component, the
occurrences it rewrote as :class:`Rewrite` values); for a PCGS the steps of
the derivation found. The searches work on their own compact states; a yes
is trusted only once :func:`replay` has applied each step with
:func:`psgs.derivation.apply_tuple` (which checks it) to real configurations
and the last one holds the words.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Union

from ..derivation import Derivation, apply_tuple, initial_configuration
from ..errors import ValidationError
from ..model import PCGS, PSGS, Nonterminal, SyncTuple, Terminal, Word
from ..steps import Step

__all__ = ["Rewrite", "ScheduledMove", "PSGSSchedule", "PCGSSchedule", "Schedule", "replay"]


@dataclass(frozen=True, slots=True)
class Rewrite:
    """One occurrence rewritten by a scheduled move.

    ``symbol`` derives ``word[start:end]``; ``split`` gives the boundaries
    ``(start = m0 ≤ m1 ≤ … ≤ mr = end)`` of the spans of the rule's body
    symbols, one more boundary than the body has symbols.
    """

    symbol: Nonterminal
    start: int
    end: int
    split: tuple[int, ...]


@dataclass(frozen=True, slots=True)
class ScheduledMove:
    """One step of a PSGS schedule: the tuple applied and, per component, what it rewrote."""

    entries: SyncTuple
    rewrites: tuple[tuple[Rewrite, ...], ...]


@dataclass(frozen=True, slots=True)
class PSGSSchedule:
    """A PSGS schedule: the words it derives and its moves, in order."""

    words: tuple[Word, ...]
    moves: tuple[ScheduledMove, ...]


@dataclass(frozen=True, slots=True)
class PCGSSchedule:
    """A PCGS derivation found by the search, as its steps."""

    steps: tuple[Step, ...]


Schedule = Union[PSGSSchedule, PCGSSchedule]




def replay(system: PSGS | PCGS, schedule: Schedule) -> Derivation:
    """Turn a schedule into a :class:`~psgs.derivation.Derivation`, checking each step."""
    if isinstance(schedule, PCGSSchedule):
        return _replay_pcgs(system, schedule)
    if not isinstance(schedule, PSGSSchedule):
        raise ValidationError(f"not a schedule: {schedule!r}")
    words = schedule.words
    configuration = initial_configuration(system)
    # per component, the span each symbol of the form must derive (None for terminals)
    spans: list[list] = [[(0, len(w))] for w in words]
    steps = []
    for move in schedule.moves:
        where_per_component = [_locate(rw, spans[c], configuration[c])
                               for c, rw in enumerate(move.rewrites)]
        positions = [tuple(sorted(where)) if where else None for where in where_per_component]
        step = apply_tuple(system, configuration, move.entries, positions)
        for c, (rw, where) in enumerate(zip(move.rewrites, where_per_component)):
            if not rw:
                continue
            split_at = {k: r.split for r, k in zip(rw, where)}
            rhs = move.entries[c].rhs
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


def _locate(rewrites, spans, form) -> list[int]:
    """The form positions of the rewritten occurrences, in the order of ``rewrites``.

    Equal occurrences (same symbol, same span) are taken leftmost first; an
    index of them keeps this linear in the form's length.
    """
    if not rewrites:
        return []
    wanted = {(r.symbol, r.start, r.end) for r in rewrites}
    free: dict[tuple, list[int]] = {}
    for k in range(len(spans) - 1, -1, -1):  # reversed, so pop() gives the leftmost
        sp = spans[k]
        if sp is not None and (form[k], *sp) in wanted:
            free.setdefault((form[k], *sp), []).append(k)
    taken: list[int] = []
    for r in rewrites:
        where = free.get((r.symbol, r.start, r.end))
        if not where:  # pragma: no cover - would be a bug in the search
            raise ValidationError("witness replay lost track of an occurrence")
        taken.append(where.pop())
    return taken


def _replay_pcgs(system: PCGS, schedule: PCGSSchedule) -> Derivation:
    configuration = initial_configuration(system)
    steps = []
    for found in schedule.steps:
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
