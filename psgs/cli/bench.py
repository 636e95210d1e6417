"""``psgs synth`` and ``psgs bench noise``: the paper's synthetic protocol from the command line.

``synth`` writes one seeded synthetic actiongram with its ground truth as
comments; ``bench noise`` runs the noise protocol (:func:`psgs.induce.sweep.noise_sweep`)
and prints a table, writes a CSV, and a plot beside the paper's points when
matplotlib is there.
"""

from __future__ import annotations

import csv
import os
import sys
import time
from pathlib import Path

from ..errors import PSGSError, ValidationError
from .._foundation.pictures import picture_suffix
from .._foundation.shell import file_name, natural, positive_int, share


def register(subparsers) -> None:
    """Add ``synth`` and ``bench`` to the ``psgs`` command.

    Parameters
    ----------
    subparsers : argparse._SubParsersAction
        The ``psgs`` parser's subcommands.

    Examples
    --------
    >>> from psgs.cli import build_parser
    >>> build_parser().parse_args(["bench", "noise", "--levels", "0:0.1:0.05"]).levels
    (0.0, 0.05, 0.1)
    """
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
    synth.add_argument("-o", "--output", metavar="FILE", type=file_name,
                       help="write here instead of stdout")
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
                       help="inducer to run (repeatable, each inducer once; default pal "
                            "and sequential)")
    noise.add_argument("--variant", choices=("paper", "random-durations", "irregular-gaps",
                                             "unequal-lengths", "all"), default="paper",
                       help="protocol variant (default paper)")
    noise.add_argument("--seed", type=natural, default=0, help="first seed (default 0)")
    noise.add_argument("--jobs", type=positive_int, default=2,
                       help="worker processes (default 2)")
    noise.add_argument("--csv", metavar="OUT.csv", type=file_name, help="write the results here")
    noise.add_argument("--plot", metavar="OUT.png", type=file_name,
                       help="plot the curves (needs matplotlib)")
    noise.set_defaults(run=run_bench_noise)


# -- argument types -------------------------------------------------------------------
#: the most noise levels one --levels grid may make
MAX_LEVELS = 10_000


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
    # a tiny STEP made a grid of 1e300 levels (counted without end) or an infinite one
    # (OverflowError); every level costs trials, so a grid this long is a slip of the STEP
    span = (high - low) / step
    if not span < MAX_LEVELS:
        many = f"{round(span) + 1:,}" if span < 1e9 else f"{span + 1:.3g}"
        raise argparse.ArgumentTypeError(f"{text!r} makes {many} levels; at most "
                                         f"{MAX_LEVELS:,} (a larger STEP)")
    count = int(round(span)) + 1
    return tuple(round(low + k * step, 10) for k in range(count) if low + k * step <= high + 1e-9)


# -- psgs synth -------------------------------------------------------------------------
def run_synth(args) -> int:
    """``psgs synth``: write one seeded synthetic actiongram, its ground truth as comments.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``psgs synth`` arguments.

    Returns
    -------
    int
        0.

    Raises
    ------
    ValidationError
        For ``--patterned`` outside 0..8.

    Examples
    --------
    >>> from psgs.cli import main
    >>> main(["synth", "--seed", "3"])  # doctest: +ELLIPSIS
    # psgs synth --seed 3 --noise 0
    # truth s...
    0
    """
    from ..induce.synthetic import generate

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
    """``psgs bench noise``: the success-against-noise sweep, as a table, a CSV and a plot.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``psgs bench noise`` arguments.

    Returns
    -------
    int
        0.

    Raises
    ------
    ValidationError
        For an unknown inducer, one given twice, a ``--csv``/``--plot`` path that cannot be
        written, one file named by both, or a ``--plot`` name whose suffix is no picture
        format of matplotlib's (all checked before the sweep runs).
    PSGSError
        For ``--plot`` without matplotlib.

    Examples
    --------
    >>> from psgs.cli import main
    >>> main(["bench", "noise", "--trials", "1", "--levels", "0", "--jobs", "1"])
    ... # doctest: +ELLIPSIS, +NORMALIZE_WHITESPACE
     noise         pal  sequential
      0.00     100.00%       0.00%
    1 levels x 1 trials x 2 inducer(s), variant paper: ... s wall, 1 job(s)
    0
    """
    from ..induce import get
    from ..induce.sweep import noise_sweep

    inducers = tuple(args.inducer or ("pal", "sequential"))
    for k, name in enumerate(inducers):
        # an inducer's parameters and trials are those of its name: a second run would print
        # the same column again, so a repeated name is a slip, said before hours of trials
        if name in inducers[:k]:
            raise ValidationError(f"--inducer {name} is given twice: give each inducer once")
        get(name)  # fail early, with one line, on an unknown name
    for out in (args.csv, args.plot):  # and on an output path that cannot be written
        if out and (Path(out).is_dir() or not Path(out).resolve().parent.is_dir()):
            raise ValidationError(f"{out}: not a file in an existing directory")
        if out:
            _check_writable(out)
    if args.csv and args.plot and Path(args.csv).resolve() == Path(args.plot).resolve():
        raise ValidationError(f"--csv and --plot name one file, {args.plot}: the plot would be "
                              f"written over the table")
    if args.plot:
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            raise PSGSError("--plot needs matplotlib: pip install 'psgs[plot]'") from None
        # matplotlib refuses a format only when it saves, after every trial has run
        picture_suffix(args.plot)
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
    """Success-rate curves per inducer beside the paper's reported points, saved to ``path``.

    Parameters
    ----------
    rows : sequence of SweepRow
        What :func:`psgs.induce.sweep.noise_sweep` returned.
    path : str
        The image file to write (its format from the extension).
    title : str, optional
        A title above the plot.

    Raises
    ------
    ImportError
        When matplotlib is not installed (the ``plot`` extra).
    ValidationError
        For a ``path`` whose suffix is no picture format of matplotlib's (before drawing).

    Examples
    --------
    >>> import os, tempfile
    >>> from psgs.induce.sweep import SweepRow
    >>> path = os.path.join(tempfile.mkdtemp(), "noise.png")
    >>> plot_noise([SweepRow("pal", 0.0, 1, 1, 0.1), SweepRow("pal", 0.1, 1, 1, 0.1)], path)
    >>> open(path, "rb").read(4)[1:]
    b'PNG'
    """
    import matplotlib

    picture_suffix(path)
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..induce.synthetic import PAPER_POINTS

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


def _check_writable(path: str) -> None:
    """ValidationError unless ``path``, in an existing folder, can be written there: the
    results are written after the sweep, so a folder or a file without write permission
    failed only once every trial had run."""
    folder = Path(path).resolve().parent
    if not os.access(folder, os.W_OK | os.X_OK):
        raise ValidationError(f"{path}: the folder {folder} is not writable")
    if Path(path).exists() and not os.access(path, os.W_OK):
        raise ValidationError(f"{path}: the file is there and read-only")
