"""Names in a praxicon's files that name nothing there are refused, naming the file, the
action and the name, where they were used with a default without a word.

A record's ``mean_pose`` key renamed left that channel posed at 0 in a generated motion; a
``component_names`` key or value renamed was "the system derives '' for Hand_R.ry"; a feature
renamed alike in a spread and its actions was never compared by recognition. And descriptions
made in Python are checked as a file's are: the same damage, the same line.
"""

from __future__ import annotations

import json
import math
import shutil
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from kinetology import read_bvh, synthetic_motion
from praxicon import dump, load
from praxicon._description_json import FieldError, check_feature_names, feature_problem
from praxicon.description import (ActionDescription, DescriptionError, Descriptions, Spread,
                                  describe)
from praxicon.features import motion_features
from praxicon.generation import RecordFieldError, generate, generate_motion
from praxicon.parsing import describe_windows
from praxicon.records import PraxiconError
from praxicon_fixtures import build_wave_and_step, leg_body, refused, run_praxicon, take


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    """A praxicon of two actions (moves.step, moves.wave) learnt from BVH takes."""
    return build_wave_and_step(tmp_path_factory.mktemp("misnamed"))


def _damaged(built, tmp_path, change):
    """A copy of the folder with ``change(record)`` made to moves.wave's record JSON."""
    folder = tmp_path / "px"
    shutil.copytree(built, folder)
    path = folder / "records" / "moves.wave.json"
    stored = json.loads(path.read_text())
    change(stored["record"])
    path.write_text(json.dumps(stored, indent=2, sort_keys=True) + "\n")
    return folder


def _renamed(mapping: dict, old: str, new: str) -> None:
    mapping[new] = mapping.pop(old)


# -- a record's mean pose and component names -------------------------------------------------

JOINTS_SAID = "which is no channel of its joints (JOINT.AXIS: a joint of all_joints, an axis " \
    "of tx ty tz rx ry rz)"
#: how load's line ends: what mends the record
DAMAGED = ": the record is damaged ('psgs praxicon build DATASET... -o FOLDER' into the folder " \
    "learns the action again)"


def _refused_everywhere(folder: Path, tmp_path, capsys) -> str:
    """The line load, generate and verify each refuse ``folder`` with (the same one)."""
    with pytest.raises(PraxiconError) as caught:
        load(folder)
    said = str(caught.value)
    assert refused(capsys, ["generate", str(folder), "moves.wave", "-o",
                            str(tmp_path / "out.bvh")]) == said
    assert not (tmp_path / "out.bvh").exists()
    assert refused(capsys, ["verify", str(folder)]) == said
    return said


def test_a_renamed_mean_pose_key_is_refused_by_load_generate_and_verify(built, tmp_path, capsys):
    # hips.rz drives no morpheme: only the mean pose gives it its angle (0 when not found)
    folder = _damaged(built, tmp_path, lambda r: _renamed(r["mean_pose"], "hips.rz", "hipz.rz"))
    assert _refused_everywhere(folder, tmp_path, capsys) == \
        f"{folder / 'records' / 'moves.wave.json'}: 'mean_pose' names 'hipz.rz', {JOINTS_SAID}" \
        f"{DAMAGED}"


def test_a_mean_pose_without_a_channel_of_the_skeleton_is_refused(built):
    record = load(built, descriptions=False)["moves.wave"]
    cut = replace(record, mean_pose=tuple(p for p in record.mean_pose if p[0] != "head.ry"))
    with pytest.raises(ValueError, match=r"^action 'moves.wave': 'mean_pose' has no value for "
                                         r"'head.ry', a channel of its skeleton \("):
        generate_motion(cut, 1, source_motion=take(1))


def test_a_renamed_component_names_key_is_refused_by_load_generate_and_verify(
        built, tmp_path, capsys):
    channel = dict(load(built, descriptions=False)["moves.wave"].component_names)
    first = min(channel)
    folder = _damaged(built, tmp_path,
                      lambda r: _renamed(r["component_names"], first, first[:-1] + "q"))
    assert _refused_everywhere(folder, tmp_path, capsys) == \
        f"{folder / 'records' / 'moves.wave.json'}: 'component_names' names " \
        f"{first[:-1] + 'q'!r}, {JOINTS_SAID}{DAMAGED}"


