"""JSON values as frozen values: typed access to a JSON object with one-line errors, and
:func:`freeze`/:func:`thaw` between JSON objects and sorted tuples of pairs.

Its one job is the boundary between the praxicon's JSON files and its frozen records: every
reader of a record goes through :class:`Fields`, so a damaged file gives one line naming the
file and the key, never a ``KeyError`` or ``TypeError``.
"""

from __future__ import annotations

import json
import math

from psgs._foundation.files import read_text
from psgs.errors import FormatError

__all__ = ["Fields", "freeze", "thaw", "as_dict", "pairs", "read_json", "written_by",
           "shown", "bad_item", "one_each"]

def read_json(path, error: type[Exception], missing: str | None = None):
    """The JSON value in the file ``path``; whatever is wrong is one ``error`` line naming the
    file (and the line and column of text that is not UTF-8 or not JSON).

    ``missing`` is the message for a file that does not exist (default ``PATH: missing``).
    Read through :func:`psgs._foundation.files.read_text`, so a device in place of the file
    is refused instead of read until memory runs out.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "x.json"
    >>> _ = path.write_text('{"a": 1,\\n "b": }')
    >>> read_json(path, ValueError)  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: .../x.json:2:7: not JSON (Expecting value)
    """
    try:
        text = read_text(path)
    except FileNotFoundError:
        raise error(missing or f"{path}: missing") from None
    except FormatError as exc:  # not a regular file, or not UTF-8 (with the place)
        raise error(str(exc)) from None
    except OSError as exc:
        raise error(f"{path}: cannot be read ({exc.strerror or exc})") from None
    except ValueError as exc:  # a NUL byte in the path
        raise error(f"{path}: cannot be read ({exc})") from None
    try:
        return json.loads(text)
    except RecursionError:
        raise error(f"{path}: nests too deeply to be a praxicon file") from None
    except json.JSONDecodeError as exc:
        raise error(f"{path}:{exc.lineno}:{exc.colno}: not JSON ({exc.msg})") from None
    except ValueError as exc:  # e.g. an integer of more digits than Python converts
        raise error(f"{path}: not JSON ({exc})") from None


def written_by(said, version: int) -> str | None:
    """Which psgs wrote a file whose ``"version"`` is ``said``, for this one, which reads
    ``version``: ``None`` this one (the same version), ``"later"`` a later one (a whole
    number above ``version``), ``"earlier"`` an earlier one (any other value, a missing
    version too).

    A later psgs's file is neither read (upgrade psgs) nor written over, where an earlier
    one's is learnt or built again: every reader of a praxicon's versioned files (the index,
    the descriptions file, the descriptions in it, the build's check of its folder) tells them
    apart here, so that they cannot come to disagree on which is which.

    Examples
    --------
    >>> written_by(3, 3), written_by(4, 3), written_by(2, 3)
    (None, 'later', 'earlier')
    >>> written_by(None, 3), written_by("4", 3), written_by(4.0, 3)
    ('earlier', 'earlier', 'earlier')
    """
    if said == version:
        return None
    # a bool is an int to Python, and True > 0: no psgs writes a version as true
    return "later" if type(said) is int and said > version else "earlier"


def shown(value) -> str:
    """``value`` as a JSON reader's error shows it: its ``repr``, or its type's name when
    that is longer than 40 characters (a list of thousands of numbers stays one short line).

    Examples
    --------
    >>> shown(-1), shown("x"), shown(list(range(100)))
    ('-1', "'x'", 'list')
    """
    text = repr(value)
    return text if len(text) <= 40 else type(value).__name__


