"""Recognising motion through the praxicon: which learnt action a take is, or none of them.

Every action's :class:`~praxicon.description.ActionDescription` scores the take's feature
vector with the same Gaussian log-likelihood (one covariance shared by every action), so the
scores compare across actions; an action
with many joints gains nothing from them, because the joints that must stay still and the
joints that move but are not the action's cost as much as a joint that moves wrongly. The
root's drift (its travel and turning velocities) is also scored in each action's own spread
(:func:`~praxicon.description.scores`): a walk backwards always travels backwards. The best
action is the answer unless its mean penalty exceeds the threshold calibrated on the training
takes, or one group of features (a joint, one of the root's drifts, sways or turn excursions,
the tempo) that tells it apart from another learnt action is further from it, in the action's
own spread, than its calibrated limit (exceeded by a held-out training take with probability
``GROUP_LEVEL``): then the answer is ``None`` ("none of these").

A praxicon may hold actions learnt from different skeletons. A motion is compared with each
action over the features the two share (its distance scaled to one number of features, so
the scores stay on one scale); ``Recognition.lacking`` names, per action shown, the action's
joints the motion lacks, and an action that shares no joint with the motion is ranked last,
at probability 0, and named in ``Recognition.unshared``.

>>> from kinetology import synthetic_motion
>>> from praxicon.description import describe
>>> takes = {"left": [synthetic_motion(3, (0,), seed=1, noise=n) for n in (0.2, 0.5, 1.0)],
...          "right": [synthetic_motion(3, (2,), seed=2, noise=n) for n in (0.2, 0.5, 1.0)]}
>>> px = describe(takes)
>>> found = recognise(px, synthetic_motion(3, (2,), seed=2, noise=0.7))
>>> found.action, [name for name, _ in found.ranking]
('right', ['right', 'left'])
>>> recognise(px, synthetic_motion(3, (1,), seed=5)).action is None  # none of these
True
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from ._arguments import motion_of, motions_of, whole_number
from .description import DescriptionError, Descriptions, feature_rows, own_columns
from .feature_table import feature_matrix
from .features import feature_joint, pace_of, share_of_flight
from .scoring import (_part, mahalanobis_terms, model_scores, overflow_reason, probabilities,
                      unscored)
from ._verdict import ScoreModels, _Unscorable, _tested
from ._verdict import _excess, _score_model  # noqa: F401  (parse, benchmarks read them here)
from .records import REBUILD, Praxicon, _count

__all__ = ["Recognition", "recognise", "recognise_many", "feature_matrix", "JointReason",
           "family_verdicts", "FamilyVerdict"]


@dataclass(frozen=True)
class JointReason:
    """One joint's part in a recognition: its penalty and why (for :meth:`Recognition.explain`)."""

    joint: str
    penalty: float  # summed over the joint's features, relative to a perfect match
    role: str  # "matched", "still but should move", "moves but should be still", "differs"


