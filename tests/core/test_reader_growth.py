"""The readers of psgs take time in proportion to what they read, however bad the input.

Each regression test reads the worst input found for a reader that once took time growing
with the square of the input's size, at a size where that reader took well over the suite's
15 s a test, and checks what is read (not how long it takes): the reader of today answers in
milliseconds. Each change of a pattern comes with a property test that the new way reads what
the old one did. ``psgs show`` sorted names by ``int()``, whose time grows with the square of
the digits too: Python refuses 4,300 digits and more, so a longer run was a ValueError.
"""

from __future__ import annotations

import json
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import Actiongram, FormatError, ValidationError
from psgs.actiongram._json_form import _JSON_TOKEN, _json_tokens
from psgs.cli import main
from psgs.cli.core import _natural_key
from psgs.model import PCGS, Grammar, Nonterminal, Query, Rule, Terminal

#: JSON values of every kind, nested a little (NaN and the infinities too: json.loads reads them)
VALUES = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=6),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=4), inner,
                                                                max_size=4),
    max_leaves=12)
#: JSON's white space, as a document may have it between tokens and around the whole
SPACE = st.text(alphabet=" \t\n\r", max_size=4)


@settings(max_examples=150, deadline=None)
@given(value=VALUES, before=SPACE, after=SPACE, comma=SPACE, colon=SPACE,
       indent=st.none() | st.sampled_from(["", "\t", " \r\n", "  "]),
       ascii_only=st.booleans())
def test_json_tokens_are_the_ones_finditer_found(value, before, after, comma, colon, indent,
                                                 ascii_only):
    """On any text json.loads reads, the tokens read one after another are finditer's."""
    text = before + json.dumps(value, indent=indent, separators=(comma + ",", colon + ":"),
                               ensure_ascii=ascii_only) + after
    json.loads(text)  # a document the actiongram reader has decoded before it places an error
    old = [(m.group(1), m.start(1)) for m in _JSON_TOKEN.finditer(text)]
    assert [(m.group(1), m.start(1)) for m in _json_tokens(text)] == old


@pytest.mark.parametrize("space", [" ", "\n", "\r\n\t"])
def test_a_json_error_is_placed_past_much_white_space(space):
    # white space after the document, where no token follows: the place of the error was
    # found by a walk that read it again from every character (20,000 spaces took 6 s)
    text = '{"strings": [5]}' + space * (50_000 // len(space))
    with pytest.raises(FormatError) as caught:
        Actiongram.from_json(text, source="walk.json")
    assert "strings[0] must be an object" in caught.value.message
    assert (caught.value.line, caught.value.column) == (1, 14)


#: names with runs of digits of several scripts (ASCII, Arabic-Indic, Devanagari), leading
#: zeros and digits that are no decimals ('²')
NAMED = st.text(alphabet="a.0019\u0660\u0661\u0969\u00b2", max_size=6)


@settings(max_examples=500, deadline=None)
@given(NAMED, NAMED)
def test_the_natural_order_is_the_order_of_int(x, y):
    def old(name):  # runs of digits by int(), which reads every script's
        return [int(p) if k % 2 else p for k, p in enumerate(re.split(r"(\d+)", name))]

    assert (_natural_key(x) < _natural_key(y), _natural_key(x) == _natural_key(y)) == \
        (old(x) < old(y), old(x) == old(y))


def test_show_sorts_a_terminal_of_more_digits_than_int_reads(capsys, tmp_path):
    # int() refuses 4,300 digits and more (its time grows with their square): show raised
    path = tmp_path / "digits.psgs"
    many = "1" * 5_000
    path.write_text(f'psgs D\ncomponent A start S\n  p: S -> "a{many}" "a2" "{many}0" "3"\n',
                    encoding="utf-8")
    assert main(["show", str(path)]) == 0
    assert f"T (4): 3 {many}0 a2 a{many}\n" in capsys.readouterr().out


def test_a_query_of_no_component_among_many_components_is_named():
    # every query was searched for in the list of the components' names: 20,000 components
    # that query the last one took 5 s to check (2e9 comparisons here: some 25 s)
    many, start = 45_000, Nonterminal("S")
    asks_last = (Rule("p", start, (Terminal("a"), Query(f"G{many - 2}"))),)
    components = [Grammar(f"G{i}", start, asks_last) for i in range(many - 1)]
    components.append(Grammar("Z", start, (Rule("p", start, (Query("H"),)),)))
    with pytest.raises(ValidationError, match=r"component Z: query \?H names no component"):
        PCGS(tuple(components))


# -- DECIMAL: a number's digits read once ---------------------------------------------------
#: the pattern before: '\d+\.?\d*' tried every split of a run of digits between its two parts
_OLD_DECIMAL = re.compile(r"[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|inf(?:inity)?|nan)\Z",
                          re.ASCII | re.IGNORECASE)


@settings(max_examples=500, deadline=None)
@given(st.text(alphabet="0123456789.eE+-infatyIN x", max_size=12))
def test_decimal_accepts_what_the_old_pattern_did(text):
    from psgs._foundation.text import DECIMAL

    assert bool(DECIMAL.match(text)) == bool(_OLD_DECIMAL.match(text))


def test_a_long_run_of_digits_and_a_letter_is_refused():
    from psgs._foundation.text import decimal

    assert decimal("1" * 200_000 + "x") is None  # the old pattern: minutes
    assert decimal("0" * 200_000 + "1.5") == 1.5
