"""The JSON form of an actiongram, read and written (:meth:`psgs.Actiongram.from_json`,
:meth:`psgs.Actiongram.to_json`).

``{"format": "psgs-actiongram", "version": 1, "strings": [{"name", "start", "symbols",
"durations", "displacements", "actuator"}, ...], "skeleton": {...}, "keep_repeats": true}``;
an error names the line and column of the value (or key) at fault. docs/actiongram.md
describes the form.
"""

from __future__ import annotations

import json
import re

from ..errors import FormatError, ValidationError
from ._checks import _bad_name, _shown
from ._extras import default_actuator
from ._faults import first_fault, first_refused, strings_of

__all__: list[str] = []  # private: Actiongram.from_json and to_json are the interface

#: what a JSON document says it is (``Actiongram.to_json`` writes it)
_FORMAT = "psgs-actiongram"

#: the keys a document and each of its string objects may have (what ``to_json`` writes): any
#: other is a misspelling (``"duration"``) that would leave its data unread
_DOCUMENT_KEYS = ("format", "version", "strings", "skeleton", "keep_repeats")
_STRING_KEYS = ("name", "start", "symbols", "durations", "displacements", "actuator")


class _KeyTwice(Exception):
    """A JSON object gives one key twice (``json.loads`` would keep the last silently)."""


class _Misplaced(Exception):
    """An error of the decoded document, with where it is: places to try in turn, each
    ``(path, key)``, the path of a value (``("strings", 3, "durations")``) and whether its key
    is meant rather than the value. Placed in the text only once raised, so that a good
    document is read once."""

    def __init__(self, message: str, *places: tuple[tuple, bool]) -> None:
        super().__init__(message)
        self.message = message
        self.places = places


def _unique_keys(pairs: list[tuple[str, object]]) -> dict[str, object]:
    out: dict[str, object] = {}
    for key, value in pairs:
        if key in out:
            raise _KeyTwice(key)
        out[key] = value
    return out


def _unknown_key(data: dict, known: tuple[str, ...], where: str, path: tuple) -> None:
    extra = [k for k in data if k not in known]
    if extra:
        raise _Misplaced(f"{where} has unknown key {_shown(extra[0])} (its keys: "
                         f"{', '.join(known)})", (path + (extra[0],), True))


def read_json(cls, text: str, source: str):
    """The actiongram (of class ``cls``) that the JSON ``text`` holds; FormatError if none,
    at the line and column of the value (or key) at fault."""
    if not isinstance(text, (str, bytes, bytearray)):  # what json.loads reads
        raise ValidationError(f"from_json reads a str or bytes, not {type(text).__name__}")
    try:
        data = json.loads(text, object_pairs_hook=_unique_keys)
    except _KeyTwice as exc:  # the second of the two, in the first object to close with one
        line, column = _json_place(text, None) or (None, None)
        raise FormatError(f"key {_shown(exc.args[0])} is given twice in one object",
                          source=source, line=line, column=column) from None
    except json.JSONDecodeError as exc:
        raise FormatError(f"not JSON: {exc.msg}", source=source, line=exc.lineno,
                          column=exc.colno) from None
    except RecursionError:  # '[' * 100000: the decoder recurses per nesting level
        raise FormatError("not JSON that can be read: nested too deeply", source=source,
                          line=1, column=1) from None
    except ValueError as exc:  # an integer of thousands of digits (Python's int limit)
        raise FormatError(f"not JSON that can be read: {str(exc).split(':')[0]}",
                          source=source) from None
    try:
        return _read_document(cls, data)
    except _Misplaced as exc:
        found = (_json_place(text, path, key) for path, key in exc.places)
        line, column = next((place for place in found if place), (None, None))
        raise FormatError(exc.message, source=source, line=line, column=column) from None


