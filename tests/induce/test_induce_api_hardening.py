"""Bad arguments to psgs.induce: one ValidationError naming the parameter, never a TypeError
from numpy or a draw that runs until memory does."""

from __future__ import annotations

import math

import pytest

from psgs.errors import ValidationError
from psgs.induce.synthetic import generate

_SIZES = ("strings", "alphabet", "patterned", "templates", "template_length", "copies", "gap")


@pytest.mark.parametrize("value", [None, "3", 2.5, math.nan, math.inf, True, -1])
@pytest.mark.parametrize("name", _SIZES)
def test_generate_refuses_a_size_that_is_no_whole_number(name, value):
    with pytest.raises(ValidationError, match=name):
        generate(0, **{name: value})


@pytest.mark.parametrize("value", [None, "0.1", math.nan, True, -0.1, 1.5])
def test_generate_refuses_a_noise_that_is_no_share(value):
    with pytest.raises(ValidationError, match="noise"):
        generate(0, value)


@pytest.mark.parametrize("name", ["alphabet", "templates", "template_length", "copies",
                                  "strings", "gap"])
def test_generate_refuses_sizes_it_could_not_hold_before_drawing(name):
    # each of these once ran until memory ran out (or numpy overflowed) instead of refusing
    with pytest.raises(ValidationError, match="MAX_SYMBOLS"):
        generate(0, **{name: 10 ** 12})


@pytest.mark.parametrize("name", ["irregular_gaps", "unequal_lengths"])
def test_generate_refuses_a_flag_that_is_no_bool(name):
    for value in ("yes", 2, 0.5):
        with pytest.raises(ValidationError, match=name):
            generate(0, **{name: value})
    # 0 and 1 were read as flags before the check, and still are
    assert generate(0, **{name: 1}) == generate(0, **{name: True})


def test_generate_takes_numpy_sizes_as_before():
    np = pytest.importorskip("numpy")
    assert generate(1, np.float64(0.1), copies=np.int64(10)) == generate(1, 0.1, copies=10)


# ---------------------------------------------------------------- noise_sweep
@pytest.mark.parametrize("kwargs, name", [
    ({"trials": 0}, "trials"), ({"trials": -2}, "trials"), ({"trials": None}, "trials"),
    ({"trials": 2.5}, "trials"), ({"trials": True}, "trials"),
    ({"levels": 0.1}, "levels"), ({"levels": "0.1"}, "levels"), ({"levels": None}, "levels"),
    ({"levels": ["0.1"]}, "noise level"), ({"levels": [math.nan]}, "noise level"),
    ({"levels": [True]}, "noise level"), ({"levels": [1.5]}, "noise level"),
    ({"inducers": "sequential"}, "inducers"), ({"inducers": None}, "inducers"),
    ({"inducers": ("sequential", "pal", "sequential")}, "names 'sequential' twice"),
    ({"params": 3}, "params"), ({"params": {"sequential": 2}}, "params"),
    ({"variant": "random"}, "variant"), ({"seed": None}, "seed"), ({"seed": "0"}, "seed"),
    ({"jobs": 0}, "jobs"), ({"jobs": None}, "jobs"), ({"progress": 3}, "progress"),
])
def test_noise_sweep_refuses_bad_arguments_before_any_trial(kwargs, name):
    from psgs.induce.sweep import noise_sweep

    arguments = {"levels": [0.0], "trials": 1, "inducers": ("sequential",)} | kwargs
    levels, trials = arguments.pop("levels"), arguments.pop("trials")
    with pytest.raises(ValidationError, match=name):
        noise_sweep(levels, trials, **arguments)


def test_noise_sweep_takes_a_numpy_seed_and_a_generator_of_levels():
    np = pytest.importorskip("numpy")
    from psgs.induce.sweep import noise_sweep

    rows = noise_sweep((x for x in [0.0]), 1, inducers=["sequential"], seed=np.int64(2))
    assert [(r.inducer, r.noise, r.trials) for r in rows] == [("sequential", 0.0, 1)]
    # trials and jobs counted in numpy, as a script reading them from an array has them
    again = noise_sweep([0.0], np.int64(1), inducers=["sequential"], seed=2, jobs=np.int32(1))
    assert [(r.inducer, r.noise, r.trials, r.successes) for r in again] == \
        [(r.inducer, r.noise, r.trials, r.successes) for r in rows]  # all but the seconds


