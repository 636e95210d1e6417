"""The long fuzz run over every reader and writer: 0 crashes, 0 hangs, 0 allocations over 1 GB.

    nice -n 10 flock /tmp/fuzz.lock python benchmarks/fuzz.py --seconds 600    # the whole run
    python benchmarks/fuzz.py --inputs 500 --reader codec             # a quick look

The mutations and the rule are those of the suite's fuzz tests (``tests/fuzz_support.py``):
each input is a seed file from ``tests/data/fuzz`` with one to four edits (of its bytes, or of
one value of a JSON file), written to a file and read by the public reader (psgs text, actiongram text and JSON, BVH, ASF, AMC, codec
streams and their decompressed base part, ``write_bvh`` and ``compress`` round trips, events
tables, praxicon manifests, label
files, praxicon folders: index, record, descriptions); it must, within the time limit, read
(and pass the reader's check) or raise the reader's documented error. With ``--seconds N`` the readers take turns, one input
each, until N seconds have passed; with ``--inputs K`` each gets K inputs. Inputs are drawn
from ``random.Random(seed)``, so a run is reproducible; a finding prints its seed file and
mutations, which ``fuzz_support.apply`` replays.

Printed: per reader the inputs tried, how many read, raised the documented error, crashed
(any other exception) or hung, the slowest input and the largest allocation one input made
(``tracemalloc``'s peak: numpy's arrays and LZMA's buffers are traced), then every distinct
finding *signature* (exception type and the innermost project line) with a count and one
replayable input. Exit status 1 when anything crashed, hung or allocated more than
``--max-bytes``.
"""

from __future__ import annotations

import argparse
import importlib.util
import random
import sys
import time
import tracemalloc
import traceback
from pathlib import Path

from _common import REPO, load_file, require


def _praxicon_package() -> None:
    """Import the praxicon package, not this folder's benchmarks/praxicon.py, which Python
    finds first when a script of this folder runs: the package is then loaded from the
    repository by its path (nothing is added to the module search path)."""
    found = importlib.util.find_spec("praxicon")
    if found is not None and Path(found.origin or "").resolve().parent == REPO / "benchmarks":
        init = REPO / "praxicon" / "__init__.py"
        spec = importlib.util.spec_from_file_location(
            "praxicon", init, submodule_search_locations=[str(init.parent)])
        module = importlib.util.module_from_spec(spec)
        sys.modules["praxicon"] = module
        spec.loader.exec_module(module)


_praxicon_package()
require("psgs")
require("kinetology")
require("praxicon")
# the suite's mutation helpers, loaded by path (the tests are not a package)
_fuzz = load_file(REPO / "tests" / "fuzz_support.py", "fuzz_support")
READERS, TIME_LIMIT, Hang, apply = _fuzz.READERS, _fuzz.TIME_LIMIT, _fuzz.Hang, _fuzz.apply
outcome, random_mutations, seed_bytes = _fuzz.outcome, _fuzz.random_mutations, _fuzz.seed_bytes


def signature(error: BaseException) -> str:
    """``Type at file:line``: the innermost frame in the project (the fuzz helpers aside)."""
    where = "?"
    for frame in traceback.extract_tb(error.__traceback__):
        path = Path(frame.filename)
        if REPO in path.parents and "fuzz" not in path.name:
            where = f"{path.relative_to(REPO)}:{frame.lineno}"
    return f"{type(error).__name__} at {where}"


class Tally:
    """One reader's counts, slowest input, largest allocation and findings by signature."""

    def __init__(self, name: str, seed: int) -> None:
        self.reader = READERS[name]
        self.rng = random.Random(f"{seed}:{name}")
        self.counts = {"ok": 0, "error": 0, "crash": 0, "hang": 0, "big": 0}
        self.tried = 0
        self.slowest = 0.0
        self.peak = 0
        self.seconds = 0.0
        self.findings: dict[str, list] = {}  # signature -> [count, first input]

    def one(self, limit: float, max_bytes: int) -> None:
        index = self.rng.randrange(len(self.reader.seeds))
        mutations = random_mutations(self.rng)
        data = apply(seed_bytes(self.reader, index), mutations)
        replay = (self.tried, self.reader.seeds[index], mutations)
        self.tried += 1
        tracemalloc.reset_peak()
        before = tracemalloc.get_traced_memory()[0]
        began = time.perf_counter()
        try:
            self.counts[outcome(self.reader, data, limit=limit)] += 1
        except Hang:
            self.counts["hang"] += 1
            self.note("hang", replay)
        except Exception as error:  # the finding: anything but the documented error
            self.counts["crash"] += 1
            self.note(signature(error), replay)
        took = time.perf_counter() - began
        self.seconds += took
        self.slowest = max(self.slowest, took)
        grew = tracemalloc.get_traced_memory()[1] - before
        self.peak = max(self.peak, grew)
        if grew > max_bytes:
            self.counts["big"] += 1
            self.note(f"allocation of {grew / 2 ** 20:.0f} MiB", replay)

    def note(self, what: str, replay) -> None:
        entry = self.findings.setdefault(what, [0, replay])
        entry[0] += 1


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seconds", type=float, default=None,
                        help="run the readers in turn for this long (default: --inputs each)")
    parser.add_argument("--inputs", type=int, default=2_000,
                        help="inputs per reader without --seconds (2000)")
    parser.add_argument("--reader", action="append", choices=sorted(READERS),
                        help="reader to fuzz (repeatable; default all)")
    parser.add_argument("--seed", type=int, default=0, help="random seed (0)")
    parser.add_argument("--time-limit", type=float, default=TIME_LIMIT,
                        help=f"seconds per input before it counts as a hang ({TIME_LIMIT:g})")
    parser.add_argument("--max-bytes", type=float, default=2 ** 30,
                        help="allocation by one input that counts as a finding (1 GiB)")
    args = parser.parse_args(argv)
    tallies = [Tally(name, args.seed) for name in (args.reader or list(READERS))]
    tracemalloc.start()
    start = time.perf_counter()
    if args.seconds is None:
        for tally in tallies:
            for _ in range(args.inputs):
                tally.one(args.time_limit, args.max_bytes)
    else:
        while time.perf_counter() - start < args.seconds:
            for tally in tallies:
                tally.one(args.time_limit, args.max_bytes)
    tracemalloc.stop()
    wall = time.perf_counter() - start
    print(f"| reader | inputs | read | documented error | crash | hang "
          f"| over {args.max_bytes / 2 ** 30:g} GiB | slowest input (s) "
          f"| largest allocation (MiB) | total (s) |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    bad = 0
    for t in tallies:
        c = t.counts
        print(f"| {t.reader.name} | {t.tried} | {c['ok']} | {c['error']} | {c['crash']} "
              f"| {c['hang']} | {c['big']} | {t.slowest:.3f} | {t.peak / 2 ** 20:.1f} "
              f"| {t.seconds:.1f} |")
        bad += c["crash"] + c["hang"] + c["big"]
    total = sum(t.tried for t in tallies)
    signatures = sum(len(t.findings) for t in tallies)
    print(f"\n{total} inputs in {wall:.0f} s; {signatures} finding signatures")
    for t in tallies:
        for what, (count, (i, seed_file, mutations)) in sorted(t.findings.items()):
            print(f"- {t.reader.name}: {what} x{count} (first: input {i}, seed file "
                  f"{seed_file}, mutations {mutations})")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
