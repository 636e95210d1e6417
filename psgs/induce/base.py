"""The inducer contract, and the ending every built-in inducer shares.

An inducer follows scikit-learn's estimator contract: every parameter is a
keyword argument of ``__init__``, stored as an attribute of the same name;
:meth:`Inducer.get_params`, :meth:`Inducer.set_params` and
:meth:`Inducer.clone` read, change and copy them (changes are validated again,
by the same ``__init__``); the one learning method is ``induce``. An inducer
declares its parameters once, in a frozen table (:class:`~psgs.induce.conf.Conf`,
the class attribute ``Conf``): ``__init__`` is then made from the table (it
stores the values as given and builds the table's value, which validates
them), and :meth:`Inducer.conf` gives the frozen value ``induce`` hands to its
phases. It takes one
:class:`~psgs.actiongram.Actiongram` or a sequence of them, each one
performance of the same action (:func:`as_performances` checks and normalises
that), and returns an :class:`~psgs.induce.results.Induction`.

The ending is the same for every inducer -- identifiers for the components
(:func:`component_name`), the grammar system (:func:`build_system`), the
:class:`Induction` -- and lives once, in :meth:`Inducer.build_induction`.
"""

from __future__ import annotations

import copy
import dataclasses
import inspect
import re
from collections.abc import Iterable, Mapping, Sequence
from typing import ClassVar

from ..actiongram import Actiongram
from ..errors import ValidationError
from ..model import PSGS, Grammar, Nonterminal, Rule, Terminal
from .conf import Conf
from .results import Induction, StringReport

__all__ = ["Inducer", "as_performances", "build_system", "component_name"]


