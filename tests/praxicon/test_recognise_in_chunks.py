"""``psgs praxicon recognise`` reads its FILEs a chunk at a time.

The command read every FILE before recognising them in one batch, so its memory grew with the
number of files; it now reads, recognises and prints a chunk (``CHUNK_FILES``, ``CHUNK_BYTES``)
and drops its motions before reading the next, its output the same whatever the chunks. What
scoring reads of the descriptions alone (the score model, the telling groups) is made once for
the command, not once per chunk. The chunks are made small here through the command's
parameters (``run_recognise(args, most_files=..., most_bytes=...)``).
"""

from __future__ import annotations

import gc
import weakref
from collections.abc import Iterator
from pathlib import Path

import pytest

from praxicon import recognition_cli
from praxicon_fixtures import take


@pytest.fixture(scope="module")
def folder(tmp_path_factory) -> Path:
    """A praxicon of a waving arm and a stepping leg (``px``), and eight new takes beside it:
    ``new0.bvh`` ... ``new7.bvh``, waves and steps in turn."""
    from kinetology import write_bvh
    from praxicon import build, read_dataset

    root = tmp_path_factory.mktemp("chunks")
    rows = ["action,file"]
    for name, seeds in (("wave", (1, 2, 3)), ("step", (4, 5, 6))):
        for seed in seeds:
            write_bvh(_move(take(seed), name), root / f"{name}{seed}.bvh")
            rows.append(f"{name},{root / f'{name}{seed}.bvh'}")
    (root / "m.csv").write_text("\n".join(rows) + "\n")
    build(read_dataset(root / "m.csv"), root / "px", progress=False, log=lambda s: None)
    for k in range(8):
        write_bvh(_move(take(10 + k), "wave" if k % 2 else "step"), root / f"new{k}.bvh")
    return root


def _move(motion, name: str):
    """The take with only the arm (a wave) or only the leg (a step) moving."""
    from kinetology import Motion

    values = motion.values.copy()
    still = ("leg.rx",) if name == "wave" else ("arm.rx", "arm.rz")
    for channel in still:
        values[:, motion.channels.index(channel)] *= 0.02
    return Motion(values, motion.channels, motion.frame_rate, motion.skeleton, motion.source)


def _files(folder: Path) -> list[str]:
    return [str(folder / f"new{k}.bvh") for k in range(8)]


def _recognise(capsys, argv, **chunks) -> tuple[int, str, str]:
    """``psgs praxicon recognise ARGV`` in this process, its chunks given (``most_files``,
    ``most_bytes``): its status, stdout and stderr."""
    from psgs.cli import build_parser

    from praxicon.cli import register

    args = build_parser({"praxicon": register}).parse_args(["praxicon", "recognise", *argv])
    assert args.run is recognition_cli.run_recognise
    capsys.readouterr()
    status = args.run(args, **chunks)
    captured = capsys.readouterr()
    return status, captured.out, captured.err


@pytest.fixture
def held(monkeypatch) -> Iterator[list[int]]:
    """Before each FILE the command reads: how many of the motions it read before are still
    held (reachable), filled in as the command runs."""
    alive: list[weakref.ref] = []
    out: list[int] = []
    real = recognition_cli._read_motion

    def reading(path, doing="recognising"):
        gc.collect()  # held means reachable, not merely not yet collected
        out.append(sum(ref() is not None for ref in alive))
        motion = real(path, doing)
        alive.append(weakref.ref(motion))
        return motion

    monkeypatch.setattr(recognition_cli, "_read_motion", reading)
    # what the process held before the command is set aside from the collections above (the
    # motions are all made after, and nothing made before can come to hold one unless it is
    # reachable): in a worker that has run hundreds of tests, a full collection walked its
    # whole heap, 0.1-0.2 s each of the 8 reads
    gc.freeze()
    try:
        yield out
    finally:
        gc.unfreeze()


def test_the_command_holds_one_chunk_of_motions_at_a_time(folder, held, capsys):
    status, out, err = _recognise(capsys, [str(folder / "px"), *_files(folder)], most_files=3)
    assert status == 0 and err == "" and len(out.splitlines()) == 8
    # a chunk's first, second and third read find 0, 1 and 2 of its motions held: none of the
    # chunk before (read all at once, the eighth read found seven)
    assert held == [0, 1, 2, 0, 1, 2, 0, 1]


def test_a_chunk_ends_at_its_bytes_too(folder, held, capsys):
    # one take's values (180 frames x 5 channels) are 7,200 bytes: two fill a chunk
    status, out, _ = _recognise(capsys, [str(folder / "px"), *_files(folder)],
                                most_bytes=10_000)
    assert status == 0 and len(out.splitlines()) == 8
    assert held == [0, 1] * 4


