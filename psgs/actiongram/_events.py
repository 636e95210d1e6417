"""Actiongrams from events tables (:meth:`psgs.Actiongram.from_events`) and back.

An event is ``(stream, onset, duration, symbol)``: a note of a voice, a label of a sensor, a
state of a machine. An actiongram has no gaps (each symbol of a string starts where the one
before ends), so a stretch of a stream with no event has to become something: a segment of
the rest symbol (``gaps="rest"``), the event before lasting until the next onset
(``gaps="hold"``), or an error (``gaps="error"``). Each string starts at its stream's first
onset.

Rows come as tuples, as mappings, as a pandas DataFrame (recognised only when the caller has
pandas loaded: psgs never imports it) or, for the command line, as a CSV file. Every bad row is
one error naming the row (its index, or the file's line and the column of the cell at fault).
"""

from __future__ import annotations

import csv
import io
import math
import numbers
import re
import sys
from array import array
from collections.abc import Callable, Iterable, Mapping, Sequence
from pathlib import Path

from .._foundation.files import read_text
from .._foundation.text import decimal
from ..errors import FormatError, ValidationError
from ._checks import _bad_name, _bad_symbol, _real, _shown

__all__: list[str] = []  # private: Actiongram.from_events and to_events are the interface

FIELDS = ("stream", "onset", "duration", "symbol")
#: what a gap between two events of a stream becomes (``from_events(gaps=...)``): a rest
#: symbol, the event before held until the next onset, or an error
GAPS = ("rest", "hold", "error")
#: times closer than this share of their size (and of 1) are equal: 0.1 + 0.2 ends at 0.3
TOLERANCE = 1e-9


class _RowError(Exception):
    """A bad row: its position in the input, what is wrong (the caller names the row) and the
    field at fault (a file's error names that field's cell)."""

    def __init__(self, index: int, message: str, field: str) -> None:
        super().__init__(message)
        self.index = index
        self.message = message
        self.field = field


def _close(a: float, b: float) -> bool:
    return abs(a - b) <= TOLERANCE * max(1.0, abs(a), abs(b))


def _text(value: object, what: str, index: int) -> str:
    """A stream name or symbol as text: a str as it is, an integer (MIDI pitch 60, voice 1) in
    decimal; anything else is an error."""
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        value = str(int(value))
    problem = _bad_name(value) if what == "stream" else _bad_symbol(value)
    if problem:
        raise _RowError(index, f"{what}: {problem}" if what == "stream" else problem, what)
    return value


def _time(value: object, what: str, index: int) -> float:
    if not _real(value):  # a numpy timedelta64 too: its count would be read without its unit
        raise _RowError(index, f"{what} must be a number, not {_shown(value)}", what)
    try:
        number = float(value)
    except OverflowError:  # an int past the floats (10**400): no time a float can hold
        number = math.inf
    if not math.isfinite(number):
        raise _RowError(index, f"{what} must be finite, not {_shown(value)}", what)
    if number < 0 if what == "onset" else number <= 0:
        raise _RowError(index, f"{what} must be {'0 or more' if what == 'onset' else 'positive'}"
                               f", not {_shown(value)}", what)
    return number


def _dataframe_columns(rows, columns: Mapping[str, str]) -> list | None:
    """The four columns of a pandas DataFrame as lists, with its index; None when ``rows`` is
    not a DataFrame. Only a pandas the caller has already imported is looked at."""
    pandas = sys.modules.get("pandas")
    if pandas is None or not isinstance(rows, pandas.DataFrame):
        return None
    names = [columns.get(f, f) for f in FIELDS]
    missing = [n for n in names if n not in rows.columns]
    if missing:
        raise ValidationError(f"the table has no column {_shown(missing[0])} (its columns: "
                              f"{', '.join(map(str, rows.columns))}); name them stream, onset, "
                              f"duration, symbol or map yours with columns={{...}}")
    return [list(rows.index), *(rows[n].tolist() for n in names)]


