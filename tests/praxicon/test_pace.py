"""The pace feature: how fast the body travels over the ground, in its hips' heights a second."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology import Motion
from kinetology.bvh import parse_bvh
from praxicon_fixtures import SHARED, leg_body, needs_mocap
from praxicon.features import motion_features, travel_pace


def _walker(seconds: float, rate: float, speed: float, heading: float, scale: float,
            sway: float = 0.0, floor: float = 0.0):
    """A hip and a straight leg (thigh 4, shin 5, in units of ``scale``) whose foot keeps to
    the ground at height ``floor`` (lifting it a twentieth of a unit between steps) while the
    thigh swings 20 degrees each way, and the hips' median height above the ground; it travels
    ``speed`` units a second along ``heading`` (degrees) and sways ``sway`` units sideways,
    once a second (a step's sway, which a second's travel leaves out)."""
    frames = max(3, int(round(seconds * rate)))
    t = np.arange(frames) / rate
    swing = 20 * np.sin(2 * np.pi * t)
    # the foot lifts a little between steps (a point of one height is not read as the body)
    hip = floor + scale * (4 + 5 * np.cos(np.radians(swing)) + 0.05 * np.sin(2 * np.pi * t) ** 2)
    along = speed * t
    side = sway * np.sin(2 * np.pi * t)
    h = np.radians(heading)
    x = along * np.cos(h) - side * np.sin(h)
    z = along * np.sin(h) + side * np.cos(h)
    return leg_body(x, hip, z, swing, scale, f"{1 / rate:.9f}"), float(np.median(hip - floor))


@settings(max_examples=40, deadline=None)
@given(seconds=st.floats(1.5, 6.0), rate=st.sampled_from([7.5, 24.0, 29.97, 30.0, 60.0, 120.0]),
       legs=st.floats(0.0, 4.0), heading=st.floats(-180.0, 180.0),
       scale=st.floats(0.01, 100.0), floor=st.floats(-500.0, 500.0))
def test_the_pace_is_the_travel_a_second_over_the_hips_height(seconds, rate, legs, heading,
                                                              scale, floor):
    # ``legs``: hips' heights a second. Any heading, any unit of length, any frame rate, any
    # floor height: the same pace
    hips = 9 * scale  # about: the leg swings, so the hip is a little lower on average
    motion, median = _walker(seconds, rate, legs * hips, heading, scale, floor=floor)
    assert travel_pace(motion, ["Hips"]) == pytest.approx(legs * hips / median, rel=0.02,
                                                          abs=1e-6)


@settings(max_examples=20, deadline=None)
@given(sway=st.floats(0.0, 1.0), scale=st.floats(0.1, 10.0), heading=st.floats(-180, 180))
def test_swaying_on_the_spot_is_no_travel(sway, scale, heading):
    # a step's sway (a hip's height at most, once a second) goes nowhere in a second
    motion, _ = _walker(4.0, 30.0, 0.0, heading, scale, sway=sway * 9 * scale)
    assert travel_pace(motion, ["Hips"]) < 0.02


def test_a_motion_without_a_skeleton_has_no_pace():
    motion, _ = _walker(3.0, 30.0, 9.0, 0.0, 1.0)
    bare = Motion(motion.values, motion.channels, motion.frame_rate, None, motion.source)
    assert travel_pace(bare, ["Hips"]) is None
    assert "pace" not in motion_features(bare)[0] and "pace" in motion_features(motion)[0]


def test_a_top_joint_on_the_floor_is_no_unit():
    # the travel carried by a top joint at floor level (it jitters, so it is the chain's last
    # moving joint) and the hips above it without a translation: that joint's height is no
    # length to measure a pace in
    frames, rate = 90, 30.0
    t = np.arange(frames) / rate
    swing = 20 * np.sin(2 * np.pi * t)
    rows = [f"{9 * t[k]:.9f} {1e-3 * (k % 2):.9f} 0 0 {swing[k]:.9f}" for k in range(frames)]
    motion = parse_bvh(f"""HIERARCHY
