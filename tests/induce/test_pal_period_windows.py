"""The period mode reports a string's copies only where the string is, and only strings that
repeat at the same times as another."""

from __future__ import annotations

from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import Actiongram
from psgs.induce import PAL

FIGURE = "abcdbacd"


def test_strings_repeating_at_other_times_are_not_in_step():
    # the same figure twice in each, but one string ends before the other begins
    ag = Actiongram.from_strings({"a": FIGURE * 2, "b": FIGURE * 2}, starts={"b": 100.0})
    result = PAL(min_copies=2, timing="period").induce(ag)
    assert result.components == ()


@settings(max_examples=30, deadline=None, derandomize=True)
@given(late=st.integers(0, 4), copies=st.integers(2, 4))
def test_a_copy_lies_where_its_string_is(late, copies):
    # two strings the whole time, a third that joins later: each copy reported lies inside
    # its string's time
    start = 8.0 * late
    strings = {"a": FIGURE * 6, "b": FIGURE * 6, "c": FIGURE * copies}
    ag = Actiongram.from_strings(strings, starts={"c": start})
    result = PAL(min_copies=2, timing="period").induce(ag)
    assert {"a", "b"} <= set(result.components)
    spans = {"a": (0.0, 48.0), "b": (0.0, 48.0), "c": (start, start + 8.0 * copies)}
    for name in result.components:
        lo, hi = spans[name]
        for a, b in result.occurrences[name]:
            # a window may reach past its string by less than half of it
            assert min(b, hi) - max(a, lo) >= (b - a) / 2, (name, (a, b), (lo, hi))