def bad_item(key: str, items, good, expected: str) -> str | None:
    """The words of an error naming the first of ``items`` (a list; or a JSON object, its
    values named by their keys) that is not ``good(item)``: ``'KEY' must be EXPECTED: value N
    is V`` (N counted from 1), or ``... value of 'NAME' is V``; ``None`` when every item is.

    Every JSON reader of the praxicon words a bad item of a list or object so: the item and
    its place, not the whole value, which is most often too long to show.

    Examples
    --------
    >>> bad_item("durations", [0.5, 0.5, 0.5, -1], lambda v: v > 0, "numbers above 0")
    "'durations' must be numbers above 0: value 4 is -1"
    >>> bad_item("names", {"a.rx": "a_rx", "a.ry": 3}, lambda v: isinstance(v, str),
    ...          "channel -> text")
    "'names' must be channel -> text: value of 'a.ry' is 3"
    >>> bad_item("names", [], None, "text") is None
    True
    """
    places = items.items() if isinstance(items, dict) else enumerate(items, 1)
    for place, item in places:
        if not good(item):
            where = f"value of {place!r}" if isinstance(items, dict) else f"value {place}"
            return f"{key!r} must be {expected}: {where} is {shown(item)}"
    return None


def one_each(keys, names, kind: str, each: str) -> str | None:
    """What is wrong with ``keys`` (a JSON object's, each a ``kind``) that must be one for
    each of ``names`` (each an ``each``): the first name without one, else the first key of
    no name; ``None`` when they match.

    Examples
    --------
    >>> one_each(["a.rx", "a.rq"], ["a.rx", "a.ry"], "morpheme", "channel")
    "its morphemes are not one per channel: channel 'a.ry' has none"
    >>> one_each(["a.rx", "a.rq"], ["a.rx"], "morpheme", "channel")
    "its morphemes are not one per channel: 'a.rq' is no channel of it"
    """
    keys, names = set(keys), list(names)
    if keys == set(names):
        return None
    start = f"its {kind}s are not one per {each}: "
    missing = next((n for n in names if n not in keys), None)
    if missing is not None:
        return f"{start}{each} {shown(missing)} has none"
    named = set(names)
    return f"{start}{shown(min(k for k in keys if k not in named))} is no {each} of it"


def _is_number(value) -> bool:
    return not isinstance(value, bool) and isinstance(value, (int, float))


