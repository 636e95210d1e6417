"""Printing in the paper's notation: forms, configurations and tuples.

``N12d``, ``(N4N4, b)``, ``(p1, #, q3)``: symbols are concatenated as in the
paper unless some terminal has a name longer than one character, then they
are separated by spaces.
"""

from __future__ import annotations

from .model import IDLE, Form, Terminal

__all__ = ["format_form", "format_configuration", "show_tuple", "spaced", "short"]


def spaced(system) -> bool:
    """True when some terminal of ``system`` is longer than one character (print with spaces)."""
    return any(len(t.name) > 1 for t in system.terminals)


def format_form(form: Form, system=None, *, spaced: bool | None = None) -> str:
    """A sentential form in the paper's notation: ``N12d``, ``N4N4``; ``ε`` when empty.

    Symbols are concatenated, as in the paper, unless some terminal of
    ``system`` has a name longer than one character (then they are
    separated by spaces).

    >>> from psgs.model import Nonterminal as N, Terminal as T
    >>> format_form((N("N4"), N("N4"), T("b"))), format_form(())
    ('N4N4b', 'ε')
    """
    if spaced is None:
        spaced = _spaced(system) if system is not None else any(
            isinstance(s, Terminal) and len(s.name) > 1 for s in form)
    if not form:
        return "ε"
    return (" " if spaced else "").join(str(s) for s in form)


_spaced = spaced


def format_configuration(configuration, system=None, *, spaced: bool | None = None) -> str:
    """``(x_1, …, x_n)`` with each form in the paper's notation.

    >>> from psgs.model import Nonterminal as N, Terminal as T
    >>> format_configuration(((N("S1"),), (T("a"), T("b"))))
    '(S1, ab)'
    """
    if spaced is None and system is not None:
        spaced = _spaced(system)
    return "(" + ", ".join(format_form(f, system, spaced=spaced) for f in configuration) + ")"


def show_tuple(sync_tuple) -> str:
    """A tuple of rules by their labels, ``#`` for an idle component: ``(p1, #, q3)``."""
    return "(" + ", ".join("#" if r is IDLE else r.label for r in sync_tuple) + ")"


def short(text: str, limit: int = 60) -> str:
    """Long forms make unreadable messages: keep the start."""
    return text if len(text) <= limit else text[:limit] + f"… ({len(text)} characters)"
