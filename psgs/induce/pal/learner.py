"""The paper's learner: a PSGS from one actiongram, its phases run in order.

:class:`ContentPAL` (registered as ``"pal_content"``) runs the steps of
:mod:`psgs.induce.pal` on one actiongram: motifs per string
(:mod:`~psgs.induce.pal.motifs`), the significance screen, synchronisation and
pooling (:mod:`~psgs.induce.pal.content`), and, when content finds nothing or
on request, the period mode (:mod:`~psgs.induce.pal.period`). Every phase is
handed the one frozen :class:`~psgs.induce.pal.conf.ContentConf`.
:func:`learn_content` is the learner without its class, for :class:`~psgs.induce.PAL`,
which hands it one actiongram.
"""

from __future__ import annotations

from dataclasses import replace

from ...actiongram import Actiongram
from ..._foundation.engines import for_input
from ...errors import BoundReached, ValidationError
from ..base import Inducer, as_performances
from ..results import NO_REPETITION, Induction, StringReport
from ._encoding import encode
from .conf import NO_BOUND, Bounds, ContentConf, bounds, stop_reason, undecided
from .choice import add_sections, keep_agreeing
from .content import LEFT_ALONE, ContentResult, find_candidates, pool_groups
from .motifs import Timed
from .period import period_mode

#: Symbols (over all strings) from which ``engine="auto"`` searches with numba in a fresh
#: process. Measured on a 2-core machine: numpy takes some 1.7 µs a symbol, numba 0.6 µs
#: once loaded, and reading its cache costs about 1.2 s a process, which an input of about
#: a million symbols repays.
CROSSOVER = 2 ** 20

__all__ = ["ContentPAL", "learn_content"]


class ContentPAL(Inducer):
    """The paper's learner, on one actiongram (``"pal_content"``; see :mod:`psgs.induce.pal`).

    :class:`~psgs.induce.PAL` runs it for one actiongram; use it directly to
    be sure the paper's protocol runs (several performances are refused, not
    handed to the real-motion learner). Its parameter table, with each rule,
    is :class:`~psgs.induce.pal.conf.ContentConf`.

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
        with its voted pattern (at most: a round that moves no copy ends the voting, since
        every round after it would repeat it).
    joins_copies : int, default 4
        A string outside every group joins one when, read in the group's windows, at least
        this many of its copies have the common length and half of their columns agree,
        beyond chance, in a share ``conserve`` of them.
    copy_agreement : float, default 0.5
        Least share of a pattern's positions a copy must agree with to be reported in
        ``occurrences``; a string left with fewer than ``min_copies`` such copies is no
        component.
    section_durations : {"any", "equal"}, default "any"
        What a section's copies (a string's long exact repeat, with ``min_copies=2`` a
        section played twice) must repeat. ``"any"``: the symbols; ``"equal"``: the
        symbols and each one's duration alike (to float rounding), so that a stream whose
        times mean something (music's notes, an event log's) does not count the same
        symbols in another rhythm as a repeat. Their significance stays that of the
        symbols alone (an upper bound on the chance of the stricter repeat).
    section_search : {"own", "pairs"}, default "own"
        Where sections are looked for. ``"own"``: each string's own longest repeat, grouped
        with the others' in step. ``"pairs"`` (with ``min_copies=2``): as well, for the
        strings no section group took, each string's exact repeats at least half as strong
        as a pair must be, every other such string read at the same times, the pair weighed
        as one event and as one string of both (so that, in this search, streams that move
        together are not counted twice); it finds a short section two strings play at the
        same times where either one's longest repeat lies elsewhere (``docs/streams.md``,
        "Sections found by pairs"), and shorter repeats that voices of music play together.
    timing : {"auto", "content", "period"}, default "auto"
        How copies are located. ``"content"``: by content in each string, joined in time;
        ``"period"``: by time windows of the action's period pooled over all strings (for
        real motion, where joints cycle through the same few states at different rates and
        phases); ``"auto"``: content, and the period mode when content finds no component.
    period_quantile : float, default 0.9
        The period mode's pooled excess self-agreement at each lag is this quantile over the
        strings (the driving joints decide).
    period_agreement : float, default 0.6
        In the period mode, least share of times at which a string's symbol recurs one
        (tracked) window later.
    engine : {"auto", "numpy", "numba"}, default "auto"
        What runs the motif search and synchronisation: numba's compiled loops (``"numba"``,
        all strings in one call; ``pip install 'psgs[fast]'``), numpy's array passes
        (``"numpy"``), or numba when it imports and numpy otherwise (``"auto"``). Every
        engine gives the same result, to the bit, so an Induction does not record it.
    max_seconds : float or None, default None
        A wall-clock bound on the induction (None: none), read at the head of its loops:
        each seed of a string's motif search (in a string of 2^19 symbols or more, each
        growth step and each column scanned too), each row of synchronisation pairs, each
        group pooled, each string's section search, each period tried. Past it the learner
        stops; the
        Induction's ``bound`` is ``"max_seconds"``, its ``reason`` says at which stage, its
        components are the groups pooled by then (their copies held to ``copy_agreement``,
        a group left with one member dropped) and every other string is ``"not decided:
        stopped at max_seconds"``. Not recorded in ``params``: an induction it does not
        stop is the same without it.
    max_bytes : float or None, default None
        A bound on the bytes of the working data that grow faster than the input (None:
        none), counted from their sizes as they are made, not measured (the same on every
        machine and every run): 32 bytes a pair of synchronised strings (motifs' and
        sections'; the pairs are up to the strings squared), and the period mode's time
        grid and FFTs (8 bytes a string a grid point and 32 a string a point of the
        transform, some 1.2 MB a string on the finest grid). The rest grows with the input
        alone and is not counted (measured: some 100 to 130 bytes a symbol in all; the
        compiled synchronisation tests its pairs a block of rows at a time, in a table of
        1 MB or one row). A step that would pass it does not run: the learner stops as at
        ``max_seconds``, ``bound`` ``"max_bytes"``, what was found by then kept, every other
        string ``"not decided: stopped at max_bytes"``. Not recorded in ``params``.

    Examples
    --------
    >>> from psgs.induce.synthetic import generate
    >>> case = generate(seed=1, noise=0.1)
    >>> result = ContentPAL().induce(case.actiongram)
    >>> sorted(result.components) == sorted(case.components), result.inducer
    (True, 'pal_content')
    >>> ContentPAL(engine="fortran")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: engine must be one of 'auto', 'numpy', 'numba', not 'fortran'
    """

    name = "pal_content"
    Conf = ContentConf

    def induce(self, performances) -> Induction:
        """Learn a PSGS from one actiongram; see :class:`~psgs.induce.Induction`.

        Parameters
        ----------
        performances : Actiongram or sequence of one Actiongram
            The actiongram.

        Returns
        -------
        Induction
            Synchronised: every component repeats its pattern the same number of times.

        Raises
        ------
        TypeError
            When the input is not an actiongram or a sequence of them.
        ValidationError
            For an empty sequence, or more than one performance (the paper's
            learner reads one actiongram; :class:`~psgs.induce.PAL` hands several
            to the real-motion learner).
        """
        takes = as_performances(performances, "ContentPAL.induce")
        if len(takes) > 1:
            raise ValidationError(f"ContentPAL.induce learns from one actiongram, got "
                                  f"{len(takes)} performances (PAL or MotionPAL learn from "
                                  f"several)")
        return learn_content(self, self.conf(), takes[0])