@dataclass(frozen=True)
class Recognition:
    """What a motion is: ``action`` (or None: none of these) and every action's score.

    ``ranking`` holds ``(action, probability)`` best first: the probabilities come from one
    log-likelihood per action, on one scale, and sum to 1 over the praxicon's actions; the
    order is that of the log-likelihoods, also where the probabilities of the actions far
    behind the best round to 0.
    ``penalty`` is the best action's squared Mahalanobis distance per feature and
    ``threshold`` the largest it may be for an answer other than None (when ``family`` is
    set, these and ``excess`` are the family's, whose test decided); ``missing`` names the
    best-ranked action's joints the motion lacks (recognised over the joints it has),
    ``lacking`` the same per action shown, ``unread`` the best-ranked action's joints the
    motion has but not with every feature learnt of them (a root whose position does not
    move has no travel or turning; a joint of other channels), and ``unshared`` the actions
    that share no joint with the motion (ranked last, probability 0: learnt from another
    skeleton); ``reasons`` holds, for the best three actions, every joint's part.
    """

    source: str
    action: str | None
    ranking: tuple[tuple[str, float], ...]
    penalty: float
    threshold: float
    missing: tuple[str, ...] = ()
    reasons: tuple[tuple[str, tuple[JointReason, ...]], ...] = ()
    tempo: tuple[tuple[str, float], ...] = ()  # per action shown: the tempo's distance term
    drift: tuple[tuple[str, float], ...] = ()  # per action shown: the root drift's terms
    excess: float = 0.0  # the best action's worst feature group over its limit
    excess_group: str = ""  # which group that is
    lacking: tuple[tuple[str, tuple[str, ...]], ...] = ()  # per action shown: joints not here
    unshared: tuple[str, ...] = ()  # actions sharing no joint with the motion
    family: str = ""  # the family whose description decided none of these ("": the action's)
    #: per action shown that has the flight: its distance term and the share of its takes'
    #: frames off the ground its mean stands for (``max(0, exp(mean) - 0.1)``, the feature
    #: read back: a typical share, below the mean share)
    flight: tuple[tuple[str, float, float], ...] = ()
    #: the share of the motion's frames off the ground; None when the flight is not among the
    #: features compared (the motion has no skeleton, no action of the praxicon has the flight,
    #: or it could not be read)
    off_ground: float | None = None
    #: per action shown that has the pace: its distance term and the pace its mean stands for
    #: (hips' heights a second, ``max(0, exp(mean) - 0.05)``: a typical pace)
    pace: tuple[tuple[str, float, float], ...] = ()
    #: how fast the motion travels, hips' heights a second; None as ``off_ground``
    travel: float | None = None
    #: the best-ranked action's joints the motion has, read without some of their features
    unread: tuple[str, ...] = ()

    def __repr__(self) -> str:  # a summary, not the dataclass dump of every reason
        best = dict(self.ranking).get(self.action) if self.action else None
        answer = f"{self.action} (p={best:.3f})" if self.action else "none of these"
        missing = f", {_count(len(self.missing), 'joint')} missing" if self.missing else ""
        return (f"<Recognition {self.source!r}: {answer}, distance {self.penalty:.3f} per "
                f"feature (threshold {self.threshold:.3f}), "
                f"{_count(len(self.ranking), 'action')} ranked{missing}>")

    def explain(self, joints: int | None = 4) -> str:
        """The reasons, as text: per shown action the ``joints`` that decided it, at most
        (None: every one) of each role; ``joints`` not a whole number ≥ 0: DescriptionError."""
        if joints is not None:  # -1 left out the last joint of each role, 1.5 failed slicing
            whole_number(joints, "joints")
        lines = [f"{self.source}: {self.action or 'none of these'} (distance {self.penalty:.3f}"
                 f" per feature, threshold {self.threshold:.3f})"]
        if self.family:
            lines.append(f"  'none of these' tested by the family {self.family} (the styles "
                         f"of one content together)")
        if self.excess_group:
            lines.append(f"  furthest feature group: {self.excess_group}, {self.excess:.2f} x "
                         f"its limit (none of these above 1)")
        if self.off_ground is not None:
            lines.append(f"  off the ground in {100 * self.off_ground:.0f} % of its frames")
        if self.travel is not None:
            lines.append(f"  travels {self.travel:.2f} hips' heights a second")
        if self.missing:
            lines.append(f"  missing joints (recognised without them): "
                         f"{', '.join(self.missing)}")
        if self.unread:
            lines.append(f"  joints read without some of their learnt features (a root that "
                         f"does not move, or other channels): {', '.join(self.unread)}")
        probability = dict(self.ranking)
        tempo, drift, lacking = dict(self.tempo), dict(self.drift), dict(self.lacking)
        flight = {name: (term, share) for name, term, share in self.flight}
        pace = {name: (term, value) for name, term, value in self.pace}
        for name, reasons in self.reasons:
            flies = (f", flight term {_term(flight[name][0])} (its takes typically off the ground "
                     f"{100 * flight[name][1]:.0f} %)" if name in flight else "")
            goes = (f", pace term {_term(pace[name][0])} (its takes typically {pace[name][1]:.2f} "
                    f"hips' heights a second)" if name in pace else "")
            lines.append(f"  {name}: p={probability[name]:.3f}, tempo term "
                         f"{_term(tempo.get(name, 0.0))}, drift terms {_term(drift.get(name, 0.0))}"
                         f"{flies}{goes}")
            if lacking.get(name):
                lines.append(f"    lacks the action's joints: {', '.join(lacking[name])}")
            matched = [r.joint for r in sorted(reasons, key=lambda r: r.penalty)
                       if r.role == "matched"][:joints]
            if matched:
                lines.append(f"    matched: {', '.join(matched)}")
            for role in ("still but should move", "moves but should be still", "differs"):
                worst = [r for r in sorted(reasons, key=lambda r: -r.penalty)
                         if r.role == role][:joints]
                if worst:
                    lines.append(f"    {role}: " + ", ".join(
                        f"{r.joint} ({r.penalty:.1f})" for r in worst))
        if self.unshared:
            shown = ", ".join(self.unshared[:6]) + (f" and {len(self.unshared) - 6} more"
                                                    if len(self.unshared) > 6 else "")
            lines.append(f"  ranked last, sharing no joint with the motion (learnt from "
                         f"another skeleton): {shown}")
        return "\n".join(lines)


