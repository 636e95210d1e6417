"""PAL's speed and memory on actiongrams of 10^4 to 10^6 symbols, beside a peer.

Run from the repository root:

    python benchmarks/pal_speed.py            # writes docs/data/pal_speed*.csv, the pal section
    python benchmarks/pal_speed.py --quick    # smaller sizes, no files written

Three sweeps, so that every way an actiongram grows is measured. *Length*:
100 strings whose length grows from 100 to 10,000 symbols (10^4 to 10^6
symbols in all), 8 of them repeating an 8-symbol template (2 random symbols
after each copy, 10% noise), the others random; the peer runs beside PAL on
these. *Strings*: strings of 10,000 symbols, their number growing from 10 to
100 (10^5 to 10^6 symbols), 8% of them patterned (2 at least). *Short*: many
short strings, 1,000 symbols each, their number growing from 100 to 1,000
(10^5 to 10^6 symbols), 8% patterned; its last row, 1,000 strings of 1,000,
is where PAL's per-string costs decide. PAL runs with the compiled engine
when numba imports (``pip install 'psgs[fast]'``), asked for by name: under
``engine="auto"`` an input below ``learner.CROSSOVER`` symbols (2^20, more than
every row here) runs on numpy until the compiled loops have run in the process,
which would time numpy under the compiled engine's name; at 10^6 symbols each sweep also times ``engine="numpy"``, so
that the compiled engine's gain shows side by side (both give the same
Induction; the script checks it). The peer is scikit-sequitur
(``pip install scikit-sequitur``, the ``bench`` extra), which learns the same
strings one by one; when it is missing, the script says so and times psgs's
own Sequential baseline instead (up to 10^5 symbols, as it re-counts digrams
after every rule). Times are wall-clock seconds, the best of ``--repeat``
runs, on an otherwise shared 2-core machine; PAL's first run on each
actiongram (no cache warm, numba's compiled code loaded) is given too. The
growth exponent is the least-squares slope of log(time) against log(symbols),
over each whole sweep and over its upper decade (10^5 to 10^6 symbols, where
fixed costs matter least). Peak memory is the maximum resident set size of a
fresh process that builds the 10^6-symbol actiongram and runs PAL on it.
Targets: at least 3 M symbols/s at 10^6 symbols and an exponent of
at most 1.05 in every sweep.
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
SHORT_SWEEP = tuple((strings, 100, max(2, strings * 8 // 100))
                    for strings in (100, 200, 300, 500, 1000))
MANY_SHORT = SHORT_SWEEP[-1]  # 1,000 strings of 1,000 symbols, 80 patterned
SWEEPS = ("length", "strings", "short")
#: the speed targets the sweeps are held to (printed beside the results)
TARGET_RATE, TARGET_EXPONENT = 3e6, 1.05


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


#: the child's own peak resident set, in kB: Linux's VmHWM belongs to the new process image
#: (``ru_maxrss`` keeps the parent's peak across the exec, this script's own hundreds of MB);
#: ``ru_maxrss`` elsewhere
_PEAK = ("def peak():\n"
         "    try:\n"
         "        for line in open('/proc/self/status'):\n"
         "            if line.startswith('VmHWM:'):\n"
         "                return int(line.split()[1])\n"
         "    except OSError:\n"
         "        pass\n"
         "    import resource\n"
         "    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss\n")


def peak_rss_mb(strings: int, copies: int, patterned: int) -> dict:
    # the child imports the same installed psgs as this process (same interpreter)
    code = (_PEAK +
            "from psgs.induce.synthetic import generate; from psgs.induce import PAL\n"
            "c = generate(seed=0, noise=0.1, strings=%d, patterned=%d, templates=%d, copies=%d)\n"
            "before = peak()\n"
            "r = PAL().induce(c.actiongram)\n"
            "after = peak()\n"
            "print(before, after, c.actiongram.total_symbols, len(r.components))"
            % (strings, patterned, max(8, patterned), copies))
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    before, after, symbols, comps = (int(v) for v in out)
    return {"symbols": symbols, "rss_after_building_mb": before / 1024,
            "peak_rss_mb": after / 1024, "components": comps}


def measure(sweep: str, shape, repeat: int, peer_learn=None, peer_name: str = "",
            sequential=None, engine: str = "auto", expected=None) -> dict:
    """One row: PAL's best time on one actiongram (and the peer's, when given)."""
    case = actiongram(*shape)
    ag = case.actiongram
    n = ag.total_symbols
    pal = PAL(engine=engine)
    first_s, result = best_of(1, lambda: pal.induce(ag))
    correct = (set(result.components) == set(case.components)
               and all(result.patterns[c] == case.patterns[c] for c in case.components))
    if expected is not None and result != expected:
        raise SystemExit(f"engine={engine!r} gave another Induction on {shape}")
    pal_s = best_of(repeat, lambda: pal.induce(ag))[0]
    peer_s = float("nan")
    if peer_learn is not None:
        peer_s = best_of(1 if n >= 10**5 else repeat,
                         lambda: [peer_learn(s) for s in ag.symbols])[0]
    elif sequential is not None and n <= 10**5:
        peer_s = best_of(1, lambda: sequential.induce(ag))[0]
    row = {"sweep": sweep, "engine": engine_name(engine), "symbols": n, "strings": len(ag),
           "string_length": n // len(ag), "pal_first_seconds": first_s,
           "pal_seconds": pal_s, "pal_symbols_per_s": n / pal_s, "pal_correct": correct,
           "peer": peer_name, "peer_seconds": peer_s,
           "peer_symbols_per_s": n / peer_s if peer_s == peer_s else float("nan"),
           "speed_ratio": peer_s / pal_s if peer_s == peer_s else float("nan")}
    print(f"{sweep:>8} {len(ag):>5} x {n // len(ag):>6} = {n:>9,} symbols  PAL[{row['engine']}] "
          f"{pal_s:7.3f} s ({row['pal_symbols_per_s']:>12,.0f}/s, first run {first_s:.3f} s, "
          f"correct={correct})"
          + (f"  {peer_name} {peer_s:7.3f} s  ratio {row['speed_ratio']:.1f}"
             if peer_s == peer_s else ""), flush=True)
    row["_result"] = result
    return row


def one_thread(sweep: str, shape, repeat: int, expected, engine: str = "auto") -> dict:
    """The compiled engine's row with its motif search kept in one thread (it takes two
    from ``motifs._THREADED_SYMBOLS`` symbols on)."""
    from psgs.induce.pal import motifs
    threaded = motifs._THREADED_SYMBOLS
    motifs._THREADED_SYMBOLS = 1 << 62
    try:
        row = measure(sweep, shape, repeat, expected=expected, engine=engine)
    finally:
        motifs._THREADED_SYMBOLS = threaded
    row["engine"] += " (one thread)"
    return row


def engine_name(engine: str) -> str:
    """The engine ``engine`` runs here ("auto" is numba's when it imports)."""
    from psgs._foundation.engines import resolve
    return resolve(engine)


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
    short_sweep = SHORT_SWEEP[:2] if args.quick else SHORT_SWEEP
    print(f"PAL engine: {engine_name('auto')} (engine='auto'); numpy's engine too at the "
          f"largest size of each sweep", flush=True)
    own = engine_name("auto")  # by name: "auto" keeps these sizes on numpy in a fresh process
    rows = [measure("length", shape, args.repeat, peer_learn, peer_name, sequential, own)
            for shape in length_sweep]
    rows += [measure("strings", shape, args.repeat, engine=own) for shape in strings_sweep]
    rows += [measure("short", shape, args.repeat, engine=own) for shape in short_sweep]
    for sweep, sweep_rows in (("length", length_sweep), ("strings", strings_sweep),
                              ("short", short_sweep)):
        if engine_name("auto") != "numpy":  # numpy's engine beside it, on the largest
            last = [r for r in rows if r["sweep"] == sweep][-1]
            rows.append(measure(sweep, sweep_rows[-1], min(args.repeat, 3), engine="numpy",
                                expected=last["_result"]))
            rows.append(one_thread(sweep, sweep_rows[-1], args.repeat, last["_result"], own))
    for r in rows:
        del r["_result"]
    main_engine = engine_name("auto")
    summary = {"peer": peer_name, "repeat": args.repeat, "engine": main_engine,
               "command": "python benchmarks/pal_speed.py"}
    for sweep in SWEEPS:
        own = [r for r in rows if r["sweep"] == sweep and r["engine"] == main_engine]
        whole, top = exponents(own)
        summary[f"{sweep}_exponent"], summary[f"{sweep}_exponent_upper"] = whole, top
        largest = own[-1]
        summary[f"{sweep}_rate_at_largest"] = largest["pal_symbols_per_s"]
        print(f"growth exponent, {sweep} sweep: PAL {whole:.2f} (from 10^5 up: {top:.2f}); "
              f"{largest['pal_symbols_per_s'] / 1e6:.2f} M symbols/s at "
              f"{largest['symbols']:,} symbols (targets: >= {TARGET_RATE / 1e6:.0f} M/s, "
              f"exponent <= {TARGET_EXPONENT})")
    whole, top = exponents([r for r in rows if r["sweep"] == "length"
                            and r["engine"] == main_engine], "peer_seconds")
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
    lines = ["## PAL: speed and noise", ""]
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
        lines += _speed_lines(json.loads((DATA / "pal_speed.json").read_text()), _table(speed))
    replace_section(BENCHMARKS_PAGE, "pal", "\n".join(lines))


def _speed_lines(summary: dict, table: list[dict]) -> list[str]:
    """The speed part of the pal section: a table per sweep, the engines side by side."""
    for r in table:
        r.setdefault("sweep", "length")  # written by an earlier version of this script
        r.setdefault("engine", summary.get("engine", "numpy"))
    engine = summary.get("engine", "numpy")
    own = [r for r in table if r["engine"] == engine]
    lines = [f"Speed, measured with `{summary['command']}` (wall clock, the best of "
             f"{summary.get('repeat', 3)} runs for PAL, its first run on each actiongram "
             f"beside it, one run for the peer from 10⁵ symbols up; shared 2-core machine); "
             f"PAL's engine: **{engine}** (`engine=\"auto\"`); peer: {summary['peer']} "
             "learning the same strings one by one. Growing the strings' length (100 "
             "strings):", "",
             "| symbols | strings x length | PAL s | PAL symbols/s | PAL first run s | peer s | "
             "peer symbols/s | peer/PAL |", "|---|---|---|---|---|---|---|---|"]
    for r in own:
        if r["sweep"] == "length":
            lines.append(f"| {int(r['symbols']):,} | {r['strings']} x "
                         f"{r.get('string_length', '')} | {float(r['pal_seconds']):.3f} | "
                         f"{float(r['pal_symbols_per_s']):,.0f} | "
                         f"{_seconds(r.get('pal_first_seconds'))} | "
                         f"{float(r['peer_seconds']):.3f} | "
                         f"{float(r['peer_symbols_per_s']):,.0f} | "
                         f"{float(r['speed_ratio']):.1f} |")
    titles = {"strings": "Growing the number of strings (10,000 symbols each):",
              "short": "Many short strings (1,000 symbols each), their number growing:"}
    for sweep, title in titles.items():
        rows = [r for r in own if r["sweep"] == sweep]
        if not rows:
            continue
        lines += ["", title, "", "| symbols | strings x length | PAL s | PAL symbols/s | "
                  "PAL first run s |", "|---|---|---|---|---|"]
        for r in rows:
            lines.append(f"| {int(r['symbols']):,} | {r['strings']} x "
                         f"{r['string_length']} | {float(r['pal_seconds']):.3f} | "
                         f"{float(r['pal_symbols_per_s']):,.0f} | "
                         f"{_seconds(r.get('pal_first_seconds'))} |")
    others = [r for r in table if r["engine"] != engine]
    if others:
        lines += ["", f"The engines side by side at the largest size of each sweep (the same "
                      f"Induction from each, checked by the script; {engine} in one thread: "
                      "its motif search not split over the two cores):", "",
                  "| sweep | strings x length | engine | PAL s | PAL symbols/s | "
                  f"time / {engine}'s |", "|---|---|---|---|---|---|"]
        for sweep in dict.fromkeys(r["sweep"] for r in others):
            rivals = [r for r in others if r["sweep"] == sweep]
            mine = [q for q in own if q["sweep"] == sweep
                    and q["symbols"] == rivals[0]["symbols"]][-1]
            for q in [mine] + rivals:
                lines.append(f"| {q['sweep']} | {q['strings']} x {q['string_length']} | "
                             f"{q['engine']} | {float(q['pal_seconds']):.3f} | "
                             f"{float(q['pal_symbols_per_s']):,.0f} | "
                             f"{float(q['pal_seconds']) / float(mine['pal_seconds']):.2f} |")
    if "length_exponent" in summary:
        parts = [f"{name} {summary[f'{key}_exponent']:.2f} / "
                 f"{summary[f'{key}_exponent_upper']:.2f}"
                 for key, name in (("length", "growing the length"),
                                   ("strings", "growing the number of strings"),
                                   ("short", "many short strings"))
                 if f"{key}_exponent" in summary]
        lines += ["", "Growth exponent (slope of log time on log symbols), whole sweep / "
                      "from 10⁵ symbols up: PAL " + ", ".join(parts)
                  + f"; the peer growing the length {summary['peer_exponent']:.2f} / "
                    f"{summary['peer_exponent_upper']:.2f}. Targets: at least "
                    f"3 M symbols/s at 10⁶ symbols, exponent at most {TARGET_EXPONENT}."]
    else:
        lines += ["", f"Growth exponent (slope of log time on log symbols): PAL "
                      f"{summary['pal_exponent']:.2f}, peer {summary['peer_exponent']:.2f}."]
    if "memory" in summary:
        m = summary["memory"]
        lines.append(f"Peak RSS on {m['symbols']:,} symbols: {m['peak_rss_mb']:.0f} MB "
                     f"({m['rss_after_building_mb']:.0f} MB after building the actiongram, "
                     f"before PAL).")
    return lines


def _seconds(value) -> str:
    return "" if value in (None, "") else f"{float(value):.3f}"


if __name__ == "__main__":
    sys.exit(main())
