"""Generated motion judged as generation models are judged, on the shared Bandai data.

Run from the repository root (heavy: under the lock on a shared machine)::

    flock /tmp/heavy.lock python benchmarks/generation.py           # print, write the CSV
    python benchmarks/generation.py --no-docs                        # print only

Per content of Bandai Namco dataset 1 and of the dataset-2 subset (one action per content,
all styles together), the takes (sorted by name, then dealt round-robin so that each part
holds every style it can) are split three ways, never sharing a take:

* ``--learn`` takes (default 4) build a praxicon (``praxicon.build`` in a temporary folder);
* ``--test`` takes (default 3) are the held-apart real takes the judges are scored on;
* the rest train the judges (MiniRocket, aeon) on real motion only: every judge of
  ``--train`` (default ``3,all``: the first 3 of the rest, or all of them).

Contents with fewer than ``learn + test + 3`` takes are left out. A judge is a training size
and a view of a take:

* ``windows``: windows of 2 s (64 frames, half-overlapping, a take shorter than that padded
  with its last frame) of every rotation channel (the root's heading-free), the root's
  horizontal speed (cm/s) and turning rate (deg/s of its heading); a take's label the
  majority of its windows' labels;
* ``body windows``: the same windows of what the body does, whichever joint carries it:
  the rotation channels of every joint below the root, and the root chain's velocity and
  turning rate in its own frame (``praxicon.features.root_motion``);
* ``whole``: that body view of the whole take resampled to 64 steps.

The judge used is the one most accurate on the held-apart real takes (ties: more training
takes, then the order above); every judge's figures are printed. Every learnt action is
generated once from all its performances and once per style of the performances it was
learnt from (``generate(..., style=...)``); n is printed. An action with a grammar is
``--repeat`` (3) cycles of it; one in which PAL found no synchronised repetition (no
grammar: Bandai's guide) is its performances' course played once, as a real take performs
it (``praxicon.acyclic``), and its figures are printed beside the others' too.

Figures printed and written to ``docs/data/generation.csv`` (one row per action):

* accuracy on generated takes beside accuracy on held-apart real takes;
* per actuator channel, the distance from the generated angles to the learning performances'
  (the RMS difference of their 21 quantiles, so amplitude and offset, not tempo; angles on
  one side of ±180°) beside the spread between real performances (the largest mean distance
  of one performance to the others): a channel is "within the spread" when its distance is
  no larger;
* root travel speed, and the net heading change over the take (degrees), generated against
  the learning performances' range;
* the symbolic round trip (``Generated.round_trip``): channels whose re-segmented string is
  the morpheme repeated, over the actions with a grammar (one without has no morpheme);
* for an action without a grammar, which has no actuators: the channels-within-spread
  figure over the rotation channels that move (10 degrees or more) in its performances,
  outside the actuator count, and (column ``alignment``) its generated range and speed
  against the performances', with the takes warped onto one another as generated and
  linearly time-normalised instead.
"""

from __future__ import annotations

import argparse
import atexit
import csv
import importlib.machinery
import importlib.util
import shutil
import sys
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np

from _common import REPO, require

# this folder holds praxicon.py, a benchmark: load the package from the repository instead
_SPEC = importlib.machinery.PathFinder.find_spec("praxicon", [str(REPO)])
if _SPEC is not None and "praxicon" not in sys.modules:
    sys.modules["praxicon"] = importlib.util.module_from_spec(_SPEC)
    _SPEC.loader.exec_module(sys.modules["praxicon"])
require("praxicon")
require("aeon")
import kinetology  # noqa: E402
from praxicon import build, load, read_dataset  # noqa: E402
from kinetology.kinematics import forward_kinematics  # noqa: E402
from praxicon.body_motion import body_frame, global_rotation, heading, \
    heading_free_angles, nearest_turn, root_chain, style_of  # noqa: E402
from praxicon.features import root_motion  # noqa: E402
from praxicon.acyclic import performed_motion  # noqa: E402
from praxicon.generation import generate, has_grammar  # noqa: E402

MOCAP = REPO.parent / "shared" / "data" / "mocap"
DATASETS = ("bandai-namco-1", "bandai-namco-2-subset")
WINDOW, STRIDE = 64, 32
QUANTILES = np.linspace(0.0, 1.0, 21)
ROOT = "Hips"  # the joint that travels in the Bandai skeleton (joint_Root above it stays still)


