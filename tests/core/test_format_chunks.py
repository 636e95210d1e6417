"""The text format read a chunk of lines at a time, and a long line token by token.

``psgs.loads`` parses a file in chunks of whole lines so that lark's tokens (hundreds of bytes
each) are held for one chunk, not the whole file; a line longer than a chunk is read from the
lexer's tokens as they come. These tests read the same texts with chunks of a few characters
(every rule and tuple line then takes the token-by-token path) and as one chunk, the way the
parser alone reads them, and ask for the same answer.
"""

from __future__ import annotations

import random
import tracemalloc
from unittest import mock

import lark
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import psgs.strategies as pst
from psgs import FormatError, dumps, loads
from psgs import _format_reader

from test_format import ERRORS

WHOLE = 1 << 40  # one chunk: the text read as the parser alone reads it
SMALL_CHUNKS = (1, 7, 40)


def _read(text: str, chunk: int):
    with mock.patch.object(_format_reader, "_CHUNK", chunk):
        try:
            return loads(text, source="t.psgs")
        except FormatError as error:
            return error


def _first_syntax_error(text: str):
    """Where the parser alone first fails on ``text`` (as loads prepares it), or None."""
    text = text[1:] if text.startswith("\ufeff") else text
    text = text if text.endswith("\n") else text + "\n"
    try:
        _format_reader._parser().parse(text)
    except lark.exceptions.UnexpectedInput as exc:
        return (exc.line, exc.column)
    return None


def _same_answer(text: str) -> None:
    whole = _read(text, WHOLE)
    syntax = _first_syntax_error(text)
    for chunk in SMALL_CHUNKS:
        got = _read(text, chunk)
        if syntax is None or not isinstance(whole, FormatError):
            # no syntax error: the builder reads the same lines in the same order
            assert type(got) is type(whole) and str(got) == str(whole), (chunk, text)
            continue
        # a syntax error: read in chunks, a mistake of meaning on a line before it (or on
        # the same line, before it) may be met first, never one after it
        assert isinstance(got, FormatError), (chunk, text)
        assert (got.line, got.column) <= syntax, (chunk, str(got), syntax)
        if (got.line, got.column) == syntax:
            assert str(got) == str(whole), (chunk, text)


@pytest.mark.parametrize("name,text,line,column,words", ERRORS, ids=[e[0] for e in ERRORS])
@pytest.mark.parametrize("chunk", SMALL_CHUNKS)
def test_every_mistake_is_found_where_it_is_whatever_the_chunks(name, text, line, column,
                                                                words, chunk):
    error = _read(text, chunk)
    assert isinstance(error, FormatError)
    assert (error.line, error.column) == (line, column) and words in error.message, str(error)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.one_of(pst.psgs_systems(max_components=3), pst.pcgs_systems(max_components=3)))
def test_a_system_reads_back_the_same_in_any_chunks(system):
    text = dumps(system)
    for chunk in SMALL_CHUNKS:
        assert _read(text, chunk) == system


@settings(max_examples=150, deadline=None)
@given(st.text(alphabet=st.sampled_from(list('psgcomnt SAB:->"()#,\n?ε→ab12_/\r')),
               max_size=80))
def test_arbitrary_text_gets_the_same_answer_in_chunks(text):
    _same_answer(text)


@settings(max_examples=50, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(pst.psgs_systems(max_components=3), st.randoms(use_true_random=False),
       st.lists(st.sampled_from(list('S:->"()#,\n?ε→a1 /\\\x00')), min_size=1, max_size=3))
def test_a_damaged_system_gets_the_same_answer_in_chunks(system, rnd, inserted):
    text = dumps(system)
    for character in inserted:  # characters put in, or put in place of others, anywhere
        at = rnd.randrange(len(text) + 1)
        text = text[:at] + character + text[at + rnd.randrange(2):]
    _same_answer(text)


def _memory(text: str) -> tuple[int, int]:
    """Bytes allocated at the peak of reading ``text``, and still held by the system read."""
    tracemalloc.start()
    try:
        system = loads(text)  # noqa: F841 - held, so that what it takes is counted as held
        held, peak = tracemalloc.get_traced_memory()
        return peak, held
    finally:
        tracemalloc.stop()


def test_reading_holds_one_chunk_of_tokens_beyond_the_system_not_a_token_per_symbol():
    rng = random.Random(3)
    # a quarter of the reader's chunk, and texts a quarter as long: what is measured is the
    # tokens held against the chunk, the same ratio at any size, in a quarter of the time.
    # One rule of 15,000 symbols on one line (over 3 times a chunk), and 1,200 rules and
    # their tuples on lines of their own
    chunk = _format_reader._CHUNK // 4
    line = " ".join(f'"{rng.choice("abcd")}"' for _ in range(15_000))
    one_line = f'psgs Big\ncomponent G start S\n  p1: S -> {line}\n  p2: S -> "a"\n'
    rules = [f'  r{i}: S -> {" ".join(chr(97 + int(c)) for c in bin(i)[2:])} S'
             for i in range(1_200)]
    many = ("psgs Many\ncomponent G start S\n" + "\n".join(rules) + '\n  e: S -> "e"\n'
            "  x: a -> \"x\"\n  y: b -> \"y\"\ncomponent H start T\n  t: T -> \"t\"\nsync\n"
            + "\n".join(f"  (r{i}, #)" for i in range(1_200)) + "\n")
    for text in (one_line, many):
        assert len(text) > 3 * chunk
        with mock.patch.object(_format_reader, "_CHUNK", chunk):
            peak, held = _memory(text)
        # beyond the system, lark's tokens of one chunk at most (~100 bytes a character);
        # for the whole text at once, as before chunks, they were 5.5 and 5.6 MB here
        # against the 2.5 MB allowed (at four times the sizes, 22 and 20 MB against 9.8)
        assert peak - held < 150 * chunk, (len(text), peak, held)
