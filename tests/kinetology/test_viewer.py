"""The skeleton viewer: what a page holds, the subsampling rule, GIF/MP4, bad input, notebook repr.

The page in a real browser is tests/kinetology/test_viewer_browser.py.
"""

from __future__ import annotations

import json
import math
import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from kinetology import Joint, Motion, Skeleton
from kinetology.bvh import parse_bvh
from kinetology.cli import main
from kinetology.kinematics import forward_kinematics
from kinetology.segmentation import STATES, states
from kinetology._viewer_contents import frame_step
from kinetology.viewer import ViewError, view

from kinetology_fixtures import MOCAP, needs_mocap, real_take

BVH = MOCAP / "bandai-namco-1" / "data" / "dataset-1_bow_active_001.bvh"
AMC = MOCAP / "cmu-subject02" / "02_01.amc"


def _leg(frames: int = 60, rate: float = 30.0, source: str = "leg.bvh") -> Motion:
    """Hip and knee of a leg; the knee bends and straightens once, the hip sways a little."""
    t = np.linspace(0, 2 * np.pi, frames)
    rows = "\n".join(f"{5 * math.sin(a):.4f} {45 * (1 - math.cos(a)):.4f}" for a in t)
    return parse_bvh(f"""HIERARCHY
ROOT hip
{{ OFFSET 0 0 0
  CHANNELS 1 Xrotation
  JOINT knee
  {{ OFFSET 0 -10 0
    CHANNELS 1 Xrotation
    End Site
    {{ OFFSET 0 -10 0 }} }} }}
MOTION
Frames: {frames}
Frame Time: {1 / rate:.8f}
{rows}
""", source=source)


def _data(page: str) -> dict:
    text = re.search(r'<script type="application/json" class="data">(.*?)</script>', page,
                     re.S).group(1)
    return json.loads(text)


def _decoded(panel: dict) -> np.ndarray:
    """The page's positions as its script decodes them (centred, in file units)."""
    n = len(panel["joints"])
    deltas = np.array(panel["pos"], float).reshape(panel["frames"], n, 3)
    return np.cumsum(deltas, axis=0) * panel["quantum"]


def _assert_page_positions(panel, data) -> None:
    """The page's integers decode to the panel's positions within half a quantum: the
    differences are whole numbers, so summing them back loses nothing."""
    centre = panel._centre()
    error = np.abs(_decoded(data) - (panel.positions - centre)).max()
    assert error <= data["quantum"] / 2 * (1 + 1e-9), (error, data["quantum"])
    radius, height = panel._fit
    assert data["quantum"] == max(2 * radius, height) / 1000  # 1/1000 of the body's size


@settings(max_examples=40, deadline=None)
@given(angles=st.lists(st.floats(-720, 720), min_size=2, max_size=60),
       travel=st.floats(-1e4, 1e4), length=st.floats(0.01, 1e3))
def test_page_positions_decode_within_half_a_quantum(angles, travel, length):
    skeleton = Skeleton((Joint("root", None, (0, 0, 0), ("root.tz", "root.rx")),
                         Joint("knee", 0, (0, -length, 0), ("knee.rx",)),
                         Joint("foot", 1, (0, -length, 0), end_site=True)))
    n = len(angles)
    values = np.column_stack([np.linspace(0, travel, n), angles, angles[::-1]])
    panel = view(Motion(values, ("root.tz", "root.rx", "knee.rx"), 30, skeleton),
                 kinetemes=False).panels[0]
    _assert_page_positions(panel, panel.to_json())


@settings(max_examples=200, deadline=None)
@given(rate=st.floats(1, 1000), frames=st.integers(1, 10 ** 6),
       max_rate=st.floats(1, 120), max_frames=st.integers(1, 2000))
def test_step_is_the_smallest_meeting_both_caps(rate, frames, max_rate, max_frames):
    motion = Motion(np.zeros((1, 1)), ("a.rx",), rate)
    object.__setattr__(motion, "values", np.zeros((frames, 0)))  # a shape, not data
    k = frame_step(motion, max_rate, max_frames)

    def fits(step):
        return rate / step <= max_rate * (1 + 1e-9) and math.ceil(frames / step) <= max_frames

    assert fits(k)
    assert k == 1 or not fits(k - 1)


def test_page_holds_the_kept_frames_positions_and_states():
    leg = _leg(frames=90, rate=60.0)
    player = view(leg, actuators=["knee.rx"], max_rate=20)
    panel = player.panels[0]
    assert panel.step == 3 and panel.frames == 30 and panel.frame_rate == 20
    assert panel.actuators == (False, True, False)  # a channel stands for its joint
    # positions: forward kinematics of every third frame, to the page's quantum
    data = _data(player.to_html())["panels"][0]
    assert np.allclose(panel.positions, forward_kinematics(leg)[::3])
    _assert_page_positions(panel, data)
    # states: each moving joint shows its channel's state at the kept frames; end site still
    for joint, channel in (("hip", "hip.rx"), ("knee", "knee.rx")):
        codes = states(leg.column(channel), leg.frame_rate)[::3]
        assert data["states"][leg.skeleton.index(joint)] == "".join(STATES[c] for c in codes)
    assert set(data["states"][2]) == {"-"}


