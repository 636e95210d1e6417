"""The feature groups of the "none of these" test: which columns form a group, which groups
tell an action apart from the other learnt actions, and each group's distance.

A deviation concentrated in a few features (a walk's missing heading drift against a turn's
tight one) drowns in a sum over all features but stands out in its group; these are the plain
functions over a description's means and per-action variances that
:mod:`praxicon.description` calibrates and :mod:`praxicon.recognition` applies.
"""

from __future__ import annotations

import numpy as np

from .features import feature_joint

__all__ = ["ALWAYS_READ", "feature_groups", "group_distances", "telling_groups"]

#: Groups the "none of these" test reads even where every learnt action looks alike in them:
#: a learnt set that never leaves the ground (walks and turns alone) is no run, however fast
#: or slow; a take that flies is none of them, where a style's sideways drift or tempo is
#: still most likely the action it ranked as. Likewise a learnt set of gaits alone is no action
#: performed in place (a punch that steps on the spot is no walk), and actions performed in
#: place alone no gait: the pace is read too.
ALWAYS_READ = ("flight", "pace")


def feature_groups(features) -> dict[str, np.ndarray]:
    """The columns of each feature group: a joint's features, each of the root's travel and
    turning features alone, the flight, the pace, the tempo (the units a deviation
    concentrates in).

    A joint's features move together (a pose, its range and its speed are one movement), but
    the root's are separate quantities a gait is defined by: a turn's heading rate is one
    number, and summed with the sideways and vertical travel its absence in a walk drowns.
    Where a whole take's turn excursion is there, it stands for that axis's turning and the
    mean turning rate is in no group: the rate is the net turn over the take, so a take that
    turned and came partly back reads as a turn the other way, while how far it turned says
    what it performed (the rate is still scored, in the ranking).

    Examples
    --------
    >>> g = feature_groups(["a.rx:pose", "a.ry:spread", "Hips.turnx:drift",
    ...                     "Hips.turnx:energy", "tempo"])
    >>> {k: v.tolist() for k, v in g.items()}
    {'a': [0, 1], 'Hips.turnx:drift': [2], 'Hips.turnx:energy': [3], 'tempo': [4]}
    >>> list(feature_groups(["Hips.turnx:drift", "Hips.turnx:excursion"]))
    ['Hips.turnx:excursion']
    """
    features = list(features)
    turned = {f.rsplit(":", 1)[0] for f in features if f.endswith(":excursion")}
    out: dict[str, list[int]] = {}
    for i, f in enumerate(features):
        root = ".travel" in f or ".turn" in f
        if root and f.endswith(":drift") and f.rsplit(":", 1)[0] in turned:
            continue
        joint = feature_joint(f)  # "*": a take-wide feature (the tempo, the flight, the pace)
        key = f if root or joint == "*" else joint
        out.setdefault(key, []).append(i)
    return {k: np.array(v, dtype=int) for k, v in out.items()}


def telling_groups(means, variance, scale, groups: dict[str, np.ndarray], bound) -> np.ndarray:
    """Actions x groups: whether the group tells the action apart from another learnt action
    (that action's mean would fail the group's limit ``bound`` in this action's own spread).

    A group in which every learnt action looks alike (the sideways drift of walks, turns and
    runs) cannot tell the answer from the other answers; a take far out in it is still most
    likely what it ranked as, and failing it rejects known takes that a style or a slip moved
    there. The group test reads only the groups that do tell; with a single action there is
    nothing to tell it from, and every group is read. Another action that lacks a group (NaN
    means: learnt from another skeleton) cannot be told apart in it; a group no other action
    has is read, as with a single action. The groups of :data:`ALWAYS_READ` are always read.

    Examples
    --------
    >>> groups = {"a": np.array([0]), "b": np.array([1])}
    >>> means = np.array([[0.0, 0.0], [5.0, 0.1]])  # the actions differ in "a" only
    >>> telling_groups(means, np.ones((2, 2)), np.ones(2), groups, np.array([4.0, 4.0])).tolist()
    [[True, False], [True, False]]
    """
    means = np.atleast_2d(means)
    if len(means) < 2:
        return np.ones((len(means), len(groups)), dtype=bool)
    out = np.empty((len(means), len(groups)), dtype=bool)
    for a in range(len(means)):
        others = np.delete(means, a, axis=0)
        far = group_distances(others, means[a], variance[a], scale, groups) / bound
        known = ~np.isnan(far)
        out[a] = np.where(known, far, -np.inf).max(axis=0) > 1.0
        out[a] |= ~known.any(axis=0)
    out[:, [k for k, g in enumerate(groups) if g in ALWAYS_READ]] = True
    return out


def group_distances(x, mean, variance, scale, groups: dict[str, np.ndarray]) -> np.ndarray:
    """Rows x groups: each group's squared distance from ``mean``, every feature in units of
    the action's own ``variance`` (after dividing by ``scale``)."""
    z = ((np.atleast_2d(x) - mean) / scale) ** 2 / variance
    return np.stack([z[:, c].sum(axis=1) for c in groups.values()], axis=1)
