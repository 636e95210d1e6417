"""PAL's max_seconds: a wall-clock bound read in its loops, named in the Induction it stops.

The clock here is a fake one that moves a second each time it is read, so where PAL stops
depends on how often it reads the clock, not on the machine: max_seconds=k + 0.5 stops it at
its (k + 1)-th reading. Without the bound, and with one it does not reach, PAL's answer is
the one it gave before the bound existed.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

import psgs.budget
from psgs import Actiongram
from psgs.budget import Budget
from psgs.cli import main
from psgs.errors import BoundReached, ValidationError
from psgs.induce import PAL, ContentPAL, MotionPAL
from psgs.induce.pal import motifs, synchronisation
from psgs.induce.pal.conf import UNDECIDED, ContentConf
from psgs.induce.pal.learner import encode
from psgs.induce.synthetic import generate

sys.path.insert(0, str(Path(__file__).parent))
from test_pal_performances import performance  # noqa: E402


class TickingClock:
    """time as psgs.budget reads it: a second later at every reading."""

    def __init__(self) -> None:
        self.now = 0.0

    def monotonic(self) -> float:
        self.now += 1.0
        return self.now


@pytest.fixture
def ticking(monkeypatch):
    monkeypatch.setattr(psgs.budget, "time", TickingClock())


def _stops(inducer_of, data, most: int = 200, stride: int = 1):
    """Every induction of ``inducer_of(k + 0.5)`` from k = 0 by ``stride`` until one is not
    stopped."""
    out = []
    for k in range(0, most * stride, stride):
        result = inducer_of(k + 0.5).induce(data)
        out.append(result)
        if result.bound is None:
            return out
    raise AssertionError(f"still stopped after {most} readings of the clock")


def test_a_bound_not_reached_changes_nothing():
    for seed, noise in [(1, 0.1), (4, 0.2), (6, 0.0)]:
        actiongram = generate(seed=seed, noise=noise).actiongram
        plain = PAL().induce(actiongram)
        bounded = PAL(max_seconds=1e6).induce(actiongram)
        assert bounded == plain and bounded.bound is None and bounded.reason is None
        assert bounded.to_dict() == plain.to_dict() and "bound" not in plain.to_dict()
    takes = [performance(k) for k in range(3)]
    assert PAL(max_seconds=1e6).induce(takes) == PAL().induce(takes)


@pytest.mark.parametrize("engine", ["numpy", "numba"])
def test_each_stage_stops_where_the_clock_says_and_names_itself(ticking, engine):
    if engine == "numba":
        pytest.importorskip("numba", reason="the compiled engine needs numba (test extra)")
    actiongram = generate(seed=1, noise=0.1).actiongram
    full = PAL(engine=engine).induce(actiongram)  # reads no clock
    # (numpy reads the clock at each column of each scan: some 500 readings, every fourth
    # tried)
    stride = 4 if engine == "numpy" else 1
    results = _stops(lambda s: PAL(max_seconds=s, engine=engine), actiongram, stride=stride)
    assert results[-1] == full and len(results) > 20
    stages = []
    for result in results[:-1]:
        assert result.bound == "max_seconds"
        stage = result.reason.split(", in ")[1]
        assert result.reason == (f"stopped after {len(stages) * stride + 0.5:g} seconds "
                                 "(max_seconds), "
                                 f"in {stage}")
        stages.append(stage)
        for report in result.reports:
            assert report.status == ("component" if report.name in result.components
                                     else UNDECIDED)
        if not result.components:
            assert result.system is None
            assert result.verdict == "no component found before max_seconds"
        else:
            # the groups pooled by then: here the protocol's four strings, as in the end
            assert result.components == full.components and result.verdict == ""
            assert result.patterns == full.patterns and result.agreements
        data = result.to_dict()
        assert data["bound"] == "max_seconds" and data["reason"] == result.reason
    # the stages in the order they run, each met at some reading
    assert list(dict.fromkeys(stages)) == ["the motif search and synchronisation",
                                           "the pooling of synchronised strings",
                                           "the section search"]


def test_the_period_mode_stops_too(ticking):
    random = generate(seed=3, patterned=0).actiongram  # content finds nothing: period mode
    stages = {r.reason.split(", in ")[1] for r in _stops(lambda s: PAL(max_seconds=s),
                                                          random)[:-1]}
    assert "the period mode" in stages
    # timing="period": the period mode's components replace the content mode's, and a
    # period mode cut short has none
    case = generate(seed=1, noise=0.1).actiongram
    for result in _stops(lambda s: ContentPAL(max_seconds=s, timing="period"), case)[:-1]:
        assert result.components == () and result.bound == "max_seconds"


def test_the_real_motion_learner_stops_with_no_joint(ticking):
    takes = [performance(k) for k in range(3)]
    results = _stops(lambda s: MotionPAL(max_seconds=s), takes)
    assert results[-1] == MotionPAL().induce(takes) and len(results) > 3
    for result in results[:-1]:
        assert result.components == () and result.actuators == ()
        assert result.performances == 3 and result.bound == "max_seconds"
        assert result.reason.endswith("before the joints were chosen")
        assert {r.status for r in result.reports} == {UNDECIDED}
    # PAL hands several performances to it, max_seconds with them
    assert PAL(max_seconds=0.5).induce(takes).bound == "max_seconds"


@pytest.mark.parametrize("value", [0, -1, math.inf, math.nan, "5", True, [1]])
def test_max_seconds_is_validated_like_the_other_parameters(value):
    with pytest.raises(ValidationError, match="parameter max_seconds must be"):
        PAL(max_seconds=value)


def test_max_seconds_takes_none_and_numbers_and_is_not_recorded():
    assert PAL().max_seconds is None and PAL(max_seconds=None).conf().max_seconds is None
    assert PAL(max_seconds=np.float32(0.5)).conf().max_seconds == 0.5
    result = PAL(max_seconds=60).induce(generate(seed=2).actiongram)
    assert "max_seconds" not in result.params and result.bound is None


def test_psgs_induce_prints_what_was_found_names_the_bound_and_exits_3(ticking, tmp_path,
                                                                        capsys):
    path = tmp_path / "ag.txt"
    path.write_text(generate(seed=1, noise=0.1).actiongram.to_text())
    # numpy's engine reads the clock before each seed of each string's motif search, between
    # the passes before its first seed and before each column of its scans, and the pooling
    # before each member's vote: the 490th reading is in the section search, where the groups
    # pooled by then are components
    assert main(["induce", str(path), "--param", "max_seconds=489.5", "--param",
                 "engine=numpy"]) == 3
    captured = capsys.readouterr()
    assert "pal: 4 component(s) of 20 strings" in captured.out
    assert "16 not decided: stopped at max_seconds" in captured.out
    assert captured.err == ("psgs: pal stopped after 489.5 seconds (max_seconds), in the "
                            "section search: its components are those found by then\n")
    assert main(["induce", str(path), "--param", "max_seconds=2.5", "--json"]) == 3
    captured = capsys.readouterr()
    data = json.loads(captured.out)
    assert data["bound"] == "max_seconds" and data["components"] == []
    assert captured.err.endswith("no component was found by then\n")


def test_the_compiled_pairs_come_a_block_of_rows_at_a_time_alike(monkeypatch):
    rng = np.random.default_rng(0)
    lists = []
    for _ in range(30):
        starts = np.sort(rng.uniform(0, 100, 12))
        lists.append(np.column_stack((starts, starts + rng.uniform(0.5, 6, 12))))
    whole = _pairs(synchronisation._pairs_compiled(lists, 0.5, 3))  # (30 rows: one block)
    monkeypatch.setattr(synchronisation, "PAIRS_PER_CALL", 40)  # 1 row a block
    assert _pairs(synchronisation._pairs_compiled(lists, 0.5, 3, Budget(seconds=1e6))) == whole
    assert whole == _pairs(synchronisation._pairs_each(lists, 0.5, 3)) and len(whole) > 20
    # and the clock stops them between blocks
    with pytest.raises(BoundReached):
        _pairs(synchronisation._pairs_compiled(lists, 0.5, 3, _expired()))


def _pairs(blocks) -> list[tuple[int, int]]:
    """The pairs of pooling's blocks of rows, in order."""
    return [pair for rows, columns in blocks for pair in zip(rows, columns, strict=True)]


def _expired() -> Budget:
    clock = Budget(seconds=1e-3)
    clock.deadline -= 1.0
    return clock


def test_a_stopped_induction_is_a_value_like_any_other(ticking):
    import pickle

    stopped = PAL(max_seconds=495.5, engine="numpy").induce(generate(seed=1).actiongram)
    assert stopped.bound == "max_seconds" and stopped.components
    assert pickle.loads(pickle.dumps(stopped)) == stopped
    assert repr(stopped).endswith(", stopped at max_seconds>")
    with pytest.raises(ValidationError, match="bound must be a str or None"):
        type(stopped)(None, (), {}, {}, bound=3)


def test_an_actiongram_with_no_string_is_no_trouble(ticking):
    empty = Actiongram.from_strings({})
    assert PAL(max_seconds=0.5).induce(empty).components == ()
