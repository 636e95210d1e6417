"""Actiongrams from events tables, kept repeats, and the '#' rule of the text form."""

from __future__ import annotations

import doctest
import json
import math
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import Actiongram, FormatError, ValidationError
from psgs.actiongram import read_events_csv

ROOT = Path(__file__).resolve().parents[2]


# -- from_events against a brute-force expansion ---------------------------------------------
# the strategies tables() draws from, made once: hypothesis validates a strategy and works out
# its properties the first time it draws from it, which for strategies made afresh in every
# example cost more than the drawing (they draw the same either way)
_NAMES = st.lists(st.sampled_from("SATB"), min_size=1, max_size=4, unique=True)
_EVENTS = st.lists(st.tuples(st.sampled_from([0, 0, 0, 1, 2]), st.integers(1, 3),
                             st.sampled_from("ab_")), min_size=1, max_size=8)


@st.composite
def tables(draw):
    """Integer-timed streams: per stream its first onset, then (gap, duration, symbol) events
    laid end to end; and the rows, shuffled."""
    names = draw(_NAMES)
    streams, rows = {}, []
    for name in names:
        t = draw(st.integers(0, 3))
        events = []
        for gap, duration, symbol in draw(_EVENTS):
            t += gap if events else 0
            events.append((t, duration, symbol))
            t += duration
        streams[name] = events
        rows.extend((name, onset, duration, symbol) for onset, duration, symbol in events)
    return streams, draw(st.permutations(rows))


def cells_of_events(events, gaps):
    """One symbol per unit of time from the first onset to the last end, the slow way."""
    first, last = events[0][0], events[-1][0] + events[-1][1]
    cells = []
    for t in range(first, last):
        covering = [s for onset, d, s in events if onset <= t < onset + d]
        if covering:
            cells.append(covering[0])
        elif gaps == "rest":
            cells.append("_")
        else:  # hold: the last event that began before t
            cells.append([s for onset, _, s in events if onset <= t][-1])
    return cells


def cells_of_string(symbols, durations):
    out = []
    for s, d in zip(symbols, durations):
        assert float(d).is_integer()
        out.extend([s] * int(d))
    return out


@settings(max_examples=80, deadline=None)
@given(tables(), st.sampled_from(["rest", "hold"]), st.booleans())
def test_from_events_is_the_brute_force_expansion(table, gaps, keep_repeats):
    streams, rows = table
    ag = Actiongram.from_events(rows, gaps=gaps, keep_repeats=keep_repeats)
    assert set(ag.names) == set(streams)
    for name, events in streams.items():
        syms, durs = ag.string(name), ag.durations[name]
        assert ag.starts[name][0] == events[0][0]
        assert cells_of_string(syms, durs) == cells_of_events(events, gaps)
        gap_count = sum(1 for a, b in zip(events, events[1:]) if b[0] > a[0] + a[1])
        if keep_repeats:
            assert len(syms) == len(events) + (gap_count if gaps == "rest" else 0)
        else:
            assert all(a != b for a, b in zip(syms, syms[1:]))


@settings(max_examples=80, deadline=None)
@given(tables(), st.booleans())
def test_to_events_and_back(table, keep_repeats):
    streams, rows = table
    ag = Actiongram.from_events(rows, keep_repeats=keep_repeats)
    assert Actiongram.from_events(ag.to_events(), keep_repeats=keep_repeats) == ag
    # leaving the rests out, gaps come back as rests: the same value when rests are only
    # inside strings and merge (kept apart, a rest event beside a gap would come back as one)
    if not keep_repeats and all(e[0][2] != "_" != e[-1][2] for e in streams.values()):
        assert Actiongram.from_events(ag.to_events("_"), keep_repeats=keep_repeats) == ag


def test_streams_keep_the_order_of_their_first_row_and_float_ends_meet():
    rows = [("b", 0.3, 0.5, "y"), ("a", 0.1, 0.2, "x"), ("b", 0.0, 0.3, "x"),
            ("a", 0.3, 1, "z")]
    ag = Actiongram.from_events(rows, gaps="error")  # 0.1 + 0.2 meets 0.3: no gap
    assert ag.names == ("b", "a")
    assert ag.strings == {"b": ("x", "y"), "a": ("x", "z")}
    assert ag.durations["a"] == (0.2, 1.0) and ag.origins == (0.0, 0.1)


