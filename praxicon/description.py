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
(:func:`scores`); probabilities are those scores' likelihoods at the ``temperature`` and the
``tail`` (infinite: Gaussian; :func:`~praxicon.scoring.log_likelihoods`) that fit the left-out
training takes best.

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

import math
from collections.abc import Mapping, Sequence
from dataclasses import replace
from functools import partial

import numpy as np

from ._arguments import DescriptionError, described
from ._description_json import check_window
# the spread and its calibration live in .calibration (``calibrate`` is imported under another
# name: describe_table has a flag of that name)
from .calibration import _RANK, GROUP_LEVEL, fit_spread, scale_floors
from .calibration import calibrate as _calibrate
from .calibration import held_together
from .feature_choice import _FOLDS as _CHOICE_FOLDS
from .feature_choice import choose_features
from .features import FeatureError, feature_joint, motion_features
# the model and its scores live in .scoring; those of __all__ are this module's as well, for
# the callers that read descriptions and score with them from one place
from .scoring import OWN_KINDS, ScoreModel, own_columns, own_terms, score_model, scores
# the values learnt, which recognition reads, live in ._description_types (with the version
# of what they hold); they are this module's names as well, where they are documented (last:
# the API page lists names in the order they come, and these came after the scores')
from ._description_types import (FORMAT_VERSION, ActionDescription, Spread, Descriptions,
                                  _fields)

__all__ = ["FORMAT_VERSION", "ActionDescription", "Spread", "Descriptions", "describe",
           "describe_table", "chosen_table", "family_descriptions", "DescriptionError",
           "GROUP_LEVEL", "OWN_KINDS", "own_columns", "own_terms", "scores",
           "ScoreModel", "score_model"]

#: Bumped when how descriptions are learnt changes but what they hold does not: a praxicon
#: keeps reading its descriptions, and a build learns them again (4: the pace feature, its
#: group always read; 3: the flight feature, its
#: group always read, and a group's takes held out together in the calibration; 2: the kinds
#: of features are chosen by held-out recognition, ``praxicon.feature_choice``).
LEARNING = 4


def _floats(values) -> tuple[float, ...]:
    return tuple(float(v) for v in values)


def describe_table(table: dict[str, np.ndarray], features: tuple[str, ...], *,
                   window: float = 0.0, rank: int = _RANK, sources=None,
                   level: float = GROUP_LEVEL, calibrate: bool = True) -> Descriptions:
    """Descriptions from feature rows (``{action: takes x features}``), sorted by name.

    A NaN in an action's column means the action lacks that feature (its takes are of another
    skeleton, :func:`common_table`): the action keeps the features all its rows have, and
    must have a joint among them. ``sources`` (``{action: per row a fold key}``: for windows
    the take a row comes from, numbered from 0; for takes their group's number,
    :func:`~praxicon.calibration.held_together`) keeps rows of one key together when the
    threshold is calibrated; ``level`` is how often a known take may fail the feature-group
    test. Without ``calibrate`` there is no "none of these" (an infinite threshold, no group
    limits): descriptions that only rank, learnt without the five more models the calibration
    learns.
    """
    # what from_dict would refuse is refused here, not after a dump that cannot be loaded
    window = float(_fields(check_window, window))
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
    floors = scale_floors(features)
    scale, means, factors, noise = fit_spread(groups, rank, floors)
    spread = Spread(tuple(features), _floats(scale), tuple(_floats(f) for f in factors),
                    _floats(noise), math.inf, 1.0, window)
    # a window's likelihoods stay Gaussian: parse's costs are its distances at a temperature
    threshold, temperature, limits, tail = (math.inf, 1.0, (), math.inf) if not calibrate \
        else _calibrate(groups, rank, None if sources is None else
                        [_fold_keys(n, sources, len(g)) for n, g in zip(names, groups)],
                        floors, features=features, level=level, tailed=not window)
    spread = Spread(spread.features, spread.scale, spread.factors, spread.noise, threshold,
                    temperature, window, FORMAT_VERSION, limits, tail)
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


