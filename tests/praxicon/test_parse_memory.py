"""The memory of ``praxicon.parse``: one row of numbers a window beside the recording.

It held about five times its windows' features at its peak (1,350 bytes a frame above a 30 fps
Bandai recording's own 1,056): the rows as a list, then as a matrix, then its kept columns; and
the scores' temporaries, a few copies of every window's features per action. The rows are now
written into one block made at once (the answer itself when every window has every feature),
the scores made a block of rows at a time, and the group test reads the rows in place; the
answers are the same to the bit (checked against the former matrix, and a row's scores alone).
"""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology import Motion, synthetic_motion
from praxicon import feature_table, scoring
from praxicon.parsing import describe_windows, parse, windows


@pytest.fixture(scope="module")
def described():
    """Window descriptions of two actions, and a recording of the first (40 joints, 12 s at
    30 fps)."""
    d = describe_windows({
        "a": [synthetic_motion(40, (0, 1), seed=s, repetitions=3, frame_rate=30.0)
              for s in (1, 2)],
        "b": [synthetic_motion(40, (2, 3), seed=s, repetitions=3, frame_rate=30.0)
              for s in (3, 4)]})
    return d, synthetic_motion(40, (0, 1), seed=5, repetitions=12, frame_rate=30.0)


def _former(descriptions, rows):
    """The feature matrix as it was made: a list of rows, then a matrix, then its columns."""
    wanted = descriptions.spread.features
    present = np.array([[f in r for f in wanted] for r in rows], dtype=bool)
    present = present.reshape(len(rows), len(wanted))
    values = np.array([[r.get(f, np.nan) for f in wanted] for r in rows], dtype=float)
    columns = np.flatnonzero(present.all(axis=0)).astype(int)
    x = values.reshape(len(rows), len(wanted))[:, columns]
    missing = tuple(tuple(sorted({feature_table.feature_joint(wanted[i])
                                  for i in np.flatnonzero(~p)})) for p in present)
    return columns, x, missing


def _rows_of(monkeypatch, rows):
    """``feature_table`` reads the given feature rows, one a motion in turn, for what
    ``feature_rows`` would compute: as long a recording as wanted, at no cost."""
    it = iter(rows)
    monkeypatch.setattr(feature_table, "feature_rows", lambda motions, shape=True: [next(it)])


@settings(max_examples=60, deadline=None)
@given(data=st.data())
def test_the_matrix_is_the_former_one_bit_for_bit(described, data):
    d, _ = described
    wanted = d.spread.features
    n = data.draw(st.integers(0, 9), label="motions")
    count = data.draw(st.sampled_from([None, max(n, 1), n + 3, 2]), label="count")
    # each motion lacks a few of the features (another skeleton's, a root that does not move)
    rows = []
    for k in range(n):
        lacks = data.draw(st.sets(st.integers(0, len(wanted) - 1), max_size=3), label="lacks")
        rows.append({f: float(k * 1000 + i) + 0.5 for i, f in enumerate(wanted)
                     if i not in lacks})
    with pytest.MonkeyPatch.context() as monkeypatch:
        _rows_of(monkeypatch, rows)
        monkeypatch.setattr(feature_table, "_BLOCK", 4)  # several blocks without a count
        columns, x, missing = feature_table.feature_matrix(d, range(n), count=count)
    old_columns, old_x, old_missing = _former(d, rows)
    assert np.array_equal(columns, old_columns) and columns.dtype == old_columns.dtype
    assert x.shape == old_x.shape and np.array_equal(x, old_x, equal_nan=True)
    # laid out as before (the kept columns of a matrix come in column order)
    assert x.strides == old_x.strides and missing == old_missing


def test_the_windows_rows_are_one_block_made_at_once(described, monkeypatch):
    d, _ = described
    wanted = d.spread.features
    n = 4000
    row = {f: 1.0 + i for i, f in enumerate(wanted)}
    _rows_of(monkeypatch, [row] * n)
    tracemalloc.start()
    try:
        _, x, _ = feature_table.feature_matrix(d, range(n), count=n)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert x.shape == (n, len(wanted))
    # the block (and a flag a feature): the list, the matrix and its columns held three times
    assert peak < 1.3 * x.nbytes, (peak, x.nbytes)


def test_rows_are_scored_the_same_a_block_at_a_time(described, monkeypatch):
    d, recording = described
    columns = np.arange(len(d.spread.features))
    fitted = scoring.score_model(d, columns)
    own = scoring.own_columns(d.spread.features)
    rng = np.random.default_rng(7)
    x = np.asfortranarray(np.array(d.actions[0].mean) + rng.normal(0, 2, (1000, len(columns))))
    monkeypatch.setattr(scoring, "_ROWS", 10**9)
    whole = scoring.model_scores(fitted, x, own)
    monkeypatch.setattr(scoring, "_ROWS", 7)
    blocks = scoring.model_scores(fitted, x, own)
    assert all(np.array_equal(a, b) for a, b in zip(whole, blocks))
    # the temporaries are a block's: at most a few hundred rows' worth, however many rows
    monkeypatch.setattr(scoring, "_ROWS", 100)
    tracemalloc.start()
    try:
        scoring.model_scores(fitted, x, own)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    answers = 2 * 2 * x.shape[0] * len(d.names) * 8  # the two answers, and their blocks
    assert peak < answers + 0.5 * x.nbytes, (peak, x.nbytes)


def test_parse_holds_its_windows_rows_and_little_more(described, monkeypatch):
    d, recording = described
    # a recording of 3,000 windows (a frame apart), each read as one of the recording's
    # real windows in turn: the features' work is not what is measured
    long = Motion(np.tile(recording.values, (9, 1)), recording.channels, 30.0)
    starts, cuts = windows(long, d.spread.window, 1 / 30)
    real = [feature_table.feature_rows([cuts[k]], shape=False)[0] for k in range(0, 120, 6)]
    _rows_of(monkeypatch, [real[k % len(real)] for k in range(len(starts))])
    tracemalloc.start()
    try:
        faked = parse(d, long, hop=1 / 30, switch=2.0)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert faked.bound is None and faked.spans[-1].stop == pytest.approx(long.duration)
    rows = len(starts) * len(real[0]) * 8  # the windows' features, a row of numbers each
    # about 1.35 times that (the scores, the group test, the path a window); it was 5 times
    assert peak < 2 * rows, (peak, rows)


def test_the_group_test_reads_the_rows_in_place(described):
    from praxicon._verdict import _excess

    d, recording = described
    columns = np.arange(len(d.spread.features))
    fitted = scoring.score_model(d, columns)
    rng = np.random.default_rng(3)
    x = np.asfortranarray(np.array(d.actions[1].mean) + rng.normal(0, 30, (50, len(columns))))
    rows = np.array([3, 4, 10, 49, 0])
    best = np.array([0, 1, 1, 0, 1])
    features = list(d.spread.features)
    # every group read (of these two actions, none tells them apart)
    copied = _excess(d, features, x[rows], best, fitted, telling=False)
    in_place = _excess(d, features, x, best, fitted, telling=False, rows=rows)
    assert np.array_equal(copied[0], in_place[0]) and copied[1] == in_place[1]
    assert np.array_equal(copied[2], in_place[2]) and copied[0].any()
