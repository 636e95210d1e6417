"""Recognising and parsing real motion: the praxicon's descriptions against three peers.

Run from the repository root (heavy: under the lock on a shared machine)::

    flock /tmp/heavy.lock python benchmarks/recognition.py           # everything, writes docs
    python benchmarks/recognition.py --only d2-in-style --no-docs     # one protocol

Peers, in the same run, on the same split and the same channels (every rotation channel of the
non-root joints, unwrapped, and the root's travel and turning velocities in its own frame):
DTW 1-nearest-neighbour (``dtaidistance``, multivariate, at 10 fps), MiniRocket (``aeon``,
every take resampled to 64 steps) and a nearest centroid on each joint's angle range.

Protocols: Bandai dataset 1 leave one style out; the dataset-2 subset in style (takes 1-3
learn, 4-5 test) and leave one style out; open set (one content left out of the learning: its
takes must come back "none of these"); parsing cmu-mocap6 leave one sequence out (frame
accuracy and segment F1) and recordings joined from three takes of different Bandai dataset-1
contents (time precision and recall of the spans, absent actions reported), each against a
sliding-window MiniRocket. CPU per take is ``time.process_time`` of classifying the test takes
(features included, reading the files not), divided by their number.
"""

from __future__ import annotations

import argparse
import os
import re
import sys
import time
from collections import defaultdict
from dataclasses import dataclass
from pathlib import Path

os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402

import importlib.machinery  # noqa: E402
import importlib.util  # noqa: E402

from _common import DATA, DOCS, MOCAP, REPO, require, write_csv  # noqa: E402

# benchmarks/praxicon.py sits first on the import path and would be imported as "praxicon":
# the package is loaded from the repository (as benchmarks/praxicon.py itself does)
_SPEC = importlib.machinery.PathFinder.find_spec("praxicon", [str(REPO)])
if _SPEC is not None and "praxicon" not in sys.modules:
    sys.modules["praxicon"] = importlib.util.module_from_spec(_SPEC)
    _SPEC.loader.exec_module(sys.modules["praxicon"])

_NAME = re.compile(r"^dataset-\d+_(?P<content>.+?)_(?P<style>[^_]+)_(?P<take>\d+)$")


@dataclass(frozen=True)
class Take:
    content: str
    style: str
    take: int
    motion: object


def read_bandai(folder: Path) -> list[Take]:
    import kinetology

    out = []
    for path in sorted((folder / "data").glob("*.bvh")):
        m = _NAME.match(path.stem)
        out.append(Take(m["content"], m["style"], int(m["take"]), kinetology.read(path)))
    return out


# -- the peers' input: the same channels the descriptions read ----------------------------------
def series(motion, rate: float = 10.0) -> np.ndarray:
    """Frames x channels at ``rate`` fps: non-root rotations and the root's local velocities."""
    from kinetology.segmentation import smooth, unwrap
    from praxicon.features import _ROTATIONS, _root_joints

    roots = _root_joints(motion)
    cols = [c for c, ch in enumerate(motion.channels)
            if ch.rpartition(".")[2] in _ROTATIONS and ch.rpartition(".")[0] not in roots]
    x = smooth(unwrap(motion.values[:, cols].astype(float)), motion.frame_rate, 0.05)
    extra = [_root_series(motion, j) for j in sorted(roots)]
    if extra:
        x = np.concatenate([x[:-1]] + extra, axis=1)
    step = max(1, int(round(motion.frame_rate / rate)))
    return np.ascontiguousarray(x[::step])


def _root_series(motion, joint):
    from kinetology.kinematics import rotation_matrices
    from kinetology.segmentation import smooth, unwrap

    rate = motion.frame_rate
    order = "".join(c.rsplit(".", 1)[1][1].upper() for c in motion.channels
                    if c.startswith(joint + ".") and c.rsplit(".", 1)[1] in ("rx", "ry", "rz"))
    if motion.skeleton is not None and joint in motion.skeleton.names:
        order = motion.skeleton.joints[motion.skeleton.index(joint)].rotation_order
    angles = {a.upper(): smooth(unwrap(motion.column(f"{joint}.r{a}").astype(float)), rate, 0.05)
              for a in "xyz" if f"{joint}.r{a}" in motion.channels}
    rot = rotation_matrices(angles, order or "XYZ", motion.frames)
    pos = np.stack([smooth(motion.column(f"{joint}.t{a}").astype(float), rate, 0.05)
                    if f"{joint}.t{a}" in motion.channels else np.zeros(motion.frames)
                    for a in "xyz"], axis=1)
    velocity = np.einsum("tji,tj->ti", rot[:-1], np.diff(pos, axis=0)) * rate
    step = np.einsum("tji,tjk->tik", rot[:-1], rot[1:])
    turning = np.degrees(np.stack([step[:, 2, 1] - step[:, 1, 2], step[:, 0, 2] - step[:, 2, 0],
                                   step[:, 1, 0] - step[:, 0, 1]], axis=1) / 2) * rate
    return np.concatenate([velocity, turning], axis=1)


def _resampled(x: np.ndarray, length: int) -> np.ndarray:
    t = np.linspace(0, len(x) - 1, length)
    return np.stack([np.interp(t, np.arange(len(x)), x[:, c]) for c in range(x.shape[1])])


# -- classifiers: fit(train motions, labels) -> predict(test motions) ---------------------------
def praxicon_fit(motions, labels, styles=None):
    """The praxicon's descriptions; with ``styles``, one action per content and style (as
    ``psgs praxicon build`` groups the dataset-2 subset), the answer's content counted."""
    from praxicon.description import describe

    groups = defaultdict(list)
    for i, (m, y) in enumerate(zip(motions, labels)):
        groups[y if styles is None else f"{y}|{styles[i]}"].append(m)
    descriptions = describe(groups)

    def predict(test):
        from praxicon.recognition import recognise_many
        found = recognise_many(descriptions, test, explain=0)
        return ([r.ranking[0][0].split("|")[0] for r in found],
                [r.action.split("|")[0] if r.action else None for r in found])
    return predict


