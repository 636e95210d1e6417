"""Edit costs and edit scripts for :func:`psgs.nearest`.

An edit turns the input word into the nearest word: ``insert`` a terminal,
``delete`` an input symbol, or ``substitute`` a terminal for an input symbol.
A match costs nothing. :class:`EditCosts` gives each operation a cost (the
same for every symbol, or per symbol and per pair of symbols);
:class:`Edit` is one step of an edit script, :func:`apply_edits` replays a
script on a word.
"""

from __future__ import annotations

import numbers
from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Literal

from .._foundation.text import finite
from ..errors import ValidationError
from ..model import Terminal, Word, as_word

__all__ = ["EditCosts", "Edit", "apply_edits", "edit_costs"]


def _number(value, what: str) -> float:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise ValidationError(f"{what} must be a number, not {value!r}")
    if not finite(value) or value < 0:  # not NaN nor inf, nor an int past the floats
        raise ValidationError(f"{what} must be a finite number ≥ 0, not {value!r}")
    # a numpy number as the Python one it stands for: np.int64 sums wrap round past 2**63
    return int(value) if isinstance(value, numbers.Integral) else float(value)


def _terminal(value, what: str) -> Terminal:
    if isinstance(value, Terminal):
        return value
    if isinstance(value, str):
        word = as_word([value])
        return word[0]
    raise ValidationError(f"{what}: {value!r} is not a terminal")


def _frozen(mapping) -> Mapping:
    return MappingProxyType(dict(mapping))


@dataclass(frozen=True)
class EditCosts:
    """What each edit costs: unit insertion, deletion and substitution by default.

    ``insert``, ``delete`` and ``substitute`` are the costs of the operation
    for any symbol; ``insert_symbol`` and ``delete_symbol`` override them per
    terminal, ``pairs`` per (input symbol, new terminal) substitution. Costs
    are finite and ≥ 0; a match costs 0. :func:`edit_costs` builds one from
    a plain mapping and checks it.

    Attributes
    ----------
    insert, delete, substitute : float, default 1
        The cost of the operation on any symbol.
    insert_symbol, delete_symbol : mapping of Terminal to float
        Per-symbol costs, overriding ``insert`` and ``delete``.
    pairs : mapping of (Terminal, Terminal) to float
        Per-pair substitution costs, overriding ``substitute``.

    Examples
    --------
    >>> from psgs.model import Terminal as T
    >>> costs = edit_costs({"substitute": 2, "pairs": {("a", "b"): 0.5}})
    >>> costs.substitution(T("a"), T("b")), costs.substitution(T("a"), T("c")), costs.insertion(T("a"))
    (0.5, 2, 1)
    """

    insert: float = 1
    delete: float = 1
    substitute: float = 1
    insert_symbol: Mapping = field(default_factory=lambda: _frozen({}))
    delete_symbol: Mapping = field(default_factory=lambda: _frozen({}))
    pairs: Mapping = field(default_factory=lambda: _frozen({}))

    def __post_init__(self) -> None:
        for name in ("insert", "delete", "substitute"):
            object.__setattr__(self, name, _number(getattr(self, name), f"the {name} cost"))
        for name in ("insert_symbol", "delete_symbol"):
            table = getattr(self, name)
            if not isinstance(table, Mapping):
                raise ValidationError(f"{name} must be a mapping of terminals to costs")
            clean = {_terminal(k, name): _number(v, f"the {name} cost of {k!r}")
                     for k, v in table.items()}
            object.__setattr__(self, name, _frozen(clean))
        if not isinstance(self.pairs, Mapping):
            raise ValidationError("pairs must be a mapping of (symbol, symbol) to costs")
        clean = {}
        for k, v in self.pairs.items():
            if not isinstance(k, tuple) or len(k) != 2:
                raise ValidationError(f"pairs: {k!r} is not a pair of symbols")
            clean[(_terminal(k[0], "pairs"), _terminal(k[1], "pairs"))] = _number(
                v, f"the substitution cost of {k!r}")
        object.__setattr__(self, "pairs", _frozen(clean))

    @property
    def unit(self) -> bool:
        """True for unit costs everywhere (what the fast paths assume)."""
        return (self.insert == self.delete == self.substitute == 1 and not self.insert_symbol
                and not self.delete_symbol and not self.pairs)

    def insertion(self, t: Terminal) -> float:
        """The cost of inserting ``t``."""
        return self.insert_symbol.get(t, self.insert)

    def deletion(self, t: Terminal) -> float:
        """The cost of deleting input symbol ``t``."""
        return self.delete_symbol.get(t, self.delete)

    def substitution(self, old: Terminal, new: Terminal) -> float:
        """The cost of replacing input symbol ``old`` by ``new`` (0 when equal)."""
        if old == new:
            return 0
        return self.pairs.get((old, new), self.substitute)


