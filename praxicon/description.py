"""What the praxicon keeps per action for recognition, and the spread its actions share.

Every take becomes one feature vector (:func:`praxicon.features.motion_features`). An
:class:`ActionDescription` is the mean of its action's vectors and how much its own copies vary
(per feature); :class:`Spread` is how the copies of *any* action vary around their action's
mean, pooled over every action and style: a per-feature scale, a few correlated directions
(``factors``, the main ways a style changes a performance: faster, bigger, more stooped) and
what is left per feature (``noise``). Together (:class:`Descriptions`) they are a Gaussian per
action with one shared covariance, ``diag(noise) + factorsᵀ factors`` in scaled units, so the
log-likelihoods of all actions are on one scale; their size grows with the number of actions
and features, never with the number of takes (no take is kept).

A motion is "none of these" when even its best action's squared Mahalanobis distance per
feature exceeds ``Spread.threshold``, the largest a training take reached when left out of its
own action's mean, or when one group of its features (a joint; each of the root's drifts and
sways, axis by axis, a whole take's turning read by its excursion; the tempo) is further from
that action than its limit (``Spread.limits``: what a held-out training take exceeds with
probability ``GROUP_LEVEL`` over all groups). The group test measures each action against its
own spread (shrunk towards the shared one): a deviation concentrated in a few features, such
as a walk's missing heading drift against a turn whose drift is tight, drowns in a sum over
all features but stands out in its group. It reads only the groups that tell the action apart
from another learnt action (:func:`~praxicon.feature_groups.telling_groups`). Actions are
ranked by the shared distance plus the root drift's distance in each action's own spread
(:func:`scores`); probabilities are those scores' likelihoods at the ``temperature`` that fits
the left-out training takes best.

>>> from kinetology import synthetic_motion
>>> takes = {"a": [synthetic_motion(3, (0,), seed=s) for s in (1, 2, 3)],
...          "b": [synthetic_motion(3, (2,), seed=s) for s in (4, 5, 6)]}
>>> d = describe(takes)
>>> [a.name for a in d.actions], Descriptions.from_json(d.to_json()) == d
(['a', 'b'], True)
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass

import numpy as np

from psgs.errors import PSGSError

from .feature_groups import feature_groups, group_distances
from .features import FeatureError, motion_features

__all__ = ["FORMAT_VERSION", "ActionDescription", "Spread", "Descriptions", "describe",
           "describe_table", "DescriptionError",
           "GROUP_LEVEL", "OWN_KINDS", "own_columns", "own_terms", "scores", "ScoreModel",
           "score_model"]

#: Bumped when what a description holds or how features are computed changes.
FORMAT_VERSION = 3
_RANK = 16  # shared directions of variation kept (fewer when there are fewer takes)
_NOISE_FLOOR = 0.05  # smallest per-feature variance left, in scaled units
_PRIOR_TAKES = 10.0  # pseudo-takes of typical spread each feature's own spread is shrunk to
_MARGIN = 1.5  # the "none of these" threshold: this times the worst held-out training take
_FOLDS = 5  # held-out folds of the calibration
#: How often a known take may fail the feature-group test (over all groups together).
GROUP_LEVEL = 0.01
#: Kinds of the root's features every action also scores in its own spread (:func:`scores`).
OWN_KINDS = ("drift",)


class DescriptionError(PSGSError, ValueError):
    """Descriptions that cannot be made, read or used (one line, naming what to do)."""


def _floats(values) -> tuple[float, ...]:
    return tuple(float(v) for v in values)


@dataclass(frozen=True)
class ActionDescription:
    """One action: per feature the mean of its takes and their spread (standard deviation).

    ``takes`` counts the takes (or windows) learnt from; ``window`` is the length in seconds of
    the windows learnt from (0: whole takes).
    """

    name: str
    features: tuple[str, ...]
    mean: tuple[float, ...]
    spread: tuple[float, ...]
    takes: int
    window: float = 0.0
    version: int = FORMAT_VERSION

    def to_dict(self) -> dict:
        """Plain JSON values (floats kept exactly: JSON writes them with ``repr``)."""
        return {"format": "praxicon-action-description", "version": self.version,
                "name": self.name, "features": list(self.features), "mean": list(self.mean),
                "spread": list(self.spread), "takes": self.takes, "window": self.window}

    def to_json(self) -> str:
        """JSON text of :meth:`to_dict`."""
        return json.dumps(self.to_dict())

    @classmethod
    def from_dict(cls, data: dict) -> "ActionDescription":
        """The description :meth:`to_dict` wrote (another format or version: a clear error)."""
        _check(data, "praxicon-action-description")
        return cls(str(data["name"]), tuple(data["features"]), _floats(data["mean"]),
                   _floats(data["spread"]), int(data["takes"]), float(data["window"]))

    @classmethod
    def from_json(cls, text: str) -> "ActionDescription":
        """The description :meth:`to_json` wrote.

        Examples
        --------
        >>> d = ActionDescription("wave", ("a.rx:pose",), (0.1,), (2.0 / 3,), 2)
        >>> ActionDescription.from_json(d.to_json()) == d
        True
        """
        return cls.from_dict(_loads(text))


@dataclass(frozen=True)
class Spread:
    """How copies of an action vary around its mean, shared by every action of a praxicon.

    Features are divided by ``scale``; in those units the covariance is
    ``diag(noise) + factorsᵀ factors`` (``factors``: rows of shared directions).
    """

    features: tuple[str, ...]
    scale: tuple[float, ...]
    factors: tuple[tuple[float, ...], ...]
    noise: tuple[float, ...]
    threshold: float
    temperature: float
    window: float = 0.0
    version: int = FORMAT_VERSION
    limits: tuple[tuple[str, float], ...] = ()  # per feature group: its largest distance

    def to_dict(self) -> dict:
        """Plain JSON values (floats kept exactly)."""
        return {"format": "praxicon-spread", "version": self.version,
                "features": list(self.features), "scale": list(self.scale),
                "factors": [list(f) for f in self.factors], "noise": list(self.noise),
                "threshold": self.threshold, "temperature": self.temperature,
                "window": self.window, "limits": [[g, v] for g, v in self.limits]}

    @classmethod
    def from_dict(cls, data: dict) -> "Spread":
        """The spread :meth:`to_dict` wrote."""
        _check(data, "praxicon-spread")
        return cls(tuple(data["features"]), _floats(data["scale"]),
                   tuple(_floats(f) for f in data["factors"]), _floats(data["noise"]),
                   float(data["threshold"]), float(data["temperature"]), float(data["window"]),
                   FORMAT_VERSION,
                   # descriptions written before the group test have none: no group test
                   tuple((str(g), float(v)) for g, v in data.get("limits", [])))


@dataclass(frozen=True)
class Descriptions:
    """Every action's description and their shared spread: what recognition reads."""

    actions: tuple[ActionDescription, ...]
    spread: Spread

    @property
    def names(self) -> tuple[str, ...]:
        """The actions' names, in order."""
        return tuple(a.name for a in self.actions)

    def to_dict(self) -> dict:
        """Plain JSON values (floats kept exactly)."""
        return {"format": "praxicon-descriptions", "version": FORMAT_VERSION,
                "actions": [a.to_dict() for a in self.actions], "spread": self.spread.to_dict()}

    def to_json(self) -> str:
        """JSON text; floats come back exactly from :meth:`from_json`."""
        return json.dumps(self.to_dict())

    @classmethod
    def from_dict(cls, data: dict) -> "Descriptions":
        """The descriptions :meth:`to_dict` wrote (another version: a clear error)."""
        _check(data, "praxicon-descriptions")
        try:
            return cls(tuple(ActionDescription.from_dict(a) for a in data["actions"]),
                       Spread.from_dict(data["spread"]))
        except (KeyError, TypeError, ValueError, OverflowError) as exc:  # Overflow: float(10**400)
            if isinstance(exc, DescriptionError):
                raise
            raise DescriptionError(f"malformed praxicon descriptions ({type(exc).__name__}: "
                                   f"{exc})") from None

    @classmethod
    def from_json(cls, text: str) -> "Descriptions":
        """The descriptions :meth:`to_json` wrote (another version: a clear error)."""
        return cls.from_dict(_loads(text))


