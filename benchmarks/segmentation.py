"""Segmentation (and reading) throughput, in samples per second.

Run from the repository root:

    python benchmarks/segmentation.py

A sample is one value of one channel in one frame. Measures, best of
``--repeat`` runs each: reading every CMU AMC file, segmenting every angle
channel of those files with the default parameters (``segments``, and ``segment``: the
same plus building the ``psgs.Actiongram``), and segmenting a synthetic
100,000-frame x 62-channel motion (issue 13's target: at least 50 M samples/s).
Writes its table into the ``kin-segmentation`` part of docs/benchmarks.md.
"""

from __future__ import annotations

import argparse
import platform
import sys

import numpy as np
from _common import BENCHMARKS_PAGE, MOCAP, best_of, replace_section, require

kinetology = require("kinetology")
from kinetology.segmentation import segment, segments  # noqa: E402


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    rows = []
    if MOCAP.is_dir():
        files = sorted(MOCAP.glob("cmu-*/**/*.amc"))
        read_time, motions = best_of(args.repeat, lambda: [kinetology.read(f) for f in files])
        samples = sum(m.values.size for m in motions)
        rows.append((f"read {len(files)} CMU AMC files", samples, read_time))
        angle_samples = sum(m.frames * len(m.rotation_channels()) for m in motions)
        seg_time, _ = best_of(args.repeat, lambda: [segments(m) for m in motions])
        rows.append(("segment their angle channels (defaults)", angle_samples, seg_time))
        seg_time, _ = best_of(args.repeat, lambda: [segment(m) for m in motions])
        rows.append(("the same into actiongrams (`segment`)", angle_samples, seg_time))
        bandai = sorted((MOCAP / "bandai-namco-1" / "data").glob("*.bvh"))
        read_time, bvhs = best_of(1, lambda: [kinetology.read(f) for f in bandai])
        rows.append((f"read {len(bandai)} Bandai Namco BVH files (30 fps)",
                     sum(m.values.size for m in bvhs), read_time))
        seg_time, _ = best_of(args.repeat, lambda: [segments(m) for m in bvhs])
        bvh_samples = sum(m.frames * len(m.rotation_channels()) for m in bvhs)
        rows.append(("segment their angle channels", bvh_samples, seg_time))
        seg_time, _ = best_of(args.repeat, lambda: [segment(m) for m in bvhs])
        rows.append(("the same into actiongrams (`segment`)", bvh_samples, seg_time))
    rng = np.random.default_rng(0)
    big = kinetology.Motion(np.cumsum(rng.normal(size=(100_000, 62)), axis=0),
                            tuple(f"j{i}.rx" for i in range(62)), 120.0)
    seg_time, _ = best_of(args.repeat, lambda: segments(big))
    rows.append(("segment a synthetic 100,000 x 62 random walk", big.values.size, seg_time))
    lines = [f"Measured by `python benchmarks/segmentation.py` (best of {args.repeat}; "
             f"Python {platform.python_version()}, numpy {np.__version__}, one core of the "
             f"project's 2-core machine). All channels of a take are segmented together "
             f"(kinetology/_kinetemes.py: the 120 fps smoothing as blocks of a banded matrix "
             f"product, runs and dead bands as array passes over groups of channels), and "
             f"the actiongram is built from the codes by `Actiongram.from_codes`; the output "
             f"is byte-identical to the former per-channel code on every file of "
             f"../shared/data/mocap.", "",
             "| task | samples | seconds | samples/s |", "|---|---:|---:|---:|"]
    for name, samples, seconds in rows:
        lines.append(f"| {name} | {samples:,} | {seconds:.3f} | {samples / seconds:,.0f} |")
    text = "\n".join(lines)
    print(text)
    if not args.no_write:
        replace_section(BENCHMARKS_PAGE, "kin-segmentation", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
