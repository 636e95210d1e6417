"""Reading the two file forms of an actiongram: text and JSON (:meth:`psgs.Actiongram.from_text`,
:meth:`psgs.Actiongram.from_json`).

One line per string, ``name[@T]: sym sym@D sym@D~X ...``; ``%`` directive lines for the
extras and for ``%keep_repeats``; ``#`` comments. The grammar is in the docstring of
:mod:`psgs.actiongram` and in docs/actiongram.md.
"""

from __future__ import annotations

import itertools
import json
import re

from .._foundation.text import character_name, split_lines
from ..errors import FormatError, ValidationError
from ._checks import (_bad_duration, _bad_name, _bad_symbol, _finite, _read_number, _shown,
                      _times_problem)
from ._extras import DIRECTIVE as _DIRECTIVE
from ._extras import _bad_displacement, _merge, _merge_displacements, default_actuator
from ._extras import read_directive as _read_directive

__all__: list[str] = []  # private: Actiongram.from_text is the interface

#: the directive line that keeps equal neighbours apart (``Actiongram.keep_repeats``)
KEEP_REPEATS = "%keep_repeats"
#: what a JSON document says it is (``Actiongram.to_json`` writes it)
_FORMAT = "psgs-actiongram"

_COMMENT = re.compile(r"(?:^|\s)#")
_TOKEN = re.compile(r"\S+")


def strip_comment(line: str, source: str, line_no: int) -> str:
    """``line`` without its comment.

    A line whose first non-blank character is ``#`` is a comment; elsewhere a comment starts
    at a ``#`` after white space that is followed by white space or ends the line. A token
    that starts with ``#`` and goes on (``1 #4 5``) is neither a symbol (none starts with
    ``#``) nor a comment, so it is an error at its place rather than a silent cut.
    """
    match = _COMMENT.search(line)
    if match is None:
        return line
    at = match.end() - 1  # the '#'
    if not line[:at].strip():
        return ""
    after = line[at + 1:at + 2]
    if after and not after.isspace():
        token = line[at:].split(None, 1)[0]
        raise FormatError(f"{_shown(token)} starts with '#': a symbol cannot, and a comment "
                          f"needs white space after its '#' ('# note')", source=source,
                          line=line_no, column=at + 1)
    return line[:at]


# every control character but the tab, and the characters str.splitlines breaks lines at
# (lines break at "\n" only, so an error names the line an editor shows)
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f\x85\u2028\u2029]")


