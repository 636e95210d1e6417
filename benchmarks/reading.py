"""Reading the text format: psgs.loads beside a plain Lark parse of the whole text.

``psgs.loads`` parses a file a chunk of whole lines at a time and a line longer than a chunk
token by token (docs/format.md). The peer is what a Lark user would write and what
``loads`` itself did before: the format's own grammar (``psgs/format.lark``, LALR) parsing
the whole text into a tree, with no system built from it. Both are timed on the same
texts (CPU, best of three) and their peak memory measured (``tracemalloc``, a run of its
own); for ``loads`` also the memory the system read still holds.

    python benchmarks/reading.py            # ~2 minutes; writes docs/data/reading.csv and
                                            # the "reading" section of docs/format.md
    python benchmarks/reading.py --no-write
"""

from __future__ import annotations

import argparse
import sys
import time
from importlib import resources

from _common import DATA, DOCS, peak_bytes, replace_section, require, write_csv


def _rules_text(rules: int) -> str:
    """Two components of ``rules`` rules each (right sides spelt in binary) and a tuple per
    rule: many short lines, as an induced system of many rules is written."""
    def side(i: int, tail: str) -> str:
        return " ".join('"a"' if c == "1" else '"b"' for c in bin(i)[2:]) + f" {tail}"

    lines = ["psgs Many", "component G start S"]
    lines += [f"  r{i}: S -> {side(i, 'S')}" for i in range(rules)]
    lines += ['  r: S -> "a"', "component H start T"]
    lines += [f"  q{i}: T -> {side(i, 'T')}" for i in range(rules)]
    lines += ['  q: T -> "b"', "sync"] + [f"  (r{i}, q{i})" for i in range(rules)]
    return "\n".join(lines) + "\n"


def _long_rule_text(symbols: int) -> str:
    """One rule of ``symbols`` terminals on one line, and one to end its derivations."""
    body = " ".join(f'"{"abcd"[(7 * i * i + 3 * i) % 4]}"' for i in range(symbols))
    return f'psgs Long\ncomponent G start S\n  p1: S -> {body}\n  p2: S -> "a"\n'


def _cpu(repeat: int, function) -> float:
    best = float("inf")
    for _ in range(repeat):
        started = time.process_time()
        function()
        best = min(best, time.process_time() - started)
    return best


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-write", action="store_true", help="print only")
    args = parser.parse_args(argv)
    psgs = require("psgs")
    import lark

    grammar = resources.files("psgs").joinpath("format.lark").read_text(encoding="utf-8")
    whole = lark.Lark(grammar, parser="lalr", maybe_placeholders=False)
    texts = [("many lines: 2 x 5,000 rules, 5,000 tuples", _rules_text(5_000)),
             ("many lines: 2 x 20,000 rules, 20,000 tuples", _rules_text(20_000)),
             ("one rule of 50,000 symbols on one line", _long_rule_text(50_000)),
             ("one rule of 200,000 symbols on one line", _long_rule_text(200_000))]
    rows, lines = [], []
    for name, text in texts:
        size = len(text.encode())
        assert psgs.loads(text) is not None and whole.parse(text) is not None
        cpu_psgs = _cpu(3, lambda: psgs.loads(text))
        cpu_lark = _cpu(3, lambda: whole.parse(text))
        peak_psgs, held = peak_bytes(lambda: psgs.loads(text))
        peak_lark, tree = peak_bytes(lambda: whole.parse(text))
        rows.append([name, size, f"{cpu_psgs:.3f}", f"{cpu_lark:.3f}", peak_psgs, held,
                     peak_lark, tree])
        lines.append(f"| {name} | {size / 1e6:.2f} MB | {cpu_psgs:.2f} s | {cpu_lark:.2f} s | "
                     f"{cpu_psgs / cpu_lark:.2f} | {peak_psgs / size:.1f} ({held / size:.1f} "
                     f"held) | {peak_lark / size:.1f} | {peak_psgs / peak_lark:.2f} |")
        print(lines[-1], flush=True)
    table = ("Measured by `python benchmarks/reading.py` (CPU: best of three; memory: "
             "`tracemalloc`, bytes per byte of the file):\n\n"
             "| text | size | `psgs.loads` CPU | Lark parse CPU | ratio | `psgs.loads` peak "
             "(the system read) | Lark parse peak (its tree) | ratio |\n"
             "|---|---:|---:|---:|---:|---:|---:|---:|\n" + "\n".join(lines))
    if not args.no_write:
        write_csv(DATA / "reading.csv",
                  ["text", "bytes", "psgs_cpu_s", "lark_cpu_s", "psgs_peak_bytes",
                   "psgs_held_bytes", "lark_peak_bytes", "lark_held_bytes"], rows)
        replace_section(DOCS / "format.md", "reading", table)
    return 0


if __name__ == "__main__":
    sys.exit(main())
