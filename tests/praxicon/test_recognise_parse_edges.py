"""Edge cases of recognise and parse met by a new user: a motion too short, a praxicon that
learnt nothing or holds numbers it cannot score with, a root that does not move, a long
recording, and arguments of the wrong kind. Each is one clear line (the command: status 2,
naming the file), never a traceback, a silent wrong answer or an unbounded wait.
"""

from __future__ import annotations

import json
import math
import shutil
from pathlib import Path

import numpy as np
import pytest

from praxicon import load, parse, recognise
from praxicon.description import DescriptionError
from psgs.errors import ValidationError
from praxicon_fixtures import build_walk_and_stay, leg_body, refused, run_praxicon

_RATE = 30.0


def _leg(seed: int, pace: float, seconds: float = 5.0, *, bob: float = 0.2):
    """A hip and a swinging leg that travels ``pace`` units a second along x, its hip bobbing
    ``bob`` units (0 and a pace of 0: no position of it moves)."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * _RATE)) / _RATE
    swing = 30 * np.sin(2 * np.pi * t / (1 + 0.05 * (seed % 3))) + rng.normal(0, 1, t.size)
    still = bob == 0 and pace == 0
    hip = 9 + bob * np.sin(4 * np.pi * t) + (0 if still else rng.normal(0, 0.02, t.size))
    drift = 0 if still else rng.normal(0, 0.01, t.size)
    return leg_body(pace * t + drift, hip, 0 * t + drift, swing, 1.0, f"{1 / _RATE:.9f}")


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    """A praxicon of a walk and a stand (m.walk, m.stay), new takes beside it: a walk, a walk
    on the spot whose hips do not move at all (fixed.bvh), a walk of 2 frames and a long
    walk (long.bvh, 60 s)."""
    from kinetology import Motion, write_bvh

    root = tmp_path_factory.mktemp("edges")
    build_walk_and_stay(root, _leg)
    write_bvh(_leg(7, 10.0), root / "new.bvh")
    write_bvh(_leg(8, 0.0, bob=0.0), root / "fixed.bvh")
    walk = _leg(9, 10.0)
    write_bvh(Motion(walk.values[:2], walk.channels, walk.frame_rate, walk.skeleton),
              root / "two.bvh")
    write_bvh(_leg(10, 10.0, seconds=60.0), root / "long.bvh")
    return root


# -- a motion of fewer than 3 frames -----------------------------------------------------------
def test_parse_says_parsing_needs_three_frames(built, capsys):
    """The command said 'recognising needs at least 3' of a file given to parse."""
    assert refused(capsys, ["parse", str(built / "px"), str(built / "two.bvh")]) == \
        f"{built / 'two.bvh'}: 2 frames; parsing needs at least 3"
    assert refused(capsys, ["recognise", str(built / "px"), str(built / "two.bvh")]) == \
        f"{built / 'two.bvh'}: 2 frames; recognising needs at least 3"


def test_the_api_counts_one_frame_as_one_frame(built):
    from kinetology import Motion, read

    walk = read(built / "new.bvh")
    one = Motion(walk.values[:1], walk.channels, walk.frame_rate, walk.skeleton, "one")
    with pytest.raises(DescriptionError, match=r"^one: 1 frame; recognising needs at least 3$"):
        recognise(built / "px", one)
    with pytest.raises(DescriptionError, match=r"^one: 1 frame; parsing needs at least 3$"):
        parse(built / "px", one)


# -- descriptions the scores cannot compute with: the file named ------------------------------
@pytest.mark.parametrize("part", ["takes", "windows"])
def test_descriptions_that_overflow_the_scores_name_their_file(built, tmp_path, capsys, part):
    """A mean of 1e308 in descriptions.json: the line named no file (a praxicon given as a
    folder, to the command or the API, is named with the part of the file)."""
    px = Path(shutil.copytree(built / "px", tmp_path / "px"))
    data = json.loads((px / "descriptions.json").read_text())
    action = data[part]["actions"][0]
    action["mean"] = [1e308, *action["mean"][1:]]
    (px / "descriptions.json").write_text(json.dumps(data))
    command, call = ("recognise", recognise) if part == "takes" else ("parse", parse)
    line = refused(capsys, [command, str(px), str(built / "new.bvh")])
    assert line.startswith(f"{px / 'descriptions.json'}: {part}: the praxicon's descriptions "
                           f"overflow the scores: the mean of {action['name']}'s feature ")
    with pytest.raises(DescriptionError) as info:
        call(px, built / "new.bvh")
    assert str(info.value) == line
    # the other part is whole: the other command answers
    other = "parse" if part == "takes" else "recognise"
    status, out, _ = run_praxicon(capsys, [other, str(px), str(built / "new.bvh")])
    assert status == 0 and out


# -- a praxicon that learnt no action ----------------------------------------------------------
def test_a_praxicon_that_learnt_nothing_says_so(tmp_path, capsys):
    """Every action failed (one take each): the line said to learn the descriptions with a
    build that resumes and describes its actions, which learns nothing either."""
    from praxicon import build, read_dataset
    from praxicon_fixtures import write_manifest

    manifest = write_manifest(tmp_path, {"wave": [1], "step": [4]})
    build(read_dataset(manifest), tmp_path / "px", progress=False, log=lambda s: None)
    px = tmp_path / "px"
    said = (f"{px}: no action of this praxicon was learnt (its 2 actions failed; "
            f"index.json says why): nothing to recognise with")
    assert refused(capsys, ["recognise", str(px), str(manifest.parent / "wave_1.bvh")]) == said
    assert refused(capsys, ["parse", str(px), str(manifest.parent / "wave_1.bvh")]) == \
        said.replace("recognise", "parse")
    with pytest.raises(DescriptionError, match="no action of this praxicon was learnt"):
        recognise(load(px), manifest.parent / "wave_1.bvh")
    with pytest.raises(DescriptionError, match="no action of this praxicon was learnt"):
        parse(px, manifest.parent / "wave_1.bvh")


# -- a root that does not move -----------------------------------------------------------------
def test_a_root_that_does_not_move_is_not_said_to_be_missing(built, capsys):
    """A walk on the spot whose hips hold still has no travel to read: it was said to lack
    the joint Hips, which it has."""
    found = recognise(built / "px", built / "fixed.bvh")
    assert "Hips" not in found.missing and found.unread == ("Hips",)
    assert found == recognise(load(built / "px"), built / "fixed.bvh")
    assert "Hips" not in parse(built / "px", built / "fixed.bvh").missing
    for command in ("recognise", "parse"):
        status, out, err = run_praxicon(capsys, [command, str(built / "px"),
                                                 str(built / "fixed.bvh")])
        assert status == 0 and out
        assert err == (f"{built / 'fixed.bvh'}: recognised without the travel and turning of "
                       f"Hips: no position of the motion moves\n")


# -- parse's own kinds -------------------------------------------------------------------------
@pytest.mark.parametrize("own", [("nosuch",), ("drift", "Drift"), ("",)])
def test_parse_refuses_a_kind_it_does_not_know(built, own):
    """An unknown kind was scored as no kind, without a word."""
    with pytest.raises(DescriptionError, match="own: .* is no kind of the root's features"):
        parse(built / "px", built / "new.bvh", own=own)


def test_parse_takes_every_kind_it_knows(built):
    for own in ((), ("drift",), ("drift", "energy"), ("excursion",)):
        assert parse(built / "px", built / "new.bvh", own=own).spans


# -- Timeline.labels and Recognition.explain check their arguments ------------------------------
@pytest.mark.parametrize("times, match", [
    ([math.nan], "finite"), ([math.inf], "finite"), (["a"], "numbers"), (None, "sequence"),
    (1.0, "sequence"), ([-0.5], "0 to"), ([1e9], "0 to"),
    # an int of 400 digits overflowed float (OverflowError), a ragged list was numpy's
    # ValueError, a text of digits and a date were read as seconds
    ([10**400], "finite"), ([[1.0, 2.0], [1.0]], "numbers"), (["1.5"], "seconds, not str"),
    ([np.datetime64(1, "s")], "numbers"), ([True], "seconds, not bool"),
])
def test_labels_refuses_times_outside_the_recording(built, times, match):
    """A string, a NaN or a time past the end was given the last span's action; None and a
    number were a TypeError of numpy's."""
    timeline = parse(built / "px", built / "new.bvh")
    with pytest.raises(DescriptionError, match=match):
        timeline.labels(times)


