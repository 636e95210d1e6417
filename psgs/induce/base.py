"""What every inducer returns, and the pieces inducers share.

An inducer is an object configured by keyword arguments at construction
(:meth:`Inducer.get_params` gives them back) with one method,
``induce(actiongram) -> Induction``.
"""

from __future__ import annotations

import inspect
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType

from ..model import PSGS, Grammar, Nonterminal, Rule, Terminal

__all__ = ["Induction", "StringReport", "Inducer", "build_system", "component_name"]


@dataclass(frozen=True)
class StringReport:
    """What an inducer found in one string, whether or not it became a component.

    ``status`` is ``"component"`` or a short reason it was dropped
    (``"no repetition"``, ``"not significant"``, ``"not synchronised"``).
    ``significance`` is log10 of the chance that a random string of the same
    length and symbol frequencies holds a motif this well repeated (more
    negative is stronger evidence; 0 when no motif was found). ``motif`` is
    the repeated block found in the string alone, ``copies`` how many times it
    was located, ``synchronised_with`` the strings whose copies cover the same
    time.
    """

    name: str
    status: str
    motif: tuple[str, ...] = ()
    copies: int = 0
    significance: float = 0.0
    synchronised_with: tuple[str, ...] = ()


@dataclass(frozen=True)
class Induction:
    """The result of ``inducer.induce(actiongram)``.

    ``system``: a PSGS in ``parallel`` mode with one component per entry of
    ``components`` (component names are the actuator names, made into
    identifiers when they are not; ``component_names`` maps them).
    ``components``: actuator names kept, in actiongram order.
    ``patterns``: actuator name -> the motion pattern (terminal symbol names).
    ``occurrences``: actuator name -> the (start, end) time of each located
    copy of its pattern. ``reports``: one :class:`StringReport` per string of
    the actiongram, in its order. ``params``: the inducer's parameters.
    The mappings are read-only views (patterns and occurrences hold tuples):
    an induction is a value, like the system it holds.
    """

    system: PSGS | None
    components: tuple[str, ...]
    patterns: Mapping[str, tuple[str, ...]]
    occurrences: Mapping[str, tuple[tuple[float, float], ...]]
    reports: tuple[StringReport, ...] = ()
    component_names: Mapping[str, str] = field(default_factory=dict)
    inducer: str = ""
    params: Mapping[str, object] = field(default_factory=dict)

    def __post_init__(self) -> None:
        frozen = {
            "components": tuple(self.components),
            "patterns": MappingProxyType({k: tuple(v) for k, v in self.patterns.items()}),
            "occurrences": MappingProxyType({k: tuple(tuple(span) for span in v)
                                             for k, v in self.occurrences.items()}),
            "reports": tuple(self.reports),
            "component_names": MappingProxyType(dict(self.component_names)),
            "params": MappingProxyType(dict(self.params)),
        }
        for key, value in frozen.items():
            object.__setattr__(self, key, value)

    def __reduce__(self):
        # read-only views do not pickle; rebuild from plain dicts (e.g. across processes)
        return (type(self), (self.system, self.components, dict(self.patterns),
                             dict(self.occurrences), self.reports, dict(self.component_names),
                             self.inducer, dict(self.params)))

    def report(self, name: str) -> StringReport:
        """The report of the string named ``name``."""
        for r in self.reports:
            if r.name == name:
                return r
        raise KeyError(f"no string named {name!r}")

    def to_dict(self) -> dict:
        """A JSON-ready summary (the system as text needs ``psgs.dumps``)."""
        return {
            "inducer": self.inducer,
            "params": dict(self.params),
            "components": list(self.components),
            "patterns": {k: list(v) for k, v in self.patterns.items()},
            "occurrences": {k: [list(p) for p in v] for k, v in self.occurrences.items()},
            "reports": [{"name": r.name, "status": r.status, "motif": list(r.motif),
                         "copies": r.copies, "significance": round(r.significance, 3),
                         "synchronised_with": list(r.synchronised_with)}
                        for r in self.reports],
        }


