"""PAL, the name users know: it hands one actiongram to the paper's learner, several
performances to the real-motion learner.

The two learners are inducers of their own (:class:`~psgs.induce.pal.learner.ContentPAL`,
:class:`~psgs.induce.pal.motion.learner.MotionPAL`), each with its frozen
parameter table. PAL's table is their union (:data:`PALConf`, every rule still
declared once, in the learner's table), with ``timing`` taking one more value,
``"performances"``, that sends one actiongram to the real-motion learner.
"""

from __future__ import annotations

from ..base import Inducer, as_performances
from ..conf import Choice, parameter, union
from ..results import Induction
from .conf import TIMINGS, ContentConf
from .learner import learn_content
from .motion.conf import MotionConf
from .motion.learner import learn_performances, same_strings

__all__ = ["PAL", "PALConf"]

#: PAL's parameters: the paper's learner's, then the real-motion learner's, ``engine`` last.
PALConf = union("PALConf", (ContentConf, MotionConf), last=("engine",), module=__name__,
                replace={"timing": parameter("auto", Choice((*TIMINGS, "performances")))},
                doc="PAL's parameters: those of ContentConf and of MotionConf (a row both "
                    "declare is one parameter), ``timing`` also taking ``\"performances\"``.")


class PAL(Inducer):
    """The parallel learning algorithm (see :mod:`psgs.induce.pal` and ``docs/pal.md``).

    One actiongram goes to the paper's learner
    (:func:`~psgs.induce.pal.learner.learn_content`); several performances of one
    action, or one with ``timing="performances"``, go to the real-motion learner
    (:func:`~psgs.induce.pal.motion.learner.learn_performances`). The Induction
    is PAL's either way (``inducer="pal"``, PAL's parameters recorded).

    Parameters
    ----------
    **params
        Keyword parameters. The paper's learner reads those of
        :class:`~psgs.induce.pal.conf.ContentConf`: ``min_copies`` (3),
        ``conserve`` (0.6), ``edge_share`` (0.5), ``column_alpha`` (1e-3),
        ``match_fraction`` (0.5), ``scan_alpha`` (0.05), ``alpha`` (1e-2),
        ``sync_fraction`` (0.5), ``window_support`` (0.34), ``max_pattern`` (64),
        ``seeds`` (3), ``rounds`` (2), ``joins_copies`` (4), ``timing``
        ("auto"), ``period_quantile`` (0.9), ``period_agreement`` (0.6) and
        ``engine`` ("auto"). The real-motion learner reads those of
        :class:`~psgs.induce.pal.motion.conf.MotionConf`: ``min_copies``,
        ``alpha``, ``evidence`` ("kinetemes"), ``joint_share`` (0.25),
        ``neighbour_share`` (0.03), ``channel_share`` (0.25), ``max_shift``
        (0.1), ``min_cycle`` (0.25) and ``min_cycle_score`` (0.05). ``timing``
        takes ``"content"``, ``"period"``, ``"auto"`` or ``"performances"``.

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
    ValueError: engine must be one of 'auto', 'numpy', 'numba', not 'fortran'
    """

    name = "pal"
    Conf = PALConf

    def induce(self, performances) -> Induction:
        """Learn a PSGS from an actiongram; see :class:`~psgs.induce.Induction`.

        Parameters
        ----------
        performances : Actiongram or sequence of Actiongram
            One actiongram (a sequence holding one is the same), or several
            performances of one action (never joined into one stream): then
            the real-motion learner runs (also for one with
            ``timing="performances"``).

        Returns
        -------
        Induction
            Synchronised: every component repeats its pattern the same number of times.

        Raises
        ------
        TypeError
            When the input is not an actiongram or a sequence of them.
        ValidationError
            For an empty sequence.
        """
        takes = as_performances(same_strings(performances), "PAL.induce")
        conf = self.conf()
        if len(takes) > 1 or conf.timing == "performances":
            return learn_performances(self, MotionConf.pick(conf), takes)
        return learn_content(self, ContentConf.pick(conf), takes[0])
