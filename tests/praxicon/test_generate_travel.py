"""Generated motion moves its root as the performances do (and keeps the symbolic round trip)."""

from __future__ import annotations

import numpy as np

import kinetology
from praxicon import build, read_dataset
from praxicon.generation import generate
from praxicon_fixtures import SHARED, needs_mocap


def _speed(motion, root="Hips"):
    """Net horizontal speed (cm/s) of the root over the whole motion."""
    ch = list(motion.channels)
    x, z = motion.values[:, ch.index(f"{root}.tx")], motion.values[:, ch.index(f"{root}.tz")]
    return float(np.hypot(x[-1] - x[0], z[-1] - z[0]) / ((motion.frames - 1) / motion.frame_rate))


@needs_mocap()
def test_a_generated_walk_advances_at_the_performances_speed(tmp_path):
    data = SHARED / "bandai-namco-2-subset" / "data"
    files = [data / f"dataset-2_walk_normal_00{i}.bvh" for i in (1, 2, 3)]
    manifest = tmp_path / "m.csv"
    manifest.write_text("action,file\n" + "".join(f"walk,{f}\n" for f in files))
    build(read_dataset(manifest), tmp_path / "px", progress=False, log=lambda s: None)
    generated = generate(tmp_path / "px", "m.walk", repeat=3)
    real = [_speed(kinetology.read(f)) for f in files]
    speed = _speed(generated.motion)
    # the root was held still before: now it advances, as fast as the takes do on average
    assert 0.8 * min(real) <= speed <= 1.2 * max(real), (speed, real)
    assert all(generated.round_trip().values())
