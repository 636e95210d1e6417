"""Success against noise on the paper's synthetic protocol, its variants, and random input.

Run from the repository root (about 3 minutes on 2 cores):

    python benchmarks/noise.py [--trials 100] [--jobs 2]

Writes docs/data/noise.csv (paper protocol, PAL and Sequential, 0 to 40% in
steps of 2%), docs/data/noise_variants.csv (PAL on random durations,
irregular gaps, unequal lengths and all three, 0 to 40% in steps of 4%),
docs/data/noise_summary.json, the figures docs/img/noise_paper.png and
docs/img/noise_variants.png (when matplotlib is installed), and the pal
section of docs/benchmarks.md. The same sweep is available as
``psgs bench noise``.
"""

from __future__ import annotations

import argparse
import datetime
import json
import sys
import time

from _common import DATA, IMG, require, write_csv

require("psgs")
from pal_speed import write_section  # noqa: E402 (a sibling script, found the same way)

from psgs.induce import PAL, Sequential  # noqa: E402
from psgs.induce.sweep import noise_sweep  # noqa: E402
from psgs.induce.synthetic import PAPER_POINTS, generate  # noqa: E402
PAPER_LEVELS = tuple(round(0.02 * k, 2) for k in range(21))
VARIANT_LEVELS = tuple(round(0.04 * k, 2) for k in range(11))
VARIANTS = {"random durations": {"durations": "random"},
            "irregular gaps": {"irregular_gaps": True},
            "unequal lengths": {"unequal_lengths": True},
            "all three": {"durations": "random", "irregular_gaps": True,
                          "unequal_lengths": True}}


def progress(label):
    began = time.perf_counter()

    def report(done, total):
        sys.stderr.write(f"\r{label}: {done}/{total} cells, {time.perf_counter() - began:.0f} s")
        if done == total:
            sys.stderr.write("\n")
    return report


HEADER = ["inducer", "variant", "noise", "trials", "successes", "rate", "seconds"]


def sweep_rows(rows, variant):
    """CSV rows of a sweep's results, all of one protocol variant."""
    return [[r.inducer, variant, f"{r.noise:.2f}", r.trials, r.successes, f"{r.rate:.4f}",
             f"{r.seconds:.3f}"] for r in rows]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=100)
    parser.add_argument("--random-trials", type=int, default=1000)
    parser.add_argument("--jobs", type=int, default=2)
    args = parser.parse_args(argv)
    DATA.mkdir(parents=True, exist_ok=True)
    IMG.mkdir(parents=True, exist_ok=True)

    began = time.perf_counter()
    pal_rows = noise_sweep(PAPER_LEVELS, args.trials, inducers=("pal",), jobs=args.jobs,
                           progress=progress("paper protocol, PAL"))
    pal_wall = time.perf_counter() - began
    seq_rows = noise_sweep(PAPER_LEVELS, args.trials, inducers=("sequential",), jobs=args.jobs,
                           progress=progress("paper protocol, Sequential"))
    paper_rows = pal_rows + seq_rows
    write_csv(DATA / "noise.csv", HEADER, sweep_rows(paper_rows, "paper"))

    variant_rows = {}
    for name, variant in VARIANTS.items():
        variant_rows[name] = noise_sweep(VARIANT_LEVELS, args.trials, inducers=("pal",),
                                         variant=variant, jobs=args.jobs,
                                         progress=progress(f"variant {name}"))
    write_csv(DATA / "noise_variants.csv", HEADER,
              [row for name, rows in variant_rows.items() for row in sweep_rows(rows, name)])

    with_components = {"pal": 0, "sequential": 0}
    pal, seq = PAL(), Sequential()
    for t in range(args.random_trials):
        ag = generate(seed=100_000 + t, patterned=0).actiongram
        with_components["pal"] += bool(pal.induce(ag).components)
        with_components["sequential"] += bool(seq.induce(ag).components)
    print(f"all-random actiongrams with components: {with_components} of {args.random_trials}")

    by = {(r.inducer, r.noise): r.rate for r in paper_rows}
    summary = {
        "command": "python benchmarks/noise.py" + (f" --trials {args.trials}"
                                                   if args.trials != 100 else ""),
        "date": datetime.date.today().isoformat(),
        "trials": args.trials, "levels": len(PAPER_LEVELS), "jobs": args.jobs,
        "pal_sweep_seconds": pal_wall,
        "pal_sweep_cpu_seconds": sum(r.cpu_seconds for r in pal_rows),
        "paper_table": [{"noise": lv, "pal": by["pal", lv], "sequential": by["sequential", lv],
                         "paper": (f"{PAPER_POINTS[lv]:.0%}" if lv in PAPER_POINTS else "")}
                        for lv in PAPER_LEVELS],
        "random_trials": args.random_trials, "random_with_components": with_components,
        "variants": {name: {f"{r.noise:.2f}": r.rate for r in rows}
                     for name, rows in variant_rows.items()},
    }
    (DATA / "noise_summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    for row in summary["paper_table"]:
        print(f"{row['noise']:.2f}  PAL {row['pal']:.0%}  Sequential {row['sequential']:.0%}")
    print(f"PAL sweep: {pal_wall:.1f} s wall ({args.jobs} jobs), "
          f"{summary['pal_sweep_cpu_seconds']:.1f} s CPU in the workers")

    try:
        from psgs.cli.bench import plot_noise
        plot_noise(paper_rows, str(IMG / "noise_paper.png"),
                   title=f"Paper protocol, {args.trials} actiongrams per level")
        plot_variants(variant_rows, pal_rows, IMG / "noise_variants.png", args.trials)
    except ImportError:
        print("matplotlib is not installed: no figures (pip install 'psgs[plot]')",
              file=sys.stderr)

    write_section()
    return 0


def plot_variants(variant_rows, paper_rows, path, trials) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=120)
    base = sorted((r.noise, r.rate) for r in paper_rows)
    ax.plot([x * 100 for x, _ in base], [y * 100 for _, y in base], color="black", lw=2,
            label="paper protocol")
    for name, rows in variant_rows.items():
        pts = sorted((r.noise, r.rate) for r in rows)
        ax.plot([x * 100 for x, _ in pts], [y * 100 for _, y in pts], marker="o", markersize=3,
                label=name)
    ax.set_xlabel("noise (% of symbols replaced in each patterned string)")
    ax.set_ylabel("PAL success (% of actiongrams)")
    ax.set_ylim(-3, 103)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower left", fontsize=8)
    ax.set_title(f"PAL on harder variants, {trials} actiongrams per level", fontsize=9)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


if __name__ == "__main__":
    sys.exit(main())
