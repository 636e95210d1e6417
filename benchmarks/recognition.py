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
takes must come back "none of these"; DTW 1-NN and MiniRocket with a rejection threshold
calibrated on held-out known takes beside the praxicon; and the bound: the same splits
classified by every method with the left-out content learnt too); parsing cmu-mocap6 leave one
sequence out (frame accuracy and segment F1) and recordings joined from three takes of
different Bandai dataset-1 contents (time precision and recall of the spans, absent actions
reported), each against a sliding-window MiniRocket. CPU per take is ``time.process_time``
of classifying the test takes (features included, reading the files not), divided by their
number.
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

import warnings  # noqa: E402

import numpy as np  # noqa: E402

# aeon warns once per fit that some channels of some takes barely move (a joint held still):
# true of motion capture, and the same for every run, so it is not printed hundreds of times
warnings.filterwarnings("ignore", message="Data seen by instance of MiniRocket")

import importlib.machinery  # noqa: E402
import importlib.util  # noqa: E402

from _common import DATA, DOCS, IMG, MOCAP, REPO, require, write_csv  # noqa: E402

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


# -- open set ----------------------------------------------------------------------------------
_MARGINS = (1.0, 1.5, 2.0)  # the whole-vector threshold: x the worst held-out training take
_LEVELS = (0.1, 0.01, 0.001, 0.0001)  # the feature-group test: how often a known take fails it


def open_set(results, protocol, train, test, *, by_style: bool = False):
    """One content left out of the learning: its test takes should come back None.

    Counted for the whole-vector threshold alone (``_MARGINS`` times the worst left-out
    training take; 1.5 is the praxicon's) and for it with the feature-group test at each of
    ``_LEVELS`` (0.01 is the praxicon's), so the trade-off between rejecting the unknown and
    keeping the known is printed, not one chosen point. Features are computed once per split.
    With ``by_style`` one action is learnt per content and style (as ``psgs praxicon build``
    groups a dataset with several takes of each pair) and the answer's content counted.
    """
    from praxicon.description import (_MARGIN, GROUP_LEVEL, common_table, describe_table,
                                      feature_rows, score_model, scores)
    from praxicon.recognition import _excess, feature_matrix

    groups = defaultdict(list)
    for t in train:
        groups[f"{t.content}|{t.style}" if by_style else t.content].append(t.motion)
    order, table = common_table({c: feature_rows(m) for c, m in groups.items()})
    known = {t.content for t in train}
    x = None
    for level in _LEVELS:
        d = describe_table(table, order, level=level)
        if x is None:
            columns, x, _ = feature_matrix(d, [t.motion for t in test])
            features = [d.spread.features[i] for i in columns]
        fitted = score_model(d, columns)
        dist, score = scores(d, x, columns, fitted=fitted)
        best = score.argmin(axis=1)
        penalty = dist[np.arange(len(x)), best] / len(columns)
        excess, _ = _excess(d, features, x, best, fitted)
        rules = {f"groups a={level:g}": (penalty <= d.spread.threshold) & (excess <= 1.0)}
        if level == GROUP_LEVEL:  # every group read, not only those that tell actions apart
            every, _ = _excess(d, features, x, best, fitted, telling=False)
            rules[f"every group a={level:g}"] = (penalty <= d.spread.threshold) & (every <= 1.0)
        if level == _LEVELS[0]:
            rules.update({f"whole x{m:g}": penalty <= d.spread.threshold / _MARGIN * m
                          for m in _MARGINS})
        if level == GROUP_LEVEL and not by_style:
            # a pairwise test on top: how far the take lies from its best action towards the
            # runner-up, against how far held-out known takes lay (tried, not the praxicon's)
            runner = np.where(np.arange(score.shape[1])[None] == best[:, None], np.inf,
                              score).argmin(axis=1)
            towards = _towards(fitted, dist, best, runner)
            held = _towards_held_out(table, order)
            for q in _PAIR_QUANTILES:
                rules[f"groups+pair q={q:g}"] = rules[f"groups a={level:g}"] & (
                    towards <= np.quantile(held, q))
        for name, accept in rules.items():
            r = results[protocol, name]
            for t, b, ok in zip(test, best, accept):
                decided = d.names[b].split("|")[0] if ok else None
                _tally(r, t.content, known, decided)
                if name == f"groups a={GROUP_LEVEL:g}":
                    # what the praxicon's own rule answered, per left-out content and per
                    # known take it got wrong: where the open set fails
                    detail = results[protocol, "detail"]
                    if t.content not in known:
                        detail.setdefault("left-out", {}).setdefault(t.content, []).append(
                            decided)
                    elif decided != t.content:
                        detail.setdefault("known-wrong", {}).setdefault(
                            f"{t.content} {t.style}_{t.take:03d}", []).append(decided)


_PAIR_QUANTILES = (0.9, 0.99)  # the pairwise test: share of held-out known takes it keeps


