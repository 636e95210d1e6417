"""The derivation engine: configurations, steps and derivations of PSGS and PCGS.

A *configuration* holds one sentential form per component. For a
:class:`~psgs.model.PSGS`, a step applies one synchronisation tuple
(the decisions D1-D3 of ``docs/semantics.md``); for a :class:`~psgs.model.PCGS` a
step is either a communication step (which has priority) or a rewriting
step in which every non-terminal component rewrites once.

This module is the checked front of the step kernel (:mod:`psgs.steps`):
it validates what a caller hands in, lists and applies steps, and builds
:class:`Derivation` values. Everything here is a pure function of
immutable values; randomness comes only from an explicit seed. Languages
are enumerated by :mod:`psgs.enumeration`.
"""

from __future__ import annotations

import math
import operator
import numbers
import random
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Union

from .analysis import moves
from .budget import Budget, check_count, check_seconds
from .errors import ValidationError
from .model import IDLE, PCGS, PSGS, Form, Nonterminal, Query, Terminal, resolve_tuple
from .notation import format_configuration, format_form, short, show_tuple, spaced
from .steps import (Configuration, Step, has_query, initial_configuration as _initial,
                    is_terminal_configuration, is_terminal_form, occurrences, pcgs_communicate,
                    pcgs_steps, positions_by_name, psgs_successors, random_step, rewritten)

# Configuration and Step are psgs.steps', the notation psgs.notation's: used here, not
# offered again from here (one home per name)
__all__ = [
    "Derivation", "initial_configuration", "applicable_steps", "apply_tuple",
    "communication_step", "random_derivation",
]

_System = Union[PSGS, PCGS]


# ---------------------------------------------------------------- basics
def initial_configuration(system: _System) -> Configuration:
    """The axioms ``(S_1, …, S_n)``, one one-symbol form per component.

    Parameters
    ----------
    system : PSGS or PCGS
        The system.

    Returns
    -------
    tuple of forms
        One one-symbol form (the axiom) per component.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> [str(form[0]) for form in psgs.initial_configuration(gamma)]
    ['S1', 'S2', 'S3', 'S4']
    """
    _require_system(system)
    return _initial(system)


def _require_system(system: object) -> None:
    if not isinstance(system, (PSGS, PCGS)):
        raise ValidationError(f"expected a PSGS or a PCGS, not {type(system).__name__}")


def _check_configuration(system: _System, configuration: Sequence[Form]) -> Configuration:
    try:
        configuration = tuple(tuple(f) for f in configuration)
    except TypeError:  # None, a number, a lone symbol: not forms
        raise ValidationError(f"a configuration is a sequence of forms, one per component, "
                              f"not {short(repr(configuration))}") from None
    if len(configuration) != len(system.components):
        raise ValidationError(f"a configuration of this system has {len(system.components)} "
                              f"forms, not {len(configuration)}")
    allowed = _PSGS_SYMBOLS if isinstance(system, PSGS) else _PCGS_SYMBOLS
    for g, form in zip(system.components, configuration):
        if set(map(type, form)) <= allowed:  # the fast check; the loop below finds the culprit
            continue
        for sym in form:
            if isinstance(sym, Query) and isinstance(system, PSGS):
                raise ValidationError(f"component {g.name}: a PSGS form holds no query symbol")
            if type(sym) not in allowed:
                raise ValidationError(f"component {g.name}: {sym!r} is not a symbol")
    return configuration


_PSGS_SYMBOLS = frozenset({Terminal, Nonterminal})
_PCGS_SYMBOLS = frozenset({Terminal, Nonterminal, Query})


