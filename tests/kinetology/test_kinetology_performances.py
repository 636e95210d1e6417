"""Performances as input: cut, the label readers (against the real files), joints and parents."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest

import kinetology
from kinetology import Motion, MotionFormatError
from kinetology.joints import CMU_PARENTS, actuator_map, skeleton_parents
from kinetology.labels import (MOCAP6_ACTIONS, Span, read_bandai_json, read_cmu_truelabels,
                               spans_of)
from kinetology.performances import cut, from_spans, performances

from kinetology_fixtures import MOCAP, needs_mocap, real_take


def ramp(frames=100, rate=10.0):
    return Motion(np.arange(float(frames))[:, None], ("knee.rx",), rate, source="ramp")


# -- cut ---------------------------------------------------------------------------------

def test_cut_keeps_frames_from_start_to_stop():
    part = cut(ramp(), 1.0, 2.5)
    assert part.column("knee.rx").tolist() == list(np.arange(10.0, 25.0))
    assert part.meta["cut"] == (1.0, 2.5)
    assert part.frame_rate == 10.0


def test_cut_defaults_are_the_whole_take_and_adjacent_cuts_share_no_frame():
    m = ramp()
    assert cut(m).frames == 100
    a, b = cut(m, 0, 3.3), cut(m, 3.3, None)
    assert a.frames + b.frames == 100
    assert a.column("knee.rx")[-1] + 1 == b.column("knee.rx")[0]


def test_cut_of_a_cut_reports_times_in_the_original_take():
    assert cut(cut(ramp(), 2.0, 8.0), 1.0, 2.0).meta["cut"] == (3.0, 4.0)


@pytest.mark.parametrize("start, stop, words", [
    (-1.0, None, "start -1 s is outside"), (10.0, None, "start 10 s is outside"),
    (0.0, 12.0, "stop 12 s is outside"), (5.0, 4.0, "not after start")])
def test_cut_outside_the_take_is_a_clear_error(start, stop, words):
    with pytest.raises(ValueError, match=words) as info:
        cut(ramp(), start, stop)
    assert "10 s" in str(info.value) or "after" in words


def test_from_spans_cuts_one_performance_per_labelled_span():
    spans = [Span("wave", 0.0, 2.0), Span("rest", 2.0, 5.0), Span("wave", 5.0, 6.0)]
    waves = from_spans(ramp(), spans, "wave")
    assert [p.frames for p in waves] == [20, 10]
    assert all(p.meta["label"] == "wave" for p in waves)
    assert len(from_spans(ramp(), spans, min_seconds=1.5)) == 2
    assert len(performances(ramp(), spans=spans, label="rest")) == 1
    with pytest.raises(ValueError, match="one take"):
        performances(ramp(), ramp(), spans=spans)


def test_span_is_validated():
    with pytest.raises(ValueError, match="start < stop"):
        Span("x", 2.0, 1.0)


# -- CMU truelabels ------------------------------------------------------------------------

def test_truelabels_runs_become_spans(tmp_path):
    path = tmp_path / "t.txt"
    path.write_text("1 1 5\n5 5 12\n")
    spans = read_cmu_truelabels(path)
    assert [(s.label, s.start, s.stop) for s in spans] == [
        ("JumpJack", 0.0, 0.2), ("ArmCircle", 0.2, 0.5), ("ToeTouchTwoHands", 0.5, 0.6)]
    assert read_cmu_truelabels(path, frame_rate=60)[0].stop == 0.4


@pytest.mark.parametrize("text, where", [("1 1 x\n", ":1:5"), ("1\n2 13\n", ":2:3"),
                                         ("0\n", ":1:1")])
def test_truelabels_bad_token_names_line_and_column(tmp_path, text, where):
    path = tmp_path / "bad.txt"
    path.write_text(text)
    with pytest.raises(MotionFormatError) as info:
        read_cmu_truelabels(path)
    assert str(info.value).startswith(f"{path}{where}:")


@needs_mocap
def test_truelabels_of_the_real_takes_cover_them_and_match_the_evaluation_reader():
    from kinetology.evaluation import mocap6_performances

    folder = MOCAP / "cmu-mocap6"
    motions, found = mocap6_performances(folder, min_seconds=2.0)
    for take, motion in motions.items():
        spans = read_cmu_truelabels(folder / "truelabels" / f"{take}.txt")
        assert spans[0].start == 0 and all(a.stop == b.start for a, b in zip(spans, spans[1:]))
        assert all(s.label in MOCAP6_ACTIONS for s in spans)
        # the labels cover the take to within one label block (1/10 s)
        assert abs(spans[-1].stop - motion.duration) < 0.1 + 1e-9
        long = [s for s in spans if s.duration >= 2.0]
        expected = [p for p in found if p.take == take]
        assert [(s.label, round(s.start * 120)) for s in long] == \
            [(p.action, p.start) for p in expected]


# -- Bandai JSON ---------------------------------------------------------------------------

@needs_mocap
@pytest.mark.parametrize("dataset", ["bandai-namco-1", "bandai-namco-2-subset"])
def test_bandai_labels_agree_with_every_file_name(dataset):
    files = sorted((MOCAP / dataset / "data").glob("*.json"))
    assert len(files) >= 140
    for path in files:
        span, = read_bandai_json(path, duration=1.0)  # (one take has no BVH in the subset)
        _, content, style, _ = re.match(r"(dataset-\d)_(.+)_(.+)_(\d+)$", path.stem).groups()
        assert (span.label, span.style) == (content, style), path.name


@needs_mocap
def test_bandai_span_is_the_whole_take():
    path = MOCAP / "bandai-namco-1" / "data" / "dataset-1_byebye_sad_001.json"
    span, = read_bandai_json(path)
    motion = real_take(path.with_suffix(".bvh"))
    assert span.start == 0 and span.stop == pytest.approx(motion.duration, abs=1e-3)
    assert len(performances(motion, spans=[span])) == 1
    assert spans_of(path) == (span,)


def test_bandai_bad_files_name_the_file(tmp_path):
    (tmp_path / "cfg").mkdir()
    (tmp_path / "cfg" / "content_label.txt").write_text("dataset-1_walk\ndataset-1_bye\n")
    (tmp_path / "cfg" / "style_label.txt").write_text("dataset-1_normal\n")
    data = tmp_path / "data"
    data.mkdir()
    good = data / "x.json"
    good.write_text(json.dumps({"content": 1, "style": 0}))
    assert read_bandai_json(good, duration=2.0) == (Span("bye", 0.0, 2.0, "normal"),)
    with pytest.raises(MotionFormatError, match="no take x.bvh"):
        read_bandai_json(good)
    for text, words in [("{nope", "not JSON"), ('{"content": 7, "style": 0}', "outside"),
                        ('{"content": "1", "style": 0}', "integer"), ("[]", "expected an")]:
        good.write_text(text)
        with pytest.raises(MotionFormatError, match=words) as info:
            read_bandai_json(good, duration=1.0)
        assert str(info.value).startswith(str(good))
    with pytest.raises(MotionFormatError, match="unknown label format"):
        spans_of(tmp_path / "labels.csv")


# -- joints ----------------------------------------------------------------------------------

def test_dot_rule_without_a_skeleton():
    m = Motion(np.zeros((3, 3)), ("lfemur.rx", "lfemur.ry", "tail"), 30)
    assert actuator_map(m) == {"lfemur.rx": "lfemur", "lfemur.ry": "lfemur", "tail": "tail"}
    assert skeleton_parents(m, ["lfemur", "tail"]) == {}  # not all CMU bones: unknown


def test_cmu_fallback_parents_skip_joints_that_are_not_actuators():
    m = Motion(np.zeros((2, 3)), ("root.rx", "lfemur.rx", "ltibia.rx"), 120)
    assert skeleton_parents(m, ["root", "lfemur", "ltibia"]) == {
        "root": None, "lfemur": "root", "ltibia": "lfemur"}
    assert set(CMU_PARENTS) >= {"rhumerus", "rradius", "lowerback"}


@needs_mocap
def test_parents_come_from_the_bvh_and_asf_hierarchies():
    bvh = real_take(MOCAP / "bandai-namco-1" / "data" / "dataset-1_bye_normal_001.bvh")
    seg = kinetology.segments(bvh)
    assert seg.skeleton["LowerArm_R"] == "UpperArm_R"
    assert seg.skeleton["UpperArm_R"] == "Shoulder_R"
    assert seg.actuators and all(joint == channel.split(".")[0]
                                 for channel, joint in seg.actuators.items())
    assert set(seg.skeleton) == set(seg.actuators.values())
    amc = real_take(MOCAP / "cmu-subject02" / "02_01.amc")  # with 02.asf beside it
    seg = kinetology.segments(amc)
    assert seg.skeleton["lfemur"] == "root" and seg.skeleton["rradius"] == "rhumerus"
    bare = real_take(MOCAP / "cmu-mocap6" / "amc" / "13_29.amc")  # no ASF
    assert bare.skeleton is None
    seg = kinetology.segments(bare)
    assert seg.skeleton["ltibia"] == "lfemur" and seg.skeleton["root"] is None


def test_segment_performances_gives_every_take_the_same_strings():
    from kinetology.performances import segment_performances

    t = np.arange(90) / 30
    still_in_a = Motion(np.stack([20 * np.sin(2 * np.pi * t), 0 * t + 1.0, 0 * t], 1),
                        ("arm.rx", "leg.rx", "toe.rx"), 30)
    moving_in_b = Motion(np.stack([20 * np.sin(2 * np.pi * t), 10 * np.sin(np.pi * t), 0 * t], 1),
                         ("arm.rx", "leg.rx", "toe.rx"), 30)
    a, b = segment_performances([still_in_a, moving_in_b])
    assert a.names == b.names == ("arm.rx", "leg.rx")  # toe still everywhere: left out
    assert a.string("leg.rx") != b.string("leg.rx")
    assert segment_performances([]) == ()


@needs_mocap
def test_segment_performances_of_real_takes_are_accepted_by_pal_together():
    from psgs.induce.pal import PAL
    from kinetology.performances import segment_performances

    paths = sorted((MOCAP / "bandai-namco-2-subset" / "data").glob("dataset-2_walk_normal_*.bvh"))
    grams = segment_performances(performances(*paths[:2]))
    assert grams[0].names == grams[1].names
    assert grams[0].skeleton["LowerLeg_L"] == "UpperLeg_L"
    PAL().induce(list(grams))  # one actuator set: accepted as performances of one action