def _loads(text: str) -> dict:
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise DescriptionError(f"not JSON (line {exc.lineno}, column {exc.colno}: "
                               f"{exc.msg})") from None
    if not isinstance(data, dict):
        raise DescriptionError("not a praxicon description (a JSON object expected)")
    return data


def _check(data: dict, kind: str) -> None:
    if not isinstance(data, dict):
        raise DescriptionError(f"not a {kind} (a JSON object expected)")
    if data.get("format") != kind:
        raise DescriptionError(f"not a {kind} (format {data.get('format')!r})")
    if data.get("version") != FORMAT_VERSION:
        raise DescriptionError(f"{kind} of version {data.get('version')!r}; this psgs reads "
                               f"version {FORMAT_VERSION}: learn the descriptions again "
                               f"(psgs praxicon build ... -o PX resumes the build and "
                               f"describes its actions)")


# -- the model ---------------------------------------------------------------------------------
def precision_parts(spread: Spread, columns) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(scale, 1/noise, W, M⁻¹)`` pieces of the precision on ``columns`` (Woodbury)."""
    scale = np.asarray(spread.scale)[columns]
    inverse = 1.0 / np.asarray(spread.noise)[columns]
    w = np.asarray(spread.factors, dtype=float).reshape(-1, len(spread.scale))[:, columns]
    inner = np.linalg.inv(np.eye(len(w)) + (w * inverse) @ w.T)
    return scale, inverse, w, inner


def mahalanobis_terms(x: np.ndarray, mean: np.ndarray, parts) -> np.ndarray:
    """Per-feature terms ``d_f (Σ⁻¹ d)_f`` of the squared Mahalanobis distance (rows: motions);
    they sum to the distance, and their sums per joint are the explanation."""
    scale, inverse, w, inner = parts
    d = (np.atleast_2d(x) - mean) / scale
    pd = d * inverse
    b = pd @ w.T
    return d * (pd - ((b @ inner) @ w) * inverse)


def distances(x: np.ndarray, means: np.ndarray, parts) -> np.ndarray:
    """Squared Mahalanobis distance of every row of ``x`` to every mean (motions x actions)."""
    scale, inverse, w, inner = parts
    out = np.empty((len(x), len(means)))
    for a, mean in enumerate(means):
        d = (x - mean) / scale
        b = (d * inverse) @ w.T
        out[:, a] = (d * d * inverse).sum(axis=1) - np.einsum("ni,ij,nj->n", b, inner, b)
    return out


def probabilities(dist: np.ndarray, temperature: float) -> np.ndarray:
    """Posterior probabilities (equal priors) from squared distances at ``temperature``."""
    logits = -0.5 * dist / temperature
    logits -= logits.max(axis=-1, keepdims=True)
    p = np.exp(logits)
    return p / p.sum(axis=-1, keepdims=True)


def own_columns(features, kinds=OWN_KINDS) -> np.ndarray:
    """The columns of the root's features of ``kinds`` (``"drift"``: the mean travel and
    turning velocities; ``"energy"``: the sway around them), scored in each action's own spread.

    Examples
    --------
    >>> own_columns(["a.rx:pose", "Hips.travelz:drift", "Hips.travelz:energy", "tempo"]).tolist()
    [1]
    """
    return np.array([i for i, f in enumerate(features) if (".travel" in f or ".turn" in f)
                     and f.rsplit(":", 1)[-1] in kinds], dtype=int)


def own_terms(x, means, variance, scale) -> np.ndarray:
    """Motions x actions: each action's own-spread term, relative to the best action's.

    Per action the Gaussian log-likelihood of the columns given (``x``: motions x columns,
    ``means`` and ``variance``: actions x columns, the variance in units of ``scale``), as
    ``sum z²/v + log v``, minus the smallest over actions: the action whose own spread fits
    best pays nothing more, so a "none of these" threshold on the shared distance keeps its
    meaning.

    Examples
    --------
    >>> t = own_terms(np.array([[1.0]]), np.array([[1.0], [-1.0]]), np.ones((2, 1)), np.ones(1))
    >>> t.tolist()
    [[0.0, 4.0]]
    """
    x, means = np.atleast_2d(x), np.atleast_2d(means)
    z = ((x[:, None, :] - means[None]) / scale) ** 2 / variance[None]
    terms = (z + np.log(variance)[None]).sum(axis=2)
    return terms - terms.min(axis=1, keepdims=True) if terms.size else terms


@dataclass(frozen=True)
class ScoreModel:
    """What scoring reads on some of the descriptions' columns, computed once per call: the
    actions' means, the shared precision's pieces (:func:`precision_parts`) and each action's
    own variance, in the spread's scaled units (``scale``)."""

    columns: np.ndarray
    means: np.ndarray  # actions x columns
    parts: tuple
    variance: np.ndarray  # actions x columns
    scale: np.ndarray


