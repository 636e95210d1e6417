"""The spread every action shares and the "none of these" calibration, fitted from feature
tables: the per-feature scale, the shared directions of variation and what is left per
feature (:func:`fit_spread`), and the threshold, temperature and feature-group limits read
from held-out training takes (:func:`calibrate`, its folds keeping a style's takes together
by :func:`held_together`). :mod:`praxicon.description` turns what these return into
:class:`~praxicon.description.Descriptions`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from ._arguments import DescriptionError
from .feature_groups import feature_groups, group_distances
from .scoring import (_NOISE_FLOOR, _PRIOR_TAKES, _action_variances, _part, _score_model,
                      model_scores, own_columns, probabilities)

__all__ = ["fit_spread", "calibrate", "fit_likelihood", "group_limits", "held_together",
           "scale_floors", "GROUP_LEVEL"]

_RANK = 16  # shared directions of variation kept (fewer when there are fewer takes)
_MARGIN = 1.5  # the "none of these" threshold: this times the worst held-out training take
_FOLDS = 5  # held-out folds of the calibration
#: How often a known take may fail the feature-group test (over all groups together).
GROUP_LEVEL = 0.01


def scale_floors(features) -> np.ndarray:
    """The smallest scale of each feature: a degree (or a degree per second, a length unit per
    second) for angles and rates, 10 % for the log ranges and energies, 5 % of the tempo, 1
    for the flight's log share and the pace's log.

    A joint that never moves in training has a near-zero spread; divided by it, a tenth of a
    degree in a new take would count as a thousand standard deviations.
    """
    # the flight's log share spans about 1.8 from never to half the time off the ground (2.4
    # to always): a floor of 1 makes it tell flying from not flying, not how much (0.25,
    # tried, let four more runs of a style not learnt pass as walks when run was not learnt:
    # docs/praxicon.md)
    # the pace's log spans about 4 from standing (-3) to a dash (1.6): a floor of 1 makes it
    # tell travelling from standing and a walk's pace from a dash's, not a style's from another
    floors = {"spread": 0.1, "energy": 0.1, "tempo": 0.05, "flight": 1.0, "pace": 1.0}
    return np.array([floors.get(f.rsplit(":", 1)[-1].rstrip("0123456789"), 1.0)
                     for f in features])


def _blocks(has: np.ndarray):
    """Features grouped by which actions have them (``has``: actions x features):
    ``(columns, actions)`` per group, one group when every action has every feature."""
    same: dict[bytes, list[int]] = {}
    for c in range(has.shape[1]):
        same.setdefault(has[:, c].tobytes(), []).append(c)
    return [(np.array(c), np.flatnonzero(has[:, c[0]])) for c in same.values()]


def _singular(a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The singular values of ``a`` and its right singular vectors (rows), largest first.

    LAPACK's divide-and-conquer SVD, which numpy calls, can fail to converge on a finite
    matrix (a praxicon's residuals of 139 takes x 557 features did, with OpenBLAS 0.3.30); the
    same routine on the transpose, and failing that the eigenvectors of the smaller Gram
    matrix, give the same values and vectors (up to each vector's sign, which the factors'
    outer products do not see). Through the Gram matrix a value is exact only to about
    ``sqrt(eps)`` times the largest, and the vector of a zero value is a row of zeros: the
    factors read only the leading values and the rest only as a sum of squares, which both
    keep.

    Examples
    --------
    >>> s, vt = _singular(np.array([[3.0, 0.0], [0.0, 4.0]]))
    >>> s.tolist(), np.abs(vt).tolist()
    ([4.0, 3.0], [[0.0, 1.0], [1.0, 0.0]])
    """
    try:
        return np.linalg.svd(a, full_matrices=False)[1:]
    except np.linalg.LinAlgError:
        pass
    try:
        u, singular, _ = np.linalg.svd(a.T, full_matrices=False)
        return singular, u.T
    except np.linalg.LinAlgError:
        pass
    # a^T a's eigenvectors are the right singular vectors; through a a^T when a is wide
    wide = a.shape[0] < a.shape[1]
    eigen, vectors = np.linalg.eigh(a @ a.T if wide else a.T @ a)
    order = np.argsort(eigen)[::-1][:min(a.shape)]
    singular = np.sqrt(np.maximum(eigen[order], 0.0))
    if not wide:
        return singular, vectors[:, order].T
    safe = np.where(singular > 0, singular, 1.0)
    return singular, (vectors[:, order].T @ a) / safe[:, None]


