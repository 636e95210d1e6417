"""The step kernel: what one step of a PSGS or a PCGS does to a configuration.

Derivation, membership and enumeration all take their steps from here, so
the semantics (decisions D1-D3 of docs/semantics.md for a PSGS, the classical communication and
rewriting steps for a PCGS, see ``docs/semantics.md``) is written once:

* :func:`occurrences` and :func:`rewrite` -- where a nonterminal occurs in a
  form, and replacing occurrences by a right-hand side;
* :func:`psgs_successors` -- every applicable tuple of a PSGS with its
  positions and the configuration after it;
* :func:`pcgs_steps` -- the communication step (which has priority) or every
  rewriting step of a PCGS;
* :func:`random_step` -- one uniformly random applicable step, drawn without
  listing them (in ``single`` mode their number is a product of occurrence
  counts), at the index :func:`psgs.derivation.applicable_steps` would give it.

These functions trust their input (a configuration of the system's own
symbols); :mod:`psgs.derivation` checks what a caller hands in.
"""

from __future__ import annotations

import itertools
import math
import random
from collections.abc import Iterator, Sequence
from dataclasses import dataclass
from typing import Literal, Union

from .analysis import moves as system_moves
from .model import IDLE, PCGS, PSGS, Form, Nonterminal, Query, Rule, SyncTuple, Terminal
from .notation import show_tuple

__all__ = [
    "Configuration", "Step", "initial_configuration", "is_terminal_form",
    "is_terminal_configuration", "has_query", "occurrences", "rewrite", "psgs_choices",
    "rewritten", "psgs_successors", "pcgs_communicate", "pcgs_steps", "random_step",
]

#: One sentential form per component.
Configuration = tuple[Form, ...]

_System = Union[PSGS, PCGS]


@dataclass(frozen=True)
class Step:
    """One step of a derivation: what was applied, where, and the configurations around it.

    ``tuple`` holds, per component, the rule applied there or ``None``
    (:data:`~psgs.model.IDLE`, ``#``). For a PSGS it is the synchronisation
    tuple of M that was applied (an unsynchronised rule applied alone under
    ``free`` appears as ``(#, …, p, …, #)``); a component whose form was
    already terminal keeps its entry but gets no positions. ``positions``
    gives, per component, the indices in ``before`` of the occurrences that
    were rewritten: all occurrences of the left-hand side in ``parallel``
    mode, one in ``single`` mode, none for idle or terminal components.

    For a PCGS, ``kind`` is ``"rewrite"`` (``tuple`` holds each component's
    rule, ``None`` for a terminal component) or ``"communicate"`` (``tuple``
    is all ``None``; ``positions`` are the query symbols that were replaced).

    Attributes
    ----------
    tuple : tuple of Rule or None
        Per component, the rule applied there or None (idle).
    positions : tuple of tuple of int
        Per component, the rewritten occurrences (or replaced queries) in ``before``.
    before, after : Configuration
        The configurations around the step.
    kind : {"rewrite", "communicate"}
        ``"communicate"`` only for a PCGS communication step.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> step = psgs.applicable_steps(gamma, psgs.initial_configuration(gamma))[0]
    >>> step.kind, step.positions
    ('rewrite', ((0,), (0,), (0,), (0,)))
    """

    tuple: tuple[Rule | None, ...]
    positions: tuple[tuple[int, ...], ...]
    before: Configuration
    after: Configuration
    kind: Literal["rewrite", "communicate"] = "rewrite"

    def __str__(self) -> str:
        return "communicate" if self.kind == "communicate" else show_tuple(self.tuple)


def initial_configuration(system: _System) -> Configuration:
    """The axioms ``(S_1, …, S_n)``, one one-symbol form per component.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> from psgs.notation import format_configuration
    >>> format_configuration(initial_configuration(gamma))
    '(S1, S2, S3, S4)'
    """
    return tuple((g.start,) for g in system.components)


def is_terminal_form(form: Form) -> bool:
    """True when every symbol of ``form`` is a terminal.

    Examples
    --------
    >>> from psgs.model import Nonterminal as N, Terminal as T
    >>> is_terminal_form((T("a"), T("b"))), is_terminal_form((T("a"), N("S")))
    (True, False)
    """
    return all(s.__class__ is Terminal for s in form)


