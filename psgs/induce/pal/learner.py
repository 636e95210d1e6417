"""PAL, the learner: its parameters and ``induce`` as a short sequence of named phases."""

from __future__ import annotations

from dataclasses import replace

from ...actiongram import Actiongram
from ..base import Inducer, as_performances, check_choice, check_number
from ..results import ActuatorReport, Induction, Morpheme, StringReport
from ._encoding import encode
from ._engines import ENGINES, select
from .content import ContentResult, find_candidates, pool_groups
from .motifs import Timed
from .performances import NO_REPETITION, learn_motion
from .period import period_mode

__all__ = ["PAL"]

_TIMINGS = ("content", "period", "auto", "performances")
_EVIDENCE = ("kinetemes", "path")


class PAL(Inducer):
    """The parallel learning algorithm (see the module docstring and ``docs/pal.md``).

    Parameters
    ----------
    min_copies : int, default 3
        Fewest copies of a motif that count as repetition.
    conserve : float, default 0.6
        Share of copies that must agree on a new column.
    edge_share : float, default 0.5
        An end column of a voted pattern whose plurality symbol holds no more than this
        share of the copies is trimmed (it is not conserved), unless the group's members
        agree there beyond chance at level ``column_alpha``.
    column_alpha : float, default 1e-3
        Chance level (the members' plurality counts added over all their copies) below
        which an end column is kept, and a column beyond the shared windows added, however
        low its plurality share (heavy noise lowers every member's share at once); 0 turns
        it off.
    match_fraction : float, default 0.5
        Least share of positions a copy must match.
    scan_alpha : float, default 0.05
        Expected chance copies per string tolerated by the scan.
    alpha : float, default 1e-2
        Chance level a string's repetition must beat to be a candidate.
    sync_fraction : float, default 0.5
        Share of the merged copy clusters of two strings that must hold copies of both for
        them to be synchronised.
    window_support : float, default 0.34
        Share of a group's members that must show a copy in a window.
    max_pattern : int, default 64
        Longest motif, in symbols.
    seeds : int, default 3
        How many of a string's most frequent digrams are grown into motifs.
    rounds : int, default 2
        Rounds of pooling; after each but the last, every member's copies are located again
        with its voted pattern.
    joins_copies : int, default 4
        A string outside every group joins one when, read in the group's windows, at least
        this many of its copies have the common length and half of their columns agree,
        beyond chance, in a share ``conserve`` of them.
    timing : str, default "auto"
        How copies are located. ``"content"``: by content in each string, joined in time
        (steps 1-6); ``"period"``: by time windows of the action's period pooled over all
        strings (for real motion, where joints cycle through the same few states at
        different rates and phases); ``"auto"``: content, and the period mode when content
        finds no component.
    period_quantile : float, default 0.9
        The period mode's pooled excess self-agreement at each lag is this quantile over the
        strings (the driving joints decide).
    period_agreement : float, default 0.6
        In the period mode, least share of times at which a string's symbol recurs one
        (tracked) window later.
    evidence : str, default "kinetemes"
        For several performances of real motion, what a joint's repeated motion is measured
        on: ``"kinetemes"`` (chance-corrected agreement of the kineteme states, with a
        significance test) or ``"path"`` (plain angular path length, no test: the
        benchmark's ablation).
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
    engine : {"auto", "numpy", "numba"}, default "auto"
        What runs the content mode's motif search and synchronisation: numba's compiled
        loops (``"numba"``, all strings in one call; ``pip install 'psgs[fast]'``), numpy's
        array passes (``"numpy"``), or numba when it imports and numpy otherwise
        (``"auto"``). Every engine gives the same result, to the bit.

    Examples
    --------
    >>> from psgs.induce.synthetic import generate
    >>> case = generate(seed=1, noise=0.1)
    >>> result = PAL().induce(case.actiongram)
    >>> sorted(result.components) == sorted(case.components)
    True
    >>> PAL(engine="numpy").induce(case.actiongram) == result
    True
    >>> PAL(engine="fortran")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: engine must be one of 'auto', 'numpy', 'numba', not 'fortran'
    """

    name = "pal"

    def __init__(self, *, min_copies: int = 3, conserve: float = 0.6, edge_share: float = 0.5,
                 column_alpha: float = 1e-3,
                 match_fraction: float = 0.5, scan_alpha: float = 0.05, alpha: float = 1e-2,
                 sync_fraction: float = 0.5, window_support: float = 0.34,
                 max_pattern: int = 64, seeds: int = 3, rounds: int = 2,
                 joins_copies: int = 4, timing: str = "auto",
                 period_quantile: float = 0.9, period_agreement: float = 0.6,
                 evidence: str = "kinetemes", joint_share: float = 0.25,
                 neighbour_share: float = 0.03, channel_share: float = 0.25,
                 max_shift: float = 0.1, min_cycle: float = 0.25,
                 min_cycle_score: float = 0.05, engine: str = "auto") -> None:
        check_number("min_copies", min_copies, low=2, integer=True)
        check_number("conserve", conserve, low=0, high=1, low_open=True)
        check_number("edge_share", edge_share, low=0, high=1)
        check_number("column_alpha", column_alpha, low=0, high=1)
        check_number("match_fraction", match_fraction, low=0, high=1, low_open=True)
        check_number("scan_alpha", scan_alpha, low=0, low_open=True)
        check_number("alpha", alpha, low=0, high=1, low_open=True)
        check_number("sync_fraction", sync_fraction, low=0, high=1, low_open=True)
        check_number("window_support", window_support, low=0, high=1)
        check_number("max_pattern", max_pattern, low=2, integer=True)
        check_number("seeds", seeds, low=1, integer=True)
        check_number("rounds", rounds, low=1, integer=True)
        check_number("joins_copies", joins_copies, low=2, integer=True)
        check_choice("timing", timing, _TIMINGS)
        check_number("period_quantile", period_quantile, low=0, high=1)
        check_number("period_agreement", period_agreement, low=0, high=1, low_open=True)
        self.min_copies = min_copies
        self.conserve = conserve
        self.edge_share = edge_share
        self.column_alpha = column_alpha
        self.match_fraction = match_fraction
        self.scan_alpha = scan_alpha
        self.alpha = alpha
        self.sync_fraction = sync_fraction
        self.window_support = window_support
        self.max_pattern = max_pattern
        self.seeds = seeds
        self.rounds = rounds
        self.joins_copies = joins_copies
        self.timing = timing
        self.period_quantile = period_quantile
        self.period_agreement = period_agreement
        check_choice("evidence", evidence, _EVIDENCE)
        check_number("joint_share", joint_share, low=0, high=1, low_open=True)
        check_number("neighbour_share", neighbour_share, low=0, high=1)
        check_number("channel_share", channel_share, low=0, high=1)
        check_number("max_shift", max_shift, low=0, high=0.5)
        check_number("min_cycle", min_cycle, low=0)
        check_number("min_cycle_score", min_cycle_score, low=0, high=1)
        self.evidence = evidence
        self.joint_share = joint_share
        self.neighbour_share = neighbour_share
        self.channel_share = channel_share
        self.max_shift = max_shift
        self.min_cycle = min_cycle
        self.min_cycle_score = min_cycle_score
        if not isinstance(engine, str) or engine not in ENGINES:
            select(engine)  # raises the ValueError naming the engines
        self.engine = engine

    def induce(self, performances) -> Induction:
        """Learn a PSGS from an actiongram; see :class:`~psgs.induce.Induction`.

        Parameters
        ----------
        performances : Actiongram or sequence of Actiongram
            One actiongram (a sequence holding one is the same), or several
            performances of one action (never joined into one stream): then
            the real-motion learner of :mod:`psgs.induce.pal.performances`
            runs (also for one with ``timing="performances"``).

        Returns
        -------
        Induction
            Synchronised: every component repeats its pattern the same number of times.

        Raises
        ------
        TypeError
            When the input is not an actiongram or a sequence of them.
        ValidationError
            For an empty sequence, or performances whose actuators differ.
        """
        takes = as_performances(_same_strings(performances), "PAL.induce")
        if len(takes) > 1 or self.timing == "performances":
            return _from_performances(self, takes)
        actiongram = takes[0]
        strings, symbol_of = encode(actiongram)
        found = pool_groups(strings, find_candidates(strings, self), self)
        by_period = None
        if self.timing == "period" or (self.timing == "auto" and not found.patterns):
            by_period = self._period_phase(strings, len(symbol_of), found)
        reports = _reports(actiongram, found, by_period is not None or self.timing == "period",
                           symbol_of)
        patterns = {i: tuple(symbol_of[c] for c in codes) for i, codes in found.patterns.items()}
        return _result(self, actiongram, patterns, found.occurrences, reports)

    def _period_phase(self, strings: list[Timed], size: int, found: ContentResult):
        """Replace the content mode's findings by the period mode's (which may be none)."""
        by_period = period_mode(strings, size, self)
        found.patterns, found.occurrences, found.joined = {}, {}, {}
        if by_period is not None:
            for i, codes in by_period.patterns.items():
                found.patterns[i] = codes
                found.occurrences[i] = by_period.occurrences[i]
                found.partners[i] = [j for j in by_period.patterns if j != i]
        return by_period


