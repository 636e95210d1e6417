"""PAL's speed and memory on actiongrams of 10^4 to 10^6 symbols, beside a peer.

Run from the repository root:

    python benchmarks/pal_speed.py            # writes docs/data/pal_speed*.csv, the pal section
    python benchmarks/pal_speed.py --quick    # smaller sizes, no files written

Two sweeps, so that both ways an actiongram grows are measured. *Length*:
100 strings whose length grows from 100 to 10,000 symbols (10^4 to 10^6
symbols in all), 8 of them repeating an 8-symbol template (2 random symbols
after each copy, 10% noise), the others random; the peer runs beside PAL on
these. *Strings*: strings of 10,000 symbols, their number growing from 10 to
100 (10^5 to 10^6 symbols), 8% of them patterned (2 at least). A last row
gives the other extreme at 10^6 symbols: 1,000 strings of 1,000 symbols (80
patterned), where PAL's per-string costs decide. The peer is scikit-sequitur
(``pip install scikit-sequitur``, the ``bench`` extra), which learns the same
strings one by one; when it is missing, the script says so and times psgs's
own Sequential baseline instead (up to 10^5 symbols, as it re-counts digrams
after every rule). Times are wall-clock seconds, the best of ``--repeat``
runs, on an otherwise shared 2-core machine. The growth exponent is the
least-squares slope of log(time) against log(symbols), over each whole sweep
and over its upper decade (10^5 to 10^6 symbols, where fixed costs matter
least). Peak memory is the maximum resident set size of a fresh process that
builds the 10^6-symbol actiongram and runs PAL on it.
"""

from __future__ import annotations

import argparse
import csv
import json
import subprocess
import sys
from pathlib import Path

from _common import BENCHMARKS_PAGE, DATA, best_of, loglog_slope, replace_section, require

require("psgs")
from psgs.induce import PAL, Sequential  # noqa: E402
from psgs.induce.synthetic import generate  # noqa: E402