def test_integer_streams_and_symbols_are_written_in_decimal_and_mappings_are_rows():
    rows = [{"voice": 1, "t": 0, "len": 1, "pitch": 60}, {"voice": 1, "t": 1, "len": 1,
                                                          "pitch": 62}]
    ag = Actiongram.from_events(rows, columns={"stream": "voice", "onset": "t",
                                               "duration": "len", "symbol": "pitch"})
    assert ag.strings == {"1": ("60", "62")}


def test_a_column_mapped_from_no_field_is_refused():
    # a misspelt field ("note" for "symbol") was ignored, and the table read without it
    with pytest.raises(ValidationError, match="'note', which is no field: the fields are stream"):
        Actiongram.from_events([("a", 0, 1, "x")], columns={"note": "symbol"})


@pytest.mark.parametrize("columns, words", [
    ({"onset": "t", "duration": "t"}, "fields 'onset' and 'duration' one column, 't'"),
    ({"stream": "v", "symbol": "v"}, "fields 'stream' and 'symbol' one column, 'v'"),
    # a field left out reads the column of its own name, which another field now reads too
    ({"onset": "duration"}, ("fields 'onset' and 'duration' one column, 'duration' "
                             "('duration' is not in columns")),
])
def test_two_fields_given_one_column_are_refused(columns, words):
    # one column was read as both fields, and another column of the table not at all
    rows = [{"t": 0, "v": "a", "onset": 0, "duration": 1, "stream": "s", "symbol": "a"}]
    import pandas  # in the test extra: the DataFrame path reads columns by the same mapping

    for table in (rows, pandas.DataFrame(rows)):
        with pytest.raises(ValidationError) as info:
            Actiongram.from_events(table, columns=columns)
        assert words in str(info.value) and "each field needs a column of its own" in str(
            info.value)
    # a swap is two columns, each read once
    swapped = Actiongram.from_events([{"stream": "s", "onset": 2, "duration": 0, "symbol": "a"}],
                                     columns={"onset": "duration", "duration": "onset"})
    assert swapped.origins == (0.0,) and swapped.durations == {"s": (2.0,)}


@pytest.mark.parametrize("rows, words", [
    ([("s", -1, 1, "a")], "row 0: onset must be 0 or more"),
    ([("s", 0, 1, "a"), ("s", math.nan, 1, "a")], "row 1: onset must be finite"),
    ([("s", 0, math.inf, "a")], "row 0: duration must be finite"),
    ([("s", 0, 0, "a")], "row 0: duration must be positive"),
    ([("s", 0, 1, "a"), ("s", 1e308, 1e308, "b")], "row 1: its end"),  # (past float's range)
    ([("s", 0, "1", "a")], "row 0: duration must be a number"),
    ([("s", 0, 2, "a"), ("t", 0, 1, "a"), ("s", 1, 1, "b")], "row 2: overlaps row 0"),
    ([("s", 0, 1, "#4")], "row 0: symbol '#4' must have no white space"),
    ([("s", 0, 1, "a b")], "row 0: symbol 'a b'"),
    ([("s", 0, 1, "x@1")], "row 0: symbol 'x@1'"),
    ([("s", 0, 1, 1.5)], "row 0: a symbol must be non-empty text"),
    ([("s", 0, 1, "a"), (True, 0, 1, "a")], "row 1: stream"),
    ([("s", 0, 1)], "row 0: expected (stream, onset, duration, symbol)"),
    ([{"stream": "s", "onset": 0, "symbol": "a"}], "row 0: no 'duration'"),
    ([], "no events"),
    ("s,0,1,a", "not str"),
])
def test_bad_rows_are_one_validation_error_naming_the_row(rows, words):
    with pytest.raises(ValidationError) as info:
        Actiongram.from_events(rows)
    assert words in str(info.value) and "\n" not in str(info.value)


def test_bad_options_and_a_refused_gap():
    with pytest.raises(ValidationError, match="row 1: a gap in stream 's' from 1 to 2"):
        Actiongram.from_events([("s", 0, 1, "a"), ("s", 2, 1, "b")], gaps="error")
    with pytest.raises(ValidationError, match="gaps must be one of"):
        Actiongram.from_events([("s", 0, 1, "a")], gaps="silence")
    with pytest.raises(ValidationError, match="rest_symbol"):
        Actiongram.from_events([("s", 0, 1, "a")], rest_symbol="a rest")


