"""The recognition benchmark's open set: one content left out of the learning, its takes
to be answered "none of these" while the known takes stay right.

Per split (:func:`open_split`): the praxicon's rules (the whole-vector threshold, the
feature-group test at several levels, every group read, a pairwise test on top), the peers'
rejection as an analyst would calibrate it on held-out known takes (DTW 1-NN's nearest
distance, MiniRocket's top score), the oracle (the praxicon's group statistics at the best
threshold chosen on the split's test takes themselves: what no calibration of them can beat)
and the bound: the same split classified by every method
with the left-out content learnt too. :func:`run_open_sets` runs the protocols'
splits and :func:`report_open_sets` prints their rows; ``recognition.py`` calls both, and
running this file prints the open-set rows alone (as ``recognition.py --only open-set
--no-docs`` does)::

    flock /tmp/heavy.lock python benchmarks/recognition_open.py [--only open-d1] [--no-peers]
"""

from __future__ import annotations

import argparse
import sys
from collections import defaultdict

# first: one thread per method and the praxicon package from the repository (see there)
from recognition_methods import _resampled, read_bandai, series  # isort: skip

import numpy as np  # noqa: E402

from _common import MOCAP, require  # noqa: E402

# -- the praxicon's rules ----------------------------------------------------------------------
_MARGINS = (1.0, 1.5, 2.0)  # the whole-vector threshold: x the worst held-out training take
_LEVELS = (0.1, 0.01, 0.001, 0.0001)  # the feature-group test: how often a known take fails it


def _grouped(takes, by_style: bool):
    """Per action (a content, or with ``by_style`` a content and a style) its takes' motions
    and their styles, what the praxicon learns from and holds out by."""
    groups, styles = defaultdict(list), defaultdict(list)
    for t in takes:
        name = f"{t.content}|{t.style}" if by_style else t.content
        groups[name].append(t.motion)
        styles[name].append(t.style)
    return groups, styles


def open_set(results, protocol, train, test, *, by_style: bool = False):
    """One content left out of the learning: its test takes should come back None.

    Counted for the whole-vector threshold alone (``_MARGINS`` times the worst left-out
    training take; 1.5 is the praxicon's) and for it with the feature-group test at each of
    ``_LEVELS`` (0.01 is the praxicon's), so the trade-off between rejecting the unknown and
    keeping the known is printed, not one chosen point. Features are computed once per split.
    With ``by_style`` one action is learnt per content and style (as ``psgs praxicon build``
    groups a dataset with several takes of each pair) and the answer's content counted.
    """
    from praxicon.calibration import _MARGIN, held_together
    from praxicon.description import (GROUP_LEVEL, chosen_table, common_table,
                                      describe_table, feature_rows, score_model, scores)
    from praxicon.recognition import _excess, feature_matrix

    groups, styles = _grouped(train, by_style)
    rows = {c: feature_rows(m) for c, m in groups.items()}
    order, table = common_table(rows)
    # the kinds of features chosen as describe chooses them, each style held out together
    order, table = chosen_table(table, order, groups=styles)
    known = {t.content for t in train}
    x = None
    for level in _LEVELS:
        # calibrated as describe calibrates: each style's takes held out together
        d = describe_table(table, order, level=level, sources=held_together(styles))
        if x is None:
            columns, x, _ = feature_matrix(d, [t.motion for t in test])
            features = [d.spread.features[i] for i in columns]
        fitted = score_model(d, columns)
        dist, score = scores(d, x, columns, fitted=fitted)
        best = score.argmin(axis=1)
        penalty = dist[np.arange(len(x)), best] / len(columns)
        excess, _, _ = _excess(d, features, x, best, fitted)
        rules = {f"groups a={level:g}": (penalty <= d.spread.threshold) & (excess <= 1.0)}
        if by_style:
            # the praxicon's rule: a content's styles, a family, decide none of these for
            # their members (describe's families); each style's own test beside it
            rules[f"own style a={level:g}"] = rules[f"groups a={level:g}"]
            rules[f"groups a={level:g}"] = _family_accepts(d, rows, test, best, level,
                                                           rules[f"own style a={level:g}"])
        if level == GROUP_LEVEL:  # every group read, not only those that tell actions apart
            every, _, _ = _excess(d, features, x, best, fitted, telling=False)
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
        if level == GROUP_LEVEL and not by_style:
            # the group statistics per take, for the best threshold chosen on the test takes
            # themselves (``_oracle_row``): what no calibration of these statistics can beat
            whole = penalty <= d.spread.threshold
            for name, stat in (("groups", excess), ("every group", every)):
                results[protocol, "oracle"].setdefault(name, []).extend(
                    (float(v) if w else np.inf, t.content not in known, d.names[b] == t.content)
                    for v, w, t, b in zip(stat, whole, test, best))
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


