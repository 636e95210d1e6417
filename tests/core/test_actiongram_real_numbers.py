"""An actiongram takes every real number as a duration, a start time or a displacement:
Python's int and float, a Fraction, numpy's integer and floating scalars and arrays of them,
each read as the float of its value; a bool, a complex number, text and numpy's timedelta64
stay refused. A value made in memory is refused naming no file."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import Actiongram, FormatError, ValidationError


def test_numpy_durations_starts_and_displacements_are_numbers():
    made = Actiongram.from_strings(
        {"a": "abb", "b": "xy"},
        durations={"a": np.array([1, 2, 3]), "b": np.array([0.5, 1.5], dtype=np.float32)},
        starts={"a": np.int64(3), "b": np.float32(0.25)},
        displacements={"a": np.array([1, -2, 4]), "b": np.array([1.5, 2], dtype=np.float64)})
    plain = Actiongram.from_strings(
        {"a": "abb", "b": "xy"}, durations={"a": [1, 2, 3], "b": [0.5, 1.5]},
        starts={"a": 3, "b": 0.25}, displacements={"a": [1, -2, 4], "b": [1.5, 2.0]})
    assert made == plain and made.to_json() == plain.to_json()
    assert made.durations == {"a": (1.0, 5.0), "b": (0.5, 1.5)}
    # what is stored is Python's float, never a numpy scalar that goes on into every sum
    stored = [*made.origins, *sum(made.segment_durations, ()),
              *sum(made.segment_displacements, ())]
    assert {type(v) for v in stored} == {float}


def test_a_float32_is_read_as_its_value_and_sums_as_a_float():
    # a float32 added to a float stays a float32 under numpy 2: the merged run lost digits
    third = np.float32(1 / 3)
    made = Actiongram.from_strings({"a": "aa"}, durations={"a": [third, third]},
                                   displacements={"a": [third, third]})
    assert made.durations["a"] == (float(third) + float(third),)
    assert made.displacements("a") == (float(third) + float(third),)
    assert type(made.durations["a"][0]) is float


def test_a_fraction_is_a_number():
    made = Actiongram.from_strings({"a": "ab"}, durations={"a": [Fraction(1, 2), 1]},
                                   starts={"a": Fraction(3, 4)})
    assert made.durations["a"] == (0.5, 1.0) and made.origins == (0.75,)


@pytest.mark.parametrize("value, said", [
    (True, "a duration must be a number, not True"),
    (np.bool_(True), "a duration must be a number, not np.True_"),
    (2j, "a duration must be a number, not 2j"),
    (np.complex128(2), "a duration must be a number, not np.complex128(2+0j)"),
    ("1", "a duration must be a number, not '1'"),
    # a Real to numpy, but its count is read without its unit (5 ms as 5)
    (np.timedelta64(5, "ms"), "a duration must be a number, not np.timedelta64(5,'ms')"),
    (np.float64("nan"), "a duration must be positive and finite, not np.float64(nan)"),
    (np.float32("inf"), "a duration must be positive and finite, not np.float32(inf)"),
    (np.int64(0), "a duration must be positive and finite, not np.int64(0)"),
    (Fraction(10 ** 400), "a duration must be positive and finite, not Fraction("),
])
def test_what_is_no_positive_real_number_is_still_refused(value, said):
    with pytest.raises(FormatError) as refused:
        Actiongram.from_strings({"a": "ab"}, durations={"a": [1, value]})
    assert str(refused.value).startswith(f"Actiongram: string 'a': {said}")


@pytest.mark.parametrize("start", [True, np.bool_(False), 1j, "0", np.float64("inf"),
                                   np.timedelta64(1, "s")])
def test_a_start_that_is_no_finite_real_number_is_refused(start):
    with pytest.raises(FormatError, match=r"^Actiongram: string 'a': start time must be a "
                                          r"finite number, not "):
        Actiongram.from_strings({"a": "ab"}, starts={"a": start})


@pytest.mark.parametrize("move", [False, 1j, "1", np.float32("nan"), np.timedelta64(1)])
def test_a_displacement_that_is_no_finite_real_number_is_refused(move):
    with pytest.raises(FormatError, match=r"^Actiongram: string 'a': a displacement must be "):
        Actiongram.from_strings({"a": "ab"}, displacements={"a": [1, move]})


def test_an_event_of_a_numpy_timedelta_is_refused_not_a_type_error():
    # a duration of 5 ms was float()'s TypeError; one of 5 ns was read as 5
    for value in (np.timedelta64(5, "ms"), np.timedelta64(5, "ns")):
        with pytest.raises(ValidationError, match=r"^row 0: duration must be a number, not "
                                                  r"np.timedelta64\(5,"):
            Actiongram.from_events([("s", 0, value, "a")])
    assert Actiongram.from_events([("s", np.int64(1), np.float32(0.5), "a")]).durations == \
        {"s": (0.5,)}


# -- a value made in memory names no file; a file's error names its place, as before --------------
@pytest.mark.parametrize("make, said", [
    (lambda: Actiongram.from_strings({"a": "ab"}, durations={"a": [1, "x"]}),
     "string 'a': a duration must be a number, not 'x'"),
    (lambda: Actiongram(("a",), (("x",),), ((1,),), (), (), (), (("a", "a"),)),
     "skeleton: 'a' is its own parent"),
    (lambda: Actiongram.from_strings({"a": "ab"}, starts={"z": 1}),
     "durations or starts given for unknown string 'z'"),
    (lambda: Actiongram(("a",), (("x",),), ((1,),), keep_repeats=1),
     "keep_repeats must be True or False, not 1"),
    (lambda: Actiongram.from_codes({"a": [0]}, ["x", "y z"]),
     "alphabet: symbol 'y z' holds U+0020 SPACE (character 2): it must have no white space, "
     "control character, '@' or ':' and not start with '#'"),
])
def test_a_value_made_in_memory_is_refused_naming_no_file(make, said):
    # it was '<string>: ...', the source of text read from a string, as if a file were at fault
    with pytest.raises(FormatError) as refused:
        make()
    error = refused.value
    assert (error.message, error.source, error.line, error.column) == \
        (said, "Actiongram", None, None)
    assert str(error) == f"Actiongram: {said}"


def test_the_readers_still_place_the_same_message_in_their_file():
    # the constructor's faults, each at the token or value it names
    with pytest.raises(FormatError) as text:
        Actiongram.from_text("a: x y\ns@1e15: a b@1e-9\n", source="t.txt")
    assert str(text.value) == ("t.txt:2:11: string 's': duration 1e-09 of symbol 2 vanishes "
                               "beside its start time 1000000000000001.0 (T + D == T in "
                               "floating point)")
    document = '{"strings": [{"name": "a", "symbols": ["x", "y"], "durations": [1, true]}]}'
    with pytest.raises(FormatError) as json_form:
        Actiongram.from_json(document, source="t.json")
    assert str(json_form.value) == ("t.json:1:68: string 'a': a duration must be a number, "
                                    "not True")


# -- numpy and Python numbers of equal value: equal actiongrams -------------------------------
def _as_numpy(value, kind: int):
    """``value`` as a numpy scalar of the same value (``kind`` picks the type)."""
    if isinstance(value, int):
        return (np.int64, np.int32, np.uint16 if value >= 0 else np.int16)[kind % 3](value)
    return np.float64(value)


_INTS = st.integers(-1000, 1000)
_FLOATS = st.floats(-1e6, 1e6, allow_nan=False, allow_infinity=False)
_FLOAT32 = _FLOATS.map(lambda x: float(np.float32(x)))  # values a float32 holds exactly


# the strategies rows() and actiongram_fields() draw from, made once: hypothesis validates a
# strategy and works out its properties the first time it draws from it, which for strategies
# made afresh in every example cost more than the drawing (they draw the same either way)
_NUMBERS = {True: st.one_of(st.integers(1, 1000), st.floats(1e-3, 1e3), _FLOAT32.filter(
    lambda x: 1e-3 <= x)), False: st.one_of(_INTS, _FLOATS, _FLOAT32)}
_SIZES = st.integers(0, 6)
_VALUES = {(positive, size): st.lists(_NUMBERS[positive], min_size=size, max_size=size)
           for positive in (True, False) for size in range(7)}
_KINDS = {size: st.lists(st.integers(0, 5), min_size=size, max_size=size) for size in range(7)}
_NAMES = st.lists(st.sampled_from(["knee.rx", "knee.ry", "hip", "s"]), min_size=1, max_size=4,
                  unique=True)
_SYMBOLS = {size: st.lists(st.sampled_from("ab"), min_size=size, max_size=size)
            for size in range(7)}  # equal neighbours: merged
_MOVES = {size: st.none() | st.lists(st.one_of(_INTS, _FLOATS, _FLOAT32), min_size=size,
                                     max_size=size) for size in range(7)}
_STARTS = st.one_of(st.integers(-100, 100), _FLOATS, _FLOAT32)
_HOW = st.sampled_from(["scalars", "arrays"])


@st.composite
def rows(draw, positive: bool):
    """A row of numbers (Python's), and how each is to be given as numpy's."""
    size = draw(_SIZES)
    values = draw(_VALUES[positive, size])
    return values, draw(_KINDS[size])


@st.composite
def actiongram_fields(draw):
    names = draw(_NAMES)
    fields = {}
    for name in names:
        durations, kinds = draw(rows(positive=True))
        symbols = draw(_SYMBOLS[len(durations)])
        moves = draw(_MOVES[len(durations)])
        start = draw(_STARTS)
        fields[name] = (symbols, durations, kinds, moves, start)
    return fields, draw(st.booleans()), draw(_HOW)


def _numpy_row(values, kinds, how):
    if how == "arrays" and values and all(isinstance(v, int) for v in values):
        return np.array(values, dtype=np.int64)
    if how == "arrays" and values and all(float(np.float32(v)) == v for v in values):
        return np.array(values, dtype=np.float32)
    return [_as_numpy(v, k) if isinstance(v, int) else
            (np.float32(v) if k % 2 and float(np.float32(v)) == v else np.float64(v))
            for v, k in zip(values, kinds)]


def _build(fields, keep, numpy_how):
    strings, durations, starts, moves = {}, {}, {}, {}
    for name, (symbols, durs, kinds, disp, start) in fields.items():
        strings[name] = symbols
        durations[name] = _numpy_row(durs, kinds, numpy_how) if numpy_how else durs
        starts[name] = (_as_numpy(start, 0) if isinstance(start, int) else np.float64(start)) \
            if numpy_how else start
        if disp is not None:
            moves[name] = _numpy_row(disp, [1] * len(disp), numpy_how) if numpy_how else disp
    try:
        return Actiongram.from_strings(strings, durations, starts, displacements=moves,
                                       keep_repeats=keep)
    except FormatError as error:
        return error.message  # (durations that vanish beside a start): the same refusal


@settings(max_examples=150)
@given(actiongram_fields())
def test_numpy_and_python_numbers_of_equal_value_give_equal_actiongrams(case):
    fields, keep, how = case
    plain = _build(fields, keep, None)
    made = _build(fields, keep, how)
    assert made == plain
    if isinstance(plain, Actiongram):
        assert made.to_json() == plain.to_json() and made.to_text() == plain.to_text()