def score_model(descriptions: "Descriptions", columns) -> ScoreModel:
    """The :class:`ScoreModel` of ``descriptions`` on ``columns``."""
    columns = np.asarray(columns, dtype=int)
    return ScoreModel(columns, np.array([a.mean for a in descriptions.actions])[:, columns],
                      precision_parts(descriptions.spread, columns),
                      action_variances(descriptions, columns),
                      np.asarray(descriptions.spread.scale)[columns])


def scores(descriptions: "Descriptions", x, columns, *, kinds=OWN_KINDS,
           fitted: ScoreModel | None = None):
    """Motions x actions: the shared distance (what the "none of these" threshold reads) and
    the score actions are ranked by, which adds :func:`own_terms` for the root's features of
    ``kinds``. ``fitted``: the :func:`score_model` on ``columns``, when the caller has it.

    The shared spread pools how every action's copies vary; a style that walks faster moves
    the forward travel of every gait alike, so the shared directions let a walk's travel be
    read as a walk backwards' at little cost, and a heading rate drowns among hundreds of
    features. Each action's own spread of its drift (a walk backwards always travels
    backwards, a turn's heading rate is tight) keeps them apart.

    Examples
    --------
    >>> from kinetology import synthetic_motion
    >>> d = describe({"a": [synthetic_motion(2, (0,), seed=s) for s in (1, 2)],
    ...               "b": [synthetic_motion(2, (1,), seed=s) for s in (3, 4)]})
    >>> x = np.array([d.actions[0].mean])
    >>> shared, score = scores(d, x, np.arange(len(d.spread.features)))
    >>> shared.shape, bool(np.all(score >= shared))
    ((1, 2), True)
    """
    columns = np.asarray(columns, dtype=int)
    m = score_model(descriptions, columns) if fitted is None else fitted
    shared = distances(x, m.means, m.parts)
    own = own_columns([descriptions.spread.features[i] for i in columns], kinds)
    if not len(own):
        return shared, shared
    return shared, shared + own_terms(np.asarray(x)[:, own], m.means[:, own],
                                      m.variance[:, own], m.scale[own])


