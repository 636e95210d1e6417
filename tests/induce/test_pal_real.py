"""PAL on real motion capture segmented by kinetology (skips when the shared data is absent).

The content mode finds nothing here (joints cycle through B G R Y at different
rates and phases); the period mode, which the default ``timing="auto"`` falls
back to, must find the joints that drive the action.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import psgs
from psgs.induce import PAL

MOCAP = Path(__file__).resolve().parents[2] / ".." / "shared" / "data" / "mocap"
kinetology = pytest.importorskip("kinetology")
pytestmark = pytest.mark.skipif(not MOCAP.is_dir(),
                                reason=f"shared motion-capture data not found at {MOCAP}")

MOCAP6 = ("JumpJack", "Jog")  # labels 1 and 2 of cmu-mocap6/truelabels


def performance(take: str, label: int, occurrence: int = 0) -> psgs.Actiongram:
    """The kinetology actiongram of one labelled exercise of a cmu-mocap6 take.

    Labels are one per 1/10 s, covering 12 AMC frames each (as in
    kinetology.evaluation.mocap6_performances).
    """
    folder = MOCAP / "cmu-mocap6"
    amc = folder / "amc" / f"{take}.amc"
    if not amc.is_file():
        pytest.skip(f"{amc} not found")
    motion = kinetology.read(amc)
    labels = np.array((folder / "truelabels" / f"{take}.txt").read_text().split(), dtype=int)
    per_frame = np.repeat(labels, 12)[:motion.frames]
    frames = np.flatnonzero(per_frame == label)
    runs = np.split(frames, np.flatnonzero(np.diff(frames) > 1) + 1)
    run = runs[occurrence]
    cut = kinetology.Motion(motion.values[run[0]:run[-1] + 1], motion.channels,
                            motion.frame_rate, motion.skeleton)
    return kinetology.segment(cut)


def walk(take: str) -> psgs.Actiongram:
    amc = MOCAP / "cmu-subject02" / f"{take}.amc"
    if not amc.is_file():
        pytest.skip(f"{amc} not found")
    return kinetology.segment(kinetology.read(amc))


def check_components(result, actiongram, copies: int) -> None:
    assert result.system is not None and result.system.mode == "parallel"
    # selective: the driving joints, not every moving channel
    assert len(result.components) < len(actiongram) / 2
    for name in result.components:
        pattern = result.patterns[name]
        assert len(pattern) >= 2 and set(pattern) <= {"B", "G", "R", "Y"}
        assert len(result.occurrences[name]) >= copies
    # all components share the same copy windows (synchronised in time)
    assert len({result.occurrences[n] for n in result.components}) == 1


@pytest.mark.parametrize("take", ["13_29", "14_14", "14_20"])
def test_jumping_jacks_arms_and_legs_are_components(take):
    ag = performance(take, 1)
    result = PAL().induce(ag)
    check_components(result, ag, copies=3)
    for joint in ("rtibia.rx", "ltibia.rx", "rhumerus.rx", "lhumerus.rx"):
        assert joint in result.components, (joint, result.components)
    # a copy is one jump: about a second
    first = result.occurrences[result.components[0]][0]
    assert 0.8 < first[1] - first[0] < 1.4
    # the content mode alone finds nothing here: this is the period mode's doing
    assert PAL(timing="content").induce(ag).components == ()


@pytest.mark.parametrize("take", ["13_31", "14_14"])
def test_jogging_legs_are_components(take):
    ag = performance(take, 2)
    result = PAL().induce(ag)
    check_components(result, ag, copies=4)
    assert {"rtibia.rx", "ltibia.rx"} <= set(result.components)
    legs = [n for n in result.components if n[1:].startswith(("femur", "tibia", "foot"))]
    assert len(legs) >= 3
    first = result.occurrences[result.components[0]][0]
    assert 0.5 < first[1] - first[0] < 1.0  # a stride


def test_short_walk_needs_two_copies():
    ag = walk("02_01")  # 2.9 s: two and a half gait cycles
    assert PAL().induce(ag).components == ()  # fewer than min_copies=3 whole cycles
    result = PAL(min_copies=2).induce(ag)
    check_components(result, ag, copies=2)
    assert {"rfemur.rx", "lfemur.rx", "rtibia.rx", "ltibia.rx", "rfoot.rx", "lfoot.rx"} <= \
        set(result.components)
    first = result.occurrences[result.components[0]][0]
    assert 0.9 < first[1] - first[0] < 1.4  # one gait cycle


def test_period_mode_language_holds_the_patterns():
    result = PAL().induce(performance("14_14", 1))
    patterns = [result.patterns[n] for n in result.components]
    assert psgs.accepts(result.system, [p * 2 for p in patterns])
    # every component repeats the same number of times
    assert not psgs.accepts(result.system, [p * (2 if i else 3) for i, p in enumerate(patterns)])
