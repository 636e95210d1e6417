"""Benchmark: psgs.accepts against Lark (Earley and LALR) on the same component words; psgs.nearest.

    python benchmarks/membership.py            # full run; rewrites the membership section
    python benchmarks/membership.py --quick    # small sizes, prints only

For each system of ``grammars/`` and each size, the words are a member tuple
of the language. ``accepts`` is timed end to end (parse every component and
find a synchronised schedule; building the schedule found and replaying the
witness are left to first access and not timed). Lark is timed parsing each
component's word with the exported grammar (``psgs.to_lark``,
``lark.Lark(..., parser="earley", lexer="basic")``,
symbols joined by spaces), parser construction excluded; Lark's time is the
same for both modes (it knows nothing of them) and is measured once per word
tuple; Lark's LALR parser is timed the same way where the exported grammar
has no LALR conflict ("n/a" otherwise). The growth exponent is the
least-squares slope of log(time) against log(size) over the sizes of one row
group.

``nearest``: member tuples of the shipped grammars with random edits (a
seeded generator inserts, deletes or substitutes a symbol at a random place
of a random component) at 0.1%, 1% and 5% of the symbols (at least one),
timed end to end (best of 2), once exact (no ``max_errors``) and once with
``max_errors`` set to the number of edits made (the distance is at most
that: undoing each edit costs 1).
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import platform
import random
import time

import lark
from _common import BENCHMARKS_PAGE, REPO, loglog_slope, replace_section, require

require("psgs")
from psgs import to_lark  # noqa: E402
from psgs.format import load  # noqa: E402
from psgs.membership import accepts, nearest  # noqa: E402

GAMMA_BLOCKS = ("abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad")


def cases(quick: bool):
    """(label, file, size, words) for every benchmarked word tuple."""
    sizes = (10, 30, 100) if quick else (10, 100, 1000)
    for k in sizes:
        yield "Γ (paper_example)", "paper_example.psgs", k, [b * k for b in GAMMA_BLOCKS]
    for n in sizes:
        yield "counting (aⁿ, bⁿ)", "counting.psgs", n, ["a" * n, "b" * n]
    for n in sizes:
        yield "idling (aⁿcⁿ, bⁿ)", "idling.psgs", n, ["a" * n + "c" * n, "b" * n]
    for n in sizes:
        yield "modes (aⁿb aⁿb)", "modes.psgs", n, ["a" * n + "b" + "a" * n + "b"]


def time_accepts(system, words, repeats: int) -> tuple[float, str]:
    best = math.inf
    answer = ""
    for _ in range(repeats):
        start = time.perf_counter()
        result = accepts(system, words, check_witness=False, max_seconds=600.0,
                         max_states=5_000_000)
        best = min(best, time.perf_counter() - start)
        answer = result.answer
    return best, answer


def time_lark(system, words, algorithm: str = "earley") -> float | None:
    texts = to_lark(system)
    total = 0.0
    for g, w in zip(system.components, words):
        try:
            parser = lark.Lark(texts[g.name], start="start", parser=algorithm, lexer="basic")
        except lark.exceptions.GrammarError:
            return None  # an LALR conflict: Lark cannot build this parser
        sentence = " ".join(w)
        start = time.perf_counter()
        parser.parse(sentence)
        total += time.perf_counter() - start
    return total


def run(quick: bool) -> str:
    rows = []
    groups: dict[tuple[str, str], list[tuple[int, float, float]]] = {}
    lark_cache: dict[tuple[str, int], float] = {}
    lalr_cache: dict[tuple[str, int], float | None] = {}
    for label, file, size, words in cases(quick):
        base = load(REPO / "grammars" / file)
        key = (file, size)
        if key not in lark_cache:
            lark_cache[key] = time_lark(base, words)
            lalr_cache[key] = time_lark(base, words, "lalr")
        for mode in ("parallel", "single"):
            system = dataclasses.replace(base, mode=mode)
            repeats = 3
            ours, answer = time_accepts(system, words, repeats)
            theirs = lark_cache[key]
            lalr = lalr_cache[key]
            symbols = sum(len(w) for w in words)
            rows.append((label, mode, size, symbols, answer, ours, theirs, lalr))
            groups.setdefault((label, mode), []).append((size, ours, theirs))
            print(f"{label:22} {mode:8} n={size:5} symbols={symbols:6} {answer:7} "
                  f"ours={ours:8.3f}s lark={theirs:8.3f}s lalr={_s(lalr)} "
                  f"ratio={ours / theirs:6.3f}", flush=True)
    lines = ["| system | mode | size n (k) | symbols | answer | accepts (s) | Lark Earley (s) "
             "| ours / Earley | Lark LALR (s) | ours / LALR |",
             "|---|---|---:|---:|---|---:|---:|---:|---:|---:|"]
    for label, mode, size, symbols, answer, ours, theirs, lalr in rows:
        ratio = "n/a" if lalr is None else f"{ours / lalr:.2f}"
        lines.append(f"| {label} | {mode} | {size} | {symbols} | {answer} | {ours:.3f} | "
                     f"{theirs:.3f} | {ours / theirs:.3f} | {_s(lalr)} | {ratio} |")
    lines += ["", "Growth exponent (log-log slope of time against n):", "",
              "| system | mode | accepts | Lark Earley |", "|---|---|---:|---:|"]
    for (label, mode), points in groups.items():
        sizes = [n for n, _, _ in points]
        ours_slope = loglog_slope(sizes, [t for _, t, _ in points])
        lark_slope = loglog_slope(sizes, [t for _, _, t in points])
        lines.append(f"| {label} | {mode} | {ours_slope:.2f} | {lark_slope:.2f} |")
    return "\n".join(lines)


def _s(value: float | None) -> str:
    return "n/a" if value is None else f"{value:.3f}"


RATES = (0.001, 0.01, 0.05)


def edited(words: list[str], alphabet: str, rate: float, seed: int) -> tuple[list[str], int]:
    """The words with ``rate`` of their symbols edited at random (at least one edit)."""
    rng = random.Random(seed)
    out = [list(w) for w in words]
    count = max(1, round(rate * sum(map(len, out))))
    for _ in range(count):
        w = out[rng.randrange(len(out))]
        p = rng.randrange(len(w) + 1)
        op = rng.choice(("insert", "delete", "substitute")) if p < len(w) else "insert"
        if op == "insert":
            w.insert(p, rng.choice(alphabet))
        elif op == "delete":
            del w[p]
        else:
            w[p] = rng.choice([x for x in alphabet if x != w[p]])
    return ["".join(w) for w in out], count


def nearest_cases(quick: bool):
    """(label, file, size, member words, alphabet) for the nearest benchmark."""
    sizes = (10, 30) if quick else (10, 30, 100)
    for k in sizes:
        yield "Γ (paper_example)", "paper_example.psgs", k, [b * k for b in GAMMA_BLOCKS], "abcd"
    for n in ((30, 100) if quick else (30, 100, 300, 1000)):
        yield "counting (aⁿ, bⁿ)", "counting.psgs", n, ["a" * n, "b" * n], "ab"


def run_nearest(quick: bool) -> str:
    rows = []
    groups: dict[tuple[str, float, str], list[tuple[int, float]]] = {}
    for label, file, size, words, alphabet in nearest_cases(quick):
        system = load(REPO / "grammars" / file)
        for rate in RATES:
            noisy, count = edited(words, alphabet, rate, seed=size)
            for how, limit in (("exact", None), ("max_errors", count)):
                best = math.inf
                for _ in range(2):
                    start = time.perf_counter()
                    result = nearest(system, noisy, max_errors=limit, max_seconds=300.0,
                                     max_states=5_000_000)
                    best = min(best, time.perf_counter() - start)
                symbols = sum(map(len, noisy))
                shown = "none" if result.distance is None else str(result.distance)
                if not result.exact:
                    shown += f" (not exact: {result.bound})"
                rows.append((label, size, symbols, rate, count, how, shown, best))
                groups.setdefault((label, rate, how), []).append((symbols, best))
                print(f"{label:22} k={size:5} symbols={symbols:6} rate={rate:5} edits={count:4} "
                      f"{how:10} distance={shown:8} {best:8.3f}s", flush=True)
    lines = ["| system | size n (k) | symbols | edit rate | edits made | search | distance "
             "| nearest (s) |", "|---|---:|---:|---:|---:|---|---|---:|"]
    for label, size, symbols, rate, count, how, shown, best in rows:
        lines.append(f"| {label} | {size} | {symbols} | {rate:.1%} | {count} | {how} | {shown} "
                     f"| {best:.3f} |")
    lines += ["", "Growth exponent of `nearest` (log-log slope of time against symbols):", "",
              "| system | edit rate | search | exponent |", "|---|---:|---|---:|"]
    for (label, rate, how), points in groups.items():
        slope = loglog_slope([n for n, _ in points], [t for _, t in points])
        lines.append(f"| {label} | {rate:.1%} | {how} | {slope:.2f} |")
    return "\n".join(lines)


def write_section(table: str, nearest_table: str, command: str) -> None:
    cpu = platform.processor() or platform.machine()
    body = (f"## Membership (`psgs.accepts`)\n\nMeasured with `{command}` on {cpu}, Python "
            f"{platform.python_version()}, lark {lark.__version__}, "
            f"{time.strftime('%Y-%m-%d', time.gmtime())}, on a machine shared with other jobs "
            f"(load average {os.getloadavg()[0]:.1f} at the end). `accepts`: best of 3 runs; Lark: "
            f"one run. `accepts` includes parsing every component and the schedule search "
            f"(not building the schedule found and replaying the witness, both done on first "
            f"access); Lark is the parse of the same "
            f"component words alone, with the exported grammars, parser construction excluded, "
            f"measured once per word tuple (it has no modes).\n\n{table}\n")
    body += ("\n### Distance to the language (`psgs.nearest`)\n\nThe same run: member tuples "
             "with random edits at 0.1%, 1% and 5% of the symbols (seeded), best of 2; "
             "`exact` without a bound, `max_errors` bounded by the number of edits made.\n\n"
             f"{nearest_table}\n")
    replace_section(BENCHMARKS_PAGE, "membership", body)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small sizes; do not write docs")
    args = parser.parse_args()
    table = run(args.quick)
    print()
    print(table)
    nearest_table = run_nearest(args.quick)
    print()
    print(nearest_table)
    if not args.quick:
        write_section(table, nearest_table, "python benchmarks/membership.py")


if __name__ == "__main__":
    main()