class Inducer:
    """Base class: keyword parameters in ``__init__``, one method :meth:`induce`."""

    name = ""

    def get_params(self) -> dict[str, object]:
        """The parameters this inducer was built with, by name."""
        sig = inspect.signature(type(self).__init__)
        return {p: getattr(self, p) for p in sig.parameters if p != "self"}

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.get_params().items())
        return f"{type(self).__name__}({args})"

    def induce(self, actiongram):  # pragma: no cover - interface
        """Learn from an :class:`~psgs.actiongram.Actiongram`; returns an :class:`Induction`."""
        raise NotImplementedError


def check_number(name: str, value: object, *, low: float | None = None, high: float | None = None,
                 integer: bool = False, low_open: bool = False) -> None:
    """Validate one inducer parameter; ValueError naming it otherwise."""
    ok_type = (int,) if integer else (int, float)
    if isinstance(value, bool) or not isinstance(value, ok_type):
        kind = "an integer" if integer else "a number"
        raise ValueError(f"parameter {name} must be {kind}, not {value!r}")
    if not math.isfinite(value):  # NaN passes every comparison below
        raise ValueError(f"parameter {name} must be a finite number, not {value!r}")
    if low is not None and (value <= low if low_open else value < low):
        raise ValueError(f"parameter {name} must be {'>' if low_open else '>='} {low}, "
                         f"not {value!r}")
    if high is not None and value > high:
        raise ValueError(f"parameter {name} must be <= {high}, not {value!r}")


_NOT_IDENT = re.compile(r"[^A-Za-z0-9_]")


def component_name(actuator: str, taken: set[str]) -> str:
    """An identifier for ``actuator``: itself when it is one, else a cleaned, unique form."""
    name = _NOT_IDENT.sub("_", actuator)
    if not name or name[0].isdigit():
        name = "c_" + name
    base, k = name, 2
    while name in taken:
        name = f"{base}_{k}"
        k += 1
    taken.add(name)
    return name


def build_system(patterns: Sequence[tuple[str, tuple[str, ...]]], *, synchronise: bool = True,
                 name: str = "induced") -> PSGS:
    """The PSGS whose language is {(P_1^k, ..., P_n^k) : k >= 1} (synchronised) or products.

    ``patterns`` is a sequence of (component name, pattern). Each pattern
    becomes a left-branching chain of binary rules N_c_1 -> p1 p2,
    N_c_2 -> N_c_1 p3, ..., the last one being the pattern's root N_c; the
    axiom has S_c -> N_c S_c | N_c. When ``synchronise``, the two axiom rules
    form one tuple each over all components (every component repeats its
    pattern the same number of times), and the chain rules are paired level
    by level from the root down (a shorter chain idles, ``#``). Without it
    the system has no tuples and components repeat independently.
    """
    terminal_names = {s for _, p in patterns for s in p}
    prefix = "N"
    while any(t.startswith(prefix + "_") or t.startswith("S" + prefix + "_")
              for t in terminal_names):
        prefix += "N"
    grammars, chains, axiom_rules = [], [], []
    for comp, pattern in patterns:
        if not pattern:
            raise ValueError(f"component {comp}: empty pattern")
        start = Nonterminal(f"S{prefix}_{comp}")
        rules: list[Rule] = []
        if len(pattern) == 1:
            root = Nonterminal(f"{prefix}_{comp}")
            rules.append(Rule(f"r_{comp}_1", root, (Terminal(pattern[0]),)))
        else:
            left: Nonterminal | Terminal = Terminal(pattern[0])
            for j, sym in enumerate(pattern[1:], start=1):
                lhs = Nonterminal(f"{prefix}_{comp}_{j}")
                rules.append(Rule(f"r_{comp}_{j}", lhs, (left, Terminal(sym))))
                left = lhs
            root = left
        repeat = Rule(f"s_{comp}_more", start, (root, start))
        stop = Rule(f"s_{comp}_last", start, (root,))
        grammars.append(Grammar(comp, start, (repeat, stop, *rules)))
        chains.append(list(reversed(rules)))
        axiom_rules.append((repeat, stop))
    sync: list[tuple] = []
    if synchronise:
        sync.append(tuple(r for r, _ in axiom_rules))
        sync.append(tuple(s for _, s in axiom_rules))
        depth = max(len(c) for c in chains)
        for level in range(depth):
            sync.append(tuple(c[level] if level < len(c) else None for c in chains))
    return PSGS(tuple(grammars), tuple(sync), mode="parallel", name=name)