def _action_variances(sums: np.ndarray, counts) -> np.ndarray:
    """Per action and feature the variance of its own copies (scaled units) from the sums of
    squared deviations, shrunk towards the variance pooled over actions as if
    ``_PRIOR_TAKES`` more takes had shown that: a turn's tight drift stays tight, an action
    learnt from two takes borrows the others' spread."""
    counts = np.asarray(counts, dtype=float)[:, None]
    pooled = np.maximum(sums.sum(axis=0) / max(1.0, float((counts - 1).sum())), _NOISE_FLOOR)
    return (sums + _PRIOR_TAKES * pooled) / (counts - 1 + _PRIOR_TAKES)


def action_variances(descriptions: "Descriptions", columns) -> np.ndarray:
    """Actions x ``columns``: each action's own variance per feature, in the spread's scaled
    units (from the stored per-action spreads and take counts)."""
    scale = np.asarray(descriptions.spread.scale)[columns]
    n = np.array([a.takes for a in descriptions.actions], dtype=float)
    spread = np.array([a.spread for a in descriptions.actions]).reshape(len(n), -1)[:, columns]
    return _action_variances((spread / scale) ** 2 * n[:, None], n)


def _scale_floors(features) -> np.ndarray:
    """The smallest scale of each feature: a degree (or a degree per second, a length unit per
    second) for angles and rates, 10 % for the log ranges and energies, 5 % of the tempo.

    A joint that never moves in training has a near-zero spread; divided by it, a tenth of a
    degree in a new take would count as a thousand standard deviations.
    """
    floors = {"spread": 0.1, "energy": 0.1, "tempo": 0.05}
    return np.array([floors.get(f.rsplit(":", 1)[-1].rstrip("0123456789"), 1.0)
                     for f in features])


