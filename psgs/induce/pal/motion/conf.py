"""The real-motion learner's parameters, as one frozen value handed to each of its phases.

:class:`MotionConf` is the table of :class:`~psgs.induce.pal.motion.learner.MotionPAL`;
:func:`~psgs.induce.pal.motion.locate.locate` reads it back from what an
Induction recorded (:meth:`MotionConf.of`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from ...conf import Choice, Conf, Number, parameter
from ..conf import ALPHA, MAX_BYTES, MAX_SECONDS, MIN_COPIES

__all__ = ["MotionConf", "LEARNERS"]

#: The inducers whose Inductions record the real-motion learner's parameters: PAL
#: (which hands several performances to it) and the learner itself.
LEARNERS = ("pal", "pal_motion")


@dataclass(frozen=True)
class MotionConf(Conf):
    """The parameters of the real-motion learner, each with its rule (their meaning:
    :class:`~psgs.induce.pal.motion.learner.MotionPAL`; ``docs/pal.md``).

    Examples
    --------
    >>> MotionConf(joint_share=0.3).evidence
    'kinetemes'
    >>> MotionConf(max_shift=0.7)
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: parameter max_shift must be <= 0.5, not 0.7
    """

    min_copies: int = MIN_COPIES.field()
    alpha: float = ALPHA.field()
    evidence: str = parameter("kinetemes", Choice(("kinetemes", "path")))
    joint_share: float = parameter(0.25, Number(low=0, high=1, low_open=True))
    neighbour_share: float = parameter(0.03, Number(low=0, high=1))
    channel_share: float = parameter(0.25, Number(low=0, high=1))
    max_shift: float = parameter(0.1, Number(low=0, high=0.5))
    min_cycle: float = parameter(0.25, Number(low=0))
    min_cycle_score: float = parameter(0.05, Number(low=0, high=1))
    max_seconds: float | None = MAX_SECONDS.field()
    max_bytes: float | None = MAX_BYTES.field()

    @classmethod
    def of(cls, inducer: str, params: Mapping[str, object]) -> MotionConf:
        """The parameters an Induction of ``inducer`` was learnt with (defaults otherwise).

        Parameters
        ----------
        inducer : str
            ``Induction.inducer``.
        params : mapping
            ``Induction.params``.

        Returns
        -------
        MotionConf
            Read from ``params`` when ``inducer`` is one of :data:`LEARNERS`;
            the defaults for any other inducer (whose parameters mean other things).

        Examples
        --------
        >>> MotionConf.of("pal", {"joint_share": 0.4, "rounds": 2}).joint_share
        0.4
        >>> MotionConf.of("sequential", {"alpha": 0.5}).alpha
        0.01
        """
        return cls.pick(params) if inducer in LEARNERS else cls()