def _read_document(cls, data: object):
    """The actiongram of the decoded JSON ``data``; _Misplaced for an error."""
    if not isinstance(data, dict) or not isinstance(data.get("strings"), list):
        raise _Misplaced("expected a JSON object with a 'strings' list",
                         (("strings",), False), ((), False))
    _unknown_key(data, _DOCUMENT_KEYS, "the document", ())
    # another format, or a later version of this one, may hold what this reader would drop
    said = data.get("format", _FORMAT)
    if said != _FORMAT:
        raise _Misplaced(f"'format' is {_shown(said)}, not {_FORMAT!r}", (("format",), False))
    version = data.get("version", 1)
    if isinstance(version, bool) or version != 1:
        raise _Misplaced(f"'version' is {_shown(version)}: this reader knows version 1",
                         (("version",), False))
    names, symbol_rows, duration_rows, origins = [], [], [], []
    disp_rows: list[tuple | None] = []
    actuator_rows: list[object] = []
    for k, item in enumerate(data["strings"]):
        here = ("strings", k)
        if not isinstance(item, dict) or not isinstance(item.get("symbols"), list):
            raise _Misplaced(f"strings[{k}] must be an object with 'name' and 'symbols'",
                             (here + ("symbols",), False), (here, False))
        _unknown_key(item, _STRING_KEYS, f"strings[{k}]", here)
        syms = item["symbols"]
        durs = item.get("durations", [1.0] * len(syms))
        if not isinstance(durs, list):
            raise _Misplaced(f"strings[{k}].durations must be a list",
                             (here + ("durations",), False))
        disps = item.get("displacements")
        if disps is not None and not isinstance(disps, list):
            raise _Misplaced(f"strings[{k}].displacements must be a list",
                             (here + ("displacements",), False))
        names.append(item.get("name"))
        symbol_rows.append(tuple(syms))
        duration_rows.append(tuple(durs))
        origins.append(item.get("start", 0.0))
        disp_rows.append(None if disps is None else tuple(disps))
        name = item.get("name")
        actuator_rows.append(item["actuator"] if "actuator" in item
                             else default_actuator(name) if isinstance(name, str) else name)
    skeleton = data.get("skeleton", {})
    keep_repeats = data.get("keep_repeats", False)
    if not isinstance(keep_repeats, bool):
        raise _Misplaced("'keep_repeats' must be true or false", (("keep_repeats",), False))
    if not isinstance(skeleton, dict):
        raise _Misplaced("'skeleton' must be an object {actuator: parent or null}",
                         (("skeleton",), False))
    edges = tuple(skeleton.items())

    def build(strings: slice, skeleton: int):
        """The actiongram of the ``strings`` and the first ``skeleton`` entries."""
        return cls(tuple(names[strings]), tuple(symbol_rows[strings]),
                   tuple(duration_rows[strings]), tuple(origins[strings]),
                   tuple(disp_rows[strings]), tuple(actuator_rows[strings]), edges[:skeleton],
                   keep_repeats)

    try:
        return build(slice(None), len(edges))
    except FormatError as exc:  # the checks of the whole value, which know no path
        strings = strings_of(names, symbol_rows, duration_rows, origins, keep_repeats,
                             disp_rows, actuator_rows)
        message, places = _fault(exc.message, strings, lambda k: build(slice(0), k), edges)
        raise _Misplaced(message, *places) from None


def _fault(message: str, strings, build_skeleton,
           edges: tuple) -> tuple[str, list[tuple[tuple, bool]]]:
    """The constructor's error ``message`` and its places (none when not found).

    A string's fault is the first that the constructor's checks find
    (:func:`~psgs.actiongram._faults.first_fault` over ``strings``, as read), at the values
    its fields name, then at the string's object. A skeleton's entries are read together (a
    cycle takes several), so the entry at fault ends the shortest run of them that
    ``build_skeleton`` refuses, and the message is that run's (with two cycles, the whole's
    may name the other one).
    """
    found = first_fault(strings)
    if found is not None and found[1].message == message:
        k, fault = found
        here = ("strings", k)
        return message, [(here + field, False) for field in fault.fields] + [(here, False)]
    refused = first_refused(len(edges), build_skeleton)
    if refused is None:
        return message, []
    child, _ = edges[refused[0] - 1]
    # a bad actuator is the entry's key; anything else (a bad parent, itself as its parent, a
    # parent that closes a cycle) is its value
    return refused[1].message, [(("skeleton", child), _bad_name(child) is not None)]


