"""PAL's speed and memory on actiongrams of 10^4 to 10^6 symbols, beside a peer.

Run from the repository root:

    python benchmarks/pal_speed.py            # writes docs/data/pal_speed.csv, the pal section
    python benchmarks/pal_speed.py --quick    # smaller sizes, no files written

Actiongrams: 100 strings, 8 of them repeating an 8-symbol template (2 random
symbols after each copy, 10% noise), the others random; string length grows
from 100 to 10,000 symbols (10^4 to 10^6 symbols in all). The peer is
scikit-sequitur (``pip install scikit-sequitur``, the ``bench`` extra), which
learns the same strings one by one; when it is missing, the script says so and
times psgs's own Sequential baseline instead (up to 10^5 symbols, as it
re-counts digrams after every rule). Times are wall-clock seconds, the best of
``--repeat`` runs, on an otherwise shared 2-core machine. The growth exponent
is the least-squares slope of log(time) against log(symbols). Peak memory is
the maximum resident set size of a fresh process that builds the 10^6-symbol
actiongram and runs PAL on it.
"""

from __future__ import annotations

import argparse
import csv
import json
import subprocess
import sys

from _common import BENCHMARKS_PAGE, DATA, best_of, loglog_slope, replace_section, require

require("psgs")
from psgs.induce import PAL, Sequential  # noqa: E402
from psgs.induce.synthetic import generate  # noqa: E402


def actiongram(copies: int):
    return generate(seed=0, noise=0.1, strings=100, patterned=8, copies=copies)


def best_time(func, repeat: int) -> float:
    return best_of(repeat, func)[0]


def peer():
    """The peer's name and a function learning one string, or (None, None)."""
    try:
        from sksequitur import parse
    except ImportError:
        return None, None
    return "scikit-sequitur", lambda symbols: parse(list(symbols))


def peak_rss_mb(copies: int) -> dict:
    # the child imports the same installed psgs as this process (same interpreter)
    code = ("import resource;"
            "from psgs.induce.synthetic import generate; from psgs.induce import PAL;"
            "c = generate(seed=0, noise=0.1, strings=100, patterned=8, copies=%d);"
            "before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss;"
            "r = PAL().induce(c.actiongram);"
            "after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss;"
            "print(before, after, c.actiongram.total_symbols, len(r.components))"
            % copies)
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    before, after, symbols, comps = (int(v) for v in out)
    return {"symbols": symbols, "rss_after_building_mb": before / 1024,
            "peak_rss_mb": after / 1024, "components": comps}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="10^4 to 10^5 only, no files")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args(argv)
    sizes = (10, 30, 100) if args.quick else (10, 30, 100, 300, 1000)
    peer_name, peer_learn = peer()
    if peer_name is None:
        print("scikit-sequitur is not installed (pip install scikit-sequitur): comparing with "
              "psgs's Sequential baseline instead", file=sys.stderr)
        peer_name = "psgs Sequential"
        sequential = Sequential()
    rows = []
    for copies in sizes:
        case = actiongram(copies)
        ag = case.actiongram
        n = ag.total_symbols
        pal = PAL()
        result = pal.induce(ag)
        correct = (set(result.components) == set(case.components)
                   and all(result.patterns[c] == case.patterns[c] for c in case.components))
        pal_s = best_time(lambda: pal.induce(ag), args.repeat if n < 10**6 else 2)
        if peer_learn is not None:
            peer_s = best_time(lambda: [peer_learn(s) for s in ag.symbols],
                               1 if n >= 10**5 else args.repeat)
        elif n <= 10**5:
            peer_s = best_time(lambda: sequential.induce(ag), 1)
        else:
            peer_s = float("nan")
        rows.append({"symbols": n, "strings": len(ag), "pal_seconds": pal_s,
                     "pal_symbols_per_s": n / pal_s, "pal_correct": correct,
                     "peer": peer_name, "peer_seconds": peer_s,
                     "peer_symbols_per_s": n / peer_s if peer_s == peer_s else float("nan"),
                     "speed_ratio": peer_s / pal_s if peer_s == peer_s else float("nan")})
        r = rows[-1]
        print(f"{n:>9,} symbols  PAL {pal_s:7.3f} s ({r['pal_symbols_per_s']:>12,.0f}/s, "
              f"correct={correct})  {peer_name} {peer_s:7.3f} s  ratio {r['speed_ratio']:.1f}",
              flush=True)
    pal_exp = loglog_slope([r["symbols"] for r in rows], [r["pal_seconds"] for r in rows])
    peer_rows = [r for r in rows if r["peer_seconds"] == r["peer_seconds"]]
    peer_exp = loglog_slope([r["symbols"] for r in peer_rows], [r["peer_seconds"] for r in peer_rows])
    print(f"growth exponent: PAL {pal_exp:.2f}, {peer_name} {peer_exp:.2f}")
    summary = {"pal_exponent": pal_exp, "peer_exponent": peer_exp, "peer": peer_name,
               "command": "python benchmarks/pal_speed.py"}
    if not args.quick:
        memory = peak_rss_mb(1000)
        print(f"memory: {memory}")
        summary["memory"] = memory
        DATA.mkdir(parents=True, exist_ok=True)
        with open(DATA / "pal_speed.csv", "w", newline="") as handle:
            writer = csv.DictWriter(handle, fieldnames=list(rows[0]))
            writer.writeheader()
            writer.writerows(rows)
        (DATA / "pal_speed.json").write_text(json.dumps(summary, indent=2) + "\n")
        write_section()
    return 0


