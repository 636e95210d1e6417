"""Reading motion files: kinetology.read's time and peak memory against the file's size.

Real takes of ../shared/data/mocap (BVH of Bandai Namco and CMU, AMC of CMU with its ASF and
without) and larger files made from them by repeating their frames (a 31 MB BVH, a 10 MB
AMC), written to a temporary folder. Each is read the best of three times (wall time) and once
more under ``tracemalloc`` for the peak bytes allocated while reading and the bytes the motion
read still holds, both per byte of the file.

    python benchmarks/motion_reading.py            # ~1 minute; writes docs/data/motion_reading.csv
                                                   # and the "motion-reading" section of
                                                   # docs/kinetology.md
    python benchmarks/motion_reading.py --no-write
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

from _common import (DATA, DOCS, MOCAP, best_of, peak_bytes, replace_section, require,
                     write_csv)

_BANDAI = MOCAP / "bandai-namco-1" / "data" / "dataset-1_dance-short_normal_001.bvh"
_CMU_BVH = MOCAP / "cmu-01_01-pair" / "01_01.bvh"
_CMU_AMC = MOCAP / "cmu-subject02" / "02_10.amc"
_MOCAP6 = MOCAP / "cmu-mocap6" / "amc" / "13_29.amc"


def _repeated_bvh(source: Path, times: int, out: Path) -> Path:
    """``source`` with its frame lines repeated ``times`` over (the header's count to match)."""
    head, _, tail = source.read_text(encoding="utf-8").partition("\nMOTION")
    lines = tail.split("\n")
    at = next(i for i, line in enumerate(lines) if line.strip().lower().startswith("frame time"))
    frames = [line for line in lines[at + 1:] if line.strip()] * times
    out.write_text(f"{head}\nMOTION\nFrames: {len(frames)}\n{lines[at].strip()}\n"
                   + "\n".join(frames) + "\n", encoding="utf-8")
    return out


def _repeated_amc(source: Path, times: int, out: Path) -> Path:
    """``source``'s frames repeated ``times`` over, numbered on; its ASF copied beside."""
    lines = source.read_text(encoding="utf-8").split("\n")
    start = next(i for i, line in enumerate(lines) if line.strip().isdigit())
    data = [line for line in lines[start:] if line.strip()]
    per_frame = next(i for i in range(1, len(data)) if data[i].strip().isdigit())
    bones = [data[i + 1:i + per_frame] for i in range(0, len(data), per_frame)]
    written = lines[:start]
    for number in range(len(bones) * times):
        written.append(str(number + 1))
        written.extend(bones[number % len(bones)])
    out.write_text("\n".join(written) + "\n", encoding="utf-8")
    asf = source.with_name(source.name.split("_")[0] + ".asf")
    out.with_name(out.name.split("_")[0] + ".asf").write_bytes(asf.read_bytes())
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-write", action="store_true", help="print only")
    args = parser.parse_args(argv)
    kinetology = require("kinetology")
    for path in (_BANDAI, _CMU_BVH, _CMU_AMC, _MOCAP6):
        if not path.is_file():
            raise SystemExit(f"{path} not found: the shared motion data is needed")
    rows, lines = [], []
    with tempfile.TemporaryDirectory() as folder:
        made = Path(folder)
        files = [("Bandai Namco dance (BVH)", _BANDAI), ("CMU 01_01 (BVH)", _CMU_BVH),
                 ("CMU 02_10 with its ASF (AMC)", _CMU_AMC),
                 ("cmu-mocap6 13_29, no ASF (AMC)", _MOCAP6),
                 ("Bandai Namco dance x 13 (BVH)", _repeated_bvh(_BANDAI, 13, made / "d.bvh")),
                 ("CMU 02_10 x 5 (AMC)", _repeated_amc(_CMU_AMC, 5, made / "02_x5.amc"))]
        for name, path in files:
            size = path.stat().st_size
            seconds, motion = best_of(3, lambda: kinetology.read(path))
            values = motion.values.size
            del motion
            peak, held = peak_bytes(lambda: kinetology.read(path))
            rows.append([name, size, values, f"{seconds:.4f}", peak, held])
            lines.append(f"| {name} | {size / 1e6:.2f} MB | {values / 1e6:.2f} M | "
                         f"{seconds:.3f} s | {size / 1e6 / seconds:.0f} MB/s | "
                         f"{peak / size:.2f} | {held / size:.2f} |")
            print(lines[-1], flush=True)
    table = ("Measured by `python benchmarks/motion_reading.py` (time: best of three, wall; "
             "memory: `tracemalloc`, bytes per byte of the file):\n\n"
             "| file | size | values | read | speed | peak | held (the motion) |\n"
             "|---|---:|---:|---:|---:|---:|---:|\n" + "\n".join(lines))
    if not args.no_write:
        write_csv(DATA / "motion_reading.csv",
                  ["file", "bytes", "values", "read_s", "peak_bytes", "held_bytes"], rows)
        replace_section(DOCS / "kinetology.md", "motion-reading", table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
