"""The text and JSON readers refuse what the constructor refuses, with its message, and place
it where the fault the message names stands.

Both readers place a fault by the constructor's own list of checks
(``psgs.actiongram._faults.CHECKS``): there is no second copy of its order to drift. Here the
place expected is read from the message alone (the string it names, the symbol, the duration
that vanishes, the times or displacements that overflow), not from that list.
"""

from __future__ import annotations

import json
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import Actiongram, FormatError
from psgs.actiongram._faults import CHECKS, STRING_CHECKS, first_fault, strings_of

NAMES = ["a", "knee.rx", "hip", "\u00e9.x"]
GOOD_SYMBOLS = ["B", "G", "x1"]
#: refused by the constructor, read by the text form: an invisible format character, a C1
#: control, a byte-order mark inside a symbol, a lone surrogate
BAD_SYMBOLS = ["b\u200bc", "\x9b", "q\ufeffr", "\ud800"]
GOOD_DURATIONS = [1.0, 0.5, 2.25]
STARTS = [0.0, 1.5, -1e15]
#: what spoils a string: a symbol the constructor refuses, a duration that vanishes beside its
#: start time, times that overflow, equal neighbours whose displacements add up past the floats
SPOILS = ["symbol", "vanishing", "times overflow", "displacements overflow"]

# the strategies mutated() draws from, made once: hypothesis validates a strategy and works out
# its properties the first time it draws from it, which for strategies made afresh in every
# example cost more than the drawing (they draw the same either way)
_NAMES = st.lists(st.sampled_from(NAMES), min_size=1, max_size=4, unique=True)
_SYMBOLS = [st.lists(st.sampled_from(GOOD_SYMBOLS), min_size=n, max_size=n) for n in range(6)]
_DURATIONS = [st.lists(st.sampled_from(GOOD_DURATIONS), min_size=n, max_size=n)
              for n in range(6)]
_STARTS = st.sampled_from(STARTS)
_DISPLACEMENTS = [st.none() | st.lists(st.sampled_from([0.0, 1.0, -2.5]), min_size=n,
                                       max_size=n) for n in range(6)]
# (the displacements' checks come after every string's: its spoil is drawn more often so that
# it is the first fault often enough)
_SPOILS = st.sampled_from(SPOILS + SPOILS[-1:] * 3)
_BAD_SYMBOLS = st.sampled_from(BAD_SYMBOLS)


@st.composite
def mutated(draw):
    """The fields of a good actiongram with a few of its strings spoilt: (names, symbols,
    durations, starts, displacements, keep_repeats)."""
    names = draw(_NAMES)
    symbols, durations, starts, displacements = [], [], [], []
    for _ in names:
        count = draw(st.integers(0, 5))
        symbols.append(draw(_SYMBOLS[count]))
        durations.append(draw(_DURATIONS[count]))
        starts.append(draw(_STARTS))
        displacements.append(draw(_DISPLACEMENTS[count]))
    for _ in range(draw(st.integers(0, 3))):
        k = draw(st.integers(0, len(names) - 1))
        if not symbols[k]:
            continue
        j = draw(st.integers(0, len(symbols[k]) - 1))
        spoil = draw(_SPOILS)
        if spoil == "symbol":
            symbols[k][j] = draw(_BAD_SYMBOLS)
        elif spoil == "vanishing":
            starts[k], durations[k][j] = 1e15, 1e-9
        elif spoil == "times overflow":
            starts[k], durations[k][j] = 1e308, 1e308
        elif j + 1 < len(symbols[k]):
            symbols[k][j + 1] = symbols[k][j]
            displacements[k] = displacements[k] or [0.0] * len(symbols[k])
            displacements[k][j] = displacements[k][j + 1] = 1e308
    return (names, [tuple(s) for s in symbols], [tuple(d) for d in durations], starts,
            [None if d is None else tuple(d) for d in displacements], draw(st.booleans()))


def text_form(fields) -> tuple[str, list[int]]:
    """The text form of ``fields`` (line k + 1 is string k, or k + 2 after %keep_repeats),
    and the column at which each token starts, per string."""
    names, symbols, durations, starts, displacements, keep = fields
    lines, columns = ["%keep_repeats"] if keep else [], []
    for name, syms, durs, start, disps in zip(names, symbols, durations, starts, displacements):
        line = f"{name}@{start!r}:" if start else f"{name}:"
        at = []
        for j, (sym, dur) in enumerate(zip(syms, durs)):
            line += " "
            at.append(len(line) + 1)
            line += f"{sym}@{dur!r}" + ("" if disps is None else f"~{disps[j]!r}")
        lines.append(line)
        columns.append(at)
    return "\n".join(lines) + "\n", columns


