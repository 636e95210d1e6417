"""Motion files recognise and parse cannot answer for, and descriptions they cannot score with.

A value too large to compute with (finite: the file reads) made every answer NaN, with NumPy's
overflow warnings and exit status 0; now it is one line naming the file and the feature, exit
status 2, and a DescriptionError from the API.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from praxicon import parse, recognise, recognise_many
from praxicon.cli import main
from praxicon.description import DescriptionError
from praxicon_fixtures import leg_body

# an overflow was a RuntimeWarning on stderr before the NaN answer: none may be left
pytestmark = pytest.mark.filterwarnings("error::RuntimeWarning")

_RATE = 30.0


def _leg(seed: int, pace: float, seconds: float = 5.0):
    """A hip and a swinging leg that travels ``pace`` units a second along x."""
    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * _RATE)) / _RATE
    swing = 30 * np.sin(2 * np.pi * t / (1 + 0.05 * (seed % 3))) + rng.normal(0, 1, t.size)
    hip = 9 + 0.2 * np.sin(4 * np.pi * t) + rng.normal(0, 0.02, t.size)
    return leg_body(pace * t + rng.normal(0, 0.01, t.size), hip,
                    rng.normal(0, 0.01, t.size), swing, 1.0, f"{1 / _RATE:.9f}")


def _with(motion, column: int, values):
    from kinetology import Motion

    out = motion.values.copy()
    out[:, column] = values
    return Motion(out, motion.channels, motion.frame_rate, motion.skeleton)


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    """A praxicon of a walk and a stand (m.walk, m.stay) and motion files beside it: two new
    walks, one whose hips rise to 1e300 for a frame, one that travels 3e154 units a second
    (every feature finite, its distances not), an empty file and a body of other joints."""
    from kinetology import Motion, write_bvh
    from kinetology.bvh_writer import star_skeleton
    from praxicon import build, read_dataset

    root = tmp_path_factory.mktemp("unanswerable")
    rows = ["action,file"]
    for name, pace, seeds in (("walk", 10.0, (1, 2, 3)), ("stay", 0.0, (4, 5, 6))):
        for seed in seeds:
            write_bvh(_leg(seed, pace), root / f"{name}{seed}.bvh")
            rows.append(f"{name},{root / f'{name}{seed}.bvh'}")
    (root / "m.csv").write_text("\n".join(rows) + "\n")
    build(read_dataset(root / "m.csv"), root / "px", progress=False, log=lambda s: None)
    write_bvh(_leg(7, 10.0), root / "new.bvh")
    write_bvh(_leg(8, 10.0), root / "new2.bvh")
    walk = _leg(9, 10.0)
    high = walk.channels.index("Hips.ty")
    write_bvh(_with(walk, high, np.where(np.arange(walk.frames) == 60, 1e300,
                                         walk.values[:, high])), root / "huge.bvh")
    ahead = walk.channels.index("Hips.tx")
    write_bvh(_with(walk, ahead, 3e154 * np.arange(walk.frames) / _RATE), root / "fast.bvh")
    (root / "empty.bvh").write_text("")
    channels = ("neck.rx", "neck.ry")
    write_bvh(Motion(np.random.default_rng(3).normal(0, 5, (150, 2)), channels, _RATE,
                     star_skeleton(channels)), root / "other.bvh")
    return root


def _run(capsys, argv) -> tuple[int, str, str]:
    capsys.readouterr()
    status = main(argv)
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def _refused(capsys, argv) -> str:
    """The one error line (without ``psgs: error: ``) of a command that answers nothing."""
    status, out, err = _run(capsys, argv)
    assert status == 2 and out == "", (status, out, err)
    (line,) = err.splitlines()
    assert line.startswith("psgs: error: ") and "Traceback" not in err
    return line[len("psgs: error: "):]


# -- a value too large to compute with ---------------------------------------------------------
def test_a_huge_value_is_one_line_naming_the_file_and_the_feature(built, capsys):
    huge = built / "huge.bvh"
    said = _refused(capsys, ["recognise", str(built / "px"), str(huge)])
    assert said == (f"{huge}: feature Hips.travely:energy is not finite (inf): a value of the "
                    f"motion is too large to compute with (its largest: 1e+300, Hips.ty at "
                    f"frame 60)")
    said = _refused(capsys, ["parse", str(built / "px"), str(huge)])
    # a window's frames are counted from its start, which the line gives
    assert said.startswith(f"{huge} (the window from ") and "is not finite (inf)" in said
    start = float(said.split("the window from ")[1].split(" s)")[0])
    frame = int(said.rsplit("at frame ", 1)[1].rstrip(")"))
    assert round(start * _RATE) + frame == 60


def test_the_api_raises_the_line_the_command_prints(built):
    huge = built / "huge.bvh"
    for call, begins in ((recognise, f"{huge}: feature Hips.travely:energy is not finite"),
                         (lambda px, m: recognise_many(px, [built / "new.bvh", m]),
                          f"{huge}: feature Hips.travely:energy is not finite"),
                         (parse, f"{huge} (the window from ")):
        with pytest.raises(DescriptionError, match="is not finite") as info:
            call(built / "px", huge)
        assert str(info.value).startswith(begins) and "\n" not in str(info.value)
