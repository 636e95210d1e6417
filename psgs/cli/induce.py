"""``psgs induce``, ``psgs synth`` and ``psgs bench noise``.

``induce`` learns a grammar system from an actiongram file (or from a
built-in synthetic example) and prints the components, their patterns and
the system; ``synth`` writes a synthetic actiongram; ``bench noise`` runs the
paper's noise protocol and writes a CSV (and a plot when matplotlib is there).
"""

from __future__ import annotations

import csv
import json
import sys
import time
from pathlib import Path

from ..errors import PSGSError, ValidationError
from ._types import natural, positive_int, share


def register(subparsers) -> None:
    """Add ``induce``, ``synth`` and ``bench`` to the ``psgs`` command."""
    induce = subparsers.add_parser(
        "induce", help="learn a grammar system from an actiongram",
        description="Learn a parallel synchronous grammar system from an actiongram file "
                    "(text form 'name: sym sym@D ...', or .json). Without FILE (or with "
                    "--example) it learns from a built-in synthetic actiongram and explains "
                    "what it found.")
    induce.add_argument("file", metavar="FILE", nargs="?", help="an actiongram file")
    induce.add_argument("--example", action="store_true",
                        help="use the built-in synthetic example (20 strings, 4 patterned)")
    induce.add_argument("--inducer", default="pal", help="pal (default), sequential, or a "
                                                         "plug-in's name")
    induce.add_argument("--param", action="append", default=[], metavar="K=V",
                        help="an inducer parameter, e.g. --param alpha=1e-6 (repeatable)")
    induce.add_argument("--json", action="store_true",
                        help="print one JSON object (the system as text under 'system')")
    induce.add_argument("-o", "--output", metavar="OUT.psgs",
                        help="also write the grammar system to this file")
    induce.set_defaults(run=run_induce)

    synth = subparsers.add_parser(
        "synth", help="write a synthetic actiongram (the paper's protocol)",
        description="Write a seeded synthetic actiongram in the text form: 20 strings of 100 "
                    "symbols over 20 letters, 4 of them repeating an 8-symbol template 10 "
                    "times, noise replacing round(P*100) symbols of each patterned string. "
                    "The ground truth is written as comments at the top.")
    synth.add_argument("--noise", type=share, default=0.0, metavar="P",
                       help="share of symbols replaced in each patterned string (default 0)")
    synth.add_argument("--seed", type=natural, default=0, help="random seed (default 0)")
    synth.add_argument("--patterned", type=int, default=4,
                       help="patterned strings (default 4; 0 = all random)")
    synth.add_argument("--durations", choices=("unit", "random"), default="unit",
                       help="every symbol lasts 1 (unit, the default) or 0.5 to 1.5 (random)")
    synth.add_argument("--irregular-gaps", action="store_true",
                       help="1 to 4 random symbols between copies instead of 2")
    synth.add_argument("--unequal-lengths", action="store_true",
                       help="strings of different lengths")
    synth.add_argument("-o", "--output", metavar="FILE", help="write here instead of stdout")
    synth.set_defaults(run=run_synth)

    bench = subparsers.add_parser("bench", help="benchmarks (noise)")
    bench_sub = bench.add_subparsers(dest="bench", metavar="BENCHMARK",
                                     help="the benchmark to run (noise)")
    bench_sub.required = True
    noise = bench_sub.add_parser(
        "noise", help="success rate against noise on the paper's synthetic protocol",
        description="Run N synthetic actiongrams per noise level through each inducer, count "
                    "successes (exactly the patterned strings are components, each pattern "
                    "is its template), print a table, write a CSV and optionally a plot "
                    "beside the paper's points. Progress goes to stderr.")
    noise.add_argument("--trials", type=positive_int, default=100,
                       help="actiongrams per level (default 100)")
    noise.add_argument("--levels", type=_levels, default=_levels("0:0.40:0.02"),
                       metavar="LO:HI:STEP", help="noise levels (default 0:0.40:0.02)")
    noise.add_argument("--inducer", action="append", metavar="NAME",
                       help="inducer to run (repeatable; default pal and sequential)")
    noise.add_argument("--variant", choices=("paper", "random-durations", "irregular-gaps",
                                             "unequal-lengths", "all"), default="paper",
                       help="protocol variant (default paper)")
    noise.add_argument("--seed", type=natural, default=0, help="first seed (default 0)")
    noise.add_argument("--jobs", type=positive_int, default=2,
                       help="worker processes (default 2)")
    noise.add_argument("--csv", metavar="OUT.csv", help="write the results here")
    noise.add_argument("--plot", metavar="OUT.png", help="plot the curves (needs matplotlib)")
    noise.set_defaults(run=run_bench_noise)


