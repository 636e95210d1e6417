"""Families: actions that are styles of one content decide "none of these" together."""

from __future__ import annotations

import json
from dataclasses import replace

import numpy as np
import pytest

from kinetology import synthetic_motion
from praxicon_fixtures import SHARED, needs_mocap
from praxicon.description import (DescriptionError, Descriptions, describe,
                                  family_descriptions, feature_rows)
from praxicon.recognition import family_verdicts, recognise_many


def _takes(patterned, period, seeds):
    return [synthetic_motion(4, patterned, period=period, seed=s, repetitions=6,
                             frame_rate=30.0) for s in seeds]


@pytest.fixture(scope="module")
def takes():
    return {"a.slow": _takes((0, 1), 1.3, (1, 2, 3)), "a.fast": _takes((0, 1), 0.8, (4, 5, 6)),
            "b": _takes((2, 3), 1.0, (7, 8, 9, 10, 11, 12))}


@pytest.fixture(scope="module")
def described(takes):
    return describe(takes, families={"a.slow": "a", "a.fast": "a"})


@pytest.fixture(scope="module")
def new():
    return (_takes((0, 1), 1.05, (20, 21, 22)) + _takes((2, 3), 1.0, (30, 31))
            + _takes((1, 2), 1.0, (40, 41)) + _takes((0, 3), 0.5, (50,)))


def test_a_family_is_described_from_its_members_takes(takes, described):
    assert described.family_of == ("a", "a", "")  # actions sorted: a.fast, a.slow, b
    assert described.families.names == ("a", "b")  # b alone is its own family
    assert [a.takes for a in described.families.actions] == [6, 6]
    # the actions themselves are described as without families
    assert replace(described, families=None, family_of=()) == describe(takes)


def test_no_family_of_two_actions_describes_no_families(takes):
    alone = describe(takes, families={"a.slow": "x", "a.fast": "y"})
    assert alone.families is None and alone == describe(takes)


def test_families_come_back_from_json(described):
    back = Descriptions.from_json(described.to_json())
    assert back == described and back.families == described.families


def test_a_members_none_of_these_is_its_familys_verdict(described, new):
    found = recognise_many(described, new)
    rows = feature_rows(new)
    best = [r.ranking[0][0] for r in found]
    verdicts = family_verdicts(described, rows, best)
    assert sorted(verdicts) == [i for i, b in enumerate(best) if b != "b"]
    plain = recognise_many(replace(described, families=None, family_of=()), new)
    for i, (r, p) in enumerate(zip(found, plain)):
        assert r.ranking == p.ranking  # families never change the ranking
        if i in verdicts:
            v = verdicts[i]
            assert r.family == "a" == v.family
            assert r.action == (best[i] if v.accepted else None)
            assert (r.penalty, r.threshold, r.excess) == (v.penalty, v.threshold, v.excess)
            assert "'none of these' tested by the family a (" in r.explain()
        else:  # an action alone keeps its own test
            assert (r.action, r.family, r.penalty, r.excess) == (p.action, "", p.penalty,
                                                                   p.excess)
    # the verdict is the family description's own test, as for an action alone
    alone = recognise_many(described.families, new)
    for i, v in verdicts.items():
        if alone[i].ranking[0][0] == "a":
            assert v.accepted == (alone[i].action == "a")
            assert v.penalty == pytest.approx(alone[i].penalty, rel=1e-9)


def test_family_descriptions_refuse_what_they_cannot_name(takes):
    rows = {n: feature_rows(m) for n, m in takes.items()}
    with pytest.raises(DescriptionError, match="families must map action names"):
        family_descriptions(rows, [("a.slow", "a")])
    with pytest.raises(DescriptionError, match="action 'a.slow': its family must be a name"):
        family_descriptions(rows, {"a.slow": 3})
    with pytest.raises(DescriptionError, match="family 'b' has the name of another action"):
        family_descriptions(rows, {"a.slow": "b", "a.fast": "b"})
    with pytest.raises(DescriptionError, match="family 'a.fast' has the name of another"):
        family_descriptions(rows, {"a.slow": "a.fast", "b": "a.fast"})


@pytest.mark.parametrize("change, match", [
    (lambda d: d.update(family_of=["a", "a"]), "'family_of' names 2 families for 3 actions"),
    (lambda d: d.update(family_of=["a", "", ""]), "family 'a' has one member"),
    (lambda d: d.update(family_of=["a", "a", "z"]), "no description of its family 'z'"),
    (lambda d: d.update(family_of=["q", "q", ""]), "no description of its family 'q'"),
    (lambda d: d.update(family_of="aa"), "'family_of' must be a list of family names"),
    (lambda d: d.pop("family_of"), "'family_of' must be a list of family names"),
    (lambda d: d["families"].update(families={}), "have families of their own"),
    (lambda d: d.update(families=[]), "families: "),
    (lambda d: d["families"]["spread"].update(window=2.0), "families: action 'a': 'window'"),
])
def test_damaged_families_are_refused(described, change, match):
    data = json.loads(described.to_json())
    change(data)
    with pytest.raises(DescriptionError, match=match):
        Descriptions.from_dict(data)


