"""The flight feature: the share of a take's frames off the ground, and its group, always read."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology.bvh import parse_bvh
from praxicon_fixtures import SHARED, needs_mocap
from praxicon.feature_groups import ALWAYS_READ, feature_groups, telling_groups
from praxicon.features import flight_share, motion_features


def _hopping(flying, lift: float, scale: float, offset: float):
    """A hip and a straight leg (thigh 4, shin 5, in units of ``scale``), standing on the
    ground at height ``offset`` but in the frames of ``flying``, where the hip is ``lift``
    leg lengths higher; it walks along x meanwhile."""
    leg = 9 * scale
    rows = [f"{0.3 * k * scale:.9f} {offset + leg + lift * leg * bool(up):.9f} 0 0 0"
            for k, up in enumerate(flying)]
    return parse_bvh(f"""HIERARCHY
ROOT Hips
{{ OFFSET 0 0 0
  CHANNELS 3 Xposition Yposition Zposition
  JOINT thigh
  {{ OFFSET 0 {-4 * scale} 0
    CHANNELS 1 Xrotation
    JOINT shin
    {{ OFFSET 0 {-5 * scale} 0
      CHANNELS 1 Xrotation
      End Site
      {{ OFFSET 0 0 0 }} }} }} }}
MOTION
Frames: {len(flying)}
Frame Time: 0.0333333
""" + "\n".join(rows) + "\n")


@settings(max_examples=40, deadline=None)
@given(st.data(), st.integers(10, 90), st.floats(0.1, 0.6), st.floats(0.01, 100.0),
       st.floats(-500.0, 500.0))
def test_flight_is_the_share_of_frames_off_the_ground(data, frames, lift, scale, offset):
    # oracle: the frames drawn as flying; the ground (every frame's lowest point in the frames
    # standing, more than 2 % of them) and the heights move and scale with the body
    standing = data.draw(st.integers(max(3, frames // 10), frames))
    flying = np.zeros(frames, dtype=bool)
    order = data.draw(st.permutations(range(frames)))
    flying[list(order[:frames - standing])] = True
    motion = _hopping(flying, lift, scale, offset)
    assert flight_share(motion, ["Hips"]) == pytest.approx(flying.mean())
    features = dict(zip(*motion_features(motion)))
    assert features["flight"] == pytest.approx(math.log(flying.mean() + 0.1))


def test_a_motion_without_a_skeleton_has_no_flight():
    from kinetology import synthetic_motion

    motion = synthetic_motion(3, (0,), seed=1)
    assert motion.skeleton is None or flight_share(motion, []) is None
    assert "flight" not in motion_features(synthetic_motion(3, (0,), seed=1))[0]


def test_flight_is_a_group_of_its_own_and_always_read():
    groups = feature_groups(["Hips.travelz:drift", "flight", "tempo", "knee.rx:pose"])
    assert {k: v.tolist() for k, v in groups.items()} == {
        "Hips.travelz:drift": [0], "flight": [1], "tempo": [2], "knee": [3]}
    assert ALWAYS_READ == ("flight",)
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
    from praxicon.recognition import recognise_many
    from kinetology import read_bvh

    data = SHARED / "bandai-namco-2-subset" / "data"
    styles = ("active", "normal", "feminine", "youthful")
    contents = ("walk", "walk-turn-left", "walk-turn-right")

    def takes(content, style, numbers):
        return [read_bvh(data / f"dataset-2_{content}_{style}_{n:03d}.bvh") for n in numbers]

    px = describe({c: [m for s in styles for m in takes(c, s, (1, 2, 3))] for c in contents},
                  groups={c: [s for s in styles for _ in range(3)] for c in contents})
    runs = recognise_many(px, [m for s in ("normal", "masculine") for m in takes("run", s, (4,))])
    assert [r.action for r in runs] == [None, None]
    assert all(r.excess_group == "flight" for r in runs)
    known = recognise_many(px, [m for c in contents for m in takes(c, "normal", (4, 5))])
    assert [r.action for r in known] == [c for c in contents for _ in (4, 5)]