def _records(rows, columns: Mapping[str, str]) -> tuple[list[tuple], list[object]]:
    """``(stream, onset, duration, symbol)`` per row, unchecked, and each row's label."""
    frame = _dataframe_columns(rows, columns)
    if frame is not None:
        index, *cols = frame
        return list(zip(*cols)), index
    if isinstance(rows, (str, bytes)) or not isinstance(rows, Iterable):
        raise ValidationError(f"events must be rows of (stream, onset, duration, symbol), "
                              f"mappings or a pandas DataFrame, not {type(rows).__name__}")
    keys = [columns.get(f, f) for f in FIELDS]
    out = []
    for k, row in enumerate(rows):
        if isinstance(row, Mapping):
            missing = [key for key in keys if key not in row]
            if missing:
                raise ValidationError(f"row {k}: no {_shown(missing[0])} (a row needs "
                                      f"{', '.join(map(str, keys))})")
            out.append(tuple(row[key] for key in keys))
        elif isinstance(row, Sequence) and not isinstance(row, (str, bytes)) and len(row) == 4:
            out.append(tuple(row))
        else:
            raise ValidationError(f"row {k}: expected (stream, onset, duration, symbol), not "
                                  f"{_shown(row)}")
    return out, list(range(len(out)))


def _strings(records: Sequence[tuple], label: Callable[[int], str], gaps: str,
             rest_symbol: str):
    """Per stream (in order of first appearance): its symbols, durations and start time."""
    if not records:
        raise ValidationError("no events: an actiongram needs at least one")
    streams: dict[str, list[tuple[float, int, float, str]]] = {}
    for k, (stream, onset, duration, symbol) in enumerate(records):
        name = _text(stream, "stream", k)
        event = (_time(onset, "onset", k), k, _time(duration, "duration", k),
                 _text(symbol, "symbol", k))
        # the onset alone is a time a float holds: the duration is the cell at fault
        if not math.isfinite(event[0] + event[2]):
            raise _RowError(k, f"its end, onset {_shown(onset)} plus duration "
                               f"{_shown(duration)}, is past the largest time a float holds",
                            "duration")
        if event[0] + event[2] == event[0]:
            raise _RowError(k, f"duration {_shown(duration)} vanishes beside onset "
                               f"{_shown(onset)}: a float cannot tell the event's end from "
                               f"its start", "duration")
        streams.setdefault(name, []).append(event)
    strings, durations, starts = {}, {}, {}
    for name, events in streams.items():
        events.sort()
        syms, durs = [], []
        for (onset, k, duration, symbol), (after, j, _, _) in zip(events, events[1:]):
            end = onset + duration
            syms.append(symbol)
            if _close(after, end):  # back to back: the table's own duration (exact round trips)
                durs.append(duration)
            elif after < end:
                raise _RowError(j, f"overlaps {label(k)} in stream {_shown(name)} ({label(k)} "
                                   f"lasts from {onset:g} to {end:g}, this one starts at "
                                   f"{after:g})", "onset")  # this row starts too early
            elif gaps == "hold":
                durs.append(after - onset)
            elif gaps == "rest":
                durs.append(duration)
                syms.append(rest_symbol)
                durs.append(after - end)
            else:
                raise _RowError(j, f"a gap in stream {_shown(name)} from {end:g} to {after:g} "
                                   f"(after {label(k)}); gaps='rest' or 'hold' fill it",
                                "onset")
        syms.append(events[-1][3])
        durs.append(events[-1][2])
        strings[name], durations[name], starts[name] = syms, durs, events[0][0]
    return strings, durations, starts


def _check_options(gaps: object, rest_symbol: object, keep_repeats: object) -> None:
    """The options are refused before any row is read (the actiongram's own check of
    ``keep_repeats`` comes after the rows, as a FormatError of no text)."""
    if gaps not in GAPS:
        raise ValidationError(f"gaps must be one of {', '.join(GAPS)}, not {_shown(gaps)}")
    problem = _bad_symbol(rest_symbol)
    if problem:
        raise ValidationError(f"rest_symbol: {problem}")
    if not isinstance(keep_repeats, bool):
        raise ValidationError(f"keep_repeats must be True or False, not {_shown(keep_repeats)}")


def _same_column(a: object, b: object) -> bool:
    """Whether column names ``a`` and ``b`` are one (as a mapping's lookup would take them)."""
    try:
        return a is b or bool(a == b)
    except (TypeError, ValueError):  # a name whose == is no truth value: no two are one
        return False