def split(actions, learn: int, test: int, train: int):
    """Per content, its takes dealt round-robin over styles: (learn, test, rest) file lists.

    A content is kept when it has at least ``learn + test + train`` takes."""
    parts = {}
    for action in actions:
        by_style: dict = {}
        for p in action.performances:
            style = Path(p.file).stem.split("_")[2] if Path(p.file).stem.count("_") >= 3 else ""
            by_style.setdefault(style, []).append(p.file)
        dealt = []
        queues = [sorted(v) for _, v in sorted(by_style.items())]
        while any(queues):
            for q in queues:
                if q:
                    dealt.append(q.pop(0))
        if len(dealt) < learn + train + test:
            continue
        parts[action.content] = (dealt[:learn], dealt[learn:learn + test], dealt[learn + test:])
    return parts


def series(motion, axis) -> np.ndarray:
    """(channels, frames): rotation channels (the root's heading-free), root speed and turning rate."""
    chans = list(motion.channels)
    values = np.asarray(motion.values, float)
    rot = {c: values[:, i] for i, c in enumerate(chans) if c.split(".")[-1] in ("rx", "ry", "rz")
           and not c.startswith("joint_Root")}
    rot.update(heading_free_angles(motion, ROOT, axis) or {})
    speed, turn = root_signals(motion, axis)
    return np.vstack([np.array(list(rot.values())), speed[None], turn[None]])


def body_series(motion) -> np.ndarray:
    """(channels, frames at 30 fps): what the body does, whichever joint carries it.

    The rotation channels of the joints below the root (smoothed as the segmentation
    smooths), and the root chain's velocity and turning rate in its own frame: a body
    turned by the joint above the root (generation's carrier) or by the root itself (a
    capture) reads the same.
    """
    from kinetology.segmentation import smooth, unwrap

    chain = [motion.skeleton.joints[j].name for j in root_chain(motion.skeleton, ROOT)]
    cols = [i for i, c in enumerate(motion.channels)
            if c.rpartition(".")[2] in ("rx", "ry", "rz") and c.rpartition(".")[0] not in chain]
    x = smooth(unwrap(motion.values[:, cols].astype(float)), motion.frame_rate, 0.05)
    x = np.concatenate([x[:-1], root_motion(motion, chain)], axis=1)
    step = max(1, int(round(motion.frame_rate / 30.0)))
    return np.ascontiguousarray(x[::step].T)


def resampled(x: np.ndarray, length: int = WINDOW) -> np.ndarray:
    t = np.linspace(0, x.shape[1] - 1, length)
    return np.stack([np.interp(t, np.arange(x.shape[1]), row) for row in x])


VIEWS = {"windows": lambda m, axis: windows(series(m, axis)),
         "body windows": lambda m, axis: windows(body_series(m)),
         "whole": lambda m, axis: [resampled(body_series(m))]}


def root_signals(motion, axis):
    """Per frame, the root's horizontal speed (cm/s, world) and turning rate (deg/s of its heading)."""
    rate = float(motion.frame_rate)
    if motion.frames < 2:
        return np.zeros(motion.frames), np.zeros(motion.frames)
    position = forward_kinematics(motion)[:, motion.skeleton.index(ROOT)]
    speed = np.hypot(np.gradient(position[:, 0]), np.gradient(position[:, 2])) * rate
    h, _ = heading(global_rotation(motion, ROOT), axis[0])
    return speed, np.degrees(np.gradient(h)) * rate


def windows(x: np.ndarray) -> list[np.ndarray]:
    if x.shape[1] < WINDOW:
        x = np.concatenate([x, np.repeat(x[:, -1:], WINDOW - x.shape[1], axis=1)], axis=1)
    return [x[:, s:s + WINDOW] for s in range(0, x.shape[1] - WINDOW + 1, STRIDE)]


def quantile_distance(a: np.ndarray, b: np.ndarray) -> float:
    return float(np.sqrt(np.mean((np.quantile(a, QUANTILES) - np.quantile(b, QUANTILES)) ** 2)))


def angles(motion, channel: str, axis) -> np.ndarray:
    """One channel's angles; the root's rotation heading-free (its Euler angles flip in a turn)."""
    free = heading_free_angles(motion, ROOT, axis) if channel.startswith(f"{ROOT}.r") else None
    return np.asarray(free[channel] if free else motion.column(channel), float)