def test_labels_reads_times_from_0_to_the_end(built):
    timeline = parse(built / "px", built / "new.bvh")
    ends = [0.0, timeline.duration]
    assert timeline.labels(ends) == [timeline.spans[0].action, timeline.spans[-1].action]
    assert timeline.labels(np.array(ends)) == timeline.labels(ends)
    assert timeline.labels([]) == []
    assert timeline.labels((0, np.float32(0.0), np.int64(0))) == [timeline.spans[0].action] * 3


@pytest.mark.parametrize("joints", [-1, 1.5, "2", True])
def test_explain_refuses_a_count_of_joints_that_is_none(built, joints):
    """-1 left out the last joint of each role, 1.5 was a TypeError of slicing."""
    with pytest.raises(DescriptionError, match="joints must be an integer"):
        recognise(built / "px", built / "new.bvh").explain(joints)


def test_explain_takes_a_numpy_count(built):
    found = recognise(built / "px", built / "new.bvh")
    assert found.explain(np.int64(2)) == found.explain(2)


# -- a long recording --------------------------------------------------------------------------
def test_parse_reports_its_progress_window_by_window(built):
    said: list[tuple[int, int]] = []
    timeline = parse(built / "px", built / "long.bvh",
                     progress=lambda done, total: said.append((done, total)))
    total = said[-1][1]
    assert said == [(k, total) for k in range(1, total + 1)] and total > 200
    assert timeline == parse(built / "px", built / "long.bvh")


