"""PAL's synchronisation pair tests with the numpy engine: a row's part at once, beside the
test of each pair.

Run from the repository root (about three minutes: the test of each pair is the slow side):

    python benchmarks/pal_pairs.py [--repeat 2] [--no-docs]

Every string of an induction that passes the motif screen has a list of copies, and every pair
of lists is tested (``synchronisation._pairs_each``, the numpy engine's loop: a row's later
lists tested at once by ``_row_synchronised``). The peer is the same test on each pair
(``synchronisation.synchronised``, which the engine used before), run here side by side on the
same lists. Cases: many short lists none in step, the same all in step (every pair a partner,
as in a protocol actiongram whose strings all repeat together), and few long lists. Both give
the same pairs (checked). Times are the best of ``--repeat`` wall-clock runs on the shared
machine. Writes docs/data/pal_pairs.csv and the ``pal-pairs`` section of docs/pal.md.
"""

from __future__ import annotations

import argparse
import sys

import numpy as np

from _common import DATA, DOCS, best_of, replace_section, write_csv

#: (name, lists, copies a list, in step)
CASES = (("none in step", 2000, 10, False), ("all in step", 2000, 10, True),
         ("long lists", 200, 1000, False))


def _lists(count: int, copies: int, in_step: bool, rng: np.random.Generator) -> list:
    """``count`` lists of ``copies`` disjoint copies: at random times, or all near the same
    times (each list shifted by under a third of a copy)."""
    out = []
    for _ in range(count):
        if in_step:
            starts = np.arange(copies) * 100.0 + rng.uniform(0, 3)
            out.append(np.column_stack((starts, starts + 10 + rng.uniform(0, 3))))
        else:
            starts = np.sort(rng.choice(np.arange(40 * copies), copies, replace=False)) * 10.0
            out.append(np.column_stack((starts, starts + rng.uniform(1, 9))))
    return out


def _each_pair(lists: list) -> list:
    from psgs.induce.pal.synchronisation import synchronised

    return [(i, j) for i in range(len(lists)) for j in range(i + 1, len(lists))
            if synchronised(lists[i], lists[j], 0.5, 2)]


def _rows(lists: list) -> list:
    from psgs.induce.pal.synchronisation import _pairs_each

    return [(i, j) for rows, columns in _pairs_each(lists, 0.5, 2) for i, j in zip(rows, columns)]


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--no-docs", action="store_true", help="print only")
    args = parser.parse_args(argv)
    rng = np.random.default_rng(1)
    rows, lines = [], []
    for name, count, copies, in_step in CASES:
        lists = _lists(count, copies, in_step, rng)
        fast, found = best_of(args.repeat, lambda: _rows(lists))
        slow, expected = best_of(args.repeat, lambda: _each_pair(lists))
        if found != expected:
            print(f"{name}: the row's pairs differ from each pair's", file=sys.stderr)
            return 1
        line = (f"{name:13s} {count:5d} lists of {copies:4d} copies, {len(found):7d} pairs in "
                f"step: a row at once {fast:6.2f} s, each pair {slow:6.2f} s "
                f"(x{slow / fast:.1f})")
        print(line, flush=True)
        lines.append(line)
        rows.append((name, count, copies, len(found), f"{fast:.3f}", f"{slow:.3f}",
                     f"{slow / fast:.2f}"))
    if not args.no_docs:
        write_csv(DATA / "pal_pairs.csv", ("case", "lists", "copies", "pairs", "rows_seconds",
                                           "each_pair_seconds", "ratio"), rows)
        replace_section(DOCS / "pal.md", "pal-pairs",
                        "Measured by `python benchmarks/pal_pairs.py` (best of "
                        f"{args.repeat}; the same pairs both ways):\n\n```text\n"
                        + "\n".join(lines) + "\n```")
    return 0


if __name__ == "__main__":
    sys.exit(main())
