"""Inducer parameters as a declarative table: one frozen value, every rule declared once.

An inducer's parameters are the fields of a frozen dataclass, a :class:`Conf`:
each field declares its default and the rule its values obey
(:func:`parameter`, with a :class:`Number` or :class:`Choice` rule or any
function ``rule(name, value)``). Building the value validates it, field by
field in declaration order; nothing else in an inducer checks a parameter.
The inducer hands the frozen value to its phases (the way a parser hands its
lexer and parser configurations to its stages), so a phase reads
``conf.min_copies`` and never needs the inducer class.

>>> from dataclasses import dataclass
>>> @dataclass(frozen=True)
... class Toy(Conf):
...     depth: int = parameter(2, Number(low=1, integer=True))
...     how: str = parameter("fast", Choice(("fast", "exact")))
>>> Toy(depth=3).depth
3
>>> Toy(how="slow")
Traceback (most recent call last):
...
psgs.errors.ValidationError: how must be one of fast, exact, not 'slow'
"""

from __future__ import annotations

import dataclasses
import math
import numbers
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TypeVar

from .._foundation.text import finite
from ..errors import ValidationError

__all__ = ["Conf", "Number", "Choice", "Parameter", "parameter", "check_number", "check_choice",
           "union", "plain_number"]

C = TypeVar("C", bound="Conf")


def check_number(name: str, value: object, *, low: float | None = None, high: float | None = None,
                 integer: bool = False, low_open: bool = False, optional: bool = False) -> None:
    """Validate one numeric inducer parameter.

    Parameters
    ----------
    name : str
        The parameter's name, for the message.
    value : object
        Its value.
    low, high : float, optional
        Bounds (``high`` inclusive; ``low`` inclusive unless ``low_open``).
    integer : bool, optional
        Whether only an ``int`` will do (``bool`` never does).
    low_open : bool, optional
        Whether ``low`` itself is refused.
    optional : bool, optional
        Whether ``None`` (no value: no bound) is allowed too.

    Raises
    ------
    ValidationError
        Naming the parameter, what it must be, and the value given.

    Examples
    --------
    >>> check_number("alpha", 0.5, low=0, high=1)
    >>> check_number("alpha", float("nan"))
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: parameter alpha must be a finite number, not nan
    >>> check_number("max_seconds", None, low=0, low_open=True, optional=True)
    """
    if optional and value is None:
        return
    ok_type = (int,) if integer else (int, float)
    if isinstance(value, bool) or not isinstance(value, ok_type):
        kind = "an integer" if integer else "a number"
        raise ValidationError(f"parameter {name} must be {kind}{' or None' if optional else ''}"
                              f", not {value!r}")
    if not finite(value):  # NaN passes every comparison below; 10**400 is no float
        if isinstance(value, int):
            given = f"a whole number of {len(str(abs(value)))} digits (past a float's range)"
        elif math.isinf(value):  # also what a number past a float's range, 1e400, reads as
            given = f"{value!r} (a number past a float's range reads as inf)"
        else:
            given = repr(value)
        raise ValidationError(f"parameter {name} must be a finite number, not {given}")
    if low is not None and (value <= low if low_open else value < low):
        raise ValidationError(f"parameter {name} must be {'>' if low_open else '>='} {low}, "
                              f"not {value!r}")
    if high is not None and value > high:
        raise ValidationError(f"parameter {name} must be <= {high}, not {value!r}")


def plain_number(value: object) -> object:
    """A numpy scalar as the Python number it holds (``np.float32(0.5)`` -> ``0.5``); any
    other value as it is, for :func:`check_number` to judge.

    Examples
    --------
    >>> import numpy as np
    >>> plain_number(np.float32(0.5)), plain_number(np.int64(3)), plain_number("x")
    (0.5, 3, 'x')
    >>> type(plain_number(np.float64(0.5)))
    <class 'float'>
    """
    if type(value) in (bool, int, float) or not isinstance(value, numbers.Real):
        return value  # np.float64 is a float, but not a plain one: its repr says np.float64
    return int(value) if isinstance(value, numbers.Integral) else float(value)


