"""The checks of names and numbers that the actiongram modules share (one job: say what is wrong).

Kept below every other module of :mod:`psgs.actiongram`, so that each can import them.
"""

from __future__ import annotations

import math
import numbers
import re

from .._foundation.text import character_name, finite as _finite, first_unseen
from ..errors import FormatError, ValidationError

__all__: list[str] = []  # private helpers

_NUMBER = re.compile(r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?\Z", re.ASCII)


#: The source an error of a value made in memory names, where a reader's names its file: there
#: is no file, line or column to name (the text and JSON readers place the same message in
#: theirs), so it names what refused the value.
IN_MEMORY = "Actiongram"


def _refused(message: str) -> FormatError:
    """The FormatError of a value made in memory (a constructor's or from_strings' argument):
    its source is :data:`IN_MEMORY`, not a file's name.

    >>> str(_refused("string 'a': a duration must be positive and finite, not -1"))
    "Actiongram: string 'a': a duration must be positive and finite, not -1"
    """
    return FormatError(message, source=IN_MEMORY)


def _real(value: object) -> bool:
    """Whether ``value`` is a real number a time or a displacement may be: an int, a float,
    a Fraction, numpy's integer and floating scalars (:class:`numbers.Real`), but no bool,
    and no ``numpy.timedelta64``, a Real to numpy whose count would be read without its unit.

    >>> import numpy as np
    >>> [_real(v) for v in (1, 2.5, np.int64(3), np.float32(0.5), True, 1j, "1")]
    [True, True, True, True, False, False, False]
    >>> _real(np.timedelta64(5, "ms"))
    False
    """
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return False
    kind = getattr(getattr(value, "dtype", None), "kind", None)  # numpy's scalars have one
    return kind is None or kind in "iuf"


def _shown(value: object, limit: int = 40) -> str:
    """``repr(value)``, cut to about ``limit`` characters so one bad token keeps errors one line."""
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 5] + "...'" + f" ({len(str(value))} chars)"


def _tuple_of(value: object, what: str, rows: bool = False) -> tuple:
    """``value`` as a tuple (each item a tuple too when ``rows``); a ValidationError naming
    ``what`` for one that is no sequence (None, a number), not Python's TypeError."""
    try:
        return tuple(tuple(row) for row in value) if rows else tuple(value)
    except TypeError:
        kind = "a sequence of sequences" if rows else "a sequence"
        raise ValidationError(f"{what} must be {kind}, not {_shown(value)}") from None


def _names_of(value: object, what: str, kind: str = "string") -> tuple:
    """``value``, a collection of names, as a tuple; a bare str is refused, not read as the
    names of its characters (``subset("ab")`` picked the strings 'a' and 'b', not 'ab').

    >>> _names_of(["ab"], "names")
    ('ab',)
    >>> _names_of("ab", "names")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: names must be a sequence of string names, not a str ('ab'); one name is given as ['ab']
    """
    if isinstance(value, str):
        raise ValidationError(f"{what} must be a sequence of {kind} names, not a str "
                              f"({_shown(value)}); one name is given as [{_shown(value)}]")
    return _tuple_of(value, what)


def _not_unicode(text: str) -> bool:
    """True for text with a lone surrogate (JSON ``"\\ud800"``): it cannot be written as UTF-8."""
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        return True
    return False


# the characters no token of the text format holds (an actuator's name); a symbol refuses
# what a grammar's terminal refuses too (first_unseen: C1 controls and invisible format
# characters besides), so that every symbol can be a terminal of the grammar learnt from it
_SPACE_OR_CONTROL = re.compile(r"[\s\x00-\x1f\x7f]")
_PLAIN_NAME = re.compile(r"[!-~]+")  # printable ASCII without white space: the common case


def _bad_name(name: object) -> str | None:
    """Why ``name`` cannot name an actuator, or None when it can."""
    if isinstance(name, str) and _PLAIN_NAME.fullmatch(name) and "@" not in name \
            and ":" not in name and name[0] != "#":
        return None  # a quick yes for the usual names; anything else takes the checks below
    if not isinstance(name, str) or not name:
        return "an actuator name must be non-empty text"
    if name[0] == "\ufeff":  # the first line's would be read back without it (psgs.load)
        return (f"actuator name {_shown(name)} starts with {character_name(name[0])}, the "
                f"byte-order mark a file's reader drops")
    return _bad_token(name, "actuator name")


def _bad_token(text: str, what: str) -> str | None:
    """Why non-empty ``text`` cannot be a token of the text format (a ``what``), or None."""
    if _not_unicode(text):
        return f"{what} {_shown(text)} is not valid Unicode (a lone surrogate)"
    rule = "must have no white space, control character, '@' or ':' and not start with '#'"
    unseen = _SPACE_OR_CONTROL.search(text)
    if unseen:  # named: a cut repr (_shown) may not show it, nor tell one space from another
        return (f"{what} {_shown(text)} holds {character_name(unseen.group())} (character "
                f"{unseen.start() + 1}): it {rule}")
    if "@" in text or ":" in text or text.startswith("#"):
        return f"{what} {_shown(text)} {rule}"
    return None


