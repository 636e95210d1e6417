"""Which kinds of features describe a set of actions, chosen by how well held-out takes are
recognised.

A kind of feature can tell actions apart in one collection and mostly carry style in
another: in a walk-and-turn family performed in seven styles, a pose is much of what a style
changes, while among seventeen different actions the poses are what tells a bow from a wave.
So no kind is left out for good. :func:`choose_features` holds takes out of the learning in
folds (the takes of one group together, when the caller knows the groups: a style, a
performer, a session, so that a fold asks what a new style asks), ranks them with
descriptions learnt from the rest, and leaves out the one kind whose absence answers more
held-out takes right than every feature does. A tie keeps every feature, and so do takes too
few to hold any out.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence

import numpy as np

from psgs.errors import PSGSError

from .scoring import scores

#: learns descriptions that rank takes from ``{action: takes x features}`` and the features'
#: names (:func:`praxicon.description.describe` hands in ``describe_table`` uncalibrated)
Learner = Callable[[dict, tuple], object]

__all__ = ["FEATURE_KINDS", "choose_features", "feature_kind", "groups_problem"]

#: the kinds a description may leave out, in the order a tie between them is broken
FEATURE_KINDS = ("pose", "energy", "spread", "shape", "tempo", "root")
_FOLDS = 5  # folds when no groups are given: each action's takes dealt out in turn
#: at most this many folds with groups: more groups are dealt into them in turn (a group's
#: takes still together), so a group per take costs 20 fits of each candidate, not one a take
MAX_FOLDS = 20


def feature_kind(feature: str) -> str:
    """The kind of a feature: ``pose``, ``energy``, ``spread``, ``shape`` (a joint's
    course over the take), ``tempo``, ``root`` (the root's drift, sway and turn),
    ``flight`` or ``pace`` (the body's against the ground, never left out: the "none of
    these" test always reads them).

    Parameters
    ----------
    feature : str
        A feature's name, as :func:`praxicon.features.motion_features` gives it.

    Returns
    -------
    str
        Its kind (the part after the last ``:``, its digits dropped, ``posec`` read as
        ``pose``; the root's travel and turning features, the flight, the pace and the tempo
        by name).

    Examples
    --------
    >>> [feature_kind(f) for f in ("Neck.rx:posec", "Neck.rx:shape2", "Hips.turny:drift",
    ...                            "tempo", "flight", "pace")]
    ['pose', 'shape', 'root', 'tempo', 'flight', 'pace']
    """
    if feature == "tempo":
        return "tempo"
    if feature in ("flight", "pace"):
        return feature
    if ".travel" in feature or ".turn" in feature:
        return "root"
    kind = feature.rsplit(":", 1)[-1].rstrip("0123456789")
    return "pose" if kind == "posec" else kind


def groups_problem(takes: Mapping[str, int], groups) -> str | None:
    """What is wrong with ``groups`` for actions of ``takes`` (``{action: number of takes}``)
    as :func:`choose_features` reads them, or None: one hashable group per take of every
    action.

    Examples
    --------
    >>> groups_problem({"a": 2}, {"a": ["x", "y"]}) is None
    True
    >>> groups_problem({"a": 2, "b": 1}, {"a": ["x", "y"]})
    "groups: no groups for action 'b'"
    """
    if not isinstance(groups, Mapping):
        return f"groups must map each action to its takes' groups, not {type(groups).__name__}"
    for name, count in takes.items():
        if name not in groups:
            return f"groups: no groups for action {name!r}"
        given = groups[name]
        if isinstance(given, (str, bytes)) or not isinstance(given, (Sequence, np.ndarray)):
            return (f"groups of action {name!r}: a sequence of one group per take, not "
                    f"{type(given).__name__}")
        if len(given) != count:
            return f"groups of action {name!r}: {len(given)} given for {count} takes"
        for g in given:
            try:
                hash(g)
            except TypeError:
                return (f"groups of action {name!r}: {g!r} is not hashable (a group is "
                        f"compared by equality)")
    return None


def _folds(table: Mapping[str, np.ndarray], groups) -> dict[str, np.ndarray]:
    """Per action, each take's fold: its group's (groups compared by equality, numbered as
    they first appear), or dealt out in turn."""
    if groups is None:
        return {a: np.arange(len(rows)) % _FOLDS for a, rows in table.items()}
    number: dict = {}
    return {a: np.array([number.setdefault(g, len(number)) % MAX_FOLDS for g in groups[a]],
                        dtype=int) for a in table}


def _held_out_right(table, features, keep, folds, learn: Learner) -> tuple[int, int] | None:
    """How many takes held out fold by fold the descriptions ``learn`` makes from the rest
    rank first as their own action, and how many were asked, over the features ``keep``
    marks (None: a fold's takes cannot be described over them)."""

    right = asked = 0
    names = list(table)
    kept = tuple(f for f, k in zip(features, keep) if k)
    for fold in sorted({int(f) for a in names for f in folds[a]}):
        # an action all of whose takes are in this fold is not learnt in it, nor asked for
        learnt = {a: table[a][folds[a] != fold][:, keep] for a in names}
        learnt = {a: rows for a, rows in learnt.items() if len(rows)}
        tested = [(a, table[a][folds[a] == fold][:, keep]) for a in learnt]
        if len(learnt) < 2 or not any(len(rows) for _, rows in tested):
            continue
        try:
            d = learn(learnt, kept)
        except PSGSError:  # a DescriptionError (which this module cannot import: it
            return None      # imports this one), e.g. these features hold no joint
        index = {f: i for i, f in enumerate(d.spread.features)}
        at = np.array([index.get(f, -1) for f in kept])
        rows = np.vstack([r for _, r in tested])
        truth = np.array([a for a, r in tested for _ in range(len(r))])
        # scored over the features a take has (another skeleton's are NaN), the takes with
        # the same ones at once
        usable = ~np.isnan(rows) & (at >= 0)
        for pattern in {tuple(u) for u in usable}:
            mask = np.array(pattern, dtype=bool)
            these = (usable == mask).all(axis=1)
            _, score = scores(d, rows[these][:, mask], at[mask])
            right += int((np.array(d.names)[score.argmin(axis=1)] == truth[these]).sum())
        asked += len(rows)
    return right, asked


def choose_features(table: Mapping[str, np.ndarray], features: Sequence[str],
                    learn: Learner, *, groups: Mapping[str, Sequence] | None = None
                    ) -> tuple[str, ...]:
    """The features that describe the actions: every one, or all but one kind when leaving
    that kind out recognises more held-out takes.

    Parameters
    ----------
    table : mapping of str to ndarray
        Per action its takes x ``features`` (NaN where the action lacks a feature), as
        :func:`praxicon.description.common_table` gives.
    features : sequence of str
        The columns' names.
    learn : callable
        ``learn(table, features)`` gives descriptions learnt from a fold's takes, which
        rank takes (``functools.partial(describe_table, calibrate=False)``, as
        :func:`praxicon.description.describe` hands in).
    groups : mapping of str to sequence, optional
        Per action, each take's group (a style, a performer; compared by equality): a
        group's takes are held out together, one fold per group (up to ``MAX_FOLDS``; more
        groups are dealt into that many folds in the order they first appear). Groups that
        each hold whole actions leave nothing to ask, and every feature is kept. Without it, each action's takes are dealt into five
        folds in the order given.

    Returns
    -------
    tuple of str
        The chosen features, in the order of ``features``.

    Examples
    --------
    Two actions told apart by their energies, in six styles of three takes each; each
    style holds its own pose, so a pose learnt from some styles says nothing of a new one:

    >>> from functools import partial
    >>> import numpy as np
    >>> from praxicon.description import describe_table
    >>> learn = partial(describe_table, calibrate=False)
    >>> rng = np.random.default_rng(0)
    >>> features = ("a.rx:pose", "b.rx:pose", "a.rx:energy", "b.rx:energy")
    >>> styles = np.repeat(np.arange(6), 3)
    >>> def takes(energy):
    ...     pose = rng.normal(0, 4, (6, 2))[styles] + rng.normal(0, 0.2, (18, 2))
    ...     return np.column_stack([pose, rng.normal(energy, 1.0, (18, 2))])
    >>> table = {"fast": takes(2.0), "slow": takes(0.0)}
    >>> choose_features(table, features, learn, groups={"fast": styles, "slow": styles})
    ('a.rx:energy', 'b.rx:energy')

    Held out without the styles, a style's other takes are learnt, its pose with them:

    >>> choose_features(table, features, learn)
    ('a.rx:pose', 'b.rx:pose', 'a.rx:energy', 'b.rx:energy')
    """
    features = tuple(features)
    kinds = [feature_kind(f) for f in features]
    folds = _folds(table, groups)
    if len({int(f) for a in table for f in folds[a]}) < 2:
        return features  # nothing can be held out
    every = np.ones(len(features), dtype=bool)
    counted = _held_out_right(table, features, every, folds, learn)
    if counted is None or counted[1] == 0:
        # nothing held out could be asked (groups that each hold whole actions): no evidence
        return features
    best, best_right = features, counted[0]
    for kind in FEATURE_KINDS:
        keep = np.array([k != kind for k in kinds])
        if keep.all() or not keep.any():
            continue
        counted = _held_out_right(table, features, keep, folds, learn)
        if counted is not None and counted[0] > best_right:
            best, best_right = tuple(f for f, k in zip(features, keep) if k), counted[0]
    return best