class Inducer:
    """Base class of inducers: keyword parameters in ``__init__``, one method :meth:`induce`.

    A subclass defines ``name`` (what :func:`psgs.induce.get` knows it by), its
    parameters, and ``induce``; it inherits the rest. The parameters are best
    declared as a table, ``Conf = MyConf`` (a frozen :class:`~psgs.induce.conf.Conf`
    dataclass): the base class then makes ``__init__`` from it. A subclass may
    instead write an ``__init__`` with keyword-only parameters that validates
    them (raising :class:`~psgs.errors.ValidationError`) and stores each as an
    attribute of the same name.

    Examples
    --------
    >>> from psgs.induce import Sequential
    >>> learner = Sequential(min_count=3)
    >>> learner.get_params()
    {'min_count': 3, 'max_rules': 100000}
    >>> learner.set_params(max_rules=10).max_rules
    10
    >>> learner.clone(min_count=4)
    Sequential(min_count=4, max_rules=10)
    """

    name = ""
    #: The parameter table (a frozen :class:`~psgs.induce.conf.Conf` subclass), or None for an
    #: inducer that writes its own ``__init__``.
    Conf: ClassVar[type[Conf] | None] = None

    def __init_subclass__(cls, **kwargs) -> None:
        super().__init_subclass__(**kwargs)
        table = cls.__dict__.get("Conf")
        if table is not None and "__init__" not in cls.__dict__:
            cls.__init__ = _init_from(table)

    @classmethod
    def _param_names(cls) -> tuple[str, ...]:
        """The parameter names, read from ``__init__``'s signature."""
        names = []
        for p in inspect.signature(cls.__init__).parameters.values():
            if p.name == "self":
                continue
            if p.kind in (p.VAR_POSITIONAL, p.VAR_KEYWORD):
                raise TypeError(f"{cls.__name__}.__init__ takes *{p.name}: an inducer's "
                                f"parameters must be named one by one")
            names.append(p.name)
        return tuple(names)

    def __setstate__(self, state: dict) -> None:
        """Restore a pickled inducer; a parameter added since it was pickled takes its
        default (what the inducer did before the parameter existed).

        Examples
        --------
        >>> from psgs.induce import Sequential
        >>> learner = Sequential.__new__(Sequential)
        >>> learner.__setstate__({"min_count": 3})  # pickled before max_rules existed
        >>> learner.get_params()
        {'min_count': 3, 'max_rules': 100000}
        """
        self.__dict__.update(state)
        for p in inspect.signature(type(self).__init__).parameters.values():
            if p.name != "self" and p.name not in state and p.default is not p.empty:
                setattr(self, p.name, p.default)

    def get_params(self) -> dict[str, object]:
        """The parameters this inducer was built with, by name, in ``__init__``'s order.

        Returns
        -------
        dict
            Parameter name -> value.

        Raises
        ------
        TypeError
            When a subclass did not store a parameter under its own name (a
            programming error in that subclass).

        Examples
        --------
        >>> from psgs.induce import PAL
        >>> PAL(min_copies=4).get_params()["min_copies"]
        4
        """
        out = {}
        for p in self._param_names():
            try:
                out[p] = getattr(self, p)
            except AttributeError:
                raise TypeError(f"{type(self).__name__} does not store its parameter {p!r} as "
                                f"an attribute of that name") from None
        return out

    def conf(self) -> Conf:
        """The parameters as the frozen value of the inducer's table, validated.

        Returns
        -------
        Conf
            What ``induce`` hands to its phases.

        Raises
        ------
        TypeError
            When the inducer declares no table (it wrote its own ``__init__``).

        Examples
        --------
        >>> from psgs.induce import Sequential
        >>> Sequential(min_count=3).conf().min_count
        3
        """
        if self.Conf is None:
            raise TypeError(f"{type(self).__name__} declares no parameter table (Conf)")
        return self.Conf(**self.get_params())

    def recorded_params(self) -> dict[str, object]:
        """The parameters an :class:`Induction` records: all but those the table declares
        ``recorded=False`` (they change how the inducer computes, never what it finds).

        Examples
        --------
        >>> from psgs.induce import PAL
        >>> "engine" in PAL().get_params(), "engine" in PAL().recorded_params()
        (True, False)
        """
        params = self.get_params()
        if self.Conf is None:
            return params
        kept = set(self.Conf.recorded_names())
        return {k: v for k, v in params.items() if k in kept}

    def set_params(self, **params) -> "Inducer":
        """Change parameters in place, validated as at construction; returns ``self``.

        Either every change is made or none: the new parameters are validated
        by building a new inducer with them first.

        Parameters
        ----------
        **params
            Parameter name -> new value.

        Returns
        -------
        Inducer
            ``self``, so calls can be chained.

        Raises
        ------
        ValidationError
            For a name that is not a parameter, or a value ``__init__`` refuses.

        Examples
        --------
        >>> from psgs.induce import Sequential
        >>> learner = Sequential()
        >>> learner.set_params(min_count=1)
        Traceback (most recent call last):
        ...
        psgs.errors.ValidationError: parameter min_count must be >= 2, not 1
        >>> learner.min_count
        2
        """
        unknown = [k for k in params if k not in self._param_names()]
        if unknown:
            raise ValidationError(unknown_parameter(self.name or type(self).__name__,
                                                    unknown[0], self._param_names()))
        checked = type(self)(**{**self.get_params(), **params})
        for key in params:
            setattr(self, key, getattr(checked, key))
        return self

    def clone(self, **params) -> "Inducer":
        """A new, independent inducer with the same parameters, changed by ``params``.

        Parameters
        ----------
        **params
            Parameters to change in the copy (validated as at construction).

        Returns
        -------
        Inducer
            A new inducer of the same class, its parameters deep copies of
            ``self``'s: changing it never changes ``self``.

        Raises
        ------
        ValidationError
            For a name that is not a parameter, or a value ``__init__`` refuses.

        Examples
        --------
        >>> from psgs.induce import PAL
        >>> a = PAL()
        >>> b = a.clone(min_copies=5)
        >>> a.min_copies, b.min_copies
        (3, 5)
        """
        unknown = [k for k in params if k not in self._param_names()]
        if unknown:
            raise ValidationError(unknown_parameter(self.name or type(self).__name__,
                                                    unknown[0], self._param_names()))
        return type(self)(**copy.deepcopy({**self.get_params(), **params}))

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self.get_params().items())
        return f"{type(self).__name__}({args})"

    def induce(self, performances):  # pragma: no cover - interface
        """Learn a grammar system from one actiongram or a sequence of performances.

        Parameters
        ----------
        performances : Actiongram or sequence of Actiongram
            One actiongram, or several, each one performance of the same action
            with the same actuators (they are never joined into one stream).

        Returns
        -------
        Induction

        Raises
        ------
        TypeError
            When ``performances`` is not an actiongram or a sequence of them.
        ValidationError
            For an empty sequence, or performances whose actuators differ.

        Examples
        --------
        >>> from psgs.induce import Sequential
        >>> takes = [Actiongram.from_strings({"arm": s}) for s in ("abab", "ab")]
        >>> Sequential().induce(takes).performances
        2
        """
        raise NotImplementedError

    def build_induction(self, actuators: Sequence[str], patterns: Mapping[str, tuple[str, ...]],
                        occurrences: Mapping[str, Sequence[tuple[float, float]]],
                        reports: Sequence[StringReport], *, synchronise: bool,
                        performances: int = 1,
                        occurrence_performance: Mapping[str, Sequence[int]] | None = None,
                        ) -> Induction:
        """The ending every inducer shares: component names, the system, the :class:`Induction`.

        Parameters
        ----------
        actuators : sequence of str
            Every actuator name, in actiongram order; the components are those
            with a pattern, in this order.
        patterns : mapping of str to tuple of str
            Actuator name -> its pattern, for the components only.
        occurrences : mapping of str to sequence of (float, float)
            Actuator name -> the (start, end) time of each copy of its pattern.
        reports : sequence of StringReport
            One per actuator.
        synchronise : bool
            Whether the components repeat their patterns in step (PAL) or
            independently (the sequential baseline); see :func:`build_system`.
        performances : int, optional
            How many performances were learnt from (default 1).
        occurrence_performance : mapping of str to sequence of int, optional
            Actuator name -> the performance of each occurrence (default: all 0).

        Returns
        -------
        Induction
            With the system named after the inducer, and its recorded parameters.

        Examples
        --------
        >>> from psgs.induce import Sequential
        >>> result = Sequential().build_induction(
        ...     ["l-knee", "hip"], {"l-knee": ("a", "b")}, {"l-knee": [(0.0, 2.0)]},
        ...     [StringReport("l-knee", "component"), StringReport("hip", "no repetition")],
        ...     synchronise=False)
        >>> result.components, result.component_names["l-knee"], result.system.name
        (('l-knee',), 'l_knee', 'sequential')
        """
        kept = tuple(n for n in actuators if n in patterns)
        taken: set[str] = set()
        comp_names = {n: component_name(n, taken) for n in kept}
        system = (build_system([(comp_names[n], patterns[n]) for n in kept],
                               synchronise=synchronise, name=self.name) if kept else None)
        occurrence_performance = occurrence_performance or {}
        return Induction(system=system, components=kept,
                         patterns={n: patterns[n] for n in kept},
                         occurrences={n: occurrences[n] for n in kept}, reports=tuple(reports),
                         component_names=comp_names, inducer=self.name,
                         params=self.recorded_params(),
                         performances=performances,
                         occurrence_performance={n: occurrence_performance[n] for n in kept
                                                 if n in occurrence_performance})


