"""The derivation engine: configurations, steps and derivations of PSGS and PCGS.

A *configuration* holds one sentential form per component. For a
:class:`~psgs.model.PSGS`, a step applies one synchronisation tuple
(SPEC D1-D3, see ``docs/semantics.md``); for a :class:`~psgs.model.PCGS` a
step is either a communication step (which has priority) or a rewriting
step in which every non-terminal component rewrites once.

Everything here is a pure function of immutable values; randomness comes
only from an explicit seed. Language enumeration lives in
:mod:`psgs.enumeration` and is re-exported here.
"""

from __future__ import annotations

import itertools
import math
import random
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass
from typing import Literal, Union

from .errors import ValidationError
from .model import (IDLE, PCGS, PSGS, Form, Nonterminal, Query, Rule, Terminal,
                    resolve_tuple_entries)

__all__ = [
    "Configuration", "Step", "Derivation", "initial_configuration", "applicable_steps",
    "apply_step", "apply_tuple", "communication_step", "is_terminal_configuration",
    "random_derivation", "language", "Language", "format_form", "format_configuration",
]

#: One sentential form per component.
Configuration = tuple[Form, ...]

_System = Union[PSGS, PCGS]


# ---------------------------------------------------------------- basics
def initial_configuration(system: _System) -> Configuration:
    """The axioms ``(S_1, …, S_n)``, one one-symbol form per component."""
    _require_system(system)
    return tuple((g.start,) for g in system.components)


def _require_system(system: object) -> None:
    if not isinstance(system, (PSGS, PCGS)):
        raise ValidationError(f"expected a PSGS or a PCGS, not {type(system).__name__}")


def _is_terminal_form(form: Form) -> bool:
    return all(s.__class__ is Terminal for s in form)


def is_terminal_configuration(system: _System, configuration: Configuration) -> bool:
    """True when the derivation is finished: every form terminal (PSGS) or the master's (PCGS)."""
    if isinstance(system, PCGS):
        return _is_terminal_form(configuration[system.master_index])
    return all(_is_terminal_form(f) for f in configuration)


