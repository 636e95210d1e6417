"""The kinds of features a description keeps, chosen by held-out recognition."""

from functools import partial

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology import synthetic_motion
from praxicon.description import DescriptionError, describe, describe_table
from praxicon.feature_choice import (FEATURE_KINDS, _folds, _held_out_right, choose_features,
                                     feature_kind)

LEARN = partial(describe_table, calibrate=False)
FEATURES = ("a.rx:pose", "a.rx:posec", "a.rx:energy", "a.rx:spread", "a.rx:shape0",
            "b.ry:pose", "b.ry:energy", "Hips.travelz:drift", "tempo")


def test_every_feature_has_one_of_the_kinds():
    assert [feature_kind(f) for f in FEATURES] == [
        "pose", "pose", "energy", "spread", "shape", "pose", "energy", "root", "tempo"]
    assert {feature_kind(f) for f in FEATURES} == set(FEATURE_KINDS)


@st.composite
def tables(draw):
    seed = draw(st.integers(0, 2**16))
    actions = draw(st.integers(2, 3))
    takes = draw(st.integers(2, 7))
    rng = np.random.default_rng(seed)
    means = rng.normal(0, draw(st.sampled_from([0.3, 1.0, 3.0])), (actions, len(FEATURES)))
    table = {f"act{k}": means[k] + rng.normal(0, 1, (takes, len(FEATURES)))
             for k in range(actions)}
    styles = draw(st.booleans())
    groups = {a: [i % 3 for i in range(takes)] for a in table} if styles else None
    return table, groups


@settings(max_examples=25, deadline=None, derandomize=True)
@given(tables())
def test_the_choice_is_every_feature_or_all_but_the_kind_that_recognises_most(drawn):
    # the oracle: every candidate's held-out count, computed one by one
    table, groups = drawn
    chosen = choose_features(table, FEATURES, LEARN, groups=groups)
    folds = _folds(table, groups)
    kinds = np.array([feature_kind(f) for f in FEATURES])
    every = _held_out_right(table, FEATURES, np.ones(len(FEATURES), bool), folds, LEARN)
    counts = {kind: _held_out_right(table, FEATURES, kinds != kind, folds, LEARN)
              for kind in FEATURE_KINDS}
    best = max([c for c in counts.values() if c is not None], default=None)
    if every is None or best is None or best <= every:
        assert chosen == FEATURES
    else:
        left_out = {feature_kind(f) for f in FEATURES} - {feature_kind(f) for f in chosen}
        assert len(left_out) == 1
        (kind,) = left_out
        assert counts[kind] == best  # the first of the best, in FEATURE_KINDS order
        assert all(counts[k] is None or counts[k] < best
                   for k in FEATURE_KINDS[:FEATURE_KINDS.index(kind)])
        assert chosen == tuple(f for f in FEATURES if feature_kind(f) != kind)


def test_takes_too_few_to_hold_out_keep_every_feature():
    table = {"a": np.zeros((1, len(FEATURES))), "b": np.ones((1, len(FEATURES)))}
    assert choose_features(table, FEATURES, LEARN) == FEATURES
    one_group = {"a": ["x"], "b": ["x"]}
    assert choose_features(table, FEATURES, LEARN, groups=one_group) == FEATURES


def test_a_kind_that_only_carries_style_is_left_out_when_styles_are_held_out():
    # the energies tell the actions apart; each style holds its own pose
    rng = np.random.default_rng(3)
    styles = np.repeat(np.arange(6), 3)
    features = ("a.rx:pose", "b.rx:pose", "a.rx:energy", "b.rx:energy")

    def takes(energy):
        pose = rng.normal(0, 4, (6, 2))[styles] + rng.normal(0, 0.2, (18, 2))
        return np.column_stack([pose, rng.normal(energy, 1.0, (18, 2))])

    table = {"fast": takes(2.0), "slow": takes(0.0)}
    assert choose_features(table, features, LEARN, groups={"fast": styles, "slow": styles}) == (
        "a.rx:energy", "b.rx:energy")


def test_describe_keeps_what_the_choice_keeps_and_can_keep_everything():
    takes = {"a": [synthetic_motion(2, (0,), seed=s) for s in (1, 2, 3)],
             "b": [synthetic_motion(2, (1,), seed=s) for s in (4, 5, 6)]}
    every = describe(takes, choose=False).spread.features
    chosen = describe(takes).spread.features
    assert set(chosen) <= set(every)
    left_out = {feature_kind(f) for f in every} - {feature_kind(f) for f in chosen}
    assert len(left_out) <= 1
    assert not set(chosen) & {f for f in every if feature_kind(f) in left_out}


def test_groups_that_do_not_name_every_take_are_a_clear_error():
    takes = {"a": [synthetic_motion(2, (0,), seed=s) for s in (1, 2)],
             "b": [synthetic_motion(2, (1,), seed=s) for s in (3, 4)]}
    with pytest.raises(DescriptionError, match="action 'b': groups name 1 takes' groups, it has 2"):
        describe(takes, groups={"a": ["x", "y"], "b": ["x"]})