def _table(path: Path) -> list[dict]:
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def write_section() -> None:
    """Rewrite the pal section of docs/benchmarks.md from docs/data (both scripts call this)."""
    lines = ["## PAL (issue 4)", ""]
    noise = DATA / "noise_summary.json"
    if noise.exists():
        s = json.loads(noise.read_text())
        lines += [f"Measured with `{s['command']}` ({s['date']}); curves in "
                  "`docs/img/noise_paper.png` and `docs/img/noise_variants.png`, data in "
                  "`docs/data/noise.csv` and `docs/data/noise_variants.csv`.", "",
                  f"Paper protocol, {s['trials']} actiongrams per level, success rate:", "",
                  "| noise | PAL | Sequential | paper |", "|---|---|---|---|"]
        for row in s["paper_table"]:
            lines.append(f"| {row['noise']:.2f} | {row['pal']:.0%} | {row['sequential']:.0%} | "
                         f"{row['paper']} |")
        lines += ["", f"- PAL's whole paper sweep ({s['levels']} levels x {s['trials']}, "
                      f"generating the actiongrams included): {s['pal_sweep_seconds']:.1f} s wall "
                      f"with {s['jobs']} processes on the shared machine, "
                      f"{s.get('pal_sweep_cpu_seconds', float('nan')):.1f} s of CPU in all.",
                  f"- All-random actiongrams: PAL found components in "
                  f"{s['random_with_components']['pal']} of {s['random_trials']}; "
                  f"Sequential in {s['random_with_components']['sequential']} of "
                  f"{s['random_trials']}."]
        for name, table in s.get("variants", {}).items():
            cells = ", ".join(f"{k}: {v:.0%}" for k, v in table.items())
            lines.append(f"- Variant {name} (PAL): {cells}.")
        lines.append("")
    speed = DATA / "pal_speed.csv"
    if speed.exists():
        summary = json.loads((DATA / "pal_speed.json").read_text())
        lines += [f"Speed, measured with `{summary['command']}` (best of 3 runs, but PAL best of 2 at 10⁶ symbols and the peer one run from 10⁵ up; wall clock, "
                  f"shared 2-core machine); peer: {summary['peer']} learning the same strings "
                  "one by one:", "",
                  "| symbols | PAL s | PAL symbols/s | peer s | peer symbols/s | peer/PAL |",
                  "|---|---|---|---|---|---|"]
        for r in _table(speed):
            lines.append(f"| {int(r['symbols']):,} | {float(r['pal_seconds']):.3f} | "
                         f"{float(r['pal_symbols_per_s']):,.0f} | "
                         f"{float(r['peer_seconds']):.3f} | "
                         f"{float(r['peer_symbols_per_s']):,.0f} | "
                         f"{float(r['speed_ratio']):.1f} |")
        lines += ["", f"Growth exponent (slope of log time on log symbols): PAL "
                      f"{summary['pal_exponent']:.2f}, peer {summary['peer_exponent']:.2f}."]
        if "memory" in summary:
            m = summary["memory"]
            lines.append(f"Peak RSS on {m['symbols']:,} symbols: {m['peak_rss_mb']:.0f} MB "
                         f"({m['rss_after_building_mb']:.0f} MB after building the actiongram, "
                         f"before PAL).")
    replace_section(BENCHMARKS_PAGE, "pal", "\n".join(lines))


if __name__ == "__main__":
    sys.exit(main())