def _bad_symbol(symbol: object) -> str | None:
    if not isinstance(symbol, str) or not symbol:
        return f"a symbol must be non-empty text, not {_shown(symbol)}"
    problem = _bad_token(symbol, "symbol")
    if problem is None and (at := first_unseen(symbol)) is not None:
        return (f"symbol {_shown(symbol)} holds {character_name(symbol[at])} (character "
                f"{at + 1}), a control or invisible format character, which no terminal of a "
                f"grammar holds")
    return problem


def _bad_duration(value: object) -> str | None:
    if not _real(value):
        return f"a duration must be a number, not {_shown(value)}"
    if not _finite(value) or value <= 0:
        return f"a duration must be positive and finite, not {_shown(value)}"
    return None


def _bad_displacement(value: object) -> str | None:
    if not _real(value):
        return f"a displacement must be a number, not {_shown(value)}"
    if not _finite(value):
        return f"a displacement must be finite, not {_shown(value)}"
    return None


def _plain_durations(durations: tuple) -> bool:
    """Fast check that every duration is a positive finite int or float (not bool)."""
    if not durations:
        return True
    if not set(map(type, durations)) <= {int, float}:
        return False
    return min(durations) > 0 and _all_finite(durations)


def _plain_displacements(displacements: tuple) -> bool:
    """Fast check that every displacement is a finite int or float (not bool): True when
    :func:`_bad_displacement` refuses none of them, False when it may refuse one (it then
    says which, and why).

    A value at a time costs a call of each check and an ABC's isinstance for every symbol
    (most of a large actiongram's construction); these types and map run in C.

    >>> _plain_displacements((1, -2.5, 0)), _plain_displacements(())
    (True, True)
    >>> [_plain_displacements(v) for v in ((True,), (float("nan"),), (10**400,), ("1",))]
    [False, False, False, False]
    """
    if not set(map(type, displacements)) <= {int, float}:
        return False  # a bool, a numpy scalar, a Fraction, what is no number: checked one by one
    return _all_finite(displacements)


def _all_finite(values: tuple) -> bool:
    """Whether every one of ``values``, ints and floats, is finite as :func:`_finite` says:
    math.isfinite mapped in C, not a Python call a value.

    >>> _all_finite((1, 2.5)), _all_finite((1, float("inf"))), _all_finite((1.0, 10**400))
    (True, False, False)
    """
    try:
        return all(map(math.isfinite, values))
    except OverflowError:  # an int past the floats, which _finite calls not finite
        return False


def _times_problem(name: str, origin: float, segments: tuple[float, ...],
                   symbols: tuple[str, ...], keep_repeats: bool) -> tuple[int, str] | None:
    """The first segment whose duration vanishes beside its start time (``T + D == T`` in
    floats): the index of its first symbol as given, and the message; None when every start
    time advances.

    ``s@1e15: a@1e-9`` is positive on paper but adds nothing to 1e15, so two symbols would
    share one start time and every later computation on times (PAL's time grid) divides by 0.
    ``segments`` are the durations as timed: a run of equal neighbours is one segment unless
    ``keep_repeats``, and is named by the symbols of ``symbols`` it merges.

    >>> _times_problem("s", 1e15, (1.0, 2e-9), ("x", "y", "y"), False)
    (1, "string 's': duration 2e-09 of symbols 2-3 (equal neighbours: one segment) vanishes beside its start time 1000000000000001.0 (T + D == T in floating point)")
    >>> _times_problem("s", 0.0, (1.0, 2e-9), ("x", "y", "y"), False) is None
    True
    """
    t = origin
    for j, d in enumerate(segments):
        after = t + d
        if after == t:
            break
        t = after
    else:
        return None
    if keep_repeats:
        first, count = j, 1
    else:  # the j-th run of equal neighbours (the checks before made every symbol hashable text)
        starts = [i for i, sym in enumerate(symbols) if i == 0 or sym != symbols[i - 1]]
        first = starts[j]
        count = (starts[j + 1] if j + 1 < len(starts) else len(symbols)) - first
    which = f"symbol {first + 1}" if count == 1 else \
        f"symbols {first + 1}-{first + count} (equal neighbours: one segment)"
    return first, (f"string {_shown(name)}: duration {d!r} of {which} vanishes beside its "
                   f"start time {t!r} (T + D == T in floating point)")


def _format_number(value: float) -> str:
    """Shortest text that reads back as the same float (integers without '.0')."""
    if float(value).is_integer() and abs(value) < 1e15:
        return str(int(value))
    return repr(float(value))


def _read_number(text: str, *, allow_nonpositive: bool) -> float | None:
    if not _NUMBER.match(text):
        return None
    value = float(text)
    if not math.isfinite(value) or (not allow_nonpositive and value <= 0):
        return None
    return value