def _towards(fitted, dist, best, other) -> np.ndarray:
    """Per take, how many shared standard deviations it lies from its best action's mean
    towards ``other``'s along the line between the two means: from the shared squared
    distances alone, ``(d_best - d_other + D²) / 2D`` with ``D`` the means' distance."""
    from praxicon.description import distances

    gap = np.array([distances(fitted.means[o][None], fitted.means[b][None], fitted.parts)[0, 0]
                    for b, o in zip(best, other)])
    gap = np.sqrt(np.maximum(gap, 1e-12))
    i = np.arange(len(best))
    return (dist[i, best] - dist[i, other] + gap ** 2) / (2 * gap)


def _towards_held_out(table, order, folds: int = 5) -> np.ndarray:
    """:func:`_towards` of the training takes, each scored by descriptions learnt without
    its fold, for those ranked right (towards their runner-up): what known takes do."""
    from praxicon.description import describe_table, score_model, scores

    out = []
    columns = np.arange(len(order))
    for fold in range(folds):
        learn = {c: v[np.arange(len(v)) % folds != fold] for c, v in table.items()}
        d = describe_table({c: v for c, v in learn.items() if len(v)}, order)
        fitted = score_model(d, columns)
        for c, v in table.items():
            v = v[np.arange(len(v)) % folds == fold]
            if not len(v) or c not in d.names:
                continue
            dist, score = scores(d, v, columns, fitted=fitted)
            best = score.argmin(axis=1)
            right = best == d.names.index(c)
            if right.any():
                runner = np.where(np.arange(score.shape[1])[None] == best[:, None], np.inf,
                                  score).argmin(axis=1)
                out.extend(_towards(fitted, dist[right], best[right], runner[right]))
    return np.array(out) if out else np.array([np.inf])


def _open_detail(protocol, results) -> str:
    """One line per protocol at the praxicon's level: per left-out content its takes answered
    none of these and the commonest other answer, and the known takes answered wrongly (how
    many splits, and as what)."""
    from collections import Counter

    detail = results[protocol, "detail"]
    parts = []
    for content, answers in sorted(detail.get("left-out", {}).items()):
        taken = Counter(a for a in answers if a is not None).most_common(1)
        parts.append(f"{content} {sum(a is None for a in answers)}/{len(answers)}"
                     + (f" (else {taken[0][0]} {taken[0][1]})" if taken else ""))
    wrong = [f"{k} x{len(v)} as {Counter(map(str, v)).most_common(1)[0][0]}"
             for k, v in sorted(detail.get("known-wrong", {}).items())]
    return (f"{protocol:16s} at a=0.01: none of these per left-out content: " + ", ".join(parts)
            + "; known takes wrong: " + (", ".join(wrong) or "none"))


# -- the peers on the open set: a rejection threshold calibrated on held-out known takes --------
_PEER_QUANTILES = (0.9, 0.95, 0.99, 1.0)  # share of held-out known takes a peer's threshold keeps


def _dtw_matrix(takes, cache: dict) -> np.ndarray:
    """Every pair's DTW distance over ``takes`` (the same scaled series as the 1-NN peer),
    computed once per dataset and read by every open-set split."""
    key = id(takes)
    if key not in cache:
        from dtaidistance import dtw_ndim

        xs = [series(t.motion) for t in takes]
        scale = np.concatenate(xs).std(axis=0) + 1e-9
        d = dtw_ndim.distance_matrix_fast([np.ascontiguousarray(x / scale) for x in xs],
                                          parallel=False)
        cache[key] = (np.where(np.isfinite(d), d, d.T) if np.isinf(d).any() else d,
                      {id(t): i for i, t in enumerate(takes)})
    return cache[key]


def peer_open_set(results, protocol, takes, train, test, cache: dict, folds: int = 5):
    """The open set as an analyst would do it with the peers: DTW 1-NN answers none of these
    when the nearest training take is further than the held-out known takes' nearest
    distances allow (each training take's nearest other training take), MiniRocket when its
    ridge head's top score is below what held-out known takes got (``folds``-fold on the
    training takes). One threshold per quantile of ``_PEER_QUANTILES``: the share of held-out
    known takes the threshold keeps, so the trade-off is printed as for the praxicon."""
    from sklearn.model_selection import KFold

    known = {t.content for t in train}
    labels = np.array([t.content for t in train])
    answers = {}
    d, index = _dtw_matrix(takes, cache)
    tr = np.array([index[id(t)] for t in train])
    te = np.array([index[id(t)] for t in test])
    own = d[np.ix_(tr, tr)].copy()
    np.fill_diagonal(own, np.inf)
    held = own.min(axis=1)
    near = d[np.ix_(te, tr)]
    nearest, dist = labels[near.argmin(axis=1)], near.min(axis=1)
    for q in _PEER_QUANTILES:
        limit = np.quantile(held, q)
        answers[f"dtw-1nn q={q:g}"] = [y if s <= limit else None for y, s in zip(nearest, dist)]

    fx, fz, head = _rocket(train, test)
    top_held = np.empty(len(train))
    for fit_i, out_i in KFold(folds, shuffle=True, random_state=0).split(fx):
        model = head().fit(fx[fit_i], labels[fit_i])
        top_held[out_i] = model.decision_function(fx[out_i]).max(axis=1)
    model = head().fit(fx, labels)
    score = model.decision_function(fz)
    best, top = model.classes_[score.argmax(axis=1)], score.max(axis=1)
    for q in _PEER_QUANTILES:
        limit = np.quantile(top_held, 1 - q)
        answers[f"minirocket q={q:g}"] = [y if s >= limit else None for y, s in zip(best, top)]
    for name, decided in answers.items():
        r = results[protocol, name]
        for t, a in zip(test, decided):
            _tally(r, t.content, known, a)