def _check_configuration(system: _System, configuration: Sequence[Form]) -> Configuration:
    configuration = tuple(tuple(f) for f in configuration)
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
    """

    tuple: tuple[Rule | None, ...]
    positions: tuple[tuple[int, ...], ...]
    before: Configuration
    after: Configuration
    kind: Literal["rewrite", "communicate"] = "rewrite"

    def __str__(self) -> str:
        return "communicate" if self.kind == "communicate" else _show_tuple(self.tuple)


def applicable_steps(system: _System, configuration: Sequence[Form]) -> tuple[Step, ...]:
    """Every step that applies to ``configuration``, in a deterministic order.

    PSGS (SPEC D3): a tuple ``(p_1, …, p_n)`` applies iff for every component
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
    """
    _require_system(system)
    configuration = _check_configuration(system, configuration)
    if isinstance(system, PCGS):
        return tuple(_pcgs_steps(system, configuration))
    return tuple(_psgs_steps(system, configuration))


# ---- PSGS
def _candidate_tuples(system: PSGS) -> Iterator[tuple[Rule | None, ...]]:
    yield from system.sync
    if system.unsynchronised == "free":
        n = len(system.components)
        for i, rules in enumerate(system.unsynchronised_rules):
            for rule in rules:
                yield tuple(rule if j == i else IDLE for j in range(n))


def _is_allowed_tuple(system: PSGS, entries: tuple[Rule | None, ...]) -> bool:
    """In M, or (under free) an unsynchronised rule alone."""
    if entries in system.sync:
        return True
    if system.unsynchronised != "free":
        return False
    used = [(i, r) for i, r in enumerate(entries) if r is not IDLE]
    return len(used) == 1 and used[0][1] in system.unsynchronised_rules[used[0][0]]


def _occurrences(form: Form, symbol: Nonterminal) -> tuple[int, ...]:
    # compares names rather than calling the dataclass __eq__ per symbol: forms get long
    name = symbol.name
    return tuple([k for k, s in enumerate(form) if s.__class__ is Nonterminal and s.name == name])


def _rewrite(form: Form, positions: Sequence[int], rhs: Form) -> Form:
    """Replace the symbols at ``positions`` (sorted) by ``rhs``."""
    out: list = []
    last = 0
    for k in positions:
        out.extend(form[last:k])
        out.extend(rhs)
        last = k + 1
    out.extend(form[last:])
    return tuple(out)


def _psgs_choices(system: PSGS, configuration: Configuration,
                  sync_tuple: tuple[Rule | None, ...]) -> list[tuple[tuple[int, ...], ...]] | None:
    """Per component the possible position choices, or None when the tuple does not apply."""
    per_component: list[list[tuple[int, ...]]] = []
    for rule, form in zip(sync_tuple, configuration):
        if rule is IDLE or _is_terminal_form(form):
            per_component.append([()])
            continue
        occ = _occurrences(form, rule.lhs)
        if not occ:
            return None
        if system.mode == "parallel":
            per_component.append([occ])
        else:
            per_component.append([(k,) for k in occ])
    return per_component


def _psgs_after(configuration: Configuration, sync_tuple, positions) -> Configuration:
    return tuple(form if not pos else _rewrite(form, pos, rule.rhs)
                 for form, rule, pos in zip(configuration, sync_tuple, positions))


def _psgs_successors(system: PSGS, configuration: Configuration):
    """Yield (tuple, positions, after) for every applicable step."""
    for sync_tuple in _candidate_tuples(system):
        choices = _psgs_choices(system, configuration, sync_tuple)
        if choices is None:
            continue
        for positions in itertools.product(*choices):
            after = _psgs_after(configuration, sync_tuple, positions)
            if after != configuration:
                yield sync_tuple, positions, after


def _psgs_steps(system: PSGS, configuration: Configuration) -> Iterator[Step]:
    for sync_tuple, positions, after in _psgs_successors(system, configuration):
        yield Step(sync_tuple, positions, configuration, after)


# ---- PCGS
def _has_query(form: Form) -> bool:
    return any(isinstance(s, Query) for s in form)


def _pcgs_communicate(system: PCGS, configuration: Configuration) -> Step | None:
    """The communication step, or None when no query can be answered."""
    n = len(configuration)
    after = list(configuration)
    positions: list[tuple[int, ...]] = [()] * n
    sent: set[int] = set()
    for i, form in enumerate(configuration):
        where = tuple(k for k, s in enumerate(form) if isinstance(s, Query))
        if not where:
            continue
        targets = [system.index(form[k].component) for k in where]
        if any(_has_query(configuration[j]) for j in targets):
            continue  # this component waits until every form it asks for is query-free
        out: list = []
        for s in form:
            out.extend(configuration[system.index(s.component)] if isinstance(s, Query) else (s,))
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
    per_component = []
    for g, form in zip(system.components, configuration):
        if _is_terminal_form(form):
            per_component.append([(IDLE, ())])
            continue
        options = [(rule, (k,)) for rule in g.rules for k in _occurrences(form, rule.lhs)]
        if not options:
            return None  # a component that must rewrite but cannot blocks the system
        per_component.append(options)
    return per_component


def _pcgs_steps(system: PCGS, configuration: Configuration) -> Iterator[Step]:
    if any(_has_query(f) for f in configuration):
        step = _pcgs_communicate(system, configuration)
        if step is not None:
            yield step
        return
    choices = _pcgs_rewrite_choices(system, configuration)
    if choices is None:
        return
    for combo in itertools.product(*choices):
        rules = tuple(r for r, _ in combo)
        positions = tuple(p for _, p in combo)
        after = tuple(form if not pos else _rewrite(form, pos, rule.rhs)
                      for form, rule, pos in zip(configuration, rules, positions))
        if after != configuration:
            yield Step(rules, positions, configuration, after)


def communication_step(system: PCGS, configuration: Sequence[Form]) -> Step:
    """The communication step of a PCGS configuration; :class:`ValidationError` if none applies."""
    if not isinstance(system, PCGS):
        raise ValidationError("communication steps exist only in a PCGS")
    configuration = _check_configuration(system, configuration)
    if not any(_has_query(f) for f in configuration):
        raise ValidationError("no communication step: no form holds a query symbol")
    step = _pcgs_communicate(system, configuration)
    if step is None:
        raise ValidationError("no communication step: every query asks for a form that holds a "
                              "query symbol itself (the system is blocked)")
    return step


# ---- one validated step
def _resolve_tuple(system: _System, sync_tuple) -> tuple[Rule | None, ...]:
    if isinstance(sync_tuple, (str, bytes)) or not isinstance(sync_tuple, Iterable):
        raise ValidationError(f"a tuple is a sequence of rules (or labels, or '#'), "
                              f"not {sync_tuple!r}")
    raw = tuple(sync_tuple)
    n = len(system.components)
    if len(raw) != n:
        raise ValidationError(f"the tuple has {len(raw)} entries but the system has {n} "
                              f"components")
    return resolve_tuple_entries(system.components, raw)


def _show_tuple(sync_tuple) -> str:
    return "(" + ", ".join("#" if r is IDLE else r.label for r in sync_tuple) + ")"


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
        elif isinstance(item, int) and not isinstance(item, bool):
            out.append((item,))
        elif isinstance(item, tuple) and all(
                isinstance(k, int) and not isinstance(k, bool) for k in item):
            out.append(tuple(sorted(item)))
        else:
            raise ValidationError(f"a component's positions are an index, a sequence of "
                                  f"indices or None, not {item!r}")
    return tuple(out)


def _short(text: str, limit: int = 60) -> str:
    """Long forms make unreadable messages: keep the start."""
    return text if len(text) <= limit else text[:limit] + f"… ({len(text)} characters)"


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
    """
    _require_system(system)
    configuration = _check_configuration(system, configuration)
    if isinstance(system, PCGS) and sync_tuple == "communicate":
        return communication_step(system, configuration)
    entries = _resolve_tuple(system, sync_tuple)
    shown = _show_tuple(entries)
    n = len(system.components)
    if isinstance(system, PSGS):
        if not _is_allowed_tuple(system, entries):
            rules = [r for r in entries if r is not IDLE]
            if len(rules) == 1 and system.unsynchronised == "strict":
                raise ValidationError(f"tuple {shown} is not in M, and unsynchronised rules "
                                      f"may not be applied alone (unsynchronised strict)")
            raise ValidationError(f"tuple {shown} is not in M")
    else:
        if any(_has_query(f) for f in configuration):
            raise ValidationError("a form holds a query symbol: only a communication step may "
                                  "follow (communication has priority)")
    given = None if positions is None else _normalise_positions(positions, n)
    chosen = []
    for i, (g, rule, form) in enumerate(zip(system.components, entries, configuration)):
        terminal = _is_terminal_form(form)
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
        occ = _occurrences(form, rule.lhs)
        if not occ:
            raise ValidationError(f"tuple {shown} does not apply: {rule.lhs} does not occur in "
                                  f"component {g.name}'s form {_short(format_form(form, system))}")
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
    after = _psgs_after(configuration, entries, chosen_t)
    if after == configuration:
        raise ValidationError(f"tuple {shown} changes nothing, so it does not apply")
    return Step(entries, chosen_t, configuration, after)