def _init_from(table: type[Conf]):
    """The ``__init__`` of an inducer whose parameters are ``table``'s fields.

    It takes the fields as keyword-only arguments with their defaults, stores
    each value as given (``get_params`` and ``clone`` give back what was
    passed) and builds the table's value, which validates them.
    """
    fields = dataclasses.fields(table)
    known = {f.name for f in fields}

    def __init__(self, **params) -> None:
        for key in params:
            if key not in known:
                raise TypeError(f"{type(self).__name__}.__init__() got an unexpected keyword "
                                f"argument {key!r}")
        values = {f.name: params.get(f.name, f.default) for f in fields}
        made = table(**values)
        for key in values:  # as given, a numpy number as the Python number the table holds
            setattr(self, key, getattr(made, key))

    __init__.__signature__ = inspect.Signature(
        [inspect.Parameter("self", inspect.Parameter.POSITIONAL_ONLY)] +
        [inspect.Parameter(f.name, inspect.Parameter.KEYWORD_ONLY, default=f.default,
                           annotation=f.type) for f in fields],
        return_annotation=None)
    __init__.__doc__ = f"Store the parameters of {table.__name__}, validated by it."
    return __init__


def as_performances(data: Actiongram | Iterable[Actiongram], inducer: str = "induce"
                    ) -> tuple[Actiongram, ...]:
    """``induce``'s input as a tuple of performances, checked; one actiongram gives a 1-tuple.

    Every performance must have the same actuators as the first; one whose
    strings come in another order is reordered to the first's order (so string
    ``i`` is the same actuator in every performance). Performances are never
    joined into one stream.

    Parameters
    ----------
    data : Actiongram or iterable of Actiongram
        One actiongram, or several performances of the same action.
    inducer : str, optional
        The name the errors give for the caller (e.g. ``"PAL.induce"``).

    Returns
    -------
    tuple of Actiongram

    Raises
    ------
    TypeError
        When ``data`` is neither an actiongram nor an iterable of them (a
        string or a mapping is refused: it is not a sequence of performances).
    ValidationError
        When the sequence is empty, or a performance's actuators differ from
        the first performance's.

    Examples
    --------
    >>> a = Actiongram.from_strings({"knee": "abab", "hip": "xy"})
    >>> b = Actiongram.from_strings({"hip": "yx", "knee": "baba"})
    >>> [p.names for p in as_performances([a, b])]
    [('knee', 'hip'), ('knee', 'hip')]
    >>> len(as_performances(a))
    1
    >>> as_performances([])
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: induce needs at least one performance, got an empty sequence
    """
    if isinstance(data, Actiongram):
        return (data,)
    if isinstance(data, (str, bytes, Mapping)) or not isinstance(data, Iterable):
        raise TypeError(f"{inducer} needs an Actiongram or a sequence of them, not "
                        f"{type(data).__name__}")
    items = tuple(data)
    if not items:
        raise ValidationError(f"{inducer} needs at least one performance, got an empty sequence")
    for k, item in enumerate(items):
        if not isinstance(item, Actiongram):
            raise TypeError(f"{inducer}: performance {k} is a {type(item).__name__}, not an "
                            f"Actiongram")
    first = items[0]
    out = [first]
    for k, item in enumerate(items[1:], start=1):
        if item.names != first.names:
            missing = [n for n in first.names if n not in item.names]
            extra = [n for n in item.names if n not in first.names]
            if missing or extra:
                parts = ([f"lacks {', '.join(map(repr, missing))}"] if missing else []) + \
                        ([f"has {', '.join(map(repr, extra))} too"] if extra else [])
                raise ValidationError(f"{inducer}: performance {k} does not have the actuators "
                                      f"of performance 0: it {' and '.join(parts)}")
            item = item.subset(first.names)
        out.append(item)
    return tuple(out)