def read_text(cls, text: str, source: str):
    """The actiongram (of class ``cls``) that ``text`` holds; FormatError at its place."""
    if not isinstance(text, str):
        raise ValidationError(f"from_text reads a str, not {type(text).__name__}")
    names, symbol_rows, duration_rows, origins = [], [], [], []
    disp_rows: list[tuple[float, ...] | None] = []
    owner: dict[str, str] = {}
    edges: list[tuple[str, str | None]] = []
    where: dict[str, int] = {}
    # (line, column) of each string, each %parent edge and each %actuator entry, in order
    string_places: list[tuple[int, int]] = []
    edge_places: list[tuple[int, int]] = []
    owner_places: list[tuple[int, int]] = []
    keep_repeats = False
    for line_no, raw in enumerate(split_lines(text), start=1):
        line = strip_comment(raw, source, line_no)
        control = _CONTROL.search(line)
        if control:  # no symbol or name may hold one (a NUL would reach the grammar unseen)
            raise FormatError(f"control character {character_name(control.group())} in the text",
                              source=source, line=line_no, column=control.start() + 1)
        if not line.strip():
            continue
        if line.strip() == KEEP_REPEATS:
            keep_repeats = True
            continue
        if _DIRECTIVE.match(line):
            counts = len(owner), len(edges)
            _read_directive(line, source, line_no, owner, edges)
            place = (line_no, len(line) - len(line.lstrip()) + 1)
            owner_places.extend([place] * (len(owner) - counts[0]))
            edge_places.extend([place] * (len(edges) - counts[1]))
            continue
        head, colon, body = line.partition(":")
        if not colon:
            col = len(raw) - len(raw.lstrip()) + 1
            raise FormatError("expected 'name: symbols' (no ':' on this line)",
                              source=source, line=line_no, column=col)
        name_col = len(head) - len(head.lstrip()) + 1
        name_text = head.strip()
        name, at, origin_text = name_text.partition("@")
        origin = 0.0
        if at:
            origin = _read_number(origin_text, allow_nonpositive=True)
            if origin is None:
                raise FormatError(f"start time {_shown(origin_text)} is not a number",
                                  source=source, line=line_no,
                                  column=name_col + len(name) + 1)
        problem = _bad_name(name)
        if problem:
            raise FormatError(problem, source=source, line=line_no, column=name_col)
        if name in where:
            raise FormatError(f"actuator {_shown(name)} already given on line {where[name]}",
                              source=source, line=line_no, column=name_col)
        where[name] = line_no
        string_places.append((line_no, name_col))
        syms, durs, disps = [], [], []
        offset = len(head) + 1
        for match in _TOKEN.finditer(body):
            token, col = match.group(), offset + match.start() + 1
            sym, at, dur_text = token.partition("@")
            if ":" in token:
                raise FormatError(f"symbol {_shown(token)} contains ':'", source=source,
                                  line=line_no, column=col)
            if not sym:
                raise FormatError(f"{_shown(token)} has a duration but no symbol",
                                  source=source,
                                  line=line_no, column=col)
            dur = 1.0
            if at and "~" in dur_text:  # sym@D~X: a duration, then a signed displacement
                dur_text, _, disp_text = dur_text.partition("~")
                disp = _read_number(disp_text, allow_nonpositive=True)
                if disp is None:
                    raise FormatError(
                        f"unknown displacement syntax {_shown('~' + disp_text)} (write "
                        f"sym@D~X with X a number)", source=source, line=line_no,
                        column=col + len(sym) + 1 + len(dur_text))
                disps.append(disp)
            if at:
                dur = _read_number(dur_text, allow_nonpositive=True)
                if dur is not None and dur <= 0:
                    raise FormatError(f"duration {_shown(dur_text)} must be positive",
                                      source=source, line=line_no, column=col + len(sym) + 1)
                if dur is None:
                    raise FormatError(
                        f"unknown duration syntax {_shown('@' + dur_text)} (write sym@D "
                        f"with D a positive number)", source=source, line=line_no,
                        column=col + len(sym))
            syms.append(sym)
            durs.append(dur)
            if len(disps) not in (0, len(syms)):
                raise FormatError("give a displacement (sym@D~X) for every symbol of a "
                                  "string or for none", source=source, line=line_no,
                                  column=col)
        names.append(name)
        symbol_rows.append(tuple(syms))
        duration_rows.append(tuple(durs))
        origins.append(origin)
        disp_rows.append(tuple(disps) if disps else None)
    for name, (line_no, column) in zip(owner, owner_places):
        if name not in where:
            raise FormatError(f"%actuator names unknown string {_shown(name)}",
                              source=source, line=line_no, column=column)
    actuators = tuple(owner.get(n, default_actuator(n)) for n in names)

    def build(strings: slice, skeleton: int):
        """The actiongram of the ``strings`` and the first ``skeleton`` parent lines."""
        return cls(tuple(names[strings]), tuple(symbol_rows[strings]),
                   tuple(duration_rows[strings]), tuple(origins[strings]),
                   tuple(disp_rows[strings]), actuators[strings], tuple(edges[:skeleton]),
                   keep_repeats)

    try:
        return build(slice(None), len(edges))
    except FormatError as exc:  # found by the checks of the whole value, which name no line
        error = _placed(exc, build, string_places, edge_places, source)
        raise _at_symbol(error, text, names, (symbol_rows, duration_rows, origins),
                         keep_repeats, string_places, source) from None


def _at_symbol(error: FormatError, text: str, names: list[str], rows: tuple[list, list, list],
               keep_repeats: bool, string_places: list[tuple[int, int]],
               source: str) -> FormatError:
    """``error``, placed at a string's name, moved to the column of the symbol at fault when
    it is that string's first bad symbol that the checks refused, or the (first) symbol of
    the segment whose duration vanishes beside its start time.

    ``rows`` are the symbols, durations and start times read, one entry per string. The
    columns of the symbols are not kept while reading (one number per symbol of a large
    file): the line is split again, here, on the error's way out.
    """
    if error.line is None:
        return error
    for k, (line_no, column) in enumerate(string_places):
        if (line_no, column) == (error.line, error.column):
            break
    else:
        return error  # a %parent line's error
    symbols, durations, origin = (row[k] for row in rows)
    j, problem = next(((j, p) for j, sym in enumerate(symbols)
                       if (p := _bad_symbol(sym)) is not None), (None, None))
    if j is not None:
        problem = f"string {_shown(names[k])}: {problem}"
    else:  # every symbol is good: the one whose duration vanishes, if that is the error
        segments = tuple(durations) if keep_repeats else _merge(symbols, durations)[1]
        j, problem = _times_problem(names[k], origin, segments, symbols, keep_repeats) \
            or (None, None)
    if j is None or error.message != problem:
        return error  # the string's name, its durations or its times: the name's place
    line = strip_comment(split_lines(text)[line_no - 1], source, line_no)
    head = line.partition(":")[0]
    token = next(itertools.islice(_TOKEN.finditer(line, len(head) + 1), j, None))
    return FormatError(error.message, source=source, line=line_no, column=token.start() + 1)


