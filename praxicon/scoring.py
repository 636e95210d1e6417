"""Scoring a motion's features against learnt descriptions: the shared Gaussian's pieces,
the distances, the own-spread terms of the root's drift, and the probabilities.

:class:`~praxicon.description.Descriptions` hold what is learnt; this module reads them. A
:class:`ScoreModel` is the part of the descriptions one set of a motion's features needs,
computed once per call; :func:`scores` (:func:`model_scores`) ranks every action. Actions
learnt from another skeleton are compared over the features they share with the motion, on
one scale (:func:`model_scores`); one that shares no joint is not compared.

>>> from praxicon.description import describe
>>> from kinetology import synthetic_motion
>>> d = describe({"a": [synthetic_motion(2, (0,), seed=s) for s in (1, 2)],
...               "b": [synthetic_motion(2, (1,), seed=s) for s in (3, 4)]})
>>> m = score_model(d, np.arange(len(d.spread.features)))
>>> m.compared.tolist(), len(m.blocks)
([True, True], 1)
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ._errors import REBUILD, DescriptionError
from .features import feature_joint

__all__ = ["OWN_KINDS", "own_columns", "own_terms", "scores", "ScoreModel", "score_model",
           "log_likelihoods", "probabilities",
           "unscored", "overflow_reason"]

_NOISE_FLOOR = 0.05  # smallest per-feature variance left, in scaled units
_PRIOR_TAKES = 10.0  # pseudo-takes of typical spread each feature's own spread is shrunk to
#: Kinds of the root's features every action also scores in its own spread (:func:`scores`).
OWN_KINDS = ("drift",)


def precision_parts(spread: "Spread", columns) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
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
    """Squared Mahalanobis distance of every row of ``x`` to every mean (motions x actions).

    Each row's distance is its own sums in a fixed order, whatever other rows ``x`` holds: a
    take recognised alone and in a batch of any size has the same numbers to the last bit, in
    whichever chunk of files ``psgs praxicon recognise`` reads it. A matrix product would not
    give that: BLAS takes another path for one row than for several, and may block the rows.

    Examples
    --------
    >>> parts = (np.ones(3), np.ones(3), np.array([[1.0, 0.0, 0.0]]), np.array([[0.5]]))
    >>> x = np.array([[1.0, 2.0, 0.0], [0.1, 0.2, 0.3]])
    >>> both = distances(x, np.zeros((1, 3)), parts)
    >>> both.tolist(), bool(distances(x[1:], np.zeros((1, 3)), parts)[0, 0] == both[1, 0])
    ([[4.5], [0.135]], True)
    """
    scale, inverse, w, inner = parts
    # C order, so that every row's sums run along contiguous memory however ``x`` was cut (a
    # matrix's chosen columns, x[:, columns], come in Fortran order)
    x = np.ascontiguousarray(x, dtype=float)
    w = np.ascontiguousarray(w, dtype=float)
    out = np.empty((len(x), len(means)))
    for a, mean in enumerate(means):
        d = (x - mean) / scale
        # einsum without optimize runs numpy's own loops (no BLAS): one dot product per row
        b = np.einsum("nf,kf->nk", d * inverse, w)
        # two operands at a time: with three, einsum's loop order followed the number of
        # rows where the spread has two shared directions (a take alone and in a batch
        # differed in the last bits)
        bm = np.einsum("ni,ij->nj", b, inner)
        out[:, a] = (d * d * inverse).sum(axis=1) - np.einsum("nj,nj->n", bm, b)
    return out


def log_likelihoods(dist: np.ndarray, temperature: float, tail: float = math.inf):
    """Each action's log-likelihood (up to one constant) from its squared distance: Gaussian,
    ``-dist / (2 temperature)``, with an infinite ``tail``; else heavy-tailed,
    ``-(tail / (2 temperature)) log(1 + dist / tail)``, which is the Gaussian's where ``dist``
    is small against ``tail`` and grows as the log of the distance beyond it (the likelihood of
    a scale mixture of Gaussians, as Student's t is). Both fall as the distance grows, so the
    actions' order is the distances' either way.

    Examples
    --------
    >>> d = np.array([[1.0, 4.0]])
    >>> log_likelihoods(d, 1.0).tolist(), log_likelihoods(d, 1.0, 1e12).round(6).tolist()
    ([[-0.5, -2.0]], [[-0.5, -2.0]])
    >>> log_likelihoods(d, 1.0, 1.0).round(3).tolist()  # log 2 / 2, log 5 / 2
    [[-0.347, -0.805]]
    """
    if math.isinf(tail):
        return -0.5 * dist / temperature
    return -(0.5 * tail / temperature) * np.log1p(dist / tail)


def probabilities(dist: np.ndarray, temperature: float, tail: float = math.inf) -> np.ndarray:
    """Posterior probabilities (equal priors) from squared distances: their
    :func:`log_likelihoods` at ``temperature`` and ``tail``, normalised."""
    logits = log_likelihoods(dist, temperature, tail)
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
    """The :class:`ScoreModel` of ``descriptions`` on ``columns``.

    Raises
    ------
    DescriptionError
        When a number of the descriptions is beyond what the scores can compute with (a mean
        of 1e308: its square, in the spread's units, is past the float range), naming it and
        the command that learns the descriptions again: every score was NaN.
    """
    spread = descriptions.spread
    columns = np.asarray(columns, dtype=int)
    scale, noise = np.asarray(spread.scale), np.asarray(spread.noise)
    factors = np.asarray(spread.factors, dtype=float).reshape(-1, len(spread.scale))
    means = descriptions.aligned("mean")
    # a number too large overflows here and in every score: silenced, and said below
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        variance = action_variances(descriptions, np.arange(len(spread.features)))
        problem = _overflowing(descriptions, columns, means / scale, variance, noise, factors)
        m = None
        if not problem:
            try:
                m = _score_model(columns, spread.features, scale, noise, factors, means,
                                 variance)
            except np.linalg.LinAlgError:  # the shared directions' matrix has no inverse
                pass
            if m is None or not all(np.isfinite(inner).all()
                                    for _, _, (*_, inner) in m.blocks):
                problem = "the spread's shared directions ('factors') have no finite precision"
    if problem:
        raise DescriptionError(f"the praxicon's descriptions overflow the scores: {problem} "
                               f"(learn the descriptions again: '{REBUILD}')")
    return m


def _overflowing(descriptions, columns, scaled, variance, noise, factors) -> str:
    """The first number of the descriptions on ``columns`` the scores cannot compute with,
    said as ``the ... is VALUE`` ("" when there is none): a mean whose square in the spread's
    units (``scaled``: actions x features) is not finite, an action's own variance that is
    not, a scale or a noise whose inverse's square is not, or a shared direction whose square
    is not."""
    spread = descriptions.spread
    names, scale = spread.features, np.asarray(spread.scale)
    # the likelihoods' first: a temperature or a tail whose inverse's square is not finite
    # (or a tail too large over the temperature) makes every log-likelihood infinite and
    # every probability NaN
    temperature, tail = spread.temperature, spread.tail
    with np.errstate(over="ignore"):
        if not np.isfinite((1.0 / np.float64(temperature)) ** 2):
            return f"the spread's temperature is {temperature:g}"
        if math.isfinite(tail) and not (np.isfinite((1.0 / np.float64(tail)) ** 2)
                                        and np.isfinite(np.float64(tail) / temperature)):
            return f"the spread's tail is {tail:g}"
    # then the spread's features: a scale too small makes every mean too large in its units
    for kind, bad, number in (("scale", ~np.isfinite((1.0 / scale[columns]) ** 2), scale),
                              ("noise", ~np.isfinite((1.0 / noise[columns]) ** 2), noise),
                              ("factors", ~np.isfinite((factors[:, columns] ** 2).sum(axis=0)),
                               np.abs(factors).max(axis=0, initial=0.0))):
        if bad.any():
            c = columns[np.flatnonzero(bad)[0]]
            return f"the spread's {kind} of feature {names[c]} is {number[c]:g}"
    has = ~np.isnan(scaled[:, columns])  # NaN: a feature the action lacks
    for kind, bad in (("mean", ~np.isfinite(scaled[:, columns] ** 2)),
                      ("spread", ~np.isfinite(variance[:, columns]))):
        bad = np.argwhere(bad & has)
        if len(bad):
            action, c = descriptions.actions[bad[0][0]], columns[bad[0][1]]
            number = getattr(action, kind)[action.features.index(names[c])]
            return f"the {kind} of {action.name}'s feature {names[c]} is {number:g}"
    return ""


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


#: Rows :func:`model_scores` scores at a time. Its temporaries are a few copies of the rows'
#: features per action (and rows x actions x the root's own features): scored at once, the
#: windows of a long recording held four times their features beside them. A row's numbers
#: are the same whatever rows it is scored with (:func:`distances`).
_ROWS = 256


def model_scores(m: ScoreModel, x, own) -> tuple[np.ndarray, np.ndarray]:
    """:func:`scores` from a :class:`ScoreModel` (``own``: positions among its columns of the
    features also scored in each action's own spread).

    Each block of actions is compared over its own columns; its distance per feature compared
    is scaled to the number of columns, so that actions compared over fewer features (learnt
    from a skeleton with fewer of the motion's joints) are on the same scale as the others:
    the "none of these" threshold, a distance per feature, reads each action's own. Actions
    not compared (no joint in common) get an infinite distance: ranked last, probability 0.
    The rows are scored ``_ROWS`` at a time.
    """
    if len(x) <= _ROWS:
        return _model_scores(m, x, own)
    parts = [_model_scores(m, x[a:a + _ROWS], own) for a in range(0, len(x), _ROWS)]
    return tuple(np.concatenate([p[k] for p in parts]) for k in (0, 1))


def _model_scores(m: ScoreModel, x, own) -> tuple[np.ndarray, np.ndarray]:
    """:func:`model_scores` of rows scored at once."""
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


def unscored(m: ScoreModel, *scored) -> np.ndarray:
    """Per motion (a row of each of ``scored``, motions x actions): whether a number of it
    against an action compared is not finite (an action not compared is infinitely far by
    design). Finite features and descriptions can still overflow a square or a product of
    the scores; the callers silence that and refuse the motions this names.

    Examples
    --------
    >>> m = ScoreModel(np.arange(1), np.zeros((2, 1)), (), np.ones((2, 1)), np.ones(1),
    ...                ((np.array([0]), np.array([0]), ()),))  # action 1 not compared
    >>> unscored(m, np.array([[1.0, np.inf], [np.nan, 2.0]])).tolist()
    [False, True]
    """
    compared = m.compared
    out = np.zeros(len(scored[0]), dtype=bool)
    for values in scored:
        out |= ~np.isfinite(np.asarray(values)[:, compared]).all(axis=1)
    return out


def overflow_reason(m: ScoreModel, row, features, names) -> str:
    """Why a motion's scores (``row``: its features on ``m``'s columns, named ``features``)
    are not finite: the feature furthest from a compared action's mean (``names``: the
    actions') in the spread's units, and which is too large to compute with, the motion's
    value or the action's mean (then the descriptions are to be learnt again).

    Examples
    --------
    >>> m = ScoreModel(np.arange(2), np.array([[0.0, 1.0]]), (), np.ones((1, 2)), np.ones(2),
    ...                ((np.array([0]), np.arange(2), ()),))
    >>> print(overflow_reason(m, np.array([0.5, 1e200]), ["a.rx:pose", "a.rx:energy"],
    ...                       ["wave"]))  # doctest: +NORMALIZE_WHITESPACE
    its feature a.rx:energy is 1e+200, too large to score: its distances to the learnt
    actions overflow
    """
    with np.errstate(over="ignore", invalid="ignore"):
        far = np.abs((np.asarray(row) - m.means) / m.scale)
    far[~m.compared] = np.nan  # an action not compared is scored over none of these
    far = np.where(np.isnan(far), -np.inf, far)  # NaN: a feature the action lacks
    a, k = np.unravel_index(int(np.argmax(far)), far.shape)
    value, mean = float(row[k]), float(m.means[a, k])
    if abs(value) >= abs(mean):
        return (f"its feature {features[k]} is {value:g}, too large to score: its distances to "
                f"the learnt actions overflow")
    return (f"the description of {names[a]} has a mean of {mean:g} for its feature "
            f"{features[k]}, too large to score: the distances overflow (learn the "
            f"descriptions again: '{REBUILD}')")


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
    >>> from praxicon.description import describe
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
