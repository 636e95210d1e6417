"""The budgets every search shares: a wall clock and a memory account.

A search takes one :class:`Budget`, started *before* any grammar analysis, so
``max_seconds`` covers everything the caller waits for. ``tick()`` is cheap
(it reads the clock only every ``every`` calls) and raises
:class:`~psgs.errors.BoundReached` naming the bound; the search catches it
and reports the bound in its result. Memory is counted, not measured: a
search adds the size of what it keeps (states × form size, in symbols) with
``hold()``, so the bound is the same on every machine and every run.
"""

from __future__ import annotations

import math
import numbers
import time

from .errors import BoundReached, ValidationError

__all__ = ["Budget", "check_seconds", "check_count"]


def check_seconds(value, name: str = "max_seconds", *, optional: bool = False) -> None:
    """A positive number of seconds (or ``None`` when ``optional``); :class:`ValidationError` if not.

    Examples
    --------
    >>> check_seconds(2.5)
    >>> check_seconds(None, optional=True)
    >>> check_seconds(-1)
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: max_seconds must be a positive number, not -1
    """
    if value is None and optional:
        return
    # numbers.Real: a numpy number (a budget read from an array) is a number of seconds too
    if isinstance(value, bool) or not isinstance(value, numbers.Real) or not value > 0:
        what = "a positive number or None" if optional else "a positive number"
        raise ValidationError(f"{name} must be {what}, not {value!r}")


def check_count(value, name: str, minimum: int = 1) -> None:
    """A whole number ≥ ``minimum``; :class:`ValidationError` if not.

    Examples
    --------
    >>> check_count(3, "max_states")
    >>> check_count(0, "max_states")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: max_states must be a whole number ≥ 1, not 0
    """
    # numbers.Integral: a numpy integer (a count read from an array) is a whole number too
    if isinstance(value, bool) or not isinstance(value, numbers.Integral) or value < minimum:
        raise ValidationError(f"{name} must be a whole number ≥ {minimum}, not {value!r}")


class Budget:
    """A wall-clock deadline and a count of the symbols a search keeps.

    ``seconds=None`` means no time limit, ``max_symbols=None`` no memory
    limit. ``expired()`` reads the clock now; ``tick()`` reads it every
    ``every`` calls and raises ``BoundReached("max_seconds")`` once the
    deadline has passed; ``hold(n)`` adds ``n`` symbols and raises
    ``BoundReached("max_symbols")`` past the limit.

    Examples
    --------
    >>> from psgs.errors import BoundReached
    >>> budget = Budget(seconds=None, max_symbols=10)
    >>> budget.expired()
    False
    >>> try:
    ...     budget.hold(11)
    ... except BoundReached as stop:
    ...     print(stop)
    max_symbols
    """

    __slots__ = ("seconds", "deadline", "max_symbols", "held", "_count", "_every")

    def __init__(self, seconds: float | None = None, max_symbols: int | None = None, *,
                 every: int = 256) -> None:
        # a NaN deadline compares false with every time: a search on it would never stop
        check_seconds(seconds, "seconds", optional=True)
        if max_symbols is not None:
            check_count(max_symbols, "max_symbols")
        check_count(every, "every")
        self.seconds = seconds
        # an int past a float's range is an unbounded wait, as inf is (the sum would overflow)
        self.deadline = None if seconds is None else \
            time.monotonic() + (seconds if seconds < 1e300 else math.inf)
        self.max_symbols = max_symbols
        self.held = 0
        self._count = 0
        self._every = every

    def expired(self) -> bool:
        """True when the deadline has passed (never without one)."""
        return self.deadline is not None and time.monotonic() > self.deadline

    def left(self) -> float | None:
        """Seconds left (at least a millisecond), or ``None`` without a deadline."""
        if self.deadline is None:
            return None
        return max(self.deadline - time.monotonic(), 1e-3)

    def tick(self) -> None:
        """Count one unit of work; every ``every`` units, raise when the deadline has passed."""
        self._count += 1
        if self._count >= self._every:
            self._count = 0
            if self.deadline is not None and time.monotonic() > self.deadline:
                raise BoundReached("max_seconds")

    def check(self) -> None:
        """Raise ``BoundReached("max_seconds")`` when the deadline has passed."""
        if self.deadline is not None and time.monotonic() > self.deadline:
            raise BoundReached("max_seconds")

    def hold(self, symbols: int) -> None:
        """Account for ``symbols`` more symbols kept; raise past ``max_symbols``."""
        self.held += symbols
        if self.max_symbols is not None and self.held > self.max_symbols:
            raise BoundReached("max_symbols")
