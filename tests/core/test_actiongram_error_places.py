"""Errors of the actiongram readers name the line and column of what is at fault: a value or a
key of a JSON document, a cell of a CSV events file.

Each test writes a good file, spoils one thing in it, and checks that the error's place is
where the spoilt text starts, however the file is laid out.
"""

from __future__ import annotations

import json
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import Actiongram, FormatError
from psgs.actiongram import read_events_csv

#: a value found nowhere else in a document or a table
MARK = "MUTATED"
#: text no symbol, name or actuator may be (white space), found nowhere else either
BAD = "MUT ATED"
#: a negative number found nowhere else
NEGATIVE = -987654.5


def place_of(text: str, offset: int) -> tuple[int, int]:
    """(line, column) of ``offset``, counted as json.JSONDecodeError counts them."""
    return text.count("\n", 0, offset) + 1, offset - text.rfind("\n", 0, offset)


# -- JSON --------------------------------------------------------------------------------------
# the strategies documents() draws from, made once: hypothesis validates a strategy and works
# out its properties the first time it draws from it, which for strategies made afresh in
# every example cost more than the drawing (they draw the same either way)
_NAMES = st.lists(st.sampled_from(["a", "knee.rx", "knee.ry", "hip", "\u00e9.x"]), min_size=1,
                  max_size=4, unique=True)
_COUNTS = st.integers(1, 5)
_SYMBOLS = {n: st.lists(st.sampled_from(["B", "G", "R", "x1"]), min_size=n, max_size=n)
            for n in range(1, 6)}
_DURATIONS = {n: st.lists(st.sampled_from([1, 0.5, 2.25]), min_size=n, max_size=n)
              for n in range(1, 6)}
_STARTS = st.sampled_from([0, 1.5, 10])
_DISPLACEMENTS = {n: st.lists(st.sampled_from([0, 1, -2.5]), min_size=n, max_size=n)
                  for n in range(1, 6)}
_SKELETONS = st.sampled_from([{}, {"knee": "hip", "hip": None}])


@st.composite
def documents(draw):
    """A good document, decoded: what ``to_json`` writes for a small actiongram."""
    names = draw(_NAMES)
    strings, durations, starts, displacements = {}, {}, {}, {}
    for name in names:
        count = draw(_COUNTS)
        strings[name] = draw(_SYMBOLS[count])
        durations[name] = draw(_DURATIONS[count])
        starts[name] = draw(_STARTS)
        if draw(st.booleans()):
            displacements[name] = draw(_DISPLACEMENTS[count])
    ag = Actiongram.from_strings(strings, durations, starts, displacements=displacements,
                                 skeleton=dict(draw(_SKELETONS)), keep_repeats=draw(st.booleans()))
    return json.loads(ag.to_json())


def with_key(mapping: dict, key: str, value: object, at: int) -> dict:
    """``mapping`` with ``key`` put in at position ``at`` of its keys."""
    items = list(mapping.items())
    return dict(items[:at] + [(key, value)] + items[at:])


# what is spoilt in string k (symbol, duration or displacement j): the spoilt value, the
# words of the error
STRING_SPOILS = {
    "durations": (MARK, "strings[{k}].durations must be a list"),
    "displacements": (MARK, "strings[{k}].displacements must be a list"),
    "symbols": (MARK, "strings[{k}] must be an object with 'name' and 'symbols'"),
    "start": (MARK, "start time must be a finite number"),
    "name": (BAD, f"actuator name {BAD!r} holds U+0020 SPACE (character 4): it must have no "
                  f"white space"),
    "actuator": (BAD, f"actuator {BAD!r}:"),
    "symbol": (BAD, f"symbol {BAD!r} holds U+0020 SPACE (character 4): it must have no white "
                    f"space"),
    "duration": (NEGATIVE, f"a duration must be positive and finite, not {NEGATIVE}"),
    "displacement": (MARK, f"a displacement must be a number, not {MARK!r}"),
}
DOCUMENT_SPOILS = {
    "format": (MARK, f"'format' is {MARK!r}, not 'psgs-actiongram'"),
    "version": (MARK, f"'version' is {MARK!r}: this reader knows version 1"),
    "keep_repeats": (MARK, "'keep_repeats' must be true or false"),
    "skeleton": (MARK, "'skeleton' must be an object"),
}

