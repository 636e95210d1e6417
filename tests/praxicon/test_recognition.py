"""Recognition through the praxicon: descriptions, recognise, parse, bad input (synthetic)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology import Motion, synthetic_motion
from praxicon.description import (FORMAT_VERSION, ActionDescription, DescriptionError,
                                  Descriptions, Spread, describe)
from praxicon.features import motion_features
from praxicon.parsing import describe_windows, parse
from praxicon.recognition import recognise, recognise_many


def _takes(pattern, seed, n=3):
    """``n`` takes of one synthetic action: the same movement, differing sensor noise."""
    return [synthetic_motion(4, pattern, seed=seed, noise=0.2 + 0.3 * k, repetitions=5)
            for k in range(n)]


@pytest.fixture(scope="module")
def takes():
    return {"left": _takes((0,), 1), "both": _takes((0, 2), 2), "right": _takes((2,), 3)}


@pytest.fixture(scope="module")
def px(takes):
    return describe(takes)


def test_each_action_recognised_and_ranked_on_one_scale(px):
    found = recognise_many(px, [synthetic_motion(4, p, seed=s, noise=0.45, repetitions=5)
                                for p, s in (((0,), 1), ((0, 2), 2), ((2,), 3))])
    assert [r.action for r in found] == ["left", "both", "right"]
    for r in found:
        probabilities = [p for _, p in r.ranking]
        assert probabilities == sorted(probabilities, reverse=True)
        assert math.isclose(sum(probabilities), 1.0)
        assert {name for name, _ in r.ranking} == {"left", "both", "right"}


def test_unseen_movement_is_none_of_these(px):
    found = recognise(px, synthetic_motion(4, (1, 3), seed=9, repetitions=5))
    assert found.action is None and (found.penalty > found.threshold or found.excess > 1.0)
    assert "none of these" in found.explain()


def test_a_motion_without_a_skeleton_is_explained_without_a_flight(px):
    # synthetic motions carry no skeleton: no point of the body to lift off the ground
    found = recognise(px, synthetic_motion(4, (0,), seed=1, noise=0.45, repetitions=5))
    assert found.off_ground is None and found.flight == ()
    assert "off the ground" not in found.explain() and "flight term" not in found.explain()


def test_explanation_names_the_extra_joint(px):
    """A one-hand take against the two-hand action: the other hand should move and does not."""
    found = recognise(px, synthetic_motion(4, (0,), seed=1, noise=0.45, repetitions=5))
    assert found.action == "left"
    assert all(r.role == "matched" for r in dict(found.reasons)["left"])
    reasons = {r.joint: r for r in dict(found.reasons)["both"]}
    assert reasons["j2"].role == "still but should move"
    assert "still but should move: j2" in found.explain()


def test_missing_joints_recognised_over_the_rest_and_named(px):
    motion = synthetic_motion(4, (2,), seed=3, noise=0.45, repetitions=5)
    fewer = motion.select(("j0.rx", "j2.rx", "j3.rx"))
    found = recognise(px, fewer)
    assert found.action == "right" and found.missing == ("j1",)
    assert "missing joints" in found.explain()


@pytest.mark.parametrize("frames", [0, 1, 2])
def test_too_short_motion_is_one_clear_error(px, frames):
    motion = Motion(np.zeros((frames, 4)), tuple(f"j{j}.rx" for j in range(4)), 120.0)
    with pytest.raises(DescriptionError, match="at least 3"):
        recognise(px, motion)


def test_motion_sharing_no_joint_is_an_error(px):
    with pytest.raises(DescriptionError, match="no joint"):
        recognise(px, Motion(np.zeros((10, 1)), ("elbow.rx",), 120.0))


def test_descriptions_round_trip_exactly(px):
    text = px.to_json()
    again = Descriptions.from_json(text)
    assert again == px and again.to_json() == text


_floats = st.floats(allow_nan=False, allow_infinity=False, width=64)


@settings(max_examples=40, deadline=None)
@given(st.lists(st.tuples(_floats, _floats.map(abs)), min_size=1, max_size=6),
       st.just(0.0) | st.floats(0.1, 60.0), st.integers(1, 10 ** 6))
def test_action_description_round_trips_every_float(pairs, window, takes):
    # every float a description may hold: spreads from 0, windows 0 (whole takes) or 0.1-60 s
    names = tuple(f"j{i}.rx:pose" for i in range(len(pairs)))
    d = ActionDescription("a", names, tuple(p[0] for p in pairs), tuple(p[1] for p in pairs),
                          takes, window)
    again = ActionDescription.from_json(d.to_json())
    assert again == d
    assert all(math.copysign(1, x) == math.copysign(1, y) for x, y in zip(again.mean, d.mean))


@pytest.mark.parametrize("text, said", [
    ('{"format": ' + "1" * 5000 + "}", "Exceeds the limit"),  # Python's int limit: ValueError
    ("[" * 100_000, "nested too deeply")])  # the decoder's RecursionError
def test_json_the_decoder_cannot_read_is_a_description_error(text, said):
    for read in (Descriptions.from_json, ActionDescription.from_json):
        with pytest.raises(DescriptionError, match=f"^not JSON that can be read: {said}"):
            read(text)


def test_other_version_is_a_clear_error(px):
    data = json.loads(px.to_json())
    data["version"] = FORMAT_VERSION - 1
    with pytest.raises(DescriptionError, match="version .*psgs praxicon build"):
        Descriptions.from_json(json.dumps(data))
    data["version"] = FORMAT_VERSION + 1  # a later psgs's: not to be learnt again over
    with pytest.raises(DescriptionError, match="version .*a later psgs wrote it; upgrade psgs"):
        Descriptions.from_json(json.dumps(data))
    with pytest.raises(DescriptionError, match="line 1, column"):
        Descriptions.from_json("{")


def _floats_stored(d: Descriptions) -> int:
    return sum(len(a.mean) + len(a.spread) for a in d.actions) + len(d.spread.scale) + \
        len(d.spread.noise) + sum(len(f) for f in d.spread.factors)


def test_size_grows_with_actions_not_takes(takes):
    """No take is kept: the floats stored are bounded by actions and features alone."""
    features = len(describe(takes).spread.features)
    for n in (2, 3):
        for k in (1, 2, 3):
            chosen = {name: v[:n] for name, v in list(takes.items())[:k]}
            d = describe(chosen)
            assert [a.takes for a in d.actions] == [n] * k
            assert _floats_stored(d) <= features * (2 * k + 2 + 16)


@settings(max_examples=15, deadline=None)
@given(st.floats(-180, 180))
def test_root_features_do_not_depend_on_heading(heading):
    """A walk to the north and one turned by any heading travel and turn alike."""
    t = np.arange(120) / 30.0
    rad = np.radians(heading)
    forward = 100 * t
    base = np.column_stack([np.zeros_like(t), 90 + 2 * np.sin(6 * t), forward,
                            np.zeros_like(t), np.zeros_like(t), 20 * t,
                            30 * np.sin(6 * t)])
    turned = base.copy()
    turned[:, 0], turned[:, 2] = forward * np.sin(rad), forward * np.cos(rad)
    turned[:, 5] = 20 * t + heading
    names = ("root.tx", "root.ty", "root.tz", "root.rx", "root.rz", "root.ry", "knee.rx")
    a = dict(zip(*motion_features(Motion(base, names, 30.0))))
    b = dict(zip(*motion_features(Motion(turned, names, 30.0))))
    roots = [f for f in a if f.startswith("root.")]
    assert roots and all(abs(a[f] - b[f]) < 1e-6 * max(1, abs(a[f])) for f in roots)
    assert a["root.turny:drift"] == pytest.approx(20.0, rel=0.01)  # the turn's rate, deg/s


def test_parse_finds_the_actions_in_order(takes):
    windows = describe_windows(takes, window=1.0, hop=0.25)
    a, b = takes["left"][0], takes["right"][1]
    joined = Motion(np.concatenate([a.values, b.values]), a.channels, a.frame_rate)
    timeline = parse(windows, joined)
    spans = timeline.spans
    assert [s.action for s in spans if s.action] == ["left", "right"]
    assert spans[0].start == 0 and spans[-1].stop == pytest.approx(joined.duration)
    assert all(x.stop == y.start for x, y in zip(spans, spans[1:]))
    cut = a.duration
    for s in spans:  # no span reaches more than one window into the other action
        if s.action == "left":
            assert s.stop <= cut + 1.0
        if s.action == "right":
            assert s.start >= cut - 1.0


def test_parse_needs_window_descriptions(px, takes):
    with pytest.raises(DescriptionError, match="window descriptions"):
        parse(px, takes["left"][0])
    with pytest.raises(DescriptionError, match="window descriptions"):
        recognise(describe_windows(takes, window=1.0), takes["left"][0])


def test_spread_is_shared_and_calibrated(px):
    assert isinstance(px.spread, Spread)
    assert 0 < px.spread.threshold < math.inf and px.spread.temperature >= 1
    assert len(px.spread.factors) <= 16


def test_group_test_names_a_joint_that_departs():
    """A take moving a joint that every learnt action keeps still (and keeping still the joint
    its nearest action moves) fails the group test on a joint's group, and
    the limits (one per feature group, calibrated on held-out takes) survive the JSON round
    trip; a new take of a learnt action passes the group test."""
    from kinetology import synthetic_motion
    from praxicon.description import Descriptions, describe
    from praxicon.recognition import recognise

    takes = {"left": [synthetic_motion(3, (0,), seed=1, noise=n) for n in (0.2, 0.5, 1.0)],
             "right": [synthetic_motion(3, (2,), seed=2, noise=n) for n in (0.2, 0.5, 1.0)]}
    px = describe(takes)
    groups = dict(px.spread.limits)
    assert {"j0", "j1", "j2"} <= set(groups) and all(0 < v < math.inf for v in groups.values())
    assert Descriptions.from_json(px.to_json()).spread.limits == px.spread.limits
    known = recognise(px, synthetic_motion(3, (2,), seed=2, noise=0.7))
    assert known.action == "right" and known.excess <= 1.0
    odd = recognise(px, synthetic_motion(3, (1,), seed=5))
    assert odd.action is None and odd.excess > 1.0 and odd.excess_group in ("j0", "j1", "j2")
    assert f"furthest feature group: {odd.excess_group}" in odd.explain()


def _gait(rate, seed: int, speed: float = 100.0, rise: float = 0.0) -> Motion:
    """A synthetic gait: travelling forward at about ``speed`` (and up at ``rise``), a knee
    swinging, the heading turning at ``rate`` degrees per second (0: straight on; a
    function of time in seconds: that course); sensor noise from ``seed``."""
    rng = np.random.default_rng(seed)
    t = np.arange(150) / 30.0
    speed, tempo = speed + 5 * rng.standard_normal(), 6 + 0.2 * rng.standard_normal()
    course = (np.cumsum(rate(t)) / 30.0 - rate(t)[0] / 30.0 if callable(rate) else rate * t)
    heading = np.radians(course)
    step = np.gradient(speed * t)
    x, z = np.cumsum(step * np.sin(heading)), np.cumsum(step * np.cos(heading))
    values = np.column_stack([x, 90 + rise * t + 2 * np.sin(tempo * t), z, np.zeros_like(t),
                              np.zeros_like(t), course, 30 * np.sin(tempo * t)])
    values += 0.2 * rng.standard_normal(values.shape)
    names = ("root.tx", "root.ty", "root.tz", "root.rx", "root.rz", "root.ry", "knee.rx")
    label = f"{rate:+.0f}" if not callable(rate) else "course"
    return Motion(values, names, 30.0, source=f"gait{label}.{seed}")


def _turns(rng, n: int = 8):
    return {name: [_gait(sign * (20 + 2 * rng.standard_normal()), seed,
                         100 + 80 * (seed % 4 == 0)) for seed in range(k, k + n)]
            for name, sign, k in (("turn-left", 1, 0), ("turn-right", -1, 100))}


def test_group_test_rejects_a_walk_against_turns_by_its_heading():
    """Learnt: a left and a right turn (heading rate +-20 deg/s, a few degrees' spread; some
    takes hurried, as a style does). A straight walk ranks first one of them, but how far it
    turns, a feature group of its own, is far outside that turn's: none of these. Summed with
    the travel into one group, the hurried takes' speeds would hide it. New turns pass. The
    whole take's excursion stands for the heading; its mean rate is in no group."""
    px = describe(_turns(np.random.default_rng(0)))
    limits = dict(px.spread.limits)
    assert "root.turny:excursion" in limits and "root.turny:drift" not in limits
    walk = recognise(px, _gait(0.0, 500))
    assert walk.action is None and walk.excess_group == "root.turny:excursion"
    turns = recognise_many(px, [_gait(21.0, 600), _gait(-19.0, 601)])
    assert [r.action for r in turns] == ["turn-left", "turn-right"]


