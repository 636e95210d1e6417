"""The flight feature: the share of a take's frames off the ground, and its group, always read."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology.bvh import parse_bvh
from praxicon_fixtures import SHARED, leg_body, needs_mocap
from praxicon.feature_groups import ALWAYS_READ, feature_groups, telling_groups
from praxicon.features import flight_share, motion_features


def _hopping(flying, lift: float, scale: float, offset, swing=None):
    """A hip and a straight leg (thigh 4, shin 5, in units of ``scale``) whose foot stands on
    the ground at height ``offset`` (a number, or one per frame: a floor that tilts) while the
    thigh swings by ``swing`` degrees, the hip as high as the swing lets it be; in the frames
    of ``flying`` the hip is ``lift`` leg lengths higher. It walks along x meanwhile."""
    leg = 9 * scale
    floor = np.broadcast_to(np.asarray(offset, dtype=float), (len(flying),))
    swing = np.zeros(len(flying)) if swing is None else np.asarray(swing, dtype=float)
    # the thigh's rotation turns the 5-long bone below it: the foot is 4 + 5 cos(swing) down
    hip = floor + scale * (4 + 5 * np.cos(np.radians(swing))) + lift * leg * np.asarray(flying)
    still = np.zeros(len(flying))
    return leg_body(0.3 * scale * np.arange(len(flying)), hip, still, swing, scale, "0.0333333")


@settings(max_examples=40, deadline=None)
@given(st.data(), st.integers(10, 150), st.floats(0.1, 0.6), st.floats(0.01, 100.0),
       st.floats(-500.0, 500.0))
def test_flight_is_the_share_of_frames_off_the_ground(data, frames, lift, scale, offset):
    # oracle: the frames drawn as flying, the foot on the ground in every other frame (one in
    # five at least, so that every second of the take shows the ground); the ground and the
    # heights move and scale with the body
    flying = np.array(data.draw(st.lists(st.booleans(), min_size=frames, max_size=frames)))
    flying[::5] = False
    swing = np.array(data.draw(st.lists(st.floats(0.0, 30.0), min_size=frames,
                                        max_size=frames)))
    swing[:2] = 0.0, 20.0  # the hip moves up and down: a body, not a board slid on the floor
    motion = _hopping(flying, lift, scale, offset, swing)
    assert flight_share(motion, ["Hips"]) == pytest.approx(flying.mean())
    features = dict(zip(*motion_features(motion)))
    assert features["flight"] == pytest.approx(math.log(flying.mean() + 0.1))


@pytest.mark.parametrize("rise", [-3.0, 3.0])
def test_a_floor_that_tilts_is_no_flight(rise):
    # a walk of 4 s over a floor rising (or falling) three times the 4 % that counts as off
    # the ground: read against one ground for the whole take, half its frames flew
    frames = 120
    thigh = 20 * np.sin(np.arange(frames) / 5)
    floor = np.linspace(0.0, rise * 0.04 * 9, frames)
    walk = _hopping(np.zeros(frames, dtype=bool), 0.0, 1.0, floor, thigh)
    assert flight_share(walk, ["Hips"]) == 0.0
    hops = np.arange(frames) % 10 >= 6
    assert flight_share(_hopping(hops, 0.2, 1.0, floor, thigh), ["Hips"]) == pytest.approx(0.4)


@pytest.mark.parametrize("level", [0.0, -5.0, 3.0])
def test_a_point_that_carries_the_travel_along_the_floor_is_not_the_body(level):
    # a top joint at one height that only travels (as some exports carry the root's motion),
    # at the floor, under it or over it, would be the lowest point in every frame, and the
    # body never off the ground
    rows = [f"{0.3 * k:.6f} {11 - level + 2 * (k % 4 == 1):.6f} 0" for k in range(40)]
    motion = parse_bvh(f"""HIERARCHY
ROOT root
{{ OFFSET 0 {level} 0
  CHANNELS 1 Xposition
  JOINT Hips
  {{ OFFSET 0 0 0
    CHANNELS 1 Yposition
    JOINT shin
    {{ OFFSET 0 -10 0
      CHANNELS 1 Xrotation
      End Site
      {{ OFFSET 0 -1 0 }} }} }} }}
MOTION
Frames: 40
Frame Time: 0.0333333
""" + "\n".join(rows) + "\n")
    assert flight_share(motion, ["root", "Hips"]) == pytest.approx(0.25)


def test_offsets_too_large_to_place_the_points_give_no_flight():
    # each offset is a finite number, their sum is not: the points cannot be placed, and the
    # take is described without its flight rather than refused
    rows = [f"{0.3 * k:.6f} {11 + (k % 3):.6f} 0 {10.0 * k:.6f} 0" for k in range(12)]
    motion = parse_bvh("""HIERARCHY
ROOT Hips
{ OFFSET 0 0 0
  CHANNELS 3 Xposition Yposition Zposition
  JOINT thigh
  { OFFSET 0 -1.5e308 0
    CHANNELS 1 Xrotation
    JOINT shin
    { OFFSET 0 -1.5e308 0
      CHANNELS 1 Xrotation
      End Site
      { OFFSET 0 0 0 } } } }