def _rocket(train, test):
    """MiniRocket's features of the ``train`` and ``test`` takes (its transform fitted on
    ``train``) and a maker of its ridge head (as ``MiniRocketClassifier`` has it)."""
    from aeon.transformations.collection.convolution_based import MiniRocket
    from sklearn.linear_model import RidgeClassifierCV
    from sklearn.pipeline import make_pipeline
    from sklearn.preprocessing import StandardScaler

    x = np.stack([_resampled(series(t.motion, 30.0), 64) for t in train])
    z = np.stack([_resampled(series(t.motion, 30.0), 64) for t in test])
    rocket = MiniRocket(random_state=0, n_jobs=1).fit(x)
    return (rocket.transform(x), rocket.transform(z),
            lambda: make_pipeline(StandardScaler(with_mean=False),
                                  RidgeClassifierCV(alphas=np.logspace(-3, 3, 10))))


def _tally(counts: dict, content: str, known, decided) -> None:
    """One open-set answer counted: a known take right, or a left-out take rejected (None)."""
    if content in known:
        counts["known"] += 1
        counts["known_right"] += int(decided == content)
    else:
        counts["unknown"] += 1
        counts["rejected"] += int(decided is None)


# -- the open set's bound: the left-out content learnt ------------------------------------------
_BOUND_FOLDS = 5  # folds over styles when the left-out content's takes are the test takes


def open_bound(results, protocol, takes, train, taught, test, cache, *, by_style=False):
    """The closed-set classifiers that have learnt the left-out content too (``taught``: its
    takes among the split's learning takes), on the split's test takes.

    A rule that accepts a region per known action and answers None elsewhere is a classifier
    of the known contents and the left-out one (None read as it), with the same rejection and
    the same known accuracy: so a left-out take answered as its own content here is one such
    a rule could reject, and a known take answered right one it could keep. Kept per take
    under ``open-bound-*``: how far the best other answer is ahead of the left-out content
    (``_margins``), that answer, and whether the take is of the left-out content; the left-out
    content is answered where the margin is under 0, or under a bias that favours it
    (``_bound_row``). When the left-out content's learning takes are its test takes (one take
    per content and style), it is learnt in ``_BOUND_FOLDS`` folds over its styles, each
    fold's takes answered by classifiers learnt from the other folds' (the known takes in
    every fold). Test takes of contents the split cannot learn are not counted.
    """
    from praxicon.description import describe, scores
    from praxicon.recognition import feature_matrix

    known = {t.content for t in train}
    content = taught[0].content
    asked = [t for t in test if t.content in known or t.content == content]
    tested = {id(t) for t in asked}
    folds = [set()]
    if any(id(t) in tested for t in taught):
        styles = sorted({t.style for t in taught})
        folds = [set(styles[i::_BOUND_FOLDS]) for i in range(_BOUND_FOLDS)]
    for fold in folds:
        learn = train + [t for t in taught if t.style not in fold]
        ask = [t for t in asked if t.content in known or not fold or t.style in fold]
        labels = np.array([t.content for t in learn])
        groups = defaultdict(list)
        for t in learn:
            groups[f"{t.content}|{t.style}" if by_style else t.content].append(t.motion)
        d = describe(groups)
        columns, x, _ = feature_matrix(d, [t.motion for t in ask])
        # every method's scores, higher better, with the content each column answers
        found = {"praxicon": (-scores(d, x, columns)[1], [n.split("|")[0] for n in d.names])}
        if _PEERS[0] and not by_style:
            near, index = _dtw_matrix(takes, cache)
            near = near[np.ix_([index[id(t)] for t in ask], [index[id(t)] for t in learn])]
            found["dtw-1nn"] = (-near, labels)
            fx, fz, head = _rocket(learn, ask)
            model = head().fit(fx, labels)
            found["minirocket"] = (model.decision_function(fz), model.classes_)
        for name, (score, answers) in found.items():
            margin, other = _margins(score, np.asarray(answers), content)
            kept = results[protocol.replace("open-", "open-bound-", 1), name]
            kept.setdefault("takes", []).extend(
                (m, t.content == content, o == t.content) for t, m, o in zip(ask, margin, other))


def _margins(score, answers, content):
    """Per take (rows of ``score``: takes x columns, higher better; ``answers``: the content
    each column answers) how far the best column of another content is ahead of the best
    column of ``content``, and that other content."""
    mine = answers == content
    others = np.where(mine[None], -np.inf, score)
    return others.max(axis=1) - score[:, mine].max(axis=1), answers[others.argmax(axis=1)]