# ---------------------------------------------------------------- build_system
@pytest.mark.parametrize("patterns", [None, 3, "arm", [], [("arm",)], [("arm", 3)],
                                      ["arm"], [("arm", ("a",), "extra")]])
def test_build_system_refuses_what_is_no_sequence_of_pairs(patterns):
    from psgs.induce.base import build_system

    with pytest.raises(ValidationError, match="pattern"):
        build_system(patterns)


def test_build_system_reads_a_pattern_from_any_iterable():
    from psgs.induce.base import build_system

    assert build_system([("arm", iter("ab"))]) == build_system([("arm", ("a", "b"))])


@pytest.mark.parametrize("truth", [None, "s01", generate(seed=1).actiongram])
def test_success_and_vote_margin_refuse_what_is_no_synthetic_case(truth):
    from psgs.induce import Sequential
    from psgs.induce.synthetic import success, vote_margin

    case = generate(seed=1)
    with pytest.raises(ValidationError, match="Synthetic"):
        success(Sequential().induce(case.actiongram), truth)
    with pytest.raises(ValidationError, match="Synthetic"):
        vote_margin(truth)


# ---------------------------------------------------------------- edge actiongrams
@pytest.mark.parametrize("performances", [1, 2])
@pytest.mark.parametrize("name", ["pal", "pal_motion", "pal_content", "sequential"])
def test_an_actiongram_of_no_string_learns_nothing_without_an_error(name, performances):
    from psgs import Actiongram
    from psgs.induce import get

    empty = Actiongram.from_strings({})
    data = empty if performances == 1 else [empty] * performances
    if name == "pal_content" and performances > 1:
        return  # the paper's learner reads one actiongram
    found = get(name).induce(data)
    assert found.components == () and found.system is None


@pytest.mark.parametrize("name", ["min_copies", "alpha", "max_pattern"])
def test_a_parameter_past_a_floats_range_is_a_validation_error(name):
    from psgs.induce import PAL

    with pytest.raises(ValidationError, match=name):
        PAL(**{name: 10 ** 400})
    with pytest.raises(ValidationError, match="copies"):
        generate(0, copies=10 ** 400)


# ---------------------------------------------------------------- locate
@pytest.mark.parametrize("method", ["joints", "pattern"])
@pytest.mark.parametrize("name, value", [
    ("threshold", None), ("threshold", "x"), ("threshold", math.nan), ("threshold", math.inf),
    ("threshold", 2.0), ("threshold", True), ("threshold", 10 ** 400),
    ("min_speed", "x"), ("min_speed", math.nan), ("min_speed", -1), ("min_speed", None),
    ("min_share", "x"), ("min_share", math.nan), ("min_share", -1), ("min_share", 2.0),
])
def test_locate_checks_every_level_whichever_method_reads_it(method, name, value):
    # threshold is read by the pattern method only, min_share by the joints method only:
    # a bad value was ignored by the other, or a TypeError deep in numpy
    from psgs import Actiongram
    from psgs.induce import PAL, locate

    ag = Actiongram.from_strings({"a": "abababab", "b": "abababab"})
    with pytest.raises(ValidationError, match=name):
        locate(PAL().induce(ag), ag, method=method, **{name: value})


@pytest.mark.parametrize("source", [None, 3, "min_copies", [("min_copies",)]])
def test_conf_pick_refuses_what_is_no_table_or_mapping(source):
    from psgs.induce.pal.conf import ContentConf

    with pytest.raises(ValidationError, match="pick"):
        ContentConf.pick(source)


def test_conf_pick_and_noise_sweep_read_name_value_pairs_as_dict_does(monkeypatch):
    from psgs.induce import sweep
    from psgs.induce.pal.conf import ContentConf

    wanted = {"min_copies": 4}
    assert ContentConf.pick([("min_copies", 4)]) == ContentConf.pick(wanted) == \
        ContentConf.pick(wanted.items())
    asked = []  # what each trial's actiongram was drawn with
    drawn = sweep.generate
    monkeypatch.setattr(sweep, "generate", lambda **kw: asked.append(kw) or drawn(**kw))
    pairs = (("strings", 6), ("copies", 3))
    for variant in (list(pairs), iter(pairs), dict(pairs)):  # an iterator is read once
        asked.clear()
        sweep.noise_sweep([0.0], 1, inducers=["sequential"], variant=variant)
        assert [(kw["strings"], kw["copies"]) for kw in asked] == [(6, 3)], variant


