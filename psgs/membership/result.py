"""What :func:`psgs.accepts` answers: an :class:`Acceptance`.

A yes carries the schedule the search found (:mod:`psgs.membership.witness`),
from which the witness derivation is rebuilt, every step checked, on demand.
"""

from __future__ import annotations

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

    >>> Acceptance("unknown", reason="out of time", bound="max_seconds").answer
    'unknown'
    >>> bool(Acceptance("no", reason="too short"))
    False
    """

    answer: Literal["yes", "no", "unknown"]
    reason: str | None = None
    bound: str | None = None
    states: int = 0
    system: PSGS | PCGS | None = field(default=None, repr=False, compare=False)
    schedule: Schedule | None = field(default=None, repr=False, compare=False)

    def __bool__(self) -> bool:
        return self.answer == "yes"

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
