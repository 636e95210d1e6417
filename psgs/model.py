"""The formal objects: symbols, rules, component grammars, PSGS and PCGS.

Everything here is an immutable value, validated when it is built: a value
that exists is well formed. ``dataclasses.replace(system, mode="single")``
builds (and validates) the other reading of a system.

Symbols are typed -- :class:`Terminal`, :class:`Nonterminal`, :class:`Query` --
so a name never changes kind on its way through the library; the same name
used as two kinds within one system is an error.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from types import MappingProxyType
from typing import Literal, Union

from .errors import ValidationError
from .names import _as_tuple, _terminal_problem, _require_identifier, is_identifier

__all__ = [
    "Terminal", "Nonterminal", "Query", "Symbol", "Word", "Form", "Rule", "Grammar",
    "SyncTuple", "resolve_tuple", "PSGS", "PCGS", "System", "IDLE", "as_word", "is_identifier",
]

#: What ``#`` (this component idles) is in a synchronisation tuple.
IDLE = None


@dataclass(frozen=True, slots=True, order=True)
class Terminal:
    """A terminal symbol: non-empty text without white space, control or format characters.

    Parameters
    ----------
    name : str
        Non-empty; no white space, control character (C0, DEL, C1), invisible format
        character (U+200B, U+FEFF, ...) or lone surrogate (``"a"``, ``"up"``, ``"döwn"``).

    Examples
    --------
    >>> a = Terminal("a")
    >>> str(a), a < Terminal("b")
    ('a', True)
    """

    name: str

    def __post_init__(self) -> None:
        if (problem := _terminal_problem(self.name)) is not None:  # names the character
            raise ValidationError(problem)

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True, slots=True, order=True)
class Nonterminal:
    """A nonterminal symbol; its name is an identifier.

    Parameters
    ----------
    name : str
        An identifier: letters, digits and ``_``, not starting with a digit.

    Examples
    --------
    >>> str(Nonterminal("S1")), str(Query("G2"))
    ('S1', '?G2')
    """

    name: str

    def __post_init__(self) -> None:
        _require_identifier(self.name, "nonterminal")

    def __str__(self) -> str:
        return self.name


@dataclass(frozen=True, slots=True, order=True)
class Query:
    """A query symbol of a PCGS: asks for the sentential form of component ``component``.

    Parameters
    ----------
    component : str
        The name of the queried component (an identifier).

    Examples
    --------
    >>> Query("G2").component
    'G2'
    """

    component: str

    def __post_init__(self) -> None:
        _require_identifier(self.component, "queried component")

    def __str__(self) -> str:
        return f"?{self.component}"


Symbol = Union[Terminal, Nonterminal, Query]
#: A word: a tuple of terminals.
Word = tuple[Terminal, ...]
#: A sentential form: a tuple of any symbols.
Form = tuple[Symbol, ...]


def as_word(value: str | Iterable[str | Terminal]) -> Word:
    """Make a word: a ``str`` is read as a sequence of one-character terminals.

    A sequence of names or of :class:`Terminal` gives one terminal per item.

    Parameters
    ----------
    value : str or iterable of str or Terminal
        A ``str`` is one terminal per character; otherwise one terminal per item.

    Returns
    -------
    tuple of Terminal

    Raises
    ------
    ValidationError
        When an item is neither a ``str`` nor a :class:`Terminal`, or is not a valid terminal.

    Examples
    --------
    >>> as_word("ab") == (Terminal("a"), Terminal("b"))
    True
    >>> as_word(["up", "down"]) == (Terminal("up"), Terminal("down"))
    True

    >>> as_word(["up", Terminal("down")])
    (Terminal(name='up'), Terminal(name='down'))
    >>> as_word([1])
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: a word holds terminals, not 1
    """
    if isinstance(value, str):
        return tuple(Terminal(ch) for ch in value)
    out = []
    for item in _as_tuple(value, "a word"):
        if isinstance(item, Terminal):
            out.append(item)
        elif isinstance(item, str):
            out.append(Terminal(item))
        else:
            raise ValidationError(f"a word holds terminals, not {item!r}")
    return tuple(out)


@dataclass(frozen=True, slots=True)
class Rule:
    """A context-free rule ``label: lhs -> rhs``; an empty ``rhs`` is ε.

    Parameters
    ----------
    label : str
        The rule's name (an identifier), unique within its grammar.
    lhs : Nonterminal
        The left-hand side.
    rhs : sequence of Terminal, Nonterminal or Query, default ()
        The right-hand side (stored as a tuple); empty for ε.

    Examples
    --------
    >>> S = Nonterminal("S")
    >>> print(Rule("p", S, [Terminal("a"), S]), "|", Rule("q", S))
    S → a S | S → ε
    """

    label: str
    lhs: Nonterminal
    rhs: Form = ()

    def __post_init__(self) -> None:
        _require_identifier(self.label, "rule label")
        if not isinstance(self.lhs, Nonterminal):
            raise ValidationError(
                f"rule {self.label}: left-hand side must be a nonterminal, not {self.lhs!r}")
        rhs = _as_tuple(self.rhs, f"rule {self.label}: the right-hand side")
        for sym in rhs:
            if not isinstance(sym, (Terminal, Nonterminal, Query)):
                raise ValidationError(f"rule {self.label}: {sym!r} is not a symbol")
        object.__setattr__(self, "rhs", rhs)

    def __str__(self) -> str:
        body = " ".join(_show_symbol(s) for s in self.rhs) if self.rhs else "ε"
        return f"{self.lhs} → {body}"


def _show_symbol(sym: Symbol) -> str:
    return str(sym)


@dataclass(frozen=True)
class Grammar:
    """A component grammar: a name, an axiom and context-free rules (labels unique).

    Parameters
    ----------
    name : str
        The component's name (an identifier).
    start : Nonterminal
        The axiom; it must have a rule.
    rules : tuple of Rule
        Distinct labels and distinct rules; a name is used as one kind of symbol only.

    Examples
    --------
    >>> S = Nonterminal("S")
    >>> g = Grammar("G", S, (Rule("p", S, (Terminal("a"), S)), Rule("q", S, ())))
    >>> g.rule("p").rhs, sorted(t.name for t in g.terminals)
    ((Terminal(name='a'), Nonterminal(name='S')), ['a'])
    """

    name: str
    start: Nonterminal
    rules: tuple[Rule, ...]

    def __post_init__(self) -> None:
        _require_identifier(self.name, "component name")
        if not isinstance(self.start, Nonterminal):
            raise ValidationError(f"component {self.name}: start symbol must be a nonterminal, "
                                  f"not {self.start!r}")
        rules = _as_tuple(self.rules, f"component {self.name}: rules")
        object.__setattr__(self, "rules", rules)
        seen_labels: dict[str, Rule] = {}
        seen_bodies: dict[tuple, Rule] = {}
        for rule in rules:
            if not isinstance(rule, Rule):
                raise ValidationError(f"component {self.name}: {rule!r} is not a Rule")
            if rule.label in seen_labels:
                raise ValidationError(f"component {self.name}: two rules are labelled {rule.label}")
            key = (rule.lhs, rule.rhs)
            if key in seen_bodies:
                raise ValidationError(f"component {self.name}: rules {seen_bodies[key].label} and "
                                      f"{rule.label} are the same rule {rule}")
            seen_labels[rule.label] = rule
            seen_bodies[key] = rule
        if not any(r.lhs == self.start for r in rules):
            raise ValidationError(f"component {self.name}: start symbol {self.start} has no rule")
        _check_kinds(self.name, rules, (self.start,))

    # the tables are cached as plain dicts (they pickle) and handed out read-only, so a
    # caller cannot change what a frozen grammar answers
    @cached_property
    def _label_table(self) -> dict[str, Rule]:
        return {r.label: r for r in self.rules}

    @cached_property
    def _lhs_table(self) -> dict[Nonterminal, tuple[Rule, ...]]:
        table: dict[Nonterminal, list[Rule]] = {}
        for r in self.rules:
            table.setdefault(r.lhs, []).append(r)
        return {k: tuple(v) for k, v in table.items()}

    @property
    def rule_by_label(self) -> Mapping[str, Rule]:
        """Read-only mapping from each rule label to its rule."""
        return MappingProxyType(self._label_table)

    @property
    def rules_by_lhs(self) -> Mapping[Nonterminal, tuple[Rule, ...]]:
        """Read-only mapping from each left-hand side to its rules, in file order."""
        return MappingProxyType(self._lhs_table)

    @cached_property
    def nonterminals(self) -> frozenset[Nonterminal]:
        """Every nonterminal of the grammar: its axiom, left sides and right sides."""
        out = {self.start}
        for r in self.rules:
            out.add(r.lhs)
            out.update(s for s in r.rhs if isinstance(s, Nonterminal))
        return frozenset(out)

    @cached_property
    def terminals(self) -> frozenset[Terminal]:
        """Every terminal on a right-hand side."""
        return frozenset(s for r in self.rules for s in r.rhs if isinstance(s, Terminal))

    @cached_property
    def queries(self) -> frozenset[Query]:
        """Every query symbol on a right-hand side (PCGS components only)."""
        return frozenset(s for r in self.rules for s in r.rhs if isinstance(s, Query))

    def rule(self, label: str) -> Rule:
        """The rule labelled ``label``; :class:`ValidationError` when there is none."""
        try:
            return self.rule_by_label[label]
        except KeyError:
            raise ValidationError(f"component {self.name} has no rule labelled {label}") from None


def _check_kinds(where: str, rules: Iterable[Rule], extra: Iterable[Symbol] = ()) -> None:
    """A name may stand for one kind of symbol only."""
    kinds: dict[str, str] = {}

    def note(sym: Symbol) -> None:
        if isinstance(sym, Query):
            return
        kind = "terminal" if isinstance(sym, Terminal) else "nonterminal"
        prior = kinds.setdefault(sym.name, kind)
        if prior != kind:
            raise ValidationError(f"{where}: symbol {sym.name!r} is used both as a terminal "
                                  f"and as a nonterminal")

    for sym in extra:
        note(sym)
    for r in rules:
        note(r.lhs)
        for s in r.rhs:
            note(s)


#: A synchronisation tuple: one rule (or :data:`IDLE`, written ``#``) per component.
SyncTuple = tuple[Union[Rule, None], ...]


def resolve_tuple(components: Sequence[Grammar], raw: object, name: str = "the tuple") -> SyncTuple:
    """Read one tuple (rule labels, :class:`Rule` values, ``"#"`` or ``None``) as rules.

    The one place that checks a tuple: that it is a sequence, that it has one
    entry per component, and that each entry is ``#`` or a rule of its
    component. ``name`` names the tuple in error messages, e.g. ``"tuple 3"``.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> [entry and entry.label for entry in resolve_tuple(gamma.components, ("S1a", "#", None, "#"))]
    ['S1a', None, None, None]
    >>> resolve_tuple(gamma.components, ("S1a", "#"), "tuple 3")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: tuple 3 has 2 entries but the system has 4 components
    """
    if isinstance(raw, (str, bytes)) or not isinstance(raw, Iterable):
        raise ValidationError(f"{name} must be a sequence of rules (or labels, or '#'), "
                              f"not {raw!r}")
    raw = tuple(raw)
    if len(raw) != len(components):
        raise ValidationError(f"{name} has {len(raw)} entries but the system has "
                              f"{len(components)} components")
    where = f"{name}: "
    entries: list[Rule | None] = []
    for g, item in zip(components, raw):
        if item is None or item == "#":
            entries.append(IDLE)
        elif isinstance(item, str):
            if item not in g.rule_by_label:
                raise ValidationError(f"{where}component {g.name} has no rule labelled {item}")
            entries.append(g.rule_by_label[item])
        elif isinstance(item, Rule):
            if g.rule_by_label.get(item.label) != item:
                raise ValidationError(f"{where}rule {item.label}: {item} is not a rule of "
                                      f"component {g.name}")
            entries.append(item)
        else:
            raise ValidationError(f"{where}{item!r} is neither a rule nor #")
    return tuple(entries)


def _check_components(kind: str, components: Sequence[Grammar]) -> tuple[Grammar, ...]:
    components = _as_tuple(components, f"a {kind}'s components")
    if not components:
        raise ValidationError(f"a {kind} needs at least one component")
    names = set()
    for g in components:
        if not isinstance(g, Grammar):
            raise ValidationError(f"a {kind}'s components are Grammar values, not {g!r}")
        if g.name in names:
            raise ValidationError(f"two components are named {g.name}")
        names.add(g.name)
    _check_kinds(f"this {kind}", [r for g in components for r in g.rules],
                 [g.start for g in components])
    return components


class _Components:
    """What a PSGS and a PCGS both answer about their components (a mixin, no fields)."""

    components: tuple[Grammar, ...]

    @property
    def axioms(self) -> tuple[Nonterminal, ...]:
        """The start symbols, in component order."""
        return tuple(g.start for g in self.components)

    @property
    def component_names(self) -> tuple[str, ...]:
        """The component names, in component order."""
        return tuple(g.name for g in self.components)

    @cached_property
    def nonterminals(self) -> frozenset[Nonterminal]:
        """Every nonterminal of every component."""
        return frozenset().union(*(g.nonterminals for g in self.components))

    @cached_property
    def terminals(self) -> frozenset[Terminal]:
        """Every terminal of every component."""
        return frozenset().union(*(g.terminals for g in self.components))

    def index(self, component: str | int) -> int:
        """The position of a component given by name or position."""
        return _component_index(self.components, component)

    def _summary(self) -> str:
        names = ", ".join(self.component_names[:6]) + (", ..." * (len(self.components) > 6))
        return (f"{self.name!r}: {len(self.components)} component(s) ({names}), "
                f"{sum(len(g.rules) for g in self.components)} rules")

    def __str__(self) -> str:  # the summary, then each component's rules on one line
        rules = ("; ".join(f"{r.label}: {r}" for r in g.rules) for g in self.components)
        lines = [f"  {g.name}: {r}" for g, r in zip(self.components, rules)]
        return "\n".join([repr(self)] + lines)


@dataclass(frozen=True)
class PSGS(_Components):
    """A Parallel Synchronous Grammar System Γ = (N, T, G_1..G_n, M).

    ``sync`` is M: each tuple holds, per component, a :class:`Rule` of that
    component or :data:`IDLE` (``#``). Tuples may be given with rule labels
    (``"p1"``) and ``"#"``; they are stored as rules and ``None``.

    ``mode`` is ``"parallel"`` (a rule rewrites every occurrence of its
    left-hand side at once, as in the paper's derivation) or ``"single"`` (one
    occurrence, the paper's formal definition). ``unsynchronised`` is
    ``"free"`` (a rule in no tuple may be applied on its own) or ``"strict"``.
    See ``docs/semantics.md``.

    Parameters
    ----------
    components : sequence of Grammar
        At least one; distinct names.
    sync : sequence of tuples, default ()
        M: one entry per component, a :class:`Rule` of it, its label, or ``"#"``/``None``.
    mode : {"parallel", "single"}
        How many occurrences of a left-hand side a rule rewrites.
    unsynchronised : {"free", "strict"}
        Whether a rule in no tuple may be applied on its own.
    name : str, default "system"
        The system's name (an identifier).

    Examples
    --------
    >>> S, T = Nonterminal("S"), Nonterminal("T")
    >>> g = Grammar("G", S, (Rule("p", S, (Terminal("a"), S)), Rule("q", S, ())))
    >>> h = Grammar("H", T, (Rule("u", T, (Terminal("b"), T)), Rule("v", T, ())))
    >>> pair = PSGS((g, h), sync=[("p", "u"), ("q", "v")], unsynchronised="strict", name="Pair")
    >>> pair.component_names, [[r.label for r in t] for t in pair.sync]
    (('G', 'H'), [['p', 'u'], ['q', 'v']])
    >>> print(pair)  # repr() is the first line
    <PSGS 'Pair': 2 component(s) (G, H), 4 rules, 2 tuples in M, parallel>
      G: p: S → a S; q: S → ε
      H: u: T → b T; v: T → ε
    """

    components: tuple[Grammar, ...]
    sync: tuple[SyncTuple, ...] = ()
    mode: Literal["parallel", "single"] = "parallel"
    unsynchronised: Literal["free", "strict"] = "free"
    name: str = "system"

    def __repr__(self) -> str:  # a summary, not the dataclass dump of every rule
        return f"<PSGS {self._summary()}, {len(self.sync)} tuples in M, {self.mode}>"

    def __post_init__(self) -> None:
        _require_identifier(self.name, "system name")
        components = _check_components("PSGS", self.components)
        object.__setattr__(self, "components", components)
        if self.mode not in ("parallel", "single"):
            raise ValidationError(f"mode must be 'parallel' or 'single', not {self.mode!r}")
        if self.unsynchronised not in ("free", "strict"):
            raise ValidationError(
                f"unsynchronised must be 'free' or 'strict', not {self.unsynchronised!r}")
        for g in components:
            if g.queries:
                raise ValidationError(f"component {g.name}: a PSGS has no query symbols "
                                      f"(found {min(g.queries, key=str)})")
        tuples = []
        seen = set()
        for t_index, raw in enumerate(_as_tuple(self.sync, "sync"), start=1):
            entries = resolve_tuple(components, raw, f"tuple {t_index}")
            if all(e is None for e in entries):
                raise ValidationError(f"tuple {t_index} idles in every component")
            key = tuple(entries)
            if key in seen:
                raise ValidationError(f"tuple {t_index} repeats an earlier tuple")
            seen.add(key)
            tuples.append(key)
        object.__setattr__(self, "sync", tuple(tuples))

    @cached_property
    def synchronised_rules(self) -> tuple[frozenset[Rule], ...]:
        """Per component, the rules that appear in some tuple of M."""
        return tuple(frozenset(t[i] for t in self.sync if t[i] is not None)
                     for i in range(len(self.components)))

    @cached_property
    def unsynchronised_rules(self) -> tuple[tuple[Rule, ...], ...]:
        """Per component, the rules in no tuple (applied alone under ``free``)."""
        return tuple(tuple(r for r in g.rules if r not in synced)
                     for g, synced in zip(self.components, self.synchronised_rules))


def _component_index(components: tuple[Grammar, ...], component: str | int) -> int:
    if isinstance(component, int) and not isinstance(component, bool):
        if 0 <= component < len(components):
            return component
        raise ValidationError(f"there is no component {component}")
    for i, g in enumerate(components):
        if g.name == component:
            return i
    raise ValidationError(f"there is no component named {component!r}")


@dataclass(frozen=True)
class PCGS(_Components):
    """A Parallel Communicating Grammar System (Păun and Sântean).

    Components may hold :class:`Query` symbols ``?name``. In a communication
    step (which has priority) every query is replaced by the queried form;
    when ``returning`` the queried component then restarts from its axiom. The
    language is the set of terminal words of the ``master`` component (the
    first one unless named). ``centralised`` is derived: only the master holds
    query symbols.

    Parameters
    ----------
    components : sequence of Grammar
        At least one; distinct names; queries name components of the system.
    returning : bool, default True
        Whether a queried component restarts from its axiom.
    master : str, default "" (the first component)
        The component whose terminal words make the language.
    name : str, default "system"
        The system's name (an identifier).

    Examples
    --------
    >>> S1, S2 = Nonterminal("S1"), Nonterminal("S2")
    >>> master = Grammar("G1", S1, (Rule("ask", S1, (Terminal("a"), Query("G2"))),))
    >>> helper = Grammar("G2", S2, (Rule("b", S2, (Terminal("b"),)),))
    >>> system = PCGS((master, helper), returning=False)
    >>> system.master, system.centralised
    ('G1', True)
    >>> system
    <PCGS 'system': 2 component(s) (G1, G2), 2 rules, master G1, non-returning>
    """

    components: tuple[Grammar, ...]
    returning: bool = True
    master: str = field(default="")
    name: str = "system"

    def __repr__(self) -> str:  # a summary, not the dataclass dump
        back = "returning" if self.returning else "non-returning"
        return f"<PCGS {self._summary()}, master {self.master}, {back}>"

    def __post_init__(self) -> None:
        _require_identifier(self.name, "system name")
        components = _check_components("PCGS", self.components)
        object.__setattr__(self, "components", components)
        if not isinstance(self.returning, bool):
            raise ValidationError(f"returning must be True or False, not {self.returning!r}")
        names = [g.name for g in components]
        if self.master is None or self.master == "":  # not 0 or [], taken for "" before
            object.__setattr__(self, "master", names[0])
        elif self.master not in names:
            raise ValidationError(f"the master {self.master!r} is not a component")
        known = set(names)  # a query's component looked up, not searched for in a list
        for g, q in ((g, q) for g in components for q in g.queries):
            if q.component not in known:
                raise ValidationError(f"component {g.name}: query ?{q.component} names no "
                                      f"component")

    @property
    def master_index(self) -> int:
        """The position of the master among the components."""
        return self.component_names.index(self.master)

    @property
    def centralised(self) -> bool:
        """True when no component but the master holds a query symbol."""
        return all(not g.queries for g in self.components if g.name != self.master)


System = Union[PSGS, PCGS]
