"""Members read at a group's core join by Holm's step-down over the strings read."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs.induce.pal.core_cover import cover_reading
from psgs.induce.pal.in_step import _read_the_rest
from psgs.induce.pal.motifs import Timed
from psgs.induce.pal.sections import follow_rate

LEVEL = -2.0


def _strings(seed: int, sectioned: int, spurious: int, length: int):
    """Strings of 60 symbols over 4 letters (no two neighbours equal); ``sectioned`` play one
    section each twice at the same times, from 6 and from 6 + length + 3."""
    rng = np.random.default_rng(seed)

    def draw(k, before=None):
        out = []
        for _ in range(k):
            last = out[-1] if out else before
            c = int(rng.integers(0, 4 - (last is not None)))
            out.append(c + (last is not None and c >= last))
        return out

    codes = []
    for _ in range(sectioned):
        section = draw(length)
        parts = draw(6)
        while parts[-1] == section[0]:
            parts = draw(6)
        parts += section
        gap = draw(3, parts[-1])
        while gap[-1] == section[0]:
            gap = draw(3, parts[-1])
        parts += gap + section
        parts += draw(60 - len(parts), parts[-1])
        codes.append(parts)
    codes += [draw(60) for _ in range(spurious)]
    strings = [Timed.from_codes(np.array(c), np.ones(60), 0.0) for c in codes]
    second = 6 + length + 3
    return strings, np.array([[6.0, 6.0 + length], [second, second + float(length)]])


@settings(max_examples=25, deadline=None, derandomize=True)
@given(seed=st.integers(0, 100_000), sectioned=st.integers(3, 6), spurious=st.integers(0, 16),
       length=st.integers(6, 9), taken=st.sets(st.integers(0, 21), min_size=1, max_size=3))
def test_the_members_are_holms_and_hold_every_one_bonferroni_keeps(seed, sectioned, spurious,
                                                                  length, taken):
    # ``taken``: the lead and the members joined before (any strings, sectioned or not)
    strings, core = _strings(seed, sectioned, spurious, length)
    follows = [follow_rate(s.codes) for s in strings]
    taken = {j % len(strings) for j in taken}
    joined = _read_the_rest(strings, core, follows, taken, LEVEL)
    read = {j: cover_reading(strings[j], core, follows[j]) for j in range(len(strings))
            if j not in taken}
    weights = {j: r[0] for j, r in read.items() if r is not None}
    count = len(read)
    # Holm's step-down, done by hand: lightest first, the k-th against log10(count - k)
    holm = []
    for k, (j, weight) in enumerate(sorted(weights.items(), key=lambda kv: (kv[1], kv[0]))):
        if weight + math.log10(count - k) > LEVEL + 1e-9:
            break
        holm.append(j)
    assert sorted(joined) == sorted(holm)
    assert all(joined[j][0] == weights[j] for j in joined)
    # every string the test of each against all keeps is kept (all the others, as before,
    # and all those read)
    kept = {j for j, w in weights.items() if w + math.log10(count) <= LEVEL}
    assert {j for j, w in weights.items() if w + math.log10(len(strings) - 1) <= LEVEL} \
        <= kept <= set(joined)


def test_a_member_short_of_the_test_against_all_joins_after_the_others():
    # six strings play an 8-symbol section over 4 letters; read at the section's times the
    # weakest weighs just short of the test against all the others, and passes once the
    # lighter ones have
    strings, core = _strings(232, 6, 16, 8)
    follows = [follow_rate(s.codes) for s in strings]
    read = {j: cover_reading(strings[j], core, follows[j]) for j in range(1, len(strings))}
    count = len(read)
    assert [j for j in range(1, 6) if read[j][0] + math.log10(count) > LEVEL] == [2]
    joined = _read_the_rest(strings, core, follows, {0}, LEVEL)
    assert set(range(1, 6)) <= set(joined)
    assert not set(joined) - set(range(1, 6))
