"""The praxicon's readers and checks take time in proportion to what they read.

Each test gives the worst input found for a check that once compared every name with every
other (``list.count`` per name, ``in`` a list per joint, a search of every channel per joint
of a root chain), at a size where that check took well over the suite's 15 s a test, and
checks what is answered, not how long it takes: the checks of today look each name up once
and answer in milliseconds. The answers are the ones the old checks gave (property tests
against the old code): the same first name in the same message, the same chain's motion.
"""

from __future__ import annotations

import re

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology.motion import Joint, Motion, Skeleton
from praxicon import datasets
from praxicon._description_json import FieldError, _texts
from praxicon.builder import build
from praxicon.datasets import Action, DatasetError, read_dataset, read_datasets
from praxicon.description import (
    FORMAT_VERSION,
    ActionDescription,
    DescriptionError,
    Descriptions,
    Spread,
)
from praxicon.features import _chain_pose, root_motion
from praxicon.records import ActionRecord
from praxicon.store import actuator_matrix

#: names enough that comparing each with all the others takes 2.5e9 comparisons (some 30 s)
MANY = 50_000


def _spread(features=("f",)) -> Spread:
    return Spread(tuple(features), (1.0,) * len(features), (), (1.0,) * len(features), 1.0, 1.0)


def _action(name: str) -> dict:
    return {"format": "praxicon-action-description", "version": FORMAT_VERSION, "name": name,
            "features": ["f"], "mean": [0.0], "spread": [1.0], "takes": 2, "window": 0.0}


def test_an_action_described_twice_among_many_is_named():
    names = [f"a{i}" for i in range(MANY)]
    data = {"format": "praxicon-descriptions", "version": FORMAT_VERSION,
            "actions": [_action(n) for n in names + [names[-1]]],
            "spread": _spread().to_dict()}
    with pytest.raises(DescriptionError, match=f"action '{names[-1]}' is described twice"):
        Descriptions.from_dict(data)


def test_a_family_of_one_member_among_many_is_named():
    def described(name: str) -> ActionDescription:
        return ActionDescription(name, ("f",), (0.0,), (1.0,), 2)

    actions = tuple(described(f"a{i}") for i in range(MANY + 1))
    family_of = tuple(f"F{i // 2}" for i in range(MANY)) + ("alone",)  # the last alone
    families = Descriptions(tuple(map(described, dict.fromkeys(family_of))), _spread())
    with pytest.raises(DescriptionError, match=f"action 'a{MANY}': family 'alone' has one"):
        Descriptions(actions, _spread(), families, family_of)


def test_a_feature_named_twice_among_many_is_named():
    features = [f"f{i}" for i in range(MANY)]
    data = _spread(features).to_dict()
    data.update(features=features + [features[-1]], scale=data["scale"] + [1.0],
                noise=data["noise"] + [1.0])
    with pytest.raises(DescriptionError, match=f"'features' names 'f{MANY - 1}' twice"):
        Spread.from_dict(data)


def test_a_manifest_column_named_twice_among_many_is_named(tmp_path):
    columns = ["action", "file"] + [f"c{i}" for i in range(MANY)]
    path = tmp_path / "wide.csv"
    path.write_text(",".join(columns + [columns[-1]]) + "\nwave,a.bvh\n", encoding="utf-8")
    with pytest.raises(DatasetError, match=f"names column 'c{MANY - 1}' twice"):
        read_dataset(path)


def _actions(count: int) -> list[Action]:
    return [Action(f"m.a{i}", "m", f"a{i}") for i in range(count)]


def test_an_action_named_by_two_datasets_among_many_is_named(monkeypatch):
    # read_dataset's own work is a manifest row's per action: the datasets' actions are given
    # as read, so that the test times the check across datasets alone
    read = {"one.csv": _actions(MANY), "two.csv": [Action("m.a7", "n", "a7")]}
    monkeypatch.setattr(datasets, "read_dataset", lambda path, group_by=None: read[path])
    with pytest.raises(DatasetError, match="action names given by two datasets: m.a7$"):
        read_datasets(["one.csv", "two.csv"])
    del read["two.csv"]
    assert len(read_datasets(["one.csv"])) == MANY


