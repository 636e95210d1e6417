"""describe, recognise and parse refuse a wrong argument with one DescriptionError naming it.

Before, a motion that was None reached the feature code (AttributeError), a rank given as a
string numpy (TypeError), and a level of 2, a hop of 0 or a NaN switch cost gave an answer
without a word.
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from kinetology import Motion, synthetic_motion
from praxicon.description import DescriptionError, describe
from praxicon.parsing import describe_windows, parse
from praxicon.recognition import recognise, recognise_many


@pytest.fixture(scope="module")
def takes():
    return {"a": [synthetic_motion(2, (0,), seed=s) for s in (1, 2)],
            "b": [synthetic_motion(2, (1,), seed=s) for s in (3, 4)]}


@pytest.fixture(scope="module")
def described(takes):
    return describe(takes)


@pytest.fixture(scope="module")
def windows():
    return describe_windows({"a": [synthetic_motion(2, (0,), seed=s, repetitions=4) for s in (1, 2)],
                             "b": [synthetic_motion(2, (1,), seed=s, repetitions=4) for s in (3, 4)]})


@pytest.mark.parametrize("make, match", [
    (lambda t: None, "takes must map each action's name"),
    (lambda t: list(t["a"]), "takes must map each action's name"),
    (lambda t: {"a": [None], "b": t["b"]}, "must be kinetology.Motion values"),
    (lambda t: {"a": t["a"][0], "b": t["b"]}, "must be a sequence of motions"),
    (lambda t: {1: t["a"], 2: t["b"]}, "an action's name must be a string"),
])
def test_describe_checks_its_takes(takes, make, match):
    with pytest.raises(DescriptionError, match=match):
        describe(make(takes))


@pytest.mark.parametrize("options, match", [
    ({"rank": -1}, "rank must be an integer"),
    ({"rank": 1.5}, "rank must be an integer"),
    ({"rank": "16"}, "rank must be an integer"),
    ({"rank": True}, "rank must be an integer"),
    ({"level": 2.0}, "level must be a number above 0 and below 1"),     # was accepted
    ({"level": 0.0}, "level must be a number above 0"),                 # was a division by 0
    ({"level": float("nan")}, "level must be a number"),
    ({"level": "0.01"}, "level must be a number"),
    ({"choose": "no"}, "choose must be True or False"),                 # "no" was true
])
def test_describe_checks_its_options(takes, options, match):
    with pytest.raises(DescriptionError, match=match):
        describe(takes, **options)


def test_describe_reads_a_generator_of_takes_once(takes):
    from_lists = describe(takes, choose=False)
    from_generators = describe({n: (m for m in ms) for n, ms in takes.items()}, choose=False)
    assert from_generators == from_lists


@pytest.mark.parametrize("motion", [None, np.zeros((10, 2)), 5])
def test_recognise_and_parse_refuse_what_is_no_motion(described, windows, motion):
    with pytest.raises(DescriptionError, match="a motion must be a kinetology.Motion"):
        recognise(described, motion)
    with pytest.raises(DescriptionError, match="a motion must be a kinetology.Motion"):
        parse(windows, motion)


@pytest.mark.parametrize("motions", [None, "motion"])
def test_recognise_many_wants_a_sequence_of_motions(described, motions):
    motions = synthetic_motion(2, (0,), seed=9) if motions == "motion" else motions
    with pytest.raises(DescriptionError, match="motions must be a sequence of motions"):
        recognise_many(described, motions)


@pytest.mark.parametrize("explain", [-1, 1.5, "3", True])
def test_recognise_checks_explain(described, explain):
    with pytest.raises(DescriptionError, match="explain must be an integer"):
        recognise(described, synthetic_motion(2, (0,), seed=9), explain=explain)


def test_recognise_explains_every_action_when_explain_is_none(described):
    motion = synthetic_motion(2, (0,), seed=9)
    every = recognise(described, motion, explain=None)     # order[:None] before the check
    assert every == recognise(described, motion, explain=len(described.actions))
    assert len(every.reasons) == len(described.actions) > len(recognise(described, motion,
                                                                        explain=1).reasons)


def test_describe_takes_a_numpy_bool(takes):
    assert describe(takes, choose=np.bool_(False)) == describe(takes, choose=False)


def recording() -> Motion:
    a, b = synthetic_motion(2, (0,), seed=7), synthetic_motion(2, (1,), seed=8)
    return Motion(np.concatenate([a.values, b.values]), a.channels, a.frame_rate)


@pytest.mark.parametrize("options, match", [
    ({"hop": 0.0}, "hop must be a finite number above 0"),    # was a window every frame
    ({"hop": -1.0}, "hop must be a finite number above 0"),
    ({"hop": float("nan")}, "hop must be a finite number"),
    ({"hop": "0.25"}, "hop must be a finite number"),
    ({"switch": -1.0}, "switch must be a number at least 0"),  # was a timeline of nonsense
    ({"switch": float("nan")}, "switch must be a number at least 0"),
    ({"switch": "10"}, "switch must be a number"),
    ({"own": None}, "own must be a sequence of feature kinds"),
    ({"own": "drift"}, "own must be a sequence of feature kinds"),
])
def test_parse_checks_its_options(windows, options, match):
    with pytest.raises(DescriptionError, match=match):
        parse(windows, recording(), **options)


def test_parse_with_an_infinite_switch_cost_is_one_action(windows):
    inf = float("inf")
    alone = parse(windows, recording(), switch=inf, support=0.0, unfit=inf).spans
    assert len({s.action for s in alone}) == 1
    # the check of the spans may answer stretches of that one action none of these, no other
    assert {s.action for s in parse(windows, recording(), switch=inf).spans} <= \
        {alone[0].action, None}


@pytest.mark.parametrize("options, match", [
    ({"hop": 0.0}, "hop must be a finite number above 0"),
    ({"window": True}, "a window of True seconds"),            # was a window of 1 s
])
def test_describe_windows_checks_its_options(takes, options, match):
    with pytest.raises(DescriptionError, match=match):
        describe_windows(takes, **options)


def test_recognise_and_parse_give_the_same_answer_twice(described, windows):
    motion = synthetic_motion(2, (0,), seed=9)
    assert recognise(described, motion) == recognise(described, motion)
    assert parse(windows, recording()) == parse(windows, recording())


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    from praxicon import build, read_dataset
    from praxicon_fixtures import write_manifest

    data = tmp_path_factory.mktemp("data")
    manifest = write_manifest(data, {"wave": [1, 2, 3], "step": [4, 5, 6]})
    return build(read_dataset(manifest), data / "px", progress=False).praxicon


@pytest.mark.parametrize("repeat", [10**9, 10**5, 1001, True, 0, 1.5, "2"])
def test_generate_refuses_a_repeat_out_of_range_at_once(built, repeat):
    from praxicon.generation import MAX_REPEAT, generate

    with pytest.raises(ValueError, match=f"repeat must be a whole number from 1 to {MAX_REPEAT}"):
        generate(built, built.names[0], repeat=repeat)   # 10**9 never returned, True was 1


def test_generate_gives_the_same_motion_twice(built):
    from praxicon.generation import generate

    first = generate(built, built.names[0], repeat=2)
    assert first.motion.values.tobytes() == \
        generate(built, built.names[0], repeat=2).motion.values.tobytes()


def test_generate_motion_refuses_what_is_no_record():
    from praxicon.generation import generate_motion

    with pytest.raises(ValueError, match="record must be an ActionRecord"):
        generate_motion(None, 2)


@pytest.mark.parametrize("options", [
    {"inducer": 5}, {"min_performances": -1}, {"min_performances": "2"},
    {"min_performances": True}, {"segmentation": (("smoothing",),)}, {"params": "ab"},
])
def test_settings_check_their_fields(options):
    from praxicon import Settings
    from psgs.errors import ValidationError

    (name, value), = options.items()
    with pytest.raises(ValidationError, match=f"^settings need (an )?{name}.* not "
                                              f"{re.escape(repr(value))}$"):
        Settings(**options)


def test_settings_take_pairs_in_a_list_a_dict_and_numpy_counts():
    import json

    from praxicon import Settings

    made = Settings.make(params={"k": 3, "a": 1}, min_performances=3)
    for given in (Settings("pal", [("a", 1), ("k", 3)], (), 3),        # refused by the check
                  Settings("pal", [["a", 1], ["k", 3]], [], 3),
                  Settings("pal", {"k": 3, "a": 1}, {}, 3),             # copied, not shared
                  Settings.make(params={"k": 3, "a": 1}, min_performances=np.int64(3))):
        assert given == made and hash(given) == hash(made)
        assert json.dumps(given.to_dict()) == json.dumps(made.to_dict())
        assert type(given.min_performances) is int and given.params == (("a", 1), ("k", 3))


def test_settings_of_a_folder_with_no_performances_needed_are_the_folders_error():
    from praxicon import PraxiconError, Settings

    with pytest.raises(PraxiconError, match="index.json: settings need"):
        Settings.from_dict({"inducer": "pal", "params": {}, "segmentation": {},
                            "min_performances": 0}, "index.json")


@pytest.mark.parametrize("folder", [None, 5])
def test_load_and_dump_refuse_a_folder_that_is_no_path(built, folder):
    from praxicon import PraxiconError, dump, load

    with pytest.raises(PraxiconError, match="a praxicon folder is a path"):
        load(folder)
    with pytest.raises(PraxiconError, match="a praxicon folder is a path"):
        dump(built, folder)


def test_load_and_dump_refuse_an_empty_folder_name(built, tmp_path, monkeypatch):
    """'' is the current folder to Path: dump wrote the praxicon's files into it."""
    from praxicon import PraxiconError, dump, load

    monkeypatch.chdir(tmp_path)
    for call in (lambda: load(""), lambda: dump(built, "")):
        with pytest.raises(PraxiconError, match="a praxicon folder's name is empty"):
            call()
    assert not any(tmp_path.iterdir())