def test_the_papers_points_are_read_only():
    from psgs.induce.synthetic import PAPER_POINTS

    with pytest.raises(TypeError):
        PAPER_POINTS[0.0] = 0.5  # type: ignore[index]
    assert PAPER_POINTS[0.10] == 0.96 and list(PAPER_POINTS) == [0.0, 0.07, 0.10]


def test_noise_sweep_takes_numpy_levels_of_any_float_width():
    np = pytest.importorskip("numpy")
    from psgs.induce.sweep import noise_sweep

    rows = noise_sweep(np.zeros(1, dtype=np.float32), 1, inducers=("sequential",))
    assert [r.noise for r in rows] == [0.0]


def test_numpy_scalars_are_numbers_to_generate_and_locate():
    np = pytest.importorskip("numpy")
    from psgs import Actiongram
    from psgs.induce import PAL, locate

    assert generate(1, np.float32(0.25)) == generate(1, float(np.float32(0.25)))
    ag = Actiongram.from_strings({"a": "abababab", "b": "abababab"})
    learned = PAL().induce(ag)
    assert locate(learned, ag, method="pattern", threshold=np.float32(0.5), min_speed=np.int64(0),
                  min_share=np.float32(0.4)) == locate(learned, ag, method="pattern",
                                                       threshold=0.5, min_speed=0)


def test_pal_stops_voting_once_a_round_leaves_every_copy_where_it_was(monkeypatch):
    # rounds=10**6 voted a million times over copies that no longer moved (hours of CPU)
    from psgs.induce import PAL
    from psgs.induce.pal import content
    from psgs.induce.synthetic import generate

    calls = []
    pooled = content.pooled_windows
    monkeypatch.setattr(content, "pooled_windows", lambda *a: calls.append(1) or pooled(*a))
    actiongram = generate(3, 0.2).actiongram
    many = PAL(rounds=10**6).induce(actiongram)
    assert len(calls) < 100
    assert many.occurrences == PAL(rounds=2).induce(actiongram).occurrences == \
        PAL(rounds=40).induce(actiongram).occurrences


@pytest.mark.parametrize("name", ["pal", "sequential", "pal_content", "pal_motion"])
def test_an_inducer_takes_numpy_numbers_as_the_numbers_they_hold(name):
    # np.int64(3) was refused as "must be an integer, not np.int64(3)" (np.float32 likewise),
    # though generate, noise_sweep and locate take them: a grid of values from np.arange
    np = pytest.importorskip("numpy")
    from psgs.induce import get

    plain = get(name)
    given = {k: (np.int64(v) if isinstance(v, int) else np.float64(v))
             for k, v in plain.get_params().items()
             if isinstance(v, (int, float)) and not isinstance(v, bool)}
    learner = get(name, **given)
    assert learner.get_params() == plain.get_params()
    assert all(type(learner.get_params()[k]) in (int, float) for k in given)
    if "alpha" in given:
        assert get(name, alpha=np.float32(0.5)).get_params()["alpha"] == 0.5
    with pytest.raises(ValidationError, match="must be an integer, not 2.5"):
        get(name, **{next(k for k, v in given.items() if isinstance(v, np.int64)):
                     np.float32(2.5)})


def test_noise_sweep_does_not_make_every_seed_at_once(monkeypatch):
    """10**11 trials made a list of every seed first (out of memory before any trial); each
    cell is handed its seeds as a range."""
    from psgs.induce import sweep

    handed = []

    def batch(cell):
        name, _, noise, seeds, _ = cell
        handed.append(seeds)
        return name, noise, len(seeds), 0, 0.0, 0.0

    monkeypatch.setattr(sweep, "_trial_batch", batch)
    rows = sweep.noise_sweep([0.0], 10**12, inducers=("pal",), seed=5, jobs=1)
    assert handed == [range(5, 5 + 10**12)] and rows[0].trials == 10**12