def test_a_dropped_component_names_key_of_a_morpheme_is_refused_when_loaded(built, tmp_path,
                                                                           capsys):
    first = min(dict(load(built, descriptions=False)["moves.wave"].component_names))
    folder = _damaged(built, tmp_path, lambda r: r["component_names"].pop(first))
    assert _refused_everywhere(folder, tmp_path, capsys) == \
        f"{folder / 'records' / 'moves.wave.json'}: 'component_names' has no value for " \
        f"{first!r}, a channel of its morphemes{DAMAGED}"


def test_dump_writes_no_record_load_would_refuse(built, tmp_path):
    good = load(built, descriptions=False)
    record = good["moves.wave"]
    pose = tuple(("hipz.rz" if c == "hips.rz" else c, v) for c, v in record.mean_pose)
    damaged = replace(good, actions=tuple(replace(a, mean_pose=pose) if a is record else a
                                          for a in good.actions))
    with pytest.raises(PraxiconError, match=r"^action 'moves.wave': 'mean_pose' names "
                                            r"'hipz.rz', which is no channel of its joints"):
        dump(damaged, tmp_path / "px")
    assert not (tmp_path / "px").exists()


def test_a_component_name_no_component_of_the_system_has_is_named(built):
    record = load(built, descriptions=False)["moves.wave"]
    (channel, name), *rest = record.component_names
    wrong = replace(record, component_names=((channel, name + "_x"), *rest))
    with pytest.raises(ValueError) as caught:
        generate_motion(wrong, 1, source_motion=take(1))
    said = str(caught.value)
    assert said.startswith(f"action 'moves.wave': 'component_names' gives {channel!r} the "
                           f"component {name + '_x'!r}, which is no component of its system "
                           f"(its components: ")
    assert name in said and "derives" not in said


def test_verify_names_a_component_name_no_component_of_the_system_has(built, tmp_path, capsys):
    channel, name = load(built, descriptions=False)["moves.wave"].component_names[0]
    folder = _damaged(built, tmp_path,
                      lambda r: r["component_names"].__setitem__(channel, name + "_x"))
    status, out, _ = run_praxicon(capsys, ["verify", str(folder)])
    assert status == 1
    assert (f"{folder / 'records' / 'moves.wave.json'}: 'component_names' gives {channel!r} "
            f"the component {name + '_x'!r}, which is no component of its system") in out


@pytest.fixture(scope="module")
def scratch(built, tmp_path_factory):
    """A copy of the folder, its moves.wave record rewritten by each example."""
    folder = tmp_path_factory.mktemp("mutated") / "px"
    shutil.copytree(built, folder)
    return folder


# names a key is renamed to or added as: channels of the skeleton, channels of its joints the
# skeleton lacks, and names of no channel of its joints
NAMES = ["hips.rz", "arm.rx", "arm.rz", "leg.rx", "head.ry", "head.rx", "arm.tx", "leg.rz",
         "hipz.rz", "arm.rq", "arm", "", "arm.rx.rx", "Arm.rx"]


@st.composite
def mutations(draw):
    """One to three renames, drops or additions of keys of mean_pose or component_names."""
    steps = []
    for _ in range(draw(st.integers(1, 3))):
        key = draw(st.sampled_from(["mean_pose", "component_names"]))
        steps.append((key, draw(st.sampled_from(["rename", "drop", "add"])),
                      draw(st.integers(0, 9)), draw(st.sampled_from(NAMES))))
    return steps


def _mutate(record: dict, steps) -> None:
    for key, how, which, name in steps:
        pairs = record[key]
        old = sorted(pairs)[which % len(pairs)] if pairs else None
        value = 0.5 if key == "mean_pose" else name.replace(".", "_")
        if how == "rename" and old is not None:
            _renamed(pairs, old, name)
        elif how == "drop" and old is not None:
            del pairs[old]
        elif how == "add":
            pairs.setdefault(name, value)