def dtw_fit(motions, labels):
    from dtaidistance import dtw_ndim

    train = [series(m) for m in motions]
    scale = np.concatenate(train).std(axis=0) + 1e-9  # every channel on one scale

    def predict(test):
        out = []
        for m in test:
            q = series(m) / scale
            d = [dtw_ndim.distance_fast(q, t / scale, use_pruning=True) for t in train]
            out.append(labels[int(np.argmin(d))])
        return out, out
    return predict


def minirocket_fit(motions, labels, length: int = 64):
    from aeon.classification.convolution_based import MiniRocketClassifier

    x = np.stack([_resampled(series(m, 30.0), length) for m in motions])
    model = MiniRocketClassifier(random_state=0, n_jobs=1).fit(x, np.array(labels))

    def predict(test):
        z = np.stack([_resampled(series(m, 30.0), length) for m in test])
        out = list(model.predict(z))
        return out, out
    return predict


def _ranges(motion) -> np.ndarray:
    x = series(motion, 30.0)
    joints = defaultdict(float)
    from praxicon.features import _ROTATIONS, _root_joints
    roots = _root_joints(motion)
    names = [ch.rpartition(".")[0] for ch in motion.channels
             if ch.rpartition(".")[2] in _ROTATIONS and ch.rpartition(".")[0] not in roots]
    r = np.percentile(x, 95, axis=0) - np.percentile(x, 5, axis=0)
    for name, value in zip(names, r):
        joints[name] = max(joints[name], value)
    return np.array([joints[j] for j in sorted(joints)])


def centroid_fit(motions, labels):
    x = np.stack([_ranges(m) for m in motions])
    names = sorted(set(labels))
    centroids = np.stack([x[[y == n for y in labels]].mean(axis=0) for n in names])

    def predict(test):
        z = np.stack([_ranges(m) for m in test])
        d = ((z[:, None, :] - centroids[None]) ** 2).sum(axis=2)
        out = [names[i] for i in d.argmin(axis=1)]
        return out, out
    return predict


METHODS = {"praxicon": praxicon_fit, "dtw-1nn": dtw_fit, "minirocket": minirocket_fit,
           "range-centroid": centroid_fit}


def run_split(results, protocol, train, test, methods=METHODS):
    """Fit and predict every method on one split; accumulate predictions and CPU."""
    labels = [t.content for t in train]
    known = set(labels)
    test = [t for t in test if t.content in known]
    if not test:
        return
    for name, fit in methods.items():
        if getattr(fit, "needs_styles", False):
            predict = fit([t.motion for t in train], labels, [t.style for t in train])
        else:
            predict = fit([t.motion for t in train], labels)
        began = time.process_time()
        ranked, decided = predict([t.motion for t in test])
        cpu = time.process_time() - began
        r = results[protocol, name]
        r["truth"] += [t.content for t in test]
        r["pred"] += list(ranked)
        r["cpu"] += cpu
        r["n"] += len(test)


def summarise(results, protocol, methods=METHODS):
    rows = []
    for name in methods:
        r = results.get((protocol, name))
        if not r or not r["n"]:
            continue
        truth, pred = np.array(r["truth"]), np.array(r["pred"])
        recall = {c: float((pred[truth == c] == c).mean()) for c in sorted(set(truth))}
        rows.append({"protocol": protocol, "method": name, "takes": int(r["n"]),
                     "accuracy": float((truth == pred).mean()),
                     "min_recall": min(recall.values()),
                     "cpu_ms_per_take": 1000 * r["cpu"] / r["n"], "recall": recall})
    return rows


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", action="append", default=None)
    parser.add_argument("--methods", default=",".join(METHODS))
    parser.add_argument("--no-docs", action="store_true")
    args = parser.parse_args(argv)
    require("praxicon")
    methods = {k: METHODS[k] for k in args.methods.split(",")}
    want = (lambda p: args.only is None or p in args.only)
    results = defaultdict(lambda: {"truth": [], "pred": [], "cpu": 0.0, "n": 0})
    rows = []
    if want("d2-in-style") or want("d2-loso"):
        d2 = read_bandai(MOCAP / "bandai-namco-2-subset")
        if want("d2-in-style"):
            run_split(results, "d2-in-style", [t for t in d2 if t.take <= 3],
                      [t for t in d2 if t.take > 3], methods)
            rows += summarise(results, "d2-in-style", methods)
        if want("d2-loso"):
            for style in sorted({t.style for t in d2}):
                run_split(results, "d2-loso", [t for t in d2 if t.style != style],
                          [t for t in d2 if t.style == style], methods)
            rows += summarise(results, "d2-loso", methods)
    if want("d1-loso"):
        d1 = read_bandai(MOCAP / "bandai-namco-1")
        for style in sorted({t.style for t in d1}):
            run_split(results, "d1-loso", [t for t in d1 if t.style != style],
                      [t for t in d1 if t.style == style], methods)
        rows += summarise(results, "d1-loso", methods)
    for row in rows:
        worst = sorted(row["recall"].items(), key=lambda kv: kv[1])[:3]
        print(f"{row['protocol']:12s} {row['method']:15s} n={row['takes']:4d} "
              f"acc={row['accuracy']:.3f} min-recall={row['min_recall']:.2f} "
              f"cpu={row['cpu_ms_per_take']:.2f} ms/take  worst: "
              + ", ".join(f"{c} {v:.2f}" for c, v in worst), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
