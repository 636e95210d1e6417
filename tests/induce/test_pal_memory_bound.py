"""PAL's max_bytes: the working data that grow faster than the input, counted as they are made,
and the Induction it stops naming it; and the compiled pair tests in a table of a block of rows.

The bytes are counted from sizes (32 a pair of synchronised strings, the period mode's grid by
:func:`~psgs.induce.pal.period.grid_bytes`, the real-motion learner's grids by
``GRID_BYTES``), so where PAL stops is the same on every machine: the protocol's actiongram
(seed 1, no noise) counts 6 motif pairs (192 bytes), then 3 section pairs (96 more).
"""

from __future__ import annotations

import json
import math
import sys
import tracemalloc
from pathlib import Path

import numpy as np
import pytest

from psgs import Actiongram
from psgs.cli import main
from psgs.errors import ValidationError
from psgs.induce import PAL, ContentPAL, MotionPAL
from psgs.induce.pal import synchronisation
from psgs.induce.pal.conf import Bounds, ContentConf, undecided
from psgs.induce.pal.learner import encode
from psgs.induce.pal.period import grid_bytes, period_mode, time_grid
from psgs.induce.synthetic import generate

sys.path.insert(0, str(Path(__file__).parent))
from test_pal_performances import performance  # noqa: E402

STOPPED = undecided("max_bytes")


def _random_copies(count: int, copies: int = 10, seed: int = 0) -> list[np.ndarray]:
    """``count`` copy lists of ``copies`` copies each at random times (few pairs in step)."""
    rng = np.random.default_rng(seed)
    lists = []
    for _ in range(count):
        starts = np.sort(rng.choice(100_000, copies, replace=False)).astype(float) * 10
        lists.append(np.column_stack((starts, starts + 8.0)))
    return lists


def test_the_compiled_pair_table_is_a_block_of_rows_not_every_pair(monkeypatch):
    pytest.importorskip("numba", reason="the compiled engine needs numba (test extra)")
    from psgs.induce.pal import _pairs_jit

    lists = _random_copies(60) + [np.array([[0.0, 8.0], [20.0, 28.0], [40.0, 48.0]])] * 6
    tables = []
    real = _pairs_jit.synchronised_rows
    monkeypatch.setattr(_pairs_jit, "synchronised_rows",
                        lambda *a: tables.append(real(*a).shape) or real(*a))
    monkeypatch.setattr(synchronisation, "PAIRS_PER_CALL", 200)
    monkeypatch.setattr(synchronisation, "PAIRS_HANDED", 4)
    blocks = list(synchronisation._pairs_compiled(lists, 0.5, 3))
    # 66 candidates, 3 rows of 66 a table, without a deadline too, the pairs handed on 4 at
    # a time: the same pairs
    assert set(tables) == {(3, 66)} and len(tables) == 22
    assert [len(rows) for rows, _ in blocks] == [4, 4, 4, 3]  # rows 60-62, then 63-65
    pairs = [p for rows, columns in blocks for p in zip(rows, columns)]
    assert pairs == [p for rows, columns in synchronisation._pairs_each(lists, 0.5, 3)
                     for p in zip(rows, columns)]
    assert pairs == [(i, j) for i in range(60, 66) for j in range(i + 1, 66)]


def test_the_compiled_pair_tests_hold_a_block_of_rows_in_memory():
    pytest.importorskip("numba", reason="the compiled engine needs numba (test extra)")
    lists = _random_copies(3000, copies=3)
    list(synchronisation._pairs_compiled(lists[:20], 0.5, 3))  # compiled (or read from the cache)
    tracemalloc.start()
    try:
        found = list(synchronisation._pairs_compiled(lists, 0.5, 3))
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    # the table of every pair would be 3000² bytes (9 MB); a block is 2²⁰ bytes, and the
    # copies (9000, some 150 kB) are copied a few times
    assert found == [] and peak < 2e6


@pytest.mark.parametrize("engine", ["numpy", "numba"])
def test_max_bytes_stops_each_stage_and_names_itself(engine):
    if engine == "numba":
        pytest.importorskip("numba", reason="the compiled engine needs numba (test extra)")
    actiongram = generate(seed=1).actiongram
    full = PAL(engine=engine).induce(actiongram)
    # 191 bytes: the six motif pairs (192) do not fit; nothing is pooled
    early = PAL(max_bytes=191, engine=engine).induce(actiongram)
    assert early.bound == "max_bytes" and early.components == () and early.system is None
    assert early.reason == ("stopped at 191 bytes (max_bytes), in the motif search and "
                            "synchronisation")
    assert early.verdict == "no component found before max_bytes"
    assert {r.status for r in early.reports} == {STOPPED}
    # 200 bytes: the motif groups are pooled, the section pairs (96 more) do not fit
    late = PAL(max_bytes=200, engine=engine).induce(actiongram)
    assert late.bound == "max_bytes" and late.reason.endswith("in the section search")
    assert late.components == full.components and late.patterns == full.patterns
    assert {r.status for r in late.reports if r.name not in late.components} == {STOPPED}
    data = late.to_dict()
    assert data["bound"] == "max_bytes" and data["reason"] == late.reason
    # 288 bytes: everything fits, and the answer is the unbounded one
    assert PAL(max_bytes=288, engine=engine).induce(actiongram) == full


