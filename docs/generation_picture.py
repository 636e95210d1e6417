"""Draw the docs' pictures of generated motion: a real take beside the action generated from it.

    python docs/generation_picture.py          # from the repository root, about two minutes

* ``docs/img/prax_generated_turn.gif``: a praxicon is built (in a temporary folder) of the
  dataset-2 subset's walk-turn-right, from the first take of each of its seven styles; the
  action is generated in the normal style (``generate(..., style="normal")``, three copies)
  and played beside the normal style's first take, which is one of the takes learnt from.
* ``docs/img/kin_view_walk.gif``: the subset's walk learnt from its five normal takes (the
  action ``psgs praxicon build`` makes of them, ``walk.normal``), three copies generated, beside
  the first normal take cut to as long.

Run by hand; the pictures are committed.
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
DATA = REPO.parent / "shared" / "data" / "mocap" / "bandai-namco-2-subset" / "data"
OUT = REPO / "docs" / "img" / "prax_generated_turn.gif"
WALK = REPO / "docs" / "img" / "kin_view_walk.gif"


def main() -> int:
    import numpy as np

    import kinetology
    from praxicon import build, read_dataset
    from praxicon.generation import generate

    takes = sorted(DATA.glob("dataset-2_walk-turn-right_*_001.bvh"))
    if not takes:
        raise SystemExit(f"{DATA}: no walk-turn-right takes (the shared data sits beside the "
                         f"repository)")
    work = Path(tempfile.mkdtemp(prefix="genpicture-"))
    manifest = work / "m.csv"
    manifest.write_text("action,file\n" + "".join(f"walk-turn-right,{f}\n" for f in takes))
    build(read_dataset(manifest), work / "px", progress=False, log=lambda line: None)
    generated = generate(work / "px", "m.walk-turn-right", repeat=3, style="normal")
    real = kinetology.read(DATA / "dataset-2_walk-turn-right_normal_001.bvh")
    player = kinetology.view({"real (walk-turn-right normal 001)": real,
                              "generated (normal style, 3 copies)": generated.motion},
                             actuators=list(generated.actuators), max_rate=10)
    player.save(OUT, dpi=56)
    print(f"{OUT.relative_to(REPO)}: {real.frames / real.frame_rate:.1f} s real beside "
          f"{generated.motion.frames / generated.motion.frame_rate:.1f} s generated, "
          f"{len(generated.actuators)} actuators ringed")

    walks = sorted(DATA.glob("dataset-2_walk_normal_*.bvh"))
    manifest = work / "walk.csv"
    manifest.write_text("action,file\n" + "".join(f"walk.normal,{f}\n" for f in walks))
    build(read_dataset(manifest), work / "walk", progress=False, log=lambda line: None)
    generated = generate(work / "walk", "walk.walk.normal", repeat=3)
    motion = generated.motion
    real = kinetology.cut(kinetology.read(walks[0]), 0, (motion.frames - 1) / motion.frame_rate)
    player = kinetology.view({"real (walk normal 001)": real, "generated (3 copies)": motion},
                             actuators=list(generated.actuators), max_rate=10)
    player.save(WALK, dpi=56)
    print(f"{WALK.relative_to(REPO)}: {real.frames / real.frame_rate:.1f} s real beside "
          f"{motion.frames / motion.frame_rate:.1f} s generated from {len(walks)} normal walks, "
          f"{len(generated.actuators)} actuators ringed")
    from kinetology.kinematics import forward_kinematics

    for name, m in (("real", real), ("generated", motion)):  # what the caption says
        at = forward_kinematics(m)
        hips, head = (at[:, m.skeleton.index(j)] for j in ("Hips", "Head"))
        print(f"  {name}: Hips.rz mean {m.column('Hips.rz').mean():.1f} deg, head at "
              f"{(head[:, 1] - at[:, :, 1].min(axis=1)).mean():.0f} above the lowest joint, hips "
              f"travel {float(np.hypot(*(hips[-1] - hips[0])[[0, 2]])):.0f} in "
              f"{(m.frames - 1) / m.frame_rate:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