def _check_one_column_each(columns: dict) -> None:
    """ValidationError when two fields would read one column: the table would be read with one
    of its columns in two places and another not at all. A field that ``columns`` leaves out
    reads the column of its own name, so ``{"onset": "duration"}`` is refused too."""
    keys = [columns.get(f, f) for f in FIELDS]
    for i, first in enumerate(FIELDS):
        for j in range(i + 1, len(FIELDS)):
            if _same_column(keys[i], keys[j]):
                second = FIELDS[j]
                unmapped = [f for f in (first, second) if f not in columns]
                why = (f" ({_shown(unmapped[0])} is not in columns, so it reads the column of "
                       f"its own name)" if unmapped else "")
                raise ValidationError(f"columns gives fields {first!r} and {second!r} one "
                                      f"column, {_shown(keys[i])}{why}: each field needs a "
                                      f"column of its own")


def from_events(cls, rows, *, gaps: str = "rest", rest_symbol: str = "_",
                keep_repeats: bool = False, columns: Mapping[str, str] | None = None):
    """:meth:`psgs.Actiongram.from_events` (its docstring says what each argument does)."""
    _check_options(gaps, rest_symbol, keep_repeats)
    if columns is not None and not isinstance(columns, Mapping):
        raise ValidationError(f"columns must map a field to a column name, not {_shown(columns)}")
    unknown = [k for k in (columns or {}) if k not in FIELDS]
    if unknown:  # a misspelt field was ignored, and the column it named never read
        raise ValidationError(f"columns maps {_shown(unknown[0])}, which is no field: the "
                              f"fields are {', '.join(FIELDS)}")
    _check_one_column_each(dict(columns or {}))
    records, labels = _records(rows, dict(columns or {}))
    label = lambda k: f"row {labels[k]!r}"  # noqa: E731 - the index a user gave, as given
    try:
        strings, durations, starts = _strings(records, label, gaps, rest_symbol)
    except _RowError as bad:
        raise ValidationError(f"{label(bad.index)}: {bad.message}") from None
    return cls.from_strings(strings, durations, starts, keep_repeats=keep_repeats)


def read_csv(cls, path: str | Path, *, gaps: str = "rest", rest_symbol: str = "_",
             keep_repeats: bool = False):
    """The actiongram of a CSV events file, header ``stream,onset,duration,symbol`` (in any
    order; other columns are ignored, but every row has as many cells as the header, and no
    column is named twice). Errors are FormatErrors naming the file, the line and, for a cell,
    its column."""
    _check_options(gaps, rest_symbol, keep_repeats)
    source = str(path)
    text = read_text(path, signature=True)
    # strict: a quote left open or text after a closing quote is an error, not read on
    reader = csv.reader(io.StringIO(text, newline=""), strict=True)
    try:
        header = [cell.strip() for cell in next(reader)]
    except StopIteration:
        raise FormatError("empty file: expected a header row stream,onset,duration,symbol",
                          source=source, line=1) from None
    except csv.Error as exc:
        raise FormatError(f"not CSV: {exc}", source=source, line=1) from None
    missing = [f for f in FIELDS if f not in header]
    if missing:  # at the header's end, where the column would be added
        raise _at(f"the header has no column {missing[0]!r} (it needs {','.join(FIELDS)})",
                  text, source, 1, None)
    twice = [f for f in FIELDS if header.count(f) > 1]
    if twice:  # which of the two is meant cannot be known: at the second
        raise _at(f"the header names column {twice[0]!r} twice", text, source, 1,
                  [k for k, cell in enumerate(header) if cell == twice[0]][1])
    where = [header.index(f) for f in FIELDS]
    # a row's stream and symbol are one of few names: one string each, not one per row, and
    # line numbers in an array, so that a long file costs little more than what it describes
    records, lines, names = [], array("q"), {}
    # a row starts on the line after the one before ends: a quoted cell may hold line
    # breaks, and the reader counts to the row's end
    ended = reader.line_num
    try:
        for row in reader:
            line, ended = ended + 1, reader.line_num
            if not any(cell.strip() for cell in row):
                continue
            if len(row) < len(header) or any(cell.strip() for cell in row[len(header):]):
                # a cell more would be dropped without a word (empty ones pad a spreadsheet's):
                # at the first such cell; a row of too few, at its end, where they are missing
                extra = [k for k in range(len(header), len(row)) if row[k].strip()]
                raise _at(f"{len(row)} cells, the header has {len(header)}", text, source,
                          line, extra[0] if extra else None)
            stream, onset, duration, symbol = (row[i].strip() for i in where)
            try:
                records.append((names.setdefault(stream, stream), _number(onset, "onset"),
                                _number(duration, "duration"),
                                names.setdefault(symbol, symbol)))
            except _RowError as bad:
                raise _at(bad.message, text, source, line,
                          where[FIELDS.index(bad.field)]) from None
            lines.append(line)
    except csv.Error as exc:
        raise FormatError(f"not CSV: {exc}", source=source, line=reader.line_num) from None
    if not records:
        raise FormatError("no events: only a header row", source=source, line=1)
    try:
        strings, durations, starts = _strings(records, lambda k: f"line {lines[k]}", gaps,
                                              rest_symbol)
    except _RowError as bad:
        raise _at(bad.message, text, source, lines[bad.index],
                  where[FIELDS.index(bad.field)]) from None
    return cls.from_strings(strings, durations, starts, keep_repeats=keep_repeats)


