"""Reading the text of an input file: its lines as an editor counts them, its numbers as written.

Python's :meth:`str.splitlines` also breaks lines at a form feed, a vertical tab, the
separators U+001C-U+001E, U+0085, U+2028 and U+2029, so a one-line file could be read as two
and an error named a line the file does not have; :func:`split_lines` breaks at ``\\n`` only
(a ``\\r`` before it is part of the line break). Python's :func:`float` also takes ``1_0``
(10) and digits of any script (``١٢``, ``１２``), which no data file means; :func:`decimal`
takes the ASCII decimal form only (and ``inf``/``nan``, which the readers then refuse with a
message of their own). :func:`finite` is :func:`math.isfinite` for any number a caller gives,
an int past the floats included.
"""

from __future__ import annotations

import math
import re

__all__ = ["split_lines", "decimal", "DECIMAL", "finite"]

#: A number as data files write it: ASCII digits, an optional point and exponent; or inf/nan.
DECIMAL = re.compile(r"[+-]?(?:(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d+)?|inf(?:inity)?|nan)\Z",
                     re.ASCII | re.IGNORECASE)


def split_lines(text: str) -> list[str]:
    """The lines of ``text``, broken at ``\\n`` only, a ``\\r`` before it dropped; a text with
    no ``\\n`` at all but a ``\\r`` is one of the old Mac's, broken at ``\\r``.

    Examples
    --------
    >>> split_lines("a b\\r\\nc\\x0cd\\n")
    ['a b', 'c\\x0cd']
    >>> "c\\x0cd".splitlines()
    ['c', 'd']
    >>> split_lines("a\\rb\\r")
    ['a', 'b']
    """
    if "\r" in text and "\n" not in text:
        text = text.replace("\r", "\n")
    lines = text.split("\n")
    if lines and lines[-1] == "":
        lines.pop()  # the break that ends the last line starts no line of its own
    return [line[:-1] if line.endswith("\r") else line for line in lines]


def decimal(text: str) -> float | None:
    """``text`` as a float when it is written as a decimal number (:data:`DECIMAL`), else None.

    Examples
    --------
    >>> decimal("-1.5e3"), decimal("1_0"), decimal("１２"), decimal("nan") != decimal("nan")
    (-1500.0, None, None, True)
    """
    return float(text) if DECIMAL.match(text) else None


def finite(value: int | float) -> bool:
    """Whether ``value`` is a finite number a float can hold: :func:`math.isfinite`, but
    False for an int past the floats (``10**400``) instead of an OverflowError.

    Examples
    --------
    >>> finite(1.5), finite(float("nan")), finite(10**400)
    (True, False, False)
    """
    try:
        return math.isfinite(value)
    except OverflowError:
        return False
