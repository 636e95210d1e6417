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
    # a vanishing duration is the string's times, not one bad symbol
    error = _refused("hip: a\n  s@1e15: a@1e-9 b@1e-9\n")
    assert (error.line, error.column) == (2, 3) and "vanishes" in error.message


@settings(max_examples=200, deadline=None)
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