@settings(max_examples=60, deadline=None)
@given(steps=mutations())
def test_load_refuses_what_generate_refuses_of_mutated_keys(built, scratch, steps):
    good = load(built, descriptions=False)
    record = good["moves.wave"]
    path = scratch / "records" / "moves.wave.json"
    stored = json.loads((built / "records" / "moves.wave.json").read_text())
    _mutate(stored["record"], steps)
    path.write_text(json.dumps(stored, indent=2, sort_keys=True) + "\n")
    try:
        load(scratch)
        by_load = None
    except PraxiconError as exc:
        assert str(exc).startswith(f"{path}: ") and str(exc).endswith(DAMAGED)
        by_load = str(exc)[len(f"{path}: "):-len(DAMAGED)]
    # generation of the same record in memory, where load is not asked
    pose, names = stored["record"]["mean_pose"], stored["record"]["component_names"]
    mutated = replace(record, mean_pose=tuple(sorted(pose.items())),
                      component_names=tuple(sorted(names.items())))
    alone = replace(good, actions=tuple(mutated if a.name == record.name else a
                                        for a in good.actions))
    try:
        generate(alone, "moves.wave", repeat=1)
        by_generate = None
    except RecordFieldError as exc:
        assert str(exc).startswith("action 'moves.wave': ")
        by_generate = str(exc)[len("action 'moves.wave': "):]
    if by_load is not None:  # what load refuses, generate refuses with the same words
        assert by_generate == by_load
    else:  # and refuses besides only what the skeleton's file shows, which load never reads
        skeleton = read_bvh(record.skeleton_source).channels
        assert (by_generate is not None) == (set(pose) != set(skeleton)), (by_generate, pose)
        assert by_generate is None or "a channel of its skeleton (" in by_generate \
            or "which is no channel of its skeleton (" in by_generate


# -- descriptions made in Python are checked as a file's are ----------------------------------

def _action(**changes) -> ActionDescription:
    fields = dict(name="a", features=("j.rx:pose", "tempo"), mean=(1.0, 0.5),
                  spread=(0.5, 0.25), takes=2, window=0.0)
    return ActionDescription(**{**fields, **changes})


def _spread(**changes) -> Spread:
    fields = dict(features=("j.rx:pose", "tempo"), scale=(1.0, 2.0), factors=((0.5, 0.25),),
                  noise=(1.0, 1.0), threshold=2.0, temperature=1.0, limits=(("j", 3.0),))
    return Spread(**{**fields, **changes})


ACTIONS = [({"mean": (math.nan, 0.5)}, "'mean' must be finite numbers: value 1 is nan"),
           # both infinities: their sum is no number at all (math.fsum refuses it)
           ({"mean": (math.inf, -math.inf)}, "'mean' must be finite numbers: value 1 is inf"),
           ({"spread": (0.5,)}, "'spread' has 1 values for 2 features"),
           ({"spread": (0.5, -1.0)}, "'spread' must be numbers from 0: value 2 is -1.0"),
           ({"takes": 0}, "'takes' must be a whole number from 1, not 0"),
           ({"window": 1e300}, "'window' must be 0 (whole takes) or 0.1 to 60 seconds"),
           ({"features": ("tempo", "tempo"), "mean": (1.0, 1.0)}, "names 'tempo' twice"),
           ({"name": ""}, "action: 'name' must be text, not ''")]
SPREADS = [({"noise": (1.0, 0.0)}, "spread: 'noise' must be numbers above 0: value 2 is 0.0"),
           ({"scale": (1.0, math.inf)}, "spread: 'scale' must be finite numbers: value 2"),
           ({"factors": ((0.5,),)}, "spread: row 1 of 'factors' has 1 values for 2 features"),
           ({"threshold": math.nan}, "spread: 'threshold' must be a finite number, not nan"),
           ({"temperature": 0.0}, "spread: 'temperature' must be above 0, not 0.0"),
           ({"tail": -1.0}, "spread: 'tail' must be above 0, not -1.0"),
           ({"limits": (("bogus", 3.0),)}, ("'limits' must be of the spread's feature groups: "
                                             "value 1 is 'bogus'")),
           ({"limits": (("j", 0.0),)}, "'limits' must be numbers above 0: value 1 is 0.0")]