def test_family_of_without_families_is_refused(described):
    with pytest.raises(DescriptionError, match="'family_of' without the families"):
        replace(described, families=None)
    data = json.loads(described.to_json())
    del data["families"]
    with pytest.raises(DescriptionError, match="'family_of' without the families"):
        Descriptions.from_dict(data)
    with pytest.raises(DescriptionError, match="families must be Descriptions, not dict"):
        replace(described, families={})


@pytest.mark.parametrize("family_of", [["a", "a", ""], "aa", ("a", "a", None)])
def test_family_of_is_a_tuple_of_names(described, family_of):
    with pytest.raises(DescriptionError, match="'family_of' must be a tuple of family names"):
        replace(described, family_of=family_of)


def test_window_descriptions_have_no_families(described):
    windows = replace(described.spread, window=2.0)
    with pytest.raises(DescriptionError, match="window descriptions have no families"):
        replace(described, spread=windows,
                actions=tuple(replace(a, window=2.0) for a in described.actions),
                families=replace(described.families, spread=windows, actions=tuple(
                    replace(a, window=2.0) for a in described.families.actions)))


def test_a_family_answers_none_of_these_for_a_take_unlike_its_members(described):
    odd = synthetic_motion(4, (0, 1, 2, 3), period=0.3, amplitude=90.0, seed=60,
                           repetitions=6, frame_rate=30.0)
    (found,) = recognise_many(described, [odd])
    assert found.ranking[0][0].startswith("a.") and found.family == "a"
    assert found.action is None and found.penalty > found.threshold


def test_the_build_groups_the_styles_of_a_content(monkeypatch):
    """describe_praxicon names each learnt action's family by its dataset and content."""
    import praxicon.description as description
    from praxicon.builder import describe_praxicon
    from praxicon.records import ActionRecord, PerformanceRecord, Praxicon, Settings

    seen = {}

    def fake_describe(takes, *, families=None, **_):
        seen.update(families)
        raise DescriptionError("stop here")

    monkeypatch.setattr(description, "describe", fake_describe)
    monkeypatch.setattr("praxicon.learn._load_performance",
                        lambda p: (synthetic_motion(3, seed=1), None))
    take = (PerformanceRecord("x.bvh", None, None, None, used=True),)
    actions = tuple(ActionRecord(f"d.{c}.{s}", "d", c, s, status="ok", performances=take,
                                 learnt_from=(0,))
                    for c, s in (("run", "happy"), ("walk", "happy"), ("walk", "sad")))
    assert describe_praxicon(Praxicon(actions, Settings.make()), log=lambda _: None) is None
    assert seen == {"d.walk.happy": "d.walk", "d.walk.sad": "d.walk", "d.run.happy": "d.run"}
    assert np.array_equal(sorted(seen), sorted(a.name for a in actions))


@needs_mocap()
def test_a_bandai_folder_built_per_style_recognises_through_its_families(tmp_path):
    """End to end on the shared data: two contents in two styles, takes 1-3 built (one
    action per content and style), a take 4 of each recognised from the folder."""
    import shutil

    from praxicon import build, load, read_dataset, recognise

    source = SHARED / "bandai-namco-2-subset"
    if not source.is_dir():
        pytest.skip("../shared/data/mocap/bandai-namco-2-subset is absent")
    folder = tmp_path / "bandai-small"
    (folder / "data").mkdir(parents=True)
    shutil.copytree(source / "cfg", folder / "cfg")
    pairs = [(c, s) for c in ("run", "walk") for s in ("active", "normal")]
    for content, style in pairs:
        for take in (1, 2, 3):
            for suffix in (".bvh", ".json"):
                name = f"dataset-2_{content}_{style}_{take:03d}{suffix}"
                shutil.copyfile(source / "data" / name, folder / "data" / name)
    built = build(read_dataset(folder, group_by="content,style"), tmp_path / "px",
                  progress=False)
    px = load(tmp_path / "px")
    assert px == built.praxicon  # the families come back from the folder as learnt
    assert px.descriptions.family_of == ("bandai-small.run",) * 2 + ("bandai-small.walk",) * 2
    for content, style in pairs:
        found = recognise(tmp_path / "px", source / "data" /
                          f"dataset-2_{content}_{style}_004.bvh")
        assert found.family == f"bandai-small.{content}"
        assert found.action == f"bandai-small.{content}.{style}"
        # the same answer from the praxicon in memory, every number equal
        assert found == recognise(built.praxicon, source / "data" /
                                  f"dataset-2_{content}_{style}_004.bvh")