def fit_spread(groups: list[np.ndarray], rank: int, floors=None):
    """Scale, means, shared factors and noise of takes-x-features ``groups``, one per action
    (NaN columns: features the action lacks, learnt from another skeleton).

    A feature's scale and variance come from the actions that have it; the residuals of the
    others are 0, so no direction of variation links features no take has together, and each
    feature's column is weighed by its own degrees of freedom.
    """
    has = np.array([~np.isnan(g).any(axis=0) for g in groups])
    scale = np.ones(groups[0].shape[1])  # a feature no action has is never read
    for columns, actions in _blocks(has):
        if len(actions) == len(groups) and len(columns) == len(scale):
            scale = np.concatenate(groups).std(axis=0)
        elif len(actions):
            scale[columns] = np.concatenate([groups[a][:, columns] for a in actions]).std(axis=0)
    scale = np.maximum(scale, 1e-9 if floors is None else floors)
    means = np.array([g.mean(axis=0) for g in groups])
    residuals = np.concatenate([np.where(h, (g - m) / scale, 0.0)
                                for g, m, h in zip(groups, means, has)])
    dof = max(1, sum(len(g) - 1 for g in groups))
    per = np.maximum(1, ((np.array([len(g) for g in groups])[:, None] - 1) * has).sum(axis=0))
    variance = (residuals ** 2).sum(axis=0) / per
    r = max(0, min(rank, dof - 1, residuals.shape[1] - 1))
    singular, vt = _singular(residuals / np.sqrt(per))
    eigen = singular ** 2
    rest = float(eigen[r:].sum() / max(1, residuals.shape[1] - r))
    factors = vt[:r] * np.sqrt(np.maximum(eigen[:r] - rest, 0.0))[:, None]
    noise = np.maximum(variance - (factors ** 2).sum(axis=0), max(_NOISE_FLOOR, rest))
    # a variance read from few takes is mostly luck: shrink each feature's towards the mean
    # over features, as if _PRIOR_TAKES more takes had shown the typical spread
    typical = noise[has.any(axis=0)].mean()  # over the features some action has
    noise = (per * noise + _PRIOR_TAKES * typical) / (per + _PRIOR_TAKES)
    return scale, means, factors, noise


def group_limits(held: np.ndarray, level: float, sizes) -> np.ndarray:
    """Per feature group (columns of ``held``: held-out takes x groups; ``sizes``: features
    per group) the distance a known
    take exceeds in any group with probability ``level`` (Bonferroni over the groups).

    Held-out distances are heavy-tailed (a style that stoops moves the spine a lot), so no
    chi-squared law fits them; the tail above the median is taken as exponential, its scale
    the mean excess over the median, which a few dozen takes estimate steadily where their
    largest value would not (the largest of n takes is exceeded by a new one with
    probability 1/(n+1) per group).
    """
    tested = ~np.isnan(held)  # NaN: a take whose action lacks the group (another skeleton)
    # Bonferroni over the groups a take is tested on: per group, those of the takes that have it
    count = np.where(tested, tested.sum(axis=1, keepdims=True), 0).max(axis=0)
    columns = [h[t] for h, t in zip(held.T, tested.T)]
    median = np.array([np.median(h) if len(h) else np.nan for h in columns])
    excess = np.array([float((h[h > m] - m).mean()) if np.any(h > m) else 0.0
                       for h, m in zip(columns, median)])
    factor = np.array([math.log(max(1.0, 0.5 * c / level)) for c in count])
    limit = median + excess * factor
    # never under one of the action's own standard deviations per feature: held-out takes that
    # all agree exactly (a tempo every training take shares) would otherwise allow nothing
    return np.maximum(limit, sizes)  # NaN (no held-out take has the group): no limit