def channel_judgement(generated, real_motions, channel, axis):
    """(distance of generated to the reals, spread between reals) for one channel."""
    reals = [angles(m, channel, axis) for m in real_motions if channel in m.channels]
    if channel.rpartition(".")[2].startswith("r"):  # one side of ±180° for all
        reals = [nearest_turn(r, float(np.mean(reals[0]))) for r in reals]
        gen = nearest_turn(angles(generated, channel, axis), float(np.mean(reals[0])))
    else:
        gen = angles(generated, channel, axis)
    distance = float(np.mean([quantile_distance(gen, r) for r in reals]))
    spread = max(float(np.mean([quantile_distance(r, o) for j, o in enumerate(reals) if j != i]))
                 for i, r in enumerate(reals)) if len(reals) > 1 else 0.0
    return distance, spread


def travel(motion, axis):
    """Mean horizontal speed (cm/s) and net heading change (degrees) over the whole take."""
    speed, turn = root_signals(motion, axis)
    return float(np.mean(speed)), float(np.sum(turn[1:] + turn[:-1]) / 2 / motion.frame_rate)


def moving_channels(reals, least: float = 10.0) -> list[str]:
    """Rotation channels below the root whose 5-95 % range is at least ``least`` degrees in
    the performances on average: what an action without actuators moves."""
    from kinetology.segmentation import unwrap

    chain = {c.split(".")[0] for c in reals[0].channels if c.startswith(("joint_Root", ROOT))}
    out = []
    for c in reals[0].channels:
        if c.rpartition(".")[2] in ("rx", "ry", "rz") and c.split(".")[0] not in chain:
            ranges = [np.subtract(*np.percentile(unwrap(m.column(c)), [95, 5])) for m in reals]
            if np.mean(ranges) >= least:
                out.append(c)
    return out


def alignment_figures(record, reals) -> str:
    """For an action generated from its performances' course: per moving channel, the
    generated 5-95 % range and 95th percentile of speed over the performances' mean of
    each (medians over channels), with the takes warped onto one another (as generated)
    and linearly time-normalised instead."""
    from kinetology.segmentation import unwrap

    def spread(x):
        return float(np.subtract(*np.percentile(unwrap(x), [95, 5])))

    def fast(m, c):
        return float(np.percentile(np.abs(np.gradient(unwrap(m.column(c)))), 95)) * m.frame_rate

    channels = moving_channels(reals)
    out = []
    for alignment in ("warp", "linear"):
        motion, _ = performed_motion(record, 1, reals[0], alignment=alignment)
        size = np.median([spread(motion.column(c)) / np.mean([spread(m.column(c)) for m in reals])
                          for c in channels])
        speed = np.median([fast(motion, c) / np.mean([fast(m, c) for m in reals])
                           for c in channels])
        out.append(f"{alignment}: range {size:.2f} speed {speed:.2f}")
    return f"{len(channels)} moving channels, of the takes' mean: " + "; ".join(out)


def fit_judges(parts, read, axis, sizes, seed):
    """Every judge (training size x view): name -> (size, view, fitted classifier)."""
    from aeon.classification.convolution_based import MiniRocketClassifier

    judges = {}
    for size in sizes:
        for view, cut in VIEWS.items():
            xs, ys = [], []
            for content, (_, _, rest) in sorted(parts.items()):
                for f in rest[:size]:
                    pieces = cut(read(f), axis)
                    xs += pieces
                    ys += [content] * len(pieces)
            clf = MiniRocketClassifier(random_state=seed, n_jobs=1)
            clf.fit(np.stack(xs), np.array(ys))
            largest = max(len(rest) for _, _, rest in parts.values())
            judges[f"{view}, {'all' if size >= largest else size} training takes"] = \
                (size, view, clf)
    return judges


