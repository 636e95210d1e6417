"""PAL on real motion capture segmented by kinetology (skips when the shared data is absent).

Performances are kept apart (labelled spans of the cmu-mocap6 takes, the two
walks of CMU subject 02); the joints that take part are named by
``Induction.actuators``. The one-actiongram period mode keeps a test of its own.
"""

from __future__ import annotations

import functools
from pathlib import Path

import pytest

import psgs
from psgs.induce import PAL

MOCAP = Path(__file__).resolve().parents[2] / ".." / "shared" / "data" / "mocap"
kinetology = pytest.importorskip("kinetology")
pytestmark = pytest.mark.skipif(not MOCAP.is_dir(),
                                reason=f"shared motion-capture data not found at {MOCAP}")


@pytest.fixture(scope="module")
def read():
    """The cmu-mocap6 takes as read: ``read(take)`` is ``(motion, labels)``, or None where the
    take's AMC file is absent; each take read once for this module's tests (a Motion is
    frozen and the labels a tuple: the tests only read them)."""
    from kinetology.labels import read_cmu_truelabels

    folder = MOCAP / "cmu-mocap6"

    @functools.cache
    def take(name: str):
        amc = folder / "amc" / f"{name}.amc"
        if not amc.is_file():
            return None  # 14_06.amc is absent from the shared data (its README says so)
        motion = kinetology.read(amc)
        return motion, read_cmu_truelabels(folder / "truelabels" / f"{name}.txt",
                                           motion.frame_rate)

    return take


def spans(read, action: str, takes=None, limit: int | None = None):
    """Labelled performances of one cmu-mocap6 exercise, each its own actiongram (``read``:
    the module's reader of takes)."""
    from kinetology.performances import from_spans

    folder = MOCAP / "cmu-mocap6"
    if takes is None:  # every take with labels, as benchmarks/actuators.py reads them
        takes = sorted(p.stem for p in (folder / "truelabels").glob("*.txt"))
    out = []
    for take in takes:
        found = read(take)
        if found is not None:
            out.extend(from_spans(*found, action, min_seconds=3.0))
    if not out:
        pytest.skip(f"no {action} span in {folder}")
    return [kinetology.segment(m) for m in out[:limit]]


def test_jumping_jacks_arms_and_legs_take_part(read):
    result = PAL().induce(spans(read, "JumpJack"))
    assert {"lhumerus", "rhumerus", "lfemur", "rfemur", "ltibia", "rtibia"} <= \
        set(result.actuators)
    assert result.verdict == "" and result.system.mode == "parallel"
    for name in result.components:
        assert set(result.patterns[name]) <= {"B", "G", "R", "Y"}
    period = result.occurrences[result.components[0]][0]
    assert 0.5 < period[1] - period[0] < 1.6  # a copy is one jump


def test_jogging_legs_take_part(read):
    result = PAL().induce(spans(read, "Jog"))
    assert {"lfemur", "rfemur", "ltibia", "rtibia"} <= set(result.actuators)


def test_the_tours_walk_learns_the_legs():
    walks = [kinetology.segment(kinetology.read(MOCAP / "cmu-subject02" / f"02_0{k}.amc"))
             for k in (1, 2)]
    result = PAL().induce(walks)
    assert {"lfemur", "rfemur", "ltibia", "rtibia"} <= set(result.actuators)
    # the system recognises its own patterns, repeated in step
    patterns = [result.patterns[n] for n in result.components]
    assert psgs.accepts(result.system, [p * 2 for p in patterns])
    assert not psgs.accepts(result.system, [p * (2 if i else 3) for i, p in enumerate(patterns)])


def test_one_take_in_the_period_mode_still_finds_the_jump(read):
    ag = spans(read, "JumpJack", takes=("14_14",), limit=1)[0]
    result = PAL().induce(ag)
    assert result.components and {"rtibia.rx", "ltibia.rx"} & set(result.components)
    assert PAL(timing="content").induce(ag).components == ()
