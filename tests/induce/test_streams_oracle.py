"""The music benchmark's oracle of written-out repetition, which judges its negatives."""

from __future__ import annotations

import importlib.util
import random
import sys
from pathlib import Path

import pytest

BENCHMARKS = Path(__file__).resolve().parents[2] / "benchmarks"


@pytest.fixture(scope="module")
def script():
    """benchmarks/streams.py, loaded by its path."""
    sys.path.insert(0, str(BENCHMARKS))  # (the script imports its neighbour _common)
    had_common = "_common" in sys.modules
    try:
        spec = importlib.util.spec_from_file_location("streams_benchmark",
                                                      BENCHMARKS / "streams.py")
        module = importlib.util.module_from_spec(spec)
        sys.modules[spec.name] = module  # (its dataclasses look their module up by name)
        spec.loader.exec_module(module)
    finally:
        sys.path.remove(str(BENCHMARKS))
        sys.modules.pop("streams_benchmark", None)
        if not had_common:
            sys.modules.pop("_common", None)
    return module


@pytest.fixture(scope="module")
def oracle(script):
    """benchmarks/streams.py's ``written_repeat``."""
    return script.written_repeat


def test_a_claim_counts_only_on_a_written_out_repeat(script):
    rng = random.Random(3)
    section = _random(rng, 8)
    voice = _voice(section + [(1.0, "r")] + section + _random(rng, 6))
    assert script.lies_on_repeat(voice, ((0.0, 8.0), (9.0, 17.0)))
    assert not script.lies_on_repeat(voice, ((0.0, 8.0), (10.0, 18.0)))  # off by a beat
    piece = script.Piece("p", (voice, voice), ())
    assert not script.false_claim({"v0": ((0.0, 8.0), (9.0, 17.0))}, piece)
    assert script.false_claim({"v0": ((0.0, 8.0), (9.0, 17.0)), "x3": ((0.0, 8.0), (9.0, 17.0))},
                              piece)  # a spurious string named


def _voice(notes: list[tuple[float, str]]) -> tuple[tuple[float, float, str], ...]:
    """(duration, symbol) notes as rows (onset, duration, symbol) from beat 0."""
    rows, t = [], 0.0
    for d, s in notes:
        rows.append((t, d, s))
        t += d
    return tuple(rows)


def _random(rng: random.Random, count: int) -> list[tuple[float, str]]:
    """``count`` notes of one beat, random pitches."""
    return [(1.0, rng.choice("CDEFGAB") + "4") for _ in range(count)]


def test_a_section_two_voices_play_twice_at_the_same_times_is_found(oracle):
    rng = random.Random(3)
    voices = []
    for _ in range(2):
        section = _random(rng, 8)
        voices.append(_voice([(4.0, "r")] + section + [(3.0, "r")] + section + [(1.0, "r")]))
    # (length, shift, start, voices): 8 beats from beat 4, again 11 beats later
    assert oracle(voices, 8.0) == (8.0, 11.0, 4.0, (0, 1))
    assert oracle(voices, 9.0) is None


def test_no_section_when_the_voices_repeat_at_different_times(oracle):
    rng = random.Random(5)
    a, b = _random(rng, 10), _random(rng, 10)
    one = _voice(a + [(2.0, "r")] + a + _random(rng, 6))
    other = _voice(b + [(5.0, "r")] + b + _random(rng, 3))
    assert oracle([one, one], 8.0)[:2] == (10.0, 12.0)
    assert oracle([one, other], 4.0) is None  # each repeats, 12 and 15 beats apart


def test_voices_resting_at_two_times_are_no_repetition(oracle):
    voices = [_voice([(8.0, "r"), (1.0, "C4"), (8.0, "r"), (1.0, "D4")]),
              _voice([(8.0, "r"), (1.0, "E4"), (8.0, "r"), (1.0, "F4")])]
    assert oracle(voices, 8.0) is None


def test_a_section_shorter_than_the_bound_is_not_counted(oracle):
    section = [(1.0, "C4"), (1.0, "E4"), (1.0, "G4")]
    voices = [_voice(section + [(1.0, "D4")] + section + [(1.0, "F4")]),
              _voice(section + [(1.0, "A4")] + section + [(1.0, "B4")])]
    assert oracle(voices, 4.0) is None
    assert oracle(voices, 3.0)[:3] == (3.0, 4.0, 0.0)


def test_a_section_after_a_shared_rest_is_found_inside_the_longer_span(oracle):
    rng = random.Random(7)
    voices = []
    for pitch in ("C5", "D5"):
        section = _random(rng, 8)
        voices.append(_voice([(10.0, "r")] + section + [(3.0, pitch)] + [(10.0, "r")] +
                             section + [(1.0, "E5")]))
    # the span both voices share at a shift of 21 beats is 18 long, 10 of them rests: too
    # quiet as a whole, the 8 notes after the rest a section
    found = oracle(voices, 8.0)
    assert found is not None and found[1] == 21.0 and found[0] >= 8.0
    assert 2 * 8.0 >= found[0]