def test_dump_refuses_what_is_no_praxicon(tmp_path):
    from praxicon import PraxiconError, dump

    with pytest.raises(PraxiconError, match="dump writes a Praxicon"):
        dump(None, tmp_path / "px")


@pytest.mark.parametrize("options, match", [
    ({"min_length": 0}, "min_length must be a whole number of at least 1"),   # was accepted
    ({"min_length": -1}, "min_length must be a whole number"),   # patterns of 7 kinetemes
    ({"min_length": "4"}, "min_length must be a whole number"),
    ({"min_actions": True}, "min_actions must be a whole number"),
])
def test_shared_patterns_checks_its_counts(built, options, match):
    from praxicon import shared_patterns
    from psgs.errors import ValidationError

    with pytest.raises(ValidationError, match=match):
        shared_patterns(built, **options)


def test_shared_patterns_refuses_what_is_no_record():
    from praxicon import shared_patterns
    from psgs.errors import ValidationError

    with pytest.raises(ValidationError, match="^shared_patterns reads a Praxicon or its "
                                              "ActionRecords, not None$"):
        shared_patterns(None)
    with pytest.raises(ValidationError, match="ActionRecords, not one holding 'x'$"):
        shared_patterns(["x"])


@pytest.mark.parametrize("actions, out, match", [
    (None, "px", r"^build learns a list of praxicon.Action \(read_dataset makes one\), not None$"),
    ("abc", "px", "build learns a list .*, not one holding 'a'$"),  # an AttributeError before
    ([], None, "out must be a folder's path"),
])
def test_build_checks_its_actions_and_folder(tmp_path, actions, out, match):
    from praxicon import build
    from psgs.errors import ValidationError

    with pytest.raises(ValidationError, match=match):
        build(actions, tmp_path / out if isinstance(out, str) else out, progress=False)


