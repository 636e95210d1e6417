"""Segmentation (and reading) throughput, in samples per second, numpy engine beside numba's.

Run from the repository root:

    python benchmarks/segmentation.py

A sample is one value of one channel in one frame. Measures, best of ``--repeat`` runs each:
reading every CMU AMC file, segmenting every angle channel of those files with the default
parameters (``segments``, and ``segment``: the same plus building the ``psgs.Actiongram``),
the same for the Bandai Namco takes, and segmenting a synthetic 100,000-frame x 62-channel
motion (the target: at least 50 M samples/s), each with ``engine="numpy"`` and
``engine="numba"`` side by side; the synthetic walk also pinned to one core
(``os.sched_getaffinity``), which is the numba engine's single-thread figure. The compiled
functions are compiled (or loaded from numba's cache) before anything is timed; the time
that took is printed. Writes its table into the ``kin-segmentation`` part of
docs/benchmarks.md.
"""

from __future__ import annotations

import argparse
import os
import platform
import sys
import time

import numpy as np
from _common import BENCHMARKS_PAGE, MOCAP, best_of, replace_section, require

kinetology = require("kinetology")
from kinetology.segmentation import segment, segments  # noqa: E402

ENGINES = ("numpy", "numba")


def _both(repeat: int, task) -> tuple[float, float]:
    """Best-of times of ``task(engine)`` for each engine."""
    return tuple(best_of(repeat, lambda e=engine: task(e))[0] for engine in ENGINES)


def _pinned(cores: set[int], task):
    """``task()`` with this process allowed only ``cores`` (restored afterwards)."""
    allowed = os.sched_getaffinity(0)
    os.sched_setaffinity(0, cores)
    try:
        return task()
    finally:
        os.sched_setaffinity(0, allowed)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    numba = require("numba")  # the fast extra: pip install -e '.[fast]'

    start = time.perf_counter()
    warm = kinetology.Motion(np.cumsum(np.ones((64, 2)), axis=0), ("a.rx", "b.rx"), 120.0)
    for rate in (120.0, 30.0):  # both kernel lengths (18 and 5 frames each side)
        segments(kinetology.Motion(warm.values, warm.channels, rate), engine="numba")
    compile_seconds = time.perf_counter() - start
    cores = len(os.sched_getaffinity(0))
    rows = []  # (task, samples, numpy seconds or None (no engine), seconds)
    if MOCAP.is_dir():
        files = sorted(MOCAP.glob("cmu-*/**/*.amc"))
        read_time, motions = best_of(args.repeat, lambda: [kinetology.read(f) for f in files])
        rows.append((f"read {len(files)} CMU AMC files", sum(m.values.size for m in motions),
                     None, read_time))
        angle_samples = sum(m.frames * len(m.rotation_channels()) for m in motions)
        rows.append(("segment their angle channels (defaults)", angle_samples,
                     *_both(args.repeat, lambda e: [segments(m, engine=e) for m in motions])))
        rows.append(("the same into actiongrams (`segment`)", angle_samples,
                     *_both(args.repeat, lambda e: [segment(m, engine=e) for m in motions])))
        bandai = sorted((MOCAP / "bandai-namco-1" / "data").glob("*.bvh"))
        read_time, bvhs = best_of(1, lambda: [kinetology.read(f) for f in bandai])
        rows.append((f"read {len(bandai)} Bandai Namco BVH files (30 fps)",
                     sum(m.values.size for m in bvhs), None, read_time))
        bvh_samples = sum(m.frames * len(m.rotation_channels()) for m in bvhs)
        rows.append(("segment their angle channels", bvh_samples,
                     *_both(args.repeat, lambda e: [segments(m, engine=e) for m in bvhs])))
        rows.append(("the same into actiongrams (`segment`)", bvh_samples,
                     *_both(args.repeat, lambda e: [segment(m, engine=e) for m in bvhs])))
    rng = np.random.default_rng(0)
    big = kinetology.Motion(np.cumsum(rng.normal(size=(100_000, 62)), axis=0),
                            tuple(f"j{i}.rx" for i in range(62)), 120.0)
    walk = "segment a synthetic 100,000 x 62 random walk"
    rows.append((f"{walk} ({cores} cores)", big.values.size,
                 *_both(args.repeat, lambda e: segments(big, engine=e))))
    one = {min(os.sched_getaffinity(0))}
    rows.append((f"{walk}, pinned to one core", big.values.size,
                 *_pinned(one, lambda: _both(args.repeat, lambda e: segments(big, engine=e)))))
    lines = [f"Measured by `python benchmarks/segmentation.py` (best of {args.repeat}; "
             f"Python {platform.python_version()}, numpy {np.__version__}, numba "
             f"{numba.__version__}; the project's 2-core machine, which other jobs share). "
             f"`engine=\"numpy\"`: array passes over groups of channels "
             f"(kinetology/_kinetemes.py); `engine=\"numba\"`: one compiled pass per channel "
             f"after the smoothing (kinetology/_kinetemes_jit.py), the channels of a take of "
             f"at least 2^19 samples in one thread per core ({cores} here), so the "
             f"\"pinned to one core\" row is its single-thread figure. The smoothing is the "
             f"fixed-order direct sum in both (no BLAS: the same floats on every CPU). Both "
             f"engines' output is byte-identical on every file of ../shared/data/mocap. "
             f"Compiling (or loading the compiled code from numba's cache) took "
             f"{compile_seconds:.1f} s before the timings.", "",
             "| task | samples | numpy s | numpy samples/s | numba s | numba samples/s "
             "| numba / numpy |", "|---|---:|---:|---:|---:|---:|---:|"]
    for name, samples, plain, fast in rows:
        if plain is None:  # reading: no engine
            lines.append(f"| {name} | {samples:,} | {fast:.3f} | {samples / fast:,.0f} | | | |")
        else:
            lines.append(f"| {name} | {samples:,} | {plain:.3f} | {samples / plain:,.0f} | "
                         f"{fast:.3f} | {samples / fast:,.0f} | {plain / fast:.2f}x |")
    text = "\n".join(lines)
    print(text)
    if not args.no_write:
        replace_section(BENCHMARKS_PAGE, "kin-segmentation", text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
