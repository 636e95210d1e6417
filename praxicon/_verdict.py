"""The "none of these" test that recognition and parsing apply to a motion's best action:
its distance per feature within the descriptions' threshold, and no feature group that tells
the action apart from the others further from it than that group's calibrated limit.

Kept apart from :mod:`praxicon.recognition`, which ranks the actions and explains the answer:
:func:`~praxicon.parsing.parse` applies the same test to each window of a recording. What the
test and the scores read of the descriptions alone (the score model and the telling groups on
a skeleton's columns) is made once per set of columns by :class:`ScoreModels`.
"""

from __future__ import annotations

import numpy as np

from ._errors import DescriptionError
from .feature_groups import feature_groups, group_distances, telling_groups
from .scoring import score_model, unscored

__all__: list[str] = []


class _Unscorable(DescriptionError):
    """Descriptions holding a number the scores cannot compute with: an error of the
    praxicon, not of a motion, which names its file where it was read from one."""


def _score_model(descriptions, columns):
    """:func:`~praxicon.description.score_model`, its error an :class:`_Unscorable`."""
    try:
        return score_model(descriptions, columns)
    except DescriptionError as exc:
        raise _Unscorable(str(exc)) from None


#: The most score models :class:`ScoreModels` keeps (about 0.24 MB each for 28 actions): one
#: a skeleton, and a command's files seldom have more, but its memory must not grow with them.
KEPT_MODELS = 16


class ScoreModels:
    """The score models of ``descriptions`` (and of their families, ``families``), each made
    when a set of columns is first asked for and then kept (the last :data:`KEPT_MODELS`).

    What scoring and the group test read of the descriptions alone (the score model, the
    feature groups, the groups that tell each action apart: about 17 ms for 28 actions) depends
    on the columns a motion has, one set per skeleton, not on the motions: ``psgs praxicon
    recognise``, which recognises its files a chunk at a time, makes them once per skeleton
    for the whole command rather than once per chunk.

    Examples
    --------
    >>> from kinetology import synthetic_motion
    >>> from praxicon.description import describe
    >>> px = describe({"a": [synthetic_motion(2, (0,), seed=1, noise=n) for n in (0.2, 0.6)],
    ...                "b": [synthetic_motion(2, (1,), seed=2, noise=n) for n in (0.2, 0.6)]})
    >>> models = ScoreModels(px)
    >>> columns = np.arange(len(px.spread.features))
    >>> models(columns) is models(columns.copy())  # made once
    True
    """

    __slots__ = ("descriptions", "families", "_made")

    def __init__(self, descriptions) -> None:
        self.descriptions = descriptions
        families = descriptions.families
        self.families = None if families is None else ScoreModels(families)
        self._made: dict[bytes, tuple] = {}

    def __call__(self, columns) -> tuple:
        """``(fitted, test)`` on ``columns`` (indices of the descriptions' features): the
        score model (raising :class:`_Unscorable`) and what the group test reads on them
        (:func:`_group_test`)."""
        columns = np.asarray(columns, dtype=int)
        key = columns.tobytes()
        if key not in self._made:
            fitted = _score_model(self.descriptions, columns)
            features = [self.descriptions.spread.features[c] for c in columns]
            # a group distance too large overflows to inf, which tells as it compares
            with np.errstate(over="ignore", invalid="ignore"):
                test = _group_test(self.descriptions, features, fitted)
            if len(self._made) >= KEPT_MODELS:  # files of many skeletons: the oldest goes
                del self._made[next(iter(self._made))]
            self._made[key] = (fitted, test)
        return self._made[key]


def _tested(descriptions, features, x, best, fitted, dist, test):
    """The "none of these" test of each motion against its ``best`` action (``dist``: the
    shared distances, motions x actions; ``test``: :func:`_group_test` on the motions'
    columns): ``(accepted, penalty, excess, group, lost)``, accepted where the distance per
    feature is within the threshold and no telling feature group (:func:`_excess`) is past
    its limit; ``lost`` where a distance is not finite (an overflow: the motion cannot be
    scored)."""
    excess, group, lost = _excess_of(test, x, best, fitted)
    penalty = dist[np.arange(len(best)), best] / max(1, len(features))
    accepted = (penalty <= descriptions.spread.threshold) & (excess <= 1.0)
    return accepted, penalty, excess, group, lost | unscored(fitted, dist)


def _group_test(descriptions, features, fitted, *, telling: bool = True):
    """What the group test reads on the columns of ``fitted`` (``features``), whatever the
    motions: ``(groups, their limits, actions x groups read)``, or None when the descriptions
    have no limits for these features.

    Only the groups that tell an action apart from another learnt action are read
    (:func:`~praxicon.feature_groups.telling_groups`; ``telling=False``: every group, as the
    benchmark compares).
    """
    limits = dict(descriptions.spread.limits)
    groups = {g: c for g, c in feature_groups(features).items() if g in limits}
    if not groups:
        return None
    bound = np.maximum(np.array([limits[g] for g in groups]), 1e-12)
    # told apart from the actions the motion is compared with (those sharing a joint with it)
    tells = np.ones((len(fitted.means), len(groups)), dtype=bool)
    if telling:
        compared = np.flatnonzero(fitted.compared)
        tells[compared] = telling_groups(fitted.means[compared], fitted.variance[compared],
                                         fitted.scale, groups, bound)
    return groups, bound, tells


def _excess(descriptions, features, x, best, fitted, *, telling: bool = True, rows=None):
    """Per motion: its best action's worst feature group over that group's calibrated limit
    (0 and "" when the descriptions have no limits), the group's name, and whether a group's
    distance overflowed (the motion cannot be scored).

    The groups read are :func:`_group_test`'s (``telling=False``: every group); ``fitted`` is
    the score model on the motions' columns. ``rows``: the rows of ``x`` tested, ``best``
    their actions (None: every row), read in place (parse tests the windows answered by an
    action among all of a recording's).
    """
    if not len(best):
        return _excess_of(None, x, best, fitted)
    return _excess_of(_group_test(descriptions, features, fitted, telling=telling), x, best,
                      fitted, rows)


def _excess_of(test, x, best, fitted, rows=None):
    """:func:`_excess` with what the group test reads on the motions' columns (``test``:
    :func:`_group_test`) made before."""
    n = len(best)
    if test is None or not n:
        return np.zeros(n), [""] * n, np.zeros(n, dtype=bool)
    groups, bound, tells = test
    rows = range(n) if rows is None else rows
    far = np.empty((n, len(groups)))  # a row at a time: a list of them held ten times more
    for k, (i, b) in enumerate(zip(rows, best)):
        far[k] = group_distances(x[i], fitted.means[b], fitted.variance[b], fitted.scale,
                                 groups)[0]
    # a sum of squares that overflowed is inf (NaN: a group the best action lacks), read
    # before a group not read (x 0) turns it into a NaN
    lost = np.isinf(far).any(axis=1)
    ratio = far  # in place: a recording's windows x groups, once
    ratio /= bound
    ratio *= tells[best]
    ratio[np.isnan(ratio)] = 0.0  # a group the best action lacks: not read
    names = list(groups)
    # no group read (none tells the best action apart): no group to name
    return ratio.max(axis=1), [names[k] if r[k] > 0 else "" for k, r in
                               zip(ratio.argmax(axis=1), ratio)], lost