_KEYS = ("insert", "delete", "substitute", "pairs")


def edit_costs(costs) -> EditCosts:
    """Read the ``costs`` argument of :func:`psgs.nearest` (``None``, mapping or EditCosts).

    A mapping holds ``insert``/``delete`` (a number, or a mapping of
    terminals to numbers: those symbols get their own cost, others 1),
    ``substitute`` (a number) and ``pairs`` (a mapping of (old, new) to
    numbers).

    Examples
    --------
    >>> edit_costs(None).unit
    True
    >>> edit_costs({"insert": 2}).insert
    2
    >>> edit_costs({"delete": -1})
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: the delete cost must be a finite number ≥ 0, not -1
    """
    if costs is None:
        return EditCosts()
    if isinstance(costs, EditCosts):
        return costs
    if not isinstance(costs, Mapping):
        raise ValidationError(f"costs must be a mapping or EditCosts, not {costs!r}")
    unknown = [k for k in costs if k not in _KEYS]
    if unknown:
        raise ValidationError(f"costs: unknown key {unknown[0]!r} (use {', '.join(_KEYS)})")
    args = {}
    for name in ("insert", "delete"):
        value = costs.get(name, 1)
        if isinstance(value, Mapping):
            args[f"{name}_symbol"] = value
        else:
            args[name] = value
    if "substitute" in costs:
        args["substitute"] = costs["substitute"]
    if "pairs" in costs:
        args["pairs"] = costs["pairs"]
    return EditCosts(**args)


@dataclass(frozen=True, slots=True)
class Edit:
    """One edit of the input word: what is done at which input position, and its cost.

    ``position`` counts input symbols from 0: the symbol deleted or
    substituted, or the symbol an insertion goes before (``len(word)`` for
    the end). ``old`` is the input symbol (``None`` for an insertion),
    ``new`` the nearest word's terminal (``None`` for a deletion).

    Examples
    --------
    >>> from psgs.model import Terminal as T
    >>> str(Edit("substitute", 2, T("x"), T("c"), 1))
    'substitute x→c at 2'
    """

    op: Literal["insert", "delete", "substitute"]
    position: int
    old: Terminal | None
    new: Terminal | None
    cost: float

    def __str__(self) -> str:
        if self.op == "insert":
            return f"insert {self.new} at {self.position}"
        if self.op == "delete":
            return f"delete {self.old} at {self.position}"
        return f"substitute {self.old}→{self.new} at {self.position}"


def apply_edits(word: Word, edits) -> Word:
    """The word an edit script turns ``word`` into (edits in order of position).

    Examples
    --------
    >>> from psgs.model import Terminal as T, as_word
    >>> edits = (Edit("delete", 0, T("x"), None, 1), Edit("insert", 3, None, T("c"), 1))
    >>> "".join(map(str, apply_edits(as_word("xab"), edits)))
    'abc'
    """
    out: list[Terminal] = []
    at = 0
    for edit in edits:
        if edit.position < at or edit.position > len(word):
            raise ValidationError(f"edit {edit} is out of order or outside the word")
        out.extend(word[at:edit.position])
        at = edit.position
        if edit.op == "insert":
            out.append(edit.new)
            continue
        if word[at] != edit.old:
            raise ValidationError(f"edit {edit} does not match the word ({word[at]} there)")
        if edit.op == "substitute":
            out.append(edit.new)
        at += 1
    out.extend(word[at:])
    return tuple(out)