def test_a_build_of_many_actions_names_the_one_given_twice(tmp_path):
    actions = _actions(MANY)
    with pytest.raises(DatasetError, match=f"two actions are named 'm.a{MANY - 1}'"):
        build(actions + [actions[-1]], tmp_path / "px", progress=False)
    assert not (tmp_path / "px").exists()  # refused before anything is written


def test_the_actuator_matrix_of_many_joints():
    joints = tuple(f"j{i}" for i in range(50_000))
    listed = ActionRecord("a", "d", "a", status="ok", actuators=joints[1::2],
                          all_joints=joints + joints[:10])
    # a record without all_joints: its joints are its mean pose's, in order
    posed = ActionRecord("b", "d", "b", status="ok", actuators=("k1",),
                         mean_pose=tuple((f"{j}.{axis}", 0.0) for j in ("k0", "j3", "k1")
                                         for axis in ("rx", "ry")))
    names, columns, rows = actuator_matrix([listed, posed])
    assert names == ["a", "b"] and columns == [*joints, "k0", "k1"]
    assert rows[0] == [i % 2 for i in range(len(joints))] + [0, 0]
    assert rows[1] == [0] * len(joints) + [0, 1]


# -- the answers are the old checks' ------------------------------------------------------------
NAMES = st.lists(st.sampled_from(["a", "b", "c", "hip", "hip.x", ""]), min_size=1, max_size=8)


@settings(max_examples=200, deadline=None)
@given(NAMES)
def test_the_name_given_twice_is_the_one_the_old_check_named(value):
    """The first name (in order) that is given more than once, as ``value.count`` found it."""
    twice = next((v for v in value if value.count(v) > 1), None)
    try:
        got = _texts({"features": value}, "features", "spread: ")
    except FieldError as exc:
        assert twice is not None and str(exc) == f"spread: 'features' names {twice!r} twice"
    else:
        assert twice is None and got == tuple(value)


def _old_actuator_matrix(records):
    """actuator_matrix as it searched lists: the oracle of the order of joints and rows."""
    learnt = [r for r in records if r.learnt]
    joints: list[str] = []
    for r in learnt:
        if r.all_joints:
            found = list(r.all_joints)
        else:
            found = []
            for channel, _ in r.mean_pose:
                if channel.rsplit(".", 1)[0] not in found:
                    found.append(channel.rsplit(".", 1)[0])
        for joint in found:
            if joint not in joints:
                joints.append(joint)
    return [r.name for r in learnt], joints, [[int(j in r.actuators) for j in joints]
                                              for r in learnt]


JOINTS = st.lists(st.sampled_from(["hip", "knee", "a.b", "x"]), max_size=5)


@st.composite
def records(draw):
    out = []
    for k in range(draw(st.integers(0, 4))):
        channels = [f"{j}.{axis}" for j in draw(JOINTS) for axis in ("rx", "ty")]
        out.append(ActionRecord(f"r{k}", "d", "r", status=draw(st.sampled_from(["ok", "failed"])),
                                actuators=tuple(draw(JOINTS)), all_joints=tuple(draw(JOINTS)),
                                mean_pose=tuple((c, 0.0) for c in channels)))
    return out


@settings(max_examples=100, deadline=None)
@given(records())
def test_the_actuator_matrix_is_the_old_one(given_records):
    assert actuator_matrix(given_records) == _old_actuator_matrix(given_records)