def test_the_period_mode_counts_its_grid():
    actiongram = generate(seed=3, patterned=0).actiongram  # content finds nothing
    full = PAL().induce(actiongram)
    assert full.bound is None and not full.components
    grid = PAL(max_bytes=grid_bytes(20, 2) - 1).induce(actiongram)
    assert grid.bound == "max_bytes" and grid.reason.endswith("in the period mode")
    assert PAL(max_bytes=1e9).induce(actiongram) == full


def test_the_period_mode_s_count_bounds_its_traced_peak():
    # 46 symbols on 16,384 points: each symbol about 360 times, at the size where its pairs
    # are listed one by one rather than transformed (the most pairs a row can hold)
    rng = np.random.default_rng(0)
    symbols = [f"s{k}" for k in range(46)]
    actiongram = Actiongram.from_strings(
        {f"j{i}": [symbols[k] for k in rng.integers(0, 46, 16384)] for i in range(2)})
    strings, symbol_of = encode(actiongram)
    times, _, grid = time_grid(strings)
    counted = grid_bytes(len(strings), len(times))
    del grid
    tracemalloc.start()
    try:
        period_mode(strings, len(symbol_of), ContentConf())
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak <= counted


def test_the_real_motion_learner_counts_its_grids():
    takes = [performance(k) for k in range(3)]
    full = MotionPAL().induce(takes)
    stopped = MotionPAL(max_bytes=1000).induce(takes)
    assert stopped.bound == "max_bytes" and stopped.components == ()
    assert stopped.reason == ("stopped at 1000 bytes (max_bytes), before the joints were "
                              "chosen")
    assert {r.status for r in stopped.reports} == {STOPPED}
    assert PAL(max_bytes=1000).induce(takes).bound == "max_bytes"  # PAL hands it on
    assert MotionPAL(max_bytes=1e12).induce(takes) == full


@pytest.mark.parametrize("value", [0, -1, math.inf, math.nan, "5", True, [1]])
def test_max_bytes_is_validated_like_the_other_parameters(value):
    with pytest.raises(ValidationError, match="parameter max_bytes must be"):
        PAL(max_bytes=value)
    with pytest.raises(ValidationError, match="parameter max_bytes must be"):
        MotionPAL(max_bytes=value)


def test_a_bound_past_a_float_s_range_and_a_bound_of_one_are_worded_as_such():
    with pytest.raises(ValidationError, match=r"not inf \(a number past a float's range"):
        PAL(max_bytes=float("1e400"))
    with pytest.raises(ValidationError, match="not a whole number of 401 digits"):
        PAL(max_bytes=10 ** 400)
    actiongram = generate(seed=1).actiongram
    assert PAL(max_bytes=1).induce(actiongram).reason.startswith(
        "stopped at 1 byte (max_bytes), in ")


def test_max_bytes_is_not_recorded_and_counts_nothing_without_a_value():
    result = ContentPAL(max_bytes=1e9).induce(generate(seed=2).actiongram)
    assert "max_bytes" not in result.params and result.bound is None
    assert PAL().max_bytes is None
    unbounded = Bounds()
    unbounded.keep(10 ** 30)
    assert unbounded.kept == 0  # (NO_BOUND is shared: nothing changes in it)


def test_psgs_induce_names_max_bytes_and_exits_3(tmp_path, capsys):
    path = tmp_path / "ag.txt"
    path.write_text(generate(seed=1).actiongram.to_text())
    assert main(["induce", str(path), "--param", "max_bytes=200"]) == 3
    captured = capsys.readouterr()
    assert "pal: 4 component(s) of 20 strings" in captured.out
    assert f"16 {STOPPED}" in captured.out
    assert captured.err == ("psgs: pal stopped at 200 bytes (max_bytes), in the section "
                            "search: its components are those found by then\n")
    assert main(["induce", str(path), "--param", "max_bytes=100", "--json"]) == 3
    data = json.loads(capsys.readouterr().out)
    assert data["bound"] == "max_bytes" and data["components"] == []


@pytest.mark.parametrize("name", ["max_bytes", "max_seconds"])
def test_a_bound_of_zero_of_either_sign_is_refused_as_the_number_it_is(name, tmp_path, capsys):
    # -0.0 is refused as -0.0 (it is no more a bound than 0); the command line reads the
    # text -0 as the integer 0 (int("-0")), so it is refused as 0, and -0.0 as -0.0
    for value, shown in [(-0.0, "-0.0"), (0.0, "0.0"), (0, "0")]:
        with pytest.raises(ValidationError) as refused:
            PAL(**{name: value})
        assert str(refused.value) == f"parameter {name} must be > 0, not {shown}"
        with pytest.raises(ValidationError, match=f"must be > 0, not {shown}$"):
            MotionPAL(**{name: value})
    path = tmp_path / "ag.txt"
    path.write_text(generate(seed=1).actiongram.to_text())
    for text, shown in [("-0", "0"), ("-0.0", "-0.0"), ("-0e0", "-0.0")]:
        assert main(["induce", str(path), "--param", f"{name}={text}"]) == 2
        assert capsys.readouterr().err == (f"psgs: error: parameter {name} must be > 0, "
                                           f"not {shown}\n")
