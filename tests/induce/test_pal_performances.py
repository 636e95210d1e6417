"""PAL on several performances: joints, the foreign limb, abstention, reports, determinism.

Synthetic performances built from angles the way kinetology reads them (the
state of each instant from the signs of velocity and acceleration), so the
expected joints are known exactly; real takes are in test_pal_locate.py.
"""

from __future__ import annotations

import numpy as np
import pytest

from psgs import Actiongram
from psgs.induce import PAL

RATE = 30.0
STATES = "BGRY"  # (v+, a+), (v+, a-), (v-, a-), (v-, a+)


def kinetemes(angle: np.ndarray) -> tuple[list[str], list[float], list[float]]:
    """Symbols, durations (s) and displacements (deg) of one sampled angle."""
    v = np.gradient(angle) * RATE
    a = np.gradient(v) * RATE
    code = np.where(v >= 0, np.where(a >= 0, 0, 1), np.where(a < 0, 2, 3))
    starts = np.concatenate(([0], np.flatnonzero(code[1:] != code[:-1]) + 1))
    ends = np.append(starts[1:], len(angle))
    last = np.minimum(ends, len(angle) - 1)
    return ([STATES[c] for c in code[starts]], list((ends - starts) / RATE),
            list(angle[last] - angle[starts]))


def performance(seed: int, *, wave: bool = True, foreign: bool = True) -> Actiongram:
    """One take: arm and hand wave in step (period varies by take), the leg sways a little
    at random, a 'foreign' joint moves a lot with a period and phase of its own."""
    rng = np.random.default_rng(seed)
    seconds = 6 + rng.uniform(0, 2)
    t = np.arange(int(seconds * RATE)) / RATE
    period = rng.uniform(0.6, 1.0)
    phase = rng.uniform(0, 2 * np.pi)

    def drift(scale):  # a smooth random walk
        steps = rng.normal(0, 1, len(t)).cumsum()
        kernel = np.exp(-0.5 * (np.arange(-15, 16) / 5) ** 2)
        return scale * np.convolve(steps, kernel / kernel.sum(), mode="same") / 10

    angles = {
        "arm.rx": 40 * np.sin(2 * np.pi * t / period + phase) if wave else drift(8),
        "arm.ry": 15 * np.sin(2 * np.pi * t / period + phase + 0.8) if wave else drift(4),
        "hand.rx": 20 * np.sin(2 * np.pi * t / period + phase + 1.5) if wave else drift(4),
        "leg.rx": drift(3),
        "spine.rx": 3 * np.sin(2 * np.pi * t / period + phase) + drift(1) if wave else drift(2),
    }
    if foreign:
        other = rng.uniform(0.3, 2.5)
        angles["other.rx"] = 50 * np.sin(2 * np.pi * t / other + rng.uniform(0, 6)) + drift(5)
    strings, durations, displacements = {}, {}, {}
    for name, angle in angles.items():
        strings[name], durations[name], displacements[name] = kinetemes(angle)
    return Actiongram.from_strings(strings, durations, displacements=displacements,
                                   skeleton={"spine": None, "arm": "spine", "hand": "arm",
                                             "leg": "spine", "other": "spine"})


def test_the_waving_joints_are_the_actuators_and_the_foreign_limb_is_not():
    takes = [performance(seed) for seed in range(6)]
    result = PAL().induce(takes)
    # the trunk sways in step a little: it joins as the arm's skeleton neighbour
    assert result.actuators == ("arm", "hand", "spine")
    assert {r.name: r.status for r in result.actuator_reports}["spine"] == \
        "component (skeleton neighbour)"
    assert "other" not in result.actuators and "leg" not in result.actuators
    assert result.verdict == ""
    assert set(result.actuator_channels["arm"]) <= {"arm.rx", "arm.ry"}
    assert result.performances == 6
    # occurrences are cycles in every performance, with their performance index
    name = result.components[0]
    assert set(result.occurrence_performance[name]) == set(range(6))
    assert len(result.occurrences[name]) >= 6 * 5
    # the morpheme of a component: kinetemes with typical durations and displacements
    morpheme = result.morphemes[name]
    assert len(morpheme.kinetemes) == len(morpheme.durations) == len(morpheme.displacements)
    assert 0.3 < sum(morpheme.durations) < 1.1  # about one wave
    report = {r.name: r for r in result.actuator_reports}
    assert report["arm"].share == 1.0 or report["hand"].share == 1.0
    assert report["other"].status in ("not significant", "below the share of the leader")
    assert "joint other" in result.report("other.rx").status


def test_no_synchronised_repetition_is_said_plainly():
    takes = [performance(seed, wave=False) for seed in range(5)]
    result = PAL().induce(takes)
    assert result.components == () and result.actuators == () and result.system is None
    assert result.verdict == "no synchronised repetition"
    assert all("no synchronised repetition" in r.status for r in result.reports)


def test_path_evidence_names_what_moves_most_the_ablation():
    takes = [performance(seed) for seed in range(6)]
    by_path = PAL(evidence="path").induce(takes)
    # the foreign limb moves most of all: magnitude alone takes it
    assert "other" in by_path.actuators
    by_kinetemes = PAL().induce(takes)
    assert "other" not in by_kinetemes.actuators


def test_a_skeleton_neighbour_joins_at_a_small_share():
    takes = [performance(seed, foreign=False) for seed in range(5)]
    strict = PAL(neighbour_share=1.0).induce(takes)
    loose = PAL(neighbour_share=0.001, joint_share=0.99).induce(takes)
    assert "spine" not in strict.actuators
    assert len(loose.actuators) >= 2
    statuses = {r.name: r.status for r in loose.actuator_reports}
    assert "component (skeleton neighbour)" in statuses.values()


def test_performances_with_different_strings_are_completed_not_refused():
    takes = [performance(seed) for seed in range(4)]
    takes[1] = takes[1].subset([n for n in takes[1].names if n != "leg.rx"])
    result = PAL().induce(takes)
    assert result.actuators[:2] == ("arm", "hand") and "other" not in result.actuators


def test_deterministic_and_independent_of_the_order_of_parameters():
    takes = [performance(seed) for seed in range(5)]
    first, second = PAL().induce(takes), PAL().induce(list(takes))
    assert first.to_dict() == second.to_dict()
    assert first.morphemes == second.morphemes


@pytest.mark.parametrize("bad", [{"evidence": "magic"}, {"joint_share": 0},
                                 {"max_shift": 0.9}])
def test_bad_parameters_are_validation_errors(bad):
    from psgs.errors import ValidationError

    with pytest.raises(ValidationError):
        PAL(**bad)
