"""The recognition benchmark's takes and methods: Bandai takes with their content, style and
take number; the peers' input (the channels the praxicon's descriptions read); and the four
classifiers every protocol compares (the praxicon, DTW 1-NN, MiniRocket, a joint-range
nearest centroid), each ``fit(train motions, labels) -> predict(test motions)``.

Shared by :mod:`recognition` (the closed-set protocols, parsing, the command) and
:mod:`recognition_open` (the open set).
"""

from __future__ import annotations

import os

# one thread per method, as the CPU per take is measured (before numpy and numba load)
os.environ.setdefault("NUMBA_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import importlib.machinery  # noqa: E402
import importlib.util  # noqa: E402
import re  # noqa: E402
import sys  # noqa: E402
import warnings  # noqa: E402
from collections import defaultdict  # noqa: E402
from dataclasses import dataclass  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

from _common import REPO  # noqa: E402

# aeon warns once per fit that some channels of some takes barely move (a joint held still):
# true of motion capture, and the same for every run, so it is not printed hundreds of times
warnings.filterwarnings("ignore", message="Data seen by instance of MiniRocket")

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
    if not (folder / "data").is_dir():
        raise SystemExit(f"{folder}: no such dataset (the shared data is read from "
                         f"../shared/data/mocap beside the repository)")
    for path in sorted((folder / "data").glob("*.bvh")):
        m = _NAME.match(path.stem)
        out.append(Take(m["content"], m["style"], int(m["take"]), kinetology.read(path)))
    return out


# -- the peers' input: the same channels the descriptions read ----------------------------------
def series(motion, rate: float = 10.0) -> np.ndarray:
    """Frames x channels at ``rate`` fps: non-root rotations and the root's local velocities."""
    from kinetology.segmentation import smooth, unwrap
    from praxicon.features import _ROTATIONS, _root_joints, root_motion

    roots = _root_joints(motion)
    cols = [c for c, ch in enumerate(motion.channels)
            if ch.rpartition(".")[2] in _ROTATIONS and ch.rpartition(".")[0] not in roots]
    x = smooth(unwrap(motion.values[:, cols].astype(float)), motion.frame_rate, 0.05)
    if roots:
        x = np.concatenate([x[:-1], root_motion(motion, roots)], axis=1)
    step = max(1, int(round(motion.frame_rate / rate)))
    return np.ascontiguousarray(x[::step])


def _resampled(x: np.ndarray, length: int) -> np.ndarray:
    t = np.linspace(0, len(x) - 1, length)
    return np.stack([np.interp(t, np.arange(len(x)), x[:, c]) for c in range(x.shape[1])])

# -- classifiers: fit(train motions, labels) -> predict(test motions) ---------------------------
def praxicon_fit(motions, labels, styles=None, *, per_style: bool = False):
    """The praxicon's descriptions, the kinds of features chosen with each style's takes
    held out together (``styles``); with ``per_style``, one action per content and style (as
    ``psgs praxicon build`` groups the dataset-2 subset), the answer's content counted."""
    from praxicon.description import describe
    from praxicon.feature_choice import FEATURE_KINDS, feature_kind

    groups, held = defaultdict(list), defaultdict(list)
    for i, (m, y) in enumerate(zip(motions, labels)):
        name = f"{y}|{styles[i]}" if per_style else y
        groups[name].append(m)
        held[name].append(None if styles is None else styles[i])
    descriptions = describe(groups, groups=None if styles is None else held)

    def predict(test):
        from praxicon.recognition import recognise_many
        found = recognise_many(descriptions, test, explain=0)
        # each content's probability (a content's styles summed where actions are per style):
        # what the calibration of the ranking is measured on
        predict.probabilities = []
        for r in found:
            by_content = defaultdict(float)
            for name, p in r.ranking:
                by_content[name.split("|")[0]] += p
            predict.probabilities.append(dict(by_content))
        return ([r.ranking[0][0].split("|")[0] for r in found],
                [r.action.split("|")[0] if r.action else None for r in found])
    # the kind of features the choice left out (every kind is among a Bandai take's features)
    predict.left_out = ",".join(sorted(set(FEATURE_KINDS) - {
        feature_kind(f) for f in descriptions.spread.features})) or "none"
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


praxicon_fit.needs_styles = True  # the split's styles: what the feature choice holds out
METHODS = {"praxicon": praxicon_fit, "dtw-1nn": dtw_fit, "minirocket": minirocket_fit,
           "range-centroid": centroid_fit}