def test_turn_excursion_is_the_largest_signed_turn_from_the_start():
    """Oracle: a gait turning right at 40 deg/s for 3 s and then back left at 50 deg/s has
    turned furthest (-120 deg) at 3 s, and its mean turning rate is the net turn (-20 deg)
    over the take; the excursion reads the first, the drift the second. Windows (no course
    features) have no excursion."""
    motion = _gait(lambda t: np.where(t < 3.0, -40.0, 50.0), 3)
    features = dict(zip(*motion_features(motion)))
    course = np.cumsum(np.where(np.arange(150) / 30.0 < 3.0, -40.0, 50.0)) / 30.0
    assert features["root.turny:excursion"] == pytest.approx(-120.0, abs=4.0)
    assert features["root.turny:drift"] == pytest.approx(course[-1] / motion.duration, abs=2.0)
    assert abs(features["root.turnx:excursion"]) < 2.0
    assert not any(f.endswith(":excursion") for f in motion_features(motion, shape=False)[0])


def test_group_test_reads_only_the_groups_that_tell_actions_apart():
    """Every learnt turn travels on the level: the vertical travel cannot tell one turn from
    the other, so a right turn taken up a slope, far outside that group's limit, is still a
    right turn; the heading, which tells them apart, is read (a walk is none of these)."""
    from praxicon.description import score_model
    from praxicon.feature_groups import feature_groups, group_distances, telling_groups
    from praxicon.recognition import feature_matrix

    px = describe(_turns(np.random.default_rng(3)))
    climbing = _gait(-20.0, 901, rise=2.0)
    columns, x, _ = feature_matrix(px, [climbing])
    features = [px.spread.features[i] for i in columns]
    limits = dict(px.spread.limits)
    groups = {g: c for g, c in feature_groups(features).items() if g in limits}
    fitted = score_model(px, columns)
    bound = np.array([limits[g] for g in groups])
    right = px.names.index("turn-right")
    far = dict(zip(groups, group_distances(x[0], fitted.means[right], fitted.variance[right],
                                           fitted.scale, groups)[0] / bound))
    tells = dict(zip(groups, telling_groups(fitted.means, fitted.variance, fitted.scale,
                                            groups, bound)[right]))
    upward = max((g for g in groups if ".travel" in g and g.endswith(":drift")), key=far.get)
    assert far[upward] > 1.0 and not tells[upward] and tells["root.turny:excursion"]
    found = recognise(px, climbing)
    assert found.action == "turn-right" and found.excess_group != upward
    assert recognise(px, _gait(0.0, 902)).action is None