def test_the_command_shows_parse_progress_on_a_terminal_only(built, capsys, monkeypatch):
    import sys

    argv = ["parse", str(built / "px"), str(built / "long.bvh")]
    status, quiet, err = run_praxicon(capsys, argv)
    assert status == 0 and err == ""  # not a terminal: no progress line
    monkeypatch.setattr(sys.stderr, "isatty", lambda: True, raising=False)
    status, out, err = run_praxicon(capsys, argv)
    assert status == 0 and out == quiet
    assert "\rparsing: window " in err and err.endswith("\r")  # wiped: one line, rewritten
    status, out, err = run_praxicon(capsys, [*argv, "--no-progress"])
    assert status == 0 and out == quiet and err == ""


def test_parse_holds_no_dict_of_features_per_window():
    """The windows' features are kept as one row of numbers each: a dict per window held
    about ten times as much (an hour of recording, 14,400 windows of 500 features, held most
    of a gigabyte)."""
    import tracemalloc

    from kinetology import synthetic_motion

    from praxicon.parsing import describe_windows, windows
    from praxicon.recognition import feature_matrix

    descriptions = describe_windows({
        "a": [synthetic_motion(40, (0, 1), seed=s, repetitions=3, frame_rate=30.0)
              for s in (1, 2)],
        "b": [synthetic_motion(40, (2, 3), seed=s, repetitions=3, frame_rate=30.0)
              for s in (3, 4)]})
    recording = synthetic_motion(40, (0, 1), seed=5, repetitions=40, frame_rate=30.0)
    _, cuts = windows(recording, descriptions.spread.window, 0.25)
    tracemalloc.start()
    try:
        _, x, _ = feature_matrix(descriptions, cuts, shape=False)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert x.shape[1] > 100
    assert peak < 3 * x.nbytes + 2**20, (peak, x.nbytes)


# -- the timeline's picture --------------------------------------------------------------------
def test_the_timeline_is_drawn_over_its_own_motion_only(built, tmp_path):
    pytest.importorskip("matplotlib")
    from kinetology import read

    from praxicon.recognition_pictures import draw_timeline

    timeline = parse(built / "px", built / "new.bvh")
    with pytest.raises(ValidationError, match="lasts 60.00 s; the timeline 5.00 s"):
        draw_timeline(timeline, read(built / "long.bvh"), tmp_path / "t.png")
    with pytest.raises(ValidationError, match="a motion must be a kinetology.Motion"):
        draw_timeline(timeline, None, tmp_path / "t.png")
    assert draw_timeline(timeline, read(built / "new.bvh"), tmp_path / "t.png").is_file()


def test_large_distance_terms_are_labelled_apart(tmp_path, monkeypatch):
    """Terms of 10^5 (a joint held still that an action moves) were labelled 50000100000...,
    the labels of the x axis running into one another."""
    pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt

    from praxicon.recognition import JointReason, Recognition
    from praxicon.recognition_pictures import draw_explanation

    close, kept = plt.close, []
    monkeypatch.setattr(plt, "close", kept.append)
    reasons = tuple(JointReason(f"joint{k}", 416059.9 / (k + 1), "still but should move")
                    for k in range(12))
    found = Recognition("still.bvh", None, (("m.a", 0.54), ("m.b", 0.46)), 1656.9, 80.7,
                        reasons=(("m.a", reasons), ("m.b", reasons)))
    draw_explanation(found, tmp_path / "why.png")
    (fig,) = kept
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    for ax in fig.axes:
        boxes = [t.get_window_extent(renderer) for t in ax.get_xticklabels() if t.get_text()]
        assert len(boxes) >= 2
        assert all(a.x1 < b.x0 for a, b in zip(boxes, boxes[1:])), [
            t.get_text() for t in ax.get_xticklabels()]
    close(fig)
