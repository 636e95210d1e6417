"""Synthetic datasets for the praxicon tests: small BVH takes of a waving arm and a stepping leg."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

SHARED = Path(__file__).resolve().parents[2] / ".." / "shared" / "data" / "mocap"
CHANNELS = ("hips.rz", "arm.rx", "arm.rz", "leg.rx", "head.ry")


def take(seed: int, seconds: float = 6.0, rate: float = 30.0, period: float = 1.0):
    """A take: the arm (two channels) and the leg swing in step; hips and head barely move."""
    from kinetology import Motion
    from kinetology.bvh_writer import star_skeleton

    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * rate)) / rate
    phase = 2 * np.pi * t / (period * (1 + 0.03 * seed))
    values = np.column_stack([
        0.2 * rng.standard_normal(t.size),          # hips: still
        40 * np.sin(phase) + 10,                     # arm.rx: waves
        25 * np.sin(phase + 0.7),                    # arm.rz: waves, another phase
        30 * np.sin(phase + 2.0),                    # leg.rx: steps in time with the arm
        0.2 * rng.standard_normal(t.size),          # head: still
    ])
    return Motion(values, CHANNELS, rate, star_skeleton(CHANNELS), f"take{seed}")


def leg_body(x, hip, z, swing, scale: float, frame_time: str):
    """A hip and a straight leg (thigh 4, shin 5, in units of ``scale``): per frame the hip at
    ``x``, ``hip`` (height), ``z`` and the thigh turned ``swing`` degrees about x, which turns
    the shin below it (the foot is ``scale * (4 + 5 cos(swing))`` under the hip)."""
    from kinetology.bvh import parse_bvh

    rows = [f"{x[k]:.9f} {hip[k]:.9f} {z[k]:.9f} {swing[k]:.9f} 0" for k in range(len(hip))]
    return parse_bvh(f"""HIERARCHY
ROOT Hips
{{ OFFSET 0 0 0
  CHANNELS 3 Xposition Yposition Zposition
  JOINT thigh
  {{ OFFSET 0 {-4 * scale} 0
    CHANNELS 1 Xrotation
    JOINT shin
    {{ OFFSET 0 {-5 * scale} 0
      CHANNELS 1 Xrotation
      End Site
      {{ OFFSET 0 0 0 }} }} }} }}
MOTION
Frames: {len(hip)}
Frame Time: {frame_time}
""" + "\n".join(rows) + "\n")


def build_walk_and_stay(root: Path, leg) -> Path:
    """A praxicon (``root/px``) of a walk and a stand, m.walk and m.stay, each learnt from three
    takes ``leg(seed, pace)`` (pace 10 and 0 units a second) written into ``root``."""
    from kinetology import write_bvh
    from praxicon import build, read_dataset

    rows = ["action,file"]
    for name, pace, seeds in (("walk", 10.0, (1, 2, 3)), ("stay", 0.0, (4, 5, 6))):
        for seed in seeds:
            write_bvh(leg(seed, pace), root / f"{name}{seed}.bvh")
            rows.append(f"{name},{root / f'{name}{seed}.bvh'}")
    (root / "m.csv").write_text("\n".join(rows) + "\n")
    build(read_dataset(root / "m.csv"), root / "px", progress=False, log=lambda s: None)
    return root / "px"


def build_wave_and_step(folder: Path) -> Path:
    """A praxicon (``folder/px``) of moves.wave and moves.step, learnt from three BVH takes
    each written into ``folder`` with their manifest (:func:`write_manifest`)."""
    from praxicon import build, read_dataset

    manifest = write_manifest(folder, {"wave": [1, 2, 3], "step": [4, 5, 6]})
    build(read_dataset(manifest), folder / "px", progress=False, log=lambda s: None)
    return folder / "px"


def write_manifest(folder: Path, actions: dict[str, list[int]], missing: bool = False) -> Path:
    """BVH takes and a CSV manifest: ``actions`` maps an action to its takes' seeds."""
    from kinetology import write_bvh

    lines = ["action,file,start,stop"]
    for action, seeds in actions.items():
        for seed in seeds:
            name = f"{action}_{seed}.bvh"
            write_bvh(take(seed), folder / name)
            lines.append(f"{action},{name},,")
    if missing:
        lines.append("ghost,nowhere.bvh,,")
        lines.append("ghost,nowhere_either.bvh,0,1")
    path = folder / "moves.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture
def manifest(tmp_path) -> Path:
    """Two actions of three takes each, one of a single take, one whose files are missing."""
    data = tmp_path / "data"
    data.mkdir()
    return write_manifest(data, {"wave": [1, 2, 3], "step": [4, 5, 6], "alone": [7]},
                          missing=True)


def needs_mocap():
    return pytest.mark.skipif(not SHARED.is_dir(), reason="../shared/data/mocap is absent")


def run_praxicon(capsys, argv) -> tuple[int, str, str]:
    """``psgs praxicon ARGV`` in this process: its status, stdout and stderr."""
    from praxicon.cli import main

    capsys.readouterr()
    status = main(argv)
    captured = capsys.readouterr()
    return status, captured.out, captured.err


def refused(capsys, argv) -> str:
    """The one error line (without ``psgs: error: ``) of a command that must refuse before
    printing any answer."""
    status, out, err = run_praxicon(capsys, argv)
    assert status == 2 and out == "", (status, out, err)
    (line,) = err.splitlines()
    assert line.startswith("psgs: error: ") and "Traceback" not in err
    return line[len("psgs: error: "):]