def is_terminal_configuration(system: _System, configuration: Configuration) -> bool:
    """True when the derivation is finished: every form terminal (PSGS) or the master's (PCGS).

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> is_terminal_configuration(gamma, psgs.initial_configuration(gamma))
    False
    """
    if isinstance(system, PCGS):
        return is_terminal_form(configuration[system.master_index])
    return all(is_terminal_form(f) for f in configuration)


def has_query(form: Form) -> bool:
    """True when ``form`` holds a query symbol.

    Examples
    --------
    >>> from psgs.model import Query, Terminal as T
    >>> has_query((T("a"), Query("G2"))), has_query((T("a"),))
    (True, False)
    """
    return any(s.__class__ is Query for s in form)


def occurrences(form: Form, symbol: Nonterminal) -> tuple[int, ...]:
    """The positions of ``symbol`` in ``form``, in order.

    Examples
    --------
    >>> from psgs.model import Nonterminal as N, Terminal as T
    >>> occurrences((N("A"), T("b"), N("A")), N("A"))
    (0, 2)
    """
    # compares names rather than calling the dataclass __eq__ per symbol: forms get long
    name = symbol.name
    return tuple([k for k, s in enumerate(form) if s.__class__ is Nonterminal and s.name == name])


def positions_by_name(form: Form) -> dict[str, tuple[int, ...]]:
    """Every nonterminal of ``form`` by name, with its positions in order (one scan)."""
    table: dict[str, list[int]] = {}
    for k, s in enumerate(form):
        if s.__class__ is Nonterminal:
            table.setdefault(s.name, []).append(k)
    return {name: tuple(where) for name, where in table.items()}


def rewrite(form: Form, positions: Sequence[int], rhs: Form) -> Form:
    """Replace the symbols at ``positions`` (sorted) by ``rhs``.

    Examples
    --------
    >>> from psgs.model import Nonterminal as N, Terminal as T
    >>> rewrite((N("A"), T("b"), N("A")), [0, 2], (T("c"),))
    (Terminal(name='c'), Terminal(name='b'), Terminal(name='c'))
    """
    out: list = []
    last = 0
    for k in positions:
        out.extend(form[last:k])
        out.extend(rhs)
        last = k + 1
    out.extend(form[last:])
    return tuple(out)


def rewritten(configuration: Configuration, rules, positions) -> Configuration:
    """The configuration after rewriting, per component, ``positions`` with that ``rule``.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> from psgs.notation import format_configuration
    >>> start = psgs.initial_configuration(gamma)
    >>> format_configuration(rewritten(start, gamma.sync[0], [(0,)] * 4))
    '(N13S1, N18S2, N7S3, N23S4)'
    """
    return tuple(form if not pos else rewrite(form, pos, rule.rhs)
                 for form, rule, pos in zip(configuration, rules, positions))


# ---------------------------------------------------------------- PSGS
def psgs_choices(system: PSGS, configuration: Configuration, sync_tuple: SyncTuple,
                 where: Sequence[dict[str, tuple[int, ...]]] | None = None
                 ) -> list[list[tuple[int, ...]]] | None:
    """Per component the possible position choices, or None when the tuple does not apply.

    ``where`` (per component :func:`positions_by_name` of its form) saves a
    scan of every form per tuple when many tuples are tried on one
    configuration.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> start = psgs.initial_configuration(gamma)
    >>> psgs_choices(gamma, start, gamma.sync[0])
    [[(0,)], [(0,)], [(0,)], [(0,)]]
    """
    if where is None:
        where = [positions_by_name(form) for form in configuration]
    spots = _spots(sync_tuple, where)
    if spots is None:
        return None
    parallel = system.mode == "parallel"
    # a component that does not rewrite has the one choice (): idle, or a terminal form
    return [[()] if not occ else [occ] if parallel else [(k,) for k in occ] for occ in spots]


def psgs_successors(system: PSGS, configuration: Configuration,
                    moves: Sequence[SyncTuple] | None = None):
    """Yield ``(tuple, positions, after)`` for every applicable step, in listing order.

    ``moves`` are the system's moves (:func:`psgs.analysis.moves`); a search
    that calls this per configuration passes them in so they are built once.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> from psgs.notation import show_tuple
    >>> start = psgs.initial_configuration(gamma)
    >>> [show_tuple(entries) for entries, positions, after in psgs_successors(gamma, start)]
    ['(S1a, S2a, S3a, S4a)', '(S1b, S2b, S3b, S4b)']
    """
    where = [positions_by_name(form) for form in configuration]
    for sync_tuple in (system_moves(system) if moves is None else moves):
        choices = psgs_choices(system, configuration, sync_tuple, where)
        if choices is None:
            continue
        for positions in itertools.product(*choices):
            after = rewritten(configuration, sync_tuple, positions)
            if after != configuration:
                yield sync_tuple, positions, after