def test_a_joint_takes_the_state_of_its_widest_channel():
    t = np.linspace(0, 2 * np.pi, 60)
    values = np.column_stack([40 * np.sin(t), 8 * np.cos(3 * t)])
    skeleton = Skeleton((Joint("knee", None, (0, 0, 0), ("knee.rx", "knee.rz")),
                         Joint("foot", 0, (0, -10, 0), end_site=True)))
    motion = Motion(values, ("knee.rx", "knee.rz"), 30, skeleton)
    shown = view(motion).panels[0].states[0]
    assert shown == "".join(STATES[c] for c in states(values[:, 0], 30.0))
    assert shown != "".join(STATES[c] for c in states(values[:, 1], 30.0))


@needs_mocap
def test_real_takes_side_by_side_page_is_small_and_self_contained(tmp_path):
    out = tmp_path / "both.html"
    assert main(["view", str(BVH), str(AMC), "-o", str(out)]) == 0
    page = out.read_text()
    data = _data(page)
    assert [p["label"] for p in data["panels"]] == [BVH.name, AMC.name]
    assert data["rate"] == 30 and data["panels"][1]["frames"] == math.ceil(343 / 4)
    # nothing fetched: no src/href to anything, the script inline
    assert not re.search(r"\b(src|href)=", page) and "http" not in page.split("<script")[0]
    assert len(page) < 200_000
    # kinetemes on a real take: several states, and the still joints grey
    cmu = data["panels"][1]
    assert {s for row in cmu["states"] for s in row} == {"B", "G", "R", "Y", "-"}