#: The name the public API table uses for :func:`apply_tuple`.
apply_step = apply_tuple


# ---------------------------------------------------------------- printing
def _spaced(system) -> bool:
    return any(len(t.name) > 1 for t in system.terminals)


def format_form(form: Form, system=None, *, spaced: bool | None = None) -> str:
    """A sentential form in the paper's notation: ``N12d``, ``N4N4``; ``ε`` when empty.

    Symbols are concatenated, as in the paper, unless some terminal of
    ``system`` has a name longer than one character (then they are
    separated by spaces).
    """
    if spaced is None:
        spaced = _spaced(system) if system is not None else any(
            isinstance(s, Terminal) and len(s.name) > 1 for s in form)
    if not form:
        return "ε"
    return (" " if spaced else "").join(str(s) for s in form)


def format_configuration(configuration: Configuration, system=None, *,
                         spaced: bool | None = None) -> str:
    """``(x_1, …, x_n)`` with each form in the paper's notation."""
    if spaced is None and system is not None:
        spaced = _spaced(system)
    return "(" + ", ".join(format_form(f, system, spaced=spaced) for f in configuration) + ")"


# ---------------------------------------------------------------- derivations
@dataclass(frozen=True)
class Derivation:
    """A sequence of steps and the configurations it passes through.

    ``configurations[k]`` is ``steps[k].before`` and ``configurations[k+1]``
    is ``steps[k].after``. ``bound`` is ``None``, or a sentence naming the
    bound a bounded producer (e.g. :func:`random_derivation`) stopped at.
    ``str(d)`` prints the paper's notation ``(S1, S2) ⇒ (N13, N18) ⇒ …``.
    """

    system: _System
    steps: tuple[Step, ...]
    configurations: tuple[Configuration, ...] = ()
    bound: str | None = None

    def __post_init__(self) -> None:
        steps = tuple(self.steps)
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
        if not applicable_steps(self.system, self.result):
            return "blocked"
        return "open"

    def __len__(self) -> int:
        return len(self.steps)

    def __str__(self) -> str:
        spaced = _spaced(self.system)
        return " ⇒ ".join(format_configuration(c, spaced=spaced) for c in self.configurations)


