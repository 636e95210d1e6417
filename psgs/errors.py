"""Exceptions raised by psgs.

Every error that bad input can cause derives from :class:`PSGSError`, so a
command-line front end can catch one class and print one line.
"""

from __future__ import annotations


class PSGSError(Exception):
    """Base class of every error psgs raises on purpose."""


class ValidationError(PSGSError, ValueError):
    """A grammar system, grammar, rule or symbol is malformed.

    The message says what is wrong in words, e.g. ``tuple 3 has 3 entries but
    the system has 4 components``.
    """


class FormatError(PSGSError, ValueError):
    """Text that could not be read, with the place it went wrong.

    ``str(error)`` is one line, ``file:line:col: message``; the parts are kept
    as attributes for programs.
    """

    def __init__(self, message: str, *, source: str = "<string>", line: int | None = None,
                 column: int | None = None) -> None:
        self.message = message
        self.source = source
        self.line = line
        self.column = column
        super().__init__(str(self))

    def __str__(self) -> str:
        where = self.source
        if self.line is not None:
            where += f":{self.line}"
            if self.column is not None:
                where += f":{self.column}"
        return f"{where}: {self.message}"


class BoundReached(PSGSError):
    """A bounded search stopped at its bound before it could answer.

    Raised only where a caller asked for an exception; the functions that can
    stop at a bound normally report it in their result (``complete=False`` and
    the name of the bound). ``bound`` is the name of the budget parameter
    that ran out, e.g. ``"max_seconds"``.
    """

    @property
    def bound(self) -> str:
        """The name of the budget that ran out (the first argument)."""
        return str(self.args[0]) if self.args else ""