#: (strings, copies per string, patterned strings): string length is 10 symbols a copy
LENGTH_SWEEP = tuple((100, copies, 8) for copies in (10, 30, 100, 300, 1000))
STRINGS_SWEEP = tuple((strings, 1000, max(2, strings * 8 // 100))
                      for strings in (10, 20, 30, 50, 100))
MANY_SHORT = (1000, 100, 80)


def actiongram(strings: int, copies: int, patterned: int):
    return generate(seed=0, noise=0.1, strings=strings, patterned=patterned,
                    templates=max(8, patterned), copies=copies)


def peer():
    """The peer's name and a function learning one string, or (None, None)."""
    try:
        from sksequitur import parse
    except ImportError:
        return None, None
    return "scikit-sequitur", lambda symbols: parse(list(symbols))


def peak_rss_mb(strings: int, copies: int, patterned: int) -> dict:
    # the child imports the same installed psgs as this process (same interpreter)
    code = ("import resource;"
            "from psgs.induce.synthetic import generate; from psgs.induce import PAL;"
            "c = generate(seed=0, noise=0.1, strings=%d, patterned=%d, templates=%d, copies=%d);"
            "before = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss;"
            "r = PAL().induce(c.actiongram);"
            "after = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss;"
            "print(before, after, c.actiongram.total_symbols, len(r.components))"
            % (strings, patterned, max(8, patterned), copies))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    before, after, symbols, comps = (int(v) for v in out)
    return {"symbols": symbols, "rss_after_building_mb": before / 1024,
            "peak_rss_mb": after / 1024, "components": comps}


def measure(sweep: str, shape, repeat: int, peer_learn=None, peer_name: str = "",
            sequential=None) -> dict:
    """One row: PAL's best time on one actiongram (and the peer's, when given)."""
    case = actiongram(*shape)
    ag = case.actiongram
    n = ag.total_symbols
    pal = PAL()
    result = pal.induce(ag)
    correct = (set(result.components) == set(case.components)
               and all(result.patterns[c] == case.patterns[c] for c in case.components))
    pal_s = best_of(repeat, lambda: pal.induce(ag))[0]
    peer_s = float("nan")
    if peer_learn is not None:
        peer_s = best_of(1 if n >= 10**5 else repeat,
                         lambda: [peer_learn(s) for s in ag.symbols])[0]
    elif sequential is not None and n <= 10**5:
        peer_s = best_of(1, lambda: sequential.induce(ag))[0]
    row = {"sweep": sweep, "symbols": n, "strings": len(ag), "string_length": n // len(ag),
           "pal_seconds": pal_s, "pal_symbols_per_s": n / pal_s, "pal_correct": correct,
           "peer": peer_name, "peer_seconds": peer_s,
           "peer_symbols_per_s": n / peer_s if peer_s == peer_s else float("nan"),
           "speed_ratio": peer_s / pal_s if peer_s == peer_s else float("nan")}
    print(f"{sweep:>8} {len(ag):>5} x {n // len(ag):>6} = {n:>9,} symbols  PAL {pal_s:7.3f} s "
          f"({row['pal_symbols_per_s']:>12,.0f}/s, correct={correct})"
          + (f"  {peer_name} {peer_s:7.3f} s  ratio {row['speed_ratio']:.1f}"
             if peer_s == peer_s else ""), flush=True)
    return row


def exponents(rows: list[dict], key: str = "pal_seconds") -> tuple[float, float]:
    """Growth exponent over the whole sweep and over its rows from 10^5 symbols up."""
    rows = [r for r in rows if r[key] == r[key]]
    upper = [r for r in rows if r["symbols"] >= 10**5]
    whole = loglog_slope([r["symbols"] for r in rows], [r[key] for r in rows])
    top = (loglog_slope([r["symbols"] for r in upper], [r[key] for r in upper])
           if len(upper) > 1 else float("nan"))
    return whole, top


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="10^4 to 10^5 only, no files")
    parser.add_argument("--repeat", type=int, default=9)
    args = parser.parse_args(argv)
    length_sweep = LENGTH_SWEEP[:3] if args.quick else LENGTH_SWEEP
    strings_sweep = tuple((s, 100, max(2, s * 8 // 100)) for s in (10, 30, 100)) \
        if args.quick else STRINGS_SWEEP
    peer_name, peer_learn = peer()
    sequential = None
    if peer_name is None:
        print("scikit-sequitur is not installed (pip install scikit-sequitur): comparing with "
              "psgs's Sequential baseline instead", file=sys.stderr)
        peer_name = "psgs Sequential"
        sequential = Sequential()
    rows = [measure("length", shape, args.repeat, peer_learn, peer_name, sequential)
            for shape in length_sweep]
    rows += [measure("strings", shape, args.repeat) for shape in strings_sweep]
    if not args.quick:
        rows.append(measure("short", MANY_SHORT, args.repeat))
    summary = {"peer": peer_name, "repeat": args.repeat,
               "command": "python benchmarks/pal_speed.py"}
    for sweep in ("length", "strings"):
        whole, top = exponents([r for r in rows if r["sweep"] == sweep])
        summary[f"{sweep}_exponent"], summary[f"{sweep}_exponent_upper"] = whole, top
        print(f"growth exponent, {sweep} sweep: PAL {whole:.2f} (from 10^5 up: {top:.2f})")
    whole, top = exponents([r for r in rows if r["sweep"] == "length"], "peer_seconds")
    summary["peer_exponent"], summary["peer_exponent_upper"] = whole, top
    print(f"growth exponent, length sweep: {peer_name} {whole:.2f} (from 10^5 up: {top:.2f})")
    if not args.quick:
        memory = peak_rss_mb(*LENGTH_SWEEP[-1])
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


def _share(value) -> str:
    return "" if value is None else f"{value:.0%}"


def _table(path: Path) -> list[dict]:
    with open(path, newline="") as handle:
        return list(csv.DictReader(handle))


def write_section() -> None:
    """Rewrite the pal section of docs/benchmarks.md from docs/data (both scripts call this)."""
    lines = ["## PAL (issues 4 and 13)", ""]
    noise = DATA / "noise_summary.json"
    if noise.exists():
        s = json.loads(noise.read_text())
        lines += [f"Measured with `{s['command']}` ({s['date']}); curves in "
                  "`docs/img/noise_paper.png` and `docs/img/noise_variants.png`, data in "
                  "`docs/data/noise.csv` and `docs/data/noise_variants.csv`.", "",
                  f"Paper protocol, {s['trials']} actiongrams per level, success rate; the "
                  "ceiling is the share of the same actiongrams where no wrong symbol "
                  "outnumbers the true one at a template position across the copies (no tie: "
                  "where the true one leads everywhere):", "",
                  "| noise | PAL | Sequential | paper | ceiling | no tie |",
                  "|---|---|---|---|---|---|"]
        for row in s["paper_table"]:
            lines.append(f"| {row['noise']:.2f} | {row['pal']:.0%} | {row['sequential']:.0%} | "
                         f"{row['paper']} | {_share(row.get('ceiling'))} | "
                         f"{_share(row.get('no_tie'))} |")
        lines += ["", f"- PAL's whole paper sweep ({s['levels']} levels x {s['trials']}, "
                      f"generating the actiongrams included): {s['pal_sweep_seconds']:.1f} s wall "
                      f"with {s['jobs']} processes on the shared machine, "
                      f"{s.get('pal_sweep_cpu_seconds', float('nan')):.1f} s of CPU in all.",
                  f"- All-random actiongrams: PAL found components in "
                  f"{s['random_with_components']['pal']} of {s['random_trials']}; "
                  f"Sequential in {s['random_with_components']['sequential']} of "
                  f"{s['random_trials']}."]
        for c in s.get("ceiling_check", []):
            lines.append(
                f"- At the ceiling, {c['noise']:.0%} noise, {c['trials']:,} further actiongrams "
                f"(seeds from {s['check_seed']:,}): PAL {c['pal_successes']:,} "
                f"({c['pal_successes'] / c['trials']:.1%}). {c['above_ceiling']} are above the "
                f"ceiling (PAL fails {c['pal_failures_above']}), {c['ties']} have a tie (a wrong "
                f"symbol as frequent as the true one: a coin flip for any vote; PAL fails "
                f"{c['pal_failures_tie']}); where the true symbol leads everywhere PAL fails "
                f"**{c['pal_failures_leading']}** of {c['trials'] - c['above_ceiling'] - c['ties']:,}.")
        paper = {f"{row['noise']:.2f}": row["pal"] for row in s["paper_table"]}
        for name, table in s.get("variants", {}).items():
            cells = ", ".join(f"{k}: {v:.0%}" for k, v in table.items())
            lines.append(f"- Variant {name} (PAL): {cells}.")
            ceiling = s.get("variant_ceiling", {}).get(name)
            if ceiling:
                lines.append("  Against the paper protocol (points): " + ", ".join(
                    f"{k}: {100 * (v - paper[k]):+.0f}" for k, v in table.items() if k in paper)
                    + "; its ceiling: " + ", ".join(f"{k}: {v:.0%}" for k, v in ceiling.items())
                    + ".")
        lines.append("")
    speed = DATA / "pal_speed.csv"
    if speed.exists():
        summary = json.loads((DATA / "pal_speed.json").read_text())
        table = _table(speed)
        if "sweep" not in table[0]:  # written by the previous version of this script
            table = [dict(r, sweep="length") for r in table]
        lines += [f"Speed, measured with `{summary['command']}` (wall clock, the best of "
                  f"{summary.get('repeat', 3)} runs for PAL, one run for the peer from 10⁵ "
                  f"symbols up; shared 2-core machine); peer: {summary['peer']} learning the "
                  "same strings one by one. Growing the strings' length (100 strings):", "",
                  "| symbols | strings x length | PAL s | PAL symbols/s | peer s | "
                  "peer symbols/s | peer/PAL |", "|---|---|---|---|---|---|---|"]
        for r in table:
            if r["sweep"] != "length":
                continue
            lines.append(f"| {int(r['symbols']):,} | {r['strings']} x "
                         f"{r.get('string_length', '')} | {float(r['pal_seconds']):.3f} | "
                         f"{float(r['pal_symbols_per_s']):,.0f} | "
                         f"{float(r['peer_seconds']):.3f} | "
                         f"{float(r['peer_symbols_per_s']):,.0f} | "
                         f"{float(r['speed_ratio']):.1f} |")
        others = [r for r in table if r["sweep"] != "length"]
        if others:
            lines += ["", "Growing the number of strings (10,000 symbols each), and last the "
                          "other extreme at 10⁶ symbols, 1,000 strings of 1,000:", "",
                      "| symbols | strings x length | PAL s | PAL symbols/s |",
                      "|---|---|---|---|"]
            for r in others:
                lines.append(f"| {int(r['symbols']):,} | {r['strings']} x "
                             f"{r['string_length']} | {float(r['pal_seconds']):.3f} | "
                             f"{float(r['pal_symbols_per_s']):,.0f} |")
        if "length_exponent" in summary:
            lines += ["", "Growth exponent (slope of log time on log symbols), whole sweep / "
                          f"from 10⁵ symbols up: PAL growing the length "
                          f"{summary['length_exponent']:.2f} / "
                          f"{summary['length_exponent_upper']:.2f}, growing the number of "
                          f"strings {summary['strings_exponent']:.2f} / "
                          f"{summary['strings_exponent_upper']:.2f}; the peer growing the "
                          f"length {summary['peer_exponent']:.2f} / "
                          f"{summary['peer_exponent_upper']:.2f}."]
        else:
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
