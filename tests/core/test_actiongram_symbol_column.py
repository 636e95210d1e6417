"""The text form names a refused symbol at its own column, not at its string's name.

What no terminal of a grammar holds (a C1 control, an invisible format character, a lone
surrogate) is refused by the actiongram's checks once the lines are read; the error used to
carry the place of the string's name, column 1 of a line whose bad symbol was far along it.
"""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import Actiongram, FormatError

# a zero-width space, a C1 control (CSI), a byte-order mark inside a token, a lone surrogate
BAD = ["\u200b", "\x9b", "\ufeff", "\ud800"]


def _refused(text: str) -> FormatError:
    with pytest.raises(FormatError) as caught:
        Actiongram.from_text(text, source="ag.txt")
    return caught.value


@pytest.mark.parametrize("bad", BAD)
def test_a_bad_symbol_in_the_middle_of_a_line_is_named_at_its_column(bad):
    line = f"knee@2: a@1 b@0.5 c{bad}d@2 e"
    error = _refused(f"hip: a b\n{line}\n")
    assert (error.line, error.column) == (2, line.index(f"c{bad}") + 1), str(error)
    assert str(error).startswith(f"ag.txt:2:{line.index('c' + bad) + 1}: string 'knee': symbol")


def test_the_first_bad_symbol_of_the_line_is_the_one_named():
    line = "\tknee:  a  b\u200bx\tc \u200by  # a comment"
    error = _refused(line + "\n")
    assert (error.line, error.column) == (1, line.index("b\u200bx") + 1)
    assert "'b\\u200bx'" in error.message


def test_a_repeated_bad_symbol_is_named_where_it_first_stands():
    # the checks read each distinct symbol once; its first place is the one to show
    line = "s: a x\u200b a x\u200b"
    assert _refused(line).column == line.index("x") + 1


def test_what_is_not_a_symbol_stays_at_the_string_name():
    # times that overflow are the whole string's, not one symbol's
    error = _refused("hip: a\n  s@1e308: a@1e308\n")
    assert (error.line, error.column) == (2, 3) and "its times overflow" in error.message


def test_a_vanishing_duration_is_named_at_its_symbol():
    # it was named at the string's name (2:3), however far along the line the symbol stood
    line = "  s@1e15: a@2  b@1e-9 c  # a comment"
    error = _refused(f"hip: a\n{line}\n")
    assert (error.line, error.column) == (2, line.index("b@") + 1)
    assert error.message.startswith("string 's': duration 1e-09 of symbol 2 vanishes beside "
                                    "its start time 1000000000000002.0")
    # a run of equal neighbours is one segment, named at its first symbol, and by the
    # symbols it merges (it was 'symbol 2', the segment's number, beside a third symbol)
    error = _refused("s@1e15: x@1 x@1 y@1e-9 y@1e-9 z\n")
    assert (error.line, error.column) == (1, len("s@1e15: x@1 x@1 ") + 1)
    assert "duration 2e-09 of symbols 3-4 (equal neighbours: one segment)" in error.message
    error = _refused("%keep_repeats\ns@1e15: x@1 x@1 y@1e-9 y@1e-9 z\n")
    assert (error.line, error.column) == (2, len("s@1e15: x@1 x@1 ") + 1)
    assert "duration 1e-09 of symbol 3 vanishes" in error.message


@settings(max_examples=150, deadline=None)
@given(st.lists(st.sampled_from(["B", "G@2", "x1@3", "é"]), max_size=6),
       st.lists(st.sampled_from(["B", "G@2", "R@1e-9", "é@1e-9"]), max_size=4),
       st.sampled_from([" ", "  ", "\t", " \t "]), st.sampled_from(["", "  ", "\t"]),
       st.sampled_from(["1e15", "-1e15", "999999999999999.5"]), st.sampled_from(["", "  # note"]))
def test_the_column_is_that_of_the_nth_symbol_whose_duration_vanishes(before, after, gap,
                                                                      indent, start, comment):
    # near 1e15 a float's step is 1/8: the durations of 'before' (1 to 3) advance the start
    # time, v's does not; equal neighbours of 'before' merge into one segment, which must
    # not change the number nor the column of the symbol named
    tokens = [*before, "v@1e-9", *after]
    line = f"{indent}arm@{start}:{gap}{gap.join(tokens)}{comment}"
    error = _refused(f"hip: a\n{line}\n")
    assert error.message.startswith(f"string 'arm': duration 1e-09 of symbol {len(before) + 1} "
                                    f"vanishes beside its start time"), error.message
    column = len(f"{indent}arm@{start}:{gap}") + sum(len(t) + len(gap) for t in before) + 1
    assert (error.line, error.column) == (2, column), (line, str(error))


@settings(max_examples=100, deadline=None)
@given(st.lists(st.sampled_from(["B", "G@2", "R@0.5", "x1", "é@3"]), min_size=1, max_size=8),
       st.integers(0, 8), st.sampled_from(BAD), st.sampled_from([" ", "  ", "\t", " \t "]),
       st.sampled_from(["", "  ", "\t"]), st.sampled_from(["", "@1.5"]))
def test_the_column_is_where_the_bad_symbol_starts(tokens, at, bad, gap, indent, start):
    at = min(at, len(tokens))
    tokens = [*tokens[:at], "q" + bad + "r", *tokens[at:]]
    line = f"{indent}arm{start}:{gap}{gap.join(tokens)}"
    error = _refused(f"hip: a\n{line}\n")
    offset = line.index("q" + bad)
    assert (error.line, error.column) == (2, offset + 1), (line, str(error))
