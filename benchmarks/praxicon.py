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
* **generation round trip**: every learnt action generated with ``--repeat`` copies and
  segmented again; per actuator channel, whether its kineteme string is the morpheme repeated
  K times (exactly, and in its interior), over all channels and over those whose morpheme is a
  smooth cycle (:func:`praxicon.generation.is_smooth_cycle`).

Writes ``docs/data/praxicon.csv`` (one row per action) and the summary into
``docs/benchmarks.md`` between ``<!-- praxicon:start -->`` and ``<!-- praxicon:end -->``.
"""

from __future__ import annotations

import argparse
import csv
import importlib.util
import io
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

from _common import REPO, require

require("praxicon")
from praxicon import Settings, build, executor_for, load_record, read_datasets  # noqa: E402
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


def timed_build(paths, out: Path, workers: int) -> tuple[float, dict]:
    """Wall seconds of reading the datasets and building from nothing, and the index."""
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
    return time.perf_counter() - began, result.index


def score_actions(folder: Path, index: dict) -> list[dict]:
    bench = _actuators_benchmark()
    rows = []
    for action in index["actions"]:
        row = {"action": action["name"], "dataset": action["dataset"],
               "content": action["content"], "status": action["status"],
               "performances": sum(p.get("used", False) for p in action["performances"]),
               "actuators": " ".join(action.get("actuators", ())),
               "precision": "", "recall": "", "f1": ""}
        truth = bench.TRUTH.get(action["content"])
        if action["status"] == "ok" and truth is not None:
            joints = load_record(folder, action["name"])["all_joints"]
            p, r, f = bench.score(action["actuators"], joints, truth)
            row.update(precision=round(p, 3), recall=round(r, 3), f1=round(f, 3))
        rows.append(row)
    return rows


def round_trips(folder: Path, index: dict, repeat: int) -> dict:
    counts = {"all": [0, 0, 0], "smooth": [0, 0, 0]}
    for action in index["actions"]:
        if action["status"] != "ok" or not action.get("actuators"):
            continue
        try:
            generated = generate(folder, action["name"], repeat=repeat)
        except ValueError:
            continue
        exact, interior = generated.round_trip(), generated.round_trip(interior=True)
        for channel in generated.channels:
            kinds = ["all"] + (["smooth"] if is_smooth_cycle(generated.words[channel]) else [])
            for kind in kinds:
                counts[kind][0] += 1
                counts[kind][1] += exact[channel]
                counts[kind][2] += interior[channel]
    return counts


def summarise(times, rows, trips, repeat, same_bytes, index) -> str:
    (t1, t2), runs = times
    counts = index["counts"]
    out = io.StringIO()
    out.write(f"Command: `flock /tmp/heavy.lock python benchmarks/praxicon.py` (one run: "
              f"{runs} builds of each kind from nothing, alternating, the best of each; the "
              f"machine has 2 cores shared with other sessions).\n\n")
    out.write(f"| build of {', '.join(DATASETS)} | wall seconds |\n|---|---|\n")
    out.write(f"| `--workers 1` | {t1:.1f} |\n| `--workers 2` | {t2:.1f} |\n")
    out.write(f"| ratio (1 worker / 2 workers) | **{t1 / t2:.2f}x** |\n\n")
    out.write(f"{counts['actions']} actions, {counts['learnt']} learnt, {counts['failed']} "
              f"failed (each with its one-line reason in `index.json`); the two praxicons are "
              f"{'byte-identical' if same_bytes else 'DIFFERENT'}.\n\n")
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
    out.write(f"\nGeneration round trip ({repeat} copies, re-segmented with the same "
              f"parameters), per actuator channel:\n\n| channels | count | exactly the morpheme "
              f"x {repeat} | in the interior |\n|---|---|---|---|\n")
    for kind, label in (("all", "all"), ("smooth", "morpheme a smooth cycle")):
        n, exact, inner = trips[kind]
        if n:
            out.write(f"| {label} | {n} | {exact} ({exact / n:.0%}) | {inner} "
                      f"({inner / n:.0%}) |\n")
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
    parser.add_argument("--repeat", type=int, default=3)
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
            seconds, index = timed_build(paths, out, 2)
            two.append(seconds)
            print(f"build: {one[-1]:.1f} s with 1 worker, {two[-1]:.1f} s with 2",
                  file=sys.stderr)
        t1, t2 = min(one), min(two)
        same = _files(scratch / "one") == _files(out)
        rows = score_actions(out, index)
        trips = round_trips(out, index, args.repeat)
        summary = summarise(((t1, t2), args.runs), rows, trips, args.repeat, same, index)
        print(summary)
        if not args.no_docs:
            write_docs(summary, rows)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