# ---------------------------------------------------------------- PCGS
def pcgs_communicate(system: PCGS, configuration: Configuration) -> Step | None:
    """The communication step, or None when no query can be answered.

    Examples
    --------
    >>> import psgs
    >>> copy = psgs.load("grammars/pcgs_copy.psgs")
    >>> pcgs_communicate(copy, psgs.initial_configuration(copy)) is None     # no query yet
    True
    """
    n = len(configuration)
    after = list(configuration)
    positions: list[tuple[int, ...]] = [()] * n
    sent: set[int] = set()
    for i, form in enumerate(configuration):
        where = tuple(k for k, s in enumerate(form) if s.__class__ is Query)
        if not where:
            continue
        targets = [system.index(form[k].component) for k in where]
        if any(has_query(configuration[j]) for j in targets):
            continue  # this component waits until every form it asks for is query-free
        out: list = []
        for s in form:
            out.extend(configuration[system.index(s.component)] if s.__class__ is Query else (s,))
        after[i] = tuple(out)
        positions[i] = where
        sent.update(targets)
    if not sent:
        return None
    if system.returning:
        for j in sent:
            after[j] = (system.components[j].start,)
    return Step((IDLE,) * n, tuple(positions), configuration, tuple(after), kind="communicate")


def _pcgs_rewrite_choices(system: PCGS, configuration: Configuration):
    """Per component its (rule, positions) options, or None when a component is stuck."""
    per_component = []
    for g, form in zip(system.components, configuration):
        if is_terminal_form(form):
            per_component.append([(IDLE, ())])
            continue
        where = positions_by_name(form)
        options = [(rule, (k,)) for rule in g.rules for k in where.get(rule.lhs.name, ())]
        if not options:
            return None  # a component that must rewrite but cannot blocks the system
        per_component.append(options)
    return per_component


def _pcgs_rewrite_step(configuration: Configuration, combo) -> Step:
    rules = tuple(r for r, _ in combo)
    positions = tuple(p for _, p in combo)
    return Step(rules, positions, configuration, rewritten(configuration, rules, positions))


def pcgs_steps(system: PCGS, configuration: Configuration) -> Iterator[Step]:
    """The communication step, if any form holds a query; otherwise every rewriting step.

    Examples
    --------
    >>> import psgs
    >>> copy = psgs.load("grammars/pcgs_copy.psgs")
    >>> steps = list(pcgs_steps(copy, psgs.initial_configuration(copy)))
    >>> {step.kind for step in steps}
    {'rewrite'}
    """
    if any(has_query(f) for f in configuration):
        step = pcgs_communicate(system, configuration)
        if step is not None:
            yield step
        return
    choices = _pcgs_rewrite_choices(system, configuration)
    if choices is None:
        return
    for combo in itertools.product(*choices):
        step = _pcgs_rewrite_step(configuration, combo)
        if step.after != configuration:
            yield step


# ---------------------------------------------------------------- random steps
def random_step(system: _System, configuration: Configuration,
                rng: random.Random, *, moves: Sequence[SyncTuple] | None = None,
                where: Sequence[dict[str, tuple[int, ...]]] | None = None) -> Step | None:
    """A uniformly random applicable step, or None; never lists all of them.

    In single mode the steps of one tuple are every choice of occurrences, a
    product that grows like the forms' lengths to the power n; counting them
    is cheap. The index drawn is the position the step would have in
    :func:`psgs.derivation.applicable_steps`, so a seed picks the same step
    either way. ``moves`` is :func:`psgs.analysis.moves` of a PSGS, when the
    caller draws many steps and has it already (it is the same every step);
    ``where`` (per component :func:`positions_by_name` of its form) saves a
    scan of every form when the caller has made it.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> import random
    >>> step = random_step(gamma, psgs.initial_configuration(gamma), random.Random(0))
    >>> step in psgs.applicable_steps(gamma, psgs.initial_configuration(gamma))
    True
    """
    if isinstance(system, PCGS):
        return _random_pcgs_step(system, configuration, rng)
    single = system.mode == "single"
    candidates = []
    total = 0
    if where is None:
        where = [positions_by_name(form) for form in configuration]
    for sync_tuple in (system_moves(system) if moves is None else moves):
        spots = _spots(sync_tuple, where)
        # whether a tuple changes something does not depend on the occurrences chosen, so it
        # is asked of its rules (no configuration built per tuple and step)
        if spots is None or not _changes(sync_tuple, spots):
            continue
        # single mode: one occurrence per rewriting component, the product of their counts;
        # the occurrences themselves are listed only for the tuple drawn
        count = math.prod(len(occ) for occ in spots if occ) if single else 1
        candidates.append((sync_tuple, spots, count))
        total += count
    if not total:
        return None
    index = rng.randrange(total)
    for sync_tuple, spots, count in candidates:
        if index < count:
            break
        index -= count
    positions = _unrank_spots(spots, index) if single else spots
    return Step(sync_tuple, positions, configuration, rewritten(configuration, sync_tuple, positions))


