"""locate: a learned action found in held-apart takes, not in takes of other actions.

Real takes from ../shared/data/mocap (Bandai Namco dataset 1, segmented by
kinetology); skips only when the shared data is absent. A synthetic case
checks the pattern method and the errors.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from psgs import Actiongram
from psgs.errors import ValidationError
from psgs.induce import Induction, PAL
from psgs.induce import Located, locate

MOCAP = Path(__file__).resolve().parents[2] / ".." / "shared" / "data" / "mocap"
BANDAI = MOCAP / "bandai-namco-1" / "data"
needs_data = pytest.mark.skipif(not BANDAI.is_dir(),
                                reason=f"shared motion-capture data not found at {BANDAI}")


def takes(content: str, limit: int | None = None):
    kinetology = pytest.importorskip("kinetology")
    files = sorted(BANDAI.glob(f"dataset-1_{content}_*.bvh"))[:limit]
    return [kinetology.segment(kinetology.read(f)) for f in files]


@pytest.fixture(scope="module")
def wave():
    """The right-hand wave learnt from every other style's take, and the takes held apart."""
    if not BANDAI.is_dir():
        pytest.skip(f"shared motion-capture data not found at {BANDAI}")
    every = takes("bye")
    return PAL().induce(every[::2]), every[1::2]


@needs_data
def test_the_learned_wave_is_the_right_arm(wave):
    learned, _ = wave
    assert set(learned.actuators) == {"UpperArm_R", "LowerArm_R", "Hand_R"}


@needs_data
def test_locate_finds_the_wave_in_held_apart_takes(wave):
    learned, held = wave
    found = [locate(learned, ag) for ag in held]
    assert sum(bool(spans) for spans in found) >= 0.9 * len(held)
    for ag, spans in zip(held, found):
        for span in spans:
            assert isinstance(span, Located) and 0 <= span.start < span.stop
            assert span.stop <= max(o + sum(d) for o, d in zip(ag.origins,
                                                                 ag.segment_durations)) + 0.1


@needs_data
def test_locate_does_not_find_the_wave_in_other_actions(wave):
    learned, _ = wave
    others = takes("walk", 4) + takes("run", 4) + takes("bow", 4) + takes("guide", 4)
    hits = sum(bool(locate(learned, ag)) for ag in others)
    assert hits <= 0.1 * len(others)


def test_pattern_method_on_a_synthetic_case_and_errors():
    learned = Induction(None, ("a", "b"), {"a": ("x", "y"), "b": ("u", "v")},
                        {"a": ((0, 2),), "b": ((0, 2),)})
    new = Actiongram.from_strings({"a": "xy" * 6 + "xxxxyyyyxxxx", "b": "uv" * 6 + "u" * 12})
    spans = locate(learned, new, threshold=0.6)  # one channel of two agreeing scores 0.5
    assert [(round(s.start), round(s.stop)) for s in spans] == [(0, 12)]
    assert locate(learned, Actiongram.from_strings({"a": "x" * 20, "b": "u" * 20})) == ()
    # a take without the learned strings: not found, by each method alike
    for method in ("auto", "pattern"):
        assert locate(learned, Actiongram.from_strings({"q": "xy"}), method=method) == ()
    assert locate(Induction(None, (), {}, {}), new) == ()  # nothing learnt: found nowhere
    with pytest.raises(TypeError):
        locate(learned, "a: x y")
    with pytest.raises(ValidationError, match="method"):
        locate(learned, new, method="guess")


def test_a_take_without_what_was_learnt_is_not_found_by_either_method():
    import sys

    sys.path.insert(0, str(Path(__file__).parent))
    from test_pal_performances import performance

    learned = PAL().induce([performance(k) for k in range(6)])  # the waving arm, by joint
    assert learned.actuators and learned.morphemes
    held = performance(7)
    assert locate(learned, held)  # found in a take with the learned joints
    # a take whose channels are none of the learned ones (segmentation leaves out the
    # channels that hardly move): the pattern method raised where the joints method (the
    # default for an action learnt as cycles by joint) answered "not found"
    other = Actiongram.from_strings({"q": "xyxyxyxyxyxyxyxy", "r": "uvuvuvuvuvuvuvuv"})
    for method in ("auto", "joints", "pattern"):
        assert locate(learned, other, method=method) == (), method
    # and a grammar system whose components are no string of the take
    assert locate(learned.system, other) == ()


def test_locate_with_a_grammar_system_reads_its_patterns():
    learned = PAL().induce(Actiongram.from_strings(
        {"a": "xyzw" * 8, "b": "pqrs" * 8, "c": "mnmnnmmnmnmnnnmnmmmnnmnmnnmmmnmn"}))
    assert learned.system is not None
    new = Actiongram.from_strings({"a": "wwxx" + "xyzw" * 5, "b": "ssrr" + "pqrs" * 5})
    spans = locate(learned.system, new)
    assert spans and spans[0].start >= 2


def _synthetic_case():
    learned = Induction(None, ("a", "b"), {"a": ("x", "y"), "b": ("u", "v")},
                        {"a": ((0, 2),), "b": ((0, 2),)})
    new = Actiongram.from_strings({"a": "xy" * 6 + "xxxxyyyyxxxx", "b": "uv" * 6 + "u" * 12})
    return learned, new


