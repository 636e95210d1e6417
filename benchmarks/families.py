"""Families on the dataset-2 subset: what deciding "none of these" by a content's styles buys.

Run from the repository root (under a minute on 2 cores):

    python benchmarks/families.py [--no-write]

Three measures, on ``../shared/data/mocap/bandai-namco-2-subset`` (takes 1-3 learn, takes
4-5 test, as the recognition benchmark's in-style protocol):

1. **Through a folder.** A Bandai folder of the takes 1-3 (its ``cfg/`` and the takes copied)
   built as ``psgs praxicon build`` groups it (one action per content and style), then every
   take 4-5 recognised from the folder: with the families, and with them taken off the same
   descriptions (each style's own test).
2. **The blind spot.** Run and walk alone learnt, from 2, 3, 4 and 7 styles (random draws of
   the styles, seeded), their takes 4-5 known and every turn's takes 4-5 unknown: rejected and
   right, by the families, by a praxicon learnt per content, by each style's own test; and the
   families' test together with each style's own test made k times looser (tried, not the
   praxicon's rule), beside the leave-one-content-out protocol with every style.
3. **Parsing.** Recordings joined from three takes 4-5 of one style each (four per style, as
   the recognition benchmark joins dataset 1's), parsed by the praxicons built per style and
   per content: time precision, recall and the share of time answered "none".

Results go to ``docs/data/families.csv`` (``none_of_these``: the share of the unknown takes
rejected, in the open set; of every take, in a folder; of the time, parsing; ``right``: the
share of the known takes answered with their content, in a folder with their content and
style); the figures are quoted in docs/praxicon.md ("Families").
"""

from __future__ import annotations

import argparse
import shutil
import tempfile
from dataclasses import replace
from pathlib import Path

# first: it loads the praxicon package from the repository, not benchmarks/praxicon.py
from recognition_methods import Take  # isort: skip

import numpy as np  # noqa: E402

from _common import DATA, MOCAP, require, write_csv  # noqa: E402
from recognition_parse import _joined  # noqa: E402

SUBSET = MOCAP / "bandai-namco-2-subset"
CONTENTS = ("run", "walk", "walk-turn-left", "walk-turn-right")
STYLES = ("active", "elderly", "exhausted", "feminine", "masculine", "normal", "youthful")
LOOSER = (1.0, 2.0, 4.0, 8.0, 1e9)  # k: each style's own test k times looser (1e9: not read)
SEED = 1


class Takes:
    """The subset's takes, read once each."""

    def __init__(self):
        self.read = {}

    def __call__(self, content: str, style: str, take: int):
        import kinetology

        key = (content, style, take)
        if key not in self.read:
            self.read[key] = kinetology.read(SUBSET / "data" /
                                             f"dataset-2_{content}_{style}_{take:03d}.bvh")
        return self.read[key]


def _learnt_folder(work: Path, group_by: str) -> Path:
    """A Bandai folder of the subset's takes 1-3 built into a praxicon grouped so."""
    from praxicon import build, read_dataset

    folder = work / "bandai-namco-2-train"
    if not folder.is_dir():
        (folder / "data").mkdir(parents=True)
        shutil.copytree(SUBSET / "cfg", folder / "cfg")
        for path in sorted((SUBSET / "data").glob("*_00[123].*")):
            shutil.copyfile(path, folder / "data" / path.name)
    out = work / f"px-{group_by.replace(',', '-')}"
    build(read_dataset(folder, group_by=group_by), out, progress=False, log=lambda line: None)
    return out


def through_a_folder(work: Path, rows: list, say) -> None:
    from praxicon import load, recognise_many

    px = load(_learnt_folder(work, "content,style"))
    files = sorted((SUBSET / "data").glob("*_00[45].bvh"))
    for rule, d in (("families", px.descriptions),
                    ("each style's own test", replace(px.descriptions, families=None,
                                                      family_of=()))):
        found = recognise_many(d, files, explain=0)
        none = sum(r.action is None for r in found)
        right = sum(r.action is not None and r.action.endswith(
            ".".join(f.stem.split("_")[1:3])) for r, f in zip(found, files))
        rows.append({"measure": "through a folder", "rule": rule, "takes": len(files),
                     "none_of_these": none / len(files), "right": right / len(files)})
        say(f"through a folder, {rule}: {right} of {len(files)} right (content and style), "
            f"{none} none of these")


def _answers(d, motions, explain=0):
    from praxicon import recognise_many

    return recognise_many(d, motions, explain=explain)


