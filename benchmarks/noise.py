"""Success against noise on the paper's synthetic protocol, its variants, and random input.

Run from the repository root (about 4 minutes on 2 cores):

    python benchmarks/noise.py [--trials 100] [--check-trials 1000] [--jobs 2]

Writes docs/data/noise.csv (paper protocol, PAL and Sequential, 0 to 40% in
steps of 2%, and 25%), docs/data/noise_variants.csv (PAL on random durations,
irregular gaps, unequal lengths and all three, 0 to 40% in steps of 4%, and 25% and 30%),
docs/data/noise_ceiling.csv (the information ceiling of the same actiongrams,
see below), docs/data/noise_summary.json, the figures docs/img/noise_paper.png
and docs/img/noise_variants.png (when matplotlib is installed), and the pal
section of docs/benchmarks.md. The same sweep is available as
``psgs bench noise``.

The information ceiling of a level is the share of its actiongrams where, at
no template position of any patterned string, a wrong symbol outnumbers the
true one across the true copies (``psgs.induce.synthetic.vote_margin`` >= 0),
computed on exactly the actiongrams PAL is run on; "no tie" is the share where
the true symbol leads everywhere (margin > 0), what a vote reaches without luck.

At the ceiling: on ``--check-trials`` further actiongrams a level (seeds from
1,000,000 on, not the sweep's) at 22, 24, 25, 26 and 28%, every actiongram is
run and its margin computed, so that PAL's failures are split three ways: above
the ceiling (margin < 0: a wrong symbol outnumbers the true one, no vote
recovers it), at a tie (margin 0: a wrong symbol as frequent as the true one
somewhere, a coin flip for any vote, as the noise treats both alike) and with
the true symbol leading everywhere (margin > 0: PAL's own failures); written to
docs/data/noise_ceiling_check.csv.
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
from psgs.induce.synthetic import PAPER_POINTS, generate, vote_margin  # noqa: E402

# every 2%, and 25% itself (the paper's curve holds 100% up to 25%)
PAPER_LEVELS = tuple(sorted({round(0.02 * k, 2) for k in range(21)} | {0.25}))
# every 4%, and 25% and 30% themselves (the levels the paper's curve is read at)
VARIANT_LEVELS = tuple(sorted({round(0.04 * k, 2) for k in range(11)} | {0.25, 0.30}))
CHECK_LEVELS = (0.22, 0.24, 0.25, 0.26, 0.28)
CHECK_SEED = 1_000_000  # the ceiling check's actiongrams are not the sweep's
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
    parser.add_argument("--check-trials", type=int, default=1000)
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

    ceiling = {"paper": ceiling_rows(PAPER_LEVELS, args.trials, {})}
    for name, variant in VARIANTS.items():
        ceiling[name] = ceiling_rows(VARIANT_LEVELS, args.trials, variant)
    write_csv(DATA / "noise_ceiling.csv", ["variant", "noise", "trials", "ceiling", "no_tie"],
              [[name, f"{lv:.2f}", args.trials, f"{c:.4f}", f"{t:.4f}"]
               for name, rows in ceiling.items() for lv, c, t in rows])

    check = ceiling_check(CHECK_LEVELS, args.check_trials, args.jobs)
    write_csv(DATA / "noise_ceiling_check.csv",
              ["noise", "trials", "pal_successes", "above_ceiling", "ties", "pal_failures_above",
               "pal_failures_tie", "pal_failures_leading"],
              [[f"{c['noise']:.2f}", c["trials"], c["pal_successes"], c["above_ceiling"],
                c["ties"], c["pal_failures_above"], c["pal_failures_tie"],
                c["pal_failures_leading"]] for c in check])

    with_components = {"pal": 0, "sequential": 0}
    pal, seq = PAL(), Sequential()
    for t in range(args.random_trials):
        ag = generate(seed=100_000 + t, patterned=0).actiongram
        with_components["pal"] += bool(pal.induce(ag).components)
        with_components["sequential"] += bool(seq.induce(ag).components)
    print(f"all-random actiongrams with components: {with_components} of {args.random_trials}")

    by = {(r.inducer, r.noise): r.rate for r in paper_rows}
    paper_ceiling = {lv: (c, t) for lv, c, t in ceiling["paper"]}
    summary = {
        "command": "python benchmarks/noise.py" + (f" --trials {args.trials}"
                                                   if args.trials != 100 else ""),
        "date": datetime.date.today().isoformat(),
        "trials": args.trials, "levels": len(PAPER_LEVELS), "jobs": args.jobs,
        "pal_sweep_seconds": pal_wall,
        "pal_sweep_cpu_seconds": sum(r.cpu_seconds for r in pal_rows),
        "paper_table": [{"noise": lv, "pal": by["pal", lv], "sequential": by["sequential", lv],
                         "paper": (f"{PAPER_POINTS[lv]:.0%}" if lv in PAPER_POINTS else ""),
                         "ceiling": paper_ceiling[lv][0], "no_tie": paper_ceiling[lv][1]}
                        for lv in PAPER_LEVELS],
        "random_trials": args.random_trials, "random_with_components": with_components,
        "variants": {name: {f"{r.noise:.2f}": r.rate for r in rows}
                     for name, rows in variant_rows.items()},
        "variant_ceiling": {name: {f"{lv:.2f}": c for lv, c, _ in rows}
                            for name, rows in ceiling.items() if name != "paper"},
        "ceiling_check": check, "check_seed": CHECK_SEED,
    }
    (DATA / "noise_summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    for row in summary["paper_table"]:
        print(f"{row['noise']:.2f}  PAL {row['pal']:.0%}  Sequential {row['sequential']:.0%}  "
              f"ceiling {row['ceiling']:.0%} (no tie {row['no_tie']:.0%})")
    for name, rows in variant_rows.items():
        print(f"{name}: " + ", ".join(f"{r.noise:.2f} {r.rate:.0%}" for r in rows))
    for c in check:
        print(f"at the ceiling, {c['noise']:.2f}: PAL {c['pal_successes']}/{c['trials']}; "
              f"{c['above_ceiling']} above the ceiling, {c['ties']} ties; PAL fails "
              f"{c['pal_failures_above']} above, {c['pal_failures_tie']} at a tie, "
              f"{c['pal_failures_leading']} where the true symbol leads "
              f"(seeds {c['failed_seeds']})")
    print(f"PAL sweep: {pal_wall:.1f} s wall ({args.jobs} jobs), "
          f"{summary['pal_sweep_cpu_seconds']:.1f} s CPU in the workers")

    try:
        plot_paper(paper_rows, ceiling["paper"], IMG / "noise_paper.png", args.trials)
        plot_variants(variant_rows, pal_rows, IMG / "noise_variants.png", args.trials)
    except ImportError:
        print("matplotlib is not installed: no figures (pip install 'psgs[plot]')",
              file=sys.stderr)

    write_section()
    return 0


def _check_batch(job):
    """(margin, PAL's success) of each seed of one batch: module level for the workers."""
    from psgs.induce.synthetic import success

    level, seeds = job
    pal = PAL()
    out = []
    for seed in seeds:
        case = generate(seed=seed, noise=level)
        out.append((vote_margin(case), bool(success(pal.induce(case.actiongram), case))))
    return level, out


def ceiling_check(levels, trials, jobs):
    """Per level: PAL's successes and failures split by the information ceiling."""
    from concurrent.futures import ProcessPoolExecutor

    batches = [(float(level), list(range(CHECK_SEED + a, CHECK_SEED + min(a + 100, trials))))
               for level in levels for a in range(0, trials, 100)]
    found = {float(level): [] for level in levels}
    report = progress("at the ceiling")
    with ProcessPoolExecutor(max(1, jobs)) as pool:
        for done, (level, out) in enumerate(pool.map(_check_batch, batches), 1):
            found[level] += out
            report(done, len(batches))
    rows = []
    for level, out in found.items():
        rows.append({"noise": level, "trials": len(out),
                     "pal_successes": sum(ok for _, ok in out),
                     "above_ceiling": sum(m < 0 for m, _ in out),
                     "ties": sum(m == 0 for m, _ in out),
                     "pal_failures_above": sum(m < 0 and not ok for m, ok in out),
                     "pal_failures_tie": sum(m == 0 and not ok for m, ok in out),
                     "pal_failures_leading": sum(m > 0 and not ok for m, ok in out),
                     "failed_seeds": [CHECK_SEED + i for i, (_, ok) in enumerate(out) if not ok]})
    return rows


def ceiling_rows(levels, trials, variant):
    """(level, share with margin >= 0, share with margin > 0) on the sweep's own actiongrams."""
    out = []
    for level in levels:
        margins = [vote_margin(generate(seed=t, noise=float(level), **variant))
                   for t in range(trials)]
        out.append((float(level), sum(m >= 0 for m in margins) / trials,
                    sum(m > 0 for m in margins) / trials))
    return out


def plot_paper(rows, ceiling, path, trials) -> None:
    """PAL and Sequential beside the paper's points and the information ceiling."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=120)
    ax.fill_between([lv * 100 for lv, _, _ in ceiling], [c * 100 for _, c, _ in ceiling], 103,
                    color="0.9", label="above the information ceiling")
    ax.plot([lv * 100 for lv, _, _ in ceiling], [c * 100 for _, c, _ in ceiling], color="0.4",
            lw=1.2, ls="--", label="ceiling: no wrong symbol outnumbers the true one")
    styles = {"pal": ("tab:blue", "o", "PAL"), "sequential": ("tab:orange", "s", "Sequential")}
    for name in dict.fromkeys(r.inducer for r in rows):
        mine = sorted((r.noise, r.rate) for r in rows if r.inducer == name)
        color, marker, label = styles.get(name, (None, "^", name))
        ax.plot([x * 100 for x, _ in mine], [y * 100 for _, y in mine], marker=marker,
                markersize=3.5, color=color, label=label)
    ax.plot([x * 100 for x in PAPER_POINTS], [y * 100 for y in PAPER_POINTS.values()], "k*",
            markersize=10, label="the paper (Fig. 4)")
    ax.set_xlabel("noise (% of symbols replaced in each patterned string)")
    ax.set_ylabel("success (% of actiongrams)")
    ax.set_ylim(-3, 103)
    ax.grid(alpha=0.3)
    ax.legend(loc="center left", fontsize=8)
    ax.set_title(f"Paper protocol, {trials} actiongrams per level", fontsize=9)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


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