@pytest.mark.parametrize("changes, said", ACTIONS)
def test_an_action_description_made_in_python_is_checked_as_read(changes, said):
    with pytest.raises(DescriptionError) as made:
        _action(**changes)
    assert said in str(made.value)
    # the same damage in a file: the same line (one check, whichever way it was made)
    data = _action().to_dict()
    data.update(changes)
    with pytest.raises(DescriptionError) as read:
        ActionDescription.from_dict(json.loads(json.dumps(
            {k: list(v) if isinstance(v, tuple) else v for k, v in data.items()})))
    assert str(read.value) == str(made.value)


@pytest.mark.parametrize("changes, said", SPREADS)
def test_a_spread_made_in_python_is_checked_as_read(changes, said):
    with pytest.raises(DescriptionError) as made:
        _spread(**changes)
    assert said in str(made.value)
    data = _spread().to_dict()
    data.update({k: [list(p) for p in v] if k in ("limits", "factors") else
                 list(v) if isinstance(v, tuple) else v for k, v in changes.items()})
    with pytest.raises(DescriptionError) as read:
        Spread.from_dict(json.loads(json.dumps(data)))
    assert str(read.value) == str(made.value)


def test_descriptions_made_in_python_are_checked_as_read():
    with pytest.raises(DescriptionError, match="action 'a' is described twice"):
        Descriptions((_action(), _action()), _spread())
    with pytest.raises(DescriptionError, match="action 'a': 'window' 2 is not the spread's 0"):
        Descriptions((_action(window=2.0),), _spread())
    with pytest.raises(DescriptionError, match="'actions' must be a tuple of action "
                                               "descriptions, one or more"):
        Descriptions((), _spread())


def test_a_good_description_is_made_and_read_back_alike():
    d = Descriptions((_action(), _action(name="b")), _spread())
    assert Descriptions.from_json(d.to_json()) == d


# -- features a motion can have -----------------------------------------------------------------

def _walk(seed: int):
    frames = 90
    t = np.arange(frames) / 30.0
    return leg_body(np.zeros(frames), np.full(frames, 9.0) + 0.1 * np.sin(6 * t + seed),
                    10.0 * t, 20 * np.sin(2 * np.pi * t + seed), 1.0, "0.0333333")


@pytest.mark.parametrize("shape", [True, False])
def test_every_feature_a_motion_has_is_one_a_motion_can_have(shape):
    # the oracle: the names motion_features gives, with and without a moving root
    names = set()
    for motion in (synthetic_motion(3, (0,), seed=1), take(1), _walk(1)):
        names.update(motion_features(motion, shape=shape)[0])
    assert {"flight", "pace", "tempo", "Hips.turny:drift", "thigh.rx:energy"} <= names
    assert [n for n in names if feature_problem(n, window=not shape)] == []
    if shape:  # a whole take's course, which no window has
        course = [n for n in names if feature_problem(n, window=True)]
        assert course and all(n.endswith((":excursion", ":shape0", ":shape1", ":shape2",
                                          ":shape3")) for n in course)


@pytest.mark.parametrize("renamed", ["arm.rx:range", "arm.rq:pose", "Hips.travelq:drift",
                                     "Hips.travelx:excursion", "rx:pose", ".rx:pose",
                                     "arm.rx", "tempo2", "", "arm.rx:pose:pose"])
