"""The quick checks of displacements and durations (every value a finite int or float,
checked in C) say what the check of one value at a time says: the same values accepted and
stored, the same first value refused with the same message."""

from __future__ import annotations

import math
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import Actiongram, FormatError
from psgs.actiongram import _faults
from psgs.actiongram._checks import (_bad_displacement, _bad_duration,
                                     _plain_displacements, _plain_durations)

#: every kind of value a displacement may be given as: the plain ones most of the time (the
#: quick check's case), and among them what is refused or takes the slow path
VALUES = st.one_of(
    st.floats(allow_nan=False, allow_infinity=False),
    st.integers(-10**6, 10**6),
    st.sampled_from([0.0, -0.0, 5e-324, 1.7976931348623157e308, -1.7976931348623157e308,
                     10**308, 10**309, -10**400, 2**1024, 2**1024 - 1, float("nan"),
                     float("inf"), -float("inf"), True, False, np.bool_(True), np.int64(3),
                     np.uint8(7), np.float32(0.5), np.float64(-2.5), np.float64("nan"),
                     np.float32("inf"), np.float16(1.5), np.timedelta64(5, "ms"),
                     Fraction(1, 3), Decimal("1.5"), 1j, "1", b"1", None, [1.0], object()]),
)
ROWS = st.one_of(
    st.lists(st.floats(allow_nan=False, allow_infinity=False), max_size=12),  # the usual row
    st.lists(VALUES, max_size=12),
)


def _one_by_one(values: tuple) -> tuple[int, str] | None:
    """The check before the quick one: each value in turn, the first refused and why."""
    for j, value in enumerate(values):
        problem = _bad_displacement(value)
        if problem is not None:
            return j, problem
    return None


@settings(max_examples=400, deadline=None)
@given(ROWS)
def test_the_quick_check_accepts_only_what_each_value_s_check_accepts(row):
    values = tuple(row)
    quick = _plain_displacements(values)
    slow = _one_by_one(values)
    assert not (quick and slow is not None), (values, slow)  # never a refused value let pass
    if set(map(type, values)) <= {int, float} and slow is None:
        assert quick  # and the plain rows it is for take it


@settings(max_examples=400, deadline=None)
@given(ROWS)
def test_the_string_s_fault_is_the_one_of_each_value_s_check(row):
    values = tuple(row)
    string = _faults.StringFields("a", ("x",) * len(values), (1.0,) * len(values)).given(values)
    fault = _faults._displacement_values(string)
    slow = _one_by_one(values)
    if slow is None:
        assert fault is None
    else:
        assert fault == _faults.Fault(f"string 'a': {slow[1]}", (("displacements", slow[0]),))


@settings(max_examples=300, deadline=None)
@given(ROWS)
def test_the_durations_quick_check_accepts_only_what_each_value_s_check_accepts(row):
    # the same finiteness in C (math.isfinite mapped) serves the durations' quick check
    values = tuple(abs(v) if type(v) in (int, float) and not v != v else v for v in row)
    refused = [v for v in values if _bad_duration(v) is not None]
    assert not (_plain_durations(values) and refused), refused
    if set(map(type, values)) <= {int, float} and not refused:
        assert _plain_durations(values)


def _made(rows, keep_repeats: bool, quick: bool):
    """The actiongram of ``rows`` (per string a displacement row or None, and how many
    symbols more than the row's values it has), or the error refusing it, with or without
    the quick check."""
    with pytest.MonkeyPatch.context() as monkeypatch:
        if not quick:
            monkeypatch.setattr(_faults, "_plain_displacements", lambda values: False)
        symbols = tuple(tuple("xxy"[j % 3] for j in range(len(r or (0,)) + more))
                        for r, more in rows)
        try:
            ag = Actiongram(tuple(f"s{k}" for k in range(len(rows))), symbols,
                            tuple((0.5,) * len(s) for s in symbols),
                            segment_displacements=tuple(r for r, _ in rows),
                            keep_repeats=keep_repeats)
        except (FormatError, ValueError, TypeError) as exc:
            return type(exc).__name__, str(exc)
    # repr tells -0.0 from 0.0 and shows a nan; and the types of what is stored
    return [None if r is None else [(type(v).__name__, repr(v)) for v in r]
            for r in ag.segment_displacements]


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.one_of(st.none(), ROWS), st.sampled_from([0, 0, 0, 1])),
                min_size=1, max_size=4), st.booleans())
def test_an_actiongram_is_made_or_refused_alike_with_and_without_the_quick_check(rows,
                                                                                 keep_repeats):
    assert _made(rows, keep_repeats, True) == _made(rows, keep_repeats, False)


def test_the_first_fault_in_the_strings_order_is_named_alike():
    # a count wrong in the first string is named before a nan of the second; a bool of the
    # first before a count of the second (each string's checks in turn, then the next's)
    for rows in ([((1.0, 2.0), 1), ((float("nan"),), 0)],
                 [((1.0, True), 0), ((1.0,), 1)],
                 [((1.0, 2.0), 0), ((np.float32("inf"), 10**400), 0)]):
        quick = _made(rows, False, True)
        assert quick == _made(rows, False, False)
        assert quick[0] == "FormatError", quick
    assert _made([((1.0, 2.0), 1), ((float("nan"),), 0)], False, True)[1] == \
        "Actiongram: string 's0' has 3 symbols but 2 displacements"
    assert _made([((1.0, True), 0), ((1.0,), 1)], False, True)[1] == \
        "Actiongram: string 's0': a displacement must be a number, not True"
    assert _made([((1.0, 2.0), 0), ((np.float32("inf"), 10**400), 0)], False, True)[1] == \
        "Actiongram: string 's1': a displacement must be finite, not np.float32(inf)"


def test_plain_rows_take_the_quick_check_alone(monkeypatch):
    # a value at a time was most of a large actiongram's construction: a row of ints and
    # floats asks nothing of the one-value check
    def called(value):
        raise AssertionError(f"the one-value check was asked about {value!r}")

    monkeypatch.setattr(_faults, "_bad_displacement", called)
    rows = ((1, -2.5, 0.0, 3), (1e308, -1e308, 5e-324, -0.0))
    ag = Actiongram(("a", "b"), (("x", "y", "x", "y"),) * 2, ((1.0,) * 4,) * 2,
                    segment_displacements=rows)
    assert ag.segment_displacements == tuple(tuple(map(float, r)) for r in rows)
    assert all(type(v) is float for r in ag.segment_displacements for v in r)
    assert math.copysign(1, ag.segment_displacements[1][3]) == -1.0
