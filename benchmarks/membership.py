"""Benchmark: psgs.accepts against Lark's Earley parser alone on the same component words.

    python benchmarks/membership.py            # full run; rewrites the membership section
    python benchmarks/membership.py --quick    # small sizes, prints only

For each system of ``grammars/`` and each size, the words are a member tuple
of the language. ``accepts`` is timed end to end (parse every component and
find a synchronised schedule; the witness replay is left to first access and
not timed). Lark is timed parsing each component's word with the exported
grammar (``psgs.to_lark``, ``lark.Lark(..., parser="earley", lexer="basic")``,
symbols joined by spaces), parser construction excluded; Lark's time is the
same for both modes (it knows nothing of them) and is measured once per word
tuple. The growth exponent is the least-squares slope of log(time) against
log(size) over the sizes of one row group.
"""

from __future__ import annotations

import argparse
import dataclasses
import math
import os
import platform
import time

import lark
from _common import BENCHMARKS_PAGE, REPO, loglog_slope, replace_section, require

require("psgs")
from psgs import to_lark  # noqa: E402
from psgs.format import load  # noqa: E402
from psgs.membership import accepts  # noqa: E402

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


def time_lark(system, words) -> float:
    texts = to_lark(system)
    total = 0.0
    for g, w in zip(system.components, words):
        parser = lark.Lark(texts[g.name], start="start", parser="earley", lexer="basic")
        sentence = " ".join(w)
        start = time.perf_counter()
        parser.parse(sentence)
        total += time.perf_counter() - start
    return total


def run(quick: bool) -> str:
    rows = []
    groups: dict[tuple[str, str], list[tuple[int, float, float]]] = {}
    lark_cache: dict[tuple[str, int], float] = {}
    for label, file, size, words in cases(quick):
        base = load(REPO / "grammars" / file)
        key = (file, size)
        if key not in lark_cache:
            lark_cache[key] = time_lark(base, words)
        for mode in ("parallel", "single"):
            system = dataclasses.replace(base, mode=mode)
            repeats = 3
            ours, answer = time_accepts(system, words, repeats)
            theirs = lark_cache[key]
            symbols = sum(len(w) for w in words)
            rows.append((label, mode, size, symbols, answer, ours, theirs))
            groups.setdefault((label, mode), []).append((size, ours, theirs))
            print(f"{label:22} {mode:8} n={size:5} symbols={symbols:6} {answer:7} "
                  f"ours={ours:8.3f}s lark={theirs:8.3f}s ratio={ours / theirs:6.3f}",
                  flush=True)
    lines = ["| system | mode | size n (k) | symbols | answer | accepts (s) | Lark Earley (s) "
             "| ours / Lark |", "|---|---|---:|---:|---|---:|---:|---:|"]
    for label, mode, size, symbols, answer, ours, theirs in rows:
        lines.append(f"| {label} | {mode} | {size} | {symbols} | {answer} | {ours:.3f} | "
                     f"{theirs:.3f} | {ours / theirs:.3f} |")
    lines += ["", "Growth exponent (log-log slope of time against n):", "",
              "| system | mode | accepts | Lark Earley |", "|---|---|---:|---:|"]
    for (label, mode), points in groups.items():
        sizes = [n for n, _, _ in points]
        ours_slope = loglog_slope(sizes, [t for _, t, _ in points])
        lark_slope = loglog_slope(sizes, [t for _, _, t in points])
        lines.append(f"| {label} | {mode} | {ours_slope:.2f} | {lark_slope:.2f} |")
    return "\n".join(lines)


def write_section(table: str, command: str) -> None:
    cpu = platform.processor() or platform.machine()
    body = (f"## Membership (`psgs.accepts`)\n\nMeasured with `{command}` on {cpu}, Python "
            f"{platform.python_version()}, lark {lark.__version__}, "
            f"{time.strftime('%Y-%m-%d', time.gmtime())}, on a machine shared with other jobs "
            f"(load average {os.getloadavg()[0]:.1f} at the end). `accepts`: best of 3 runs; Lark: "
            f"one run. `accepts` includes parsing every component and the schedule search "
            f"(not the witness replay, done on first access); Lark is the parse of the same "
            f"component words alone, with the exported grammars, parser construction excluded, "
            f"measured once per word tuple (it has no modes).\n\n{table}\n")
    replace_section(BENCHMARKS_PAGE, "membership", body)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small sizes; do not write docs")
    args = parser.parse_args()
    table = run(args.quick)
    print()
    print(table)
    if not args.quick:
        write_section(table, "python benchmarks/membership.py")


if __name__ == "__main__":
    main()
