"""The "none of these" test that recognition and parsing apply to a motion's best action:
its distance per feature within the descriptions' threshold, and no feature group that tells
the action apart from the others further from it than that group's calibrated limit.

Kept apart from :mod:`praxicon.recognition`, which ranks the actions and explains the answer:
:func:`~praxicon.parsing.parse` applies the same test to each window of a recording.
"""

from __future__ import annotations

import numpy as np

from .feature_groups import feature_groups, group_distances, telling_groups
from .scoring import unscored

__all__: list[str] = []


def _tested(descriptions, features, x, best, fitted, dist):
    """The "none of these" test of each motion against its ``best`` action (``dist``: the
    shared distances, motions x actions): ``(accepted, penalty, excess, group, lost)``,
    accepted where the distance per feature is within the threshold and no telling feature
    group (:func:`_excess`) is past its limit; ``lost`` where a distance is not finite (an
    overflow: the motion cannot be scored)."""
    excess, group, lost = _excess(descriptions, features, x, best, fitted)
    penalty = dist[np.arange(len(best)), best] / max(1, len(features))
    accepted = (penalty <= descriptions.spread.threshold) & (excess <= 1.0)
    return accepted, penalty, excess, group, lost | unscored(fitted, dist)


def _excess(descriptions, features, x, best, fitted, *, telling: bool = True):
    """Per motion: its best action's worst feature group over that group's calibrated limit
    (0 and "" when the descriptions have no limits), the group's name, and whether a group's
    distance overflowed (the motion cannot be scored).

    Only the groups that tell the best action apart from another learnt action are read
    (:func:`~praxicon.feature_groups.telling_groups`; ``telling=False``: every group, as the
    benchmark compares); ``fitted`` is the score model on the motions' columns.
    """
    limits = dict(descriptions.spread.limits)
    groups = {g: c for g, c in feature_groups(features).items() if g in limits}
    if not groups or not len(x):
        return np.zeros(len(x)), [""] * len(x), np.zeros(len(x), dtype=bool)
    bound = np.maximum(np.array([limits[g] for g in groups]), 1e-12)
    # told apart from the actions the motion is compared with (those sharing a joint with it)
    tells = np.ones((len(fitted.means), len(groups)), dtype=bool)
    if telling:
        compared = np.flatnonzero(fitted.compared)
        tells[compared] = telling_groups(fitted.means[compared], fitted.variance[compared],
                                         fitted.scale, groups, bound)
    far = np.stack([group_distances(x[i], fitted.means[b], fitted.variance[b], fitted.scale,
                                    groups)[0] for i, b in enumerate(best)])
    # a sum of squares that overflowed is inf (NaN: a group the best action lacks), read
    # before a group not read (x 0) turns it into a NaN
    lost = np.isinf(far).any(axis=1)
    ratio = far / bound * tells[best]
    ratio = np.where(np.isnan(ratio), 0.0, ratio)  # a group the best action lacks: not read
    names = list(groups)
    # no group read (none tells the best action apart): no group to name
    return ratio.max(axis=1), [names[k] if r[k] > 0 else "" for k, r in
                               zip(ratio.argmax(axis=1), ratio)], lost