def _fold_keys(name: str, sources, rows: int) -> np.ndarray:
    """``sources[name]`` checked: one whole number from 0 per row (a calibration fold key)."""
    keys = np.asarray(sources.get(name) if isinstance(sources, Mapping) else None)
    if keys.shape != (rows,) or (rows and not (np.issubdtype(keys.dtype, np.integer)
                                               and keys.min() >= 0)):
        raise DescriptionError(f"action {name!r}: sources must give each of its {rows} rows a "
                               f"whole number from 0 (the fold key its row is held out by)")
    return keys.astype(int)


def describe(takes: dict[str, list], *, rank: int = _RANK,
             level: float = GROUP_LEVEL, groups: Mapping[str, Sequence] | None = None,
             choose: bool = True, families: Mapping[str, str] | None = None) -> Descriptions:
    """Descriptions of every action from its takes.

    Each action keeps the features all its takes have: actions learnt from different
    skeletons keep their own joints (an action's takes must share one).

    Parameters
    ----------
    takes : dict of str to list of Motion
        Per action (a string) its takes.
    rank : int
        The shared directions of variation kept (0 or more).
    level : float
        How often (0 < level < 1) a known take may be answered "none of these" (group test).
    groups : mapping of str to sequence, optional
        Per action, each take's group (a style, a performer; any hashable value, compared
        by equality): the choice of features, and the calibration of "none of these", hold a
        group's takes out together, which asks what a new style asks
        (:func:`~praxicon.calibration.held_together`). Groups that each hold whole actions
        leave nothing to hold out, and every feature is kept. Without it, each action's takes
        are dealt into five folds in the order given. Checked even without ``choose``.
    choose : bool
        Choose the kinds of features by how well held-out takes are recognised
        (:func:`praxicon.feature_choice.choose_features`); without it, every feature.
    families : mapping of str to str, optional
        Per action the family it belongs to (an action not named: a family of its own): the
        actions of one family are styles of one content (``bandai-namco-2.walk.elderly`` and
        ``bandai-namco-2.walk.active`` of family ``bandai-namco-2.walk``). Recognition ranks
        the actions, and "none of these" is decided for a family's member by the family's
        description (:func:`family_descriptions`): a new take of a learnt content in a
        learnt style differs from that style's few takes more than they differ from each
        other, but lies among the content's styles.

    Returns
    -------
    Descriptions

    Raises
    ------
    DescriptionError
        When the takes cannot be described (no takes, no joint in common, not names to
        motions), ``groups`` does not give one hashable group per take of every action, or
        ``rank``, ``level`` or ``choose`` is out of its type or range.

    Examples
    --------
    >>> from kinetology import synthetic_motion
    >>> d = describe({"a": [synthetic_motion(2, (0,), seed=s) for s in (1, 2)],
    ...               "b": [synthetic_motion(2, (1,), seed=s) for s in (3, 4)]})
    >>> d.names, [a.takes for a in d.actions], len(d.spread.features) == len(d.actions[0].mean)
    (('a', 'b'), [2, 2], True)

    With each take's style, so that the choice holds a style out at a time:

    >>> d = describe({"a": [synthetic_motion(2, (0,), seed=s) for s in (1, 2, 3, 4)],
    ...               "b": [synthetic_motion(2, (1,), seed=s) for s in (5, 6, 7, 8)]},
    ...              groups={"a": ["x", "y", "x", "y"], "b": ["x", "y", "x", "y"]})
    >>> d.names
    ('a', 'b')
    """
    takes = described(takes, rank, level, choose, groups)
    rows = {name: feature_rows(motions) for name, motions in takes.items()}
    order, table = common_table(rows)
    if choose:
        order, table = chosen_table(table, order, groups=groups, rank=rank)
    out = describe_table(table, order, rank=rank, level=level,
                         sources=None if groups is None else held_together(groups))
    if families is None:
        return out
    described_families, family_of = family_descriptions(rows, families, rank=rank,
                                                        level=level, choose=choose)
    if described_families is None:
        return out
    return replace(out, families=described_families,
                   family_of=tuple(family_of[n] for n in out.names))


