"""What every inducer returns: an :class:`Induction`, with a :class:`StringReport` per string.

Both are values (frozen, their mappings read-only views, picklable), like the
grammar system an induction holds; nothing here learns anything. What only
the real-motion learner fills in (per-joint reports, morphemes) has its types
beside that learner (:mod:`psgs.induce.pal.motion.results`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import TYPE_CHECKING

from ..errors import ValidationError
from ..model import PSGS

if TYPE_CHECKING:
    from .pal.motion.results import ActuatorReport, Morpheme

__all__ = ["Induction", "StringReport", "NO_REPETITION"]

#: The verdict of an Induction in which nothing repeats in step.
NO_REPETITION = "no synchronised repetition"


@dataclass(frozen=True)
class StringReport:
    """What an inducer found in one string, whether or not it became a component.

    Parameters
    ----------
    name : str
        The string's (actuator's) name.
    status : str
        ``"component"``, or a short reason the string was dropped (``"no
        repetition"``, ``"not significant"``, ``"not synchronised"``, ...) or kept
        with a caveat (``"rule bound reached"``).
    motif : tuple of str, optional
        The repeated block found in the string alone.
    copies : int, optional
        How many times ``motif`` was located.
    significance : float, optional
        log10 of the chance that a random string of the same length and symbol
        frequencies holds a motif this well repeated (more negative is stronger
        evidence; 0 when no motif was found).
    synchronised_with : tuple of str, optional
        The strings whose copies cover the same time.

    Examples
    --------
    >>> StringReport("knee", "no repetition").copies
    0
    """

    name: str
    status: str
    motif: tuple[str, ...] = ()
    copies: int = 0
    significance: float = 0.0
    synchronised_with: tuple[str, ...] = ()


@dataclass(frozen=True)
class Induction:
    """The result of ``inducer.induce(performances)``.

    Parameters
    ----------
    system : PSGS or None
        A PSGS in ``parallel`` mode with one component per entry of
        ``components``; None when no string became a component.
    components : tuple of str
        The actuator names kept, in actiongram order.
    patterns : mapping of str to tuple of str
        Actuator name -> its motion pattern (terminal symbol names).
    occurrences : mapping of str to tuple of (float, float)
        Actuator name -> the (start, end) time of each located copy of its
        pattern, in the time of the performance it was found in.
    reports : tuple of StringReport, optional
        One report per string of the actiongram, in its order.
    component_names : mapping of str to str, optional
        Actuator name -> component name in ``system`` (actuator names made into
        identifiers when they are not: ``l-knee`` -> ``l_knee``).
    inducer : str, optional
        The name of the inducer that made it.
    params : mapping, optional
        The inducer's parameters.
    performances : int, optional
        How many performances (actiongrams of the same action) it was learnt
        from; 1 by default.
    occurrence_performance : mapping of str to tuple of int, optional
        Actuator name -> the index (from 0) of the performance each entry of
        ``occurrences[name]`` lies in; filled with 0 for every actuator not
        given (always right for one performance).
    actuators : tuple of str, optional
        The joints that take part (in actiongram order); empty when the
        inducer does not group strings by joint.
    actuator_channels : mapping of str to tuple of str, optional
        Per joint of ``actuators``, the channels (strings) that carry the pattern.
    morphemes : mapping of str to Morpheme, optional
        Per component channel, its pattern with typical durations and displacements.
    verdict : str, optional
        A plain sentence when nothing was learnt, such as ``"no synchronised
        repetition"``; empty otherwise.
    actuator_reports : tuple of ActuatorReport, optional
        One per joint, with the stage that dropped it.
    agreements : mapping of str to tuple of float, optional
        Actuator name -> for each entry of ``occurrences[name]``, the share of
        the pattern's positions that copy agrees with (1.0 for an exact copy);
        empty when the inducer does not measure it.
    bound : str or None, optional
        The bound the inducer stopped at (``"max_seconds"``, ``"max_rules"``), None when
        it ran to the end; what it holds is then what was found by that point.
    reason : str or None, optional
        The same in words, with the bound's value.

    Raises
    ------
    ValidationError
        When ``performances`` is not a positive integer, or an
        ``occurrence_performance`` entry does not have one index per occurrence
        or names a performance outside ``range(performances)``.

    Notes
    -----
    The mappings are read-only views and patterns and occurrences hold tuples:
    an induction is a value, like the system it holds.

    Examples
    --------
    >>> result = Induction(None, ("knee",), {"knee": ["a", "b"]}, {"knee": [(0, 2), (2, 4)]})
    >>> result.patterns["knee"], result.occurrence_performance["knee"]
    (('a', 'b'), (0, 0))
    >>> result
    <Induction unnamed inducer: 1 component(s) (knee)>
    >>> print(result)
    <Induction unnamed inducer: 1 component(s) (knee)>
      knee: a b  (2 copies)
    """

    system: PSGS | None
    components: tuple[str, ...]
    patterns: Mapping[str, tuple[str, ...]]
    occurrences: Mapping[str, tuple[tuple[float, float], ...]]
    reports: tuple[StringReport, ...] = ()
    component_names: Mapping[str, str] = field(default_factory=dict)
    inducer: str = ""
    params: Mapping[str, object] = field(default_factory=dict)
    performances: int = 1
    occurrence_performance: Mapping[str, tuple[int, ...]] = field(default_factory=dict)
    actuators: tuple[str, ...] = ()
    actuator_channels: Mapping[str, tuple[str, ...]] = field(default_factory=dict)
    morphemes: Mapping[str, Morpheme] = field(default_factory=dict)
    verdict: str = ""
    actuator_reports: tuple[ActuatorReport, ...] = ()
    agreements: Mapping[str, tuple[float, ...]] = field(default_factory=dict)
    bound: str | None = None
    reason: str | None = None

    def __post_init__(self) -> None:
        for name in ("bound", "reason"):
            if not isinstance(getattr(self, name), (str, type(None))):
                raise ValidationError(f"{name} must be a str or None, not "
                                      f"{getattr(self, name)!r}")
        if isinstance(self.performances, bool) or not isinstance(self.performances, int) \
                or self.performances < 1:
            raise ValidationError(f"performances must be a positive integer, not "
                                  f"{self.performances!r}")
        occurrences = {k: tuple(tuple(span) for span in v) for k, v in self.occurrences.items()}
        given = {k: tuple(v) for k, v in self.occurrence_performance.items()}
        where = {}
        for name, spans in occurrences.items():
            indices = given.pop(name, (0,) * len(spans))
            if len(indices) != len(spans):
                raise ValidationError(f"occurrence_performance[{name!r}] has {len(indices)} "
                                      f"entries for {len(spans)} occurrences")
            if any(not 0 <= k < self.performances for k in indices):
                raise ValidationError(f"occurrence_performance[{name!r}] names a performance "
                                      f"outside 0..{self.performances - 1}")
            where[name] = indices
        if given:
            raise ValidationError(f"occurrence_performance names {next(iter(given))!r}, "
                                  f"which has no occurrences")
        agreements = {k: tuple(float(a) for a in v) for k, v in self.agreements.items()}
        for name, shares in agreements.items():
            if len(shares) != len(occurrences.get(name, ())):
                raise ValidationError(f"agreements[{name!r}] has {len(shares)} entries for "
                                      f"{len(occurrences.get(name, ()))} occurrences")
        frozen = {
            "components": tuple(self.components),
            "patterns": MappingProxyType({k: tuple(v) for k, v in self.patterns.items()}),
            "occurrences": MappingProxyType(occurrences),
            "reports": tuple(self.reports),
            "component_names": MappingProxyType(dict(self.component_names)),
            "params": MappingProxyType(dict(self.params)),
            "occurrence_performance": MappingProxyType(where),
            "actuators": tuple(self.actuators),
            "actuator_channels": MappingProxyType({k: tuple(v) for k, v in
                                                   self.actuator_channels.items()}),
            "morphemes": MappingProxyType(dict(self.morphemes)),
            "actuator_reports": tuple(self.actuator_reports),
            "agreements": MappingProxyType(agreements),
        }
        for key, value in frozen.items():
            object.__setattr__(self, key, value)

    def __reduce__(self):
        # read-only views do not pickle; rebuild from plain dicts (e.g. across processes)
        return (type(self), (self.system, self.components, dict(self.patterns),
                             dict(self.occurrences), self.reports, dict(self.component_names),
                             self.inducer, dict(self.params), self.performances,
                             dict(self.occurrence_performance), self.actuators,
                             dict(self.actuator_channels), dict(self.morphemes), self.verdict,
                             self.actuator_reports, dict(self.agreements), self.bound,
                             self.reason))

    def __repr__(self) -> str:
        # a summary, not the dataclass dump of every pattern and occurrence
        found = ", ".join(self.components[:6]) + (", ..." if len(self.components) > 6 else "")
        joints = f", joints {', '.join(self.actuators)}" if self.actuators else ""
        takes = f" from {self.performances} performances" if self.performances > 1 else ""
        verdict = f" ({self.verdict})" if self.verdict else ""
        stopped = f", stopped at {self.bound}" if self.bound else ""
        return (f"<Induction {self.inducer or 'unnamed inducer'}{takes}: "
                f"{len(self.components)} component(s) ({found or 'none'}){joints}{verdict}"
                f"{stopped}>")

    def __str__(self) -> str:
        # one line per component: its pattern (cut at 12 symbols) and how many copies
        lines = [repr(self)]
        for name in self.components:
            pattern = self.patterns.get(name, ())
            shown = " ".join(pattern[:12]) + (f" ... ({len(pattern)} symbols)"
                                              if len(pattern) > 12 else "")
            lines.append(f"  {name}: {shown}  ({len(self.occurrences.get(name, ()))} copies)")
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        """Verdict, actuators, patterns and the system's picture (notebooks)."""
        from ..draw import induction_html

        return induction_html(self)

    def report(self, name: str) -> StringReport:
        """The report of the string named ``name``.

        Parameters
        ----------
        name : str
            A string (actuator) name of the actiongram.

        Returns
        -------
        StringReport

        Raises
        ------
        KeyError
            When no report has that name.

        Examples
        --------
        >>> Induction(None, (), {}, {}, (StringReport("hip", "no repetition"),)).report("hip")
        StringReport(name='hip', status='no repetition', motif=(), copies=0, significance=0.0, \
synchronised_with=())
        """
        for r in self.reports:
            if r.name == name:
                return r
        raise KeyError(f"no string named {name!r}")

    def to_dict(self) -> dict:
        """A JSON-ready summary (the system as text needs ``psgs.dumps``).

        Returns
        -------
        dict
            Plain lists, numbers and strings only; ``occurrence_performance`` is
            included only when there was more than one performance,
            ``agreements`` only when the inducer measured them, and ``bound`` and
            ``reason`` only when it stopped at a bound.

        Examples
        --------
        >>> Induction(None, ("k",), {"k": ("a", "b")}, {"k": ((0.0, 2.0),)}).to_dict()["patterns"]
        {'k': ['a', 'b']}
        """
        out = {
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
        if self.actuators or self.actuator_reports or self.verdict:
            out["actuators"] = list(self.actuators)
            out["actuator_channels"] = {k: list(v) for k, v in self.actuator_channels.items()}
            out["morphemes"] = {k: {"kinetemes": list(m.kinetemes),
                                    "durations": [round(d, 4) for d in m.durations],
                                    "displacements": None if m.displacements is None else
                                    [round(d, 3) for d in m.displacements]}
                                for k, m in self.morphemes.items()}
            out["verdict"] = self.verdict
            out["actuator_reports"] = [{"name": r.name, "status": r.status,
                                        "share": round(r.share, 4),
                                        "significance": round(r.significance, 3)}
                                       for r in self.actuator_reports]
        if self.agreements:
            out["agreements"] = {k: [round(a, 4) for a in v] for k, v in self.agreements.items()}
        if self.bound is not None:
            out["bound"] = self.bound
            out["reason"] = self.reason
        if self.performances > 1:
            out["performances"] = self.performances
            out["occurrence_performance"] = {k: list(v)
                                             for k, v in self.occurrence_performance.items()}
        return out
