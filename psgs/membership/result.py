"""What :func:`psgs.accepts` answers: an :class:`Acceptance`.

A yes carries the schedule the search found (:mod:`psgs.membership.witness`),
from which the witness derivation is rebuilt, every step checked, on demand.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from typing import Literal

from ..model import PCGS, PSGS
from .witness import Schedule, replay

__all__ = ["Acceptance"]


@dataclass(frozen=True)
class Acceptance:
    """The answer of :func:`psgs.accepts`.

    ``bool(result)`` is true only for ``answer == "yes"``. ``reason`` is a
    short sentence when the answer is ``"no"`` or ``"unknown"``; ``bound``
    names the budget that ran out (``"unknown"`` only). ``states`` counts the
    search states explored. ``witness`` is the derivation (a
    :class:`psgs.derivation.Derivation`, ``str()`` prints the paper's
    notation) when the answer is ``"yes"``: it is replayed from ``schedule``
    with :func:`psgs.derivation.apply_tuple`, which checks every step, on
    first access (at once for short words, see
    :data:`psgs.membership.EAGER_REPLAY_LIMIT`).

    Attributes
    ----------
    answer : {"yes", "no", "unknown"}
        The answer.
    reason : str or None, default None
        Why not, for ``"no"`` and ``"unknown"``.
    bound : str or None, default None
        The budget that ran out (``"unknown"`` only).
    states : int, default 0
        Search states explored.
    system : PSGS or PCGS, optional
        The system asked about (to replay the witness).
    plan : Schedule, or a function of no arguments that builds one, optional
        The schedule found (what the witness is replayed from), or how to build it: a
        search that found a long schedule leaves building it to the first access of
        ``schedule``.

    Examples
    --------
    >>> Acceptance("unknown", reason="out of time", bound="max_seconds").answer
    'unknown'
    >>> bool(Acceptance("no", reason="too short"))
    False

    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> result = psgs.accepts(gamma, ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad"])
    >>> result.answer, bool(result), result.bound
    ('yes', True, None)
    >>> str(result.witness).startswith("(S1, S2, S3, S4) ⇒")
    True
    >>> no = psgs.accepts(gamma, ["abcd", "bcad", "cdab", "abcd"])
    >>> no.answer, no.reason is not None
    ('no', True)
    """

    answer: Literal["yes", "no", "unknown"]
    reason: str | None = None
    bound: str | None = None
    states: int = 0
    system: PSGS | PCGS | None = field(default=None, repr=False, compare=False)
    plan: Schedule | Callable[[], Schedule] | None = field(default=None, repr=False,
                                                          compare=False)

    def __bool__(self) -> bool:
        return self.answer == "yes"

    @cached_property
    def schedule(self) -> Schedule | None:
        """The schedule found (``None`` unless the answer is yes), built on first access."""
        return self.plan() if callable(self.plan) else self.plan

    @cached_property
    def witness(self):
        """The witness derivation (``None`` unless the answer is yes)."""
        if self.answer != "yes":
            return None
        return replay(self.system, self.schedule)

    def __str__(self) -> str:
        if self.answer == "yes":
            return "yes"
        if self.answer == "no":
            return f"no: {self.reason}"
        return f"unknown: {self.reason}"