def family_descriptions(rows: dict[str, list], families: Mapping[str, str], *,
                        rank: int = _RANK, level: float = GROUP_LEVEL, choose: bool = True):
    """``(descriptions of the families, {action: its family or ""})`` from each action's
    feature rows (:func:`feature_rows`); ``(None, ...)`` when no family has two actions.

    A family's takes are its members' takes together (the choice of features and the
    calibration of "none of these" hold whole members out, as styles not learnt, in five
    folds); an action alone is its own family, named by its own name and learnt from its
    takes alone, so that the families' "none of these" reads the groups that tell a family
    from every other learnt content.

    Examples
    --------
    >>> rows = {"a.x": [{"j.rx:pose": 0.0, "tempo": 1.0}, {"j.rx:pose": 0.2, "tempo": 1.1}],
    ...         "a.y": [{"j.rx:pose": 1.0, "tempo": 1.0}, {"j.rx:pose": 1.1, "tempo": 0.9}],
    ...         "b": [{"j.rx:pose": 9.0, "tempo": 2.0}, {"j.rx:pose": 9.3, "tempo": 2.1}]}
    >>> d, of = family_descriptions(rows, {"a.x": "a", "a.y": "a"}, choose=False)
    >>> d.names, [a.takes for a in d.actions], of
    (('a', 'b'), [4, 2], {'a.x': 'a', 'a.y': 'a', 'b': ''})
    """
    if not isinstance(families, Mapping):
        raise DescriptionError(f"families must map action names to family names, not "
                               f"{type(families).__name__}")
    members: dict[str, list[str]] = {}
    for name in rows:
        if name not in families:
            continue
        family = families[name]
        if not isinstance(family, str) or not family:
            raise DescriptionError(f"action {name!r}: its family must be a name, not "
                                   f"{family!r}")
        members.setdefault(family, []).append(name)
    for name in rows:  # an action not named is a family of its own, named by its name
        if name not in families:
            if name in members:
                raise DescriptionError(f"family {name!r} has the name of another action")
            members[name] = [name]
    of = {n: f if len(m) > 1 else "" for f, m in members.items() for n in m}
    if not any(len(m) > 1 for m in members.values()):
        return None, of
    table_rows, groups = {}, {}
    for family, names in members.items():
        key = family if len(names) > 1 else names[0]
        if key in table_rows or (len(names) > 1 and key in rows and key not in names):
            raise DescriptionError(f"family {family!r} has the name of another action")
        table_rows[key] = [r for n in names for r in rows[n]]
        # five folds, as without groups: a family's members dealt into them (a member held
        # out whole, as a style not learnt), an action alone's takes dealt in turn; a fold per
        # member made 20 folds on the shared data, four times the time for the same choice
        groups[key] = ([f"fold {k % _CHOICE_FOLDS}" for k, n in enumerate(names)
                        for _ in rows[n]] if len(names) > 1 else
                       [f"fold {i % _CHOICE_FOLDS}" for i in range(len(rows[key]))])
    order, table = common_table(table_rows)
    if choose:
        order, table = chosen_table(table, order, groups=groups, rank=rank)
    return describe_table(table, order, rank=rank, level=level,
                          sources=held_together(groups)), of


def chosen_table(table: dict[str, np.ndarray], features: tuple[str, ...], *,
                 groups=None, rank: int = _RANK):
    """``(features, table)`` keeping only the features
    :func:`~praxicon.feature_choice.choose_features` chooses (``groups`` as in
    :func:`describe`; each fold's descriptions only rank: no calibration)."""
    chosen = choose_features(table, features, partial(describe_table, rank=rank,
                                                      calibrate=False), groups=groups)
    if chosen == tuple(features):
        return tuple(features), table
    columns = [features.index(f) for f in chosen]
    return chosen, {n: t[:, columns] for n, t in table.items()}

