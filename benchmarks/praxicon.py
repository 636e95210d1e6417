"""The whole shared-data praxicon: build time with 1 and 2 workers, actuators against the truth.

Run from the repository root (heavy: under the lock on a shared machine)::

    flock /tmp/heavy.lock python benchmarks/praxicon.py            # build, score, write docs
    python benchmarks/praxicon.py --out out/praxicon --no-docs      # keep the praxicon, no docs

In one run it builds the praxicon of every shared dataset (cmu-mocap6, Bandai Namco dataset 1,
the dataset-2 subset) twice from nothing, with ``--workers 1`` and ``--workers 2`` (processes),
and reports both wall times and their ratio (the same praxicon bytes both times, checked). Then:

* **actuators against the truth**: each learnt action's joints scored with the truth table and
  the scoring of ``benchmarks/actuators.py`` (active and inactive major joints; distal, girdle
  and axial joints don't-care), per dataset;
* **generation round trip**: every learnt action generated with each ``--repeat`` K (3 and 1
  by default, on 2 processes) and segmented again; per actuator channel, whether its kineteme
  string is the morpheme repeated K times, how it was made (the quartic alone, or with the
  correction layer, segments lengthened), per actuator whether all its channels came back, and
  over the channels whose morpheme is a smooth cycle (:func:`praxicon.generation.is_smooth_cycle`).
  The channels that do not come back, with generation's reason, go to
  ``docs/data/praxicon_generation.csv``.

Writes ``docs/data/praxicon.csv`` (one row per action) and the summary into
``docs/benchmarks.md`` between ``<!-- praxicon:start -->`` and ``<!-- praxicon:end -->``.
"""

from __future__ import annotations

import argparse
import csv
import importlib.machinery
import importlib.util
import io
import os
import shutil
import statistics
import sys
import tempfile
import time
from pathlib import Path

# one thread per worker for kinetology's compiled segmentation, which threads takes of 2^19
# samples and more over the cores: "--workers 1" then stays on one core whatever the data, so
# the ratio measures the build's own scaling (the shared data's takes are all smaller, at most
# 288,486 samples, so here it changes nothing). Set before numba is imported (it reads it then).
os.environ.setdefault("NUMBA_NUM_THREADS", "1")

from _common import REPO, require  # noqa: E402

# this script is called praxicon.py and its folder comes first on the import path, so a plain
# "import praxicon" would import this very file: the package is loaded from the repository
_SPEC = importlib.machinery.PathFinder.find_spec("praxicon", [str(REPO)])
if _SPEC is not None and "praxicon" not in sys.modules:
    sys.modules["praxicon"] = importlib.util.module_from_spec(_SPEC)
    _SPEC.loader.exec_module(sys.modules["praxicon"])
require("praxicon")
from praxicon import Settings, build, dump, executor_for, load, read_datasets  # noqa: E402
from praxicon.generation import generate, is_smooth_cycle  # noqa: E402

MOCAP = Path("..") / "shared" / "data" / "mocap"  # as the docs name it (run from the repo root)
DATASETS = ("cmu-mocap6", "bandai-namco-1", "bandai-namco-2-subset")
DOCS = REPO / "docs"


def _actuators_benchmark():
    """benchmarks/actuators.py as a module (its truth table and scoring)."""
    spec = importlib.util.spec_from_file_location("actuators_benchmark",
                                                  REPO / "benchmarks" / "actuators.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # its dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


def _files(folder: Path) -> dict:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*"))
            if p.is_file() and p.name != "timings.json"}


def timed_build(paths, out: Path, workers: int):
    """Wall seconds of reading the datasets and building from nothing, and the praxicon."""
    if out.exists():
        shutil.rmtree(out)
    began = time.perf_counter()
    actions = read_datasets(paths)
    executor, close = executor_for(workers)
    try:
        result = build(actions, out, settings=Settings.make(), executor=executor,
                       progress=False, datasets=[str(p) for p in paths], log=lambda s: None)
    finally:
        close()
    return time.perf_counter() - began, result.praxicon


def typed_round_trip(folder: Path, built, scratch: Path) -> tuple[bool, bool]:
    """(the folder loaded equals the praxicon the build returned; the loaded praxicon dumped
    anew gives the same bytes as the build wrote, timings.json aside)."""
    loaded = load(folder)
    again = scratch / "dumped"
    dump(loaded, again)
    return loaded == built, _files(again) == _files(folder)


def score_actions(px) -> list[dict]:
    bench = _actuators_benchmark()
    rows = []
    for action in px.actions:
        row = {"action": action.name, "dataset": action.dataset,
               "content": action.content, "status": action.status,
               "performances": sum(bool(p.used) for p in action.performances),
               "actuators": " ".join(action.actuators),
               "precision": "", "recall": "", "f1": ""}
        truth = bench.TRUTH.get(action.content)
        if action.learnt and truth is not None:
            p, r, f = bench.score(list(action.actuators), list(action.all_joints), truth)
            row.update(precision=round(p, 3), recall=round(r, 3), f1=round(f, 3))
        rows.append(row)
    return rows