def test_a_feature_renamed_alike_in_the_spread_and_every_action_is_named(renamed):
    takes = {"wave": [take(s) for s in (1, 2, 3)], "still": [take(s) for s in (4, 5, 6)]}
    learnt = describe(takes, choose=False)
    old = next(f for f in learnt.spread.features if f.startswith("arm.rx:"))
    data = json.loads(json.dumps(learnt.to_dict()).replace(json.dumps(old), json.dumps(renamed)))
    damaged = Descriptions.from_dict(data)  # each part alone reads: no check sees the names
    with pytest.raises(FieldError) as caught:
        check_feature_names(damaged, "takes")
    assert str(caught.value).startswith(f"takes: action 'still': 'features' names "
                                        f"{renamed!r}: no motion has it (a feature is ")
    check_feature_names(learnt, "takes")  # as learnt: every name one a motion has


def test_a_window_description_of_a_whole_takes_feature_is_named():
    takes = {"wave": [take(s) for s in (1, 2, 3)], "still": [take(s) for s in (4, 5, 6)]}
    windows = describe_windows(takes)
    old = windows.spread.features[0]
    course = old.rsplit(":", 1)[0] + ":shape0"
    data = json.loads(json.dumps(windows.to_dict()).replace(json.dumps(old), json.dumps(course)))
    with pytest.raises(FieldError, match=r"^windows: action 'still': 'features' names '.*:shape0'"
                                         r": no window of a recording has it"):
        check_feature_names(Descriptions.from_dict(data), "windows")


KINDS = ["pose", "posec", "spread", "energy", "shape0", "shape3", "shape4", "drift",
         "excursion", "range", "", "Pose"]


@settings(max_examples=40, deadline=None)
@given(joints=st.lists(st.text("ab:._1", min_size=1, max_size=4), min_size=1, max_size=3,
                       unique=True),
       axes=st.lists(st.sets(st.sampled_from(["rx", "ry", "rz"]), min_size=1), min_size=3,
                     max_size=3),
       moves=st.booleans(), shape=st.booleans(), kind=st.sampled_from(KINDS))
def test_the_features_accepted_are_those_motion_features_names(joints, axes, moves, shape,
                                                               kind):
    # the oracle: for each channel of a drawn motion the kinds motion_features gives it are
    # exactly the kinds feature_problem accepts for that channel
    from kinetology import Motion

    channels = [f"{j}.{a}" for j, per in zip(joints, axes) for a in sorted(per)]
    if moves:  # the first joint travels: the root's features
        channels = [f"{joints[0]}.t{a}" for a in "xyz"] + channels
    assume(len(set(channels)) == len(channels))
    t = np.arange(60) / 30.0
    values = np.column_stack([np.sin((k + 1) * t) * 10 + (k < 3 and moves) * 5 * t
                              for k in range(len(channels))])
    try:
        motion = Motion(values, tuple(channels), 30.0, None, "drawn")
    except ValueError:
        assume(False)
    names = motion_features(motion, shape=shape)[0]
    assert [n for n in names if feature_problem(n, window=not shape)] == []
    given_kinds: dict[str, set] = {}
    for n in names:
        if ":" in n:
            channel, _, k = n.rpartition(":")
            given_kinds.setdefault(channel, set()).add(k)
    for channel, kinds in given_kinds.items():
        accepted = feature_problem(f"{channel}:{kind}", window=not shape) is None
        assert accepted == (kind in kinds), (channel, kind, kinds)


def test_a_folder_whose_features_were_renamed_alike_is_refused_by_every_reader(built, tmp_path,
                                                                             capsys):
    folder = tmp_path / "px"
    shutil.copytree(built, folder)
    path = folder / "descriptions.json"
    old = next(f for f in load(built).descriptions.spread.features if f.startswith("arm.rx:"))
    path.write_text(path.read_text().replace(json.dumps(old), json.dumps("arm.rx:bogus")))
    said = (f"{path}: takes: action 'moves.step': 'features' names 'arm.rx:bogus': no motion "
            f"has it (a feature is ")
    for command in (["recognise", str(folder), str(tmp_path / "none.bvh")],
                    ["parse", str(folder), str(tmp_path / "none.bvh")]):
        assert refused(capsys, command).startswith(said)
    status, out, _ = run_praxicon(capsys, ["verify", str(folder)])
    assert status == 1 and said in out