def _bound_row(taken, recall: float = 0.9):
    """The left-out content's recall and the known takes' accuracy where it is answered when
    its margin is under 0, and the known accuracy where it is answered when its margin is
    under the one bias, pooled over every split, at which ``recall`` of its takes are (a bias
    over 0 favours it; the trade-off the classifiers have on offer at that recall)."""
    margin, mine, right = (np.array(v) for v in zip(*taken))
    known = lambda bias: float((right & (margin >= bias))[~mine].mean())  # noqa: E731
    ranked = np.sort(margin[mine])
    if not len(ranked):  # no take of the left-out content tested
        return float("nan"), known(0.0), float("nan")
    bias = ranked[min(len(ranked) - 1, int(np.ceil(recall * len(ranked))) - 1)]
    return float((margin[mine] < 0).mean()), known(0.0), known(np.nextafter(bias, np.inf))


def open_split(results, protocol, takes, pool, test, content, cache, *, by_style=False):
    """One open-set split: ``content`` left out of ``pool`` (the split's learning takes); the
    praxicon's rules, the peers' (not for ``by_style``) and the bound on ``test``."""
    train = [t for t in pool if t.content != content]
    open_set(results, protocol, train, test, by_style=by_style)
    if _PEERS[0] and not by_style:
        peer_open_set(results, protocol, takes, train, test, cache)
    open_bound(results, protocol, takes, train, [t for t in pool if t.content == content],
               test, cache, by_style=by_style)


# -- parsing -----------------------------------------------------------------------------------
def _rate(motion, rate: float = 30.0):
    """The motion at about ``rate`` fps (every k-th frame after smoothing): parsing's input."""
    from kinetology import Motion
    from kinetology.segmentation import smooth

    k = max(1, int(round(motion.frame_rate / rate)))
    values = smooth(np.asarray(motion.values, dtype=float), motion.frame_rate, 0.5 * k /
                    motion.frame_rate)[::k]
    return Motion(values, motion.channels, motion.frame_rate / k, motion.skeleton,
                  motion.source)


def _cut(motion, start, stop):
    from kinetology import Motion
    a, b = int(round(start * motion.frame_rate)), int(round(stop * motion.frame_rate))
    return Motion(motion.values[a:b], motion.channels, motion.frame_rate, motion.skeleton,
                  motion.source)


_PEERS = [True]  # --no-peers (a quick check of the praxicon alone) sets it False


def _window_peer(takes: dict, window: float, hop: float, length: int = 64):
    """Sliding-window MiniRocket: fit on the training takes' windows, label every window."""
    if not _PEERS[0]:
        return lambda motion: (np.array([0.0]), [None])
    from aeon.classification.convolution_based import MiniRocketClassifier
    from praxicon.parsing import windows

    x, y = [], []
    for name, motions in takes.items():
        for m in motions:
            for w in windows(m, window, 2 * hop)[1]:
                x.append(_resampled(series(w, 30.0), length))
                y.append(name)
    model = MiniRocketClassifier(random_state=0, n_jobs=1).fit(np.stack(x), np.array(y))

    def label(motion):
        starts, cuts = windows(motion, window, hop)
        z = np.stack([_resampled(series(w, 30.0), length) for w in cuts])
        centres = np.array(starts) + min(window, motion.duration) / 2
        return centres, list(model.predict(z))
    return label


def _timeline_labels(timeline, times):
    return timeline.labels(times)


def _peer_labels(centres, labels, times):
    idx = np.abs(np.asarray(times)[:, None] - centres[None, :]).argmin(axis=1)
    return [labels[i] for i in idx]


def _segments(labels, times, step):
    out = []
    i = 0
    while i < len(labels):
        j = i
        while j + 1 < len(labels) and labels[j + 1] == labels[i]:
            j += 1
        out.append((labels[i], times[i] - step / 2, times[j] + step / 2))
        i = j + 1
    return out


def segment_f1(truth, found, step):
    """Segments (runs of one label) matched when the label agrees and IoU >= 0.5."""
    times = np.arange(len(truth)) * step + step / 2
    t = [s for s in _segments(truth, times, step) if s[0] is not None]
    f = [s for s in _segments(found, times, step) if s[0] is not None]
    hit = 0
    for label, a, b in t:
        for label2, c, d in f:
            inter = max(0.0, min(b, d) - max(a, c))
            if label == label2 and inter / (max(b, d) - min(a, c)) >= 0.5:
                hit += 1
                break
    precision = hit / len(f) if f else 0.0
    recall = hit / len(t) if t else 0.0
    return 2 * precision * recall / (precision + recall) if hit else 0.0