def test_a_dataframe_is_read_by_its_columns_and_named_by_its_index():
    import pandas  # in the test extra: this path is tested, never skipped
    frame = pandas.DataFrame({"voice": ["S", "S", "B"], "onset": [0.0, 1.0, 0.5],
                              "duration": [1.0, 1.0, 2.0], "note": ["C5", "D5", "C3"]},
                             index=[10, 11, 12])
    ag = Actiongram.from_events(frame, columns={"stream": "voice", "symbol": "note"})
    assert ag.strings == {"S": ("C5", "D5"), "B": ("C3",)} and ag.origins == (0.0, 0.5)
    frame.loc[12, "duration"] = -2.0
    with pytest.raises(ValidationError, match="row 12: duration must be positive"):
        Actiongram.from_events(frame, columns={"stream": "voice", "symbol": "note"})
    with pytest.raises(ValidationError, match="no column 'stream'"):
        Actiongram.from_events(frame)


def test_psgs_does_not_import_pandas():
    code = ("import sys, psgs; psgs.Actiongram.from_events([('s', 0, 1, 'a')]); "
            "print('pandas' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, cwd=ROOT).stdout
    assert out.strip() == "False"


# -- kept repeats ----------------------------------------------------------------------------
def test_kept_repeats_survive_text_and_json_and_default_merging_is_unchanged():
    kept = Actiongram.from_strings({"v": "CCD"}, {"v": [1, 0.5, 1]}, keep_repeats=True,
                                   displacements={"v": [1, 2, 3]})
    assert kept.string("v") == ("C", "C", "D") and kept.displacements("v") == (1.0, 2.0, 3.0)
    assert kept.to_text().startswith("%keep_repeats\n")
    assert Actiongram.from_text(kept.to_text()) == kept
    assert Actiongram.from_json(kept.to_json()) == kept
    assert json.loads(kept.to_json())["keep_repeats"] is True
    merged = Actiongram.from_strings({"v": "CCD"})
    assert merged.string("v") == ("C", "D") and not merged.keep_repeats
    assert "keep_repeats" not in json.loads(merged.to_json())
    assert "%keep_repeats" not in merged.to_text()
    assert kept.subset(["v"]) == kept
    with pytest.raises(FormatError, match="'keep_repeats' must be true or false"):
        Actiongram.from_json('{"strings": [], "keep_repeats": "yes"}')


repeat_strings = st.lists(st.tuples(st.sampled_from("CDE"), st.sampled_from([1.0, 0.5, 2.0])),
                          max_size=10)


@settings(max_examples=60, deadline=None)
@given(st.dictionaries(st.sampled_from(["s", "a", "t.x"]), repeat_strings, min_size=1))
def test_round_trip_with_kept_repeats(rows):
    ag = Actiongram.from_strings({n: [s for s, _ in r] for n, r in rows.items()},
                                 {n: [d for _, d in r] for n, r in rows.items()},
                                 keep_repeats=True)
    assert ag.strings == {n: tuple(s for s, _ in r) for n, r in rows.items()}
    assert Actiongram.from_text(ag.to_text()) == ag
    assert Actiongram.from_json(ag.to_json()) == ag


def test_pal_runs_on_an_actiongram_with_kept_repeats():
    from psgs.induce import PAL

    motif = ["C", "C", "D", "E", "E", "G"]
    strings = {"s": motif * 6, "a": ["G", "G", "A", "B", "B", "D"] * 6,
               "t": list("CDEFGAB" * 5)[:36]}
    ag = Actiongram.from_strings(strings, keep_repeats=True)
    assert len(ag.string("s")) == 36
    result = PAL().induce(ag)
    assert {r.name for r in result.reports} == set(strings)
    for name in result.components:
        assert result.occurrences[name]


# -- the '#' rule of the text form -----------------------------------------------------------
@pytest.mark.parametrize("text, column", [("S: 1 #4 5\n", 6), ("S@2: a\tb\t#b\n", 10),
                                          ("%parent a: #b\n", 12)])
def test_a_hash_token_on_a_line_is_an_error_at_its_place(text, column):
    with pytest.raises(FormatError) as info:
        Actiongram.from_text(text, source="s.txt")
    assert (info.value.line, info.value.column) == (1, column)
    assert "starts with '#'" in info.value.message


def test_comments_are_lines_or_a_hash_and_white_space_after_white_space():
    ag = Actiongram.from_text("#comment\n  #4 also a comment line\nS: 1 # 4 5\nA: C#4 D#\t#\n")
    assert ag.strings == {"S": ("1",), "A": ("C#4", "D#")}


symbols_with_hashes = st.text(alphabet="ab#~%.", min_size=1, max_size=4).filter(
    lambda s: not s.startswith("#"))


@settings(max_examples=100, deadline=None)
@given(st.lists(symbols_with_hashes, min_size=1, max_size=8), st.booleans())
def test_symbols_holding_hashes_round_trip_through_the_text_form(symbols, keep_repeats):
    ag = Actiongram.from_strings({"s": symbols}, keep_repeats=keep_repeats)
    assert Actiongram.from_text(ag.to_text()) == ag


# -- the command line and the docs -----------------------------------------------------------
def test_induce_reads_an_events_file(tmp_path, capsys):
    from psgs.cli import main

    path = tmp_path / "song.csv"
    lines = ["stream,onset,duration,symbol,velocity"]
    for voice, notes in {"S": "CCDEEG", "A": "GGABBD"}.items():
        lines += [f"{voice},{6 * k + j},1,{n},64" for k in range(5) for j, n in enumerate(notes)]
    path.write_text("\n".join(lines) + "\n")
    assert main(["induce", "--events", str(path), "--keep-repeats", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["inducer"] == "pal"
    ag = read_events_csv(path, keep_repeats=True)
    assert len(ag.string("S")) == 30 and len(read_events_csv(path).string("S")) == 20


@pytest.mark.parametrize("content, where, words", [
    # a cell's error names its column; the overlap and the gap are the onset's
    ("stream,onset,duration,symbol\ns,0,1,a\ns,0.5,1,b\n", ":3:3:", "overlaps line 2"),
    ("stream,onset,duration,symbol\ns,0,1,a\ns,x,1,b\n", ":3:3:", "onset 'x' is not a number"),
    ("stream,onset,duration,symbol\ns,0,nan,a\n", ":2:5:", "duration must be finite"),
    # a quoted cell holding a line break: the row is named by the line it starts on
    ('stream,onset,duration,symbol\ns,0,1,a\n"s\nx",1,1,b\n', ":3:1:", "stream"),
    # and a cell after it by its own line
    ('note,stream,onset,duration,symbol\n"a\nb",s,0,-1,x\n', ":3:8:", "duration must be"),
    # what is missing from a row, at the row's end
    ("stream,onset,symbol\ns,0,a\n", ":1:20:", "no column 'duration'"),
    ("stream,onset,duration,symbol\ns,0,1\n", ":2:6:", "3 cells"),
    ("stream,onset,duration,symbol\n", ":1: ", "no events"),
    ("", ":1: ", "empty file"),
    # a cell past the header's would be dropped without a word; a column twice is ambiguous
    ("stream,onset,duration,symbol\ns,0,1,a,extra\n", ":2:9:", "5 cells, the header has 4"),
    ("stream,onset,duration,symbol\ns,0,1,a,, ,extra\n", ":2:12:", "7 cells, the header has 4"),
    ("stream,stream,onset,duration,symbol\ns,t,0,1,a\n", ":1:8:", "'stream' twice"),
    # an end a float cannot tell from its start; a NUL in a symbol
    ("stream,onset,duration,symbol\ns,0,1,a\ns,1e300,1,b\n", ":3:9:", "vanishes beside onset"),
    ("stream,onset,duration,symbol\ns,0,1,a\x00\n", ":2:7:", "control character"),
    # float() would read these as 10 and 12; a quote left open would swallow the rest
    ("stream,onset,duration,symbol\ns,1_0,1,a\n", ":2:3:", "onset '1_0' is not a number"),
    ("stream,onset,duration,symbol\ns,\uff11\uff12,1,a\n", ":2:3:", "is not a number"),
    ('stream,onset,duration,symbol\ns,0,1,a\ns,1,1,"b\n', ":3: ", "not CSV"),
])
def test_induce_events_errors_name_the_line(tmp_path, capsys, content, where, words):
    from psgs.cli import main

    path = tmp_path / "bad.csv"
    path.write_text(content)
    assert main(["induce", "--events", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert f"{path}{where}" in err and words in err and "\n" not in err


def test_a_huge_integer_or_a_vanishing_duration_is_a_validation_error_naming_the_row():
    with pytest.raises(ValidationError, match="^row 0: onset must be finite"):
        Actiongram.from_events([("a", 10 ** 400, 1, "x")])
    with pytest.raises(ValidationError, match="^row 1: duration 1 vanishes beside onset"):
        Actiongram.from_events([("a", 0, 1, "y"), ("a", 1e300, 1, "x")])


def test_empty_cells_past_the_header_pad_a_row_and_are_no_error(tmp_path):
    path = tmp_path / "padded.csv"
    path.write_text("stream,onset,duration,symbol\ns,0,1,a,,\ns,1,1,b, ,\n")
    assert read_events_csv(path).string("s") == ("a", "b")


def test_a_device_is_refused_not_read(capsys):
    from psgs.cli import main

    assert main(["induce", "--events", "/dev/zero"]) == 2
    assert "not a regular file" in capsys.readouterr().err


def test_event_options_need_events(capsys):
    from psgs.cli import main

    assert main(["induce", "--example", "--keep-repeats"]) == 2
    assert "go with --events" in capsys.readouterr().err


@pytest.mark.parametrize("page", ["streams.md"])
def test_documentation_examples_run(page):
    result = doctest.testfile(str(ROOT / "docs" / page), module_relative=False,
                              optionflags=doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE)
    assert result.attempted > 0 and result.failed == 0


def test_performances_padded_to_the_same_strings_keep_their_repeats():
    """Takes with different strings are padded for the motion learner; a re-struck note stays."""
    from psgs.induce.pal.motion.learner import same_strings

    a = Actiongram.from_strings({"knee": "aab"}, keep_repeats=True)
    b = Actiongram.from_strings({"hip": "xxy"}, keep_repeats=True)
    padded = same_strings([a, b])
    assert [p.keep_repeats for p in padded] == [True, True]
    assert padded[0].string("knee") == ("a", "a", "b")


def test_a_name_read_from_many_rows_is_held_once(tmp_path):
    # one string per row was most of what a long events file cost in memory (symbols of two
    # letters: a one-letter string is one object in CPython anyway)
    path = tmp_path / "long.csv"
    rows = [f"{'ab'[k % 2]},{k // 2},1,{'CDE'[k % 3]}4" for k in range(600)]
    path.write_text("stream,onset,duration,symbol\n" + "\n".join(rows) + "\n")
    ag = read_events_csv(path)
    symbols = [s for name in ag.names for s in ag.string(name)]
    assert len(symbols) == 600 and len({id(s) for s in symbols}) == 3


def test_a_column_named_by_a_number_is_said_missing_as_a_name_is():
    # the message joined the keys as text, and a number among them was a TypeError
    rows = [{0: "bass", "onset": 0, "duration": 1, "symbol": "C"}]
    assert Actiongram.from_events(rows, columns={"stream": 0}).names == ("bass",)
    with pytest.raises(ValidationError, match=r"row 0: no 3 \(a row needs 3, onset, duration"):
        Actiongram.from_events(rows, columns={"stream": 3})


def test_a_keep_repeats_that_is_no_bool_is_an_argument_error_not_a_format_error(tmp_path):
    # it was a FormatError of '<string>', as though some text were malformed, after the
    # whole table was read
    path = tmp_path / "t.csv"
    path.write_text("stream,onset,duration,symbol\nb,0,1,C\n")
    for read in (lambda: Actiongram.from_events([("b", 0, 1, "C")], keep_repeats="yes"),
                 lambda: read_events_csv(path, keep_repeats="yes")):
        with pytest.raises(ValidationError) as caught:
            read()
        assert not isinstance(caught.value, FormatError)
        assert str(caught.value) == "keep_repeats must be True or False, not 'yes'"