def blind_spot(takes: Takes, rows: list, say) -> None:
    from praxicon.description import describe

    def measure(learnt, chosen, unknown_contents):
        train = {f"{c}.{s}": [takes(c, s, t) for t in (1, 2, 3)] for c in learnt for s in chosen}
        d = describe(train, families={f"{c}.{s}": c for c in learnt for s in chosen})
        own = replace(d, families=None, family_of=())
        per_content = describe({c: [takes(c, s, t) for s in chosen for t in (1, 2, 3)]
                                for c in learnt},
                               groups={c: [s for s in chosen for _ in (1, 2, 3)]
                                       for c in learnt})
        unknown = [takes(c, s, t) for c in unknown_contents for s in STYLES for t in (4, 5)]
        known = [(c, takes(c, s, t)) for c in learnt for s in chosen for t in (4, 5)]
        motions = unknown + [m for _, m in known]
        answers = {"families": _answers(d, motions), "per content": _answers(per_content,
                                                                               motions),
                   "each style's own test": _answers(own, motions)}
        counts = {}
        for rule, found in answers.items():
            counts[rule] = (sum(r.action is None for r in found[:len(unknown)]),
                            sum(r.action is not None and r.action.split(".")[0] == c
                                for r, (c, _) in zip(found[len(unknown):], known)))
        for k in LOOSER:  # the families' test and each style's own test k times looser
            accepted = [a.action is not None and o.penalty <= o.threshold * k and o.excess <= k
                        for a, o in zip(answers["families"], answers["each style's own test"])]
            counts[f"families and own x{k:g}"] = (
                sum(not a for a in accepted[:len(unknown)]),
                sum(a and r.action.split(".")[0] == c for a, r, (c, _) in
                    zip(accepted[len(unknown):], answers["families"][len(unknown):], known)))
        return counts, len(unknown), len(known)

    rng = np.random.default_rng(SEED)
    protocols = [("leave one content out, 7 styles",
                  [([c for c in CONTENTS if c != left], list(STYLES), [left])
                   for left in CONTENTS])]
    for n in (2, 3, 4, 7):
        draws = [list(rng.choice(STYLES, n, replace=False)) for _ in range(3 if n < 7 else 1)]
        protocols.append((f"run and walk, {n} styles",
                          [(["run", "walk"], chosen, ["walk-turn-left", "walk-turn-right"])
                           for chosen in draws]))
    for label, splits in protocols:
        total: dict[str, list[int]] = {}
        unknown = known = 0
        for learnt, chosen, left in splits:
            counts, u, k = measure(learnt, chosen, left)
            unknown, known = unknown + u, known + k
            for rule, (rejected, right) in counts.items():
                t = total.setdefault(rule, [0, 0])
                t[0] += rejected
                t[1] += right
        for rule, (rejected, right) in total.items():
            rows.append({"measure": "open set", "rule": rule, "protocol": label,
                         "takes": unknown + known, "none_of_these": rejected / unknown,
                         "right": right / known})
            say(f"{label:32s} {rule:24s} unknown rejected {rejected / unknown:.3f} "
                f"({rejected}/{unknown})  known right {right / known:.3f}")


def parsing(work: Path, takes: Takes, rows: list, say) -> None:
    from praxicon import load, parse

    praxicons = {g: load(_learnt_folder(work, g)) for g in ("content,style", "content")}
    rng = np.random.default_rng(0)
    recordings = []
    for style in STYLES:
        for _ in range(4):
            chosen = rng.choice(CONTENTS, 3, replace=False)
            recordings.append(_joined([Take(str(c), style, 4, takes(c, style, 4))
                                       for c in chosen], rng))
    for group_by, px in praxicons.items():
        claimed = inside = true = covered = none = 0
        for motion, spans in recordings:
            step = 0.05
            times = np.arange(int(motion.duration / step)) * step + step / 2
            truth = [next((c for c, a, b in spans if a <= x < b), None) for x in times]
            found = [None if p is None else p.split(".")[1]
                     for p in parse(px, motion).labels(times)]
            claimed += sum(p is not None for p in found)
            none += sum(p is None for p in found)
            inside += sum(p is not None and p == t for p, t in zip(found, truth))
            true += len(truth)
            covered += sum(p == t for p, t in zip(found, truth))
        rows.append({"measure": "parsing", "rule": f"built per {group_by}",
                     "protocol": f"{len(recordings)} joined recordings",
                     "none_of_these": none / true, "precision": inside / claimed,
                     "recall": covered / true})
        say(f"parsing {len(recordings)} joined recordings, built per {group_by}: time "
            f"precision {inside / claimed:.3f} recall {covered / true:.3f} none "
            f"{none / true:.3f}")


def _cell(value):
    return f"{value:.4f}" if isinstance(value, float) else value


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--no-write", action="store_true", help="print only")
    args = parser.parse_args(argv)
    require("praxicon")
    rows: list = []
    takes = Takes()

    def say(line):
        print(line, flush=True)

    with tempfile.TemporaryDirectory(prefix="psgs-families-") as work:
        through_a_folder(Path(work), rows, say)
        blind_spot(takes, rows, say)
        parsing(Path(work), takes, rows, say)
    if not args.no_write:
        header = ["measure", "rule", "protocol", "takes", "none_of_these", "right", "precision",
                  "recall"]
        write_csv(DATA / "families.csv", header,
                  ([_cell(row.get(name, "")) for name in header] for row in rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
