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

Actions need not share a skeleton. Each action keeps the features every one of its takes has
(``ActionDescription.features``: its joints are its takes'), and the spread covers every
feature some action has. A motion is compared with each action over the features the two
share, and its distance is read per feature compared and scaled to the motion's own number of
features, so actions compared over fewer features stay on one scale (:func:`scores`); an
action that shares no joint with the motion is not compared at all.

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
from .features import FeatureError, feature_joint, motion_features

__all__ = ["FORMAT_VERSION", "ActionDescription", "Spread", "Descriptions", "describe",
           "describe_table", "DescriptionError",
           "GROUP_LEVEL", "OWN_KINDS", "own_columns", "own_terms", "scores", "ScoreModel",
           "score_model"]

#: Bumped when what a description holds or how features are computed changes (4: each
#: action keeps its own features, which need not be the spread's, so that actions learnt from
#: different skeletons keep their joints; before, only the features every take had were kept).
FORMAT_VERSION = 4
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

    ``features`` are the ones every take of the action has (a subset of the spread's: actions
    learnt from other skeletons have other joints); ``takes`` counts the takes (or windows)
    learnt from; ``window`` is the length in seconds of the windows learnt from (0: whole
    takes).
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

    def __post_init__(self) -> None:
        known = set(self.spread.features)
        for a in self.actions:
            if not (len(a.features) == len(a.mean) == len(a.spread)):
                raise DescriptionError(f"action {a.name!r}: {len(a.features)} features but "
                                       f"{len(a.mean)} means and {len(a.spread)} spreads")
            if not known.issuperset(a.features):
                extra = sorted(set(a.features) - known)[:3]
                raise DescriptionError(f"action {a.name!r} has features the spread has not "
                                       f"({', '.join(extra)})")

    @property
    def names(self) -> tuple[str, ...]:
        """The actions' names, in order."""
        return tuple(a.name for a in self.actions)

    def aligned(self, field: str = "mean") -> np.ndarray:
        """Actions x the spread's features: each action's ``field`` (``"mean"`` or
        ``"spread"``), NaN where the action lacks the feature.

        Examples
        --------
        >>> spread = Spread(("a", "b"), (1.0, 1.0), (), (1.0, 1.0), 1.0, 1.0)
        >>> d = Descriptions((ActionDescription("x", ("b",), (2.0,), (0.5,), 2),), spread)
        >>> d.aligned().tolist()
        [[nan, 2.0]]
        """
        index = {f: i for i, f in enumerate(self.spread.features)}
        out = np.full((len(self.actions), len(index)), np.nan)
        for k, a in enumerate(self.actions):
            values = np.asarray(getattr(a, field), dtype=float)
            if a.features == self.spread.features:
                out[k] = values
            else:
                out[k, [index[f] for f in a.features]] = values
        return out

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
    return _parts(np.asarray(spread.scale), np.asarray(spread.noise),
                  np.asarray(spread.factors, dtype=float).reshape(-1, len(spread.scale)),
                  columns)


def _parts(scale, noise, factors, columns):
    """:func:`precision_parts` from the spread's arrays (all features) on ``columns``: the
    marginal of the shared Gaussian on those features."""
    scale = scale[columns]
    inverse = 1.0 / noise[columns]
    w = factors[:, columns]
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
    terms = _own_raw(x, means, variance, scale)
    return terms - terms.min(axis=1, keepdims=True) if terms.size else terms


def _own_raw(x, means, variance, scale) -> np.ndarray:
    x, means = np.atleast_2d(x), np.atleast_2d(means)
    z = ((x[:, None, :] - means[None]) / scale) ** 2 / variance[None]
    return (z + np.log(variance)[None]).sum(axis=2)


@dataclass(frozen=True)
class ScoreModel:
    """What scoring reads on some of the descriptions' columns, computed once per call: the
    actions' means, the shared precision's pieces (:func:`precision_parts`) and each action's
    own variance, in the spread's scaled units (``scale``).

    ``means`` and ``variance`` are NaN where an action lacks a column (it was learnt from
    another skeleton). ``blocks`` groups the actions compared over the same columns:
    ``(actions, positions among the columns, the precision's pieces on them)``; an action
    that has no joint among the columns is in no block (not compared).
    """

    columns: np.ndarray
    means: np.ndarray  # actions x columns
    parts: tuple
    variance: np.ndarray  # actions x columns
    scale: np.ndarray
    blocks: tuple = ()

    @property
    def compared(self) -> np.ndarray:
        """Per action: whether it is compared (shares a joint with the columns)."""
        out = np.zeros(len(self.means), dtype=bool)
        for actions, _, _ in self.blocks:
            out[actions] = True
        return out

    def block_of(self, action: int):
        """``(positions, parts)`` the action is compared over (``None`` if it is not)."""
        for actions, positions, parts in self.blocks:
            if action in actions:
                return positions, parts
        return None


def _score_model(columns, names, scale, noise, factors, means, variance) -> ScoreModel:
    """The :class:`ScoreModel` on ``columns`` from the spread's arrays over every feature
    (``names``) and the actions' means and own variances (NaN where an action lacks one)."""
    columns = np.asarray(columns, dtype=int)
    parts = _parts(scale, noise, factors, columns)
    means, variance = means[:, columns], variance[:, columns]
    has = ~np.isnan(means)
    joint = np.array([feature_joint(names[c]) != "*" for c in columns], dtype=bool)
    same: dict[bytes, list[int]] = {}
    for a, row in enumerate(has):
        if np.any(row & joint):  # the take-wide tempo alone compares no movement
            same.setdefault(row.tobytes(), []).append(a)
    blocks = []
    for actions in same.values():
        positions = np.flatnonzero(has[actions[0]])
        blocks.append((np.array(actions), positions, parts if len(positions) == len(columns)
                       else _parts(scale, noise, factors, columns[positions])))
    return ScoreModel(columns, means, parts, variance, scale[columns], tuple(blocks))


def score_model(descriptions: "Descriptions", columns) -> ScoreModel:
    """The :class:`ScoreModel` of ``descriptions`` on ``columns``."""
    spread = descriptions.spread
    return _score_model(columns, spread.features, np.asarray(spread.scale),
                        np.asarray(spread.noise),
                        np.asarray(spread.factors, dtype=float).reshape(-1, len(spread.scale)),
                        descriptions.aligned("mean"),
                        action_variances(descriptions, np.arange(len(spread.features))))


def _part(a: np.ndarray, rows=None, columns=None) -> np.ndarray:
    """``a[rows][:, columns]`` (``None``: all), and ``a`` itself when that is all of it: a
    copy may lie differently in memory, and a matrix product's last bits can depend on that,
    so that one skeleton's scores are those of a praxicon of that skeleton alone."""
    if rows is not None and not (len(rows) == len(a) and np.array_equal(rows, np.arange(len(a)))):
        a = a[rows]
    if columns is not None and not (len(columns) == a.shape[-1]
                                    and np.array_equal(columns, np.arange(a.shape[-1]))):
        a = a[..., columns]
    return a


def model_scores(m: ScoreModel, x, own) -> tuple[np.ndarray, np.ndarray]:
    """:func:`scores` from a :class:`ScoreModel` (``own``: positions among its columns of the
    features also scored in each action's own spread).

    Each block of actions is compared over its own columns; its distance per feature compared
    is scaled to the number of columns, so that actions compared over fewer features (learnt
    from a skeleton with fewer of the motion's joints) are on the same scale as the others:
    the "none of these" threshold, a distance per feature, reads each action's own. Actions
    not compared (no joint in common) get an infinite distance: ranked last, probability 0.
    """
    n = len(m.columns)
    shared = np.full((len(x), len(m.means)), np.inf)
    raw = np.zeros_like(shared)
    compared = m.compared
    for actions, positions, parts in m.blocks:
        shared[:, actions] = distances(_part(x, None, positions),
                                       _part(m.means, actions, positions),
                                       parts) * (n / len(positions))
        mine = positions[np.isin(positions, own)]
        if len(mine):
            raw[:, actions] = _own_raw(x[:, mine], _part(m.means, actions)[:, mine],
                                       _part(m.variance, actions)[:, mine],
                                       m.scale[mine]) * (len(own) / len(mine))
    if not len(own):
        return shared, shared
    if not raw.size or not compared.any():
        return shared, shared + raw
    best = np.where(compared, raw, np.inf).min(axis=1, keepdims=True)
    return shared, shared + np.where(compared, raw - best, 0.0)


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
    own = own_columns([descriptions.spread.features[i] for i in columns], kinds)
    return model_scores(m, np.asarray(x), own)


def _action_variances(sums: np.ndarray, counts) -> np.ndarray:
    """Per action and feature the variance of its own copies (scaled units) from the sums of
    squared deviations, shrunk towards the variance pooled over actions as if
    ``_PRIOR_TAKES`` more takes had shown that: a turn's tight drift stays tight, an action
    learnt from two takes borrows the others' spread."""
    counts = np.asarray(counts, dtype=float)[:, None]
    has = ~np.isnan(sums)  # pooled over the actions that have the feature
    dof = np.maximum(1.0, np.where(has, counts - 1, 0.0).sum(axis=0))
    pooled = np.maximum(np.where(has, sums, 0.0).sum(axis=0) / dof, _NOISE_FLOOR)
    return (sums + _PRIOR_TAKES * pooled) / (counts - 1 + _PRIOR_TAKES)


def action_variances(descriptions: "Descriptions", columns) -> np.ndarray:
    """Actions x ``columns``: each action's own variance per feature, in the spread's scaled
    units (from the stored per-action spreads and take counts)."""
    scale = np.asarray(descriptions.spread.scale)[columns]
    n = np.array([a.takes for a in descriptions.actions], dtype=float)
    spread = descriptions.aligned("spread")[:, columns]
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


def _blocks(has: np.ndarray):
    """Features grouped by which actions have them (``has``: actions x features):
    ``(columns, actions)`` per group, one group when every action has every feature."""
    same: dict[bytes, list[int]] = {}
    for c in range(has.shape[1]):
        same.setdefault(has[:, c].tobytes(), []).append(c)
    return [(np.array(c), np.flatnonzero(has[:, c[0]])) for c in same.values()]


def _fit_spread(groups: list[np.ndarray], rank: int, floors=None):
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
    _, singular, vt = np.linalg.svd(residuals / np.sqrt(per), full_matrices=False)
    eigen = singular ** 2
    rest = float(eigen[r:].sum() / max(1, residuals.shape[1] - r))
    factors = vt[:r] * np.sqrt(np.maximum(eigen[:r] - rest, 0.0))[:, None]
    noise = np.maximum(variance - (factors ** 2).sum(axis=0), max(_NOISE_FLOOR, rest))
    # a variance read from few takes is mostly luck: shrink each feature's towards the mean
    # over features, as if _PRIOR_TAKES more takes had shown the typical spread
    typical = noise[has.any(axis=0)].mean()  # over the features some action has
    noise = (per * noise + _PRIOR_TAKES * typical) / (per + _PRIOR_TAKES)
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


def _calibrate(groups: list[np.ndarray], rank: int, sources=None, floors=None,
               folds: int = _FOLDS, *, features, level: float = GROUP_LEVEL):
    """Threshold and temperature from held-out training takes (``folds``-fold).

    Every take is scored by a model learnt without it (its action's mean *and* the shared
    spread), as an unseen take would be, over its action's features (:func:`model_scores`, as
    recognition scores a motion); an action with a single take cannot be held out.
    The threshold is ``_MARGIN`` times the largest distance per feature such a take got; the
    group limits from each group's held-out distances to its own action, in
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
        scale, means, factors, noise = _fit_spread([train[a] for a in keep], rank, floors)
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
        return math.inf, 1.0, ()
    limits = (_group_limits(np.concatenate(grouped), level,
                             np.array([len(c) for c in parts_of.values()], dtype=float))
              if grouped else ())
    limits = tuple((g, float(v)) for g, v in zip(parts_of, limits) if not math.isnan(v))
    dist = np.array(moved)
    nearest = dist[np.arange(len(truth)), truth] / np.array(compared)
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

    A NaN in an action's column means the action lacks that feature (its takes are of another
    skeleton, :func:`common_table`): the action keeps the features all its rows have, and
    must have a joint among them. ``sources`` (``{action: per row the take it comes from}``,
    for windows) keeps each take's rows together when the threshold is calibrated; ``level``
    is how often a known take may fail the feature-group test.
    """
    names = sorted(table)
    groups = [np.asarray(table[n], dtype=float) for n in names]
    if not groups:
        raise DescriptionError("no action to describe")
    features = tuple(features)
    has = [~np.isnan(g).any(axis=0) for g in groups]
    if not all(h.all() for h in has):
        groups = [np.where(h, g, np.nan) for g, h in zip(groups, has)]
        used = np.any(has, axis=0)  # a feature no action has is left out
        if not used.all():
            features = tuple(f for f, u in zip(features, used) if u)
            groups, has = [g[:, used] for g in groups], [h[used] for h in has]
    for n, h in zip(names, has):
        if not any(k and feature_joint(f) != "*" for f, k in zip(features, h)):
            raise DescriptionError(f"action {n!r}: its takes share no joint (learn an action "
                                   f"from takes of one skeleton)")
    floors = _scale_floors(features)
    scale, means, factors, noise = _fit_spread(groups, rank, floors)
    spread = Spread(tuple(features), _floats(scale), tuple(_floats(f) for f in factors),
                    _floats(noise), math.inf, 1.0, window)
    threshold, temperature, limits = _calibrate(
        groups, rank, None if sources is None else [sources[n] for n in names], floors,
        features=features, level=level)
    spread = Spread(spread.features, spread.scale, spread.factors, spread.noise, threshold,
                    temperature, window, FORMAT_VERSION, limits)
    actions = tuple(ActionDescription(n, tuple(f for f, k in zip(features, h) if k),
                                      _floats(m[h]), _floats(g.std(axis=0)[h]), len(g), window)
                    for n, g, m, h in zip(names, groups, means, has))
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
    """Per action the features every one of its rows has; every action's features, in the
    order they first appear, and the table of them (per action rows x features, NaN where the
    action lacks a feature: its takes are of another skeleton).

    Examples
    --------
    >>> order, table = common_table({"a": [{"x": 1.0, "t": 2.0}], "b": [{"y": 3.0, "t": 4.0}]})
    >>> order, table["a"].tolist(), table["b"].tolist()
    (('x', 't', 'y'), [[1.0, 2.0, nan]], [[nan, 4.0, 3.0]])
    """
    for name, per in rows.items():
        if not per:
            raise DescriptionError(f"action {name!r} has no takes")
    kept = {n: set.intersection(*(set(r) for r in per)) for n, per in rows.items()}
    order = tuple(dict.fromkeys(f for n, per in rows.items() for f in per[0] if f in kept[n]))
    return order, {n: np.array([[r[f] if f in kept[n] else math.nan for f in order]
                                for r in per]) for n, per in rows.items()}


def describe(takes: dict[str, list], *, rank: int = _RANK,
             level: float = GROUP_LEVEL) -> Descriptions:
    """Descriptions of every action from its takes (``{name: [Motion, ...]}``).

    Each action keeps the features all its takes have: actions learnt from different
    skeletons keep their own joints (an action's takes must share one). ``level``: how often
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
