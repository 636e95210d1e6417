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


# ---------------------------------------------------------------- actiongrams
_NOT_SEQUENCES = [None, 3, math.nan, True, object()]


@pytest.mark.parametrize("value", _NOT_SEQUENCES)
@pytest.mark.parametrize("what", ["strings", "durations", "displacements"])
def test_from_strings_refuses_a_string_value_that_is_no_sequence(what, value):
    strings = {"a": value} if what == "strings" else {"a": "x"}
    extra = {} if what == "strings" else {what: {"a": value}}
    with pytest.raises(ValidationError, match=what):
        psgs.Actiongram.from_strings(strings, **extra)


@pytest.mark.parametrize("skeleton", ["a", 3, [("a", None)], object()])
def test_from_strings_refuses_a_skeleton_that_is_no_mapping(skeleton):
    with pytest.raises(ValidationError, match="skeleton"):
        psgs.Actiongram.from_strings({"a": "x"}, skeleton=skeleton)


@pytest.mark.parametrize("value", _NOT_SEQUENCES)
@pytest.mark.parametrize("field", range(7))
def test_the_constructor_refuses_a_field_that_is_no_sequence(field, value):
    fields = [("x",), (("a",),), ((1.0,),), (0.0,), (), (), ()]
    fields[field] = value
    if field >= 3 and not value:  # an empty optional field is its default
        return
    with pytest.raises(ValidationError):
        psgs.Actiongram(*fields)


def test_the_constructor_says_fields_of_different_lengths_as_a_validation_error():
    with pytest.raises(ValidationError, match="one entry per string"):
        psgs.Actiongram(("x", "y"), (("a",),), ((1.0,),))


@pytest.mark.parametrize("text", [None, 3, b"a: x", ["a: x"]])
def test_from_text_refuses_what_is_no_str(text):
    with pytest.raises(ValidationError, match="from_text"):
        psgs.Actiongram.from_text(text)


@pytest.mark.parametrize("text", [None, 3, ["{}"]])
def test_from_json_refuses_what_is_no_text(text):
    with pytest.raises(ValidationError, match="from_json"):
        psgs.Actiongram.from_json(text)


def test_from_json_still_reads_bytes():
    ag = psgs.Actiongram.from_strings({"a": "xy"})
    assert psgs.Actiongram.from_json(ag.to_json().encode()) == ag


@pytest.mark.parametrize("kwargs, name", [
    ({"codes": None}, "codes"), ({"codes": [[0, 1]]}, "codes"), ({"alphabet": None}, "alphabet"),
    ({"alphabet": 3}, "alphabet"), ({"durations": 3}, "durations"),
    ({"durations": {"a": None}}, "durations"), ({"durations": {"a": 3}}, "durations"),
    ({"skeleton": "a"}, "skeleton"), ({"codes": {"a": [0, 9]}}, "codes"),
    ({"codes": {"a": [0.5]}}, "codes"),
])
def test_from_codes_refuses_bad_arguments(kwargs, name):
    arguments = {"codes": {"a": [0, 1]}, "alphabet": "xy"} | kwargs
    codes, alphabet = arguments.pop("codes"), arguments.pop("alphabet")
    with pytest.raises(ValidationError, match=name):
        psgs.Actiongram.from_codes(codes, alphabet, **arguments)


@pytest.mark.parametrize("columns", ["stream", 3, ["stream"]])
def test_from_events_refuses_columns_that_are_no_mapping(columns):
    with pytest.raises(ValidationError, match="columns"):
        psgs.Actiongram.from_events([("s", 0, 1, "a")], columns=columns)


@pytest.mark.parametrize("name", [None, 3, "nope", ("a",)])
def test_a_missing_string_is_not_found(name):
    ag = psgs.Actiongram.from_strings({"a": "xy"})
    for look_up in (ag.index, ag.string, ag.displacements, ag.actuator):
        with pytest.raises(psgs.errors.NotFound, match="no string named"):
            look_up(name)


@pytest.mark.parametrize("names", [None, 3, object()])
def test_subset_refuses_names_that_are_no_sequence(names):
    with pytest.raises(ValidationError, match="names"):
        psgs.Actiongram.from_strings({"a": "xy"}).subset(names)


def test_parent_of_an_unhashable_actuator_is_none():
    ag = psgs.Actiongram.from_strings({"a.x": "xy"}, skeleton={"a": "b", "b": None})
    assert ag.parent([]) is None and ag.parent("a") == "b"


# ---------------------------------------------------------------- the model's values
@pytest.mark.parametrize("value", [None, 3, math.nan, True, object()])
def test_model_values_refuse_a_field_that_is_no_sequence(value):
    from psgs.model import PCGS, PSGS, Grammar, Nonterminal, Rule, as_word

    S = Nonterminal("S")
    g = Grammar("G", S, (Rule("r", S, ()),))
    for make, what in ((lambda: Rule("r", S, value), "right-hand side"),
                       (lambda: Grammar("G", S, value), "rules"),
                       (lambda: PSGS(value), "components"),
                       (lambda: PCGS(value), "components"),
                       (lambda: PSGS((g,), value), "sync"),
                       (lambda: as_word(value), "word")):
        with pytest.raises(ValidationError, match=what):
            make()


