"""How often PAL names exactly the strings that play a section twice, by region of the draws.

Run from the repository root:

    python benchmarks/sections.py [--draws N] [--no-write]

The draws are those of ``tests/induce/test_pal_sections.py`` (its generator and its criterion,
loaded from that file so both read the same thing): two to six strings of 60 symbols each play
a section of 8 to 16 symbols over 4 to 12 letters twice at the same times among random
symbols, with up to 16 random strings beside them; a draw is right when PAL (``min_copies=2``,
each string's sections alone and with ``section_search="pairs"``) names exactly the sectioned
strings, each with both copies (every reported copy exact). The
test checks a few hundred seeded draws for an error rate; this counts thousands of fresh ones
per region of the ranges, the hardest (an 8-symbol section over 4 letters, which a random
string of 60 holds by chance about 1 time in 13) apart, and says what each wrong draw got
wrong. In the same run, on the same draws, the peer of ``benchmarks/streams.py``: each
string's longest exact repeat, strings grouped by time span (the copies it reports are exact
by construction). Results go to ``docs/data/sections.csv`` and ``docs/streams.md``.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np
from _common import DATA, DOCS, REPO, load_file, replace_section, write_csv

#: (name, sectioned strings, symbols of the section, letters, share of the draws asked for)
REGIONS = (
    ("full ranges: 2-6 sectioned, 8-16 symbols over 4-12 letters", (2, 6), (8, 16), (4, 12), 2),
    ("8 symbols over 4 letters, 3-6 sectioned", (3, 6), (8, 8), (4, 4), 1),
    ("8 symbols over 4 letters, 2 sectioned (the hardest)", (2, 2), (8, 8), (4, 4), 2),
    ("9-10 symbols over 4 letters, 2 sectioned", (2, 2), (9, 10), (4, 4), 1),
)
SEED = 20261205


def _draws(rng, count, sectioned, length, letters):
    return [(int(rng.integers(0, 1_000_000)), int(rng.integers(sectioned[0], sectioned[1] + 1)),
             int(rng.integers(0, 17)), int(rng.integers(length[0], length[1] + 1)),
             int(rng.integers(letters[0], letters[1] + 1))) for _ in range(count)]


def _verdict(named: dict, truth: list[str], copies, exact: dict) -> str:
    """'right', or what is wrong: a sectioned string not named, a random one named, or a
    sectioned string named without both of its copies (or with a copy not exact)."""
    if not set(truth) <= set(named):
        return "sectioned string not named"
    if set(named) - set(truth):
        return "random string named"
    for name in truth:
        found = named[name]
        held = all(any(min(end, b) - max(start, a) >= (b - a) / 2 for start, end in found)
                   for a, b in copies)
        if not (held and exact[name]):
            return "copies wrong"
    return "right"


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--draws", type=int, default=1000,
                        help="draws per share of a region (default 1000: 6,000 in all)")
    parser.add_argument("--no-write", action="store_true", help="print only")
    args = parser.parse_args(argv)
    from psgs.induce import PAL
    from streams import longest_repeat, peer  # it says which psgs is measured

    drawn = load_file(REPO / "tests" / "induce" / "test_pal_sections.py", "pal_section_draws")
    rng = np.random.default_rng(SEED)
    rows, lines = [], []
    for name, sectioned, length, letters, share in REGIONS:
        draws = _draws(rng, args.draws * share, sectioned, length, letters)
        for method in ("PAL min_copies=2", "PAL min_copies=2, section_search=pairs",
                       "longest repeat per string, grouped by time"):
            verdicts, started = {}, time.process_time()
            for k, draw in enumerate(draws):
                ag, truth, copies = drawn._sectioned(*draw)
                if method.startswith("PAL"):
                    result = PAL(min_copies=2, **({"section_search": "pairs"}
                                                  if "pairs" in method else {})).induce(ag)
                    named = {n: result.occurrences[n] for n in result.components}
                    exact = {n: all(a == 1.0 for a in result.agreements[n]) for n in named}
                else:
                    named = peer(ag, longest_repeat)
                    exact = {n: True for n in named}
                verdict = _verdict(named, truth, copies, exact)
                verdicts[verdict] = verdicts.get(verdict, 0) + 1
                if (k + 1) % 500 == 0:
                    print(f"  {method}, {name}: {k + 1}/{len(draws)}", file=sys.stderr,
                          flush=True)
            seconds = time.process_time() - started
            right = verdicts.pop("right", 0)
            wrong = ", ".join(f"{n} {v}" for v, n in sorted(verdicts.items(),
                                                              key=lambda kv: -kv[1]))
            rows.append([name, method, len(draws), right, f"{right / len(draws):.4f}",
                         *(verdicts.get(v, 0) for v in ("sectioned string not named",
                                                        "random string named",
                                                        "copies wrong")), f"{seconds:.1f}"])
            lines.append(f"| {name} | {method} | {len(draws):,} | {right:,} "
                         f"({100 * right / len(draws):.2f} %) | {wrong or '-'} |")
            print(lines[-1], flush=True)
    if not args.no_write:
        write_csv(DATA / "sections.csv",
                  ["region", "method", "draws", "right", "share_right", "sectioned_missed",
                   "random_named", "copies_wrong", "cpu_seconds"], rows)
        replace_section(DOCS / "streams.md", "sections",
                        "Measured by `python benchmarks/sections.py` (fresh draws, seed "
                        f"{SEED}; the counts of each kind of error after the draws):\n\n"
                        "| draws of | method | draws | right | wrong, by kind |\n"
                        "|---|---|---:|---:|---|\n" + "\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