@pytest.mark.parametrize("workers", [-1, 0, "2", True])
def test_executor_for_checks_workers(workers):
    from praxicon import executor_for
    from psgs.errors import ValidationError

    with pytest.raises(ValidationError, match="workers must be a whole number"):
        executor_for(workers)


def test_numpy_integers_are_whole_numbers(built, tmp_path):
    from praxicon import executor_for, shared_patterns

    assert executor_for(np.int64(1))[0] is None                 # refused by the check
    pool, close = executor_for(np.int64(2))
    close()
    assert pool is not None
    assert shared_patterns(built, min_length=np.int64(2), min_actions=np.int64(1)) == \
        shared_patterns(built, min_length=2, min_actions=1)


def test_read_dataset_checks_its_path_and_grouping(tmp_path):
    from praxicon import DatasetError, read_dataset

    with pytest.raises(DatasetError, match="a dataset is a folder's or a manifest's path"):
        read_dataset(None)
    with pytest.raises(DatasetError, match="--group-by must be"):
        read_dataset(tmp_path, group_by=5)


def test_actuator_matrix_refuses_what_is_no_record():
    from praxicon import PraxiconError, actuator_matrix

    with pytest.raises(PraxiconError, match="reads a Praxicon or its ActionRecords, not None$"):
        actuator_matrix(None)
    with pytest.raises(PraxiconError, match="ActionRecords, not one holding 5$"):
        actuator_matrix(iter([5]))