def _descriptions(source, *, windows: bool = False) -> Descriptions:
    if isinstance(source, (str, Path)):
        from .store import read_descriptions
        return read_descriptions(source, windows=windows)
    if isinstance(source, Descriptions):
        return source
    found = getattr(source, "window_descriptions" if windows else "descriptions", None)
    if isinstance(found, Descriptions):  # a typed praxicon value
        return found
    who = "parse" if windows else "recognise"
    if isinstance(source, Praxicon) and not source.counts["learnt"]:
        from .store import _nothing_learnt
        raise DescriptionError(f"{who}: {_nothing_learnt(source, windows)}")
    if isinstance(source, Praxicon):  # read without them, or built before they were learnt
        raise DescriptionError(f"{who}: this praxicon holds no descriptions (load(folder) "
                               f"reads them; '{REBUILD}' learns them)")
    raise DescriptionError(f"{who} needs a praxicon (folder or value) or Descriptions")


def _motion(source):
    return motion_of(source)  # a Motion, or read from its file; anything else is refused


def _frames(motion, doing: str) -> None:
    """Refuse a motion of fewer than 3 frames, the fewest whose features can be read."""
    if motion.frames < 3:
        raise DescriptionError(f"{getattr(motion, 'source', '<motion>')}: {motion.frames} "
                               f"frame{'' if motion.frames == 1 else 's'}; {doing} needs at "
                               f"least 3")


def _in_file(exc: DescriptionError, folder, *, windows: bool = False) -> DescriptionError:
    """``exc`` of the descriptions read from ``folder``, naming their file and part (as
    :func:`praxicon.load` names a damaged field) when it is an :class:`_Unscorable`."""
    if not isinstance(exc, _Unscorable):
        return exc
    from .description_store import FILE
    return _Unscorable(f"{Path(folder) / FILE}: {'windows' if windows else 'takes'}: {exc}")


def _joints_of(motion) -> set[str]:
    """The joints that carry a channel of ``motion``."""
    return {channel.rpartition(".")[0] for channel in motion.channels}


#: the take-wide features of the body against the ground, each read back from its log into
#: its own unit (a share of the frames, hips' heights a second) for the explanation
_BODY = {"flight": share_of_flight, "pace": pace_of}


def _term(value: float) -> str:
    """A term to two decimals, never ``-0.00`` (a term may be a hair under 0).

    >>> _term(-0.001), _term(2.046)
    ('0.00', '2.05')
    """
    return f"{round(value, 2) + 0.0:.2f}"