def test_drift_is_also_scored_in_each_actions_own_spread():
    """Actions are ranked by the shared distance plus each action's own-spread term of the
    root's drift, relative to the best action's (which pays nothing more); without the term
    the score is the shared distance, which the "none of these" threshold reads either way.
    A left turn's heading rate costs the right turn, whose own rates are far from it, more."""
    from praxicon.description import own_columns, scores

    rng = np.random.default_rng(1)
    takes = {name: [_gait(sign * (20 + 2 * rng.standard_normal()), seed)
                    for seed in range(k, k + 6)]
             for name, sign, k in (("turn-left", 1, 0), ("turn-right", -1, 100))}
    px = describe(takes)
    columns = np.arange(len(px.spread.features))
    x = np.array([motion_features(_gait(21.0, 700))[1]])
    shared, score = scores(px, x, columns)
    plain_shared, plain = scores(px, x, columns, kinds=())
    assert np.array_equal(shared, plain_shared) and np.array_equal(plain, shared)
    extra = score - shared
    assert len(own_columns(px.spread.features)) == 6
    assert extra.min() == 0.0 and extra[0, 0] == 0.0 and extra[0, 1] > 10.0
    found = recognise(px, _gait(21.0, 700))
    assert found.ranking[0][0] == "turn-left" and found.penalty == pytest.approx(
        shared[0, 0] / len(columns))