@pytest.mark.parametrize("method, length", [("filter", 16), ("filter", 32), ("search", 32)])
def test_language_refuses_an_option_accepts_does_not_take(gamma, method, length):
    # at length 16 there is no candidate tuple, so accepts never saw the misspelt budget
    with pytest.raises(ValidationError, match="max_state"):
        psgs.language(gamma, length, method=method, max_state=10)


@pytest.mark.parametrize("value", [-1, 0, None, 2.5, True])
def test_language_checks_a_membership_budget_before_any_candidate(gamma, value):
    with pytest.raises(ValidationError, match="max_states"):
        psgs.language(gamma, 16, method="filter", max_states=value)


def test_language_hands_on_the_options_accepts_takes(gamma):
    found = psgs.language(gamma, 32, method="filter", max_states=20_000, check_witness=False)
    assert found.complete and len(found) == 1


# ---------------------------------------------------------------- drawing, inducers by name
def test_parse_forest_refuses_a_derivation_of_another_system(gamma):
    from psgs.draw import parse_forest

    counting = psgs.load("counting")
    with pytest.raises(ValidationError, match="another system"):
        parse_forest(gamma, psgs.random_derivation(counting, 0))
    with pytest.raises(ValidationError, match="Derivation"):
        parse_forest(gamma, "S1 => a")
    assert parse_forest(gamma, psgs.random_derivation(gamma, 3)).components == ("G1", "G2",
                                                                                 "G3", "G4")


@pytest.mark.parametrize("system", [None, "paper_example", 3])
def test_sync_edges_refuses_what_is_no_system(system):
    from psgs.draw import sync_edges

    with pytest.raises(ValidationError, match="PSGS or a PCGS"):
        sync_edges(system)


@pytest.mark.parametrize("system", [None, "paper_example", 3, "grammar"])
def test_to_svg_and_draw_refuse_what_is_no_system(system, gamma, tmp_path):
    from psgs.draw import draw, to_svg

    system = gamma.components[0] if system == "grammar" else system
    with pytest.raises(ValidationError, match="PSGS or a PCGS"):
        to_svg(system)
    with pytest.raises(ValidationError, match="PSGS or a PCGS"):
        draw(system, tmp_path / "x.svg")


def test_to_svg_refuses_an_unknown_engine_as_draw_does(tmp_path):
    from psgs.draw import draw, to_svg

    counting = psgs.load("counting")
    for picture in (lambda: to_svg(counting, engine="dot"),
                    lambda: draw(counting, tmp_path / "x.svg", engine="dot")):
        with pytest.raises(ValidationError, match="engine must be auto, graphviz or matplotlib"):
            picture()
    assert not (tmp_path / "x.svg").exists()


@pytest.mark.parametrize("name", [None, 3, ["pal"], {"pal": 1}])
def test_get_refuses_a_name_that_is_no_str(name):
    from psgs.induce import get

    with pytest.raises(ValidationError, match="named by a str"):
        get(name)


def test_a_derivation_refuses_steps_of_another_system(gamma):
    from psgs.derivation import Derivation

    counting = psgs.random_derivation(psgs.load("counting"), 0)
    with pytest.raises(ValidationError, match="4 components"):
        Derivation(gamma, counting.steps)
    with pytest.raises(ValidationError, match="Step"):
        Derivation(gamma, [1])
    with pytest.raises(ValidationError, match="steps"):
        Derivation(gamma, None)
    with pytest.raises(ValidationError, match="PSGS or a PCGS"):
        Derivation(None, ())
    own = psgs.random_derivation(gamma, 1)
    assert Derivation(gamma, own.steps) == Derivation(gamma, own.steps, own.configurations)


@pytest.mark.parametrize("value", ["no", 2, [], math.nan])
def test_accepts_refuses_a_check_witness_that_is_no_bool(gamma, value):
    words = ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad"]
    with pytest.raises(ValidationError, match="check_witness"):
        psgs.accepts(gamma, words, check_witness=value)


@pytest.mark.parametrize("value", [0, 1, "numpy"])
def test_accepts_takes_a_check_witness_of_zero_one_or_a_numpy_bool(gamma, value):
    if value == "numpy":
        value = pytest.importorskip("numpy").bool_(True)
    words = ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad"]
    assert psgs.accepts(gamma, words, check_witness=value).answer == "yes"


@pytest.mark.parametrize("path", [None, 3, ["a.psgs"]])
def test_dump_refuses_a_path_that_is_no_path(gamma, path):
    with pytest.raises(ValidationError, match="path"):
        psgs.dump(gamma, path)


@pytest.mark.parametrize("kwargs, name", [
    ({"seconds": math.nan}, "seconds"), ({"seconds": -1}, "seconds"), ({"seconds": "5"}, "seconds"),
    ({"seconds": True}, "seconds"), ({"max_symbols": 0}, "max_symbols"),
    ({"max_symbols": 2.5}, "max_symbols"), ({"every": 0}, "every"), ({"every": None}, "every"),
])
def test_a_budget_refuses_bounds_it_could_not_keep(kwargs, name):
    # a NaN deadline compares false with every time: the search it bounds never stops
    from psgs.budget import Budget

    with pytest.raises(ValidationError, match=name):
        Budget(**kwargs)