# ---------------------------------------------------------------- steps
def applicable_steps(system: _System, configuration: Sequence[Form]) -> tuple[Step, ...]:
    """Every step that applies to ``configuration``, in a deterministic order.

    PSGS (decision D3 of docs/semantics.md): a tuple ``(p_1, …, p_n)`` applies iff for every component
    ``i`` with ``p_i ≠ #`` whose form is not terminal, the left-hand side of
    ``p_i`` occurs in it; idle and terminal components stay unchanged, and a
    tuple that would change nothing does not apply. Tuples come in the order
    of M, then (under ``free``) each unsynchronised rule alone, by component
    and rule order. In ``single`` mode there is one step per choice of the
    rewritten occurrences, leftmost choices first.

    PCGS: when some form holds a query symbol the only possible step is the
    communication step (none when every query waits on a form that holds a
    query itself, e.g. circular queries: the system is blocked). Otherwise
    every rewriting step in which each non-terminal component rewrites one
    occurrence once; a non-terminal component that cannot rewrite blocks the
    system (no steps).

    Parameters
    ----------
    system : PSGS or PCGS
        The system.
    configuration : sequence of forms
        One sentential form per component.

    Returns
    -------
    tuple of Step
        Empty when the configuration is terminal or blocked.

    Raises
    ------
    ValidationError
        When the configuration does not fit the system (wrong number of forms, symbols of
        another kind).

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> start = psgs.initial_configuration(gamma)
    >>> [[rule.label for rule in step.tuple] for step in psgs.applicable_steps(gamma, start)]
    [['S1a', 'S2a', 'S3a', 'S4a'], ['S1b', 'S2b', 'S3b', 'S4b']]
    """
    _require_system(system)
    configuration = _check_configuration(system, configuration)
    if isinstance(system, PCGS):
        return tuple(pcgs_steps(system, configuration))
    return tuple(_psgs_steps(system, configuration))


def _psgs_steps(system: PSGS, configuration: Configuration):
    for sync_tuple, positions, after in psgs_successors(system, configuration):
        yield Step(sync_tuple, positions, configuration, after)


def _is_allowed_tuple(system: PSGS, entries: tuple) -> bool:
    """In M, or (under free) an unsynchronised rule alone: one of the system's moves."""
    return entries in moves(system)


def communication_step(system: PCGS, configuration: Sequence[Form]) -> Step:
    """The communication step of a PCGS configuration; :class:`ValidationError` if none applies.

    Examples
    --------
    >>> import psgs
    >>> copy = psgs.load("grammars/pcgs_copy.psgs")
    >>> start = psgs.initial_configuration(copy)
    >>> communication_step(copy, start)
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: ...
    """
    if not isinstance(system, PCGS):
        raise ValidationError("communication steps exist only in a PCGS")
    configuration = _check_configuration(system, configuration)
    if not any(has_query(f) for f in configuration):
        raise ValidationError("no communication step: no form holds a query symbol")
    step = pcgs_communicate(system, configuration)
    if step is None:
        raise ValidationError("no communication step: every query asks for a form that holds a "
                              "query symbol itself (the system is blocked)")
    return step


# ---- one validated step
def _is_index(value) -> bool:
    return isinstance(value, numbers.Integral) and not isinstance(value, bool)


def _normalise_positions(positions, n: int) -> tuple[tuple[int, ...], ...]:
    if isinstance(positions, (str, bytes)) or not isinstance(positions, Iterable):
        raise ValidationError(f"positions must give one entry per component, not {positions!r}")
    raw = tuple(positions)
    if len(raw) != n:
        raise ValidationError(f"positions has {len(raw)} entries but the system has {n} "
                              f"components")
    out = []
    for item in raw:
        if isinstance(item, Iterable) and not isinstance(item, (str, bytes)):
            item = tuple(item)
        if item is None:
            out.append(())
        elif _is_index(item):
            out.append((int(item),))
        elif isinstance(item, tuple) and all(map(_is_index, item)):
            out.append(tuple(sorted(map(int, item))))  # numpy's from an array, as Python's
        else:
            raise ValidationError(f"a component's positions are an index, a sequence of "
                                  f"indices or None, not {item!r}")
    return tuple(out)


