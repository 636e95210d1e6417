"""Reading the text of an input file: its lines as an editor counts them, its numbers as written.

Python's :meth:`str.splitlines` also breaks lines at a form feed, a vertical tab, the
separators U+001C-U+001E, U+0085, U+2028 and U+2029, so a one-line file could be read as two
and an error named a line the file does not have; :func:`split_lines` breaks at ``\\n`` only
(a ``\\r`` before it is part of the line break). Python's :func:`float` also takes ``1_0``
(10) and digits of any script (``١٢``, ``１２``), which no data file means; :func:`decimal`
takes the ASCII decimal form only (and ``inf``/``nan``, which the readers then refuse with a
message of their own). :func:`finite` is :func:`math.isfinite` for any number a caller gives,
an int past the floats included. :func:`first_unseen` finds the characters no name or symbol
may hold, which a reader of the text cannot see or which break its line, and
:func:`character_name` says which one it is.
"""

from __future__ import annotations

import math
import re
import unicodedata

__all__ = ["split_lines", "decimal", "DECIMAL", "finite", "first_unseen", "character_name"]

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


# white space (Python's \s: Unicode's too, U+0085, U+00A0, U+2028 ...), C0 and DEL
_SPACE_OR_ASCII_CONTROL = re.compile(r"[\s\x00-\x1f\x7f]")
# beyond ASCII, by Unicode category: controls (C1, U+0080-U+009F), format characters (soft
# hyphen, zero-width space and joiners, direction marks and overrides, word joiner, U+FEFF,
# tags) and lone surrogates
_UNSEEN_CATEGORIES = frozenset(("Cc", "Cf", "Cs"))


def first_unseen(text: str) -> int | None:
    """The index of the first character of ``text`` that a reader cannot see or that breaks
    its line: white space, a control character (C0, DEL, C1), a format character (Unicode
    category Cf: U+00AD, U+200B-U+200F, U+202A-U+202E, U+2060-U+2064, U+FEFF, ...) or a lone
    surrogate; None when there is none.

    Two names that differ by such a character look the same wherever they are shown, and a
    control character rewrites the terminal that shows it (``\x9b`` begins an escape
    sequence), so no name or symbol holds one. Private-use and unassigned code points are
    left alone: they show as a box, and which are unassigned changes with Python's Unicode.

    Examples
    --------
    >>> first_unseen("up"), first_unseen("a b"), first_unseen("a\u200bb"), first_unseen("\x9b")
    (None, 1, 1, 0)
    >>> first_unseen("d\u00f6wn"), first_unseen("\ufeffx"), first_unseen("\ue000")
    (None, 0, None)
    """
    found = _SPACE_OR_ASCII_CONTROL.search(text)
    end = len(text) if found is None else found.start()
    if not text.isascii():  # the usual symbol is ASCII: one regex search, no loop
        category = unicodedata.category
        for k in range(end):
            if text[k] > "\x7f" and category(text[k]) in _UNSEEN_CATEGORIES:
                return k
    return None if found is None else end


# Unicode gives the control characters no name (unicodedata.name has none for them), only
# aliases (NameAliases.txt): each one's first alias of type 'control', the name ISO 6429 and
# ISO 646 give it. U+0080, U+0081 and U+0099 were never in a standard and have only a
# 'figment' alias, the name in common use, given here so that every control has a name.
_C0_NAMES = (
    "NULL", "START OF HEADING", "START OF TEXT", "END OF TEXT", "END OF TRANSMISSION",
    "ENQUIRY", "ACKNOWLEDGE", "ALERT", "BACKSPACE", "CHARACTER TABULATION", "LINE FEED",
    "LINE TABULATION", "FORM FEED", "CARRIAGE RETURN", "SHIFT OUT", "SHIFT IN",
    "DATA LINK ESCAPE", "DEVICE CONTROL ONE", "DEVICE CONTROL TWO", "DEVICE CONTROL THREE",
    "DEVICE CONTROL FOUR", "NEGATIVE ACKNOWLEDGE", "SYNCHRONOUS IDLE",
    "END OF TRANSMISSION BLOCK", "CANCEL", "END OF MEDIUM", "SUBSTITUTE", "ESCAPE",
    "INFORMATION SEPARATOR FOUR", "INFORMATION SEPARATOR THREE", "INFORMATION SEPARATOR TWO",
    "INFORMATION SEPARATOR ONE",
)  # U+0000-U+001F
_DELETE_NAME = "DELETE"  # U+007F
_C1_NAMES = (
    "PADDING CHARACTER", "HIGH OCTET PRESET", "BREAK PERMITTED HERE", "NO BREAK HERE", "INDEX",
    "NEXT LINE", "START OF SELECTED AREA", "END OF SELECTED AREA", "CHARACTER TABULATION SET",
    "CHARACTER TABULATION WITH JUSTIFICATION", "LINE TABULATION SET", "PARTIAL LINE FORWARD",
    "PARTIAL LINE BACKWARD", "REVERSE LINE FEED", "SINGLE SHIFT TWO", "SINGLE SHIFT THREE",
    "DEVICE CONTROL STRING", "PRIVATE USE ONE", "PRIVATE USE TWO", "SET TRANSMIT STATE",
    "CANCEL CHARACTER", "MESSAGE WAITING", "START OF GUARDED AREA", "END OF GUARDED AREA",
    "START OF STRING", "SINGLE GRAPHIC CHARACTER INTRODUCER", "SINGLE CHARACTER INTRODUCER",
    "CONTROL SEQUENCE INTRODUCER", "STRING TERMINATOR", "OPERATING SYSTEM COMMAND",
    "PRIVACY MESSAGE", "APPLICATION PROGRAM COMMAND",
)  # U+0080-U+009F


def character_name(char: str) -> str:
    """``char`` as a message names it: its code point and, when Unicode has one, its name.

    A control character (C0, DEL, C1), which has no name in :mod:`unicodedata`, is named by
    its Unicode alias (``NEXT LINE``, ``ESCAPE``); a private-use, unassigned or surrogate code
    point has none.

    Examples
    --------
    >>> character_name("\\u200b"), character_name("\\x9b")
    ('U+200B ZERO WIDTH SPACE', 'U+009B CONTROL SEQUENCE INTRODUCER')
    >>> character_name("\\x85"), character_name("\\t"), character_name("\\ue000")
    ('U+0085 NEXT LINE', 'U+0009 CHARACTER TABULATION', 'U+E000')
    """
    code = ord(char)
    if code < 0x20:
        name = _C0_NAMES[code]
    elif code == 0x7F:
        name = _DELETE_NAME
    elif 0x80 <= code < 0xA0:
        name = _C1_NAMES[code - 0x80]
    else:
        name = unicodedata.name(char, "")
    return f"U+{code:04X}" + (f" {name}" if name else "")
