"""An action's performances read back (``praxicon.performance_files``): a file that cannot be
read is said, never left out. ``performances_of`` skipped it without a word, and so did what
reads through it when not handed the motions (``body_of``, ``style_scales``,
``performed_motion``): the body, the scales and the course were made from the other takes.
``generate`` already named such a file; it now names it from the one read."""

from __future__ import annotations

from pathlib import Path

import pytest

import kinetology
from praxicon import build, load, read_dataset
from praxicon.acyclic import performed_motion
from praxicon.body_motion import body_of
from praxicon.generation import generate, style_scales
from praxicon.performance_files import performances_of, read_performances, unreadable


@pytest.fixture
def wave(manifest):
    """The praxicon folder, moves.wave (learnt from wave_1, wave_2 and wave_3) and its files."""
    out = manifest.parent / "px"
    build(read_dataset(manifest), out, progress=False, log=lambda s: None)
    record = load(out)["moves.wave"]
    files = [record.performances[i].file for i in record.learnt_from]
    assert [Path(f).name for f in files] == ["wave_1.bvh", "wave_2.bvh", "wave_3.bvh"]
    return out, record, files


def test_every_performance_that_reads_is_read(wave):
    _, record, files = wave
    assert [m.source for m in performances_of(record)] == files
    motions, failed = read_performances(record)
    assert [m.source for m in motions] == files and failed == {}
    assert unreadable(record, {}) is None
    # a style: the file names holding the word
    assert [m.source for m in performances_of(record, "2")] == files[1:2]


def test_a_moved_performance_is_named_not_left_out(wave):
    folder, record, files = wave
    moved = Path(files[1])
    moved.rename(moved.with_name("moved-" + moved.name))
    motions, failed = read_performances(record)
    assert [m.source for m in motions] == [files[0], files[2]]
    assert list(failed) == [files[1]] and failed[files[1]].startswith(f"{files[1]}: no such file")
    line = (f"action 'moves.wave': 1 of the 3 performances it was learnt from cannot be read "
            f"({failed[files[1]]})")
    with pytest.raises(ValueError) as error:
        performances_of(record)
    assert str(error.value) == line
    # the same line generate gives, read once
    with pytest.raises(ValueError) as error:
        generate(folder, "moves.wave", repeat=1)
    assert str(error.value) == line
    # of a style: the style's performances counted
    with pytest.raises(ValueError, match=r"^action 'moves\.wave': the one performance of style "
                                         r"'2' it was learnt from cannot be read \("):
        performances_of(record, "2")
    assert [m.source for m in performances_of(record, "3")] == files[2:]
    # what reads the performances itself when not handed them says so too
    source = kinetology.read(files[0])
    with pytest.raises(ValueError, match="^" + line[:60]):
        body_of(record, source.channels, set())
    with pytest.raises(ValueError, match="^" + line[:60]):
        style_scales(record, ["arm.rx"], 1.0, "1", 30.0)
    with pytest.raises(ValueError, match="^" + line[:60]):
        performed_motion(record, 1, source)


def test_a_damaged_performance_names_the_file_once(wave):
    _, record, files = wave
    Path(files[2]).write_text("not a motion\n")
    _, failed = read_performances(record)
    assert list(failed) == [files[2]] and failed[files[2]].count(files[2]) == 1

