"""The long fuzz run: 10^4 mutated inputs per reader, 0 crashes and 0 hangs wanted.

    flock /tmp/heavy.lock python benchmarks/fuzz.py                 # 10^4 per reader
    python benchmarks/fuzz.py --inputs 500 --reader bvh              # a quick look

The mutations and the rule are those of the suite's fuzz tests (``tests/fuzz_support.py``):
each input is a seed file from ``tests/data/fuzz`` with one to four byte edits, written to a
file and read by the public reader; it must, within the time limit, read (and pass the
reader's round-trip check) or raise the reader's documented error. Inputs are drawn from
``random.Random(seed)``, so a run is reproducible; a finding prints its seed and mutations,
which ``fuzz_support.apply`` replays. Counts per reader are printed as a Markdown table (the
one in docs/testing.md).
"""

from __future__ import annotations

import argparse
import random
import sys
import time
import traceback

from _common import REPO, load_file, require

require("psgs")
require("kinetology")
# the suite's mutation helpers, loaded by path (the tests are not a package)
_fuzz = load_file(REPO / "tests" / "fuzz_support.py", "fuzz_support")
READERS, TIME_LIMIT, Hang, apply = _fuzz.READERS, _fuzz.TIME_LIMIT, _fuzz.Hang, _fuzz.apply
outcome, random_mutations, seed_bytes = _fuzz.outcome, _fuzz.random_mutations, _fuzz.seed_bytes


def run(name: str, inputs: int, seed: int, limit: float) -> dict:
    """Fuzz one reader; returns the counts and the first findings."""
    reader = READERS[name]
    rng = random.Random(f"{seed}:{name}")
    counts = {"ok": 0, "error": 0, "crash": 0, "hang": 0}
    findings = []
    slowest = 0.0
    start = time.perf_counter()
    for i in range(inputs):
        index = rng.randrange(len(reader.seeds))
        mutations = random_mutations(rng)
        data = apply(seed_bytes(reader, index), mutations)
        began = time.perf_counter()
        try:
            counts[outcome(reader, data, limit=limit)] += 1
        except Hang:
            counts["hang"] += 1
            findings.append((i, index, mutations, "hang"))
        except Exception:  # the finding: anything but the documented error
            counts["crash"] += 1
            findings.append((i, index, mutations, traceback.format_exc(limit=-3)))
        slowest = max(slowest, time.perf_counter() - began)
    counts["seconds"] = time.perf_counter() - start
    counts["slowest"] = slowest
    return {"counts": counts, "findings": findings}


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--inputs", type=int, default=10_000, help="inputs per reader (10000)")
    parser.add_argument("--reader", action="append", choices=sorted(READERS),
                        help="reader to fuzz (repeatable; default all)")
    parser.add_argument("--seed", type=int, default=0, help="random seed (0)")
    parser.add_argument("--time-limit", type=float, default=TIME_LIMIT,
                        help=f"seconds per input before it counts as a hang ({TIME_LIMIT:g})")
    args = parser.parse_args(argv)
    names = args.reader or list(READERS)
    print(f"| reader | inputs | read | documented error | crash | hang | slowest input (s) "
          f"| total (s) |")
    print("|---|---|---|---|---|---|---|---|")
    bad = 0
    for name in names:
        result = run(name, args.inputs, args.seed, args.time_limit)
        c = result["counts"]
        print(f"| {name} | {args.inputs} | {c['ok']} | {c['error']} | {c['crash']} | {c['hang']} "
              f"| {c['slowest']:.3f} | {c['seconds']:.1f} |", flush=True)
        for i, index, mutations, what in result["findings"][:5]:
            print(f"  finding: input {i}, seed file {READERS[name].seeds[index]}, "
                  f"mutations {mutations}\n    {what.strip()}", file=sys.stderr)
        bad += c["crash"] + c["hang"]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