@needs_mocap
@pytest.mark.parametrize("take", [BVH, AMC], ids=["bvh", "amc"])
def test_cli_writes_a_gif_of_a_real_take(tmp_path, capsys, take):
    image = pytest.importorskip("PIL.Image", reason="GIFs need Pillow (matplotlib's writer)")
    out = tmp_path / "take.gif"
    assert main(["view", str(take), "-o", str(out), "--max-rate", "4"]) == 0
    with image.open(out) as gif:
        motion = real_take(take)
        step = math.ceil(motion.frame_rate / 4)  # the fewest frames dropped for 4 fps or less
        assert gif.n_frames == math.ceil(motion.frames / step)
        first = np.asarray(gif.convert("RGB"))
        gif.seek(gif.n_frames // 2)
        middle = np.asarray(gif.convert("RGB"))
    assert (first != middle).any()  # the body moved
    assert f"{out}: {take.name}:" in capsys.readouterr().out


def test_mp4_needs_ffmpeg(tmp_path, monkeypatch, capsys):
    leg = tmp_path / "leg.bvh"
    from kinetology.bvh_writer import write_bvh
    write_bvh(_leg(20), leg)
    if shutil.which("ffmpeg"):
        assert main(["view", str(leg), "-o", str(tmp_path / "leg.mp4")]) == 0
        assert (tmp_path / "leg.mp4").read_bytes()[4:8] == b"ftyp"  # an MP4 container
    monkeypatch.setattr("kinetology.viewer.shutil.which", lambda name: None)
    assert main(["view", str(leg), "-o", str(tmp_path / "none.mp4")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "ffmpeg" in err[0] and not (tmp_path / "none.mp4").exists()


@pytest.mark.parametrize("text, suffix, words", [
    ("this is not motion\n", ".bvh", "HIERARCHY"),
    ("HIERARCHY\nROOT a\n{ OFFSET 0 0 0\n CHANNELS 1 Xrotation\n End Site\n { OFFSET 0 1 0 } }\n"
     "MOTION\nFrames: 0\nFrame Time: 0.1\n", ".bvh", "no frames"),
    ("garbage", ".c3d", "unknown motion format"),
], ids=["not-motion", "empty", "unknown-format"])
def test_bad_input_is_one_line_and_status_2(tmp_path, capsys, text, suffix, words):
    path = tmp_path / f"bad{suffix}"
    path.write_text(text)
    assert main(["view", str(path), "-o", str(tmp_path / "out.html")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and words in err[0] and "bad" in err[0], err
    assert not (tmp_path / "out.html").exists()


def test_an_output_it_cannot_write_fails_before_reading(tmp_path, capsys):
    assert main(["view", str(tmp_path / "missing.bvh"), "-o", str(tmp_path / "x.png")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "'.png'" in err[0] and ".html, .gif, .mp4" in err[0]


def test_api_errors_name_the_problem():
    leg = _leg(20)
    with pytest.raises(ViewError, match="no joint or channel 'elbow'"):
        view(leg, actuators=["elbow"])
    with pytest.raises(ViewError, match="not a panel"):
        view({"real": leg}, actuators={"generated": ["knee"]})
    with pytest.raises(ViewError, match="no skeleton"):
        view(leg.select(leg.channels))
    with pytest.raises(ViewError, match="no motion"):
        view([])


def test_several_motions_share_one_clock():
    slow, fast = _leg(20, rate=10.0, source="a/walk.bvh"), _leg(60, rate=30.0,
                                                                source="b/walk.bvh")
    player = view([slow, fast])
    assert [p.label for p in player.panels] == ["walk.bvh (1)", "walk.bvh (2)"]
    assert player.frame_rate == 30 and player.ticks == 60
    assert [player.frame_of(0, t) for t in (0, 2, 3, 59)] == [0, 0, 1, 19]
    assert [player.frame_of(1, t) for t in (0, 3, 59)] == [0, 3, 59]


def test_notebook_repr_of_a_motion_is_the_player():
    leg = _leg(20)
    fragment = leg._repr_html_()
    assert 'class="kinetology-view"' in fragment and "<!DOCTYPE" not in fragment
    assert _data(fragment)["panels"][0]["joints"] == ["hip", "knee", "knee.end"]
    assert leg.select(leg.channels)._repr_html_() is None  # no skeleton: the plain repr


@needs_mocap
def test_a_root_left_behind_is_not_a_bone_and_the_camera_follows_the_body():
    bandai, cmu = view([real_take(BVH), real_take(AMC)]).panels
    # Bandai Namco's joint_Root stays at the origin while the hips' channels carry the body
    assert [bandai.joints[j] for j, b in enumerate(bandai.bones) if not b] == \
        ["joint_Root", "Hips"]
    assert not bandai.body[0] and bandai.body[1:].all()
    # CMU's root is the pelvis: every link below it is a bone
    assert cmu.bones == tuple(p >= 0 for p in cmu.parents) and cmu.body.all()
    # following: the camera's point is under the body's mean at every frame, so the body stays
    # in the picture of a walk that crosses the room (02_01 travels about 3 m: 80 ASF units)
    for panel in (bandai, cmu):
        xy = np.stack([panel.pose(f)[panel.body] for f in range(panel.frames)])
        assert np.abs(xy[..., 0].mean(axis=1)).max() < 0.5 * np.abs(xy[..., 0]).max()
    travel = np.ptp(cmu.positions[:, 0, 2])
    radius, _ = cmu._fit
    assert travel > 2 * radius  # the walk is longer than the picture is wide
    fixed = view(real_take(AMC), follow=False).panels[0]
    assert fixed._fit[0] > travel / 2  # without following, the whole path is in the picture


def test_the_floor_is_fixed_in_the_world():
    leg = _leg(30)  # the knee bends and straightens: the first and last poses are the same
    skeleton = Skeleton((Joint("hip", None, (0, 0, 0), ("hip.tz", "hip.rx")),
                         *leg.skeleton.joints[1:]))
    walking = Motion(np.column_stack([np.linspace(0, 50, 30), leg.values]),
                     ("hip.tz", *leg.channels), 30, skeleton)
    panel = view(walking).panels[0]
    # the body is drawn at the same place after 50 units of travel; the grid moved under it
    assert np.allclose(panel.pose(0), panel.pose(29), atol=1e-3)
    first, last = panel.floor(0), panel.floor(29)
    assert first.shape == last.shape == (10, 2, 2) and not np.allclose(first, last)


def test_the_command_counts_frames_in_words(tmp_path, capsys):
    from kinetology.bvh_writer import write_bvh
    one, many = write_bvh(_leg(1), tmp_path / "one.bvh"), write_bvh(_leg(20), tmp_path / "m.bvh")
    assert main(["view", str(one), str(many), "-o", str(tmp_path / "x.html")]) == 0
    assert capsys.readouterr().out.strip() == (f"{tmp_path / 'x.html'}: one.bvh: 1 frame at 30 "
                                               f"fps, m.bvh: 20 frames at 30 fps")


def test_player_and_panel_reprs_are_one_short_line():
    player = view({"real": _leg(400), "one": _leg(1)})
    assert repr(player) == ("<Player of 2 motions at 30 fps, 400 steps: real (400 frames, "
                            "3 joints), one (1 frame, 3 joints)>")
    assert repr(player.panels[1]) == "<Panel 'one': 1 frame of 3 joints at 30 fps (every frame)>"
    assert str(player) == repr(player)
    long = view(_leg(3000, rate=120.0), max_frames=500)
    assert repr(long.panels[0]) == ("<Panel 'leg.bvh': 500 frames of 3 joints at 20 fps "
                                    "(1 frame in 6)>")
