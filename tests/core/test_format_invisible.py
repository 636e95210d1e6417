"""Names and terminals of the text format hold no control character (C0, DEL, C1) and no
invisible format character (U+200B, U+FEFF, ...): written as they are or as a JSON escape, one
is refused with the line and the column where it stands. What the writer emits reads back
identically."""

from __future__ import annotations

import json

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import psgs
from psgs import Actiongram, FormatError, Grammar, Nonterminal, PSGS, Rule, Terminal
from psgs import dumps, loads
from psgs._foundation.text import character_name
from psgs.writing import _quote

HEAD = "psgs G\ncomponent A start S\n"
QUOTE_COLUMN = len('  p: S -> ') + 1  # the column of a terminal's opening quote

# each kind: C0 and DEL (the lexer and json refused C0 raw; escaped, the terminal did), C1
# (accepted before, U+0080-U+009F: U+009B begins an escape sequence on a terminal), and
# format characters (accepted before): soft hyphen, zero-width space and joiners, the
# direction marks and overrides, word joiner, U+FEFF, a tag character
REFUSED = ["\x01", "\x1b", "\x7f", "\x80", "\x9b", "\x9f", "\u00ad", "\u200b", "\u200c",
           "\u200d", "\u200e", "\u202e", "\u2060", "\ufeff", "\U000e0041"]
allowed = st.characters(exclude_categories=("Cs", "Cc", "Cf", "Zs", "Zl", "Zp"))
plain_texts = st.text(allowed, max_size=4).filter(lambda t: not any(c.isspace() for c in t))
refused_chars = st.one_of(st.sampled_from(REFUSED),
                          st.characters(categories=("Cc", "Cf"), exclude_characters="\n\r"))


def _body(text: str) -> str:
    """``text`` inside its quotes as the writer writes it."""
    return _quote(text)[1:-1]


@settings(max_examples=200, deadline=None)
@given(plain_texts, refused_chars, plain_texts, st.booleans())
def test_a_terminal_holding_one_is_refused_at_its_column(before, bad, after, escaped):
    written = json.dumps(bad)[1:-1] if escaped else bad
    text = HEAD + f'  p: S -> "{_body(before)}{written}{_body(after)}"\n'
    with pytest.raises(FormatError) as info:
        loads(text, source="x.psgs")
    error = info.value
    assert (error.line, error.column) == (3, QUOTE_COLUMN + 1 + len(_body(before))), str(error)
    # named alike, raw or escaped, by the lexer, json or the terminal: 'U+001B ESCAPE'
    assert character_name(bad) in str(error), str(error)
    assert str(error).isprintable() and "\n" not in str(error)


@pytest.mark.parametrize("bad", REFUSED[3:])  # C0 and DEL: the lexer's own test covers them
def test_a_name_holding_one_is_refused_at_its_column(bad):
    with pytest.raises(FormatError) as info:
        loads(HEAD + f'  p: S{bad} -> "a"\n', source="x.psgs")
    assert (info.value.line, info.value.column) == (3, 7)
    assert f"unexpected character {character_name(bad)}" in str(info.value)
    assert str(info.value).isprintable()


@pytest.mark.parametrize("bad", REFUSED)
def test_the_model_refuses_them_naming_the_character(bad):
    with pytest.raises(psgs.ValidationError, match=f"U\\+{ord(bad):04X}.*character 3"):
        Terminal("up" + bad + "x")
    # an actiongram's symbol becomes a terminal of the grammar learnt from it
    with pytest.raises(FormatError, match=f"U\\+{ord(bad):04X}|control character"):
        Actiongram.from_strings({"knee": ["a", "b" + bad]})


def test_what_stays_allowed():
    # letters of any script, combining and variation marks, private use, unassigned
    for text in ("döwn", "e\u0301", "\u2764\ufe0f", "\ue000", "\u0378", "😀", "a\\b", 'q"'):
        system = loads(HEAD + f"  p: S -> {_quote(text)}\n")
        assert system.components[0].rules[0].rhs == (Terminal(text),)


# made once: hypothesis validates a strategy the first time it draws from it, which for one
# made afresh in every example cost more than the drawing (it draws the same)
_TEXTS = st.lists(st.text(allowed, min_size=1, max_size=5)
                  .filter(lambda t: t != "S" and not any(c.isspace() for c in t)),
                  min_size=1, max_size=4, unique=True)


@st.composite
def systems_of_odd_terminals(draw):
    texts = draw(_TEXTS)
    S = Nonterminal("S")
    rules = tuple(Rule(f"p{k}", S, (Terminal(t), S)) for k, t in enumerate(texts))
    return PSGS((Grammar("G", S, rules + (Rule("end", S, ()),)),))


@settings(max_examples=75, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(systems_of_odd_terminals())
def test_the_writer_s_text_reads_back_identically(system):
    text = dumps(system)
    assert loads(text) == system
    assert dumps(loads(text)) == text
    # every character a reader cannot see is written as an escape
    assert all(line.isprintable() for line in text.split("\n"))
