"""A record's list or JSON object with a bad item names the item and its place (``'durations'
must be numbers above 0 and finite: value 4 is -1``), as the descriptions' reader does, where
it named the container (``..., not list``); a record's joints and a joint's morphemes that are
not one per actuator and channel name the one missing or the one of no actuator or channel.
"""

from __future__ import annotations

from dataclasses import replace

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fuzz_support import praxicon_seed
from praxicon.records import ActionRecord, ChannelMorpheme, Praxicon, PraxiconError


def _record() -> dict:
    return praxicon_seed().actions[1].to_json()  # moves.step, learnt


def _morpheme(record: dict) -> dict:
    return record["joints"]["arm"]["morphemes"]["arm.rz"]


_BAD_DURATIONS = st.sampled_from([-1, 0, 0.0, -0.5, float("inf"), float("nan")])


@settings(max_examples=40, deadline=None)
@given(durations=st.lists(st.floats(0.01, 10.0), min_size=1, max_size=6), data=st.data())
def test_a_bad_duration_is_named_with_its_place(durations, data):
    k = data.draw(st.integers(0, len(durations) - 1), label="place")
    bad = data.draw(_BAD_DURATIONS, label="bad")
    durations[k] = bad
    value = {"kinetemes": ["B"] * len(durations), "durations": durations}
    with pytest.raises(PraxiconError) as caught:
        ChannelMorpheme.from_json(value, "r.json: joint arm: arm.rz")
    assert str(caught.value) == (f"r.json: joint arm: arm.rz: 'durations' must be numbers above "
                                 f"0 and finite: value {k + 1} is {bad!r}")


@pytest.mark.parametrize("spoil, message", [
    (lambda r: _morpheme(r)["durations"].__setitem__(3, -1),
     "joint arm: arm.rz: 'durations' must be numbers above 0 and finite: value 4 is -1"),
    (lambda r: _morpheme(r)["kinetemes"].__setitem__(2, 5),
     "joint arm: arm.rz: 'kinetemes' must be a list of text: value 3 is 5"),
    (lambda r: _morpheme(r)["displacements"].__setitem__(1, "x"),
     "joint arm: arm.rz: 'displacements' must be a list of numbers: value 2 is 'x'"),
    (lambda r: r["component_names"].__setitem__("arm.rz", 3),
     "'component_names' must be channel -> text: value of 'arm.rz' is 3"),
    (lambda r: r["mean_pose"].__setitem__("leg.rx", None),
     "'mean_pose' must be channel -> number: value of 'leg.rx' is None"),
    (lambda r: r["learnt_from"].append(7),
     "'learnt_from' must be indices of its 2 performances: value 3 is 7"),
    (lambda r: r["learnt_from"].__setitem__(0, 0.5),
     "'learnt_from' must be a list of whole numbers: value 1 is 0.5"),
    (lambda r: r["actuators"].__setitem__(1, None),
     "'actuators' must be a list of text: value 2 is None"),
    (lambda r: r["joints"]["arm"]["morphemes"].pop("arm.rz"),
     "joint arm: its morphemes are not one per channel: channel 'arm.rz' has none"),
    (lambda r: r["joints"]["arm"]["morphemes"].__setitem__("arm.ry", {"kinetemes": []}),
     "joint arm: its morphemes are not one per channel: 'arm.ry' is no channel of it"),
    (lambda r: r["joints"].__setitem__("leg2", r["joints"].pop("leg")),
     "its joints are not one per actuator: actuator 'leg' has none"),
])
def test_a_record_names_its_bad_item(spoil, message):
    record = _record()
    spoil(record)
    with pytest.raises(PraxiconError) as caught:
        ActionRecord.from_json(record, "r.json")
    assert str(caught.value) == f"r.json: {message}"


def test_a_praxicons_keys_name_the_bad_one():
    whole = replace(praxicon_seed(), descriptions=None, window_descriptions=None).to_json()
    whole["keys"]["moves.wave"] = 12
    with pytest.raises(PraxiconError, match=r"^praxicon: 'keys' must be action -> text: "
                                            r"value of 'moves.wave' is 12$"):
        Praxicon.from_json(whole)
