"""Motion files recognise and parse cannot answer for, and descriptions they cannot score with.

A value too large to compute with (finite: the file reads) made every answer NaN, with NumPy's
overflow warnings and exit status 0; now it is one line naming the file and the feature, exit
status 2, and a DescriptionError from the API. Descriptions holding a number the scores cannot
compute with are one error naming it and the command that learns them again. ``recognise``
given several files answers every good one, recognised together, says one line per bad one,
and exits 2 at the end.
"""

from __future__ import annotations

import dataclasses
import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from praxicon import load, parse, recognise, recognise_many
from praxicon.description import DescriptionError
from praxicon_fixtures import build_walk_and_stay, leg_body
from praxicon_fixtures import refused as _refused, run_praxicon as _run

# an overflow was a RuntimeWarning on stderr before the NaN answer: none may be left
pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

_RATE = 30.0


def _leg(seed: int, pace: float, seconds: float = 5.0):
    """A hip and a swinging leg that travels ``pace`` units a second along x."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * _RATE)) / _RATE
    swing = 30 * np.sin(2 * np.pi * t / (1 + 0.05 * (seed % 3))) + rng.normal(0, 1, t.size)
    hip = 9 + 0.2 * np.sin(4 * np.pi * t) + rng.normal(0, 0.02, t.size)
    return leg_body(pace * t + rng.normal(0, 0.01, t.size), hip,
                    rng.normal(0, 0.01, t.size), swing, 1.0, f"{1 / _RATE:.9f}")


def _with(motion, column: int, values):
    from kinetology import Motion

    out = motion.values.copy()
    out[:, column] = values
    return Motion(out, motion.channels, motion.frame_rate, motion.skeleton)


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    """A praxicon of a walk and a stand (m.walk, m.stay) and motion files beside it: two new
    walks, one whose hips rise to 1e300 for a frame, one that travels 3e154 units a second
    (every feature finite, its distances not), an empty file and a body of other joints."""
    from kinetology import Motion, write_bvh
    from kinetology.bvh_writer import star_skeleton

    root = tmp_path_factory.mktemp("unanswerable")
    build_walk_and_stay(root, _leg)
    write_bvh(_leg(7, 10.0), root / "new.bvh")
    write_bvh(_leg(8, 10.0), root / "new2.bvh")
    walk = _leg(9, 10.0)
    high = walk.channels.index("Hips.ty")
    write_bvh(_with(walk, high, np.where(np.arange(walk.frames) == 60, 1e300,
                                         walk.values[:, high])), root / "huge.bvh")
    ahead = walk.channels.index("Hips.tx")
    write_bvh(_with(walk, ahead, 3e154 * np.arange(walk.frames) / _RATE), root / "fast.bvh")
    (root / "empty.bvh").write_text("")
    channels = ("neck.rx", "neck.ry")
    write_bvh(Motion(np.random.default_rng(3).normal(0, 5, (150, 2)), channels, _RATE,
                     star_skeleton(channels)), root / "other.bvh")
    return root


# -- a value too large to compute with ---------------------------------------------------------
def test_a_huge_value_is_one_line_naming_the_file_and_the_feature(built, capsys):
    huge = built / "huge.bvh"
    said = _refused(capsys, ["recognise", str(built / "px"), str(huge)])
    assert said == (f"{huge}: feature Hips.travely:drift is too large to square (1.15394e+282): "
                    f"a value of the motion is too large to compute with (its largest: 1e+300, "
                    f"Hips.ty at frame 60)")
    said = _refused(capsys, ["parse", str(built / "px"), str(huge)])
    # a window's frames are counted from its start, which the line gives
    assert said.startswith(f"{huge} (the window from ") and "is too large to square" in said
    start = float(said.split("the window from ")[1].split(" s)")[0])
    frame = int(said.rsplit("at frame ", 1)[1].rstrip(")"))
    assert round(start * _RATE) + frame == 60


def test_the_api_raises_the_line_the_command_prints(built):
    huge = built / "huge.bvh"
    for call, begins in ((recognise, f"{huge}: feature Hips.travely:drift is too large"),
                         (lambda px, m: recognise_many(px, [built / "new.bvh", m]),
                          f"{huge}: feature Hips.travely:drift is too large"),
                         (parse, f"{huge} (the window from ")):
        with pytest.raises(DescriptionError, match="is too large to square") as info:
            call(built / "px", huge)
        assert str(info.value).startswith(begins) and "\n" not in str(info.value)


def test_finite_features_too_large_to_square_are_refused(built, capsys):
    """Travelling 3e154 units a second, every feature is finite but its square is not: the
    scores overflowed to NaN, now the feature is named."""
    fast = built / "fast.bvh"
    said = _refused(capsys, ["recognise", str(built / "px"), str(fast)])
    assert said.startswith(f"{fast}: feature Hips.travelx:drift is too large to square "
                           f"(3e+154): a value of the motion is too large to compute with")
    said = _refused(capsys, ["parse", str(built / "px"), str(fast)])
    assert said.startswith(f"{fast} (the window from 0.00 s): feature Hips.travelx:drift")
    with pytest.raises(DescriptionError, match="too large to square"):
        recognise(built / "px", fast)


def test_descriptions_in_memory_too_large_to_score_with_are_one_error(built):
    """A mean of 1e200 squares past the float range: every score was NaN; now recognise and
    parse name the action, the feature and the command that learns the descriptions again."""
    px = load(built / "px")
    for descriptions, call in ((px.descriptions, recognise), (px.window_descriptions, parse)):
        walk = descriptions.actions[descriptions.names.index("m.walk")]
        damaged = dataclasses.replace(descriptions, actions=tuple(
            dataclasses.replace(a, mean=(1e200, *a.mean[1:])) if a is walk else a
            for a in descriptions.actions))
        with pytest.raises(DescriptionError) as info:
            call(damaged, built / "new.bvh")
        assert str(info.value) == (
            f"the praxicon's descriptions overflow the scores: the mean of m.walk's feature "
            f"{walk.features[0]} is 1e+200 (learn the descriptions again: 'psgs praxicon build "
            f"DATASET... -o FOLDER')")


def test_a_family_verdict_that_overflows_is_an_error():
    from kinetology import synthetic_motion
    from praxicon.description import describe, feature_rows
    from praxicon.recognition import family_verdicts

    takes = {name: [synthetic_motion(3, joints, period=period, seed=s) for s in seeds]
             for name, joints, period, seeds in (("a.slow", (0,), 1.3, (1, 2, 3)),
                                                 ("a.fast", (0,), 0.8, (4, 5, 6)),
                                                 ("b", (2,), 1.0, (7, 8, 9)))}
    d = describe(takes, families={"a.slow": "a", "a.fast": "a"})
    (row,) = feature_rows([synthetic_motion(3, (0,), period=1.0, seed=10)])
    feature = next(iter(row))
    row[feature] = 1e200
    with pytest.raises(DescriptionError, match=f"motion 1: its feature {feature} is 1e"):
        family_verdicts(d, [row], ["a.slow"])


# -- descriptions.json holding a number the scores cannot compute with -------------------------
@pytest.mark.parametrize("part, where, key, value, said", [
    ("takes", "actions", "mean", 1e308, "the mean of m.stay's feature thigh.rx:pose is 1e+308"),
    ("windows", "actions", "spread", 1e200,
     "the spread of m.stay's feature thigh.rx:pose is 1e+200"),
    ("takes", "spread", "noise", 1e-300, "the spread's noise of feature thigh.rx:pose is 1e-300"),
    ("windows", "spread", "factors", 1e200,
     "the spread's factors of feature thigh.rx:pose is 1e+200"),
])
def test_descriptions_json_too_large_to_score_with_is_one_error(built, tmp_path, capsys, part,
                                                               where, key, value, said):
    """Every finite number reads back (a description round-trips every float), but one whose
    square (or its inverse's) is past the float range made every probability NaN ("p=nan",
    "inf x its limit"); now it is one line naming the file, the number and the command that
    learns the descriptions again, before any answer, and the DescriptionError of the API."""
    px = Path(shutil.copytree(built / "px", tmp_path / "px"))
    data = json.loads((px / "descriptions.json").read_text())
    place = data[part]["spread"] if where == "spread" else data[part]["actions"][0]
    if key == "factors":
        place[key][0] = [value, *place[key][0][1:]]
    else:
        place[key] = [value, *place[key][1:]]
    (px / "descriptions.json").write_text(json.dumps(data))
    # the file and its part named: a folder's descriptions are what is damaged
    message = (f"{px / 'descriptions.json'}: {part}: the praxicon's descriptions overflow the "
               f"scores: {said} (learn the descriptions again: 'psgs praxicon build DATASET... "
               f"-o FOLDER')")
    command, call = ("recognise", recognise) if part == "takes" else ("parse", parse)
    assert _refused(capsys, [command, str(px), str(built / "new.bvh"),
                             *([str(built / "new2.bvh")] if part == "takes" else [])]) == message
    with pytest.raises(DescriptionError) as info:
        call(px, built / "new.bvh")
    assert str(info.value) == message


# -- several files, some bad --------------------------------------------------------------------
def test_recognise_answers_every_good_file_and_names_every_bad_one(built, capsys, monkeypatch):
    import praxicon.recognition as recognition

    batches = []
    inner = recognition._recognise

    def counted(descriptions, motions, *args):
        batches.append(sorted(Path(m.source).name for m in motions))
        return inner(descriptions, motions, *args)

    good = [str(built / "new.bvh"), str(built / "new2.bvh")]
    bad = {name: str(built / name) for name in ("empty.bvh", "huge.bvh", "missing.bvh",
                                                "other.bvh", "fast.bvh")}
    status, alone, err = _run(capsys, ["recognise", str(built / "px"), *good])
    assert status == 0 and err == "" and len(alone.splitlines()) == 2
    monkeypatch.setattr(recognition, "_recognise", counted)
    files = [bad["empty.bvh"], good[0], bad["huge.bvh"], bad["missing.bvh"], bad["other.bvh"],
             good[1], bad["fast.bvh"]]
    status, out, err = _run(capsys, ["recognise", str(built / "px"), *files])
    assert status == 2
    assert out == alone  # the same answers, as when the good files are given alone
    lines = err.splitlines()  # one per bad file, in the order given
    named = [f for f in files if f not in good]
    assert len(lines) == len(named) and "Traceback" not in err
    assert all(line.startswith(f"psgs: error: {f}") for line, f in zip(lines, named))
    assert "no such file" in lines[2] and "shares no joint" in lines[3]
    # the files whose features were computed recognised together: one call per skeleton
    assert sorted(batches) == [["new.bvh", "new2.bvh"], ["other.bvh"]]


def test_recognise_many_raises_for_the_first_motion_it_cannot_answer(built):
    """The first in the order given, whichever skeleton it has (the motions are recognised
    per skeleton)."""
    with pytest.raises(DescriptionError, match="fast.bvh: feature Hips.travelx:drift is too large"):
        recognise_many(built / "px", [built / "new.bvh", built / "fast.bvh",
                                      built / "other.bvh"])
    with pytest.raises(DescriptionError, match="other.bvh: the motion shares no joint"):
        recognise_many(built / "px", [built / "other.bvh", built / "fast.bvh"])
