"""Compactness and reconstructivity on the CMU 120 fps files: ours against quantise+delta+xz.

Run from the repository root (it takes a few minutes; on a shared machine under the lock):

    flock /tmp/heavy.lock python benchmarks/compression.py           # the 16 CMU takes
    flock /tmp/heavy.lock python benchmarks/compression.py --quick   # three takes, fewer points

Measures, on the same files:

* lossless gzip -9 and xz -9e of the AMC text;
* the peer, quantise + frame delta + xz, at a ladder of steps;
* our codec: the base alone at the rate-control ladder's settings, and the
  base plus the residual layer at a ladder of residual steps; their
  rate-distortion front (the points no other point beats on size and error);
* at every error from 0.1° to 1° (step 0.05°), our size and the peer's, each
  interpolated on its own front (size log-linear in error between the two
  measured points either side) and their ratio;
* rate control, ``compress(motion, max_error=DEG)`` at 0.15°, 0.3°, 0.45° on
  every file: the error reached on each file after decoding, the bound met or not.

Sizes are totals over the files (sum of compressed bytes / sum of AMC bytes).
Errors are mean absolute differences over every frame, over the 59 angle
channels (degrees; rotation channels compared modulo 360°, the codec decodes
them unwrapped) and over all 62 channels (root translations in ASF length
units). The fronts, the ratios and the bound are on the angle error.

Writes docs/data/kin_compression.csv (one row per measured point), the
picture docs/img/kin_rate_distortion.png, and the tables into the
``kin-compression`` part of docs/benchmarks.md and docs/kinetology.md.
"""

from __future__ import annotations

import argparse
import gzip
import lzma
import sys
import time
from pathlib import Path

import numpy as np

from _common import DATA, IMG, MOCAP, REPO, replace_section, require, write_csv

kinetology = require("kinetology")
from kinetology.baselines import (quantise_delta_compress,  # noqa: E402
                                  quantise_delta_decompress)
from kinetology.codec import CODEC_DEFAULTS, compress, decompress, mean_errors  # noqa: E402
from kinetology.codec.rate import BASE_LADDER, HYSTERESIS, RESIDUAL_BASES  # noqa: E402

PAPER = (3.698, 0.823)
PEER_STEPS = (0.3, 0.4, 0.5, 0.7, 1.0, 1.3, 1.6, 2.0, 2.5, 3.0, 4.0, 5.0)
RESIDUAL_STEPS = (0.25, 0.3, 0.4, 0.5, 0.65, 0.8, 1.0, 1.3, 1.6, 2.0, 2.5)
BOUNDS = (0.15, 0.3, 0.45)
GRID = tuple(round(0.1 + 0.05 * i, 2) for i in range(19))  # 0.1 .. 1.0


def cmu_files(quick: bool) -> list[Path]:
    files = sorted((MOCAP / "cmu-mocap6" / "amc").glob("*.amc"))
    files += sorted((MOCAP / "cmu-subject02").glob("*.amc"))
    files += sorted((MOCAP / "cmu-01_01-pair").glob("*.amc"))
    if quick:
        files = [f for f in files if f.stem in ("13_30", "02_05", "01_01")]
    return files


def log(message: str) -> None:
    print(message, file=sys.stderr, flush=True)


def measure(motions, encoded):
    """Totals over files: size (% of AMC), mean abs error over angles, over all channels."""
    packed = original = 0
    angle_sum = angle_count = all_sum = all_count = 0.0
    for (path, motion), (data, decoded) in zip(motions, encoded):
        packed += len(data)
        original += path.stat().st_size
        angles, every = mean_errors(motion, decoded)
        n_angles = len(motion.rotation_channels()) * motion.frames
        angle_sum += angles * n_angles
        angle_count += n_angles
        all_sum += every * motion.values.size
        all_count += motion.values.size
    return 100.0 * packed / original, angle_sum / angle_count, all_sum / all_count


def ours(motions, **params):
    encoded = []
    for _, motion in motions:
        data = compress(motion, **params)
        encoded.append((data, decompress(data)))
    return measure(motions, encoded)


def peer(motions, step):
    encoded = []
    for _, motion in motions:
        data = quantise_delta_compress(motion, step)
        decoded = quantise_delta_decompress(data).values
        encoded.append((data, kinetology.Motion(decoded, motion.channels, motion.frame_rate)))
    return measure(motions, encoded)


def pareto(points):
    """Points (size, error, ...) not beaten on both size and error by another, by error."""
    return sorted([p for p in points
                   if not any(q[0] <= p[0] and q[1] <= p[1] and q[:2] != p[:2] for q in points)],
                  key=lambda p: p[1])