def calibrate(groups: list[np.ndarray], rank: int, sources=None, floors=None,
              folds: int = _FOLDS, *, features, level: float = GROUP_LEVEL,
              tailed: bool = False):
    """Threshold, temperature, group limits and tail from held-out training takes
    (``folds``-fold).

    Every take is scored by a model learnt without it (its action's mean *and* the shared
    spread), as an unseen take would be, over its action's features (:func:`model_scores`, as
    recognition scores a motion); an action with a single take cannot be held out.
    The threshold is ``_MARGIN`` times the largest distance per feature such a take got; the
    group limits from each group's held-out distances to its own action, in
    that action's own spread (:func:`group_limits`); the temperature and the tail the ones
    whose probabilities, from the score actions are ranked by (:func:`scores`), fit the
    held-out takes best (:func:`fit_likelihood`; with ``tailed`` false the tail is infinite:
    Gaussian likelihoods).
    ``sources`` (per action, per row: a fold key, a whole number from 0; a row is held out in
    fold ``key % folds``) keeps rows of one key in one fold: the windows of one take, so that
    a take is never scored by a model that saw another piece of it, or the takes of one
    style, numbered alike across actions, so that a fold holds a style out of every action.
    """
    if sources is None:
        sources = [np.arange(len(g)) for g in groups]
    else:
        sources = [np.asarray(s, dtype=int) for s in sources]
    moved, ranked, truth, grouped, compared = [], [], [], [], []
    features = tuple(features)
    parts_of = feature_groups(features)
    has = [~np.isnan(g).any(axis=0) for g in groups]
    for fold in range(folds):
        out = [s % folds == fold for s in sources]
        train = [g[~o] for g, o in zip(groups, out)]
        if any(len(t) == 0 for t in train):
            keep = [a for a, t in enumerate(train) if len(t)]
        else:
            keep = list(range(len(groups)))
        if len(keep) < 1:
            continue
        scale, means, factors, noise = fit_spread([train[a] for a in keep], rank, floors)
        variance = _action_variances(
            np.array([(((train[a] - m) / scale) ** 2).sum(axis=0)
                      for a, m in zip(keep, means)]), [len(train[a]) for a in keep])
        models: dict[bytes, tuple] = {}  # one per set of features (a skeleton's actions)
        for k, a in enumerate(keep):
            held = groups[a][out[a]]
            if not len(held):
                continue
            if parts_of:
                grouped.append(group_distances(held, means[k], variance[k], scale, parts_of))
            key = has[a].tobytes()
            if key not in models:
                columns = np.flatnonzero(has[a])
                models[key] = (columns, _score_model(columns, features, scale, noise, factors,
                                                     means, variance),
                               own_columns([features[c] for c in columns]))
            columns, model, own = models[key]
            # ranked as recognition ranks: own-spread terms added
            shared, score = model_scores(model, _part(held, None, columns), own)
            # rows must share one set of actions: pad the actions left out with +inf
            pad = np.full((len(held), len(groups) - len(keep)), np.inf)
            moved.extend(np.concatenate([shared, pad], axis=1))
            ranked.extend(np.concatenate([score, pad], axis=1))
            truth.extend([k] * len(held))
            compared.extend([len(columns)] * len(held))
    if not moved:
        return math.inf, 1.0, (), math.inf
    limits = (group_limits(np.concatenate(grouped), level,
                           np.array([len(c) for c in parts_of.values()], dtype=float))
              if grouped else ())
    limits = tuple((g, float(v)) for g, v in zip(parts_of, limits) if not math.isnan(v))
    dist = np.array(moved)
    nearest = dist[np.arange(len(truth)), truth] / np.array(compared)
    threshold = float(nearest.max() * _MARGIN)
    temperature, tail = fit_likelihood(np.array(ranked), np.array(truth), tailed)
    return threshold, temperature, limits, tail