# -- argument types -------------------------------------------------------------------
def _levels(text: str) -> tuple[float, ...]:
    import argparse

    parts = text.split(":")
    try:
        if len(parts) == 1:
            level = float(parts[0])
            if not 0 <= level <= 1:
                raise argparse.ArgumentTypeError(f"{text!r}: a noise level is between 0 and 1")
            return (level,)
        low, high, step = (float(p) for p in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not LO:HI:STEP") from None
    if not (step > 0 and 0 <= low <= high <= 1):
        raise argparse.ArgumentTypeError(f"{text!r}: need 0 <= LO <= HI <= 1 and STEP > 0")
    count = int(round((high - low) / step)) + 1
    return tuple(round(low + k * step, 10) for k in range(count) if low + k * step <= high + 1e-9)


def _parse_value(text: str):
    lowered = text.lower()
    if lowered in ("true", "false"):
        return lowered == "true"
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def _params(items: list[str]) -> dict:
    out = {}
    for item in items:
        key, eq, value = item.partition("=")
        if not eq or not key:
            raise ValidationError(f"--param {item!r}: write KEY=VALUE")
        out[key.strip()] = _parse_value(value.strip())
    return out


def _make_inducer(name: str, params: dict):
    from ..induce import get

    try:
        return get(name, **params)
    except TypeError as exc:
        try:
            known = tuple(get(name).get_params())
        except Exception:  # a plug-in without defaults or get_params: keep Python's words
            known = ()
        unknown = [k for k in params if k not in known]
        if known and unknown:
            raise ValidationError(f"inducer {name} has no parameter {unknown[0]!r} "
                                  f"(its parameters: {', '.join(known)})") from None
        raise ValidationError(f"inducer {name}: {exc}") from None
    except ValueError as exc:
        raise ValidationError(str(exc)) from None


# -- psgs induce -------------------------------------------------------------------------
EXAMPLE_SEED = 1
EXAMPLE_NOISE = 0.1


def run_induce(args) -> int:
    """``psgs induce``: learn from FILE (or the built-in example) and print or write the result."""
    from ..actiongram import load_actiongram
    from ..format import dumps
    from ..synthetic import generate

    inducer = _make_inducer(args.inducer, _params(args.param))
    truth = None
    if args.file and args.example:
        raise ValidationError("give FILE or --example, not both")
    if args.file:
        actiongram = load_actiongram(args.file)
    else:
        truth = generate(seed=EXAMPLE_SEED, noise=EXAMPLE_NOISE)
        actiongram = truth.actiongram
    began = time.perf_counter()
    result = inducer.induce(actiongram)
    seconds = time.perf_counter() - began
    system_text = dumps(result.system) if result.system is not None else None
    if args.output:
        if system_text is None:
            print("psgs: no component found, nothing written to " + args.output, file=sys.stderr)
        else:
            Path(args.output).write_text(system_text, encoding="utf-8")
    if args.json:
        data = result.to_dict()
        data["system"] = system_text
        data["seconds"] = round(seconds, 6)
        print(json.dumps(data, indent=2))
        return 0
    out = []
    if truth is not None:
        out.append(f"Example: a synthetic actiongram (seed {EXAMPLE_SEED}, "
                   f"{EXAMPLE_NOISE:.0%} noise) of {len(actiongram)} strings x 100 symbols "
                   f"over 20 letters.")
        out.append(f"Hidden in it: {len(truth.components)} strings ({', '.join(truth.components)})"
                   f" each repeat an 8-symbol template 10 times, in step; the other "
                   f"{len(actiongram) - len(truth.components)} strings are random. Can "
                   f"{args.inducer} find them?")
        out.append("(Try: psgs synth --noise 0.2 --seed 3 -o ag.txt && psgs induce ag.txt)")
        out.append("")
    out.append(f"{result.inducer}: {len(result.components)} component(s) of "
               f"{len(actiongram)} strings, {actiongram.total_symbols} symbols, "
               f"in {seconds * 1000:.0f} ms")
    for name in result.components:
        pattern = " ".join(result.patterns[name])
        where = result.occurrences[name]
        times = ", ".join(f"{a:g}-{b:g}" for a, b in where[:3]) + (", ..." if len(where) > 3
                                                                      else "")
        line = f"  {name}: {pattern}   ({len(where)} copies at t = {times})"
        if truth is not None:
            ok = truth.patterns.get(name) == tuple(result.patterns[name])
            line += "   [the hidden template]" if ok else "   [NOT the hidden template]"
        out.append(line)
    dropped: dict[str, int] = {}
    for report in result.reports:
        if report.status == "component":
            continue
        if report.name in result.components:  # kept, with a caveat (e.g. a search bound hit)
            out.append(f"  note: {report.name}: {report.status}")
        else:
            dropped[report.status] = dropped.get(report.status, 0) + 1
    if dropped:
        out.append("  dropped: " + ", ".join(f"{n} {why}" for why, n in sorted(dropped.items())))
    if truth is not None:
        from ..synthetic import success
        out.append("  verdict: " + ("found exactly the hidden patterns" if success(result, truth)
                                   else "did not recover the hidden patterns exactly"))
        if args.inducer == "pal":
            from ..induce import Sequential
            baseline = Sequential().induce(actiongram)
            out.append(f"  for comparison, the sequential baseline (no synchronisation) keeps "
                       f"{len(baseline.components)} of {len(actiongram)} strings: every random "
                       f"string that repeats a digram")
    out.append("")
    if system_text is None:
        out.append("No grammar system: no string repeats in step with another.")
    else:
        out.append("Grammar system (each component repeats its pattern, all the same number of "
                   "times):")
        out.append(system_text.rstrip("\n"))
    print("\n".join(out))
    return 0


# -- psgs synth -------------------------------------------------------------------------
def run_synth(args) -> int:
    """``psgs synth``: write one seeded synthetic actiongram, its ground truth as comments."""
    from ..synthetic import generate

    if not 0 <= args.patterned <= 8:
        raise ValidationError("--patterned must be between 0 and 8")
    case = generate(seed=args.seed, noise=args.noise, patterned=args.patterned,
                    durations=args.durations, irregular_gaps=args.irregular_gaps,
                    unequal_lengths=args.unequal_lengths)
    head = [f"# psgs synth --seed {args.seed} --noise {args.noise:g}"
            f"{' --patterned ' + str(args.patterned) if args.patterned != 4 else ''}"
            f"{' --durations random' if args.durations == 'random' else ''}"
            f"{' --irregular-gaps' if args.irregular_gaps else ''}"
            f"{' --unequal-lengths' if args.unequal_lengths else ''}"]
    for name in case.components:
        head.append(f"# truth {name}: {' '.join(case.patterns[name])}")
    text = "\n".join(head) + "\n" + case.actiongram.to_text()
    if args.output:
        Path(args.output).write_text(text, encoding="utf-8")
    else:
        sys.stdout.write(text)
    return 0


# -- psgs bench noise ---------------------------------------------------------------------
_VARIANTS = {
    "paper": {},
    "random-durations": {"durations": "random"},
    "irregular-gaps": {"irregular_gaps": True},
    "unequal-lengths": {"unequal_lengths": True},
    "all": {"durations": "random", "irregular_gaps": True, "unequal_lengths": True},
}


def _progress_bar(done: int, total: int, began: float) -> None:
    width = 30
    filled = int(width * done / total)
    elapsed = time.perf_counter() - began
    sys.stderr.write(f"\r[{'#' * filled}{'.' * (width - filled)}] {done}/{total} cells "
                     f"{elapsed:5.1f} s")
    if done == total:
        sys.stderr.write("\n")
    sys.stderr.flush()


def run_bench_noise(args) -> int:
    """``psgs bench noise``: the success-against-noise sweep, as a table, a CSV and a plot."""
    from ..synthetic import noise_sweep

    inducers = tuple(args.inducer or ("pal", "sequential"))
    for name in inducers:
        _make_inducer(name, {})  # fail early, with one line, on an unknown name
    for out in (args.csv, args.plot):  # and on an output path that cannot be written
        if out and (Path(out).is_dir() or not Path(out).resolve().parent.is_dir()):
            raise ValidationError(f"{out}: not a file in an existing directory")
    if args.plot:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise PSGSError("--plot needs matplotlib: pip install 'psgs[plot]'") from None
    began = time.perf_counter()
    rows = noise_sweep(args.levels, args.trials, inducers=inducers, seed=args.seed,
                       variant=_VARIANTS[args.variant], jobs=args.jobs,
                       progress=lambda d, t: _progress_bar(d, t, began))
    wall = time.perf_counter() - began
    print(f"{'noise':>6} " + " ".join(f"{n:>11}" for n in inducers))
    for level in args.levels:
        cells = {r.inducer: r for r in rows if r.noise == float(level)}
        print(f"{level:6.2f} " + " ".join(f"{cells[n].rate:11.2%}" for n in inducers))
    print(f"{len(args.levels)} levels x {args.trials} trials x {len(inducers)} inducer(s), "
          f"variant {args.variant}: {wall:.1f} s wall, {args.jobs} job(s)")
    if args.csv:
        with open(args.csv, "w", newline="", encoding="utf-8") as handle:
            writer = csv.writer(handle)
            writer.writerow(["inducer", "variant", "noise", "trials", "successes", "rate",
                             "seconds"])
            for r in rows:
                writer.writerow([r.inducer, args.variant, f"{r.noise:.4f}", r.trials,
                                 r.successes, f"{r.rate:.4f}", f"{r.seconds:.3f}"])
    if args.plot:
        plot_noise(rows, args.plot, title=f"Synthetic protocol ({args.variant}), "
                                          f"{args.trials} actiongrams per level")
    return 0


def plot_noise(rows, path: str, title: str = "") -> None:
    """Success-rate curves per inducer beside the paper's reported points."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..synthetic import PAPER_POINTS

    fig, ax = plt.subplots(figsize=(6.4, 4.0), dpi=120)
    styles = {"pal": ("tab:blue", "o"), "sequential": ("tab:orange", "s")}
    for name in dict.fromkeys(r.inducer for r in rows):
        mine = sorted((r.noise, r.rate) for r in rows if r.inducer == name)
        color, marker = styles.get(name, (None, "^"))
        ax.plot([x * 100 for x, _ in mine], [y * 100 for _, y in mine], marker=marker,
                markersize=4, color=color, label=name.upper() if name == "pal" else name)
    ax.plot([x * 100 for x in PAPER_POINTS], [y * 100 for y in PAPER_POINTS.values()], "k*",
            markersize=11, label="paper (reported)")
    ax.set_xlabel("noise (% of symbols replaced in each patterned string)")
    ax.set_ylabel("success (% of actiongrams)")
    ax.set_ylim(-3, 103)
    ax.grid(alpha=0.3)
    ax.legend(loc="lower left")
    if title:
        ax.set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)