def apply_tuple(system: _System, configuration: Sequence[Form], sync_tuple,
                positions=None) -> Step:
    """Apply one tuple to ``configuration`` and return the :class:`Step`, checked.

    ``sync_tuple`` lists per component a :class:`Rule`, a rule label, or
    ``"#"``/``None``. For a PSGS it must be a tuple of M, or under ``free``
    an unsynchronised rule alone. ``positions`` (per component an index, a
    sequence of indices, or ``None``) says which occurrences to rewrite; when
    omitted, ``parallel`` mode rewrites every occurrence and ``single`` mode
    the leftmost one. For a PCGS, ``sync_tuple`` gives each non-terminal
    component's rule (``None`` for terminal ones), or is the string
    ``"communicate"`` for the communication step.

    Raises :class:`ValidationError` naming the reason when the step does not
    apply (this is how witnesses are replayed and checked).

    Parameters
    ----------
    system : PSGS or PCGS
        The system.
    configuration : sequence of forms
        One sentential form per component.
    sync_tuple : sequence or "communicate"
        Per component a Rule, a label, or ``"#"``/``None``; for a PCGS the string
        ``"communicate"`` asks for the communication step.
    positions : sequence, optional
        Per component an index, a sequence of indices or None: the occurrences to rewrite.

    Returns
    -------
    Step
        With ``before`` and ``after`` the configurations around it.

    Raises
    ------
    ValidationError
        When the step does not apply, naming the reason.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> start = psgs.initial_configuration(gamma)
    >>> from psgs.derivation import apply_tuple
    >>> step = apply_tuple(gamma, start, ("S1a", "S2a", "S3a", "S4a"))
    >>> [" ".join(map(str, form)) for form in step.after]
    ['N13 S1', 'N18 S2', 'N7 S3', 'N23 S4']
    >>> apply_tuple(gamma, start, ("#", "#", "#", "#"))
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: tuple (#, #, #, #) is not in M
    """
    _require_system(system)
    configuration = _check_configuration(system, configuration)
    if isinstance(system, PCGS) and sync_tuple == "communicate":
        return communication_step(system, configuration)
    entries = resolve_tuple(system.components, sync_tuple)
    shown = show_tuple(entries)
    n = len(system.components)
    if isinstance(system, PSGS):
        if not _is_allowed_tuple(system, entries):
            rules = [r for r in entries if r is not IDLE]
            if len(rules) == 1 and system.unsynchronised == "strict":
                raise ValidationError(f"tuple {shown} is not in M, and unsynchronised rules "
                                      f"may not be applied alone (unsynchronised strict)")
            raise ValidationError(f"tuple {shown} is not in M")
    else:
        if any(has_query(f) for f in configuration):
            raise ValidationError("a form holds a query symbol: only a communication step may "
                                  "follow (communication has priority)")
    given = None if positions is None else _normalise_positions(positions, n)
    chosen = []
    for i, (g, rule, form) in enumerate(zip(system.components, entries, configuration)):
        terminal = is_terminal_form(form)
        if rule is IDLE:
            if isinstance(system, PCGS) and not terminal:
                raise ValidationError(f"component {g.name} is not terminal and must rewrite")
            if given is not None and given[i]:
                raise ValidationError(f"component {g.name} idles but positions "
                                      f"{list(given[i])} were given")
            chosen.append(())
            continue
        if terminal:
            if given is not None and given[i]:
                raise ValidationError(f"component {g.name} is terminal and is not rewritten")
            if isinstance(system, PCGS):
                entries = entries[:i] + (IDLE,) + entries[i + 1:]  # as applicable_steps lists it
            chosen.append(())
            continue
        occ = occurrences(form, rule.lhs)
        if not occ:
            raise ValidationError(f"tuple {shown} does not apply: {rule.lhs} does not occur in "
                                  f"component {g.name}'s form {short(format_form(form, system))}")
        parallel = isinstance(system, PSGS) and system.mode == "parallel"
        if given is None:
            chosen.append(occ if parallel else occ[:1])
            continue
        pos = given[i]
        if parallel:
            if pos != occ:
                raise ValidationError(f"component {g.name}: parallel mode rewrites every "
                                      f"occurrence of {rule.lhs}, at {list(occ)}, not {list(pos)}")
        else:
            if len(pos) != 1 or pos[0] not in occ:
                raise ValidationError(f"component {g.name}: position {list(pos)} is not one "
                                      f"occurrence of {rule.lhs} (they are at {list(occ)})")
        chosen.append(pos)
    chosen_t = tuple(chosen)
    after = rewritten(configuration, entries, chosen_t)
    if after == configuration:
        raise ValidationError(f"tuple {shown} changes nothing, so it does not apply")
    return Step(entries, chosen_t, configuration, after)