def parse_cmu(results, window=2.0, hop=0.25):
    import kinetology
    from praxicon.parsing import describe_windows, parse

    root = MOCAP / "cmu-mocap6"
    sequences = {}
    for path in sorted((root / "amc").glob("*.amc")):
        labels = kinetology.read_cmu_truelabels(root / "truelabels" / f"{path.stem}.txt", 120.0)
        sequences[path.stem] = (_rate(kinetology.read(path)), labels)
    for left in sequences:
        takes = defaultdict(list)
        for name, (motion, spans) in sequences.items():
            if name == left:
                continue
            for span in spans:
                if span.stop - span.start >= 2.0:
                    takes[span.label].append(_cut(motion, span.start, min(span.stop,
                                                                          motion.duration)))
        motion, spans = sequences[left]
        step = 0.1
        times = np.arange(int(motion.duration / step)) * step + step / 2
        truth = [next((s.label for s in spans if s.start <= t < s.stop), None) for t in times]
        known = [lab in takes for lab in truth]
        descriptions = describe_windows(takes, window=window, hop=hop)
        began = time.process_time()
        found = parse(descriptions, motion, hop=hop).labels(times)
        cpu_ours = time.process_time() - began
        peer = _window_peer(takes, window, hop)
        began = time.process_time()
        centres, labels = peer(motion)
        other = _peer_labels(centres, labels, times)
        cpu_peer = time.process_time() - began
        for method, pred, cpu in (("praxicon", found, cpu_ours),
                                  ("minirocket-windows", other, cpu_peer)):
            r = results["cmu-parse", method]
            r["frames"] += sum(known)
            r["right"] += sum(k and p == t for k, p, t in zip(known, pred, truth))
            r["f1"].append(segment_f1([t if k else None for t, k in zip(truth, known)],
                                      pred, step))
            r["cpu"] += cpu
            r["seconds"] += motion.duration


def _joined(takes, rng):
    """Takes one after another, the root's position continued where the last take stopped."""
    from kinetology import Motion

    pieces, spans, t = [], [], 0.0
    last = None
    for take in takes:
        values = np.array(take.motion.values, dtype=float)
        trans = [c for c, ch in enumerate(take.motion.channels) if ch[-2:] in ("tx", "ty", "tz")]
        if last is not None:
            values[:, trans] += last[trans] - values[0, trans]
        last = values[-1]
        pieces.append(values)
        spans.append((take.content, t, t + take.motion.duration))
        t += take.motion.duration
    m = takes[0].motion
    return Motion(np.concatenate(pieces), m.channels, m.frame_rate, m.skeleton,
                  "<joined>"), spans


# the root's features also scored in each action's own spread: none of them, and the drift
# with the sway (the praxicon's default is the drift alone)
_OWN_VARIANTS = (("none", ()), ("drift+sway", ("drift", "energy")))


def parse_joined(results, data, per_style: int = 4, window=2.0, hop=0.25):
    from praxicon.parsing import describe_windows, parse

    rng = np.random.default_rng(0)
    for style in sorted({t.style for t in data}):
        train = defaultdict(list)
        for t in data:
            if t.style != style:
                train[t.content].append(t.motion)
        mine = [t for t in data if t.style == style and t.content in train]
        contents = sorted({t.content for t in mine})
        if len(contents) < 3:
            continue
        descriptions = describe_windows(train, window=window, hop=hop)
        peer = _window_peer(train, window, hop)
        for _ in range(per_style):
            chosen = rng.choice(contents, 3, replace=False)
            takes = [next(t for t in mine if t.content == c) for c in chosen]
            motion, spans = _joined(takes, rng)
            step = 0.05
            times = np.arange(int(motion.duration / step)) * step + step / 2
            truth = [next((c for c, a, b in spans if a <= x < b), None) for x in times]
            began = time.process_time()
            found = parse(descriptions, motion, hop=hop).labels(times)
            cpu_ours = time.process_time() - began
            # the same descriptions scored otherwise: the trade-off of the own-spread terms
            variants = [(f"praxicon own={name}", parse(descriptions, motion, hop=hop,
                                                       own=own).labels(times), 0.0)
                        for name, own in _OWN_VARIANTS]
            centres, labels = peer(motion)
            other = _peer_labels(centres, labels, times)
            for method, pred, cpu in (("praxicon", found, cpu_ours), *variants,
                                      ("minirocket-windows", other, 0.0)):
                r = results["joined-parse", method]
                pred = list(pred)
                r["claimed"] += sum(p is not None for p in pred)
                r["inside"] += sum(p is not None and p == t for p, t in zip(pred, truth))
                r["true"] += len(truth)
                r["covered"] += sum(p == t for p, t in zip(pred, truth))
                absent = set(train) - set(chosen)
                r["absent_pairs"] += len(absent)
                r["absent_reported"] += len(absent & set(pred))
                r["recordings"] += 1
                r["any_absent"] += int(bool(absent & set(pred)))
                r["cpu"] += cpu
                r["seconds"] += motion.duration