@pytest.mark.parametrize("value", [None, "G1", 3])
def test_lower_level_exports_and_analyses_refuse_what_is_no_grammar_or_system(gamma, value):
    from psgs.analysis import moves, usable_rules
    from psgs.lark_export import grammar_to_lark

    with pytest.raises(ValidationError, match="Grammar"):
        grammar_to_lark(value)
    for analyse in (moves, usable_rules):
        with pytest.raises(ValidationError, match="PSGS"):
            analyse(value)
    with pytest.raises(ValidationError, match="PSGS"):
        usable_rules(psgs.load("pcgs_abc"))


def test_accepts_reads_a_pcgs_word_from_an_iterator():
    system = psgs.load("pcgs_abc")
    assert psgs.accepts(system, iter("abc")).answer == psgs.accepts(system, "abc").answer


def test_an_int_past_a_floats_range_is_no_overflow_error(gamma):
    # math.isfinite(10**400) and time.monotonic() + 10**400 raise OverflowError
    words = ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad"]
    with pytest.raises(ValidationError, match="max_errors"):
        psgs.nearest(gamma, words, max_errors=10 ** 400)
    assert psgs.accepts(gamma, words, max_seconds=10 ** 400).answer == "yes"
    assert psgs.language(gamma, 8, max_seconds=10 ** 400).complete


@pytest.mark.parametrize("key", ["insert", "delete", "substitute"])
def test_an_edit_cost_past_a_floats_range_is_a_validation_error(gamma, key):
    words = ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbcaX"]
    with pytest.raises(ValidationError, match=key):
        psgs.nearest(gamma, words, costs={key: 10 ** 400})


@pytest.mark.parametrize("rest", [0, 1.5, ["_"], ""])
def test_to_events_refuses_a_rest_symbol_that_is_no_symbol(rest):
    # a number never equals a symbol: every rest was kept, silently
    ag = psgs.Actiongram.from_events([("s", 0, 1, "a"), ("s", 2, 1, "b")])
    with pytest.raises(ValidationError, match="rest_symbol"):
        ag.to_events(rest)
    assert len(ag.to_events("_")) == 2 and len(ag.to_events()) == 3


@pytest.mark.parametrize("name", [None, 3, ["arm.x"]])
def test_default_actuator_refuses_a_name_that_is_no_str(name):
    from psgs.actiongram import default_actuator

    with pytest.raises(ValidationError, match="name"):
        default_actuator(name)


def test_bounds_take_a_numpy_integer_as_the_whole_number_it_is():
    import numpy as np

    from psgs import accepts, language, load
    from psgs.derivation import random_derivation

    gamma = load("paper_example")
    a = random_derivation(gamma, 3, max_steps=np.int64(5))
    assert a == random_derivation(gamma, 3, max_steps=5)
    counting = load("counting")
    word = sorted(language(counting, 3))[0]
    assert accepts(counting, word, max_states=np.int32(1000)).answer == \
        accepts(counting, word, max_states=1000).answer
    assert language(counting, np.int64(3)) == language(counting, 3)
    with pytest.raises(ValidationError, match="max_steps"):
        random_derivation(gamma, 3, max_steps=np.float64(5.0))


def test_seconds_costs_and_positions_take_numpy_numbers_as_the_python_ones():
    # a budget, an edit cost or an occurrence read from an array was refused (max_seconds,
    # max_errors, costs: "must be a positive number, not np.int64(5)"; positions: "an index")
    import dataclasses

    import numpy as np

    from psgs import accepts, language, load, nearest
    from psgs.derivation import apply_tuple, initial_configuration
    from psgs.membership.costs import EditCosts

    counting = load("counting")
    assert accepts(counting, ["aa", "bb"], max_seconds=np.int64(5)).answer == "yes"
    assert language(counting, 4, max_seconds=np.int32(5)) == language(counting, 4)
    far = nearest(counting, ["aa", "b"], max_seconds=np.int64(5), max_errors=np.int64(3),
                  costs={"insert": np.int64(2), "delete": {"a": np.float32(1.5)}})
    near = nearest(counting, ["aa", "b"], max_errors=3, costs={"insert": 2, "delete": {"a": 1.5}})
    assert (far.distance, far.exact) == (near.distance, near.exact) == (1.5, True)
    costs = EditCosts(insert=np.int64(2), pairs={("a", "b"): np.uint8(1)})
    assert type(costs.insert) is int and type(next(iter(costs.pairs.values()))) is int
    single = dataclasses.replace(counting, mode="single")
    start = initial_configuration(single)
    assert apply_tuple(single, start, ("p1", "q1"), positions=np.array([0, 0])) == \
        apply_tuple(single, start, ("p1", "q1"), positions=[0, 0])
    with pytest.raises(ValidationError, match="max_seconds"):
        accepts(counting, ["a", "b"], max_seconds=np.bool_(True))