def random_derivation(system: _System, seed, *, max_steps: int = 10_000,
                      max_form_length: int = 100_000) -> Derivation:
    """A derivation from the axioms taking uniformly random applicable steps (seeded).

    Each step is drawn uniformly among :func:`applicable_steps` (the same
    step a listing would give for the same random stream) without listing
    them: in single mode their number is a product of occurrence counts.

    It stops when the configuration is terminal (``status == "terminal"``),
    when no step applies (``"blocked"``), or at a bound: ``max_steps`` steps,
    or a form longer than ``max_form_length`` symbols (parallel rewriting
    can double a form at every step). The bound hit is named in
    ``Derivation.bound``. The same seed always gives the same derivation.
    """
    _require_system(system)
    if max_steps < 0:
        raise ValidationError("max_steps must be at least 0")
    rng = random.Random(seed)
    configuration = initial_configuration(system)
    steps: list[Step] = []
    bound = None
    while not is_terminal_configuration(system, configuration):
        if len(steps) >= max_steps:
            bound = f"stopped after {max_steps} steps (max_steps)"
            break
        if max(len(f) for f in configuration) > max_form_length:
            bound = (f"stopped when a form grew beyond {max_form_length} symbols "
                     f"(max_form_length)")
            break
        step = _random_step(system, configuration, rng)
        if step is None:
            break
        steps.append(step)
        configuration = step.after
    return Derivation(system, tuple(steps), bound=bound)


def _random_step(system: _System, configuration: Configuration, rng: random.Random):
    """A uniformly random applicable step, or None; never lists all of them.

    In single mode the steps of one tuple are every choice of occurrences, a
    product that grows like the forms' lengths to the power n; counting them
    is cheap. The index drawn is the position the step would have in
    :func:`applicable_steps`, so a seed picks the same step either way.
    """
    if isinstance(system, PCGS):
        return _random_pcgs_step(system, configuration, rng)
    candidates = []
    total = 0
    for sync_tuple in _candidate_tuples(system):
        choices = _psgs_choices(system, configuration, sync_tuple)
        if choices is None:
            continue
        first = tuple(c[0] for c in choices)
        # whether a tuple changes something does not depend on the occurrences chosen
        if _psgs_after(configuration, sync_tuple, first) == configuration:
            continue
        count = math.prod(len(c) for c in choices)
        candidates.append((sync_tuple, choices, count))
        total += count
    if not total:
        return None
    index = rng.randrange(total)
    for sync_tuple, choices, count in candidates:
        if index < count:
            break
        index -= count
    positions = _unrank(choices, index)
    return Step(sync_tuple, positions, configuration,
                _psgs_after(configuration, sync_tuple, positions))


def _unrank(choices, index: int) -> tuple:
    """The ``index``-th element of ``itertools.product(*choices)``."""
    picked = []
    for options in reversed(choices):
        index, r = divmod(index, len(options))
        picked.append(options[r])
    return tuple(reversed(picked))


def _random_pcgs_step(system: PCGS, configuration: Configuration, rng: random.Random):
    if any(_has_query(f) for f in configuration):
        step = _pcgs_communicate(system, configuration)
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
    rules = tuple(r for r, _ in combo)
    positions = tuple(p for _, p in combo)
    after = tuple(form if not pos else _rewrite(form, pos, rule.rhs)
                  for form, rule, pos in zip(configuration, rules, positions))
    return Step(rules, positions, configuration, after)


def language(system, max_length: int, **options):
    """Enumerate L(system) up to a size bound; see :func:`psgs.enumeration.language`."""
    from .enumeration import language as _language
    return _language(system, max_length, **options)


def __getattr__(name: str):
    if name == "Language":
        from .enumeration import Language
        return Language
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