@pytest.mark.parametrize("scales", [(float("nan"),), (float("inf"),), (0.0,), (-1.0,), (),
                                    ("fast",), (True,)])
def test_bad_scales_are_a_validation_error(scales):
    learned, new = _synthetic_case()
    with pytest.raises(ValidationError, match="scale"):
        locate(learned, new, scales=scales)


@pytest.mark.parametrize("repeats", [0, -1, 1.5, True])
def test_bad_repeats_are_a_validation_error(repeats):
    learned, new = _synthetic_case()
    with pytest.raises(ValidationError, match="repeats"):
        locate(learned, new, scales=(1e9,), repeats=repeats)


def test_a_huge_tempo_is_skipped_without_allocating_its_pattern():
    import tracemalloc

    learned, new = _synthetic_case()
    tracemalloc.start()
    try:
        assert locate(learned, new, scales=(1e9,), method="pattern") == ()
        assert locate(learned, new, scales=(1e9,), repeats=1, method="pattern") == ()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 50 * 2**20
    # a huge tempo beside a fitting one: the fitting one still finds the action
    spans = locate(learned, new, threshold=0.6, scales=(1.0, 1e9))
    assert [(round(s.start), round(s.stop)) for s in spans] == [(0, 12)]


def test_locate_with_its_defaults_spots_an_action_between_others():
    """Pattern A, then B, then A: the spans of learnt B lie inside B's true span (before,
    the default found one span from the first cycle to the last of the whole recording)."""
    kinetology = pytest.importorskip("kinetology")
    import numpy as np
    from kinetology.synthetic import synthetic_motion

    b = synthetic_motion(patterned=(0, 1, 2), seed=1)
    before = synthetic_motion(patterned=(3, 4, 5), seed=2, repetitions=3)
    after = synthetic_motion(patterned=(3, 4, 5), seed=3, repetitions=3)
    recording = kinetology.Motion(np.concatenate([before.values, b.values, after.values]),
                                  b.channels, b.frame_rate)
    learned = PAL().induce(kinetology.segment(b))
    spans = locate(learned, kinetology.segment(recording))
    start, stop = before.duration, before.duration + b.duration
    assert spans
    assert all(start <= s.start < s.stop <= stop for s in spans), (spans, start, stop)
    # and they cover most of it (at least half of what is performed)
    assert sum(s.stop - s.start for s in spans) >= 0.5 * b.duration
    # B performed alone is found over most of the take
    alone = locate(learned, kinetology.segment(b))
    assert alone and alone[-1].stop - alone[0].start >= 0.7 * b.duration


@pytest.mark.parametrize("strings", [{"a": "abcdefghij", "b": "klmnopqrst"},  # nothing repeats
                                     {"a": "x" * 20, "b": "y" * 20},  # one symbol each
                                     {"a": "x", "b": "y"}, {"a": "", "b": ""}])
def test_nothing_learnt_is_found_nowhere_by_every_method(strings):
    """PAL learns no component from an actiongram without synchronised repetition: every
    method answers that the action is found nowhere (the pattern method raised, the joints
    method returned no span)."""
    learned = PAL().induce(Actiongram.from_strings(strings))
    assert not learned.components
    for new in (Actiongram.from_strings(strings),
                Actiongram.from_strings({"a": "xy" * 10, "b": "uv" * 10})):
        for method in ("auto", "joints", "pattern"):
            assert locate(learned, new, method=method) == (), method
    assert locate(Induction(None, (), {}, {}), Actiongram.from_strings({"a": "xy"}),
                  method="pattern") == ()


def test_numpy_integers_are_repeats():
    learned, new = _synthetic_case()
    import numpy as np

    expected = locate(learned, new, threshold=0.6, repeats=2)
    assert locate(learned, new, threshold=0.6, repeats=np.int64(2)) == expected
    assert locate(learned, new, threshold=0.6, repeats=np.uint8(2)) == expected


def test_more_repeats_than_the_new_motion_holds_find_nothing_without_allocating_them():
    """A place must hold ``repeats`` copies in a row: more copies than the new motion has
    sampled points fit nowhere, and are not made (10**12 copies raised a MemoryError)."""
    import tracemalloc

    learned, new = _synthetic_case()
    tracemalloc.start()
    try:
        assert locate(learned, new, repeats=10**12, method="pattern") == ()
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 50 * 2**20


def test_the_joints_method_of_a_grammar_system_is_a_validation_error():
    """A grammar system has no learnt joints to time: method="joints" raised the
    AttributeError of its missing inducer."""
    learned = PAL().induce(Actiongram.from_strings({"a": "xyzw" * 8, "b": "pqrs" * 8}))
    new = Actiongram.from_strings({"a": "xyzw" * 3, "b": "pqrs" * 3})
    with pytest.raises(ValidationError, match="method joints reads an induction"):
        locate(learned.system, new, method="joints")
    assert locate(learned.system, new) == locate(learned.system, new, method="pattern")
    for wrong in (None, "a: x y"):
        with pytest.raises(TypeError, match="locate needs an Induction or a PSGS"):
            locate(wrong, new, method="joints")
