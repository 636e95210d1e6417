"""The paper's learner's parameters, as one frozen value handed to each of its phases.

:class:`ContentConf` is the table of :class:`~psgs.induce.pal.learner.ContentPAL`
(every rule declared once, see :mod:`psgs.induce.conf`). The rows both
PAL learners read, :data:`MIN_COPIES`, :data:`ALPHA` and :data:`MAX_SECONDS`, are declared
here once and used by :class:`~psgs.induce.pal.motion.conf.MotionConf` too.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..conf import Choice, Conf, Number, Parameter, parameter
from ...budget import Budget
from ..._foundation.engines import ENGINES, resolve

__all__ = ["ContentConf", "MIN_COPIES", "ALPHA", "MAX_SECONDS", "NO_BOUND", "UNDECIDED",
           "TIMINGS", "SECTION_DURATIONS"]

#: Fewest copies (of a motif, or cycles of a joint) that count as repetition.
MIN_COPIES = Parameter(3, Number(low=2, integer=True))
#: The chance level a repetition must beat.
ALPHA = Parameter(1e-2, Number(low=0, high=1, low_open=True))
#: A wall-clock bound on one induction, seconds (None: none). Not recorded: an Induction it
#: stops names it in its ``bound``, and one it does not stop is the same without it.
MAX_SECONDS = Parameter(None, Number(low=0, low_open=True, optional=True), recorded=False)
#: The status of a string that is no component of an induction stopped at ``max_seconds``: a
#: stage that did not run (the sections, the joins, the choice of joints) might have made it one.
UNDECIDED = "not decided: stopped at max_seconds"
#: The clock a phase reads when it is handed none: no deadline, so ``check()`` reads no clock
#: and never raises (shared: ``check`` changes nothing in it).
NO_BOUND = Budget()
#: How the paper's learner locates copies (see :class:`ContentConf`).
TIMINGS = ("content", "period", "auto")
#: What a section's copies must repeat (see :class:`ContentConf`): the symbols, or the
#: symbols and their durations alike.
SECTION_DURATIONS = ("any", "equal")


def check_engine(name: str, value: object) -> None:
    """The rule of ``engine``: one of the engine names (numba's absence is told when run).

    Examples
    --------
    >>> check_engine("engine", "fortran")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: engine must be one of 'auto', 'numpy', 'numba', not 'fortran'
    """
    if not isinstance(value, str) or value not in ENGINES:
        resolve(value)  # raises the ValidationError naming the engines


@dataclass(frozen=True)
class ContentConf(Conf):
    """The parameters of the paper's learner, each with its rule (their meaning:
    :class:`~psgs.induce.pal.learner.ContentPAL`; ``docs/pal.md``).

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
    copy_agreement: float = parameter(0.5, Number(low=0, high=1))
    section_durations: str = parameter("any", Choice(SECTION_DURATIONS))
    timing: str = parameter("auto", Choice(TIMINGS))
    period_quantile: float = parameter(0.9, Number(low=0, high=1))
    period_agreement: float = parameter(0.6, Number(low=0, high=1, low_open=True))
    max_seconds: float | None = MAX_SECONDS.field()
    engine: str = parameter("auto", check_engine, recorded=False)