def test_the_ranking_follows_the_scores_where_the_probabilities_underflow(px):
    # at a tiny temperature every probability but the best's is 0.0: the order of the rest
    # must still be that of the scores, not the order the actions were learnt in
    from dataclasses import replace

    from praxicon.recognition import feature_matrix
    from praxicon.scoring import scores

    sharp = replace(px, spread=replace(px.spread, temperature=1e-6))
    new = [synthetic_motion(4, (2,), seed=3, noise=0.45, repetitions=5),
           synthetic_motion(4, (0,), seed=1, noise=0.45, repetitions=5)]
    columns, x, _ = feature_matrix(sharp, new)
    _, score = scores(sharp, x, columns)
    for r, s in zip(recognise_many(sharp, new), score):
        assert [p for _, p in r.ranking][1:] == [0.0, 0.0]  # underflowed: no order in them
        assert [name for name, _ in r.ranking] == [sharp.names[a] for a in np.argsort(s)]


def test_a_timeline_lines_its_scores_up_under_long_action_names():
    from praxicon.parsing import Span, Timeline

    names = ["walk", "bandai-namco-2-subset.walk-turn-right.masculine", None]
    timeline = Timeline("rec", 3.0, tuple(Span(float(i), i + 1.0, n, 0.5)
                                          for i, n in enumerate(names)), ())
    lines = timeline.text().splitlines()
    assert len({line.rindex("0.500") for line in lines}) == 1, lines