# -- the root chain's motion --------------------------------------------------------------------
def _old_chain_pose(motion, chain):
    """features._chain_pose as it searched the channels and the skeleton per joint: the
    oracle of the rotation orders and columns it reads."""
    from kinetology.kinematics import rotation_matrices
    from kinetology.segmentation import smooth, unwrap

    rate, frames = motion.frame_rate, motion.frames
    rot = np.broadcast_to(np.eye(3), (frames, 3, 3)).copy()
    pos = np.zeros((frames, 3))
    for joint in chain:
        order = "".join(c.rsplit(".", 1)[1][1].upper() for c in motion.channels
                        if c.startswith(joint + ".") and c.rsplit(".", 1)[1] in ("rx", "ry", "rz"))
        if motion.skeleton is not None and joint in motion.skeleton.names:
            order = motion.skeleton.joints[motion.skeleton.index(joint)].rotation_order
        angles = {a.upper(): smooth(unwrap(motion.column(f"{joint}.r{a}").astype(float)), rate,
                                    0.05)
                  for a in "xyz" if f"{joint}.r{a}" in motion.channels}
        r = rotation_matrices(angles, order or "XYZ", frames)
        t = np.stack([smooth(motion.column(f"{joint}.t{a}").astype(float), rate, 0.05)
                      if f"{joint}.t{a}" in motion.channels else np.zeros(frames)
                      for a in "xyz"], axis=1)
        pos = pos + np.einsum("tij,tj->ti", rot, t)
        rot = rot @ r
    return rot, pos


#: joint names whose channels' names start with another's and a '.' ('a.b.rx' with 'a')
JOINT_NAMES = ["a", "a.b", "a.b.c", "ab", "b"]


@st.composite
def chained_motions(draw):
    channels = draw(st.lists(st.sampled_from([f"{j}.{axis}" for j in JOINT_NAMES for axis in
                                              ("rx", "ry", "rz", "tx", "ty", "tz")]),
                             min_size=1, max_size=10, unique=True))
    frames = draw(st.integers(3, 5))
    values = np.array(draw(st.lists(st.floats(-90, 90), min_size=frames * len(channels),
                                    max_size=frames * len(channels)))).reshape(frames, -1)
    skeleton = None
    if draw(st.booleans()):  # some joints, a name maybe twice: its first joint's order counts
        named = draw(st.lists(st.sampled_from(JOINT_NAMES), max_size=4))
        skeleton = Skeleton(tuple(Joint(j, None, (0.0, 0.0, 0.0), (), draw(st.sampled_from(
            ["XYZ", "ZYX", "YXZ", ""]))) for j in named))
    chain = draw(st.lists(st.sampled_from(JOINT_NAMES), max_size=4))
    return Motion(values, tuple(channels), 30.0, skeleton), chain


@settings(max_examples=100, deadline=None)
@given(chained_motions())
def test_the_root_chain_s_motion_is_the_old_one(drawn):
    motion, chain = drawn
    try:
        expected = _old_chain_pose(motion, chain)
    except Exception as exc:  # noqa: BLE001 - an order rotation_matrices refuses: refused alike
        with pytest.raises(type(exc), match=re.escape(str(exc))):
            _chain_pose(motion, chain)
    else:
        got = _chain_pose(motion, chain)
        assert all(np.array_equal(a, b) for a, b in zip(got, expected))


def test_a_chain_among_many_channels_moves_as_alone():
    # a chain of 1,500 joints among 150,000 channels: each joint's search of every channel
    # made 2.3e8 comparisons (some 30 s); the channels of other joints change nothing
    chain = [f"c{i}" for i in range(1_500)]
    own = [f"{joint}.{axis}" for joint in chain for axis in ("tx", "rx")]
    values = np.random.default_rng(0).normal(size=(3, len(own) + 147_000))
    crowded = Motion(values, tuple(own + [f"r{i}.rx" for i in range(147_000)]), 30.0)
    alone = Motion(values[:, :len(own)], tuple(own), 30.0)
    assert np.array_equal(root_motion(crowded, chain), root_motion(alone, chain))
