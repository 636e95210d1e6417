"""The paper's learner's parameters, as one frozen value handed to each of its phases.

:class:`ContentConf` is the table of :class:`~psgs.induce.pal.learner.ContentPAL`
(every rule declared once, see :mod:`psgs.induce.conf`). The two rows both
PAL learners read, :data:`MIN_COPIES` and :data:`ALPHA`, are declared here once
and used by :class:`~psgs.induce.pal.motion.conf.MotionConf` too.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..conf import Choice, Conf, Number, Parameter, parameter
from ._engines import ENGINES, select

__all__ = ["ContentConf", "MIN_COPIES", "ALPHA", "TIMINGS"]

#: Fewest copies (of a motif, or cycles of a joint) that count as repetition.
MIN_COPIES = Parameter(3, Number(low=2, integer=True))
#: The chance level a repetition must beat.
ALPHA = Parameter(1e-2, Number(low=0, high=1, low_open=True))
#: How the paper's learner locates copies (see :class:`ContentConf`).
TIMINGS = ("content", "period", "auto")


def check_engine(name: str, value: object) -> None:
    """The rule of ``engine``: one of the engine names (numba's absence is told when run).

    Examples
    --------
    >>> check_engine("engine", "fortran")
    Traceback (most recent call last):
    ...
    ValueError: engine must be one of 'auto', 'numpy', 'numba', not 'fortran'
    """
    if not isinstance(value, str) or value not in ENGINES:
        select(value)  # raises the ValueError naming the engines


@dataclass(frozen=True)
class ContentConf(Conf):
    """The parameters of the paper's learner (one actiongram; ``docs/pal.md`` explains them).

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

    Examples
    --------
    >>> ContentConf(rounds=3).rounds
    3
    >>> ContentConf(timing="tempo")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: timing must be one of content, period, auto, not 'tempo'
    """

    min_copies: int = MIN_COPIES.field()
    conserve: float = parameter(0.6, Number(low=0, high=1, low_open=True))
    edge_share: float = parameter(0.5, Number(low=0, high=1))
    column_alpha: float = parameter(1e-3, Number(low=0, high=1))
    match_fraction: float = parameter(0.5, Number(low=0, high=1, low_open=True))
    scan_alpha: float = parameter(0.05, Number(low=0, low_open=True))
    alpha: float = ALPHA.field()
    sync_fraction: float = parameter(0.5, Number(low=0, high=1, low_open=True))
    window_support: float = parameter(0.34, Number(low=0, high=1))
    max_pattern: int = parameter(64, Number(low=2, integer=True))
    seeds: int = parameter(3, Number(low=1, integer=True))
    rounds: int = parameter(2, Number(low=1, integer=True))
    joins_copies: int = parameter(4, Number(low=2, integer=True))
    timing: str = parameter("auto", Choice(TIMINGS))
    period_quantile: float = parameter(0.9, Number(low=0, high=1))
    period_agreement: float = parameter(0.6, Number(low=0, high=1, low_open=True))
    engine: str = parameter("auto", check_engine, recorded=False)
