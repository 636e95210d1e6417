"""Exceptions raised by psgs.

Every error that bad input can cause derives from :class:`PSGSError`, so a
command-line front end can catch one class and print one line. It is the root of the whole
distribution's errors: kinetology's ``MotionFormatError`` is a :class:`FormatError`, and
praxicon's errors derive from :class:`PSGSError` too.
"""

from __future__ import annotations


class PSGSError(Exception):
    """Base class of every error psgs raises on purpose.

    Examples
    --------
    >>> import psgs
    >>> try:
    ...     psgs.loads("psgs Broken", source="broken.psgs")
    ... except psgs.PSGSError as error:        # every error psgs raises on purpose
    ...     print(type(error).__name__, error.source)
    FormatError broken.psgs
    """


class ValidationError(PSGSError, ValueError):
    """A grammar system, grammar, rule or symbol is malformed.

    The message says what is wrong in words, e.g. ``tuple 3 has 3 entries but
    the system has 4 components``.

    Examples
    --------
    >>> import psgs
    >>> psgs.Nonterminal("2x")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: nonterminal '2x' is not a valid name (letters, digits and _, not starting with a digit)
    >>> issubclass(psgs.ValidationError, ValueError)
    True
    """


class FormatError(PSGSError, ValueError):
    """Text that could not be read, with the place it went wrong.

    ``str(error)`` is one line, ``file:line:col: message``; the parts are kept
    as attributes for programs.

    Parameters
    ----------
    message : str
        What is wrong, in words.
    source : str, default "<string>"
        The file (or a description of the text).
    line, column : int, optional
        Where, counting from 1.

    Examples
    --------
    >>> error = FormatError("missing arrow", source="x.psgs", line=3, column=7)
    >>> str(error), error.line
    ('x.psgs:3:7: missing arrow', 3)
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


class NotFound(PSGSError, KeyError):
    """A name (a channel, a joint, an action) that is not there; the message lists what is.

    A ``KeyError``, so code that looks names up catches it too, but ``str(error)`` is the
    message itself (its one argument), not its quoted repr.

    Examples
    --------
    >>> error = NotFound("no channel 'nope' (channels: Hips.tx)")
    >>> str(error), isinstance(error, KeyError)
    ("no channel 'nope' (channels: Hips.tx)", True)
    """

    def __str__(self) -> str:
        return str(self.args[0]) if self.args else ""


class MissingDependency(PSGSError, ImportError):
    """An optional dependency that the asked-for work needs is not installed.

    The message names the extra to install (``pip install 'psgs[plot]'``) or the choice that
    needs none. An ``ImportError``, so code that falls back on a missing import catches it.

    Examples
    --------
    >>> error = MissingDependency("plotting needs matplotlib: pip install 'psgs[plot]'")
    >>> isinstance(error, ImportError), str(error)
    (True, "plotting needs matplotlib: pip install 'psgs[plot]'")
    """


class BoundReached(PSGSError):
    """A bounded search stopped at its bound before it could answer.

    Raised only where a caller asked for an exception; the functions that can
    stop at a bound normally report it in their result (``complete=False`` and
    the name of the bound). ``bound`` is the name of the budget parameter
    that ran out, e.g. ``"max_seconds"``.

    Examples
    --------
    >>> issubclass(BoundReached, PSGSError)
    True
    """

    @property
    def bound(self) -> str:
        """The name of the budget that ran out (the first argument)."""
        return str(self.args[0]) if self.args else ""
