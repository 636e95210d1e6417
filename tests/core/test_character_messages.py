"""A character at fault is named one way in every message: its code point and, when Unicode
has one, its name (``psgs._foundation.text.character_name``), and where a name or symbol
holds it, which character of it it is. A grammar's terminal and an actiongram's symbol,
name and text say it alike."""

from __future__ import annotations

import re
import unicodedata

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import Actiongram, FormatError, Terminal, ValidationError
from psgs._foundation.text import character_name, first_unseen

# white space and controls (refused by the text format's tokens), invisible format characters
# (refused as a terminal refuses them)
REFUSED = st.one_of(st.sampled_from(["\t", " ", "\xa0", "\x07", "\x1b", "\x9b", "\u2028"]),
                    st.characters(categories=("Cc", "Cf", "Zs"), exclude_characters="\n\r"))
PLAIN = st.text(st.characters(categories=("L", "N")), min_size=1, max_size=3)


@settings(max_examples=150, deadline=None)
@given(PLAIN, REFUSED, PLAIN)
def test_a_symbol_and_a_terminal_name_the_character_they_hold_alike(head, bad, tail):
    symbol = head + bad + tail
    said = f"holds {character_name(bad)} (character {len(head) + 1})"
    with pytest.raises(FormatError) as error:
        Actiongram.from_strings({"s": [symbol]})
    assert said in str(error.value)
    if first_unseen(symbol) is not None:  # a terminal refuses what a reader cannot see
        with pytest.raises(ValidationError) as refused:
            Terminal(symbol)
        assert said in str(refused.value)


CONTROLS = [*range(0x00, 0x20), 0x7F, *range(0x80, 0xA0)]


@pytest.mark.parametrize("code", CONTROLS, ids=lambda code: f"U+{code:04X}")
def test_every_control_character_is_named_by_its_unicode_alias(code):
    # unicodedata.name has none for a control; lookup knows Unicode's aliases, so it is the
    # oracle: the name given is one of the character's own, not another character's
    shown = character_name(chr(code))
    point, _, name = shown.partition(" ")
    assert point == f"U+{code:04X}" and name, shown
    assert unicodedata.lookup(name) == chr(code), shown


@pytest.mark.parametrize("char, said", [
    ("\x00", "U+0000 NULL"), ("\t", "U+0009 CHARACTER TABULATION"), ("\n", "U+000A LINE FEED"),
    ("\x1b", "U+001B ESCAPE"), ("\x7f", "U+007F DELETE"), ("\x80", "U+0080 PADDING CHARACTER"),
    ("\x85", "U+0085 NEXT LINE"), ("\x9b", "U+009B CONTROL SEQUENCE INTRODUCER"),
    ("\x9f", "U+009F APPLICATION PROGRAM COMMAND"),
    # beyond the controls, unicodedata's name, or none
    (" ", "U+0020 SPACE"), ("\xa0", "U+00A0 NO-BREAK SPACE"), ("\ue000", "U+E000"),
])
def test_a_character_is_named_by_code_point_and_name(char, said):
    assert character_name(char) == said


@pytest.mark.parametrize("name, said", [
    ("a b", "actuator name 'a b' holds U+0020 SPACE (character 2)"),
    ("a\xa0b", "actuator name 'a\\xa0b' holds U+00A0 NO-BREAK SPACE (character 2)"),
    ("\ufeffa", "actuator name '\\ufeffa' starts with U+FEFF ZERO WIDTH NO-BREAK SPACE, the "
                "byte-order mark a file's reader drops"),
])
def test_an_actuator_name_names_its_character(name, said):
    with pytest.raises(FormatError, match="^Actiongram: " + re.escape(said)):
        Actiongram.from_strings({name: ["x"]})


@pytest.mark.parametrize("char", ["\x00", "\x0c", "\x85", "\u2028", "\u2029"])
def test_a_control_character_of_the_text_is_named_at_its_place(char):
    with pytest.raises(FormatError) as error:
        Actiongram.from_text(f"a: x y\nb: p{char} q\n", source="t.txt")
    assert str(error.value) == f"t.txt:2:5: control character {character_name(char)} in the text"
    assert str(error.value).isprintable()


def test_a_symbol_names_an_invisible_character_by_its_unicode_name():
    with pytest.raises(FormatError, match=r"t.txt:1:8: string 'hip': symbol 'b\\u200bc' holds "
                                          r"U\+200B ZERO WIDTH SPACE \(character 2\), a control "
                                          r"or invisible format character"):
        Actiongram.from_text("hip: a b\u200bc d\n", source="t.txt")