def test_generate_refuses_a_plot_that_is_no_path(built):
    from praxicon.generation import generate

    with pytest.raises(ValueError, match="a picture is written to a file's path"):
        generate(built, built.names[0], repeat=1, plot=5)


def test_a_take_changed_in_place_is_read_again(tmp_path):
    """A second build in one process reads a take rewritten since the first, as a new process
    would: the cache of read takes was keyed by the path alone."""
    from kinetology import write_bvh
    from praxicon import build, learn, read_dataset
    from praxicon_fixtures import take, write_manifest

    manifest = write_manifest(tmp_path, {"wave": [1, 2, 3]})
    first = build(read_dataset(manifest), tmp_path / "px1", progress=False).praxicon
    write_bvh(take(9, seconds=4.0), tmp_path / "wave_1.bvh")
    again = build(read_dataset(manifest), tmp_path / "px2", progress=False).praxicon
    for cached in (getattr(learn, "_read_file", None), learn._read):   # as a new process
        getattr(cached, "cache_clear", lambda: None)()
    fresh = build(read_dataset(manifest), tmp_path / "px3", progress=False).praxicon
    name = first.names[0]
    assert again[name].joints == fresh[name].joints != first[name].joints


@pytest.mark.parametrize("args, match", [
    ((None,), "file must be a path"), (("x.bvh", "0", "1"), "start must be a number"),
    (("x.bvh", 5.0, 1.0), "start must come before its stop, not 5.0 and 1.0"),
    (("x.bvh", float("nan"), 1.0), "start must be a number of seconds, 0 or more, or None, "
                                   "not nan"),
    (("x.bvh", True, 2.0), "start must be"), (("x.bvh", 0.0, -1), "stop must be"),
    (("x.bvh", None, None, 5), "label must be a string or None, not 5"),
    ((b"x.bvh",), "file must be a path"),
])
def test_a_performance_made_in_python_is_checked(args, match):
    from praxicon import DatasetError, Performance

    with pytest.raises(DatasetError, match="^a performance's " + match):
        Performance(*args)


def test_a_performance_takes_a_pathlib_path_as_its_string(tmp_path):
    from pathlib import Path

    from praxicon import Action, Performance, Settings
    from praxicon.learn import input_key

    given = Performance(Path("takes") / "a.bvh", 0.5, 2.0)   # refused by the check
    assert given == Performance("takes/a.bvh", 0.5, 2.0) and type(given.file) is str
    settings = Settings.make()
    assert input_key(Action("a", "d", "a", performances=(given,)), settings) == \
        input_key(Action("a", "d", "a", performances=(Performance("takes/a.bvh", 0.5, 2.0),)),
                  settings)


