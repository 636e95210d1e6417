"""The real-motion learner: which joints perform an action, from several performances.

:class:`MotionPAL` (registered as ``"pal_motion"``) reads performances of one
action, each its own actiongram of kineteme strings grouped by joint, never
joined into one stream: evidence across the performances and within them
(:mod:`~psgs.induce.pal.motion.performances`, :mod:`~psgs.induce.pal.motion.cycles`),
the joints that take part, and their patterns with typical durations
(:mod:`~psgs.induce.pal.motion.morphemes`). Every phase is handed the one
frozen :class:`~psgs.induce.pal.motion.conf.MotionConf`; what it learnt is
read back by :func:`~psgs.induce.pal.motion.locate.locate`.
"""

from __future__ import annotations

from dataclasses import replace

from ....actiongram import Actiongram
from ....errors import BoundReached
from ...base import Inducer, as_performances
from ...results import NO_REPETITION, Induction, StringReport
from ..conf import bounds, stop_reason, undecided
from .conf import MotionConf
from .performances import learn_motion
from .results import ActuatorReport, Morpheme

__all__ = ["MotionPAL", "learn_performances", "same_strings"]


class MotionPAL(Inducer):
    """The real-motion learner (``"pal_motion"``; see the module docstring and ``docs/pal.md``).

    :class:`~psgs.induce.PAL` runs it for several performances (or one, with
    ``timing="performances"``). Its parameter table, with each rule, is
    :class:`~psgs.induce.pal.motion.conf.MotionConf`.

    Parameters
    ----------
    min_copies : int, default 3
        Fewest cycles within a performance that count as repetition.
    alpha : float, default 1e-2
        Chance level a joint's repetition must beat (Bonferroni over channels and joints).
    evidence : {"kinetemes", "path"}, default "kinetemes"
        What a joint's repeated motion is measured on: ``"kinetemes"`` (chance-corrected
        agreement of the kineteme states, with a significance test) or ``"path"`` (plain
        angular path length, no test: the benchmark's ablation).
    joint_share : float, default 0.25
        A significant joint carrying at least this share of the leader's repeated motion is
        a component.
    neighbour_share : float, default 0.03
        A skeleton neighbour (one hop) of a component joins at this share of the leader's
        repeated motion.
    channel_share : float, default 0.25
        A component joint keeps its channels carrying at least this share of its most
        repeated channel's motion.
    max_shift : float, default 0.1
        Whole performances are aligned by a shift of at most this share of their length.
    min_cycle : float, default 0.25
        Shortest cycle within a performance, seconds.
    min_cycle_score : float, default 0.05
        A joint whose best cycle score is no higher does not cycle (no period).
    max_seconds : float or None, default None
        A wall-clock bound on the induction (None: none), read for each performance
        sampled, aligned and scored and for each leader tried. Past it the learner stops
        with no component (the joints are chosen at the end): the Induction's ``bound`` is
        ``"max_seconds"`` and every string is ``"not decided: stopped at max_seconds"``.
    max_bytes : float or None, default None
        A bound on the bytes of the performances' time grids (None: none), counted, not
        measured: 24 bytes a channel a grid point a performance (its state, velocity and
        cycle score; a performance has at most 4096 points, and every other array is
        smaller), before each performance is sampled. A performance that would pass it is
        not: the learner stops as at ``max_seconds``, with ``bound`` ``"max_bytes"``.

    Examples
    --------
    >>> from psgs.induce.synthetic import generate
    >>> takes = [generate(seed=1).actiongram, generate(seed=2).actiongram]
    >>> result = MotionPAL().induce(takes)
    >>> result.performances, result.inducer
    (2, 'pal_motion')
    >>> MotionPAL(evidence="angles")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: evidence must be one of kinetemes, path, not 'angles'
    """

    name = "pal_motion"
    Conf = MotionConf

    def induce(self, performances) -> Induction:
        """Learn which joints perform the action, and their patterns.

        Parameters
        ----------
        performances : Actiongram or sequence of Actiongram
            Performances of one action (one is allowed: its cycles are then the
            only copies). A string a performance lacks is empty there.

        Returns
        -------
        Induction

        Raises
        ------
        TypeError
            When the input is not an actiongram or a sequence of them.
        ValidationError
            For an empty sequence.
        """
        takes = as_performances(same_strings(performances), "MotionPAL.induce")
        return learn_performances(self, self.conf(), takes)