def check_choice(name: str, value: object, choices: Sequence[str]) -> None:
    """Validate a parameter that takes one of a few words.

    Parameters
    ----------
    name : str
        The parameter's name, for the message.
    value : object
        Its value.
    choices : sequence of str
        The allowed values.

    Raises
    ------
    ValidationError
        When ``value`` is not one of ``choices``.

    Examples
    --------
    >>> check_choice("timing", "tempo", ("content", "period"))
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: timing must be one of content, period, not 'tempo'
    """
    if not isinstance(value, str) or value not in choices:
        raise ValidationError(f"{name} must be one of {', '.join(choices)}, not {value!r}")


@dataclass(frozen=True)
class Number:
    """The rule of a numeric parameter (see :func:`check_number` for its arguments).

    Examples
    --------
    >>> Number(low=2, integer=True)("min_copies", 1)
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: parameter min_copies must be >= 2, not 1
    """

    low: float | None = None
    high: float | None = None
    integer: bool = False
    low_open: bool = False
    optional: bool = False

    def __call__(self, name: str, value: object) -> None:
        check_number(name, value, low=self.low, high=self.high, integer=self.integer,
                     low_open=self.low_open, optional=self.optional)


@dataclass(frozen=True)
class Choice:
    """The rule of a parameter that takes one of a few words.

    Examples
    --------
    >>> Choice(("kinetemes", "path"))("evidence", "path")
    """

    choices: tuple[str, ...]

    def __call__(self, name: str, value: object) -> None:
        check_choice(name, value, self.choices)


@dataclass(frozen=True)
class Parameter:
    """One row of a parameter table, declared once and usable in several :class:`Conf` classes.

    Parameters
    ----------
    default : object
        The value when none is given.
    rule : callable
        ``rule(name, value)`` raises :class:`~psgs.errors.ValidationError` for a bad value.
    recorded : bool, optional
        Whether an :class:`~psgs.induce.Induction` records it (False for a parameter that
        changes how the inducer computes, never what it finds, so that results compare equal;
        and for a time bound, which an Induction it stopped names in its ``bound``).

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> SHARED = Parameter(3, Number(low=2, integer=True))
    >>> @dataclass(frozen=True)
    ... class A(Conf):
    ...     copies: int = SHARED.field()
    >>> A().copies
    3
    """

    default: object
    rule: Callable[[str, object], None]
    recorded: bool = True

    def field(self):
        """A dataclass field for this row (a new one per use: a field belongs to one class)."""
        return dataclasses.field(default=self.default,
                                 metadata={"rule": self.rule, "recorded": self.recorded})


def parameter(default: object, rule: Callable[[str, object], None], *, recorded: bool = True):
    """A :class:`Conf` field: its default and the rule its values obey.

    Parameters
    ----------
    default : object
        The value when none is given.
    rule : callable
        ``rule(name, value)``, raising :class:`~psgs.errors.ValidationError` for a bad value.
    recorded : bool, optional
        Whether an Induction records the parameter (see :class:`Parameter`).

    Returns
    -------
    dataclasses.Field

    Examples
    --------
    >>> from dataclasses import dataclass, fields
    >>> @dataclass(frozen=True)
    ... class B(Conf):
    ...     level: float = parameter(0.5, Number(low=0, high=1))
    >>> fields(B)[0].default
    0.5
    """
    return Parameter(default, rule, recorded).field()