def _fit_spread(groups: list[np.ndarray], rank: int, floors=None):
    every = np.concatenate(groups)
    scale = every.std(axis=0)
    scale = np.maximum(scale, 1e-9 if floors is None else floors)
    means = np.array([g.mean(axis=0) for g in groups])
    residuals = np.concatenate([(g - m) / scale for g, m in zip(groups, means)])
    dof = max(1, sum(len(g) - 1 for g in groups))
    variance = (residuals ** 2).sum(axis=0) / dof
    r = max(0, min(rank, dof - 1, residuals.shape[1] - 1))
    _, singular, vt = np.linalg.svd(residuals / math.sqrt(dof), full_matrices=False)
    eigen = singular ** 2
    rest = float(eigen[r:].sum() / max(1, residuals.shape[1] - r))
    factors = vt[:r] * np.sqrt(np.maximum(eigen[:r] - rest, 0.0))[:, None]
    noise = np.maximum(variance - (factors ** 2).sum(axis=0), max(_NOISE_FLOOR, rest))
    # a variance read from few takes is mostly luck: shrink each feature's towards the mean
    # over features, as if _PRIOR_TAKES more takes had shown the typical spread
    noise = (dof * noise + _PRIOR_TAKES * noise.mean()) / (dof + _PRIOR_TAKES)
    return scale, means, factors, noise


def _group_limits(held: np.ndarray, level: float, sizes) -> np.ndarray:
    """Per feature group (columns of ``held``: held-out takes x groups; ``sizes``: features
    per group) the distance a known
    take exceeds in any group with probability ``level`` (Bonferroni over the groups).

    Held-out distances are heavy-tailed (a style that stoops moves the spine a lot), so no
    chi-squared law fits them; the tail above the median is taken as exponential, its scale
    the mean excess over the median, which a few dozen takes estimate steadily where their
    largest value would not (the largest of n takes is exceeded by a new one with
    probability 1/(n+1) per group).
    """
    median = np.median(held, axis=0)
    excess = np.array([float((h[h > m] - m).mean()) if np.any(h > m) else 0.0
                       for h, m in zip(held.T, median)])
    limit = median + excess * math.log(max(1.0, 0.5 * held.shape[1] / level))
    # never under one of the action's own standard deviations per feature: held-out takes that
    # all agree exactly (a tempo every training take shares) would otherwise allow nothing
    return np.maximum(limit, sizes)


def _calibrate(groups: list[np.ndarray], rank: int, sources=None, floors=None,
               folds: int = _FOLDS, features=None, level: float = GROUP_LEVEL):
    """Threshold and temperature from held-out training takes (``folds``-fold).

    Every take is scored by a model learnt without it (its action's mean *and* the shared
    spread), as an unseen take would be; an action with a single take cannot be held out.
    The threshold is ``_MARGIN`` times the largest distance per feature such a take got; the
    group limits (with ``features``) from each group's held-out distances to its own action, in
    that action's own spread (:func:`_group_limits`); the temperature the one (a power of 2)
    whose probabilities, from the score actions are ranked by (:func:`scores`), fit the
    held-out takes best.
    ``sources`` (per action, per row: the take a row comes from) keeps the windows of one take
    in one fold, so that a take is never scored by a model that saw another piece of it.
    """
    if sources is None:
        sources = [np.arange(len(g)) for g in groups]
    else:  # takes numbered in order, so that a take's fold does not depend on its id
        sources = [np.unique(np.asarray(s), return_inverse=True)[1] for s in sources]
    moved, ranked, truth, grouped = [], [], [], []
    parts_of = feature_groups(features) if features is not None else {}
    own = own_columns(features) if features is not None else np.zeros(0, dtype=int)
    for fold in range(folds):
        out = [s % folds == fold for s in sources]
        train = [g[~o] for g, o in zip(groups, out)]
        if any(len(t) == 0 for t in train):
            keep = [a for a, t in enumerate(train) if len(t)]
        else:
            keep = list(range(len(groups)))
        if len(keep) < 1:
            continue
        scale, means, factors, noise = _fit_spread([train[a] for a in keep], rank, floors)
        spread = Spread(("",) * len(scale), _floats(scale), tuple(_floats(f) for f in factors),
                        _floats(noise), math.inf, 1.0)
        parts = precision_parts(spread, np.arange(len(scale)))
        if parts_of or len(own):
            variance = _action_variances(
                np.array([(((train[a] - m) / scale) ** 2).sum(axis=0)
                          for a, m in zip(keep, means)]), [len(train[a]) for a in keep])
        for k, a in enumerate(keep):
            held = groups[a][out[a]]
            if len(held) and len(train[a]) and parts_of:
                grouped.append(group_distances(held, means[k], variance[k], scale, parts_of))
            if len(held) and len(train[a]):
                shared = distances(held, means, parts)
                score = shared
                if len(own):  # ranked as recognition ranks: own-spread terms added
                    score = shared + own_terms(held[:, own], means[:, own],
                                               variance[:, own], scale[own])
                # rows must share one set of actions: pad the actions left out with +inf
                pad = np.full((len(held), len(groups) - len(keep)), np.inf)
                moved.extend(np.concatenate([shared, pad], axis=1))
                ranked.extend(np.concatenate([score, pad], axis=1))
                truth.extend([k] * len(held))
    if not moved:
        return math.inf, 1.0, ()
    limits = (_group_limits(np.concatenate(grouped), level,
                             np.array([len(c) for c in parts_of.values()], dtype=float))
              if grouped else ())
    limits = tuple((g, float(v)) for g, v in zip(parts_of, limits))
    dist = np.array(moved)
    features = groups[0].shape[1]
    nearest = dist[np.arange(len(truth)), truth] / features
    threshold = float(nearest.max() * _MARGIN)
    best, best_loss = 1.0, math.inf
    score = np.array(ranked)
    for temperature in 2.0 ** np.arange(0, 12):
        p = probabilities(score, temperature)[np.arange(len(truth)), truth]
        loss = float(-np.log(np.maximum(p, 1e-300)).mean())
        if loss < best_loss - 1e-12:
            best, best_loss = float(temperature), loss
    return threshold, best, limits