MOTION
Frames: 12
Frame Time: 0.0333333
""" + "\n".join(rows) + "\n")
    assert flight_share(motion, ["Hips"]) is None
    names = motion_features(motion)[0]
    assert "flight" not in names and "tempo" in names


def test_a_motion_without_a_skeleton_has_no_flight():
    from kinetology import Motion

    t = np.arange(60) / 30
    values = np.column_stack([30 * t, 90 + 5 * np.sin(8 * t), 0 * t, 20 * np.sin(8 * t)])
    motion = Motion(values, ("Hips.tx", "Hips.ty", "Hips.tz", "knee.rx"), 30.0)
    names = motion_features(motion)[0]
    assert any(n.startswith("Hips.travel") for n in names)  # a moving root: root features
    assert "flight" not in names and flight_share(motion, ["Hips"]) is None


def test_flight_is_a_group_of_its_own_and_always_read():
    groups = feature_groups(["Hips.travelz:drift", "flight", "tempo", "knee.rx:pose"])
    assert {k: v.tolist() for k, v in groups.items()} == {
        "Hips.travelz:drift": [0], "flight": [1], "tempo": [2], "knee": [3]}
    assert ALWAYS_READ == ("flight", "pace")
    # two actions alike in every group: none tells them apart, but the flight is read
    means = np.zeros((2, 4))
    tells = telling_groups(means, np.ones((2, 4)), np.ones(4), groups, np.ones(4))
    assert tells[:, list(groups).index("flight")].all()
    assert not tells[:, [k for k, g in enumerate(groups) if g != "flight"]].any()


@needs_mocap()
def test_walks_and_turns_alone_answer_a_run_none_of_these():
    # every learnt action keeps to the ground, so no group of theirs tells a run from them by
    # its flight; a run is none of them all the same, whatever its style, and their own new
    # takes still are what they are (the dataset-2 subset, takes 1-3 of four styles learn)
    from praxicon.description import describe
    from praxicon.recognition import feature_matrix, recognise_many
    from praxicon.features import _root_joints
    from kinetology import Motion, read_bvh

    data = SHARED / "bandai-namco-2-subset" / "data"
    styles = ("active", "normal", "feminine", "youthful")
    contents = ("walk", "walk-turn-left", "walk-turn-right")

    def takes(content, style, numbers):
        return [read_bvh(data / f"dataset-2_{content}_{style}_{n:03d}.bvh") for n in numbers]

    px = describe({c: [m for s in styles for m in takes(c, s, (1, 2, 3))] for c in contents},
                  groups={c: [s for s in styles for _ in range(3)] for c in contents})
    run_takes = [m for s in ("normal", "masculine") for m in takes("run", s, (4,))]
    runs = recognise_many(px, run_takes)
    assert [r.action for r in runs] == [None, None]
    assert all(r.excess_group == "flight" for r in runs)
    for run, motion in zip(runs, run_takes):  # the explanation says how far the run flies
        share = run.off_ground  # and how far a walk or a turn does
        assert share == pytest.approx(flight_share(motion, _root_joints(motion)), abs=1e-4)
        assert share > 0.1
        assert f"off the ground in {100 * share:.0f} % of its frames" in run.explain()
        terms = {name: (term, typical) for name, term, typical in run.flight}
        assert set(terms) == {name for name, _ in run.reasons}
        assert all(term > 1.0 and typical < 0.035 for term, typical in terms.values())
        assert f"flight term {terms[run.ranking[0][0]][0]:.2f}" in run.explain()
        # the flight's term is part of the shared distance: the joints' terms, the tempo's,
        # the flight's and the pace's sum to it (the terms are rounded to 3 decimals)
        name = run.ranking[0][0]
        columns = feature_matrix(px, [motion])[0]
        total = (sum(r.penalty for r in dict(run.reasons)[name]) + dict(run.tempo)[name]
                 + terms[name][0] + dict((n, t) for n, t, _ in run.pace)[name])
        assert total == pytest.approx(run.penalty * len(columns), abs=0.1)
    # the same run without its skeleton: no body to lift, the flight not compared
    bare = recognise_many(px, [Motion(m.values, m.channels, m.frame_rate, None, m.source)
                               for m in run_takes])
    assert all(r.off_ground is None and r.flight == () and r.travel is None and r.pace == ()
               for r in bare)
    assert all("off the ground" not in r.explain() for r in bare)
    known = recognise_many(px, [m for c in contents for m in takes(c, "normal", (4, 5))])
    assert [r.action for r in known] == [c for c in contents for _ in (4, 5)]


def test_a_frame_or_two_of_glitch_does_not_set_the_ground():
    # a walk whose lowest point dips far below the floor in two frames: read as the ground,
    # the frames around them would all have flown
    frames = 120
    floor = np.zeros(frames)
    floor[[40, 41]] = -3.0
    walk = _hopping(np.zeros(frames, dtype=bool), 0.0, 1.0, floor,
                    20 * np.sin(np.arange(frames) / 5))
    assert flight_share(walk, ["Hips"]) == 0.0


@needs_mocap()
def test_the_shared_walks_keep_to_the_ground_and_most_runs_fly():
    from kinetology import read_bvh
    from praxicon.features import _root_joints

    shares = {}
    for path in sorted((SHARED / "bandai-namco-2-subset" / "data").glob("*.bvh")):
        _, content, style, _ = path.stem.split("_")
        motion = read_bvh(path)
        shares.setdefault((content, style), []).append(flight_share(motion, _root_joints(motion)))
    walks = [v for (c, _), vs in shares.items() if c != "run" for v in vs]
    assert len(walks) == 105 and max(walks) < 0.035  # 4 frames of 133 at most
    flying = [min(vs) for (c, s), vs in shares.items() if c == "run" and s not in
              ("elderly", "exhausted")]
    assert len(flying) == 5 and min(flying) >= 0.3
