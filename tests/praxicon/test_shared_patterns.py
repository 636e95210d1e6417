"""praxicon.shared_patterns against a brute-force reading of its definition, and its bound."""

from __future__ import annotations

import json
import random
import shutil
import time
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from praxicon.records import ActionRecord, ChannelMorpheme, JointRecord
from praxicon.shared import shared_patterns
from psgs.errors import ValidationError

SEED = Path(__file__).resolve().parents[1] / "data" / "fuzz" / "praxicon"


def _brute_force(records, min_length, min_actions):
    """The definition read literally: every cyclic sub-string of every morpheme, then every
    shared one kept unless a longer one the same actions share holds it (cubic and more)."""
    def cycle(kinetemes):
        return kinetemes[:-1] if len(kinetemes) > 1 and kinetemes[0] == kinetemes[-1] else kinetemes

    def contains(longer, shorter):
        return any(longer[i:i + len(shorter)] == shorter for i in range(len(longer)))

    holders, wholes = {}, set()
    for action in records:
        if not action.learnt:
            continue
        for joint in action.joints:
            for channel, morpheme in joint.morphemes:
                c = cycle(morpheme.kinetemes)
                n, doubled = len(c), cycle(morpheme.kinetemes) * 2
                found = {doubled[i:i + k] for k in range(min_length, n) for i in range(n)}
                if n >= min_length:
                    whole = min(doubled[i:i + n] for i in range(n))
                    found.add(whole)
                    wholes.add(whole)
                for sub in found:
                    holders.setdefault(joint.name, {}).setdefault(sub, set()).add(
                        (action.name, channel))
    out = []
    for joint, patterns in holders.items():
        shared = {p: h for p, h in patterns.items() if len({a for a, _ in h}) >= min_actions}
        for pattern, held in shared.items():
            actions = {a for a, _ in held}
            if not any(o != pattern and len(o) >= len(pattern)
                       and contains(o + o if o in wholes else o, pattern)
                       and {a for a, _ in shared[o]} == actions for o in shared):
                out.append((joint, pattern, tuple(sorted(actions)), tuple(sorted(held))))
    order = {j: i for i, j in enumerate(holders)}
    return sorted(out, key=lambda p: (order[p[0]], -len(p[2]), -len(p[1]), p[1]))


def _action(name, joints, learnt=True):
    if not learnt:
        return ActionRecord(name, "d", name, reason="no takes")
    return ActionRecord(
        name, "d", name, status="ok", actuators=tuple(j for j, _ in joints),
        joints=tuple(JointRecord(j, tuple((c, ChannelMorpheme(tuple(k))) for c, k in channels))
                     for j, channels in joints))


@st.composite
def _records(draw):
    """Actions whose morphemes are often rotations and pieces of each other's (so that
    patterns are shared, held whole, read around the cycle's end), over a few letters."""
    letters = draw(st.sampled_from(["B", "BG", "BGR", "BGRY"]))
    pieces = []

    def morpheme():
        own = draw(st.lists(st.sampled_from(letters), max_size=16))
        if pieces and draw(st.booleans()):
            other = draw(st.sampled_from(pieces))
            turn = draw(st.integers(0, len(other)))
            own = (other[turn:] + other[:turn] + own[:draw(st.integers(0, 3))])[:20]
        pieces.append(own)
        return own

    records = []
    for number in range(draw(st.integers(1, 5))):
        name = draw(st.sampled_from([f"a{number}", "twin"]))  # two actions may share a name
        joints = [(j, [(f"{j}.r{c}", morpheme()) for c in range(draw(st.integers(1, 3)))])
                  for j in draw(st.lists(st.sampled_from(["arm", "leg", "hip"]),
                                         min_size=1, max_size=3, unique=True))]
        records.append(_action(name, joints, learnt=draw(st.integers(0, 9)) > 0))
    return records


@settings(max_examples=120, deadline=None)
@given(records=_records(), min_length=st.integers(1, 6), min_actions=st.integers(1, 3))
def test_shared_patterns_are_those_the_definition_gives(records, min_length, min_actions):
    found = [(p.joint, p.kinetemes, p.actions, p.channels)
             for p in shared_patterns(records, min_length=min_length, min_actions=min_actions)]
    assert found == _brute_force(records, min_length, min_actions)


def _long(length, seed=1):
    rng = random.Random(seed)
    return [rng.choice("BGRY") for _ in range(length)]


def test_two_long_alike_morphemes_are_one_pattern_found_quickly():
    morpheme = _long(1001)
    morpheme[-1] = "W"  # a cycle of 1,001 kinetemes (equal ends would merge into one)
    records = [_action(name, [("arm", [("arm.rx", morpheme)])]) for name in ("a", "b")]
    started = time.process_time()
    found = shared_patterns(records)
    assert time.process_time() - started < 5  # 4 s before for 1,000; 50 s for 400 alike
    assert [(p.actions, len(p.kinetemes)) for p in found] == [(("a", "b"), 1001)]


def test_long_unlike_morphemes_share_only_short_patterns_quickly():
    records = [_action(name, [("arm", [("arm.rx", _long(20_000, seed))])])
               for name, seed in (("a", 1), ("b", 2))]
    found = shared_patterns(records)
    assert found and max(len(p.kinetemes) for p in found) < 30


def test_the_bound_is_named_when_morphemes_are_too_long_and_alike():
    morpheme = _long(300)
    records = [_action(name, [("arm", [("arm.rx", morpheme)])]) for name in ("a", "b")]
    with pytest.raises(ValidationError, match=r"^shared_patterns: the morphemes are too long and "
                                              r"alike to compare within 10,000 steps "
                                              r"\(max_steps; reached at joint 'arm'\)$"):
        shared_patterns(records, max_steps=10_000)
    assert len(shared_patterns(records, max_steps=1_000_000)) == 1
    with pytest.raises(ValidationError, match="max_steps must be a whole number"):
        shared_patterns(records, max_steps=0)


def test_verify_of_a_folder_with_huge_alike_morphemes_says_so_in_one_line(tmp_path, capsys):
    from psgs.cli import main

    folder = tmp_path / "px"
    shutil.copytree(SEED, folder)
    kinetemes = _long(6000)
    for action in ("moves.step", "moves.wave"):
        path = folder / "records" / f"{action}.json"
        stored = json.loads(path.read_text())
        morpheme = stored["record"]["joints"]["arm"]["morphemes"]["arm.rx"]
        morpheme.update(kinetemes=kinetemes, durations=[0.1] * len(kinetemes),
                        displacements=[(-1.0) ** i for i in range(len(kinetemes))])
        path.write_text(json.dumps(stored))
    assert main(["praxicon", "verify", str(folder)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == ["psgs: error: shared_patterns: the morphemes are too long and alike to compare "
                   "within 20,000,000 steps (max_steps; reached at joint 'arm')"]


def test_more_distinct_kinetemes_than_characters_is_one_line():
    import sys

    kinetemes = [f"k{i}" for i in range(sys.maxunicode + 2)]
    records = [_action(name, [("arm", [("arm.rx", kinetemes)])]) for name in ("a", "b")]
    with pytest.raises(ValidationError, match=r"^shared_patterns: joint 'arm' has 1,114,113 "
                                              r"distinct kinetemes, more than the 1,114,112 it "
                                              r"can compare$"):
        shared_patterns(records)
