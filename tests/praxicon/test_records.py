"""Typed praxicon records: the JSON round trip is exact, and any JSON reads or is one error."""

from __future__ import annotations

import json

import pytest
from hypothesis import given, settings, strategies as st

from praxicon import dump, load
from praxicon.jsonvalues import freeze
from praxicon.records import (FORMAT_VERSION, ActionRecord, ChannelMorpheme, JointRecord,
                              PerformanceRecord, Praxicon, PraxiconError, Settings)

names = st.text(st.characters(min_codepoint=33, max_codepoint=0x2FF,
                              blacklist_characters="/\\."), min_size=1, max_size=12)
floats = st.floats(allow_nan=False, allow_infinity=False, width=64)
kinetemes = st.lists(st.sampled_from("BGRY"), min_size=1, max_size=6).map(tuple)
json_scalars = st.none() | st.booleans() | st.integers(-5, 5) | floats | st.text(max_size=4)
json_values = st.recursive(json_scalars, lambda inner: st.lists(inner, max_size=3)
                           | st.dictionaries(st.text(max_size=3), inner, max_size=3),
                           max_leaves=4)


@st.composite
def morphemes(draw):
    k = draw(kinetemes)
    same = st.lists(floats, min_size=len(k), max_size=len(k)).map(tuple)
    # a kineteme's typical duration is above 0 (load refuses others)
    durations = st.lists(st.floats(1e-6, 1e6), min_size=len(k), max_size=len(k)).map(tuple)
    return ChannelMorpheme(k, draw(st.none() | durations), draw(st.none() | same),
                           draw(st.integers(0, 9)))


@st.composite
def records(draw):
    name = draw(names)
    performances = tuple(draw(st.lists(st.builds(
        # seconds 0 or more, the stop after the start (load refuses others)
        PerformanceRecord, names, st.none() | st.floats(0, 100), st.none() | st.floats(101, 1e6),
        st.none() | names,
        st.none() | st.booleans()), max_size=3)))
    base = ActionRecord(name, draw(names), draw(names), draw(st.none() | names),
                        status="failed", reason=draw(st.none() | st.text(max_size=20)),
                        problems=tuple(draw(st.lists(st.text(max_size=20), max_size=2))),
                        performances=performances)
    if not draw(st.booleans()):
        return base
    joints = draw(st.lists(names, min_size=1, max_size=3, unique=True))
    joint_records = tuple(JointRecord(j, tuple((f"{j}.r{a}", draw(morphemes()))
                                               for a in draw(st.sets(st.sampled_from("xyz"),
                                                                     min_size=1))))
                          for j in joints)
    channels = [c for j in joint_records for c in j.channels]
    return ActionRecord(
        **{k: getattr(base, k) for k in ("name", "dataset", "content", "style", "reason",
                                         "problems", "performances")},
        status="ok", learnt_from=tuple(draw(st.lists(  # indices of its performances
            st.integers(0, max(len(performances) - 1, 0)), max_size=3 if performances else 0))),
        note=draw(st.none() | st.text(max_size=10)), actuators=tuple(joints),
        joints=joint_records, verdict=draw(st.text(max_size=10)), inducer="pal",
        params=freeze(draw(st.dictionaries(st.text(max_size=4), json_values, max_size=3))),
        system=draw(st.none() | st.text(max_size=30)),
        component_names=tuple(sorted((c, c.replace(".", "_")) for c in channels)),
        frame_rate=draw(st.floats(1.0, 1000.0)), skeleton_source=draw(names),
        all_joints=tuple(joints),
        mean_pose=tuple(sorted((c, draw(floats)) for c in channels)),
        segmentation=freeze(draw(st.dictionaries(st.text(max_size=4), json_scalars,
                                                 max_size=3))))


@settings(max_examples=30, deadline=None)
@given(records())
def test_a_record_comes_back_equal_through_json_text(record):
    text = json.dumps(record.to_json(), sort_keys=True)
    again = ActionRecord.from_json(json.loads(text))
    assert again == record
    assert json.dumps(again.to_json(), sort_keys=True) == text


