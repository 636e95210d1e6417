"""Praxicon values print as short summaries: one line per repr, a few lines per str."""

from __future__ import annotations

import kinetology
from praxicon import build, generate, load, read_dataset, recognise
from praxicon.parsing import parse
from praxicon.records import Settings

from praxicon_fixtures import take


def _one_line(value, longest: int = 200) -> str:
    text = repr(value)
    assert "\n" not in text and len(text) <= longest, text
    return text


def test_every_praxicon_value_has_a_short_repr(manifest, tmp_path):
    result = build(read_dataset(manifest), tmp_path / "px", progress=False, log=lambda s: None,
                   settings=Settings.make(params={"min_copies": 3}))
    px = load(tmp_path / "px")
    assert px == result.praxicon  # equality is the fields', untouched by the reprs
    assert _one_line(px) == ("<Praxicon: 2 actions learnt of 4, 1 dataset, inducer pal, "
                             "descriptions format 6>")
    assert str(px).splitlines() == [repr(px), "  learnt: moves.step, moves.wave",
                                    "  failed: moves.alone, moves.ghost"]
    assert _one_line(result) == (f"<BuildResult: {len(result.learnt)} learnt, 0 already done, "
                                 f"2 failed; {px!r}>")
    wave = px["moves.wave"]
    assert _one_line(wave).startswith("<ActionRecord 'moves.wave': learnt from 3 of 3 "
                                      "performances, ")
    lines = str(wave).splitlines()
    assert lines[0] == repr(wave) and 1 < len(lines) <= 7
    assert all(line.startswith(f"  {j.name}: ") for line, j in zip(lines[1:], wave.joints))
    assert _one_line(px["moves.alone"]) == ("<ActionRecord 'moves.alone': failed (1 usable "
                                            "performance(s); an action needs at least 2 to "
                                            "show what repeats across them), 1 performance>")
    assert _one_line(px.descriptions).startswith("<Descriptions of 2 actions (whole takes): ")
    assert _one_line(px.descriptions.actions[0]).startswith("<ActionDescription 'moves.step': ")
    assert _one_line(px.descriptions.spread).startswith("<Spread: ")
    generated = generate(px, "moves.wave", repeat=1)
    motion = generated.motion
    assert _one_line(generated) == (
        f"<Generated 'moves.wave': {motion.frames} frames at 30 fps, from the grammar, 1 copy, "
        f"{len(generated.channels)} channels of {len(generated.actuators)} actuators>")
    found = recognise(px, take(2))
    assert _one_line(found).startswith(f"<Recognition 'take2': {found.action} (p=")
    timeline = parse(px, kinetology.Motion(take(2).values, take(2).channels, 30.0,
                                           source="rec"))
    assert _one_line(timeline).startswith("<Timeline 'rec': 6.00 s in ")