def cost_growth(data, counts=(2, 4, 8, 10)):
    """CPU per take as the number of actions grows (takes of those actions only)."""
    contents = sorted({t.content for t in data}, key=lambda c: -sum(t.content == c
                                                                    for t in data))
    rows = []
    for k in counts:
        chosen = set(contents[:k])
        pool = [t for t in data if t.content in chosen]
        train = [t for t in pool if t.take == 1 and t.style not in ("normal", "old")]
        learnt = {t.content for t in train}
        test = [t for t in pool if t.style in ("normal", "old") and t.content in learnt][:20]
        row = {"actions": len(learnt), "train_takes": len(train), "test_takes": len(test)}
        for name in ("praxicon", "dtw-1nn"):
            predict = METHODS[name]([t.motion for t in train], [t.content for t in train])
            began = time.process_time()
            predict([t.motion for t in test])
            row[name] = 1000 * (time.process_time() - began) / len(test)
        rows.append(row)
    return rows


def pictures(data, say, style="active", contents=("walk", "byebye", "bow")):
    """The docs' pictures: a joined recording of one unseen style parsed, and a recognition's
    explanation (learnt from every other style)."""
    from praxicon.description import describe
    from praxicon.parsing import describe_windows, parse
    from praxicon.recognition import recognise
    from praxicon.recognition_pictures import draw_explanation, draw_timeline

    train = defaultdict(list)
    for t in data:
        if t.style != style:
            train[t.content].append(t.motion)
    takes = [next(t for t in data if t.style == style and t.content == c) for c in contents]
    motion, spans = _joined(takes, None)
    timeline = parse(describe_windows(train), motion)
    draw_timeline(timeline, motion, IMG / "recognition_timeline.png")
    say("truth: " + ", ".join(f"{c} {a:.2f}-{b:.2f}" for c, a, b in spans))
    for span in timeline.spans:
        say(f"parsed: {span.start:6.2f} {span.stop:6.2f} {span.action or '-'} {span.score:.3f}")
    found = recognise(describe(train), next(t.motion for t in data if t.style == style
                                            and t.content == "byebye"))
    draw_explanation(found, IMG / "recognition_explanation.png")
    for line in found.explain().splitlines():
        say(line.replace(str(MOCAP), "../shared/data/mocap"))


def _kind(feature: str) -> str:
    if feature == "tempo":
        return "tempo"
    if ".travel" in feature or ".turn" in feature:
        return "root drift and sway"
    kind = feature.rsplit(":", 1)[-1].rstrip("0123456789")
    return {"posec": "pose"}.get(kind, kind)


def ablation(say, d1, d2):
    """What each kind of feature buys: accuracy with the kind left out (same splits)."""
    from praxicon.description import OWN_KINDS, common_table, describe_table, feature_rows, scores

    splits = []
    for name, data, folds in (
            ("d2-in-style", d2, [(lambda t: t.take <= 3, lambda t: t.take > 3)]),
            ("d2-loso", d2, [(lambda t, s=s: t.style != s, lambda t, s=s: t.style == s)
                             for s in sorted({t.style for t in d2})]),
            ("d1-loso", d1, [(lambda t, s=s: t.style != s, lambda t, s=s: t.style == s)
                             for s in sorted({t.style for t in d1})])):
        rows = feature_rows([t.motion for t in data])
        order, table = common_table({"all": rows})
        splits.append((name, data, folds, order, table["all"]))
    kinds = (["none"] + sorted({_kind(f) for f in splits[0][3]})
             + ["rank 0", "own: none", "own: drift and sway"])
    out = []
    for kind in kinds:
        rank = 0 if kind == "rank 0" else 16
        own = {"own: none": (), "own: drift and sway": ("drift", "energy")}.get(kind, OWN_KINDS)
        accs = []
        for name, data, folds, order, x in splits:
            keep = np.array([_kind(f) != kind for f in order])
            feats = tuple(f for f, k in zip(order, keep) if k)
            right = total = 0
            for is_train, is_test in folds:
                tr = [i for i, t in enumerate(data) if is_train(t)]
                labels = sorted({data[i].content for i in tr})
                te = [i for i, t in enumerate(data) if is_test(t) and t.content in labels]
                d = describe_table({c: x[[i for i in tr if data[i].content == c]][:, keep]
                                    for c in labels}, feats, rank=rank)
                score = scores(d, x[te][:, keep], np.arange(len(feats)), kinds=own)[1]
                pred = np.array(d.names)[score.argmin(axis=1)]
                right += int((pred == np.array([data[i].content for i in te])).sum())
                total += len(te)
            accs.append(right / total)
        label = {"none": "all features", "rank 0": "no shared directions (diagonal)",
                 "own: none": "root drift not in own spread",
                 "own: drift and sway": "root drift and sway in own spread"}.get(
                     kind, f"without {kind}")
        say(f"ablation {label:33s} " + "  ".join(f"{n} {a:.3f}" for (n, *_), a in
                                                  zip(splits, accs)))
        out.append({"protocol": "ablation", "method": label,
                    **{n: a for (n, *_), a in zip(splits, accs)}})
    return out