def unknown_parameter(inducer: str, name: str, known: Sequence[str]) -> str:
    """The message for a parameter an inducer does not have (one wording everywhere).

    Examples
    --------
    >>> unknown_parameter("pal", "colour", ("alpha", "rounds"))
    "inducer pal has no parameter 'colour' (its parameters: alpha, rounds)"
    """
    return f"inducer {inducer} has no parameter {name!r} (its parameters: {', '.join(known)})"


_NOT_IDENT = re.compile(r"[^A-Za-z0-9_]")


def component_name(actuator: str, taken: set[str]) -> str:
    """An identifier for ``actuator``: itself when it is one, else a cleaned, unique form.

    Parameters
    ----------
    actuator : str
        The actuator (string) name.
    taken : set of str
        Names already used; the result is added to it.

    Returns
    -------
    str
        Letters, digits and ``_`` only, not starting with a digit, not in ``taken``.

    Examples
    --------
    >>> taken = set()
    >>> [component_name(a, taken) for a in ("l-knee", "l_knee", "0hip")]
    ['l_knee', 'l_knee_2', 'c_0hip']
    """
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

    Each pattern becomes a left-branching chain of binary rules
    N_c_1 -> p1 p2, N_c_2 -> N_c_1 p3, ..., the last one being the pattern's
    root N_c; the axiom has S_c -> N_c S_c | N_c. When ``synchronise``, the two
    axiom rules form one tuple each over all components (every component
    repeats its pattern the same number of times), and the chain rules are
    paired level by level from the root down (a shorter chain idles, ``#``).
    Without it the system has no tuples and components repeat independently.

    Parameters
    ----------
    patterns : sequence of (str, tuple of str)
        (component name, pattern) pairs; names must be identifiers.
    synchronise : bool, optional
        Whether the components repeat in step (default True).
    name : str, optional
        The system's name.

    Returns
    -------
    PSGS
        In ``parallel`` mode.

    Raises
    ------
    ValidationError
        For no pattern at all, an empty pattern, an entry that is no (name, pattern) pair
        (or names the model refuses).

    Examples
    --------
    >>> import psgs
    >>> system = build_system([("arm", ("a", "b")), ("leg", ("x",))])
    >>> bool(psgs.accepts(system, ["abab", "xx"])), bool(psgs.accepts(system, ["abab", "x"]))
    (True, False)
    """
    patterns = _checked_patterns(patterns)
    terminal_names = {s for _, p in patterns for s in p}
    prefix = "N"
    while any(t.startswith(prefix + "_") or t.startswith("S" + prefix + "_")
              for t in terminal_names):
        prefix += "N"
    grammars, chains, axiom_rules = [], [], []
    for comp, pattern in patterns:
        if not pattern:
            raise ValidationError(f"component {comp}: empty pattern")
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


def _checked_patterns(patterns) -> tuple[tuple[str, tuple], ...]:
    """build_system's pairs as a tuple; a ValidationError for what is none (a TypeError, or
    max() of no chain, deep in the building otherwise)."""
    if isinstance(patterns, (str, bytes)) or not isinstance(patterns, Iterable):
        raise ValidationError(f"patterns must be a sequence of (component, pattern) pairs, "
                              f"not {patterns!r}")
    pairs = tuple(patterns)
    if not pairs:
        raise ValidationError("build_system needs at least one (component, pattern) pair")
    for pair in pairs:
        if isinstance(pair, (str, bytes)) or not isinstance(pair, Sequence) or len(pair) != 2 \
                or not isinstance(pair[1], Iterable):
            raise ValidationError(f"each entry of patterns is a (component, pattern) pair, "
                                  f"not {pair!r}")
    return tuple((name, tuple(pattern)) for name, pattern in pairs)