def fit_likelihood(score: np.ndarray, truth: np.ndarray, tailed: bool) -> tuple[float, float]:
    """``(temperature, tail)`` of the :func:`~praxicon.scoring.log_likelihoods` whose
    probabilities give held-out takes' own actions the most (their mean log-probability).

    Gaussian first: a temperature among the powers of 2 from 1 to 2048, the tail infinite.
    With ``tailed``, heavy tails too, kept only where they fit better: tails from 1/64 to 128
    times the held-out takes' median score to their own action, each with the slopes
    ``tail / (2 temperature)`` from 1/4 to 724 (powers of the square root of 2). Held-out
    takes are farther from a model learnt without them than a new take is from the model
    learnt with every take, so Gaussian probabilities fitted on them come out too soft for new
    takes of the data learnt (an answer's probability 0.60 on average where 0.90 of the
    answers are right, dataset 1 with a style left out); the heavy tail fits a distance's
    scale once and holds for distances a few times larger or smaller.

    Examples
    --------
    >>> score = np.array([[1.0, 9.0], [4.0, 1.0], [2.0, 30.0]])
    >>> fit_likelihood(score, np.array([0, 1, 0]), False)
    (1.0, inf)
    """
    rows = np.arange(len(truth))

    def loss(temperature: float, tail: float) -> float:
        p = probabilities(score, temperature, tail)[rows, truth]
        return float(-np.log(np.maximum(p, 1e-300)).mean())

    best, best_tail, best_loss = 1.0, math.inf, math.inf
    for temperature in 2.0 ** np.arange(0, 12):
        value = loss(float(temperature), math.inf)
        if value < best_loss - 1e-12:
            best, best_loss = float(temperature), value
    own = score[rows, truth]
    own = own[np.isfinite(own) & (own > 0)]
    if not tailed or not len(own):
        return best, best_tail
    unit = float(np.median(own))
    for tail in unit * 2.0 ** np.arange(-6, 8):
        for slope in 2.0 ** np.arange(-2, 10, 0.5):
            value = loss(float(tail / (2 * slope)), float(tail))
            if value < best_loss - 1e-12:
                best, best_tail, best_loss = float(tail / (2 * slope)), float(tail), value
    return best, best_tail


def held_together(groups: Mapping[str, Sequence]) -> dict[str, np.ndarray]:
    """Each take's calibration fold key, so that a group's takes are held out together.

    Parameters
    ----------
    groups : mapping of str to sequence
        Per action, each take's group (hashable, compared by equality), as
        :func:`~praxicon.description.describe` takes them.

    Returns
    -------
    dict of str to numpy.ndarray
        Per action, per take, its group's number, the groups numbered as they first appear
        over every action (so that fold ``k`` holds one style out of every action, as the
        choice of features holds it); an action whose takes are all of one group has nothing
        to hold out together, and its takes are numbered one by one; an action whose groups
        would all fall in one of the ``_FOLDS`` folds has its groups numbered as its own.

    Raises
    ------
    DescriptionError
        When a group is not hashable.

    Examples
    --------
    >>> keys = held_together({"a": ["x", "y", "x"], "b": ["y", "z"], "c": ["w", "w"]})
    >>> {k: v.tolist() for k, v in keys.items()}
    {'a': [0, 1, 0], 'b': [1, 2], 'c': [0, 1]}
    """
    number: dict = {}
    out = {}
    for name, per in groups.items():
        try:
            keys = np.array([number.setdefault(g, len(number)) for g in per], dtype=int)
            own = {g: k for k, g in enumerate(dict.fromkeys(per))}
        except TypeError:
            raise DescriptionError(f"action {name!r}: a group of its takes is not hashable "
                                   f"(groups are compared by equality)") from None
        if len(own) < 2:
            out[name] = np.arange(len(per))
        elif len(set((keys % _FOLDS).tolist())) < 2:
            # its groups all fall in one fold among every action's: numbered as its own, or
            # none of its takes would be scored
            out[name] = np.array([own[g] for g in per], dtype=int)
        else:
            out[name] = keys
    return out