_KINDS = st.sampled_from([*STRING_SPOILS, *DOCUMENT_SPOILS, "unknown key",
                          "document's unknown key", "key twice", "document's key twice",
                          "name twice"])
_INDENTS = st.sampled_from([None, 0, 1, 2, 4, "\t"])
_SEPARATORS = st.sampled_from([None, (",", ":"), (" , ", " : ")])


@st.composite
def spoilt_documents(draw):
    """(document text, the spoilt text, its offset in the document, words of the error)."""
    data = draw(documents())
    items = data["strings"]
    k = draw(st.integers(0, len(items) - 1))
    item = items[k]
    j = draw(st.integers(0, len(item["symbols"]) - 1))
    kind = draw(_KINDS)
    replace = None  # (what the mark stands for in the text)
    if kind in STRING_SPOILS:
        value, words = STRING_SPOILS[kind]
        words = words.format(k=k)
        if kind in ("symbol", "duration"):
            item[kind + "s"][j] = value
        elif kind == "displacement":
            item["displacements"] = item.get("displacements") or [0] * len(item["symbols"])
            item["displacements"][j] = value
        else:
            item[kind] = value
    elif kind in DOCUMENT_SPOILS:
        value, words = DOCUMENT_SPOILS[kind]
        data[kind] = value
    elif kind in ("unknown key", "document's unknown key"):
        where = item if kind == "unknown key" else data
        spoilt = with_key(where, MARK, 1, draw(st.integers(0, len(where))))
        if where is item:
            items[k] = spoilt
        else:
            data = spoilt
        words = f"has unknown key {MARK!r}"
    elif kind in ("key twice", "document's key twice"):
        # the mark is a key the object has, given again after it: the second is at fault
        where = item if kind == "key twice" else data
        keys = list(where)
        first = draw(st.integers(0, len(keys) - 1))
        spoilt = with_key(where, MARK, 0, draw(st.integers(first + 1, len(keys))))
        if where is item:
            items[k] = spoilt
        else:
            data = spoilt
        replace = json.dumps(keys[first])
        words = f"key {keys[first]!r} is given twice in one object"
    else:  # a name an earlier string has
        k = draw(st.integers(0, len(items) - 1).filter(bool)) if len(items) > 1 else 0
        if k == 0:  # one string: a name twice is not to be had, spoil a name instead
            items[0]["name"] = BAD
            value, words = BAD, "actuator name"
        else:
            items[k]["name"] = MARK
            replace = json.dumps(items[0]["name"], ensure_ascii=False)
            words = f"two strings are named {items[0]['name']!r}"
    indent = draw(_INDENTS)
    separators = draw(_SEPARATORS)
    text = json.dumps(data, indent=indent, separators=separators,
                      ensure_ascii=draw(st.booleans()))
    marks = [json.dumps(m) for m in (MARK, BAD, NEGATIVE)]
    token = next(m for m in marks if m in text)
    assert text.count(token) == 1
    offset = text.index(token)
    if replace is not None:
        text = text.replace(token, replace)
        token = replace
    return text, token, offset, words


@settings(max_examples=250, deadline=None)
@given(spoilt_documents(), st.booleans())
def test_a_json_error_names_the_line_and_column_of_the_value_or_key_at_fault(case, as_bytes):
    text, token, offset, words = case
    try:
        Actiongram.from_json(text.encode() if as_bytes else text, source="f.json")
    except FormatError as error:
        assert words in error.message, (error.message, words)
        assert (error.line, error.column) == place_of(text, offset), (str(error), text)
        line = text.split("\n")[error.line - 1]
        assert line[error.column - 1:].startswith(token)
        assert str(error).startswith(f"f.json:{error.line}:{error.column}: ")
    else:
        raise AssertionError(f"read: {text}")