# ---------------------------------------------------------------- derivations
@dataclass(frozen=True)
class Derivation:
    """A sequence of steps and the configurations it passes through.

    ``configurations[k]`` is ``steps[k].before`` and ``configurations[k+1]``
    is ``steps[k].after``. ``bound`` is ``None``, or the name of the bound a
    bounded producer (e.g. :func:`random_derivation`) stopped at, e.g.
    ``"max_steps"``; ``reason`` says it in words.
    ``str(d)`` prints the paper's notation ``(S1, S2) ⇒ (N13, N18) ⇒ …``.

    Attributes
    ----------
    system : PSGS or PCGS
        The system derived in.
    steps : tuple of Step
        The steps, in order.
    configurations : tuple of Configuration, default () (computed from the steps)
        The configurations passed through, the axioms first.
    bound : str or None, default None
        The bound a bounded producer stopped at.
    reason : str or None, default None
        The same in words, with the bound's value.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> derivation = psgs.random_derivation(gamma, seed=1)
    >>> len(derivation) == len(derivation.steps), derivation.status
    (True, 'terminal')
    >>> str(derivation).startswith("(S1, S2, S3, S4) ⇒")
    True
    """

    system: _System
    steps: tuple[Step, ...]
    configurations: tuple[Configuration, ...] = ()
    bound: str | None = None
    reason: str | None = None

    def __post_init__(self) -> None:
        _require_system(self.system)
        if not isinstance(self.steps, Iterable):
            raise ValidationError(f"steps must be a sequence of Step values, not {self.steps!r}")
        steps = tuple(self.steps)
        for k, step in enumerate(steps, start=1):
            if not isinstance(step, Step):
                raise ValidationError(f"step {k} is not a Step: {short(repr(step))}")
        object.__setattr__(self, "steps", steps)
        configurations = tuple(self.configurations)
        if not configurations:
            configurations = ((steps[0].before,) if steps
                              else (initial_configuration(self.system),))
            configurations += tuple(s.after for s in steps)
        object.__setattr__(self, "configurations", configurations)
        if len(configurations) != len(steps) + 1:
            raise ValidationError(f"a derivation of {len(steps)} steps passes through "
                                  f"{len(steps) + 1} configurations, not {len(configurations)}")
        for k, step in enumerate(steps):
            if step.before != configurations[k] or step.after != configurations[k + 1]:
                raise ValidationError(f"step {k + 1} does not join configurations {k} and {k + 1}")
        # another system's steps would pass the joins above and read as this system's words
        width = len(self.system.components)
        for k, configuration in enumerate(configurations):
            if len(configuration) != width:
                raise ValidationError(f"configuration {k} has {len(configuration)} forms but "
                                      f"the system has {width} components")

    @property
    def result(self) -> Configuration:
        """The final configuration."""
        return self.configurations[-1]

    @property
    def is_terminal(self) -> bool:
        """True when the final configuration is terminal (PSGS) or the master's form is (PCGS)."""
        return is_terminal_configuration(self.system, self.result)

    @property
    def words(self):
        """The derived terminal tuple (PSGS) or master word (PCGS); ``None`` if not terminal."""
        if not self.is_terminal:
            return None
        if isinstance(self.system, PCGS):
            return self.result[self.system.master_index]
        return self.result

    @property
    def status(self) -> str:
        """``"terminal"``, ``"blocked"`` (no step applies) or ``"open"`` (steps remain)."""
        if self.is_terminal:
            return "terminal"
        # whether one step applies, not the list of them: in single mode their number is a
        # product of occurrence counts (two forms of 2,000 A's, a million steps)
        steps = (pcgs_steps(self.system, self.result) if isinstance(self.system, PCGS)
                 else psgs_successors(self.system, self.result))
        return "blocked" if next(steps, None) is None else "open"

    def __len__(self) -> int:
        return len(self.steps)

    def __str__(self) -> str:
        spaced_ = spaced(self.system)
        return " ⇒ ".join(format_configuration(c, spaced=spaced_) for c in self.configurations)


