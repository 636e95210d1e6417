"""PAL's real-motion learner: which joints perform an action, from several performances.

The recipe, on kineteme strings grouped by joint (each performance its own
actiongram, never joined into one stream): evidence of repeated motion across
the performances and within them (:mod:`~psgs.induce.pal.motion.performances`,
:mod:`~psgs.induce.pal.motion.cycles`, on the time grids of
:mod:`~psgs.induce.pal.motion.grids`), the joints that take part, and the
pattern of each of their channels with typical durations
(:mod:`~psgs.induce.pal.motion.morphemes`). :class:`MotionPAL` is the learner
(``"pal_motion"``), :class:`MotionConf` its parameters; :func:`locate` finds
what it learnt in new motion, reading the Induction (its patterns, morphemes,
joints and recorded parameters). The result types only this learner fills
in, :class:`ActuatorReport` and :class:`Morpheme`, live here too.
"""

from .conf import MotionConf
from .learner import MotionPAL
from .locate import Located, locate
from .results import ActuatorReport, Morpheme

__all__ = ["MotionPAL", "MotionConf", "locate", "Located", "ActuatorReport", "Morpheme"]