def labeller(judge, axis):
    size, view, clf = judge

    def label(motion):
        predicted = clf.predict(np.stack(VIEWS[view](motion, axis)))
        values, counts = np.unique(predicted, return_counts=True)
        return str(values[np.argmax(counts)])
    return label


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--learn", type=int, default=4)
    ap.add_argument("--test", type=int, default=3)
    ap.add_argument("--train", default="3,all",
                    help="training sizes of the judges, comma-separated (all: every other take)")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--no-docs", action="store_true")
    args = ap.parse_args(argv)
    sizes = [10 ** 6 if t == "all" else int(t) for t in args.train.split(",")]
    # the root's speed and turning rate are 0 throughout in-place actions: aeon warns about
    # every such window, which says nothing here
    warnings.filterwarnings("ignore", message="Data seen by instance of MiniRocket")

    t0 = time.perf_counter()
    work = Path(tempfile.mkdtemp(prefix="genbench-"))
    # the praxicons built here are scratch: removed when the run ends, however it ends
    atexit.register(shutil.rmtree, work, ignore_errors=True)
    rows, judge_rows = [], []
    for dataset in DATASETS:
        if not (MOCAP / dataset).is_dir():
            raise SystemExit(f"{MOCAP / dataset}: no such dataset (the shared data is read from "
                             f"../shared/data/mocap beside the repository)")
        actions = read_dataset(MOCAP / dataset, group_by="content")
        parts = split(actions, args.learn, args.test, min(sizes))
        manifest = work / f"{dataset}.csv"
        manifest.write_text("action,file\n" + "".join(
            f"{content},{f}\n" for content, (learn, _, _) in sorted(parts.items()) for f in learn))
        out = work / dataset
        build(read_dataset(manifest), out, progress=False)
        px = load(out)
        cache: dict = {}

        def read(f):
            if f not in cache:
                cache[f] = kinetology.read(f)
            return cache[f]

        # one body axis for the whole dataset, so that every take's heading-free angles agree
        axis = body_frame([read(f) for _, _, rest in parts.values() for f in rest[:3]], ROOT)
        judges = fit_judges(parts, read, axis, sizes, args.seed)
        real = {name: sum(labeller(j, axis)(read(f)) == content
                          for content, (_, test, _) in parts.items() for f in test)
                for name, j in judges.items()}
        real_n = sum(len(test) for _, test, _ in parts.values())
        # the most accurate on real takes; ties: more training takes, then the views' order
        order = list(judges)
        chosen = max(order, key=lambda n: (real[n], judges[n][0], -order.index(n)))
        label = labeller(judges[chosen], axis)

        generated = []  # (content, style or None, Generated)
        for content, (learn, _, _) in sorted(parts.items()):
            name = f"{manifest.stem}.{content}"
            record = px[name] if name in px else None
            if record is None or not record.learnt:
                continue
            # an action without a grammar is its performances' course played once, as a
            # real take performs it once (generate's default for it)
            repeat = args.repeat if has_grammar(record) else None
            styles = [None] + sorted({style_of(f)[2] for f in learn})
            for style in styles:
                generated.append((content, style, generate(px, name, repeat=repeat,
                                                           style=style)))
        for name, j in judges.items():
            lab = labeller(j, axis)
            hits = [lab(g.motion) == c for c, _, g in generated]
            plain = [h for h, (_, st, _) in zip(hits, generated) if st is None]
            judge_rows.append((dataset, name, real[name], real_n, sum(hits), len(hits),
                               sum(plain), len(plain), name == chosen))
        acyclic = sorted({c for c, _, g in generated if g.origin == "performances"})
        print(f"{dataset}: judges (MiniRocket trained on real takes only), chosen by their "
              f"accuracy on {real_n} held-apart real takes:")
        for d, name, r, rn, g, gn, gp, gpn, pick in judge_rows:
            if d == dataset:
                print(f"  {'*' if pick else ' '} {name:<40} real {r}/{rn} ({100 * r / rn:.0f}%)"
                      f"  generated {g}/{gn} ({100 * g / max(gn, 1):.0f}%; all styles "
                      f"together {gp}/{gpn})")

        real_ok = real_n_all = gen_ok = within = judged = trips = trip_n = 0
        course_ok = course_n = 0  # the generated takes of actions without a grammar
        for content, (learn, test, _) in sorted(parts.items()):
            name = f"{manifest.stem}.{content}"
            real_hits = sum(label(read(f)) == content for f in test)
            real_ok += real_hits
            real_n_all += len(test)
            record = px[name] if name in px else None
            row = {"dataset": dataset, "action": content, "real_correct": real_hits,
                   "real_takes": len(test), "learnt": bool(record and record.learnt)}
            mine = [(st, g) for c, st, g in generated if c == content]
            if not mine:
                row["generated_labels"] = "(not generated: " + (
                    record.reason or record.verdict if record else "no record") + ")"
                rows.append(row)
                continue
            labels = [label(g.motion) for _, g in mine]
            gen_ok += sum(lb == content for lb in labels)
            g = mine[0][1]  # all styles together: the channels, travel and round trip
            reals = [read(f) for f in learn]
            grammar = g.origin == "grammar"
            if grammar:
                judged_channels = list(g.channels)
            else:  # no actuators: every rotation channel that moves in the performances
                judged_channels = moving_channels(reals)
                course_ok += sum(lb == content for lb in labels)
                course_n += len(labels)
            dists = [channel_judgement(g.motion, reals, c, axis) for c in judged_channels]
            inside = sum(d <= sp for d, sp in dists)
            if grammar:  # the actuator figure counts actuator channels only
                within += inside
                judged += len(dists)
            trip = {}
            for st, gg in mine:
                trip.update({(st, c): ok for c, ok in gg.round_trip().items()})
            trips += sum(trip.values())
            trip_n += len(trip)
            speed, turn = travel(g.motion, axis)
            real_travel = [travel(m, axis) for m in reals]
            wrong = [f"{st or 'all'}->{lb}" for (st, _), lb in zip(mine, labels) if lb != content]
            row.update(origin=g.origin,
                       generated_correct=sum(lb == content for lb in labels),
                       generated_takes=len(labels), generated_labels=" ".join(wrong),
                       channels=len(dists), within_spread=inside,
                       median_distance=round(float(np.median([d for d, _ in dists])), 2),
                       median_spread=round(float(np.median([sp for _, sp in dists])), 2),
                       gen_speed=round(speed, 1),
                       real_speed=f"{min(v for v, _ in real_travel):.1f}..."
                                  f"{max(v for v, _ in real_travel):.1f}",
                       gen_turn_deg=round(turn, 1),
                       real_turn_deg=f"{min(t for _, t in real_travel):.1f}..."
                                     f"{max(t for _, t in real_travel):.1f}",
                       round_trip=f"{sum(trip.values())}/{len(trip)}" if grammar
                       else "n/a (no grammar)")
            if not grammar:
                row.update(alignment=alignment_figures(px[name], reals))
            rows.append(row)
        gen_n = len(generated)
        learnt_n = len({c for c, _, _ in generated})
        grammar_ok, grammar_n = gen_ok - course_ok, gen_n - course_n
        print(f"{dataset}: judge '{chosen}': held-apart real takes {real_ok}/{real_n_all} "
              f"({100 * real_ok / max(real_n_all, 1):.0f}%), generated takes {gen_ok}/{gen_n} "
              f"({100 * gen_ok / max(gen_n, 1):.0f}%; n = {gen_n}: all {learnt_n} learnt actions, "
              f"each from all its performances and once per style learnt from"
              + (f"; {', '.join(acyclic)} without a grammar, from its performances' course: "
                 f"{course_ok}/{course_n}, the actions with a grammar {grammar_ok}/{grammar_n}"
                 if acyclic else "")
              + f"); actuator channels within the real spread {within}/{judged} "
              f"({100 * within / max(judged, 1):.0f}%); symbolic round trip {trips}/{trip_n} "
              f"channels (the actions with a grammar; "
              f"{'none' if not acyclic else ', '.join(acyclic)} without one)", flush=True)
    keys = ["dataset", "action", "learnt", "origin", "real_correct", "real_takes",
            "generated_correct", "generated_takes", "generated_labels", "channels",
            "within_spread", "median_distance", "median_spread", "gen_speed", "real_speed",
            "gen_turn_deg", "real_turn_deg", "round_trip", "alignment"]
    print()
    print(" | ".join(keys[1:]))
    for r in rows:
        print(" | ".join(str(r.get(k, "")) for k in keys[1:]))
    print(f"\n{time.perf_counter() - t0:.0f} s")
    if not args.no_docs:
        path = REPO / "docs" / "data" / "generation.csv"
        with path.open("w", newline="") as fh:
            w = csv.DictWriter(fh, keys)
            w.writeheader()
            w.writerows(rows)
        judges_path = REPO / "docs" / "data" / "generation_judges.csv"
        with judges_path.open("w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(["dataset", "judge", "real_correct", "real_takes", "generated_correct",
                        "generated_takes", "all_styles_correct", "all_styles_takes", "chosen"])
            w.writerows(judge_rows)
        print(f"wrote {path.relative_to(REPO)}, {judges_path.relative_to(REPO)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