def random_derivation(system: _System, seed, *, max_steps: int = 10_000,
                      max_form_length: int = 100_000,
                      max_symbols: int = 10_000_000,
                      max_seconds: float | None = None) -> Derivation:
    """A derivation from the axioms taking uniformly random applicable steps (seeded).

    Each step is drawn uniformly among :func:`applicable_steps` (the same
    step a listing would give for the same random stream) without listing
    them: in single mode their number is a product of occurrence counts.

    It stops when the configuration is terminal (``status == "terminal"``),
    when no step applies (``"blocked"``), or at a bound: ``max_steps`` steps,
    a form longer than ``max_form_length`` symbols (parallel rewriting
    can double a form at every step), or configurations holding more than
    ``max_symbols`` symbols together (the derivation keeps every configuration
    it passes, so a form that grows by one symbol a step holds the square of
    the steps: 50 million symbols, 400 MB, at 10,000 steps), or after ``max_seconds``
    (read between steps: a step costs about the forms' length times the tuples of M). The
    bound hit is named in ``Derivation.bound`` (``"max_steps"``, ``"max_form_length"``,
    ``"max_symbols"`` or ``"max_seconds"``) and described in ``Derivation.reason``. The
    same seed always gives the same derivation, and a derivation stopped at a bound is the
    start of the one a larger bound allows.

    Parameters
    ----------
    system : PSGS or PCGS
        The system.
    seed : int, float or str
        Seeds a private ``random.Random``; the same seed gives the same derivation (so not
        ``None``, which would seed from the operating system, nor a NaN).
    max_steps : int, default 10_000
        Stop after this many steps.
    max_form_length : int, default 100_000
        Stop once a form is longer than this.
    max_symbols : int, default 10_000_000
        Stop before the configurations kept (the axioms' and every step's result)
        would hold more symbols than this, summed (a pointer each: ~80 MB).
    max_seconds : float or None, default None
        Stop once this much wall-clock time has passed (None: no limit). The only bound
        whose stopping point depends on the machine.

    Returns
    -------
    Derivation
        Its ``status`` is ``"terminal"``, ``"blocked"`` or ``"open"`` (a bound was hit, named
        by ``bound``).

    Raises
    ------
    ValidationError
        When a bound is not a whole number ≥ 0, ``seed`` is not one of the above, or
        ``system`` is not a grammar system.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> derivation = psgs.random_derivation(gamma, seed=1)
    >>> derivation.status, derivation.is_terminal
    ('terminal', True)
    >>> short = psgs.random_derivation(gamma, seed=1, max_steps=2)
    >>> short.status, len(short.steps), short.bound is not None
    ('open', 2, True)
    """
    _require_system(system)
    check_count(max_steps, "max_steps", minimum=0)
    check_count(max_form_length, "max_form_length", minimum=0)
    check_count(max_symbols, "max_symbols", minimum=1)
    check_seconds(max_seconds, optional=True)
    clock = Budget(max_seconds)
    rng = random.Random(_checked_seed(seed))
    configuration = initial_configuration(system)
    steps: list[Step] = []
    bound = reason = None
    held = sum(len(f) for f in configuration)
    # what a PSGS step may apply is the same every step: built once, not per step
    tuples = None if isinstance(system, PCGS) else moves(system)
    where = None
    while True:
        if tuples is None:
            if is_terminal_configuration(system, configuration):
                break
        else:
            # one scan of the forms a step tells whether they are terminal (a PSGS form holds
            # terminals and nonterminals only) and where the step may rewrite: they grow long
            where = [positions_by_name(form) for form in configuration]
            if not any(where):
                break
        if len(steps) >= max_steps:
            bound, reason = "max_steps", f"stopped after {max_steps} steps (max_steps)"
            break
        if clock.expired():
            bound = "max_seconds"
            reason = f"stopped after {max_seconds:g} seconds, {len(steps)} steps (max_seconds)"
            break
        if max(len(f) for f in configuration) > max_form_length:
            bound = "max_form_length"
            reason = (f"stopped when a form grew beyond {max_form_length} symbols "
                     f"(max_form_length)")
            break
        step = random_step(system, configuration, rng, moves=tuples, where=where)
        if step is None:
            break
        held += sum(len(f) for f in step.after)
        if held > max_symbols:  # the step is drawn, and let go: the memory bound holds
            bound = "max_symbols"
            reason = (f"stopped before the configurations kept would hold more than "
                      f"{max_symbols} symbols (max_symbols)")
            break
        steps.append(step)
        configuration = step.after
    return Derivation(system, tuple(steps), bound=bound, reason=reason)


def _checked_seed(seed):
    """The seed ``random.Random`` gets; a ValidationError for one that would not repeat."""
    # random.Random(None) seeds from the operating system and hashes a NaN by its identity, so
    # either would give another derivation on every call; a numpy integer is taken as its value
    if isinstance(seed, (str, bytes, bytearray)) or (
            isinstance(seed, float) and math.isfinite(seed)):
        return seed
    if not isinstance(seed, (bool, float)) and hasattr(seed, "__index__"):
        return operator.index(seed)
    raise ValidationError(f"seed must be an integer, a finite number or a string, not "
                          f"{short(repr(seed))}")