@pytest.mark.parametrize("explain", [[], ["--explain"]])
def test_the_output_is_the_same_in_chunks_of_any_size(folder, capsys, explain):
    (folder / "empty.bvh").write_text("")
    files = _files(folder)
    # unanswerable FILEs among them, each said in its place: one in a chunk of its own, one
    # the first of a chunk, one in the middle of one
    argv = [str(folder / "px"), str(folder / "nowhere.bvh"), *files[:5],
            str(folder / "empty.bvh"), *files[5:], str(folder / "nowhere.bvh"), *explain]
    seen = set()
    for size in (1, 2, 3, 5, recognition_cli.CHUNK_FILES):
        seen.add(_recognise(capsys, argv, most_files=size))
    (status, out, err), = seen  # one output, whatever the chunk
    assert status == 2 and len(err.splitlines()) == 3
    assert out.startswith(f"{files[0]}: ")
    answered = [out.index(f"{file}: ") for file in files]  # every one, in the order given
    assert answered == sorted(answered)


def test_the_score_model_is_made_once_for_every_chunk(folder, monkeypatch, capsys):
    """Three chunks of one skeleton: the score model and the telling groups (what scoring reads
    of the descriptions alone) made once, and the same output as in one chunk."""
    from praxicon import _verdict

    made = {"score_model": 0, "telling_groups": 0}
    for name in made:
        real = getattr(_verdict, name)

        def counted(*a, _real=real, _name=name, **k):
            made[_name] += 1
            return _real(*a, **k)

        monkeypatch.setattr(_verdict, name, counted)
    argv = [str(folder / "px"), *_files(folder), "--explain"]
    status, out, err = _recognise(capsys, argv, most_files=3)
    assert status == 0 and err == "" and len(out.splitlines()) > 8
    assert made == {"score_model": 1, "telling_groups": 1}
    assert (status, out, err) == _recognise(capsys, argv)


def test_the_families_score_model_is_kept_too(monkeypatch):
    """Recognised in three calls with the same ScoreModels, a praxicon of families makes its
    actions' score model and its families' once each, and answers as without them."""
    from kinetology import synthetic_motion
    from praxicon import _verdict
    from praxicon.description import describe
    from praxicon.recognition import _recognitions

    takes = {name: [synthetic_motion(3, joints, period=period, seed=s) for s in seeds]
             for name, joints, period, seeds in (("a.slow", (0,), 1.3, (1, 2, 3)),
                                                 ("a.fast", (0,), 0.8, (4, 5, 6)),
                                                 ("b", (2,), 1.0, (7, 8, 9)))}
    d = describe(takes, families={"a.slow": "a", "a.fast": "a"})
    new = [synthetic_motion(3, (0,), period=1.0, seed=10), synthetic_motion(3, (2,), seed=11)]
    made = []
    real = _verdict.score_model
    monkeypatch.setattr(_verdict, "score_model", lambda ds, c: made.append(ds) or real(ds, c))
    models = _verdict.ScoreModels(d)
    answers = [_recognitions(models, new) for _ in range(3)]
    assert made == [d, d.families]
    assert answers[0][0].family == "a"
    assert answers == [_recognitions(d, new)] * 3


def test_score_models_keep_at_most_their_bound(monkeypatch):
    """Files of many skeletons (sets of columns) do not grow what a command keeps: past
    KEPT_MODELS the oldest model goes, and one asked for again is made again, the same."""
    import numpy as np
    from kinetology import synthetic_motion
    from praxicon import _verdict
    from praxicon.description import describe
    from praxicon.recognition import _recognitions

    d = describe({"a": [synthetic_motion(3, (0,), seed=s) for s in (1, 2)],
                  "b": [synthetic_motion(3, (2,), seed=s) for s in (3, 4)]})
    new = [synthetic_motion(3, (0,), seed=5), synthetic_motion(3, (2,), seed=6)]
    monkeypatch.setattr(_verdict, "KEPT_MODELS", 2)
    models = _verdict.ScoreModels(d)
    answers = _recognitions(models, new)  # every column: the first set kept
    width = len(d.spread.features)
    for columns in (np.arange(width - 1), np.arange(1, width)):  # two more: the first goes
        models(columns)
    assert len(models._made) == 2  # noqa: SLF001 - what is kept
    assert _recognitions(models, new) == answers == _recognitions(d, new)
    assert len(models._made) == 2  # noqa: SLF001