@settings(max_examples=10, deadline=None)
@given(st.lists(records(), max_size=2, unique_by=lambda r: r.name))
def test_a_praxicon_comes_back_equal(recs):
    px = Praxicon(tuple(sorted(recs, key=lambda r: r.name)), Settings.make(params={"a": 1}),
                  ("d.csv",), tuple(sorted((r.name, "k" + r.name) for r in recs)))
    assert Praxicon.from_json(json.loads(json.dumps(px.to_json()))) == px


@settings(max_examples=100, deadline=None)
@given(st.dictionaries(st.sampled_from(["name", "dataset", "content", "style", "status",
                                        "reason", "problems", "performances", "actuators",
                                        "joints", "mean_pose", "component_names", "frame_rate",
                                        "skeleton_source", "all_joints", "learnt_from"]),
                       json_values | st.just("ok")))
def test_any_json_reads_as_a_record_or_is_one_praxicon_error(value):
    try:
        ActionRecord.from_json(value, "r.json")
    except PraxiconError as exc:
        assert str(exc).startswith("r.json") and "\n" not in str(exc)


def test_dump_then_load_is_the_same_praxicon_and_the_same_bytes(tmp_path):
    joint = JointRecord("arm", (("arm.rx", ChannelMorpheme(("B", "Y"), (0.5, 0.25),
                                                           (30.0, -30.0), 3)),))
    ok = ActionRecord("m.wave", "m", "wave", status="ok", actuators=("arm",), joints=(joint,),
                      system="psgs G\n", frame_rate=30.0, all_joints=("hips", "arm"),
                      component_names=(("arm.rx", "arm_rx"),), skeleton_source="a.bvh",
                      mean_pose=(("arm.rx", 1.5), ("hips.rz", 0.0)))
    failed = ActionRecord("m.bye", "m", "bye", reason="1 usable performance(s)")
    px = Praxicon((failed, ok), Settings.make(), ("m.csv",), (("m.wave", "abc"),))
    dump(px, tmp_path / "a")
    assert load(tmp_path / "a") == px
    dump(load(tmp_path / "a"), tmp_path / "b")
    files = sorted(p.relative_to(tmp_path / "a") for p in (tmp_path / "a").rglob("*"))
    assert [p.as_posix() for p in files] == ["actuators.csv", "index.json", "m.wave.psgs",
                                             "records", "records/m.bye.json",
                                             "records/m.wave.json", "shared.json"]
    assert all((tmp_path / "a" / p).read_bytes() == (tmp_path / "b" / p).read_bytes()
               for p in files if (tmp_path / "a" / p).is_file())
    index = json.loads((tmp_path / "a" / "index.json").read_text())
    assert index["version"] == FORMAT_VERSION and "mean_pose" not in index["actions"][1]
    assert index["actions"][1]["file"] == "m.wave.psgs"


def test_a_praxicon_holds_each_name_once_in_order():
    a, b = ActionRecord("a", "d", "a"), ActionRecord("b", "d", "b")
    with pytest.raises(PraxiconError, match="distinct names, sorted"):
        Praxicon((b, a), Settings.make())
    with pytest.raises(PraxiconError, match="distinct names, sorted"):
        Praxicon((a, a), Settings.make())
    with pytest.raises(PraxiconError, match="no action 'c' in the praxicon"):
        Praxicon((a, b), Settings.make())["c"]


def test_settings_read_back_or_one_error():
    s = Settings.make("pal", {"min_copies": 3, "scales": [1, 2]}, {"min_range": 2.0}, 3)
    assert Settings.from_dict(json.loads(json.dumps(s.to_dict()))) == s
    with pytest.raises(PraxiconError, match="'settings' must hold"):
        Settings.from_dict({"inducer": "pal"}, "index.json")