def _spots(sync_tuple: SyncTuple, where: Sequence[dict[str, tuple[int, ...]]]
           ) -> tuple[tuple[int, ...], ...] | None:
    """Per component the occurrences ``sync_tuple`` rewrites there (parallel mode's positions),
    ``()`` for an idle entry or a terminal form; None when the tuple does not apply.

    What :func:`psgs_choices` lists the choices of; :func:`random_step` counts them without
    listing single mode's one by one (a list per tuple, as long as the forms are, each step).
    """
    spots = []
    for rule, table in zip(sync_tuple, where):
        # a PSGS form holds terminals and nonterminals only: no nonterminal means terminal
        if rule is IDLE or not table:
            spots.append(())
            continue
        occ = table.get(rule.lhs.name, ())
        if not occ:
            return None
        spots.append(occ)
    return tuple(spots)


def _changes(sync_tuple: SyncTuple, spots: Sequence[tuple[int, ...]]) -> bool:
    """Whether applying ``sync_tuple`` at its occurrences ``spots`` changes the configuration.

    A component rewrites when it has occurrences (not ``()``: idle, or a terminal form);
    replacing an occurrence of ``A`` by the right-hand side changes the form unless that side
    is ``A`` alone.

    Examples
    --------
    >>> from psgs.model import Nonterminal as N, Rule, Terminal as T
    >>> keep, grow = Rule("k", N("A"), (N("A"),)), Rule("g", N("A"), (T("a"), N("A")))
    >>> _changes((keep, None), [(0,), ()]), _changes((keep, grow), [(0,), (2, 5)])
    (False, True)
    >>> _changes((grow,), [()])  # the form is terminal: the rule does not rewrite it
    False
    """
    return any(occ and rule.rhs != (rule.lhs,) for rule, occ in zip(sync_tuple, spots))


def _unrank_spots(spots: Sequence[tuple[int, ...]], index: int) -> tuple:
    """Single mode's ``index``-th step of a tuple: :func:`_unrank` of its :func:`psgs_choices`
    (``[(k,) for k in occ]`` per rewriting component, ``[()]`` per other one), unlisted."""
    picked = []
    for occ in reversed(spots):
        if occ:
            index, r = divmod(index, len(occ))
            picked.append((occ[r],))
        else:
            picked.append(())
    return tuple(reversed(picked))


def _unrank(choices, index: int) -> tuple:
    """The ``index``-th element of ``itertools.product(*choices)``."""
    picked = []
    for options in reversed(choices):
        index, r = divmod(index, len(options))
        picked.append(options[r])
    return tuple(reversed(picked))


def _random_pcgs_step(system: PCGS, configuration: Configuration, rng: random.Random):
    if any(has_query(f) for f in configuration):
        step = pcgs_communicate(system, configuration)
        if step is not None:
            rng.randrange(1)  # as if drawn from a list of one, so seeds match applicable_steps
        return step
    choices = _pcgs_rewrite_choices(system, configuration)
    if choices is None:
        return None
    unchanged = [sum(1 for rule, _ in options if rule is IDLE or rule.rhs == (rule.lhs,))
                 for options in choices]
    total = math.prod(len(options) for options in choices)
    void = math.prod(unchanged)  # combinations in which every component keeps its form
    if total == void:
        return None
    if void == 0:
        combo = _unrank(choices, rng.randrange(total))
    else:  # rare (rules A → A): draw until the step changes something, still uniform
        while True:
            combo = _unrank(choices, rng.randrange(total))
            if any(rule is not IDLE and rule.rhs != (rule.lhs,) for rule, _ in combo):
                break
    return _pcgs_rewrite_step(configuration, combo)
