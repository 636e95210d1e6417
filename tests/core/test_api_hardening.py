"""Bad arguments to the public API: one ValidationError naming the parameter, never a
TypeError from deep inside, and the same answer for the same input."""

from __future__ import annotations

import math

import pytest

import psgs
from psgs.errors import ValidationError


@pytest.fixture(scope="module")
def gamma():
    return psgs.load("paper_example")


@pytest.mark.parametrize("value", [None, "3", -1, 2.5, math.nan, True, [], object()])
@pytest.mark.parametrize("name", ["max_steps", "max_form_length"])
def test_random_derivation_refuses_a_bound_that_is_no_count(gamma, name, value):
    with pytest.raises(ValidationError, match=name):
        psgs.random_derivation(gamma, 0, **{name: value})


def test_random_derivation_takes_a_bound_of_zero(gamma):
    assert psgs.random_derivation(gamma, 0, max_steps=0).steps == ()


@pytest.mark.parametrize("seed", [None, math.nan, math.inf, True, [1], (1, 2), object()])
def test_random_derivation_refuses_a_seed_that_would_not_repeat(gamma, seed):
    # None seeds from the operating system and a NaN hashes by identity: each call would
    # draw another derivation
    with pytest.raises(ValidationError, match="seed"):
        psgs.random_derivation(gamma, seed)


@pytest.mark.parametrize("seed", [0, 7, -3, 2.5, "walk", b"walk", 10 ** 30])
def test_random_derivation_repeats_for_every_seed_it_takes(gamma, seed):
    assert psgs.random_derivation(gamma, seed) == psgs.random_derivation(gamma, seed)


def test_random_derivation_takes_a_numpy_integer_as_its_value(gamma):
    np = pytest.importorskip("numpy")
    assert psgs.random_derivation(gamma, np.int64(5)) == psgs.random_derivation(gamma, 5)


@pytest.mark.parametrize("configuration", [None, 3, math.nan, True, object()])
def test_applicable_steps_refuses_a_configuration_that_is_no_sequence(gamma, configuration):
    with pytest.raises(ValidationError, match="configuration"):
        psgs.applicable_steps(gamma, configuration)
    with pytest.raises(ValidationError, match="configuration"):
        psgs.derivation.apply_tuple(gamma, configuration, gamma.sync[0])


@pytest.mark.parametrize("kwargs, name", [
    ({"max_length": None}, "max_length"), ({"max_length": "8"}, "max_length"),
    ({"max_length": 2.5}, "max_length"), ({"max_length": math.inf}, "max_length"),
    ({"max_length": -1}, "max_length"), ({"max_length": True}, "max_length"),
    ({"max_words": None}, "max_words"), ({"max_words": 0}, "max_words"),
    ({"max_words": math.nan}, "max_words"), ({"max_words": "9"}, "max_words"),
    ({"rules": 3}, "rules"), ({"rules": "r1"}, "rules"), ({"rules": [None]}, "rules"),
    ({"start": [1]}, "start"), ({"start": "S"}, "start"),
])
def test_context_free_words_refuses_bad_arguments(gamma, kwargs, name):
    from psgs.enumeration import context_free_words

    arguments = {"max_length": 8} | kwargs
    with pytest.raises(ValidationError, match=name):
        context_free_words(gamma.components[0], **arguments)


def test_context_free_words_refuses_what_is_no_grammar(gamma):
    from psgs.enumeration import context_free_words

    with pytest.raises(ValidationError, match="Grammar"):
        context_free_words(gamma, 8)
