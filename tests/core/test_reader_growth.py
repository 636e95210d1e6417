"""The readers of psgs take time in proportion to what they read, however bad the input.

Each regression test reads the worst input found for a reader that once took time growing
with the square of the input's size, at a size where that reader took well over the suite's
15 s a test, and checks what is read (not how long it takes): the reader of today answers in
milliseconds. Each change of a pattern comes with a property test that the new way reads what
the old one did.
"""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import Actiongram, FormatError
from psgs.actiongram._text import _JSON_TOKEN, _json_tokens

#: JSON values of every kind, nested a little (NaN and the infinities too: json.loads reads them)
VALUES = st.recursive(
    st.none() | st.booleans() | st.integers() | st.floats() | st.text(max_size=6),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=4), inner,
                                                                max_size=4),
    max_leaves=12)
#: JSON's white space, as a document may have it between tokens and around the whole
SPACE = st.text(alphabet=" \t\n\r", max_size=4)


@settings(max_examples=300, deadline=None)
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