def _number(text: str, what: str) -> float:
    value = decimal(text)  # not float(): it takes '1_0' and digits of other scripts
    if value is None:
        raise _RowError(-1, f"{what} {_shown(text)} is not a number", what)
    return value


# the line breaks of io.StringIO(text, newline=""), whose lines the csv reader counts
_BREAK = re.compile(r"\r\n|\r|\n")
_UNQUOTED = re.compile(r"[^,\r\n]*")


def _row_cells(text: str, line: int) -> tuple[list[tuple[int, int]], tuple[int, int]]:
    """Where each cell of the row that starts on ``line`` starts, and where the row ends: each
    a (line, column) pair counting from 1, the column in characters.

    The csv reader says no cell's place, so an error's row is read again, by hand: a good file
    is never read twice. The reader has taken the row (strict), so it is well formed: a cell
    is quoted (``""`` a quote within, line breaks allowed) or runs to the next comma or line
    break.
    """
    at = 0
    for _ in range(line - 1):
        at = _BREAK.search(text, at).end()
    row_line, line_start, starts = line, at, []
    while True:
        starts.append((row_line, at - line_start + 1))
        if text.startswith('"', at):
            end = at + 1
            while True:  # to just past the closing quote (a doubled one is a quote within)
                end = text.find('"', end) + 1 or len(text)
                if not text.startswith('"', end):
                    break
                end += 1
            for brk in _BREAK.finditer(text, at, end):
                row_line, line_start = row_line + 1, brk.end()
            at = end
        at = _UNQUOTED.match(text, at).end()  # after a closing quote, strict: nothing
        if not text.startswith(",", at):
            return starts, (row_line, at - line_start + 1)
        at += 1


def _at(message: str, text: str, source: str, line: int, cell: int | None) -> FormatError:
    """The FormatError ``message`` at the start of cell ``cell`` (counting from 0) of the row
    that starts on ``line``, or at the row's end when ``cell`` is None."""
    starts, end = _row_cells(text, line)
    line, column = end if cell is None else starts[cell]
    return FormatError(message, source=source, line=line, column=column)


def to_events(actiongram, rest_symbol: str | None = None) -> tuple[tuple[str, float, float, str],
                                                                   ...]:
    """:meth:`psgs.Actiongram.to_events`: one ``(stream, onset, duration, symbol)`` per
    segment, string by string, leaving out segments of ``rest_symbol`` when it is given."""
    if rest_symbol is not None and _bad_symbol(rest_symbol):  # a number matched no symbol
        raise ValidationError(f"rest_symbol: {_bad_symbol(rest_symbol)}")
    out = []
    starts = actiongram.starts
    for name, syms, durs in zip(actiongram.names, actiongram.symbols,
                                actiongram.segment_durations):
        for symbol, onset, duration in zip(syms, starts[name], durs):
            if symbol != rest_symbol:
                out.append((name, onset, duration, symbol))
    return tuple(out)