@settings(max_examples=30, deadline=None)
@given(documents(), st.sampled_from([None, 0, 2, "\t"]))
def test_good_documents_read_as_ever_however_laid_out(data, indent):
    ag = Actiongram.from_json(json.dumps(data))
    assert Actiongram.from_json(json.dumps(data, indent=indent)) == ag
    assert Actiongram.from_json(ag.to_json()) == ag


def test_a_string_refused_by_the_constructor_is_placed_at_its_object_when_no_value_is_at_fault():
    with_no_name = '{"strings": [\n  {"name": "a", "symbols": ["x"]},\n  {"symbols": ["y"]}\n]}'
    with pytest.raises(FormatError) as info:
        Actiongram.from_json(with_no_name, source="f.json")
    assert str(info.value) == "f.json:3:3: an actuator name must be non-empty text"


def test_of_two_bad_strings_the_reported_one_is_placed():
    # the constructor reads every string's symbols before any string's displacements: the
    # error is the later string's symbol, not the earlier string's displacement
    doc = ('{"strings": [{"name": "a", "symbols": ["x"], "displacements": ["q"]},\n'
           '{"name": "b", "symbols": ["y z"]}]}')
    with pytest.raises(FormatError) as info:
        Actiongram.from_json(doc, source="f.json")
    assert str(info.value).startswith("f.json:2:27: string 'b': symbol 'y z'")


@pytest.mark.parametrize("doc, words", [
    # what the constructor refuses, each at its value
    ('{"strings": [{"name": "a", "symbols": ["x"], "displacements": [1], "actuator": "a b"}]}',
     "1:80: string 'a': actuator 'a b'"),
    ('{"strings": [{"name": "a", "symbols": ["x", "x"], "displacements": [1e308, 1e308]}]}',
     "1:68: string 'a': its displacements overflow"),
    ('{"strings": [{"name": "a", "symbols": ["x"], "displacements": [1, 2]}]}',
     "1:63: string 'a' has 1 symbols but 2 displacements"),
    ('{"strings": [{"name": "a", "start": 1e15, "symbols": ["x", "y", "y"],\n'
     ' "durations": [1, 1e-9, 1e-9]}]}',
     "2:19: string 'a': duration 2e-09 of symbols 2-3 (equal neighbours: one segment) vanishes"),
    ('{"strings": [{"name": "a", "symbols": ["x", "y"], "durations": [1e308, 1e308]}]}',
     "1:64: string 'a': its times overflow"),
    ('{"strings": [{"name": "a", "symbols": ["x"], "start": true}]}',
     "1:55: string 'a': start time must be a finite number"),
    ('{"strings": [{"name": "a", "symbols": ["x", "y"], "durations": [1]}]}',
     "1:64: string 'a' has 2 symbols but 1 durations"),
    ('{"strings": [{"name": "a", "symbols": ["x"]}, {"name": "a", "symbols": ["y"]}]}',
     "1:56: two strings are named 'a'"),
    ('{"strings": [], "skeleton": {"a": "b", "b": "c", "c": "a"}}',
     "1:55: skeleton: the parents of 'a' form a cycle"),
    ('{"strings": [], "skeleton": {"a": null, "b": "b"}}', "1:46: skeleton: 'b' is its own parent"),
    ('{"strings": [], "skeleton": {"a": null, "b c": "a"}}', "1:41: skeleton: actuator name 'b c'"),
])
def test_what_the_constructor_refuses_is_placed_at_its_value(doc, words):
    with pytest.raises(FormatError, match="^f.json:" + re.escape(words)):
        Actiongram.from_json(doc, source="f.json")