def same_strings(performances):
    """Performances given with different strings get every string (a missing one empty).

    Segmentation leaves out the channels that hardly move in a take, so takes
    of one action can name different strings; a string a performance lacks is
    empty there (no information, no motion), in the order of first appearance.
    Anything else is given back unchanged (for :func:`~psgs.induce.base.as_performances`
    to check).

    Examples
    --------
    >>> a = Actiongram.from_strings({"knee": "abab"})
    >>> b = Actiongram.from_strings({"hip": "xy"})
    >>> [p.names for p in same_strings([a, b])], same_strings([a, b])[1].string("knee")
    ([('knee', 'hip'), ('knee', 'hip')], ())
    """
    if isinstance(performances, Actiongram) or not isinstance(performances, (list, tuple)) \
            or not all(isinstance(p, Actiongram) for p in performances):
        return performances
    union = list(dict.fromkeys(n for p in performances for n in p.names))
    if all(p.names == tuple(union) for p in performances):
        return performances
    owner = {n: p.actuator(n) for p in reversed(performances) for n in p.names}
    out = []
    for p in performances:
        have = set(p.names)
        skeleton = p.skeleton_edges or next((q.skeleton_edges for q in performances
                                             if q.skeleton_edges), ())
        out.append(Actiongram(
            tuple(union), tuple(p.string(n) if n in have else () for n in union),
            tuple(p.durations[n] if n in have else () for n in union),
            tuple(p.origins[p.index(n)] if n in have else 0.0 for n in union),
            tuple(p.displacements(n) if n in have else None for n in union),
            tuple(owner[n] for n in union), skeleton, keep_repeats=p.keep_repeats))
    return out


def learn_performances(inducer: Inducer, conf: MotionConf, takes: tuple[Actiongram, ...]
                       ) -> Induction:
    """The real-motion learner on ``takes``, its Induction ended by ``inducer``.

    Parameters
    ----------
    inducer : Inducer
        Whose name and recorded parameters the Induction carries.
    conf : MotionConf
        The parameters every phase reads.
    takes : tuple of Actiongram
        The performances, with the same strings in the same order
        (:func:`same_strings`, then :func:`~psgs.induce.base.as_performances`).

    Returns
    -------
    Induction
        With the joints that take part (``actuators``), their channels,
        morphemes and a report per joint.

    Examples
    --------
    >>> from psgs.induce.synthetic import generate
    >>> takes = (generate(seed=1).actiongram, generate(seed=2).actiongram)
    >>> learner = MotionPAL()
    >>> learn_performances(learner, learner.conf(), takes) == learner.induce(takes)
    True
    """
    # started first: max_seconds covers everything the caller waits for
    clock = bounds(conf)
    try:
        found = learn_motion(takes, conf, clock)
    except BoundReached as stop:
        status = undecided(stop.bound)
        result = inducer.build_induction(
            takes[0].names, {}, {}, [StringReport(name, status) for name in takes[0].names],
            synchronise=True, performances=len(takes))
        return replace(result, verdict=f"no component found before {stop.bound}",
                       bound=stop.bound,
                       reason=f"{stop_reason(stop.bound, conf)}, before the joints were chosen")
    first = takes[0]
    names = first.names
    symbols = found.symbols
    kept = sorted(row for row in found.patterns)
    chosen = {j.name: j for j in found.joints}
    reports = []
    for row, name in enumerate(names):
        joint = chosen[first.actuator(name)]
        if row in found.patterns:
            status = "component"
        elif joint.status.startswith("component"):
            status = "carries little of its joint's repeated motion"
        else:
            status = f"{joint.status} (joint {joint.name})" if found.verdict == "" \
                else f"{found.verdict} ({joint.status}, joint {joint.name})"
        reports.append(StringReport(name=name, status=status, copies=len(
            found.occurrences.get(row, ())), significance=joint.log10_p,
            synchronised_with=tuple(names[k] for k in kept if k != row) if row in kept else ()))
    patterns = {names[i]: tuple(symbols[c] for c in found.patterns[i]) for i in kept}
    result = inducer.build_induction(
        names, patterns, {names[i]: found.occurrences[i] for i in kept}, reports,
        synchronise=True, performances=len(takes),
        occurrence_performance={names[i]: found.occurrence_performance[i] for i in kept})
    # the joints chosen take part even when a channel's copies agree on too little to
    # give it a pattern of two kinetemes (then it has no component of its own)
    actuators = tuple(a for a in first.actuators if a in found.channels)
    morphemes = {names[i]: Morpheme(patterns[names[i]], found.durations[i],
                                    None if all(d is None for d in first.segment_displacements)
                                    else found.displacements[i]) for i in kept}
    joint_reports = tuple(ActuatorReport(j.name, j.status, share=j.share,
                                         significance=j.log10_p,
                                         repeated=j.repeated, path=j.path)
                          for j in found.joints)
    return replace(result, actuators=actuators,
                   actuator_channels={a: tuple(names[i] for i in found.channels[a])
                                      for a in actuators},
                   morphemes=morphemes, verdict=found.verdict or ("" if kept else NO_REPETITION),
                   actuator_reports=joint_reports)