def learn_content(inducer: Inducer, conf: ContentConf, actiongram: Actiongram) -> Induction:
    """The paper's learner on ``actiongram``, its Induction ended by ``inducer``.

    Parameters
    ----------
    inducer : Inducer
        Whose name and recorded parameters the Induction carries.
    conf : ContentConf
        The parameters every phase reads.
    actiongram : Actiongram
        The one actiongram.

    Returns
    -------
    Induction

    Examples
    --------
    >>> from psgs.induce.synthetic import generate
    >>> case = generate(seed=2)
    >>> learner = ContentPAL()
    >>> learn_content(learner, learner.conf(), case.actiongram) == learner.induce(case.actiongram)
    True
    """
    # started first: max_seconds covers everything the caller waits for
    clock = bounds(conf)
    strings, symbol_of = encode(actiongram)
    conf = replace(conf, engine=for_input(conf.engine, sum(len(s.codes) for s in strings),
                                          CROSSOVER, "psgs.induce.pal._motifs_jit"))
    found, stage, before_sections = None, "the motif search and synchronisation", None
    try:
        found = find_candidates(strings, conf, clock)
        stage = "the pooling of synchronised strings"
        pool_groups(strings, found, conf, clock)
        if conf.timing != "period":
            stage = "the section search"
            # what add_sections changes before it can stop (never the components)
            before_sections = found.sections, found.section_partners, dict(found.dropped)
            add_sections(strings, found, conf, clock)
            before_sections = None
        by_period = None
        if conf.timing == "period" or (conf.timing == "auto" and not found.patterns):
            stage = "the period mode"
            by_period = _period_phase(strings, len(symbol_of), found, conf, clock)
    except BoundReached as stop:
        return _stopped(inducer, actiongram, strings, found, conf, symbol_of, stage,
                        before_sections, stop.bound)
    reports = _reports(actiongram, found, by_period is not None or conf.timing == "period",
                       symbol_of)
    return _ended(inducer, actiongram, found, reports, symbol_of)


def _ended(inducer: Inducer, actiongram: Actiongram, found: ContentResult,
           reports: tuple[StringReport, ...], symbol_of: list[str]) -> Induction:
    """The Induction of ``found``'s components, with ``reports`` and their agreements."""
    patterns = {i: tuple(symbol_of[c] for c in codes) for i, codes in found.patterns.items()}
    result = _result(inducer, actiongram, patterns, found.occurrences, reports)
    names = actiongram.names
    return replace(result, agreements={names[i]: found.agreements[i] for i in found.patterns
                                       if i in found.agreements})


