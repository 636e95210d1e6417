"""Motions, ASF skeletons and segmentations pickle and deep-copy to equal, still read-only
values: users hand them to multiprocessing and joblib, which pickle them, and a motion's
``meta`` (a mappingproxy) could not be pickled at all."""

from __future__ import annotations

import copy
import pickle
from types import MappingProxyType

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra import numpy as hnp

import kinetology
from kinetology.asf import AsfSkeleton, read_asf
from kinetology_fixtures import MOCAP, needs_mocap


def _round_trips(value):
    """The value through every pickle protocol and through copy.deepcopy."""
    for protocol in range(2, pickle.HIGHEST_PROTOCOL + 1):
        yield pickle.loads(pickle.dumps(value, protocol=protocol))
    yield copy.deepcopy(value)


def _assert_same_motion(copied, motion):
    assert type(copied) is type(motion) and copied is not motion
    # bit for bit: -0.0, subnormals and the last bit of every value survive
    assert copied.values.dtype == motion.values.dtype and copied.values.shape == motion.values.shape
    assert copied.values.tobytes() == motion.values.tobytes()
    assert copied.channels == motion.channels
    assert copied.frame_rate.hex() == motion.frame_rate.hex()
    assert copied.skeleton == motion.skeleton and copied.source == motion.source
    assert isinstance(copied.meta, MappingProxyType) and dict(copied.meta) == dict(motion.meta)
    # still immutable: the array cannot be written nor made writeable, nor a field set
    assert not copied.values.flags.writeable
    with pytest.raises(ValueError):
        copied.values.setflags(write=True)
    with pytest.raises(TypeError):
        copied.meta["format"] = "x"
    with pytest.raises(AttributeError):
        copied.frame_rate = 1.0
    # the cached column table is rebuilt, not carried over stale
    assert [copied.index(c) for c in copied.channels] == list(range(len(copied.channels)))


_finite = st.floats(allow_nan=False, allow_infinity=False, allow_subnormal=True, width=64)
_meta_values = st.recursive(st.none() | st.booleans() | st.integers() | _finite | st.text(max_size=5),
                            lambda inner: st.lists(inner, max_size=3)
                            | st.dictionaries(st.text(max_size=3), inner, max_size=3),
                            max_leaves=6)


@settings(max_examples=60, deadline=None)
@given(values=hnp.arrays(np.float64, hnp.array_shapes(min_dims=2, max_dims=2, min_side=0,
                                                      max_side=6), elements=_finite),
       rate=st.floats(1e-3, 1e4), source=st.text(max_size=8),
       meta=st.dictionaries(st.text(max_size=6), _meta_values, max_size=4))
def test_a_constructed_motion_round_trips_bit_for_bit(values, rate, source, meta):
    channels = tuple(f"j{k}.rx" for k in range(values.shape[1]))
    motion = kinetology.Motion(values, channels, rate, source=source, meta=meta)
    for copied in _round_trips(motion):
        _assert_same_motion(copied, motion)


def test_a_deep_copy_holds_meta_as_frozen_as_the_original():
    # a list in meta is kept as a tuple, so nothing in a copy's meta is shared and changeable
    motion = kinetology.Motion(np.zeros((2, 1)), ("a.rx",), 30, meta={"cut": [1, 2]})
    copied = copy.deepcopy(motion)
    assert copied.meta["cut"] == motion.meta["cut"] == (1, 2)


@needs_mocap
@pytest.mark.parametrize("name", ["cmu-01_01-pair/01_01.bvh", "cmu-subject02/02_01.amc",
                                  "cmu-mocap6/amc/13_29.amc"])
def test_a_read_motion_round_trips_with_its_skeleton(name):
    motion = kinetology.read(MOCAP / name)
    motion.index(motion.channels[-1])  # the column table is cached before the copy
    for copied in _round_trips(motion):
        _assert_same_motion(copied, motion)


@needs_mocap
def test_an_asf_skeleton_round_trips_and_stays_read_only():
    bones = read_asf(MOCAP / "cmu-subject02" / "02.asf")
    for copied in _round_trips(bones):
        assert copied == bones and isinstance(copied.dofs, MappingProxyType)
    # a dict given to the constructor is copied, read-only, like the reader's
    given_dofs = {"root": ("tx",)}
    built = AsfSkeleton(given_dofs, bones.skeleton, 1.0)
    given_dofs["root"] = ()
    assert built.dofs["root"] == ("tx",) and isinstance(built.dofs, MappingProxyType)


def test_a_segmentation_round_trips():
    found = kinetology.segments(kinetology.synthetic_motion(3, seed=0))
    assert found.actuators  # a mappingproxy to carry over
    for copied in _round_trips(found):
        assert isinstance(copied.actuators, MappingProxyType)
        assert dict(copied.actuators) == dict(found.actuators)
        assert dict(copied.skeleton) == dict(found.skeleton)
        assert copied.channels == found.channels and copied.still == found.still
        assert all(a.tobytes() == b.tobytes() for a, b in zip(copied.borders, found.borders))
        assert all(a.tobytes() == b.tobytes() for a, b in zip(copied.codes, found.codes))
        assert all(a.tobytes() == b.tobytes()
                   for a, b in zip(copied.displacements, found.displacements))