def _family_accepts(d, rows, test, best, level, own) -> np.ndarray:
    """Per test take: accepted by the family (the content) of its best action, as
    :func:`praxicon.recognition.recognise_many` decides for a praxicon built per style
    (``own``: each action's own verdict, kept for an action alone in its family)."""
    from dataclasses import replace

    from praxicon.description import family_descriptions, feature_rows
    from praxicon.recognition import family_verdicts

    families, of = family_descriptions(rows, {n: n.split("|")[0] for n in rows}, level=level)
    if families is None:
        return own
    d = replace(d, families=families, family_of=tuple(of[n] for n in d.names))
    verdicts = family_verdicts(d, feature_rows([t.motion for t in test]),
                               [d.names[b] for b in best])
    return np.array([verdicts[i].accepted if i in verdicts else bool(own[i])
                     for i in range(len(test))])


_PAIR_QUANTILES = (0.9, 0.99)  # the pairwise test: share of held-out known takes it keeps


def _towards(fitted, dist, best, other) -> np.ndarray:
    """Per take, how many shared standard deviations it lies from its best action's mean
    towards ``other``'s along the line between the two means: from the shared squared
    distances alone, ``(d_best - d_other + D²) / 2D`` with ``D`` the means' distance."""
    from praxicon.scoring import distances

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


def open_bound(results, protocol, takes, train, taught, test, cache, *, by_style=False,
               peers=True):
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
        groups, styles = _grouped(learn, by_style)
        d = describe(groups, groups=styles)
        columns, x, _ = feature_matrix(d, [t.motion for t in ask])
        # every method's scores, higher better, with the content each column answers
        found = {"praxicon": (-scores(d, x, columns)[1], [n.split("|")[0] for n in d.names])}
        if peers and not by_style:
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


def open_split(results, protocol, takes, pool, test, content, cache, *, by_style=False,
               peers=True):
    """One open-set split: ``content`` left out of ``pool`` (the split's learning takes); the
    praxicon's rules, the peers' (not for ``by_style``; ``peers=False``: none) and the bound
    on ``test``."""
    train = [t for t in pool if t.content != content]
    open_set(results, protocol, train, test, by_style=by_style)
    if peers and not by_style:
        peer_open_set(results, protocol, takes, train, test, cache)
    open_bound(results, protocol, takes, train, [t for t in pool if t.content == content],
               test, cache, by_style=by_style, peers=peers)


def run_open_sets(results, d1, d2, want, cache, *, peers=True) -> None:
    """Every open-set split of the protocols ``want`` asks for (``open-set``, or one dataset's
    part: ``open-d1``, ``open-d2``), tallied into ``results``; ``cache`` keeps the peers' DTW
    distances once per dataset."""
    if want("open-set") or want("open-d2"):
        contents = sorted({t.content for t in d2})
        for content in contents:
            for protocol, by_style in (("open-d2-in-style", False),
                                       ("open-d2-in-style-per-style", True)):
                open_split(results, protocol, d2, [t for t in d2 if t.take <= 3],
                           [t for t in d2 if t.take > 3], content, cache,
                           by_style=by_style, peers=peers)
        # across styles: the subset has four contents, so every one is left out with every
        # style in turn (dataset 1's seventeen are taken one a style)
        for style in sorted({t.style for t in d2}):
            for content in contents:
                open_split(results, "open-d2-loso", d2, [t for t in d2 if t.style != style],
                           [t for t in d2 if t.style == style], content, cache,
                           peers=peers)
    if want("open-set") or want("open-d1"):
        many = sorted(c for c in {t.content for t in d1} if sum(t.content == c for t in d1) >= 10)
        for i, style in enumerate(sorted({t.style for t in d1})):
            open_split(results, "open-d1-loso", d1, [t for t in d1 if t.style != style],
                       [t for t in d1 if t.style == style], many[i % len(many)], cache,
                       peers=peers)
        # in style on dataset 1: only walk has two takes of each style, so its second takes are
        # the known ones (their first takes learnt); every other content is left out in turn
        # with all its styles, each of them learnt from the other contents
        for content in many:
            if content != "walk":
                open_split(results, "open-d1-in-style", d1, [t for t in d1 if t.take == 1],
                           [t for t in d1 if t.content == content
                            or (t.take == 2 and t.content == "walk")], content, cache,
                           peers=peers)