def _same_strings(performances):
    """Performances given with different strings get every string (a missing one empty).

    Segmentation leaves out the channels that hardly move in a take, so takes
    of one action can name different strings; a string a performance lacks is
    empty there (no information, no motion), in the order of first appearance.
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
            tuple(owner[n] for n in union), skeleton))
    return out


def _reports(actiongram: Actiongram, found: ContentResult, period_used: bool,
             symbol_of: list[str]) -> tuple[StringReport, ...]:
    """One report per string: component, or the stage that dropped it."""
    reports = []
    partners = found.partners
    names = actiongram.names
    for i, name in enumerate(names):
        m = found.motifs[i]
        if i in found.patterns:
            status = "component"
            if i in found.joined:
                partners[i] = found.joined[i]
        elif period_used:
            status = "not in step with the period"
        elif m is None:
            status = "no repetition"
        elif i not in partners:
            status = "not significant"
        else:
            status = "not synchronised"
        reports.append(StringReport(
            name=name, status=status,
            motif=tuple([symbol_of[c] for c in m.motif.tolist()]) if m else (),
            copies=len(m.starts) if m else 0,
            significance=m.significance if m else 0.0,
            synchronised_with=tuple([names[j] for j in partners.get(i, ())])))
    return tuple(reports)


def _from_performances(inducer: PAL, takes: tuple[Actiongram, ...]) -> Induction:
    """The real-motion learner's findings as an Induction (see ``performances.py``)."""
    found = learn_motion(takes, inducer)
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
    return replace(result, params=_recorded(inducer), actuators=actuators,
                   actuator_channels={a: tuple(names[i] for i in found.channels[a])
                                      for a in actuators},
                   morphemes=morphemes, verdict=found.verdict or ("" if kept else NO_REPETITION),
                   actuator_reports=joint_reports)


def _result(inducer: PAL, actiongram: Actiongram, patterns: dict[int, tuple[str, ...]],
            occurrences: dict, reports: tuple[StringReport, ...]) -> Induction:
    """The Induction: components in actiongram order, their system and reports."""
    kept = tuple(sorted(patterns))
    names = actiongram.names
    result = inducer.build_induction(
        names, {names[i]: patterns[i] for i in kept},
        {names[i]: occurrences[i] for i in kept}, reports, synchronise=True)
    if not kept:
        return replace(result, params=_recorded(inducer), verdict=NO_REPETITION)
    owner = actiongram.string_actuators  # by index: a name lookup per string adds up
    channels: dict[str, list[str]] = {}
    for i in kept:
        channels.setdefault(owner[i], []).append(names[i])
    return replace(result, params=_recorded(inducer), actuators=tuple(channels),
                   actuator_channels={a: tuple(c) for a, c in channels.items()})


def _recorded(inducer: PAL) -> dict[str, object]:
    """The parameters an Induction records: all but ``engine``, which changes how PAL
    computes and never what it finds (so that every engine's Induction is equal)."""
    return {k: v for k, v in inducer.get_params().items() if k != "engine"}