def _action_trip(folder: str, name: str, repeat: int):
    """One action generated and segmented again: per channel and per actuator, what came back."""
    try:
        generated = generate(folder, name, repeat=repeat)
    except ValueError as exc:  # counted and listed, never dropped silently
        return name, str(exc)
    exact, interior = generated.round_trip(), generated.round_trip(interior=True)
    channels = [{"exact": exact[c], "interior": interior[c],
                 "smooth": is_smooth_cycle(generated.words[c]),
                 "method": generated.methods[c].kind.split(":")[0],
                 "lengthened": generated.methods[c].minimum_frames > 0,
                 "scaled": generated.methods[c].scale > 1.0,
                 "change": generated.methods[c].change,
                 "channel": c, "reason": generated.methods[c].kind}
                for c in generated.channels]
    return name, channels, generated.round_trip(by="actuator")


def round_trips(folder: Path, px, repeat: int, workers: int = 2) -> dict:
    """Every learnt action generated with ``repeat`` copies, on ``workers`` processes."""
    from concurrent.futures import ProcessPoolExecutor

    learnt = [a for a in px.actions if a.learnt and a.actuators]
    # the 120 fps actions (the longest programmes) first, so that none of them starts last
    names = [a.name for a in sorted(learnt, key=lambda a: (-(a.frame_rate or 0), a.name))]
    with ProcessPoolExecutor(workers) as pool:
        everything = list(pool.map(_action_trip, [str(folder)] * len(names), names,
                                   [repeat] * len(names)))
    results = [r for r in everything if len(r) == 3]
    refused = [r for r in everything if len(r) == 2]  # (name, why generation refused)
    channels = [c for _, cs, _ in results for c in cs]
    actuators = [ok for _, _, joints in results for ok in joints.values()]
    failed = [(name, c["channel"], c["reason"]) for name, cs, _ in results for c in cs
              if not c["exact"]]
    return {"channels": channels, "actuators": actuators, "failed": failed, "refused": refused,
            "actions": len(names)}


def _share(count: int, total: int) -> str:
    return f"{count} ({count / total:.0%})" if total else "0"


def summarise(times, rows, trips, repeat, same_bytes, px, typed) -> str:
    (one, two), runs = times
    t1, t2 = min(one), min(two)
    median_pair = statistics.median(a / b for a, b in zip(one, two))
    counts = px.counts
    out = io.StringIO()
    out.write(f"Command: `flock /tmp/heavy.lock python benchmarks/praxicon.py` (one run: "
              f"{runs} builds of each kind from nothing, alternating, the best of each; the "
              f"machine has 2 cores shared with other sessions; segmentation on "
              f"{os.environ.get('NUMBA_NUM_THREADS', 'all')} thread(s) per worker, "
              f"NUMBA_NUM_THREADS).\n\n")
    out.write(f"| build of {', '.join(DATASETS)} | wall seconds |\n|---|---|\n")
    out.write(f"| `--workers 1` | {t1:.1f} |\n| `--workers 2` | {t2:.1f} |\n")
    out.write(f"| ratio (1 worker / 2 workers) | **{t1 / t2:.2f}x** |\n\n")
    out.write("Each pair (1 worker, then 2, one after the other): " + "; ".join(
        f"{a:.1f} s / {b:.1f} s = {a / b:.2f}x" for a, b in zip(one, two)) +
        f"; median pair ratio **{median_pair:.2f}x**.\n\n")
    out.write(f"{counts['actions']} actions, {counts['learnt']} learnt, {counts['failed']} "
              f"failed (each with its one-line reason in `index.json`); the two praxicons are "
              f"{'byte-identical' if same_bytes else 'DIFFERENT'}.\n\n")
    equal, same_dump = typed
    out.write(f"Typed round trip: `praxicon.load` of the folder "
              f"{'equals' if equal else 'DIFFERS FROM'} the `Praxicon` the build returned, "
              f"record for record; `praxicon.dump` of it writes "
              f"{'the same bytes as the build' if same_dump else 'OTHER BYTES than the build'} "
              f"(every file but timings.json).\n\n")
    out.write("Actuator sets against the truth of `benchmarks/actuators.py` (learnt actions "
              "whose content has a truth entry):\n\n| dataset | actions scored | mean precision "
              "| mean recall | mean F1 |\n|---|---|---|---|---|\n")
    for dataset in DATASETS + ("all",):
        scored = [r for r in rows if r["f1"] != "" and (dataset == "all" or
                                                        r["dataset"] == dataset)]
        if scored:
            mean = {k: sum(r[k] for r in scored) / len(scored) for k in
                    ("precision", "recall", "f1")}
            out.write(f"| {dataset} | {len(scored)} | {mean['precision']:.2f} | "
                      f"{mean['recall']:.2f} | {mean['f1']:.2f} |\n")
    out.write("\nGeneration round trip (every learnt action generated with K copies and "
              "re-segmented with the same parameters; `Generated.round_trip`):\n\n"
              "| K | actuator channels | exactly the morpheme x K | of them by the quartic alone "
              "| by the correction layer (segments lengthened) | actuators, every channel "
              "exact | channels whose morpheme is a smooth cycle: exact |\n"
              "|---|---|---|---|---|---|---|\n")
    for k in repeat:
        got = trips[k]
        chans = got["channels"]
        exact = [c for c in chans if c["exact"]]
        smooth = [c for c in chans if c["smooth"]]
        out.write(f"| {k} | {len(chans)} | **{_share(len(exact), len(chans))}** | "
                  f"{sum(c['method'] == 'quartic' for c in exact)} | "
                  f"{sum(c['method'] == 'corrected' for c in exact)} "
                  f"({sum(c['lengthened'] for c in exact)}) | "
                  f"{_share(sum(got['actuators']), len(got['actuators']))} | "
                  f"{_share(sum(c['exact'] for c in smooth), len(smooth))} |\n")
    for k in repeat:
        got = trips[k]
        corrected = [c["change"] for c in got["channels"] if c["method"] == "corrected"]
        if corrected:
            corrected.sort()
            out.write(f"\nK = {k}: {got['actions']} actions generated, "
                      f"{len(got['refused'])} refused"
                      + "".join(f" ({name}: {why})" for name, why in got["refused"])
                      + f"; the correction layer's largest change per corrected channel: median "
                      f"{corrected[len(corrected) // 2]:.2f} deg, 90th percentile "
                      f"{corrected[int(0.9 * (len(corrected) - 1))]:.2f} deg, largest "
                      f"{corrected[-1]:.2f} deg.\n")
    first = trips[repeat[0]]
    reasons: dict[str, int] = {}
    for _, _, reason in first["failed"]:
        reasons[reason] = reasons.get(reason, 0) + 1
    if reasons:
        out.write(f"\nThe channels that do not come back at K = {repeat[0]}, by the reason "
                  f"generation gives: " + ", ".join(f"{n} `{r}`" for r, n in
                                                    sorted(reasons.items())) + ".\n")
    return out.getvalue()