ROOT joint_Root
{{ OFFSET 0 0 0
  CHANNELS 3 Xposition Yposition Zposition
  JOINT Hips
  {{ OFFSET 0 9 0
    CHANNELS 1 Xrotation
    JOINT leg
    {{ OFFSET 0 -4 0
      CHANNELS 1 Xrotation
      End Site
      {{ OFFSET 0 -5 0 }} }} }} }}
MOTION
Frames: {frames}
Frame Time: {1 / rate:.9f}
""" + "\n".join(rows) + "\n")
    from praxicon.features import _root_joints

    assert _root_joints(motion) == ["joint_Root"]
    assert travel_pace(motion, ["joint_Root"]) is None
    assert "pace" not in motion_features(motion)[0]
    # the same body with the hips as the chain's last joint has a pace
    assert travel_pace(motion, ["joint_Root", "Hips"]) == pytest.approx(1.0, rel=0.05)


def test_the_pace_is_a_log_beside_the_flight():
    motion, median = _walker(3.0, 30.0, 18.0, 30.0, 1.0)
    names, values = motion_features(motion)
    assert names[-3:] == ("flight", "pace", "tempo")
    assert values[names.index("pace")] == pytest.approx(np.log(18.0 / median + 0.05), rel=0.01)


def test_a_praxicon_of_actions_in_place_answers_a_walk_none_of_these():
    # every learnt action stands on the spot, so no group of theirs tells a walk from them by
    # its pace; a walk is none of them all the same, and their own new takes are what they are
    from praxicon.description import describe
    from praxicon.recognition import recognise_many

    def take(sway, swing_scale, seed):
        rng = np.random.default_rng(seed)
        return _walker(3.0 + rng.uniform(0, 1), 30.0, 0.0, rng.uniform(-180, 180),
                       swing_scale * rng.uniform(0.95, 1.05), sway=sway)[0]

    px = describe({"sway": [take(3.0, 1.0, k) for k in range(6)],
                   "still": [take(0.0, 1.0, 10 + k) for k in range(6)]})
    walks = recognise_many(px, [_walker(3.0, 30.0, 9.0 * s, h, 1.0)[0]
                                for s, h in ((0.8, 0.0), (1.2, 90.0), (1.5, -45.0))])
    assert [w.action for w in walks] == [None, None, None]
    assert all(w.excess_group == "pace" for w in walks)
    for walk in walks:  # the explanation says how fast the walk goes and the actions do not
        assert walk.travel > 0.5
        assert f"travels {walk.travel:.2f} hips' heights a second" in walk.explain()
        typical = {name: value for name, _, value in walk.pace}
        assert set(typical) == {"sway", "still"} and all(0 <= v < 0.1 for v in typical.values())
    known = recognise_many(px, [take(3.0, 1.0, 30), take(0.0, 1.0, 31)])
    assert [k.action for k in known] == ["sway", "still"]


@needs_mocap()
def test_the_shared_gaits_travel_and_the_actions_in_place_do_not():
    from kinetology import read_bvh
    from praxicon.features import _root_joints

    paces = {}
    for path in sorted((SHARED / "bandai-namco-1" / "data").glob("*.bvh")):
        content = path.stem.split("_")[1]
        motion = read_bvh(path)
        paces.setdefault(content, []).append(travel_pace(motion, _root_joints(motion)))
    in_place = [p for c in ("bow", "bye", "byebye", "guide", "punch", "call", "respond")
                for p in paces[c]]
    gaits = [p for c in ("walk", "walk-back", "walk-left", "walk-right", "run", "dash")
             for p in paces[c]]
    assert len(in_place) == 65 and len(gaits) == 105
    assert max(in_place) < 0.25 and min(gaits) > 0.4
    assert min(paces["dash"]) > min(paces["run"]) > max(paces["walk-back"])