@pytest.mark.parametrize("args, options, match", [
    ((None, "d", "a"), {}, "an action's name must be a string, not None"),
    (("a", "d", "a", 5), {}, "an action's style must be a string, not 5"),
    (("a", "d", "a"), {"performances": ["x.bvh"]}, "an action's performances must be a tuple"),
    (("a", "d", "a"), {"performances": "x.bvh"}, "an action's performances must be a tuple"),
    (("a", "d", "a"), {"problems": "p"}, "an action's problems must be a tuple"),
])
def test_an_action_made_in_python_is_checked(args, options, match):
    from praxicon import Action, DatasetError

    with pytest.raises(DatasetError, match=match):
        Action(*args, **options)


def test_an_action_error_shows_a_short_value():
    from praxicon import Action, DatasetError, Performance

    many = [Performance(f"take_{i:03d}.bvh", 0.0, 1.0) for i in range(200)]
    with pytest.raises(DatasetError) as error:
        Action("a", "d", "a", performances=many + ["x.bvh"])
    assert len(str(error.value)) < 200               # the whole repr: 14,660 characters
    with pytest.raises(DatasetError) as error:
        Action(None, "d", "a", performances=many)
    assert str(error.value) == "an action's name must be a string, not None"


def test_an_action_keeps_a_copy_of_the_list_it_is_given():
    from praxicon import Action, Performance

    given = [Performance("x.bvh")]
    action = Action("a", "d", "a", performances=given, problems=["p"])
    given.append(Performance("y.bvh"))  # the caller's list is the caller's
    assert action.performances == (Performance("x.bvh"),) and action.problems == ("p",)


def test_learn_action_checks_its_arguments():
    from praxicon import Action, Settings, learn_action
    from psgs.errors import ValidationError

    with pytest.raises(ValidationError, match="learn_action learns an Action with Settings"):
        learn_action(None, Settings())
    with pytest.raises(ValidationError, match="learn_action learns an Action with Settings"):
        learn_action(Action("a", "d", "a"), None)


@pytest.mark.parametrize("most", [-1, 0, "5", True])   # -1 left the last pattern out
def test_draw_shared_patterns_checks_most(built, tmp_path, most):
    pytest.importorskip("matplotlib")
    from praxicon import draw_shared_patterns

    with pytest.raises(ValueError, match="most must be a whole number of at least 1"):
        draw_shared_patterns(built, tmp_path / "s.png", most=most)


def test_a_drawing_refuses_a_path_that_is_no_path(built):
    pytest.importorskip("matplotlib")
    from praxicon import draw_actuator_matrix

    with pytest.raises(ValueError, match="a picture is written to a file's path"):
        draw_actuator_matrix(built, 5)


def test_the_drawings_take_numpy_integers(built, tmp_path):
    pytest.importorskip("matplotlib")
    from praxicon import draw_praxicon, draw_shared_patterns

    def outcome(draw, *args, **options):
        try:
            return draw(*args, **options).name
        except ValueError as exc:
            return str(exc)

    assert outcome(draw_shared_patterns, built, tmp_path / "a.png", most=np.int64(5)) == \
        outcome(draw_shared_patterns, built, tmp_path / "a.png", most=5)
    with pytest.raises(Exception) as numpy_count:
        draw_praxicon(tmp_path / "none", tmp_path / "all", workers=np.int64(1))
    with pytest.raises(Exception) as int_count:
        draw_praxicon(tmp_path / "none", tmp_path / "all", workers=1)
    assert str(numpy_count.value) == str(int_count.value)      # the folder's error, not workers


def test_draw_praxicon_checks_workers(built, tmp_path):
    pytest.importorskip("matplotlib")
    from praxicon import draw_praxicon

    with pytest.raises(ValueError, match="workers must be at least 1, not '2'"):
        draw_praxicon(built, tmp_path / "all", workers="2")