def write_docs(summary: str, rows: list[dict]) -> None:
    (DOCS / "data").mkdir(exist_ok=True)
    with (DOCS / "data" / "praxicon.csv").open("w", newline="") as handle:
        writer = csv.DictWriter(handle, fieldnames=list(rows[0]), lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)
    page = DOCS / "benchmarks.md"
    text = page.read_text()
    start, end = "<!-- praxicon:start -->", "<!-- praxicon:end -->"
    block = f"{start}\n{summary}{end}"
    if start in text:
        text = text[:text.index(start)] + block + text[text.index(end) + len(end):]
    else:
        text = text.rstrip("\n") + "\n\n## The praxicon of the shared data\n\n" + block + "\n"
    page.write_text(text)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=None,
                        help="keep the 2-worker praxicon here (default: a temporary folder)")
    parser.add_argument("--repeat", default="3,1",
                        help="copies generated for the round trip, comma-separated")
    parser.add_argument("--runs", type=int, default=2,
                        help="builds of each kind, alternating; the best of each is reported")
    parser.add_argument("--no-docs", action="store_true")
    args = parser.parse_args(argv)
    os.chdir(REPO)
    paths = [MOCAP / d for d in DATASETS]
    missing = [str(p) for p in paths if not p.is_dir()]
    if missing:
        print(f"benchmarks/praxicon.py: missing data {', '.join(missing)}", file=sys.stderr)
        return 2
    scratch = Path(tempfile.mkdtemp(prefix="praxicon-bench-"))
    try:
        out = args.out or scratch / "two"
        one, two = [], []
        for _ in range(args.runs):  # alternating, so a load from elsewhere hits both alike
            one.append(timed_build(paths, scratch / "one", 1)[0])
            seconds, px = timed_build(paths, out, 2)
            two.append(seconds)
            print(f"build: {one[-1]:.1f} s with 1 worker, {two[-1]:.1f} s with 2",
                  file=sys.stderr)
        same = _files(scratch / "one") == _files(out)
        typed = typed_round_trip(out, px, scratch)
        print(f"typed round trip: loaded == built {typed[0]}, dumped bytes == built bytes "
              f"{typed[1]}", file=sys.stderr)
        rows = score_actions(px)
        repeat = [int(k) for k in args.repeat.split(",")]
        trips = {}
        for k in repeat:
            began = time.perf_counter()
            trips[k] = round_trips(out, px, k)
            print(f"round trip K={k}: {time.perf_counter() - began:.0f} s", file=sys.stderr)
        summary = summarise(((one, two), args.runs), rows, trips, repeat, same, px, typed)
        print(summary)
        if not args.no_docs:
            write_docs(summary, rows)
            with (DOCS / "data" / "praxicon_generation.csv").open("w", newline="") as handle:
                writer = csv.writer(handle, lineterminator="\n")
                writer.writerow(["repeat", "action", "channel", "reason"])
                for k in repeat:
                    writer.writerows([k, *row] for row in sorted(trips[k]["failed"]))
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