def json_form(fields) -> str:
    names, symbols, durations, starts, displacements, keep = fields
    strings = [{"name": n, "start": t, "symbols": list(s), "durations": list(d),
                **({} if x is None else {"displacements": list(x)})}
               for n, s, d, t, x in zip(names, symbols, durations, starts, displacements)]
    # one value a line: the line of an error says which value it is at
    return json.dumps({"strings": strings, "keep_repeats": keep}, indent=1)


def outcome(read):
    try:
        return read()
    except FormatError as error:
        return error


def where_named(message: str, fields) -> tuple[int, tuple]:
    """The string a message of the constructor names, and the field it says is at fault,
    read from the words of the message."""
    names, symbols = fields[0], fields[1]
    k = next(k for k, name in enumerate(names) if message.startswith(f"string {name!r}"))
    vanishing = re.search(r" of symbols? (\d+)", message)
    if vanishing:
        return k, ("durations", int(vanishing.group(1)) - 1)
    symbol = next((j for j, sym in enumerate(symbols[k]) if f"symbol {sym!r} " in message),
                  None)
    if symbol is not None:
        return k, ("symbols", symbol)
    if "its times overflow" in message:
        return k, ("durations",)
    assert "its displacements overflow" in message, message
    return k, ("displacements",)


@settings(max_examples=150, deadline=None)
@given(mutated())
def test_the_readers_refuse_what_the_constructor_refuses_with_its_message_at_its_place(fields):
    names, symbols, durations, starts, displacements, keep = fields
    made = outcome(lambda: Actiongram(tuple(names), tuple(symbols), tuple(durations),
                                      tuple(starts), tuple(displacements), (), (), keep))
    text, columns = text_form(fields)
    document = json_form(fields)
    from_text = outcome(lambda: Actiongram.from_text(text, source="t.txt"))
    from_json = outcome(lambda: Actiongram.from_json(document, source="t.json"))
    if not isinstance(made, FormatError):
        assert from_text == made and from_json == made
        return
    assert isinstance(from_text, FormatError) and isinstance(from_json, FormatError), text
    assert from_text.message == made.message == from_json.message, text
    k, field = where_named(made.message, fields)
    # the text form: the token of the symbol or duration named, else the string's name
    line = k + 1 + keep
    column = columns[k][field[1]] if len(field) == 2 else 1
    assert (from_text.line, from_text.column) == (line, column), (str(from_text), text)
    # the JSON form: the value named (a symbol, a duration), or the list at fault
    shown = document.split("\n")[from_json.line - 1][from_json.column - 1:]
    value = fields[1 if field[0] == "symbols" else 2][k][field[1]] if len(field) == 2 else None
    expected = json.dumps(value) if value is not None else "["
    assert shown.startswith(expected), (str(from_json), document)
    if len(field) == 1:
        assert document.split("\n")[from_json.line - 1].lstrip().startswith(
            f'"{field[0]}": ['), (str(from_json), document)


def test_the_constructor_raises_the_first_fault_of_the_table():
    """The table's order is the constructor's: every string's symbols before any string's
    displacements, so the second string's bad symbol is the error, not the first string's
    displacements that overflow."""
    names, symbols = ("s", "t"), (("a", "a"), ("b\u200b",))
    durations, displacements = ((1, 1), (1,)), ((1e308, 1e308), None)
    strings = strings_of(names, symbols, durations, (0, 0), False, displacements, ("s", "t"))
    k, fault = first_fault(strings)
    assert (k, fault.fields) == (1, (("symbols", 0),))
    with pytest.raises(FormatError) as made:
        Actiongram(names, symbols, durations, (), displacements)
    assert made.value.message == fault.message
    # the text form places it at the symbol, on the second line (it named the first line's
    # displacements once, as the first string, built alone, was refused)
    with pytest.raises(FormatError) as read:
        Actiongram.from_text("s: a@1~1e308 a@1~1e308\nt: b\u200b\n", source="t.txt")
    assert (read.value.line, read.value.column, read.value.message) == (2, 4, fault.message)
    # each list of checks runs over every string before the next list
    assert first_fault(strings, (CHECKS[1],))[0] == 0
    assert first_fault(strings, (STRING_CHECKS,)) == (k, fault)