def report_open_sets(results, say) -> list[dict]:
    """The open-set rows, one line each through ``say`` (per protocol: every rule, the
    praxicon's answers per left-out content, the bound), and their CSV rows."""
    from praxicon.calibration import GROUP_LEVEL

    rows = []
    rules = ([f"whole x{m:g}" for m in _MARGINS] + [f"groups a={v:g}" for v in _LEVELS]
             + [f"own style a={v:g}" for v in _LEVELS] + ["every group a=0.01"]
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
        for statistic in ("groups", "every group"):
            taken = results[protocol, "oracle"].get(statistic)
            if not taken:
                continue
            kept = results[protocol, f"groups a={GROUP_LEVEL:g}"]
            reached, known_at = _oracle_row(taken, kept["known_right"] / kept["known"])
            oracle = protocol.replace("open-", "open-oracle-", 1)
            rows.append({"protocol": oracle, "method": statistic, "takes": int(kept["unknown"]),
                         "none_of_these": reached,
                         "closed_accuracy": kept["known_right"] / kept["known"],
                         "known_at_recall_0.9": known_at})  # (the bound's column: the same)
            say(f"{oracle:16s} {statistic:11s} best threshold on the test takes: "
                f"none-of-these={reached:.3f} at the rule's known accuracy "
                f"{kept['known_right'] / kept['known']:.3f}; none-of-these 0.9 keeps known "
                f"{known_at:.3f}")
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
    return rows


def _oracle_row(taken, known_floor: float, rejected: float = 0.9) -> tuple[float, float]:
    """Over every threshold on a statistic (``taken``: per test take its value, inf where the
    whole-vector threshold rejects it; whether it is of the left-out content; whether its best
    action is right): the largest share of left-out takes rejected (value over the threshold)
    while the known takes' accuracy stays at least ``known_floor``, and the largest known
    accuracy while at least ``rejected`` of the left-out takes are rejected.

    >>> taken = [(0.5, False, True), (2.0, False, True), (1.0, True, False), (3.0, True, False)]
    >>> _oracle_row(taken, 1.0)  # both known takes kept: 3.0 alone rejected
    (0.5, 0.5)
    >>> _oracle_row(taken, 0.5)
    (1.0, 0.5)
    """
    value, unknown, right = (np.array(v) for v in zip(*taken))
    best_rejected, best_known = 0.0, 0.0
    for threshold in np.unique(np.concatenate(([-np.inf], value[np.isfinite(value)]))):
        accept = value <= threshold
        known = float((accept & right)[~unknown].mean()) if (~unknown).any() else 1.0
        share = float((~accept)[unknown].mean()) if unknown.any() else 0.0
        if known >= known_floor - 1e-12:
            best_rejected = max(best_rejected, share)
        if share >= rejected - 1e-12:
            best_known = max(best_known, known)
    return best_rejected, best_known


def main(argv=None) -> int:
    """The open-set rows alone, without writing the docs."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", choices=("open-d1", "open-d2"), default=None,
                        help="one dataset's part (default both)")
    parser.add_argument("--no-peers", action="store_true", help="the praxicon alone")
    args = parser.parse_args(argv)
    require("praxicon")
    want = (lambda p: args.only is None and p == "open-set" or p == args.only)  # noqa: E731
    d1 = read_bandai(MOCAP / "bandai-namco-1") if want("open-d1") or want("open-set") else None
    d2 = read_bandai(MOCAP / "bandai-namco-2-subset") if want("open-d2") or want("open-set") \
        else None
    results = defaultdict(lambda: defaultdict(float, truth=[], pred=[], f1=[]))
    run_open_sets(results, d1, d2, want, {}, peers=not args.no_peers)
    report_open_sets(results, lambda line: print(line, flush=True))
    return 0


if __name__ == "__main__":
    sys.exit(main())