def size_at(error, front):
    """Size at ``error`` on a front: log-linear between the measured points either side."""
    errors = np.array([p[1] for p in front])
    sizes = np.log(np.array([p[0] for p in front]))
    if not errors[0] <= error <= errors[-1]:
        return None
    return float(np.exp(np.interp(error, errors, sizes)))


def rate_control(motions, bound):
    rows, encoded = [], []
    for path, motion in motions:
        t0 = time.perf_counter()
        data = compress(motion, max_error=bound)
        seconds = time.perf_counter() - t0
        decoded = decompress(data)
        reached = mean_errors(motion, decoded)[0]
        mode = "base + residual" if data.settings["residual_step"] else "base only"
        rows.append((path.stem, reached, 100.0 * len(data) / path.stat().st_size, mode,
                     seconds, reached <= bound))
        encoded.append((data, decoded))
    return rows, measure(motions, encoded)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="three takes, fewer points")
    parser.add_argument("--no-write", action="store_true", help="print only")
    parser.add_argument("--only", nargs="+", metavar="TAKE",
                        help="only these takes (e.g. 02_03), for a quick look")
    args = parser.parse_args(argv)
    if not MOCAP.is_dir():
        raise SystemExit(f"no motion data at {MOCAP}")
    started = time.perf_counter()
    files = cmu_files(args.quick and not args.only)
    if args.only:
        files = [f for f in files if f.stem in args.only]
    motions = [(path, kinetology.read(path)) for path in files]
    total_bytes = sum(p.stat().st_size for p in files)
    frames = sum(m.frames for _, m in motions)
    rows = []  # (codec, parameters, size %, angle error, all-channel error)

    gz = sum(len(gzip.compress(p.read_bytes(), 9)) for p in files)
    xz = sum(len(lzma.compress(p.read_bytes(), preset=9 | lzma.PRESET_EXTREME)) for p in files)
    rows.append(("gzip -9 (lossless)", "", 100.0 * gz / total_bytes, 0.0, 0.0))
    rows.append(("xz -9e (lossless)", "", 100.0 * xz / total_bytes, 0.0, 0.0))

    t0 = time.perf_counter()
    default = ours(motions)
    ours_seconds = time.perf_counter() - t0
    rows.append(("kinetology (defaults)", _params_text(CODEC_DEFAULTS), *default))

    peer_steps = PEER_STEPS[::2] + (PEER_STEPS[-1],) if args.quick else PEER_STEPS
    peer_points = []
    for step in peer_steps:
        point = peer(motions, step)
        peer_points.append(point)
        rows.append(("quantise+delta+xz", f"step={step}", *point))
        log(f"peer step {step}: {point[0]:.3f}% at {point[1]:.3f} deg")

    sweep = []  # (size, angle error, all error, description)
    for smoothing, quantum in BASE_LADDER:
        point = ours(motions, smoothing=smoothing, quantum=quantum)
        text = f"smoothing={smoothing} quantum={quantum}"
        sweep.append((*point, "base only", text))
        rows.append(("kinetology base only", text, *point))
        log(f"base {text}: {point[0]:.3f}% at {point[1]:.3f} deg")
    steps = RESIDUAL_STEPS[::2] if args.quick else RESIDUAL_STEPS
    for smoothing, quantum in RESIDUAL_BASES:
        for step in steps:
            t0 = time.perf_counter()
            point = ours(motions, smoothing=smoothing, quantum=quantum, residual_step=step,
                         hysteresis=HYSTERESIS)
            text = (f"smoothing={smoothing} quantum={quantum} residual_step={step} "
                    f"hysteresis={HYSTERESIS}")
            sweep.append((*point, "base + residual", text))
            rows.append(("kinetology base + residual", text, *point))
            log(f"residual {text}: {point[0]:.3f}% at {point[1]:.3f} deg "
                f"({time.perf_counter() - t0:.1f} s)")
    front = pareto(sweep)
    peer_front = pareto(peer_points)

    control = {}
    for bound in BOUNDS:
        per_file, total = rate_control(motions, bound)
        control[bound] = (per_file, total)
        rows.append(("kinetology max_error", f"max_error={bound}", *total))
        log(f"max_error {bound}: {total[0]:.3f}% at {total[1]:.3f} deg; "
            f"{sum(r[5] for r in per_file)}/{len(per_file)} files within the bound")
    elapsed = time.perf_counter() - started

    if not args.no_write:
        write_csv(DATA / "kin_compression.csv",
                  ["codec", "parameters", "size_percent", "mae_angles", "mae_all"],
                  [[r[0], r[1], f"{r[2]:.4f}", f"{r[3]:.4f}", f"{r[4]:.4f}"] for r in rows])

    command = f"python benchmarks/compression.py{' --quick' if args.quick else ''}"
    lines = [f"Measured by `{command}` on {len(files)} CMU takes at 120 fps ({frames} frames, "
             f"{total_bytes / 1e6:.1f} MB of AMC text: cmu-mocap6, cmu-subject02, cmu-01_01; "
             f"{elapsed:.0f} s in all). Size = total compressed bytes / total AMC bytes; "
             f"error = mean absolute difference over the 59 angle channels (degrees, compared "
             f"modulo 360°) and over all 62 channels (root translations in ASF length units).",
             "", "| codec | parameters | size (% of AMC) | mean abs error, angles (deg) | "
             "all channels |", "|---|---|---:|---:|---:|",
             f"| the paper | | {PAPER[0]:.3f} | | {PAPER[1]:.3f} |"]
    for r in rows:
        lines.append(f"| {r[0]} | {r[1]} | {r[2]:.3f} | {r[3]:.3f} | {r[4]:.3f} |")
    lines += ["", "Ours against the peer at equal angle error, from 0.1° to 1°: each size "
              "interpolated on its own rate-distortion front (the measured points above that no "
              "other point of the same codec beats on both size and error), log-linearly in size "
              "between the two points either side of the error:", "",
              "| angle error (deg) | ours: size % | quantise+delta+xz: size % | ours / peer |",
              "|---:|---:|---:|---:|"]
    ratios = []
    for error in GRID:
        a, b = size_at(error, front), size_at(error, peer_front)
        if a is None or b is None:
            lines.append(f"| {error:.2f} | {a or float('nan'):.3f} | {b or float('nan'):.3f} "
                         f"| outside a front |")
            continue
        ratios.append(a / b)
        lines.append(f"| {error:.2f} | {a:.3f} | {b:.3f} | {a / b:.2f} |")
    worst = max(ratios) if ratios else float("nan")
    lines += ["", f"Ratio below 1 at {sum(r < 1 for r in ratios)} of {len(GRID)} errors "
              f"(largest {worst:.2f}). Our front: "
              + "; ".join(f"{p[3]} {p[4].replace('smoothing=', 's=')} -> {p[0]:.3f}% at "
                          f"{p[1]:.3f}°" for p in front) + ".", "",
              "Rate control, `kinetology.compress(motion, max_error=DEG)` on every file (the "
              "error measured on the decoded motion):", "",
              "| bound (deg) | files within it | largest error reached | total size % | "
              "mean error, angles | all channels | base only / + residual | "
              "seconds per file (mean) |", "|---:|---:|---:|---:|---:|---:|---:|---:|"]
    for bound, (per_file, total) in control.items():
        within = sum(r[5] for r in per_file)
        modes = sum(r[3] == "base only" for r in per_file)
        lines.append(f"| {bound} | {within} of {len(per_file)} | "
                     f"{max(r[1] for r in per_file):.4f} | {total[0]:.3f} | {total[1]:.3f} | "
                     f"{total[2]:.3f} | {modes} / {len(per_file) - modes} | "
                     f"{np.mean([r[4] for r in per_file]):.1f} |")
    lines += ["", f"The defaults (the base alone, as in the paper) give {default[0]:.3f}% at "
              f"{default[1]:.3f}° ({default[2]:.3f} over all channels, the paper's measure: "
              f"{PAPER[0]}% at {PAPER[1]}); encoding and decoding all files at the defaults took "
              f"{ours_seconds:.1f} s. Data: `docs/data/kin_compression.csv`; picture: "
              f"`docs/img/kin_rate_distortion.png`."]
    text = "\n".join(lines)
    print(text)
    if not args.no_write:
        try:
            from kinetology.plotting import plot_rate_distortion, save
            curves = {"kinetology (front)": [(p[0], p[1]) for p in front],
                      "quantise+delta+xz": [(p[0], p[1]) for p in peer_points],
                      "kinetology max_error (0.15, 0.3, 0.45)":
                          [(t[0], t[1]) for _, t in control.values()],
                      "kinetology defaults": [(default[0], default[1])]}
            fig = plot_rate_distortion(curves, PAPER)
            ax = fig.axes[0]
            ax.set_xlabel("mean absolute error over the 59 angle channels (degrees)")
            ax.set_title(f"{len(files)} CMU takes; the paper's point is over all channels",
                         fontsize=9)
            fig.tight_layout()
            IMG.mkdir(parents=True, exist_ok=True)
            save(fig, IMG / "kin_rate_distortion.png")
        except ImportError as exc:
            print(f"(no picture: {exc})")
        replace_section(REPO / "docs" / "benchmarks.md", "kin-compression", text)
        replace_section(REPO / "docs" / "kinetology.md", "kin-compression", text)
    return 0


def _params_text(params) -> str:
    return " ".join(f"{k}={v:g}" for k, v in params.items())


if __name__ == "__main__":
    sys.exit(main())