def _energies(features, values) -> dict[str, float]:
    out: dict[str, float] = {}
    for f, v in zip(features, values):
        if f.endswith(":energy"):
            joint = feature_joint(f)
            out[joint] = max(out.get(joint, 0.0), float(np.expm1(v)))
    return out


def _reasons(features, terms, x_row, mean) -> tuple[JointReason, ...]:
    per_joint: dict[str, float] = {}
    for f, t in zip(features, terms):
        per_joint[feature_joint(f)] = per_joint.get(feature_joint(f), 0.0) + float(t)
    moves, should = _energies(features, x_row), _energies(features, mean)
    # a joint "matched" when it adds no more than an average joint of a training take would
    typical = len(features) / max(1, len(per_joint))
    out = []
    for joint, penalty in per_joint.items():
        if joint == "*":
            continue
        m, s = moves.get(joint, 0.0), should.get(joint, 0.0)
        if penalty <= typical:
            role = "matched"
        elif s > 2 * m:
            role = "still but should move"
        elif m > 2 * s:
            role = "moves but should be still"
        else:
            role = "differs"
        out.append(JointReason(joint, round(penalty, 3), role))
    return tuple(out)


def recognise_many(praxicon, motions, *, explain: int | None = 3) -> list[Recognition]:
    """:func:`recognise` for many motions in one call (features once, one matrix of scores
    per skeleton among the motions).

    Raises the :class:`~praxicon.description.DescriptionError` of the first motion, in the
    order given, that cannot be recognised (as :func:`recognise` says it).

    Examples
    --------
    >>> from kinetology import synthetic_motion
    >>> from praxicon.description import describe
    >>> px = describe({"a": [synthetic_motion(2, (0,), seed=1, noise=n) for n in (0.2, 0.6)],
    ...                "b": [synthetic_motion(2, (1,), seed=2, noise=n) for n in (0.2, 0.6)]})
    >>> [r.action for r in recognise_many(px, [synthetic_motion(2, (0,), seed=1, noise=0.4),
    ...                                        synthetic_motion(2, (1,), seed=2, noise=0.4)])]
    ['a', 'b']
    """
    out = _recognitions(praxicon, motions, explain=explain)
    for r in out:  # the first motion that cannot be recognised, as one error
        if isinstance(r, DescriptionError):
            raise r
    return out


def _recognitions(praxicon, motions, *, explain: int | None = 3) -> list:
    """:func:`recognise_many`, where a motion that cannot be recognised (too few frames, a
    feature that is not finite, no joint shared with the praxicon, scores that overflow) has
    its :class:`~praxicon.description.DescriptionError` in its place, so that the others are
    still recognised in the one call (``psgs praxicon recognise`` answers every good file). A
    praxicon that cannot be read still raises. ``praxicon`` may be the
    :class:`~praxicon._verdict.ScoreModels` of its descriptions, kept by a caller that
    recognises many batches (the models are then made once, not once per call).

    Examples
    --------
    >>> from kinetology import Motion, synthetic_motion
    >>> from praxicon.description import describe
    >>> px = describe({"a": [synthetic_motion(2, (0,), seed=1, noise=n) for n in (0.2, 0.6)],
    ...                "b": [synthetic_motion(2, (1,), seed=2, noise=n) for n in (0.2, 0.6)]})
    >>> good = synthetic_motion(2, (0,), seed=1, noise=0.4)
    >>> short = Motion(good.values[:2], good.channels, good.frame_rate, source="short")
    >>> [getattr(r, "action", str(r)) for r in _recognitions(px, [short, good])]
    ['short: 2 frames; recognising needs at least 3', 'a']
    """
    try:
        return _recognised(praxicon, motions, explain)
    except _Unscorable as exc:  # read from a folder: its descriptions' file named
        if isinstance(praxicon, (str, Path)):
            raise _in_file(exc, praxicon) from None
        raise


