"""Which text can name a nonterminal, component, rule or system, and which can be a terminal.

The one place these character rules are written, below :mod:`psgs.model` (which builds the values)
and the text format (which reads them); beside them, the model's one check that a field given
as a sequence is one.
"""

from __future__ import annotations

import re
from collections.abc import Iterable

from .errors import ValidationError

__all__ = ["is_identifier"]

_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z0-9_]*\Z")
# a lone surrogate (a "\ud800" escape, a byte of argv that is not UTF-8) is no text: no
# encoding writes it, so every command that printed the terminal failed
_BAD_TERMINAL = re.compile(r"[\s\x00-\x1f\x7f\ud800-\udfff]")


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