# one JSON token after white space: punctuation, a string, or a number or literal
_JSON_TOKEN = re.compile(r'[ \t\n\r]*([\[\]{}:,]|"[^"\\]*(?:\\.[^"\\]*)*"|[^ \t\n\r\[\]{}:,"]+)')


def _json_tokens(text: str):
    """The matches of :data:`_JSON_TOKEN` in ``text``, each where the one before ends, up to
    the first place no token follows (the white space that ends a document).

    Not ``finditer``: where no token follows, it tries again at every later character, each
    time reading the white space to its end, so a document with 20,000 spaces after it took
    6 s to place an error (quadratic); one token after another reads each character once.
    """
    at = 0
    while (match := _JSON_TOKEN.match(text, at)) is not None:
        yield match
        at = match.end()  # past at least one character: the group is never empty


def _json_place(text: str | bytes, want: tuple | None,
                key: bool = False) -> tuple[int, int] | None:
    """The (line, column) in the JSON ``text`` of the value at path ``want`` (of its key when
    ``key``), counted as ``json.JSONDecodeError`` counts them; None when there is none.

    With ``want`` None: the second of two equal keys in the first object to close with one,
    the object ``json.loads`` hands its ``object_pairs_hook`` first (inner before outer).
    The text has been decoded up to there, so it is JSON: a walk of its tokens suffices.
    """
    if not isinstance(text, str):  # decoded as json.loads decodes bytes
        text = bytes(text).decode(json.detect_encoding(text), "surrogatepass")
    # per open object or array: [its path, its current key or index, its keys, the offset of
    # its first repeated key]
    stack: list[list] = []
    want_key = False
    for match in _json_tokens(text):
        token, at = match.group(1), match.start(1)
        if token in ",:":
            if token == "," and isinstance(stack[-1][1], int):
                stack[-1][1] += 1
            want_key = token == "," and not isinstance(stack[-1][1], int)
            continue
        if token in "]}":
            closed, want_key = stack.pop(), False  # ('{}': no key came)
            if want is None and closed[3] is not None:
                at = closed[3]
                break
            continue
        if want_key:  # a key: the path of the value after it
            top, want_key = stack[-1], False
            top[1] = json.loads(token)
            if top[1] in top[2] and top[3] is None:
                top[3] = at
            top[2].add(top[1])
            if key and top[0] + (top[1],) == want:
                break
            continue
        path = stack[-1][0] + (stack[-1][1],) if stack else ()
        if not key and path == want:
            break
        if token == "{":
            stack.append([path, None, set(), None])
            want_key = True
        elif token == "[":
            stack.append([path, 0, set(), None])
    else:
        return None
    return text.count("\n", 0, at) + 1, at - text.rfind("\n", 0, at)


def write_json(actiongram) -> str:
    """The JSON form of ``actiongram``, which :func:`read_json` reads back to an equal value."""
    ag = actiongram
    strings = []
    for n, s, d, o, x, a in zip(ag.names, ag.symbols, ag.segment_durations, ag.origins,
                                ag.segment_displacements, ag.string_actuators):
        item: dict[str, object] = {"name": n, "start": o, "symbols": list(s),
                                   "durations": list(d)}
        if x is not None:
            item["displacements"] = list(x)
        if a != default_actuator(n):
            item["actuator"] = a
        strings.append(item)
    data: dict[str, object] = {"format": _FORMAT, "version": 1, "strings": strings}
    if ag.skeleton_edges:
        data["skeleton"] = dict(ag.skeleton_edges)
    if ag.keep_repeats:
        data["keep_repeats"] = True
    return json.dumps(data)
