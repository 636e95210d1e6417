"""Generated motion judged as generation models are judged, on the shared Bandai data.

Run from the repository root (heavy: under the lock on a shared machine)::

    flock /tmp/heavy.lock python benchmarks/generation.py           # print, write the CSV
    python benchmarks/generation.py --no-docs                        # print only

Per content of Bandai Namco dataset 1 and of the dataset-2 subset (one action per content,
all styles together), the takes (sorted by name, then dealt round-robin so that each part
holds every style it can) are split three ways, never sharing a take:

* ``--learn`` takes (default 4) build a praxicon (``praxicon.build`` in a temporary folder);
* ``--train`` takes (default 3) train a MiniRocket (aeon) on real motion only;
* ``--test`` takes (default 3) are the held-apart real takes it is scored on.

Dataset 1 has 15 takes per content, dataset 2 35: only the first ones of the round-robin deal
are used (a subsample, to keep a run near a minute); contents with fewer takes are left out.
Every learnt action is generated (``--repeat`` 3 cycles) and the classifier labels it.
Takes enter the classifier as windows of 2 s (64 frames, half-overlapping, a take shorter
than that padded with its last frame), a take's label the majority of its windows' labels.
A window's series: every rotation channel, the root's horizontal speed (cm/s) and
turning rate (deg/s of ``Hips.ry``).

Figures printed and written to ``docs/data/generation.csv`` (one row per action):

* accuracy on generated takes beside accuracy on held-apart real takes;
* per actuator channel, the distance from the generated angles to the learning performances'
  (the RMS difference of their 21 quantiles, so amplitude and offset, not tempo) beside the
  spread between real performances (the largest mean distance of one performance to the
  others): a channel is "within the spread" when its distance is no larger;
* root travel speed and turning rate, generated against the learning performances' range;
* the symbolic round trip (``Generated.round_trip``): channels whose re-segmented string is
  the morpheme repeated.
"""

from __future__ import annotations

import argparse
import csv
import importlib.machinery
import importlib.util
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
    heading_free_angles  # noqa: E402
from praxicon.generation import generate  # noqa: E402

MOCAP = REPO.parent / "shared" / "data" / "mocap"
DATASETS = ("bandai-namco-1", "bandai-namco-2-subset")
WINDOW, STRIDE = 64, 32
QUANTILES = np.linspace(0.0, 1.0, 21)
ROOT = "Hips"  # the joint that travels in the Bandai skeleton (joint_Root above it stays still)


def split(actions, learn: int, train: int, test: int):
    """Per content, its takes dealt round-robin over styles: (learn, train, test) file lists."""
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
        parts[action.content] = (dealt[:learn], dealt[learn:learn + train],
                                 dealt[learn + train:learn + train + test])
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
    gen = angles(generated, channel, axis)
    distance = float(np.mean([quantile_distance(gen, r) for r in reals]))
    spread = max(float(np.mean([quantile_distance(r, o) for j, o in enumerate(reals) if j != i]))
                 for i, r in enumerate(reals)) if len(reals) > 1 else 0.0
    return distance, spread