def describe_table(table: dict[str, np.ndarray], features: tuple[str, ...], *,
                   window: float = 0.0, rank: int = _RANK, sources=None,
                   level: float = GROUP_LEVEL) -> Descriptions:
    """Descriptions from feature rows (``{action: takes x features}``), sorted by name.

    ``sources`` (``{action: per row the take it comes from}``, for windows) keeps each take's
    rows together when the threshold is calibrated; ``level`` is how often a known take may
    fail the feature-group test.
    """
    names = sorted(table)
    groups = [np.asarray(table[n], dtype=float) for n in names]
    if not groups:
        raise DescriptionError("no action to describe")
    floors = _scale_floors(features)
    scale, means, factors, noise = _fit_spread(groups, rank, floors)
    spread = Spread(tuple(features), _floats(scale), tuple(_floats(f) for f in factors),
                    _floats(noise), math.inf, 1.0, window)
    threshold, temperature, limits = _calibrate(
        groups, rank, None if sources is None else [sources[n] for n in names], floors,
        features=features, level=level)
    spread = Spread(spread.features, spread.scale, spread.factors, spread.noise, threshold,
                    temperature, window, FORMAT_VERSION, limits)
    actions = tuple(ActionDescription(n, tuple(features), _floats(m), _floats(g.std(axis=0)),
                                      len(g), window) for n, g, m in zip(names, groups, means))
    return Descriptions(actions, spread)


def feature_rows(motions, *, shape: bool = True) -> list[dict[str, float]]:
    """Each motion's features as a ``{feature: value}`` dict."""
    rows = []
    for m in motions:
        try:
            rows.append(dict(zip(*motion_features(m, shape=shape))))
        except FeatureError as exc:
            raise DescriptionError(str(exc)) from None
    return rows


def common_table(rows: dict[str, list[dict[str, float]]]):
    """The features every row has, in the first row's order, and the table of them."""
    for name, per in rows.items():
        if not per:
            raise DescriptionError(f"action {name!r} has no takes")
    common = set.intersection(*(set(r) for per in rows.values() for r in per))
    order = tuple(f for f in next(iter(rows.values()))[0] if f in common)
    return order, {n: np.array([[r[f] for f in order] for r in per]) for n, per in rows.items()}


def describe(takes: dict[str, list], *, rank: int = _RANK,
             level: float = GROUP_LEVEL) -> Descriptions:
    """Descriptions of every action from its takes (``{name: [Motion, ...]}``).

    Features some take lacks (its skeleton has fewer joints) are left out. ``level``: how often
    a known take may be answered "none of these" by the feature-group test.

    Examples
    --------
    >>> from kinetology import synthetic_motion
    >>> d = describe({"a": [synthetic_motion(2, (0,), seed=s) for s in (1, 2)],
    ...               "b": [synthetic_motion(2, (1,), seed=s) for s in (3, 4)]})
    >>> d.names, [a.takes for a in d.actions], len(d.spread.features) == len(d.actions[0].mean)
    (('a', 'b'), [2, 2], True)
    """
    rows = {name: feature_rows(motions) for name, motions in takes.items()}
    order, table = common_table(rows)
    return describe_table(table, order, rank=rank, level=level)
