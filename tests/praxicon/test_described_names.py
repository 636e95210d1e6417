"""The fields of ``descriptions.json`` that name something must name what is there.

Each group limit names one feature group of its spread's features once (the group test reads
only the groups it finds a limit for: limits renamed turned the "none of these" test off, and
a walk backwards was answered as a learnt turn with probability 1); a limit is above 0 (the
test divides by it); the window descriptions are of the takes' actions, and the families
described are those of the actions.
"""

from __future__ import annotations

from dataclasses import replace

import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from fuzz_support import praxicon_seed
from kinetology import synthetic_motion
from praxicon.description import FORMAT_VERSION, Descriptions, describe
from praxicon.description_store import descriptions_in
from praxicon.feature_groups import feature_groups
from praxicon.parsing import describe_windows
from praxicon.records import Praxicon, PraxiconError

PATH = "px/descriptions.json"
#: Where each spread with limits is in the file, and the words naming it in an error.
SPREADS = {("takes",): "takes: ", ("takes", "families"): "takes: families: ",
           ("windows",): "windows: "}


def _takes(patterned, period, seeds):
    return [synthetic_motion(4, patterned, period=period, seed=s, repetitions=6,
                             frame_rate=30.0) for s in seeds]


@pytest.fixture(scope="module")
def described():
    """Whole-take descriptions with a family (a.fast, a.slow) and an action alone (b), and
    the window descriptions of the same takes."""
    takes = {"a.slow": _takes((0, 1), 1.3, (1, 2, 3)), "a.fast": _takes((0, 1), 0.8, (4, 5, 6)),
             "b": _takes((2, 3), 1.0, (7, 8, 9, 10, 11, 12))}
    return describe(takes, families={"a.slow": "a", "a.fast": "a"}), describe_windows(takes)


def _file(takes: Descriptions, windows: Descriptions) -> dict:
    return {"format": "praxicon-descriptions-file", "version": FORMAT_VERSION, "key": "",
            "takes": takes.to_dict(), "windows": windows.to_dict()}


def _spread(data: dict, place: tuple) -> dict:
    for key in place:
        data = data[key]
    return data["spread"]


def _refused(data: dict) -> str:
    with pytest.raises(PraxiconError) as caught:
        descriptions_in(data, PATH)
    said = str(caught.value)
    assert "\n" not in said
    return said


def test_descriptions_as_learnt_are_read_back(described):
    takes, windows = described
    assert all(_spread(_file(*described), p)["limits"] for p in SPREADS)  # each spread has some
    assert descriptions_in(_file(takes, windows), PATH) == (takes, windows, "")


@settings(max_examples=60, deadline=None)
@given(place=st.sampled_from(list(SPREADS)), data=st.data(),
       other=st.one_of(st.sampled_from(["bogus0", "", "j0.rx", "Hips.travelq:drift", "j9",
                                        "j0", "j3", "tempo"]), st.text(max_size=8)))
def test_a_limit_of_no_group_or_of_a_group_twice_is_named(described, place, data, other):
    value = _file(*described)
    spread = _spread(value, place)
    groups = feature_groups(spread["features"])  # the oracle: the groups the test reads
    limits = spread["limits"]
    k = data.draw(st.integers(0, len(limits) - 1), label="limit renamed")
    assume(other != limits[k][0])
    limits[k][0] = other
    said = _refused(value)
    where = f"{PATH}: {SPREADS[place]}spread: 'limits' "
    if other not in groups:  # a name too long to show is named by its type
        shown = repr(other) if len(repr(other)) <= 40 else "str"
        assert said == f"{where}must be of the spread's feature groups: value {k + 1} is {shown}"
    else:  # another group's name: that group's limit is named twice
        first = min(i for i, (g, _) in enumerate(limits) if g == other)
        second = max(i for i, (g, _) in enumerate(limits) if g == other)
        assert said == f"{where}names {other!r} twice (values {first + 1} and {second + 1})"


@pytest.mark.parametrize("place", list(SPREADS))
def test_another_groups_name_is_a_group_named_twice(described, place):
    value = _file(*described)
    limits = _spread(value, place)["limits"]
    limits[-1][0] = limits[0][0]
    assert _refused(value) == (f"{PATH}: {SPREADS[place]}spread: 'limits' names "
                               f"{limits[0][0]!r} twice (values 1 and {len(limits)})")


@pytest.mark.parametrize("bound, refused", [(0.0, True), (-1.0, True), (5e-324, False)])
def test_a_limit_is_above_0(described, bound, refused):
    value = _file(*described)
    _spread(value, ("takes",))["limits"][1][1] = bound
    if refused:
        assert _refused(value) == (f"{PATH}: takes: spread: 'limits' must be numbers above 0: "
                                   f"value 2 is {bound!r}")
    else:
        descriptions_in(value, PATH)


def _drop_window(value):
    value["windows"]["actions"].pop(1)


def _rename_window(value):
    value["windows"]["actions"][1]["name"] = "a.gone"


def _add_window(value):
    value["windows"]["actions"].append(dict(value["windows"]["actions"][0], name="a.new"))


def _stray_family(value):
    families = value["takes"]["families"]
    families["actions"].append(dict(families["actions"][0], name="c"))


def _family_named_like_b(value):
    # b is alone (its own family, "b"): the family of a.fast and a.slow named b as well
    takes = value["takes"]
    takes["family_of"] = ["b", "b", ""]
    takes["families"]["actions"] = [a for a in takes["families"]["actions"] if a["name"] != "a"]


@pytest.mark.parametrize("damage, message", [
    (_drop_window, "takes and windows describe other actions: 'a.slow' is described in takes "
                   "only"),
    (_rename_window, "takes and windows describe other actions: 'a.slow' is described in "
                     "takes only"),
    (_add_window, "takes and windows describe other actions: 'a.new' is described in windows "
                  "only"),
    (_stray_family, "takes: families: describes 'c', the family of no action"),
    (_family_named_like_b, "takes: family 'b' has the name of another action (its members: "
                           "'a.fast', 'a.slow')"),
])
def test_windows_and_families_are_of_the_takes_actions(described, damage, message):
    value = _file(*described)
    damage(value)
    assert _refused(value) == f"{PATH}: {message}"
    # a praxicon's JSON value (praxicon.loads) holds descriptions too: refused alike
    takes, windows = (Descriptions.from_dict(value[p]) for p in ("takes", "windows"))
    whole = replace(praxicon_seed(), descriptions=None, window_descriptions=None).to_json()
    whole["descriptions"] = {"takes": takes.to_dict(), "windows": windows.to_dict()}
    with pytest.raises(PraxiconError) as caught:
        Praxicon.from_json(whole)
    assert str(caught.value) == f"praxicon: descriptions: {message}"
