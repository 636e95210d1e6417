"""Generated motion moves its root as the performances do, and its other joints as they do."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

import kinetology
import kinetology.kinematics
from kinetology.motion import Joint, Skeleton
from praxicon import build, read_dataset
from praxicon.body_motion import body_frame, cycle_starts, global_rotation, heading, \
    heading_free_angles, mean_cycles, travel, yaw_matrices
from praxicon.generation import generate
from praxicon_fixtures import SHARED, needs_mocap

_DATA = SHARED / "bandai-namco-2-subset" / "data"


def _generated(tmp_path, content, styles=("normal_001", "active_001", "elderly_001")):
    files = [_DATA / f"dataset-2_{content}_{s}.bvh" for s in styles]
    manifest = tmp_path / "m.csv"
    manifest.write_text("action,file\n" + "".join(f"{content},{f}\n" for f in files))
    build(read_dataset(manifest), tmp_path / "px", progress=False, log=lambda s: None)
    return generate(tmp_path / "px", f"m.{content}", repeat=3), [kinetology.read(f) for f in files]


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    """A praxicon of three walks (normal, active, elderly), its walk generated, the takes."""
    folder = tmp_path_factory.mktemp("walk")
    generated, takes = _generated(folder, "walk")
    return folder / "px", generated, takes


@needs_mocap()
def test_a_generated_walk_advances_at_the_performances_speed(walk):
    _, generated, takes = walk
    real = [travel(m, "Hips").speed for m in takes]
    speed = travel(generated.motion, "Hips").speed
    # measured in the world (forward kinematics): the travel is on joint_Root, above the hips
    assert 0.8 * min(real) <= speed <= 1.2 * max(real), (speed, real)
    assert all(generated.round_trip().values())


@needs_mocap()
def test_a_generated_turn_turns_its_way_as_far_as_the_performances(tmp_path):
    generated, takes = _generated(tmp_path, "walk-turn-left")

    def net(m):  # the heading's whole change, degrees
        t = travel(m, "Hips")
        return t.turn * (m.frames - 1) / m.frame_rate

    real = [net(m) for m in takes]
    turn = net(generated.motion)
    assert min(real) > 45, real  # the takes turn left: the heading rises
    assert 0.8 * min(real) <= turn <= 1.2 * max(real), (turn, real)
    assert all(generated.round_trip().values())
    # joints the grammar does not drive move (a mean cycle), not held at a constant
    moving = [c for c in generated.motion.channels if c.split(".")[0] not in generated.actuators
              and c.split(".")[-1].startswith("r") and not c.startswith("joint_Root")]
    ranges = [float(np.ptp(generated.motion.column(c))) for c in moving]
    assert moving and sum(r > 0.1 for r in ranges) >= len(ranges) // 2, dict(zip(moving, ranges))


def _up_and_ahead(m):
    """The vertical and the travel's direction in the hips' own axes, over a take."""
    r = global_rotation(m, "Hips")
    up = np.einsum("fji,j->fi", r, [0.0, 1.0, 0.0]).mean(axis=0)
    p = kinetology.kinematics.forward_kinematics(m)[:, m.skeleton.index("Hips")]
    v = np.gradient(p, axis=0)
    v[:, 1] = 0.0
    ahead = np.einsum("fji,fj->fi", r, v).mean(axis=0)
    return up, ahead / np.linalg.norm(ahead)


@needs_mocap()
def test_a_generated_walk_stands_as_the_takes_stand_and_walks_where_it_faces(walk):
    # the takes' heading-free hips sit near ±180° in one Euler angle: averaged across that
    # edge, the generated body lay on its side; measured along its facing, it walked sideways
    _, generated, takes = walk
    up, ahead = _up_and_ahead(generated.motion)
    for m in takes:
        real_up, real_ahead = _up_and_ahead(m)
        assert float(up @ real_up) > 0.95, (up, real_up)
        assert float(ahead @ real_ahead) > 0.9, (ahead, real_ahead)


@needs_mocap()
def test_a_style_asked_for_is_generated_at_its_tempo_and_a_missing_one_is_refused(walk):
    folder = walk[0]
    # elderly walks are slower than active ones: so are the generated ones
    slow = generate(folder, "m.walk", repeat=3, style="elderly").motion
    fast = generate(folder, "m.walk", repeat=3, style="active").motion
    assert slow.frames > fast.frames, (slow.frames, fast.frames)
    assert travel(slow, "Hips").speed < travel(fast, "Hips").speed
    with pytest.raises(ValueError, match="no performance of style 'giant'"):
        generate(folder, "m.walk", style="giant")


def _turning(degrees_per_second, tilt, frames=61):
    """One joint turning steadily about the vertical, tilted by ``tilt`` degrees about its x."""
    skeleton = Skeleton((Joint("hip", None, (0, 0, 0), ("hip.tx", "hip.tz", "hip.ry", "hip.rx",
                                                        "hip.rz"), "YXZ"),))
    t = np.arange(frames) / 30.0
    h = np.radians(degrees_per_second * t)
    x, z = np.cumsum(50 * np.sin(h)) / 30, np.cumsum(50 * np.cos(h)) / 30
    values = np.c_[x, z, np.degrees(h), np.full(frames, tilt), np.zeros(frames)]
    return kinetology.Motion(values, ("hip.tx", "hip.tz", "hip.ry", "hip.rx", "hip.rz"), 30.0,
                             skeleton)


@settings(max_examples=25, deadline=None)
@given(st.floats(-120, 120), st.floats(-30, 30))
def test_the_heading_and_the_heading_free_pose_of_a_steady_turn(rate, tilt):
    m = _turning(rate, tilt)
    got = travel(m, "hip")
    assert abs(got.turn - rate) < 1e-6
    # forward or sideways: which horizontal body axis is read as the heading is a choice
    assert abs(got.speed - 50) < 1.0 and abs(np.hypot(got.forward, got.sideways) - 50) < 1.0
    # the heading turned away, what stays is the tilt, the same in every frame
    free = heading_free_angles(m, "hip", body_frame([m], "hip"))
    assert np.ptp(free["hip.rx"]) < 1e-6 and abs(abs(free["hip.rx"][0]) - abs(tilt)) < 1e-6


def test_heading_reads_the_turn_of_any_horizontal_body_axis():
    r = yaw_matrices(np.radians(np.linspace(0, 200, 40)))  # past 180°: unwrapped, not a jump
    for axis in (0, 2):
        h, _ = heading(r, axis)
        assert abs(np.degrees(h[-1] - h[0]) - 200) < 1e-9


@settings(max_examples=25, deadline=None)
@given(st.integers(12, 40), st.floats(0.7, 1.4), st.integers(0, 10))
def test_mean_cycles_find_a_cycle_of_any_tempo_and_phase(period, tempo, shift):
    # a take at its own tempo and phase; the template is the generated cycle
    own = int(round(period * tempo))
    frames = np.arange(shift, shift + 4 * own + 1)
    take = np.sin(2 * np.pi * frames / own)
    template = np.sin(2 * np.pi * np.arange(period) / period)
    starts = cycle_starts(take, template)
    got = mean_cycles([{"c": take}], [starts], period)["c"]
    assert np.abs(got - template).max() < 0.25, (starts, got)


def test_a_whole_cycle_is_the_stride_both_legs_complete():
    from praxicon.body_motion import Body, whole_cycle

    t = np.arange(200)
    # the hip swings every half stride (10 frames), each leg once a stride (20 frames)
    take = {"hip.rx": 10 * np.sin(2 * np.pi * t / 10), "leg_l.rx": 20 * np.sin(2 * np.pi * t / 20),
            "leg_r.rx": -20 * np.sin(2 * np.pi * t / 20), "hips.tx": np.zeros(t.size)}
    body = Body(curves=(take,))
    assert whole_cycle(body, 10 / 30.0, 30.0) == 2   # a morpheme of half a stride: two
    assert whole_cycle(body, 20 / 30.0, 30.0) == 1   # a morpheme of the stride itself
    assert whole_cycle(Body(), 1.0, 30.0) == 1       # no takes: the morpheme


@needs_mocap()
def test_a_style_reads_each_performance_once_and_wrapped_legs_stay_where_they_hang(
        walk, monkeypatch):
    folder, generated, takes = walk
    read = []
    real_read = kinetology.read
    monkeypatch.setattr(kinetology, "read", lambda f, *a, **k: read.append(str(f)) or
                        real_read(f, *a, **k))
    generate(folder, "m.walk", repeat=1, style="elderly")
    # the skeleton's source, and each of the three performances once
    assert len(read) == 4 and len(set(read)) == 3, read
    # Bandai's legs hang near ±180° and the takes write them wrapped: a mean of such raw
    # angles lies nowhere near the leg; generated, the leg hangs where the takes' does
    for c in ("UpperLeg_R.rz", "UpperLeg_R.ry", "UpperLeg_L.rz"):
        got = generated.motion.column(c)
        assert got.min() >= -180.0 and got.max() < 180.0
        direction = lambda x: np.exp(1j * np.radians(x)).mean()
        real = np.angle(np.mean([direction(m.column(c)) for m in takes]), deg=True)
        gap = abs((np.angle(direction(got), deg=True) - real + 180) % 360 - 180)
        assert gap < 15, (c, gap, real)