def travel(motion, axis):
    """Mean horizontal speed (cm/s) and net turning rate (deg/s) over the whole take."""
    speed, turn = root_signals(motion, axis)
    return float(np.mean(speed)), float(np.mean(turn))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--learn", type=int, default=4)
    ap.add_argument("--train", type=int, default=3)
    ap.add_argument("--test", type=int, default=3)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--no-docs", action="store_true")
    args = ap.parse_args(argv)
    # the root's speed and turning rate are 0 throughout in-place actions: aeon warns about
    # every such window, which says nothing here
    warnings.filterwarnings("ignore", message="Data seen by instance of MiniRocket")
    from aeon.classification.convolution_based import MiniRocketClassifier

    t0 = time.perf_counter()
    work = Path(tempfile.mkdtemp(prefix="genbench-"))
    rows, channel_rows = [], []
    summary = {}
    for dataset in DATASETS:
        actions = read_dataset(MOCAP / dataset, group_by="content")
        parts = split(actions, args.learn, args.train, args.test)
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
        axis = body_frame([read(f) for _, train, _ in parts.values() for f in train], ROOT)
        xs, ys = [], []
        for content, (_, train, _) in sorted(parts.items()):
            for f in train:
                for w in windows(series(read(f), axis)):
                    xs.append(w)
                    ys.append(content)
        clf = MiniRocketClassifier(random_state=args.seed)
        clf.fit(np.stack(xs), np.array(ys))

        def label(motion):
            predicted = clf.predict(np.stack(windows(series(motion, axis))))
            values, counts = np.unique(predicted, return_counts=True)
            return str(values[np.argmax(counts)])

        real_ok = real_n = gen_ok = gen_n = 0
        within = judged = trips = trip_n = 0
        for content, (learn, _, test) in sorted(parts.items()):
            name = f"{manifest.stem}.{content}"
            real_hits = sum(label(read(f)) == content for f in test)
            real_ok += real_hits
            real_n += len(test)
            record = px[name] if name in px else None
            row = {"dataset": dataset, "action": content, "real_correct": real_hits,
                   "real_takes": len(test), "learnt": bool(record and record.learnt)}
            if record is None or not record.learnt or not record.actuators:
                row["generated_label"] = "(not generated: "+ (record.reason or record.verdict
                                                              if record else "no record") + ")"
                rows.append(row)
                continue
            try:
                g = generate(px, name, repeat=args.repeat)
            except ValueError as exc:
                row["generated_label"] = f"(not generated: {exc})"
                rows.append(row)
                continue
            got = label(g.motion)
            gen_ok += got == content
            gen_n += 1
            reals = [read(f) for f in learn]
            dists = [channel_judgement(g.motion, reals, c, axis) for c in g.channels]
            inside = sum(d <= s for d, s in dists)
            within += inside
            judged += len(dists)
            for c, (d, s) in zip(g.channels, dists):
                channel_rows.append((dataset, content, c, d, s))
            trip = g.round_trip()
            trips += sum(trip.values())
            trip_n += len(trip)
            speed, turn = travel(g.motion, axis)
            real_travel = [travel(m, axis) for m in reals]
            row.update(generated_label=got, channels=len(dists), within_spread=inside,
                       median_distance=round(float(np.median([d for d, _ in dists])), 2),
                       median_spread=round(float(np.median([s for _, s in dists])), 2),
                       gen_speed=round(speed, 1),
                       real_speed=f"{min(s for s, _ in real_travel):.1f}..."
                                  f"{max(s for s, _ in real_travel):.1f}",
                       gen_turn=round(turn, 1),
                       real_turn=f"{min(t for _, t in real_travel):.1f}..."
                                 f"{max(t for _, t in real_travel):.1f}",
                       round_trip=f"{sum(trip.values())}/{len(trip)}")
            rows.append(row)
        summary[dataset] = (real_ok, real_n, gen_ok, gen_n, within, judged, trips, trip_n)
        print(f"{dataset}: MiniRocket on held-apart real takes {real_ok}/{real_n} "
              f"({100 * real_ok / max(real_n, 1):.0f}%), on generated takes {gen_ok}/{gen_n} "
              f"({100 * gen_ok / max(gen_n, 1):.0f}%); actuator channels within the real "
              f"spread {within}/{judged} ({100 * within / max(judged, 1):.0f}%); symbolic "
              f"round trip {trips}/{trip_n} channels", flush=True)
    keys = ["dataset", "action", "learnt", "real_correct", "real_takes", "generated_label",
            "channels", "within_spread", "median_distance", "median_spread", "gen_speed",
            "real_speed", "gen_turn", "real_turn", "round_trip"]
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
        print(f"wrote {path.relative_to(REPO)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
