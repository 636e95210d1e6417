"""A motion holds nothing a user can change: its values cannot be made writeable through any
view or ``base`` (and a reader's array is still not copied), its ``meta`` is read-only at every
depth, its skeleton's joints are tuples; and all of it survives pickle and copy, as frozen."""

from __future__ import annotations

import copy
import pickle
from collections import namedtuple
from types import MappingProxyType

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.lib.stride_tricks import as_strided

import kinetology
from kinetology._file_motion import build_motion
from kinetology.motion import Joint, Skeleton, _Owned
from kinetology_fixtures import MOCAP, needs_mocap
from psgs.errors import ValidationError

_json = st.recursive(
    st.none() | st.booleans() | st.integers() | st.text(max_size=4)
    | st.floats(allow_nan=False, allow_infinity=False),
    lambda inner: st.lists(inner, max_size=3) | st.dictionaries(st.text(max_size=3), inner,
                                                                max_size=3),
    max_leaves=12)

Cut = namedtuple("Cut", "start stop")  # at the top level, where pickle finds it


def _expected(value):
    """The oracle: the JSON-like value as the motion should hold it, lists as tuples (dicts
    kept as dicts: a read-only mapping compares equal to the dict of its items)."""
    if isinstance(value, dict):
        return {key: _expected(item) for key, item in value.items()}
    if isinstance(value, list):
        return tuple(_expected(item) for item in value)
    return value


def _assert_frozen(value, where="meta"):
    """Nothing inside ``value`` takes a change: no dict, list or set, every mapping refuses
    assignment, every array refuses writes and being made writeable."""
    assert not isinstance(value, (dict, list, set, bytearray)), where
    if isinstance(value, MappingProxyType):
        with pytest.raises(TypeError):
            value["new"] = 1
        for key, item in value.items():
            _assert_frozen(item, f"{where}[{key!r}]")
    elif isinstance(value, tuple):
        for k, item in enumerate(value):
            _assert_frozen(item, f"{where}[{k}]")
    elif isinstance(value, np.ndarray):
        _assert_unwritable(value)
        if value.dtype == object:
            for index in np.ndindex(value.shape):
                _assert_frozen(value[index], f"{where}[{index}]")


def _assert_unwritable(array):
    """Neither the array, a view of it, nor anything down its ``base`` chain can be made
    writeable; numpy's other ways of reaching the memory give read-only arrays too."""
    assert not array.flags.writeable and array.base is not None
    reached = [array, array.T, array.view(), array[..., :1], np.asarray(array.base),
               as_strided(array, writeable=True), memoryview(array).obj]
    if array.flags.c_contiguous and array.dtype != object:
        reached.append(np.frombuffer(array, dtype=array.dtype))
    for view in reached:
        with pytest.raises(ValueError, match="WRITEABLE|read-only"):
            view.setflags(write=True)
    base = array.base
    while base is not None:
        if hasattr(base, "setflags"):
            with pytest.raises(ValueError):
                base.setflags(write=True)
        base = getattr(base, "base", None)


@settings(max_examples=75)
@given(meta=st.dictionaries(st.text(max_size=4), _json, max_size=4),
       protocol=st.integers(0, pickle.HIGHEST_PROTOCOL))
def test_any_json_like_meta_is_frozen_and_round_trips_frozen(meta, protocol):
    given_meta = copy.deepcopy(meta)
    motion = kinetology.Motion(np.arange(4.0).reshape(2, 2), ("a.rx", "b.rx"), 30, meta=meta)
    assert motion.meta == _expected(given_meta)
    _assert_frozen(motion.meta)
    for copied in (pickle.loads(pickle.dumps(motion, protocol=protocol)), copy.copy(motion),
                   copy.deepcopy(motion)):
        assert copied.meta == _expected(given_meta)
        _assert_frozen(copied.meta)
        assert copied.values.tobytes() == motion.values.tobytes()
        _assert_unwritable(copied.values)
    assert meta == given_meta  # the caller's dict is read, not changed


def test_what_the_caller_keeps_cannot_change_the_motion():
    cut, labels = [0.5, 2.0], {"walk": [1, 2]}
    motion = kinetology.Motion(np.zeros((2, 1)), ("a.rx",), 30,
                               meta={"cut": cut, "labels": labels, "frames": np.arange(3)})
    cut.append(9.0)
    labels["walk"].append(3)
    labels["run"] = []
    assert motion.meta["cut"] == (0.5, 2.0)
    assert dict(motion.meta["labels"]) == {"walk": (1, 2)}
    assert motion.meta["frames"].tolist() == [0, 1, 2]
    _assert_frozen(motion.meta)