def _fmt(x, digits=3):
    return f"{x:.{digits}f}" if isinstance(x, float) else str(x)


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", action="append", default=None,
                        help="d1-loso, d2-in-style, d2-loso, open-set (open-d1, open-d2: one dataset's "
                             "part), cmu-parse, joined-parse, "
                             "growth, ablation, pictures (repeatable; default all)")
    parser.add_argument("--methods", default=",".join(METHODS))
    parser.add_argument("--no-docs", action="store_true")
    parser.add_argument("--no-peers", action="store_true",
                        help="parsing and the open set without their peers (a quick check)")
    args = parser.parse_args(argv)
    _PEERS[0] = not args.no_peers
    require("praxicon")
    methods = {k: METHODS[k] for k in args.methods.split(",")}
    want = (lambda p: args.only is None or p in args.only)
    results = defaultdict(lambda: defaultdict(float, truth=[], pred=[], f1=[]))
    rows, lines = [], []

    def say(line):
        print(line, flush=True)
        lines.append(line)

    d1 = d2 = None
    peer_cache = {}  # the peers' DTW distances, once per dataset
    if want("d2-in-style") or want("d2-loso") or want("open-set") or want("open-d2") or \
            want("ablation"):
        d2 = read_bandai(MOCAP / "bandai-namco-2-subset")
    if want("d1-loso") or want("open-set") or want("open-d1") or want("joined-parse") or want("growth") or \
            want("pictures") or want("ablation"):
        d1 = read_bandai(MOCAP / "bandai-namco-1")
    if want("d1-loso"):
        for style in sorted({t.style for t in d1}):
            run_split(results, "d1-loso", [t for t in d1 if t.style != style],
                      [t for t in d1 if t.style == style], methods)
        rows += summarise(results, "d1-loso", methods)
    if want("d2-in-style"):
        run_split(results, "d2-in-style", [t for t in d2 if t.take <= 3],
                  [t for t in d2 if t.take > 3], methods)
        rows += summarise(results, "d2-in-style", methods)
    if want("d2-loso"):
        for style in sorted({t.style for t in d2}):
            run_split(results, "d2-loso", [t for t in d2 if t.style != style],
                      [t for t in d2 if t.style == style], methods)
        rows += summarise(results, "d2-loso", methods)
    for row in rows:
        best_peer = max((r["accuracy"] for r in rows if r["protocol"] == row["protocol"]
                         and r["method"] not in ("praxicon",)), default=float("nan"))
        dtw = next((r["cpu_ms_per_take"] for r in rows if r["protocol"] == row["protocol"]
                    and r["method"] == "dtw-1nn"), float("nan"))
        row["vs_best_peer"] = row["accuracy"] - best_peer
        row["cpu_vs_dtw"] = row["cpu_ms_per_take"] / dtw
        worst = sorted(row["recall"].items(), key=lambda kv: kv[1])[:3]
        say(f"{row['protocol']:12s} {row['method']:15s} n={row['takes']:4d} "
            f"acc={row['accuracy']:.3f} (best peer {best_peer:.3f}) min-recall="
            f"{row['min_recall']:.2f} cpu={row['cpu_ms_per_take']:.2f} ms/take "
            f"(x{row['cpu_vs_dtw']:.2f} DTW)  worst: "
            + ", ".join(f"{c} {v:.2f}" for c, v in worst))
    if want("open-set") or want("open-d2"):
        contents = sorted({t.content for t in d2})
        for content in contents:
            for protocol, by_style in (("open-d2-in-style", False),
                                       ("open-d2-in-style-per-style", True)):
                open_split(results, protocol, d2, [t for t in d2 if t.take <= 3],
                           [t for t in d2 if t.take > 3], content, peer_cache,
                           by_style=by_style)
        # across styles: the subset has four contents, so every one is left out with every
        # style in turn (dataset 1's seventeen are taken one a style)
        for style in sorted({t.style for t in d2}):
            for content in contents:
                open_split(results, "open-d2-loso", d2, [t for t in d2 if t.style != style],
                           [t for t in d2 if t.style == style], content, peer_cache)
    if want("open-set") or want("open-d1"):
        many = sorted(c for c in {t.content for t in d1} if sum(t.content == c for t in d1) >= 10)
        for i, style in enumerate(sorted({t.style for t in d1})):
            open_split(results, "open-d1-loso", d1, [t for t in d1 if t.style != style],
                       [t for t in d1 if t.style == style], many[i % len(many)], peer_cache)
        # in style on dataset 1: only walk has two takes of each style, so its second takes are
        # the known ones (their first takes learnt); every other content is left out in turn
        # with all its styles, each of them learnt from the other contents
        for content in many:
            if content != "walk":
                open_split(results, "open-d1-in-style", d1, [t for t in d1 if t.take == 1],
                           [t for t in d1 if t.content == content
                            or (t.take == 2 and t.content == "walk")], content, peer_cache)
    if want("open-set") or want("open-d1") or want("open-d2"):
        rules = ([f"whole x{m:g}" for m in _MARGINS] + [f"groups a={v:g}" for v in _LEVELS]
                 + ["every group a=0.01"]
                 + [f"groups+pair q={q:g}" for q in _PAIR_QUANTILES]
                 + [f"{peer} q={q:g}" for peer in ("dtw-1nn", "minirocket")
                    for q in _PEER_QUANTILES])
        for protocol in ("open-d2-in-style", "open-d2-in-style-per-style", "open-d2-loso",
                         "open-d1-in-style", "open-d1-loso"):
            for method in rules:
                r = results[protocol, method]
                if not r["unknown"]:
                    continue
                row = {"protocol": protocol, "method": method, "takes": int(r["unknown"]),
                       "none_of_these": r["rejected"] / r["unknown"],
                       "closed_accuracy": r["known_right"] / r["known"]}
                rows.append(row)
                say(f"{protocol:16s} {method:18s} left-out takes={row['takes']} none-of-these="
                    f"{row['none_of_these']:.3f}  known takes={int(r['known'])} accuracy with "
                    f"rejection={row['closed_accuracy']:.3f}")
            if results[protocol, "detail"].get("left-out"):
                say(_open_detail(protocol, results))
            bound = protocol.replace("open-", "open-bound-", 1)
            for method in ("praxicon", "dtw-1nn", "minirocket"):
                taken = results[bound, method].get("takes")
                if not taken:
                    continue
                # the left-out content's recall stands where a rule's none-of-these would
                recall, known, favoured = _bound_row(taken)
                left = sum(mine for _, mine, _ in taken)
                row = {"protocol": bound, "method": method, "takes": int(left),
                       "none_of_these": recall, "closed_accuracy": known,
                       "known_at_recall_0.9": favoured}
                rows.append(row)
                say(f"{bound:16s} {method:10s} C-recall={recall:.3f} known={known:.3f}  "
                    f"(answers={len(taken)}, left-out {left}); "
                    f"biased to C-recall 0.9: known={favoured:.3f}")
    for protocol, run in (("cmu-parse", lambda: parse_cmu(results)),
                          ("joined-parse", lambda: parse_joined(results, d1))):
        if not want(protocol):
            continue
        run()
        variants = ([f"praxicon own={name}" for name, _ in _OWN_VARIANTS]
                    if protocol == "joined-parse" else [])
        for method in ("praxicon", *variants, "minirocket-windows"):
            r = results[protocol, method]
            if protocol == "cmu-parse":
                row = {"protocol": protocol, "method": method,
                       "frame_accuracy": r["right"] / r["frames"],
                       "segment_f1": float(np.mean(r["f1"])),
                       "cpu_ms_per_second": 1000 * r["cpu"] / r["seconds"]}
                say(f"{protocol:12s} {method:19s} frame accuracy={row['frame_accuracy']:.3f} "
                    f"segment F1={row['segment_f1']:.3f} cpu={row['cpu_ms_per_second']:.2f} "
                    f"ms per second of motion")
            else:
                row = {"protocol": protocol, "method": method,
                       "recordings": int(r["recordings"]),
                       "time_precision": r["inside"] / max(1, r["claimed"]),
                       "time_recall": r["covered"] / r["true"],
                       "absent_reported": r["absent_reported"] / r["absent_pairs"],
                       "recordings_with_absent": r["any_absent"] / r["recordings"]}
                say(f"{protocol:12s} {method:24s} recordings={row['recordings']} time precision="
                    f"{row['time_precision']:.3f} recall={row['time_recall']:.3f} absent action "
                    f"reported={row['absent_reported']:.3f} (recordings with one: "
                    f"{row['recordings_with_absent']:.2f})")
            rows.append(row)
    if want("ablation"):
        rows += ablation(say, d1, d2)
    if want("pictures"):
        pictures(d1, say)
    if want("growth"):
        for g in cost_growth(d1):
            say(f"growth  actions={g['actions']:2d} train takes={g['train_takes']:3d} "
                f"praxicon {g['praxicon']:.2f} ms/take, DTW 1-NN {g['dtw-1nn']:.2f} ms/take "
                f"(ratio {g['praxicon'] / g['dtw-1nn']:.2f})")
            rows.append({"protocol": "growth", "method": "praxicon/dtw-1nn", **g})
    if not args.no_docs:
        header = ["protocol", "method", "takes", "accuracy", "min_recall", "vs_best_peer",
                  "cpu_ms_per_take", "cpu_vs_dtw", "none_of_these", "closed_accuracy",
                  "frame_accuracy", "segment_f1", "recordings", "time_precision",
                  "time_recall", "absent_reported", "recordings_with_absent", "actions",
                  "train_takes", "praxicon", "dtw-1nn", "d2-in-style", "d2-loso", "d1-loso",
                  "known_at_recall_0.9"]
        write_csv(DATA / "recognition.csv", header,
                  [[_fmt(r.get(h, "")) if not isinstance(r.get(h, ""), float)
                    else f"{r[h]:.4f}" for h in header] for r in rows])
        from _common import replace_section
        replace_section(DOCS / "praxicon.md", "recognition",
                        "Measured by `flock /tmp/heavy.lock python benchmarks/recognition.py` "
                        "(one run, every method on the same split and channels):\n\n```text\n"
                        + "\n".join(lines) + "\n```")
    return 0


if __name__ == "__main__":
    sys.exit(main())
