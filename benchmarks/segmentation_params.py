"""Segmentation parameters across frame rates and tempos: the measurements behind the defaults.

Run from the repository root (under the lock on a shared machine):

    flock /tmp/heavy.lock python benchmarks/segmentation_params.py

For each parameter setting, three measurements on the shared real motion:

* **rate**: the cmu-mocap6 takes (120 fps) segmented as they are and with every fourth frame
  (30 fps, what a 30 fps camera records): share of the 30 fps frames whose state equals the
  120 fps state at the same instant, and the ratio of kineteme counts (30 / 120; 1 is best).
* **tempo**: the Bandai Namco dataset-1 takes (30 fps) as they are and slowed to half speed
  (cubic interpolation to twice the frames at the same rate, as a slow style would be
  recorded): state agreement at the same point of the motion and kineteme count ratio.
* **illegal**: share of kineteme transitions no smooth motion can make (B->R, B->Y, G->Y,
  R->B, R->G, Y->G: the velocity changes sign against the acceleration's), on both datasets
  at their own rates.

Writes the table into docs/kinetology.md (part ``kin-rates``) and docs/data/kin_rates.csv.
"""

from __future__ import annotations

import argparse
import csv
import sys
from pathlib import Path

import numpy as np

from _common import MOCAP, REPO, replace_section, require

require("kinetology")
import kinetology  # noqa: E402
from kinetology.segmentation import DEFAULTS, states, unwrap  # noqa: E402

# (from, to) state codes B=0 G=1 R=2 Y=3 that a smooth signal cannot make
ILLEGAL = {(0, 2), (0, 3), (1, 3), (2, 0), (2, 1), (3, 1)}
def _setting(smoothing, velocity, acceleration, relative):
    name = f"{smoothing:g} s, {velocity:g} deg/s, {acceleration:g} deg/s²" + \
        (f", relative {relative:g}" if relative else "")
    return name, {"smoothing": smoothing, "velocity_deadband": velocity,
                  "acceleration_deadband": acceleration, "relative_deadband": relative}


SETTINGS = [_setting(0.025, 5, 200, 0), _setting(0.05, 5, 200, 0), _setting(0.05, 5, 50, 0),
            _setting(0.05, 5, 25, 0), _setting(0.05, 2, 10, 0), _setting(0.05, 2, 5, 0.1),
            _setting(0.05, 2, 10, 0.1), _setting(0.05, 2, 20, 0.1), _setting(0.05, 2, 10, 0.05),
            _setting(0.05, 2, 10, 0.2), _setting(0.075, 2, 10, 0.1), _setting(0.1, 2, 10, 0.1)]


def moving_angles(motion, min_range=DEFAULTS["min_range"]):
    values = unwrap(motion.values[:, [motion.index(c) for c in motion.rotation_channels()]])
    return values[:, np.ptp(values, axis=0) >= min_range]


def kinetemes(code):
    return int((code[1:] != code[:-1]).sum() + code.shape[1])


def illegal(code):
    changed = code[1:] != code[:-1]
    pairs = list(zip(code[:-1][changed].tolist(), code[1:][changed].tolist()))
    return sum(p in ILLEGAL for p in pairs), len(pairs)


def half_speed(values):
    """Twice the frames: the samples, and between them the 4-point cubic midpoint
    ``(-x[i-1] + 9 x[i] + 9 x[i+1] - x[i+2]) / 16`` (linear interpolation would put a kink,
    a spurious acceleration sign change, at every original sample)."""
    padded = np.concatenate([2 * values[:1] - values[1:2], values,
                             2 * values[-1:] - values[-2:-1]])
    middle = (-padded[:-3] + 9 * padded[1:-2] + 9 * padded[2:-1] - padded[3:]) / 16
    slow = np.empty((2 * values.shape[0] - 1, values.shape[1]))
    slow[::2] = values
    slow[1::2] = middle
    return slow


def measure(cmu, bandai, params):
    rate_agree, rate_ratio, tempo_agree, tempo_ratio = [], [], [], []
    bad = total = 0
    for values, fps in cmu:
        fine = states(values, fps, **params, unwrap=0)
        coarse = states(values[::4], fps / 4, **params, unwrap=0)
        rate_agree.append(np.mean(coarse == fine[::4]))
        rate_ratio.append(kinetemes(coarse) / kinetemes(fine))
        b, t = illegal(fine)
        bad, total = bad + b, total + t
    for values, fps in bandai:
        code = states(values, fps, **params, unwrap=0)
        slow = half_speed(values)
        slow_code = states(slow, fps, **params, unwrap=0)
        tempo_agree.append(np.mean(slow_code[::2] == code))
        tempo_ratio.append(kinetemes(slow_code) / kinetemes(code))
        b, t = illegal(code)
        bad, total = bad + b, total + t
    return {"rate_agreement": float(np.mean(rate_agree)),
            "rate_count_ratio": float(np.mean(rate_ratio)),
            "tempo_agreement": float(np.mean(tempo_agree)),
            "tempo_count_ratio": float(np.mean(tempo_ratio)),
            "illegal": bad / max(1, total)}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bandai", type=int, default=60, help="Bandai takes used (default 60)")
    parser.add_argument("--no-write", action="store_true")
    args = parser.parse_args(argv)
    cmu = [(moving_angles(m), m.frame_rate) for m in
           (kinetology.read(p) for p in sorted((MOCAP / "cmu-mocap6" / "amc").glob("*.amc")))]
    paths = sorted((MOCAP / "bandai-namco-1" / "data").glob("*.bvh"))
    step = max(1, len(paths) // args.bandai)
    bandai = [(moving_angles(m), m.frame_rate) for m in
              (kinetology.read(p) for p in paths[::step][:args.bandai])]
    header = ("setting", "rate_agreement", "rate_count_ratio", "tempo_agreement",
              "tempo_count_ratio", "illegal")
    rows = []
    for name, params in SETTINGS:
        result = measure(cmu, bandai, params)
        rows.append((name, *(round(result[h], 4) for h in header[1:])))
        print(rows[-1], flush=True)
    lines = [f"Measured by `python benchmarks/segmentation_params.py` ({len(cmu)} cmu-mocap6 "
             f"takes, {len(bandai)} Bandai Namco dataset-1 takes; smoothing sigma, velocity "
             f"and acceleration dead band floors, relative dead band).", "",
             "| setting | 120 -> 30 fps: same state | kinetemes 30/120 fps | half speed: "
             "same state | kinetemes slow/normal | impossible transitions |",
             "|---|---:|---:|---:|---:|---:|"]
    for name, ra, rr, ta, tr, bad in rows:
        lines.append(f"| {name} | {100 * ra:.1f}% | {rr:.2f} | {100 * ta:.1f}% | {tr:.2f} | "
                     f"{100 * bad:.2f}% |")
    text = "\n".join(lines)
    print(text)
    if not args.no_write:
        replace_section(REPO / "docs" / "kinetology.md", "kin-rates", text)
        with (REPO / "docs" / "data" / "kin_rates.csv").open("w", newline="") as handle:
            writer = csv.writer(handle)
            writer.writerow(header)
            writer.writerows(rows)
    return 0


if __name__ == "__main__":
    sys.exit(main())