def test_each_kind_of_container_is_frozen_to_its_read_only_kind():
    things = np.empty(2, dtype=object)
    things[0], things[1] = [1, 2], {"a": [3]}
    motion = kinetology.Motion(np.zeros((1, 1)), ("a.rx",), 30, meta={
        "set": {1, 2}, "bytes": bytearray(b"ab"), "cut": Cut([0.0], 1.0), "objects": things,
        "floats": np.ones((2, 2))})
    meta = motion.meta
    assert meta["set"] == frozenset({1, 2}) and type(meta["set"]) is frozenset
    assert meta["bytes"] == b"ab" and type(meta["bytes"]) is bytes
    assert type(meta["cut"]) is Cut and meta["cut"] == Cut((0.0,), 1.0)
    assert meta["objects"][0] == (1, 2) and meta["objects"][1] == {"a": (3,)}
    assert not np.shares_memory(meta["floats"], np.ones((2, 2)))
    _assert_frozen(meta)
    assert things[0] == [1, 2]  # the caller's array is copied, not frozen in place
    round_trip = pickle.loads(pickle.dumps(motion))
    assert round_trip.meta["objects"][1] == {"a": (3,)}
    assert isinstance(round_trip.meta["objects"][1], MappingProxyType)


def test_a_meta_holding_itself_or_nested_too_deeply_is_a_clear_error():
    loop = {"x": []}
    loop["x"].append(loop)
    with pytest.raises(ValidationError, match=r"meta\['loop'\]\['x'\]\[0\] holds itself"):
        kinetology.Motion(np.zeros((1, 1)), ("a.rx",), 30, meta={"loop": loop})
    deep = []
    for _ in range(100_000):
        deep = [deep]
    with pytest.raises(ValidationError, match="nested too deeply"):
        kinetology.Motion(np.zeros((1, 1)), ("a.rx",), 30, meta={"deep": deep})
    shared = [1]  # the same list twice is no loop
    twice = kinetology.Motion(np.zeros((1, 1)), ("a.rx",), 30, meta={"a": shared, "b": shared})
    assert twice.meta["a"] == twice.meta["b"] == (1,)


def test_a_readers_array_is_kept_uncopied_and_cannot_be_made_writeable():
    values = np.zeros((3, 2))  # an array of its own, as a reader's (arange(6).reshape is a view)
    values[:] = np.arange(6.0).reshape(3, 2)
    motion = build_motion(values, ("a.rx", "b.rx"), 30)
    assert np.shares_memory(motion.values, values)  # not copied
    _assert_unwritable(motion.values)
    _assert_unwritable(motion.column("b.rx"))
    _assert_unwritable(motion.select(["b.rx"]).values)
    assert motion.values.tolist() == [[0, 1], [2, 3], [4, 5]]


@needs_mocap
@pytest.mark.parametrize("name", ["cmu-01_01-pair/01_01.bvh", "cmu-subject02/02_01.amc"])
def test_a_read_motion_cannot_be_made_writeable(name):
    motion = kinetology.read(MOCAP / name)
    _assert_unwritable(motion.values)
    before = motion.values.tobytes()
    with pytest.raises(ValueError):
        motion.values[0, 0] = 1.0
    assert motion.values.tobytes() == before


def test_a_frozen_array_handed_on_is_shared_not_copied_again():
    motion = kinetology.Motion(np.zeros((2, 2)), ("a.rx", "b.rx"), 30,
                               meta={"frames": np.arange(3.0)})
    part = motion.select(["b.rx"])  # hands its meta on
    assert part.meta["frames"] is motion.meta["frames"]


def test_a_skeleton_given_lists_holds_tuples():
    joints = [Joint("hip", None, [0, 0, 0], ["hip.rx"], "ZYX", np.zeros(3)),
              Joint("knee", 0, np.array([0.0, -10.0, 0.0]))]
    skeleton = Skeleton(joints)
    joints.append(joints[0])
    assert skeleton.names == ("hip", "knee") and type(skeleton.joints) is tuple
    hip, knee = skeleton.joints
    assert hip.offset == (0, 0, 0) and hip.channels == ("hip.rx",) and hip.axis == (0, 0, 0)
    assert type(knee.offset) is tuple and knee.offset == (0.0, -10.0, 0.0)
    assert hash(skeleton) == hash(Skeleton(tuple(joints[:2])))  # hashable now lists are gone
    motion = kinetology.Motion(np.zeros((1, 1)), ("hip.rx",), 30, skeleton)
    assert pickle.loads(pickle.dumps(motion)).skeleton == skeleton


@pytest.mark.parametrize("protocol", range(pickle.HIGHEST_PROTOCOL + 1))
def test_the_private_owned_array_pickles_and_is_checked_again(protocol):
    values = np.arange(4.0).reshape(2, 2)
    loaded = pickle.loads(pickle.dumps(_Owned(values), protocol=protocol))
    assert type(loaded) is _Owned and loaded.array.tolist() == values.tolist()
    # an array read back from protocol 5's bytes is a view of them: checked, so copied
    assert loaded.array.base is None and loaded.array.flags.writeable
    motion = kinetology.Motion(loaded, ("a.rx", "b.rx"), 30)
    _assert_unwritable(motion.values)