def _recognised(praxicon, motions, explain: int | None) -> list:
    """:func:`_recognitions`, the descriptions' numbers that cannot be scored with raised as
    an :class:`_Unscorable`."""
    models = praxicon if isinstance(praxicon, ScoreModels) else \
        ScoreModels(_descriptions(praxicon))
    descriptions = models.descriptions
    if any(a.window for a in descriptions.actions):
        raise DescriptionError("these are window descriptions (for parse); recognise needs the "
                               "whole-take descriptions")
    if explain is not None:  # None: every action explained (order[:None]), as before
        whole_number(explain, "explain")
    motions = motions_of(motions)
    out: list = [None] * len(motions)
    rows = {}
    for i, motion in enumerate(motions):  # one motion's features at a time: each may fail
        try:
            _frames(motion, "recognising")
            rows[i] = feature_rows([motion])[0]
        except DescriptionError as exc:
            out[i] = exc
    read = list(rows)
    for indices, columns, x in _by_features(descriptions, list(rows.values())):
        found = _recognise(models, [motions[read[k]] for k in indices], columns, x, explain)
        for k, r in zip(indices, found):
            out[read[k]] = r
    if descriptions.families is None:
        return out
    ranked = [i for i in read if isinstance(out[i], Recognition)]
    best = [out[i].ranking[0][0] for i in ranked]
    verdicts, overflows = _family_verdicts(descriptions, [rows[i] for i in ranked], best,
                                           models.families)
    for k, verdict in verdicts.items():
        i = ranked[k]
        out[i] = replace(out[i], action=best[k] if verdict.accepted else None,
                         penalty=verdict.penalty, threshold=verdict.threshold,
                         excess=verdict.excess, excess_group=verdict.group,
                         family=verdict.family)
    for k, reason in overflows.items():
        out[ranked[k]] = DescriptionError(f"{out[ranked[k]].source}: {reason}")
    return out


@dataclass(frozen=True)
class FamilyVerdict:
    """The "none of these" decision of a family's description: whether the take is accepted,
    the family, its distance per feature and threshold, its worst group over its limit."""

    family: str
    accepted: bool
    penalty: float
    threshold: float
    excess: float
    group: str


def family_verdicts(descriptions: Descriptions, rows, best) -> dict[int, FamilyVerdict]:
    """Per motion whose best action ``best[i]`` is a member of a family
    (``descriptions.family_of``), the verdict of that family's description: the test the
    action's own description would make (its distance per feature under the threshold and
    no telling feature group past its limit), made with the family's.

    ``rows`` are the motions' feature rows (:func:`~praxicon.description.feature_rows`);
    motions whose best action is alone in its family are left out of the answer.

    Examples
    --------
    >>> from kinetology import synthetic_motion
    >>> from praxicon.description import describe, feature_rows
    >>> takes = {name: [synthetic_motion(3, joints, period=period, seed=s) for s in seeds]
    ...          for name, joints, period, seeds in (("a.slow", (0,), 1.3, (1, 2, 3)),
    ...                                              ("a.fast", (0,), 0.8, (4, 5, 6)),
    ...                                              ("b", (2,), 1.0, (7, 8, 9)))}
    >>> d = describe(takes, families={"a.slow": "a", "a.fast": "a"})
    >>> new = [synthetic_motion(3, (0,), period=1.0, seed=10), synthetic_motion(3, (2,), seed=11)]
    >>> verdicts = family_verdicts(d, feature_rows(new), ["a.slow", "b"])
    >>> sorted(verdicts), verdicts[0].family  # b is alone: decided by its own description
    ([0], 'a')
    """
    out, overflows = _family_verdicts(descriptions, rows, best)
    for i, reason in overflows.items():
        raise DescriptionError(f"motion {i + 1}: {reason}")
    return out