def test_parse_holds_one_window_at_a_time():
    """Windows a frame apart were all made before any was read: window/hop copies of the
    recording at once (240 for 2-second windows at 120 fps)."""
    import time
    import tracemalloc

    takes = {"a": [synthetic_motion(20, (0, 1), seed=s, repetitions=4) for s in (1, 2)],
             "b": [synthetic_motion(20, (2, 3), seed=s, repetitions=4) for s in (3, 4)]}
    # 612 frames, 372 windows: both sides of the bound grow with the windows' count, so a
    # short recording tells the two apart as a long one does (14 repetitions, 1,683 frames,
    # took four times as long; the peak was 4 % of all_windows there, 8 % here)
    recording = synthetic_motion(20, (0, 1), seed=7, repetitions=5)
    windows = describe_windows(takes)
    tracemalloc.start()
    try:
        began = time.perf_counter()
        parse(windows, recording, hop=1 / 120)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    size = int(round(windows.spread.window * recording.frame_rate))
    all_windows = (recording.frames - size) * size * len(recording.channels) * 8
    # made at once they alone were all_windows bytes (the peak was 1.4 times that, 1.05 at
    # this length); one at a time the peak is 8 % of it here (4 % at 14 repetitions)
    assert peak < 0.75 * all_windows, (peak, all_windows, time.perf_counter() - began)


@pytest.mark.parametrize("options, match", [
    ({"datasets": "abc"}, "^datasets must be a list of names, not 'abc'$"),  # a, b and c
    ({"settings": "pal"}, "^settings must be a Settings, not 'pal'$"),  # an AttributeError
    ({"executor": "x"}, "executor must be an Executor"),
])
def test_build_checks_its_options(tmp_path, options, match):
    from praxicon import build
    from psgs.errors import ValidationError

    with pytest.raises(ValidationError, match=match):
        build([], tmp_path / "px", progress=False, **options)


def test_a_three_frame_motion_has_a_shape_and_no_nan_feature():
    import warnings

    from kinetology import Motion, synthetic_motion
    from praxicon.features import motion_features

    m = synthetic_motion(2, (0,), repetitions=1, seed=1)
    short = Motion(m.values[:3], m.channels, m.frame_rate, m.skeleton, m.source)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # numpy's "Mean of empty slice" on a quarter of no frame
        names, values = motion_features(short)
    assert np.isfinite(values).all()
    shape = [v for n, v in zip(names, values) if n.startswith("j0.rx:shape")]
    x = dict(zip(names, values))
    assert len(shape) == 4 and x["j0.rx:shape3"] == x["j0.rx:shape2"]  # the last frame twice



def test_generate_refuses_a_progress_that_cannot_be_called_before_any_work(built):
    from praxicon.generation import generate

    with pytest.raises(ValueError, match="progress must be callable"):
        generate(built, built.names[0], repeat=1, progress="x")  # a TypeError after a channel
    # a numpy integer is a count of copies, as an int is
    np_repeat = generate(built, built.names[0], repeat=np.int64(2), progress=lambda *a: None)
    assert np_repeat.motion.values.tobytes() == \
        generate(built, built.names[0], repeat=2).motion.values.tobytes()


def test_generate_in_threads_makes_the_same_motion(built):
    from praxicon.generation import generate

    one = generate(built, built.names[0], repeat=2)
    two = generate(built, built.names[0], repeat=2, workers=2)
    assert two.motion.values.tobytes() == one.motion.values.tobytes()
    assert two.methods == one.methods and two.words == one.words
    with pytest.raises(ValueError, match="workers must be a whole number"):
        generate(built, built.names[0], repeat=1, workers=0)


def test_channels_made_in_threads_stop_at_the_first_error(monkeypatch):
    import threading

    from praxicon import channel_curve as module

    started, release = [], threading.Event()

    def curve(name, *rest):
        started.append(name)
        if name == "bad":
            raise RuntimeError("no curve")
        # the good ones would take long: they must not all be waited for (the 20 would take
        # 3 s on two threads, the cancelling a moment; the pool's exit waits for the one begun)
        release.wait(0.3)
        return name, None

    monkeypatch.setattr(module, "channel_curve", curve)
    jobs = [("bad", ("bad",))] + [(f"c{k}", (f"c{k}",)) for k in range(20)]
    with pytest.raises(RuntimeError, match="no curve"):
        module.channel_curves(jobs, workers=2)
    release.set()
    assert len(started) < len(jobs)  # the channels not started were cancelled
