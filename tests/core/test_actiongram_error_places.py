"""Errors of the actiongram readers name the line and column of what is at fault: a cell of a
CSV events file.

Each test writes a good file, spoils one thing in it, and checks that the error's place is
where the spoilt text starts, however the file is laid out.
"""

from __future__ import annotations

import re

from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import FormatError
from psgs.actiongram import read_events_csv

# -- CSV events --------------------------------------------------------------------------------
# what is spoilt in one row: the field, its spoilt cell, words of the error
CELL_SPOILS = [
    ("onset", "1x", "onset '1x' is not a number"),
    ("duration", "-2", "duration must be positive"),
    ("duration", "inf", "duration must be finite"),
    ("symbol", "a@1", "symbol 'a@1'"),
    ("stream", "#s", "stream: actuator name '#s'"),
]


@st.composite
def spoilt_tables(draw):
    """(CSV text, the spoilt cell as written, its offset in the text, words of the error)."""
    order = draw(st.permutations(["stream", "onset", "duration", "symbol", "note"]))
    count = draw(st.integers(1, 5))
    rows, t = [], 0
    for _ in range(count):
        duration = draw(st.integers(1, 3))
        rows.append({"stream": "s", "onset": str(t), "duration": str(duration),
                     "symbol": draw(st.sampled_from("ab")),
                     # a quoted note may hold commas, quotes and line breaks
                     "note": draw(st.sampled_from(["", "x", "two\nlines", 'say "hi", then',
                                                   "a\r\nb"]))})
        t += duration + draw(st.integers(0, 1))
    bad = draw(st.integers(0, count - 1))
    field, value, words = draw(st.sampled_from(CELL_SPOILS))
    rows[bad][field] = value
    newline = draw(st.sampled_from(["\n", "\r\n"]))
    text, found = ",".join(order) + newline, None
    for k, row in enumerate(rows):
        if draw(st.booleans()):  # blank rows are skipped, and counted
            text += draw(st.sampled_from(["", ",,,,", " , ,"])) + newline
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


@settings(max_examples=200, deadline=None)
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
