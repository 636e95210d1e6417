"""Which text can name a nonterminal, component, rule or system, and which can be a terminal.

The one place these character rules are written, below :mod:`psgs.model` (which builds the values)
and the text format (which reads them); beside them, the model's one check that a field given
as a sequence is one.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from ._foundation.text import character_name, first_unseen
from .errors import ValidationError

__all__ = ["is_identifier"]

_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")


def _terminal_problem(name: object) -> str | None:
    """Why ``name`` cannot be a terminal's text, or None when it can.

    Non-empty text without white space, control characters (C0, DEL and C1), invisible format
    characters (U+200B, U+FEFF, ...) or lone surrogates (:func:`first_unseen`): a terminal is
    shown wherever its system is, and one that looks like another, or that rewrites the
    screen showing it, misleads whoever reads it; a lone surrogate (a ``"\\ud800"`` escape, a
    byte of argv that is not UTF-8) is no text at all, which no encoding writes.

    Examples
    --------
    >>> _terminal_problem("up") is None
    True
    >>> print(_terminal_problem("a\\u200bb"))  # doctest: +NORMALIZE_WHITESPACE
    terminal 'a\\u200bb' holds U+200B ZERO WIDTH SPACE (character 2): a terminal is non-empty
    text without white space, control or invisible format characters
    """
    rule = "non-empty text without white space, control or invisible format characters"
    if not isinstance(name, str) or not name:
        return f"terminal {name!r} must be {rule}"
    at = first_unseen(name)
    if at is None:
        return None
    return (f"terminal {name!r} holds {character_name(name[at])} (character {at + 1}): "
            f"a terminal is {rule}")


def is_identifier(name: object) -> bool:
    """True when ``name`` can name a nonterminal, component, rule or system.

    Examples
    --------
    >>> is_identifier("S1"), is_identifier("1S"), is_identifier(None)
    (True, False, False)
    """
    return isinstance(name, str) and bool(_IDENTIFIER.match(name))


def _require_identifier(name: object, what: str) -> None:
    if not is_identifier(name):
        raise ValidationError(
            f"{what} {name!r} is not a valid name (letters, digits and _, not starting with a digit)")


def _as_tuple(value: object, what: str) -> tuple:
    """``value`` as a tuple; a ValidationError naming ``what`` for a value that is no
    sequence (None, a number), where ``tuple()`` would raise a TypeError naming no field."""
    if isinstance(value, Iterable):
        return tuple(value)
    raise ValidationError(f"{what} must be a sequence, not {value!r}")