def _family_verdicts(descriptions: Descriptions, rows, best, models=None):
    """:func:`family_verdicts`, and per motion whose scores against the families overflow
    (left out of the verdicts) the reason (:func:`~praxicon.scoring.overflow_reason`);
    ``models``: the families' :class:`~praxicon._verdict.ScoreModels`, when kept."""
    families = descriptions.families
    if families is None:
        return {}, {}
    models = ScoreModels(families) if models is None else models
    of = dict(zip(descriptions.names, descriptions.family_of))
    index = {n: k for k, n in enumerate(families.names)}
    wanted = [i for i, b in enumerate(best) if of.get(b)]
    out, overflows = {}, {}
    for indices, columns, x in _by_features(families, [rows[i] for i in wanted]):
        features = [families.spread.features[c] for c in columns]
        fitted, test = models(columns)
        chosen = np.array([index[of[best[wanted[k]]]] for k in indices], dtype=int)
        with np.errstate(over="ignore", invalid="ignore"):  # an overflow: said per motion
            dist, _ = model_scores(fitted, x, own_columns(features))
            accepted, penalty, excess, group, lost = _tested(families, features, x, chosen,
                                                             fitted, dist, test)
        for k, (i, f) in enumerate(zip(indices, chosen)):
            if lost[k]:
                overflows[wanted[i]] = overflow_reason(fitted, x[k], features, families.names)
                continue
            out[wanted[i]] = FamilyVerdict(families.names[f], bool(accepted[k]),
                                           float(penalty[k]), float(families.spread.threshold),
                                           float(excess[k]), group[k])
    return out, overflows


def _by_features(descriptions: Descriptions, rows):
    """The motions' feature rows grouped by which of the descriptions' features they have
    (one group per skeleton): ``(indices, columns, rows x columns)`` per group."""
    wanted = descriptions.spread.features
    same: dict[tuple, list[int]] = {}
    for i, row in enumerate(rows):
        same.setdefault(tuple(f in row for f in wanted), []).append(i)
    for present, indices in same.items():
        columns = np.array([c for c, p in enumerate(present) if p], dtype=int)
        x = np.array([[rows[i][wanted[c]] for c in columns] for i in indices], dtype=float)
        yield indices, columns, x.reshape(len(indices), len(columns))


