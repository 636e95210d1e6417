"""The paper's learner's parameters, as one frozen value handed to each of its phases.

:class:`ContentConf` is the table of :class:`~psgs.induce.pal.learner.ContentPAL`
(every rule declared once, see :mod:`psgs.induce.conf`). The rows both
PAL learners read, :data:`MIN_COPIES`, :data:`ALPHA`, :data:`MAX_SECONDS` and
:data:`MAX_BYTES`, are declared here once and used by
:class:`~psgs.induce.pal.motion.conf.MotionConf` too, as are the budgets both learners run on
(:class:`Bounds`) and the words of a stop (:func:`stop_reason`, :func:`undecided`).
"""

from __future__ import annotations

from dataclasses import dataclass

from ..conf import Choice, Conf, Number, Parameter, parameter
from ...budget import Budget
from ...errors import BoundReached
from ..._foundation.engines import ENGINES, resolve

__all__ = ["ContentConf", "MIN_COPIES", "ALPHA", "MAX_SECONDS", "MAX_BYTES", "NO_BOUND",
           "UNDECIDED", "TIMINGS", "SECTION_DURATIONS", "SECTION_SEARCHES", "Bounds", "bounds",
           "stop_reason", "undecided"]

#: Fewest copies (of a motif, or cycles of a joint) that count as repetition.
MIN_COPIES = Parameter(3, Number(low=2, integer=True))
#: The chance level a repetition must beat.
ALPHA = Parameter(1e-2, Number(low=0, high=1, low_open=True))
#: A wall-clock bound on one induction, seconds (None: none). Not recorded: an Induction it
#: stops names it in its ``bound``, and one it does not stop is the same without it.
MAX_SECONDS = Parameter(None, Number(low=0, low_open=True, optional=True), recorded=False)
#: A bound on the bytes of the working data of one induction that grow faster than its input,
#: counted from their sizes as they are made (None: none; see :class:`Bounds`). Not recorded,
#: as ``max_seconds`` is not.
MAX_BYTES = Parameter(None, Number(low=0, low_open=True, optional=True), recorded=False)
#: How the paper's learner locates copies (see :class:`ContentConf`).
TIMINGS = ("content", "period", "auto")
#: What a section's copies must repeat (see :class:`ContentConf`): the symbols, or the
#: symbols and their durations alike.
SECTION_DURATIONS = ("any", "equal")
#: how sections are looked for: in each string alone, or in pairs of strings as well
SECTION_SEARCHES = ("own", "pairs")


def undecided(bound: str) -> str:
    """The status of a string that is no component of an induction stopped at ``bound``: a
    stage that did not run (the sections, the joins, the choice of joints) might have made it
    one.

    Examples
    --------
    >>> undecided("max_bytes")
    'not decided: stopped at max_bytes'
    """
    return f"not decided: stopped at {bound}"


#: :func:`undecided` at ``max_seconds``.
UNDECIDED = undecided("max_seconds")


def stop_reason(bound: str, conf) -> str:
    """An Induction's ``reason`` when ``bound`` (``"max_seconds"`` or ``"max_bytes"``) stopped
    a learner run with ``conf``: the bound and its value, in the words both learners use.

    Examples
    --------
    >>> stop_reason("max_seconds", ContentConf(max_seconds=2))
    'stopped after 2 seconds (max_seconds)'
    >>> stop_reason("max_bytes", ContentConf(max_bytes=1e9))
    'stopped at 1e+09 bytes (max_bytes)'
    >>> stop_reason("max_bytes", ContentConf(max_bytes=1))
    'stopped at 1 byte (max_bytes)'
    """
    if bound == "max_seconds":
        value = conf.max_seconds
        return f"stopped after {value:g} second{'' if value == 1 else 's'} (max_seconds)"
    value = conf.max_bytes
    return f"stopped at {value:g} byte{'' if value == 1 else 's'} (max_bytes)"


class Bounds(Budget):
    """The budgets of one PAL induction: :class:`~psgs.budget.Budget`'s wall clock
    (``max_seconds``) and an account of the bytes of its working data that grow faster than
    its input (``max_bytes``).

    The bytes are counted, not measured: a step adds the size of what it makes, at the
    sizes the learners' docstrings state, before it makes it (so the bound is the same on
    every machine and every run, and a step that would pass it does not run).
    :meth:`keep` adds bytes kept to the end of the induction and raises
    ``BoundReached("max_bytes")`` past ``max_bytes``; without one it counts nothing (so
    that :data:`NO_BOUND` is shared: nothing changes in it).

    Examples
    --------
    >>> from psgs.errors import BoundReached
    >>> budget = Bounds(max_bytes=100)
    >>> budget.keep(60)
    >>> try:
    ...     budget.keep(60)
    ... except BoundReached as stop:
    ...     print(stop.bound, budget.kept)
    max_bytes 120
    """

    __slots__ = ("max_bytes", "kept")

    def __init__(self, seconds: float | None = None, max_bytes: float | None = None) -> None:
        super().__init__(seconds)
        self.max_bytes = max_bytes
        self.kept = 0

    def keep(self, count: int) -> None:
        """Account for ``count`` bytes more kept; raise ``BoundReached("max_bytes")`` past
        ``max_bytes``."""
        if self.max_bytes is None:
            return
        self.kept += count
        if self.kept > self.max_bytes:
            raise BoundReached("max_bytes")


#: The budgets a phase reads when it is handed none: no deadline, so ``check()`` reads no
#: clock and never raises, and no byte bound, so ``keep()`` counts nothing (shared: neither
#: changes anything in it).
NO_BOUND = Bounds()


def bounds(conf) -> Bounds:
    """The budgets of one induction with ``conf`` (its ``max_seconds`` and ``max_bytes``),
    started now: :data:`NO_BOUND` when it has neither.

    Examples
    --------
    >>> bounds(ContentConf()) is NO_BOUND
    True
    >>> bounds(ContentConf(max_bytes=1e6)).max_bytes
    1000000.0
    """
    if conf.max_seconds is None and conf.max_bytes is None:
        return NO_BOUND
    return Bounds(conf.max_seconds, conf.max_bytes)


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
    section_search: str = parameter("own", Choice(SECTION_SEARCHES))
    timing: str = parameter("auto", Choice(TIMINGS))
    period_quantile: float = parameter(0.9, Number(low=0, high=1))
    period_agreement: float = parameter(0.6, Number(low=0, high=1, low_open=True))
    max_seconds: float | None = MAX_SECONDS.field()
    max_bytes: float | None = MAX_BYTES.field()
    engine: str = parameter("auto", check_engine, recorded=False)
