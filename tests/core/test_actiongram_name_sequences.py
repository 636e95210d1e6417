"""Where an Actiongram takes a sequence of names, a bare str is refused: it was read as the
names of its characters, so subset("ab") picked the strings 'a' and 'b', not 'ab'."""

from __future__ import annotations

import pytest

from psgs import Actiongram, ValidationError

AG = Actiongram.from_strings({"a": "x", "b": "y", "ab": "z"})


def test_subset_refuses_a_bare_str():
    with pytest.raises(ValidationError) as refused:
        AG.subset("ab")
    assert str(refused.value) == ("names must be a sequence of string names, not a str ('ab'); "
                                  "one name is given as ['ab']")


@pytest.mark.parametrize("names, picked", [
    (["ab"], ("ab",)), (("a", "b"), ("a", "b")), (iter(["b", "ab"]), ("b", "ab")), ([], ()),
])
def test_subset_takes_any_sequence_of_names(names, picked):
    part = AG.subset(names)
    assert part.names == picked and part.strings == {n: AG.string(n) for n in picked}


def test_the_constructor_refuses_a_bare_str_of_names():
    # Actiongram("ab", ...) made strings 'a' and 'b' (or refused the rows' count)
    with pytest.raises(ValidationError, match=r"^names must be a sequence of string names, not "
                                              r"a str \('a'\)"):
        Actiongram("a", (("x",),), ((1.0,),))
    with pytest.raises(ValidationError, match=r"^string_actuators must be a sequence of "
                                              r"actuator names, not a str \('k'\)"):
        Actiongram(("a",), (("x",),), ((1.0,),), string_actuators="k")
    made = Actiongram(("a",), (("x",),), ((1.0,),), string_actuators=("k",))
    assert made.names == ("a",) and made.actuators == ("k",)
