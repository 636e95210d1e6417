"""Morphemes are kineteme strings a real copy made: the medoid copy's segments, not a splice.

The plurality of stretched copies, read point by point, can join two states by a transition
that no copy shows (``R -> G`` where every copy passes through ``B``); such a morpheme is a bad
description of the action and cannot be generated at its tempo. The pattern is the medoid
copy's own segments in its take, so it is always a string some take shows, and it ends where its
first kineteme begins again, so that repeated it makes only changes a take makes: checked by
hypothesis over random copies and takes, and on real motion.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from psgs.induce import PAL
from psgs.induce.pal.motion.grids import plurality
from psgs.actiongram import Actiongram
from psgs.induce.pal.motion.morphemes import copy_runs, copy_segments, medoid_copy, ordinary_copies

MOCAP = Path(__file__).resolve().parents[2] / ".." / "shared" / "data" / "mocap"
BANDAI = MOCAP / "bandai-namco-1" / "data"


def run_string(states) -> tuple[int, ...]:
    """The states of one copy, absent points left out, one symbol per run."""
    out: list[int] = []
    for s in np.asarray(states).tolist():
        if s >= 0 and (not out or out[-1] != s):
            out.append(s)
    return tuple(out)


copies_strategy = st.integers(1, 6).flatmap(lambda n: st.integers(1, 12).flatmap(
    lambda w: arrays(np.int64, (n, w), elements=st.integers(-1, 3))))


@given(copies_strategy)
def test_the_pattern_is_the_run_string_of_a_copy(copies):
    column = plurality(copies)
    medoid = medoid_copy(copies, column)
    runs = copy_runs(copies[medoid])
    assert tuple(s for s, _, _ in runs) == run_string(copies[medoid])
    assert tuple(s for s, _, _ in runs) in {run_string(c) for c in copies}
    # the spans tile the copy, so durations add up to the copy's time
    if runs:
        assert runs[0][1] == 0 and runs[-1][2] == copies.shape[1]
        assert all(a < b for _, a, b in runs)
        assert all(runs[k][2] == runs[k + 1][1] for k in range(len(runs) - 1))
    # the medoid agrees with the plurality at least as often as any copy, the first among equals
    agree = [int(((c == column) & (column >= 0)).sum()) for c in copies]
    assert agree[medoid] == max(agree) and medoid == agree.index(max(agree))


def changes(states, cyclic) -> set:
    runs = list(run_string(states))
    if cyclic and len(runs) > 1 and runs[-1] != runs[0]:
        runs.append(runs[0])
    return set(zip(runs, runs[1:]))


@given(copies_strategy, st.booleans())
def test_the_medoid_of_ordinary_copies_makes_only_changes_others_make(copies, cyclic):
    ordinary = ordinary_copies(copies, cyclic)
    made = [changes(c, cyclic) for c in copies]
    enough = max(2, -(-len(copies) // 10))
    for k, mine in enumerate(made):
        expected = len(copies) < 2 or all(sum(ch in m for m in made) >= enough for ch in mine)
        assert bool(ordinary[k]) == expected
    column = plurality(copies)
    medoid = medoid_copy(copies, column, ordinary)
    if ordinary.any():
        assert ordinary[medoid]
        agree = [int(((c == column) & (column >= 0)).sum()) if ordinary[k] else -1
                 for k, c in enumerate(copies)]
        assert medoid == agree.index(max(agree))
    else:
        assert medoid == medoid_copy(copies, column)


def test_a_splice_of_the_plurality_is_not_the_pattern():
    # every copy goes 0 -> 1 -> 2, at different times: the plurality jumps 0 -> 2
    copies = np.array([[0, 0, 0, 1, 2, 2],
                       [0, 1, 2, 2, 2, 2],
                       [0, 0, 1, 2, 2, 2]])
    column = plurality(copies)
    assert run_string(column) == (0, 2)
    assert all(run_string(c) == (0, 1, 2) for c in copies)
    medoid = medoid_copy(copies, column)
    assert medoid == 0  # 5 points agree, as for copy 2: the first wins
    assert copy_runs(copies[medoid]) == [(0, 0, 3), (1, 3, 4), (2, 4, 6)]


take_strategy = st.lists(st.sampled_from("BGRY"), min_size=2, max_size=30).map(
    lambda syms: [s for k, s in enumerate(syms) if k == 0 or s != syms[k - 1]]).filter(
    lambda syms: len(syms) >= 2).flatmap(lambda syms: st.tuples(
        st.just(tuple(syms)),
        st.lists(st.integers(1, 8), min_size=len(syms), max_size=len(syms)),
        st.floats(0, 40), st.floats(0.5, 20), st.floats(-5, 5)))


@given(take_strategy)
def test_a_copy_is_whole_segments_of_its_take_that_close_on_themselves(case):
    symbols, frames, start, length, origin = case
    durations = tuple(f / 10 for f in frames)
    take = Actiongram(("x",), (symbols,), (durations,), origins=(origin,),
                      segment_displacements=(tuple(float(f) for f in frames),))
    start += origin  # times are the take's, its string starting at its origin
    found = copy_segments(take, 0, start, length)
    borders = origin + np.concatenate(([0.0], np.cumsum(durations)))
    first = int(np.argmin(np.abs(borders[:-1] - start)))
    assert found is not None
    kinetemes, spans, moves = found
    n = len(kinetemes)
    # a run of whole segments of the take, with their own durations and angles
    at = [i for i in range(len(symbols) - n + 1) if symbols[i:i + n] == kinetemes and
          np.allclose(durations[i:i + n], spans) and np.allclose(frames[i:i + n], moves)]
    assert at
    again = [j for j in range(len(symbols)) if j != first and symbols[j] == symbols[first] and
             length / 2 <= abs(borders[j] - borders[first]) <= 3 * length]
    if again:  # it begins at the border nearest start and ends where its first kineteme
        # begins again: repeated, it makes only changes the take makes
        i = next((i for i in at if first in (i, i + n)), None)  # forwards or backwards
        assert i is not None
        assert i + n < len(symbols) and symbols[i + n] == kinetemes[0]
        span = borders[i + n] - borders[i]
        assert all(abs(span - length) <= abs(abs(borders[j] - borders[first]) - length) + 1e-9
                   for j in again)
    else:  # the border nearest its end
        assert first in at
        ends = borders[first + 1:]
        assert np.isclose(abs(ends[n - 1] - borders[first] - length),
                          np.abs(ends - borders[first] - length).min())


def test_learnt_morphemes_of_synthetic_waves_are_strings_of_a_take():
    from test_pal_performances import performance

    takes = [performance(seed) for seed in range(6)]
    result = PAL().induce(takes)
    assert result.components
    for name in result.components:
        pattern = "".join(result.patterns[name])
        strings = ["".join(t.string(name)) for t in takes]
        # a cycle's copy starts at any phase: the pattern is a stretch of some take
        assert any(pattern in s for s in strings), name
        morpheme = result.morphemes[name]
        assert all(d > 0 for d in morpheme.durations)


@pytest.mark.skipif(not BANDAI.is_dir(), reason=f"shared motion-capture data not found at {BANDAI}")
def test_real_morphemes_make_only_transitions_a_take_shows():
    kinetology = pytest.importorskip("kinetology")
    files = sorted(BANDAI.glob("dataset-1_bye_*.bvh"))
    takes = [kinetology.segment(kinetology.read(f)) for f in files][::2]
    result = PAL().induce(takes)
    assert result.components
    for name in result.components:
        pattern = "".join(result.patterns[name])
        strings = ["".join(t.string(name)) for t in takes]
        # a stretch of a take that closes on itself there: its last kineteme runs into its
        # first, so the pattern repeated makes only changes the take makes
        assert any(pattern + pattern[0] in s for s in strings), (name, pattern)
        morpheme = result.morphemes[name]
        assert len(morpheme.durations) == len(pattern) and min(morpheme.durations) > 0