def _recognise(models: ScoreModels, motions, columns, x, explain: int):
    """:func:`recognise_many` for motions that have the same ``columns`` of the features
    (scored with ``models``, the descriptions' :class:`~praxicon._verdict.ScoreModels`): per
    motion its :class:`Recognition`, or the error that says why it cannot have one."""
    descriptions = models.descriptions
    spread = descriptions.spread
    features = [spread.features[i] for i in columns]
    fitted, test = models(columns)
    compared = fitted.compared
    if not compared.any():  # each motion of this skeleton answered by its own error
        return [DescriptionError(f"{getattr(m, 'source', '<motion>')}: the motion shares no "
                                 f"joint with the praxicon's actions") for m in motions]
    # a feature too large to score overflows a square or a product (NaN, inf): silenced
    # here, and such a motion answered by its error below, the others as they are
    with np.errstate(over="ignore", invalid="ignore"):
        dist, score = model_scores(fitted, x, own_columns(features))
        p = probabilities(score, spread.temperature, spread.tail)
        per_feature = dist / len(columns)
        # ranked by the score, not by its probability: far from every action, the
        # probabilities of all but the best underflow to 0 and would leave the rest in the
        # order learnt
        best_of = score.argmin(axis=1) if len(score) else np.zeros(0, dtype=int)
        accepted, _, excess, excess_group, lost = _tested(descriptions, features, x, best_of,
                                                          fitted, dist, test)
    lost |= unscored(fitted, score)
    names = descriptions.names
    here = set(features)
    lacking = [tuple(sorted({feature_joint(f) for f in a.features if f not in here} - {"*"}))
               for a in descriptions.actions]
    unshared = tuple(names[a] for a in np.flatnonzero(~compared))
    n = len(columns)
    out = []
    for i, motion in enumerate(motions):
        if lost[i]:
            out.append(DescriptionError(f"{getattr(motion, 'source', '<motion>')}: "
                                        f"{overflow_reason(fitted, x[i], features, names)}"))
            continue
        # a joint the motion has is not missing (its root may not move, so that its travel
        # is not read): said apart from those it lacks
        has = _joints_of(motion)
        absent = [tuple(j for j in joints if j not in has) for joints in lacking]
        order = np.argsort(score[i], kind="stable")
        order = np.concatenate([order[compared[order]], order[~compared[order]]])
        best = int(order[0])  # best_of[i]: an action not compared has an infinite score
        action = names[best] if accepted[i] else None
        reasons, tempos, drifts = [], [], []
        body: dict[str, list] = {f: [] for f in _BODY}
        for a in order[:explain]:
            if not compared[a]:
                break
            positions, parts = fitted.block_of(a)
            shown = [features[k] for k in positions]
            # scaled as the action's distance is, so that its terms sum to that distance
            row, mean = _part(x[i], None, positions), _part(fitted.means[a], None, positions)
            terms = mahalanobis_terms(row, mean, parts)[0] * (n / len(positions))
            reasons.append((names[a], _reasons(shown, terms, row, mean)))
            tempo = [k for k, f in enumerate(shown) if f == "tempo"]
            drift = [k for k, f in enumerate(shown) if f.endswith(":drift")]
            tempos.append((names[a], round(float(terms[tempo].sum()), 3)))
            # the drift's part of the shared distance and of the action's own-spread term
            drifts.append((names[a], round(float(terms[drift].sum() + score[i, a]
                                                 - dist[i, a]), 3)))
            for feature, read_back in _BODY.items():
                if feature in shown:
                    k = shown.index(feature)
                    body[feature].append((names[a], round(float(terms[k]), 3),
                                          round(read_back(float(mean[k])), 4)))
        own = {feature: round(read_back(float(x[i, features.index(feature)])), 4)
               if feature in here else None for feature, read_back in _BODY.items()}
        out.append(Recognition(
            getattr(motion, "source", "<motion>"), action,
            tuple((names[a], float(p[i, a])) for a in order),
            float(per_feature[i, best]), float(spread.threshold), absent[best],
            tuple(reasons), tuple(tempos), tuple(drifts), float(excess[i]), excess_group[i],
            tuple((names[a], absent[a]) for a in order[:explain] if compared[a]), unshared,
            flight=tuple(body["flight"]), off_ground=own["flight"],
            pace=tuple(body["pace"]), travel=own["pace"],
            unread=tuple(j for j in lacking[best] if j in has)))
    return out


def recognise(praxicon, motion, *, explain: int | None = 3) -> Recognition:
    """Which of the praxicon's actions ``motion`` is, or None for none of these.

    Parameters
    ----------
    praxicon : Praxicon, folder, or Descriptions
        The learnt actions.
    motion : kinetology.Motion or path
        The take (at least 3 frames).
    explain : int or None, default 3
        For how many of the best actions the per-joint reasons are kept (None: for every
        action).

    Returns
    -------
    Recognition

    Raises
    ------
    DescriptionError
        When the motion has fewer than 3 frames or shares no joint with any of the
        praxicon's actions (an action that shares none, learnt from another skeleton, is
        ranked last with probability 0 and named in ``Recognition.unshared``), when a value
        of it is too large to compute with (a feature that is not finite, or distances that
        overflow: the feature is named), or when the descriptions hold a number the scores
        cannot compute with (named, with the command that learns them again; and their file,
        when ``praxicon`` is a folder).
    OSError, MotionFormatError
        As :func:`kinetology.read` raises them, when ``motion`` is a path that cannot be read
        or is not motion (``MotionFormatError`` is a ``ValueError``).

    Examples
    --------
    >>> from kinetology import synthetic_motion
    >>> from praxicon.description import describe
    >>> px = describe({"a": [synthetic_motion(2, (0,), seed=1, noise=n) for n in (0.2, 0.6)],
    ...                "b": [synthetic_motion(2, (1,), seed=2, noise=n) for n in (0.2, 0.6)]})
    >>> found = recognise(px, synthetic_motion(2, (1,), seed=2, noise=0.4))
    >>> found.action, found.ranking[0][0], found.missing
    ('b', 'b', ())
    """
    return recognise_many(praxicon, [motion], explain=explain)[0]