def _first_refused(count: int, build) -> tuple[int, FormatError] | None:
    """The least ``k`` (1 to ``count``) for which ``build(k)`` raises, with its error; None
    when ``build(count)`` does not. Once refused, every longer prefix is."""
    try:
        build(count)
        return None
    except FormatError as exc:
        refused, error = count, exc
    low = 0  # build(low) is accepted, build(refused) is not
    while refused - low > 1:
        middle = (low + refused) // 2
        try:
            build(middle)
            low = middle
        except FormatError as exc:
            refused, error = middle, exc
    return refused, error


def _placed(error: FormatError, build, string_places: list[tuple[int, int]],
            edge_places: list[tuple[int, int]], source: str) -> FormatError:
    """``error``, the whole actiongram's, as the error of the first line that
    ``build(strings, skeleton)`` refuses, at that line.

    A string's checks read that string alone, so each is built alone, in order; the
    skeleton's read its parent lines together (a cycle takes several), so the first line at
    fault ends the shortest run of them that is refused.
    """
    for k, (line, column) in enumerate(string_places):
        try:
            build(slice(k, k + 1), 0)
        except FormatError as exc:
            return FormatError(exc.message, source=source, line=line, column=column)
    found = _first_refused(len(edge_places), lambda k: build(slice(0), k))
    if found is None:  # every part accepted alone (not met): the file as a whole
        return FormatError(error.message, source=source)
    k, error = found
    line, column = edge_places[k - 1]
    return FormatError(error.message, source=source, line=line, column=column)


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
        message, places = _fault(exc.message, build, data["strings"], names, edges,
                                 keep_repeats)
        raise _Misplaced(message, *places) from None


def _fault(message: str, build, items: list, names: list, edges: tuple,
           keep_repeats: bool) -> tuple[str, list[tuple[tuple, bool]]]:
    """The constructor's error ``message`` and its places (none when not found).

    A string's checks read that string alone, so the first string that, built alone, raises
    this very message is the one (when the whole is refused for another string's fault, an
    earlier string may be refused alone, for another reason); two strings of one name are
    refused only together; a skeleton's entries are read together (a cycle takes several),
    so the entry at fault ends the shortest run of them that is refused, and the message
    is that run's (with two cycles, the whole's may name the other one).
    """
    for k, item in enumerate(items):
        try:
            build(slice(k, k + 1), 0)
        except FormatError as exc:
            if exc.message == message:
                return message, _string_fault(item, ("strings", k), keep_repeats)
    seen: set[str] = set()
    for k, name in enumerate(names):
        if not isinstance(name, str):  # refused as a name, above
            continue
        if name in seen:
            return message, [(("strings", k, "name"), False), (("strings", k), False)]
        seen.add(name)
    found = _first_refused(len(edges), lambda j: build(slice(0), j))
    if found is None:
        return message, []
    child, _ = edges[found[0] - 1]
    # a bad actuator is the entry's key; anything else (a bad parent, itself as its parent, a
    # parent that closes a cycle) is its value
    return found[1].message, [(("skeleton", child), _bad_name(child) is not None)]


def _string_fault(item: dict, here: tuple, keep_repeats: bool) -> list[tuple[tuple, bool]]:
    """The places of the first fault of the string object ``item`` (at path ``here``), found
    by the constructor's checks in the constructor's order; each ends with the object."""
    def at(*tails: tuple) -> list[tuple[tuple, bool]]:
        return [(here + tail, False) for tail in tails] + [(here, False)]

    if _bad_name(item.get("name")):
        return at(("name",))
    syms = item["symbols"]
    durs = item.get("durations", [1.0] * len(syms))
    if len(durs) != len(syms):
        return at(("durations",))
    for j, sym in enumerate(syms):
        if _bad_symbol(sym):
            return at(("symbols", j))
    for j, dur in enumerate(durs):
        if _bad_duration(dur):
            return at(("durations", j))
    start = item.get("start", 0.0)
    if isinstance(start, bool) or not isinstance(start, (int, float)) or not _finite(start):
        return at(("start",))
    # the segments the constructor times, added as it adds them: runs of equal neighbours
    # merged (unless kept), each known by its first symbol
    firsts = [j for j in range(len(syms)) if keep_repeats or not j or syms[j] != syms[j - 1]]
    segments = tuple(map(float, durs)) if keep_repeats else _merge(syms, durs)[1]
    if not _finite(float(start) + sum(segments)):
        return at(("durations",), ("start",))
    t = float(start)
    for first, dur in zip(firsts, segments):
        if t + dur == t:  # a duration that vanishes beside its start time
            return at(("durations", first), ("start",))
        t += dur
    disps = item.get("displacements")
    if disps is not None:
        if len(disps) != len(syms):
            return at(("displacements",))
        bad = [j for j, x in enumerate(disps) if _bad_displacement(x)]
        if bad:
            return at(("displacements", bad[0]))
        merged = disps if keep_repeats else _merge_displacements(syms, disps)
        if not all(map(_finite, merged)):  # each finite, a merged run's sum may not be
            return at(("displacements",))
    return at(("actuator",), ("name",))


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