def _stopped(inducer: Inducer, actiongram: Actiongram, strings: list[Timed],
             found: ContentResult | None, conf: ContentConf, symbol_of: list[str],
             stage: str, before_sections, bound: str) -> Induction:
    """The Induction of a learner stopped at ``bound`` (``max_seconds`` or ``max_bytes``)
    during ``stage``: the groups pooled by then, their copies held to ``copy_agreement`` as
    add_sections holds them."""
    reason = f"{stop_reason(bound, conf)}, in {stage}"
    status = undecided(bound)
    if found is None:  # nothing is pooled before the candidates are all found
        reports = tuple(StringReport(name=name, status=status) for name in actiongram.names)
        result = _result(inducer, actiongram, {}, {}, reports)
    else:
        if before_sections is not None:
            found.sections, found.section_partners, found.dropped = before_sections
        if conf.timing == "period":
            # the period mode's components replace the content mode's: those of a mode
            # that did not finish, none
            found.patterns, found.occurrences, found.agreements = {}, {}, {}
        elif stage != "the period mode":  # (timing="auto" runs it when content found none)
            _settle(strings, found, conf)
        reports = tuple(r if r.status == "component" else replace(r, status=status)
                        for r in _reports(actiongram, found, False, symbol_of))
        result = _ended(inducer, actiongram, found, reports, symbol_of)
    return replace(result, bound=bound, reason=reason,
                   verdict="" if result.components else f"no component found before {bound}")


def _settle(strings: list[Timed], found: ContentResult, conf: ContentConf) -> None:
    """Pooled groups that the section weighing never saw, held to ``copy_agreement``; a
    group it leaves with one member is no longer in step with anything."""
    keep_agreeing(strings, found, conf)
    for group in found.groups:
        left = [i for i in group if i in found.patterns]
        if len(left) == 1:
            i = left[0]
            del found.patterns[i], found.occurrences[i], found.spans[i], found.agreements[i]
            found.joined.pop(i, None)
            found.dropped[i] = LEFT_ALONE


def _period_phase(strings: list[Timed], size: int, found: ContentResult, conf: ContentConf,
                  clock: Bounds = NO_BOUND):
    """Replace the content mode's findings by the period mode's (which may be none)."""
    by_period = period_mode(strings, size, conf, clock)
    found.patterns, found.occurrences, found.joined, found.agreements = {}, {}, {}, {}
    if by_period is not None:
        for i, codes in by_period.patterns.items():
            found.patterns[i] = codes
            found.occurrences[i] = by_period.occurrences[i]
            found.partners[i] = [j for j in by_period.patterns if j != i]
    return by_period


def _reports(actiongram: Actiongram, found: ContentResult, period_used: bool,
             symbol_of: list[str]) -> tuple[StringReport, ...]:
    """One report per string: component, or the stage that dropped it.

    A string reported "not synchronised" has no partner at all; one that had
    partners and was dropped later says by which stage.
    """
    reports = []
    partners, section_partners = found.partners, found.section_partners
    sections = found.sections or [None] * len(found.motifs)
    names = actiongram.names
    for i, name in enumerate(names):
        m, section = found.motifs[i], sections[i]
        if i in found.from_sections or (m is None and section is not None):
            m = section  # the repetition the report is about
        if i in found.joined and i in found.patterns:
            partners[i] = found.joined[i]
        # (each section partner looked up in a set of the partners, not in their list: a
        # string in step with thousands has thousands of both)
        mates = partners.get(i, ())
        known = set(mates)
        synchronised = (*mates, *(j for j in section_partners.get(i, ()) if j not in known))
        if i in found.patterns:
            status = "component"
        elif period_used:
            status = "not in step with the period"
        elif i in found.dropped:
            status = found.dropped[i]
        elif i not in partners and i not in section_partners:
            status = "no repetition" if m is None else "not significant"
        elif not synchronised:
            status = "not synchronised"
        else:
            status = "synchronised, but no pattern kept"
        reports.append(StringReport(
            name=name, status=status,
            motif=tuple([symbol_of[c] for c in m.motif.tolist()]) if m else (),
            copies=len(m.starts) if m else 0,
            significance=m.significance if m else 0.0,
            synchronised_with=tuple([names[j] for j in synchronised])))
    return tuple(reports)


def _result(inducer: Inducer, actiongram: Actiongram, patterns: dict[int, tuple[str, ...]],
            occurrences: dict, reports: tuple[StringReport, ...]) -> Induction:
    """The Induction: components in actiongram order, their system and reports."""
    kept = tuple(sorted(patterns))
    names = actiongram.names
    result = inducer.build_induction(
        names, {names[i]: patterns[i] for i in kept},
        {names[i]: occurrences[i] for i in kept}, reports, synchronise=True)
    if not kept:
        return replace(result, verdict=NO_REPETITION)
    owner = actiongram.string_actuators  # by index: a name lookup per string adds up
    channels: dict[str, list[str]] = {}
    for i in kept:
        channels.setdefault(owner[i], []).append(names[i])
    return replace(result, actuators=tuple(channels),
                   actuator_channels={a: tuple(c) for a, c in channels.items()})