class Fields:
    """Typed access to one JSON object; every error (``error``, a one-line exception class)
    names ``where`` and the key.

    Examples
    --------
    >>> Fields({"a": 1}, "x.json", "record", ValueError).number("a")
    1
    >>> Fields({"a": "1"}, "x.json", "record", ValueError).number("a")
    Traceback (most recent call last):
    ...
    ValueError: x.json: 'a' must be a number, not '1'
    """

    def __init__(self, value, where: str, what: str, error: type[Exception]):
        self.error = error
        if not isinstance(value, dict):
            raise error(f"{where}: not a praxicon {what} (a JSON object expected, "
                        f"not {type(value).__name__})")
        self.value, self.where, self.what = value, where, what

    def _bad(self, key: str, expected: str):
        return self.error(f"{self.where}: {key!r} must be {expected}, not "
                          f"{shown(self.value[key])}")

    def items(self, key: str, good, expected: str) -> None:
        """An error naming ``key`` and its first item (of a list or a JSON object) that is not
        ``good`` (:func:`bad_item`), unless every item is.

        Examples
        --------
        >>> f = Fields({"names": {"a.rx": "a_rx", "a.ry": 3}}, "x.json", "record", ValueError)
        >>> f.items("names", lambda v: isinstance(v, str), "channel -> text")
        Traceback (most recent call last):
        ...
        ValueError: x.json: 'names' must be channel -> text: value of 'a.ry' is 3
        """
        problem = bad_item(key, self.value.get(key) or (), good, expected)  # absent: none
        if problem:
            raise self.error(f"{self.where}: {problem}")

    def bounded(self, key: str, got, low: float, strict: bool = False):
        """``got``, the number or numbers read at ``key``, when each is finite and at least
        ``low`` (above it when ``strict``; ``None`` passes), else the error naming the key.

        Examples
        --------
        >>> f = Fields({"d": [0.5, 0.0]}, "x.json", "morpheme", ValueError)
        >>> f.bounded("d", f.numbers("d"), 0, strict=True)
        Traceback (most recent call last):
        ...
        ValueError: x.json: 'd' must be numbers above 0 and finite: value 2 is 0.0
        """
        def good(v) -> bool:
            return (v > low if strict else v >= low) and v < math.inf

        bound = f"{'above' if strict else 'at least'} {low:g} and finite"
        if isinstance(got, tuple):  # a list: its first number out of bounds is named
            self.items(key, good, f"numbers {bound}")
        elif got is not None and not good(got):
            raise self._bad(key, bound)
        return got

    def need(self, key: str):
        """The value at ``key`` (an error when absent)."""
        if key not in self.value:
            raise self.error(f"{self.where}: not a praxicon {self.what} (no {key!r})")
        return self.value[key]

    def text(self, key: str, optional: bool = False) -> str | None:
        """Text at ``key`` (``None`` when ``optional`` and absent)."""
        value = self.value.get(key) if optional else self.need(key)
        if value is None and optional:
            return None
        if not isinstance(value, str):
            raise self._bad(key, "text")
        return value

    def number(self, key: str, optional: bool = False) -> float | None:
        """A number at ``key`` (``None`` when ``optional`` and absent)."""
        value = self.value.get(key) if optional else self.need(key)
        if value is None and optional:
            return None
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise self._bad(key, "a number")
        return value

    def texts(self, key: str, optional: bool = False) -> tuple[str, ...] | None:
        """A list of text at ``key`` (``None`` when ``optional`` and absent)."""
        value = self.value.get(key) if optional else self.need(key)
        if value is None and optional:
            return None
        if not isinstance(value, list):
            raise self._bad(key, "a list of text")
        self.items(key, lambda v: isinstance(v, str), "a list of text")
        return tuple(value)

    def numbers(self, key: str, optional: bool = False, whole: bool = False):
        """A list of numbers at ``key`` (``None`` when ``optional`` and absent)."""
        value = self.value.get(key) if optional else self.need(key)
        if value is None and optional:
            return None
        expected = "a list of whole numbers" if whole else "a list of numbers"
        if not isinstance(value, list):
            raise self._bad(key, expected)
        self.items(key, lambda v: _is_number(v) and (not whole or isinstance(v, int)),
                   expected)
        return tuple(value)

    def object(self, key: str, optional: bool = False) -> dict | None:
        """A JSON object at ``key`` (``None`` when ``optional`` and absent)."""
        value = self.value.get(key) if optional else self.need(key)
        if value is None and optional:
            return None
        if not isinstance(value, dict):
            raise self._bad(key, "a JSON object")
        return value

    def objects(self, key: str) -> list:
        """A list at ``key`` (``None`` when ``optional`` and absent)."""
        value = self.need(key)
        if not isinstance(value, list):
            raise self._bad(key, "a list")
        return value


class _Object(tuple):
    """A JSON object frozen: its ``(key, value)`` pairs sorted by key."""

    __slots__ = ()


def freeze(value):
    """A JSON value as an immutable one: lists become tuples, objects sorted pairs.

    Examples
    --------
    >>> freeze({"b": [1, 2], "a": {"c": None}})
    (('a', (('c', None),)), ('b', (1, 2)))
    >>> thaw(freeze({"b": [1, 2], "a": {"c": None}}))
    {'a': {'c': None}, 'b': [1, 2]}
    """
    if isinstance(value, dict):
        return _Object((str(k), freeze(v)) for k, v in sorted(value.items()))
    if isinstance(value, (list, tuple)):
        return tuple(freeze(v) for v in value)
    return value


def thaw(value):
    """The JSON value of a frozen one (the inverse of :func:`freeze`)."""
    if isinstance(value, _Object):
        return {k: thaw(v) for k, v in value}
    if isinstance(value, tuple):
        return [thaw(v) for v in value]
    return value


def as_dict(pairs) -> dict:
    """The JSON object of a mapping-like field (``(key, value)`` pairs, values frozen).

    Examples
    --------
    >>> as_dict(()), as_dict(freeze({"a": [1]}))
    ({}, {'a': [1]})
    """
    return {k: thaw(v) for k, v in pairs}


def pairs(value: dict | None) -> tuple:
    """A JSON object (or None) frozen as sorted pairs."""
    return freeze(value or {})