@dataclass(frozen=True)
class Conf:
    """Base of inducer parameter tables: a frozen value whose fields validate themselves.

    Subclasses are frozen dataclasses whose fields are made by :func:`parameter`
    (or :meth:`Parameter.field`). Values are checked in field order, so when
    several are bad the first one declared is named.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class C(Conf):
    ...     rounds: int = parameter(2, Number(low=1, integer=True))
    >>> C.names(), C(rounds=3).as_dict()
    (('rounds',), {'rounds': 3})
    """

    def __post_init__(self) -> None:
        for f in dataclasses.fields(self):
            rule = f.metadata.get("rule")
            if isinstance(rule, Number):  # np.int64(3) is a count (one read from an array)
                object.__setattr__(self, f.name, plain_number(getattr(self, f.name)))
            if rule is not None:
                rule(f.name, getattr(self, f.name))

    @classmethod
    def names(cls) -> tuple[str, ...]:
        """The parameter names, in declaration order."""
        return tuple(f.name for f in dataclasses.fields(cls))

    @classmethod
    def defaults(cls) -> dict[str, object]:
        """Parameter name -> default, in declaration order."""
        return {f.name: f.default for f in dataclasses.fields(cls)}

    @classmethod
    def recorded_names(cls) -> tuple[str, ...]:
        """The parameters an Induction records (all but those declared ``recorded=False``)."""
        return tuple(f.name for f in dataclasses.fields(cls) if f.metadata.get("recorded", True))

    @classmethod
    def pick(cls: type[C], source: Conf | Mapping[str, object]) -> C:
        """This table's parameters read from another table or a mapping (missing: defaults).

        Parameters
        ----------
        source : Conf or mapping
            A wider table (e.g. PAL's, holding the learners' parameters), or the
            parameters an Induction recorded.

        Returns
        -------
        Conf
            Of this class, validated.

        Examples
        --------
        >>> from dataclasses import dataclass
        >>> @dataclass(frozen=True)
        ... class D(Conf):
        ...     rounds: int = parameter(2, Number(low=1, integer=True))
        >>> D.pick({"rounds": 4, "colour": "red"}).rounds
        4
        """
        if isinstance(source, Conf):
            values = source.as_dict()
        else:  # a mapping, or (name, value) pairs as dict() reads them (``d.items()``)
            try:
                values = dict(source)
            except (TypeError, ValueError):
                raise ValidationError(f"pick reads a Conf, a mapping or (name, value) pairs, "
                                      f"not {source!r}") from None
        return cls(**{k: values[k] for k in cls.names() if k in values})

    def as_dict(self) -> dict[str, object]:
        """Parameter name -> value, in declaration order (values as given, not copied)."""
        return {f.name: getattr(self, f.name) for f in dataclasses.fields(self)}


def union(name: str, tables: Sequence[type[Conf]], *, replace: Mapping[str, object] = (),
          last: Sequence[str] = (), doc: str = "", module: str = __name__) -> type[Conf]:
    """One table holding the parameters of several, each declared once in its own table.

    Fields come in the order of ``tables`` (a name seen before is skipped: a
    shared row), with ``replace``'s fields in place of those of the same name
    and the names in ``last`` moved to the end.

    Parameters
    ----------
    name : str
        The new class's name.
    tables : sequence of Conf subclasses
        The tables joined.
    replace : mapping of str to Field, optional
        Fields (from :func:`parameter`) that replace a joined table's field of that name.
    last : sequence of str, optional
        Names put at the end, in this order.
    doc : str, optional
        The class's docstring.
    module : str, optional
        The module that binds the class to a name (``__name__`` there), so that
        its values pickle.

    Returns
    -------
    type
        A frozen :class:`Conf` subclass.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class E(Conf):
    ...     rounds: int = parameter(2, Number(low=1, integer=True))
    ...     fast: str = parameter("yes", Choice(("yes", "no")))
    >>> @dataclass(frozen=True)
    ... class F(Conf):
    ...     rounds: int = parameter(2, Number(low=1, integer=True))
    ...     depth: int = parameter(1, Number(low=0, integer=True))
    >>> union("EF", (E, F), last=("fast",)).names()
    ('rounds', 'depth', 'fast')
    """
    replace = dict(replace)
    rows: dict[str, tuple] = {}
    for table in tables:
        for f in dataclasses.fields(table):
            if f.name in rows:
                continue
            made = replace.get(f.name)
            if made is None:
                made = dataclasses.field(default=f.default, metadata=f.metadata)
            rows[f.name] = (f.name, f.type, made)
    for key in last:
        rows[key] = rows.pop(key)
    made_class = dataclasses.make_dataclass(name, list(rows.values()), bases=(Conf,),
                                            frozen=True)
    made_class.__doc__ = doc or f"The parameters of {', '.join(t.__name__ for t in tables)}."
    made_class.__module__ = module
    return made_class