# -- CSV events --------------------------------------------------------------------------------
# what is spoilt in one row: the field, its spoilt cell, words of the error
CELL_SPOILS = [
    ("onset", "1x", "onset '1x' is not a number"),
    ("duration", "-2", "duration must be positive"),
    ("duration", "inf", "duration must be finite"),
    ("symbol", "a@1", "symbol 'a@1'"),
    ("stream", "#s", "stream: actuator name '#s'"),
]

# made once, as for documents()
_ORDERS = st.permutations(["stream", "onset", "duration", "symbol", "note"])
# a quoted note may hold commas, quotes and line breaks
_NOTES = st.sampled_from(["", "x", "two\nlines", 'say "hi", then', "a\r\nb"])
_CELL_SPOILS = st.sampled_from(CELL_SPOILS)
_NEWLINES = st.sampled_from(["\n", "\r\n"])
_BLANKS = st.sampled_from(["", ",,,,", " , ,"])


@st.composite
def spoilt_tables(draw):
    """(CSV text, the spoilt cell as written, its offset in the text, words of the error)."""
    order = draw(_ORDERS)
    count = draw(st.integers(1, 5))
    rows, t = [], 0
    for _ in range(count):
        duration = draw(st.integers(1, 3))
        rows.append({"stream": "s", "onset": str(t), "duration": str(duration),
                     "symbol": draw(st.sampled_from("ab")),
                     "note": draw(_NOTES)})
        t += duration + draw(st.integers(0, 1))
    bad = draw(st.integers(0, count - 1))
    field, value, words = draw(_CELL_SPOILS)
    rows[bad][field] = value
    newline = draw(_NEWLINES)
    text, found = ",".join(order) + newline, None
    for k, row in enumerate(rows):
        if draw(st.booleans()):  # blank rows are skipped, and counted
            text += draw(_BLANKS) + newline
        cells = []
        for name in order:
            cell = row[name]
            if draw(st.booleans()) or any(c in cell for c in ',"\r\n'):
                cell = '"' + cell.replace('"', '""') + '"'
            elif draw(st.booleans()):  # unquoted, a cell may be padded: it is stripped
                cell = " " + cell + "  "
            if k == bad and name == field:
                found = (cell, len(text) + len(",".join(cells)) + bool(cells))
            cells.append(cell)
        text += ",".join(cells) + newline
    return text, *found, words


def test_of_two_skeleton_cycles_the_one_named_is_the_one_placed():
    """The whole's message named the cycle through 'c', the place was the entry that closes
    the cycle of 'a' and 'b' (the shortest run of entries refused)."""
    doc = '{"strings": [], "skeleton": {"c": "d", "a": "b", "b": "a", "d": "c"}}'
    with pytest.raises(FormatError) as info:
        Actiongram.from_json(doc, source="f.json")
    error = info.value
    assert error.message == "skeleton: the parents of 'a' form a cycle"
    assert doc[error.column - 1:].startswith('"a", "d"')  # the value of "b": "a"


@settings(max_examples=100, deadline=None)
@given(spoilt_tables())
def test_a_csv_error_names_the_line_and_column_of_the_cell_at_fault(tmp_path_factory, case):
    text, cell, offset, words = case
    path = tmp_path_factory.mktemp("csv") / "t.csv"
    path.write_bytes(text.encode())
    try:
        read_events_csv(path)
    except FormatError as error:
        assert words in error.message, (error.message, words)
        # lines as the csv reader counts them: "\r\n", "\r" and "\n" each end one
        line = re.split(r"\r\n|\r|\n", text)[error.line - 1]
        before = text[:offset]
        expected_line = len(re.findall(r"\r\n|\r|\n", before)) + 1
        expected_column = len(re.split(r"\r\n|\r|\n", before)[-1]) + 1
        assert (error.line, error.column) == (expected_line, expected_column), (str(error), text)
        assert line[error.column - 1:].startswith(cell)
    else:
        raise AssertionError(f"read: {text!r}")
