"""The conformance kit runs on every registered inducer, and catches inducers that break a rule."""

from __future__ import annotations

import itertools
from dataclasses import replace

import pytest

from psgs import Actiongram
from psgs.induce import Sequential, available, get
from psgs.induce.testing import check_inducer, examples
from test_contract import Echo, FakeEntryPoint, plug_in


@pytest.mark.parametrize("name", available())  # the built-ins and every installed plug-in
def test_every_registered_inducer_keeps_the_contract(name):
    check_inducer(get(name))


def test_a_plug_in_is_checked_like_a_built_in(monkeypatch):
    plug_in(monkeypatch, FakeEntryPoint("echo", Echo))
    assert "echo" in available()
    check_inducer(get("echo", least=2))


def test_the_kit_learns_from_the_actiongrams_given():
    takes = [Actiongram.from_strings({"a": "xyxyxy", "b": "pqpqpq"}),
             Actiongram.from_strings({"a": "xyxy", "b": "pqpq"})]
    check_inducer(Sequential(), takes)
    with pytest.raises(AssertionError, match="needs at least two actiongrams"):
        check_inducer(Sequential(), takes[:1])


class Restless(Sequential):
    """Each call records how many came before: the same input gives another result."""

    name = "restless"
    _calls = itertools.count()

    def induce(self, performances):
        result = super().induce(performances)
        return replace(result, params={**result.params, "call": next(self._calls)})


class Backwards(Sequential):
    """Reports in reverse order."""

    name = "backwards"

    def induce(self, performances):
        result = super().induce(performances)
        return replace(result, reports=result.reports[::-1])


class Lenient(Sequential):
    """Takes a bare string as an actiongram of one string."""

    name = "lenient"

    def induce(self, performances):
        if isinstance(performances, str):
            performances = Actiongram.from_strings({"s": performances})
        return super().induce(performances)


class Forgetful(Sequential):
    """Accepts any parameter name silently."""

    name = "forgetful"

    def set_params(self, **params):
        for key, value in params.items():
            setattr(self, key, value)
        return self


class Impostor(Sequential):
    """Says another inducer made its results."""

    name = "impostor"

    def induce(self, performances):
        return replace(super().induce(performances), inducer="sequential")


class Spurious(Sequential):
    """Makes up a component the actiongram does not have."""

    name = "spurious"

    def induce(self, performances):
        result = super().induce(performances)
        return replace(result, components=(*result.components, "ghost"),
                       patterns={**result.patterns, "ghost": ("a",)},
                       occurrences={**result.occurrences, "ghost": ((0.0, 1.0),)})


class _BrokenWhenSeveral:
    """Learns one actiongram as Sequential does; breaks (as the class after it in the MRO
    breaks) only on several performances."""

    def induce(self, performances):
        if isinstance(performances, Actiongram) or len(performances) == 1:
            return Sequential.induce(self, performances)
        return super().induce(performances)


class SpuriousWhenSeveral(_BrokenWhenSeveral, Spurious):
    """Keeps the contract on one actiongram, makes up a component from several performances."""

    name = "spurious_when_several"


class ImpostorWhenSeveral(_BrokenWhenSeveral, Impostor):
    """Names another inducer only in what it learns from several performances."""

    name = "impostor_when_several"


@pytest.mark.parametrize("broken, rule", [
    (Restless(), "the same actiongram must give an equal Induction"),
    (Backwards(), "reports, when given, must be one per string, in actiongram order"),
    (Lenient(), "induce\\('abab'\\) must raise TypeError"),
    (Forgetful(), "set_params\\(no_such_parameter_xxx=1\\) must raise ValidationError"),
    (Impostor(), "the Induction must name its inducer \\('impostor'\\)"),
    (Spurious(), "components .* must be strings of the actiongram"),
    (SpuriousWhenSeveral(), "components .* must be strings of the actiongram"),
    (ImpostorWhenSeveral(), "the Induction must name its inducer \\('impostor_when_several'\\)"),
])
def test_the_kit_catches_an_inducer_that_breaks_a_rule(broken, rule):
    with pytest.raises(AssertionError, match=f"check_inducer\\({broken.name}\\): {rule}"):
        check_inducer(broken)


def test_the_default_examples_hold_repetition_and_none():
    repeated, other, plain = examples()
    assert repeated.names == other.names
    assert Sequential().induce(repeated).components
    assert get("pal").induce(plain).components == ()


def test_the_plug_in_guide_runs():
    import doctest
    from pathlib import Path

    page = Path(__file__).resolve().parents[2] / "docs" / "inducers.md"
    result = doctest.testfile(str(page), module_relative=False, optionflags=doctest.ELLIPSIS)
    assert result.attempted > 5 and result.failed == 0
