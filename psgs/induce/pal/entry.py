"""PAL, the name users know: it hands one actiongram to the paper's learner, several
performances to the real-motion learner.

The two learners are inducers of their own (:class:`~psgs.induce.pal.learner.ContentPAL`,
:class:`~psgs.induce.pal.motion.learner.MotionPAL`), each with its frozen
parameter table. PAL's table is their union (:data:`PALConf`, every rule still
declared once, in the learner's table), with ``timing`` taking one more value,
``"performances"``, that sends one actiongram to the real-motion learner.
PAL's docstring lists the learners' parameters, read from their docstrings.
"""

from __future__ import annotations

import re

from ..base import Inducer, as_performances
from ..conf import Choice, parameter, union
from ..results import Induction
from .conf import TIMINGS, ContentConf
from .learner import ContentPAL, learn_content
from .motion.conf import MotionConf
from .motion.learner import MotionPAL, learn_performances, same_strings

__all__ = ["PAL", "PALConf"]

#: PAL's parameters: the paper's learner's, then the real-motion learner's, ``engine`` last.
PALConf = union("PALConf", (ContentConf, MotionConf), last=("engine",), module=__name__,
                replace={"timing": parameter("auto", Choice((*TIMINGS, "performances")))},
                doc="""PAL's parameters: those of ContentConf and of MotionConf (a row both
    declare is one parameter), ``timing`` also taking ``"performances"``.

    Examples
    --------
    >>> PALConf(timing="performances").joint_share
    0.25
    """)

#: PAL's own words for the one parameter that means more for PAL than for a learner.
_TIMING = """    timing : {"auto", "content", "period", "performances"}, default "auto"
        As for :class:`~psgs.induce.pal.learner.ContentPAL`, and ``"performances"``: the
        real-motion learner, for one actiongram too.
"""


def _parameters_section(*classes: type, own: dict[str, str]) -> str:
    """The Parameters sections of ``classes``' docstrings joined (a name seen before is
    skipped, ``own`` replaces an entry), so that each parameter's text is written once."""
    entries: dict[str, str] = {}
    for cls in classes:
        body = (cls.__doc__ or "").split("    Parameters\n    ----------\n", 1)[1]
        body = re.split(r"\n\n    \w[\w ]*\n    -{3,}\n", body, maxsplit=1)[0]
        for entry in re.split(r"\n(?=    \w)", body.rstrip("\n")):
            name = entry.split(":", 1)[0].strip()
            entries.setdefault(name, own.get(name, entry.rstrip("\n") + "\n"))
    return "    Parameters\n    ----------\n" + "".join(entries.values())


class PAL(Inducer):
    """The parallel learning algorithm (see :mod:`psgs.induce.pal` and ``docs/pal.md``).

    One actiongram goes to the paper's learner
    (:func:`~psgs.induce.pal.learner.learn_content`); several performances of one
    action, or one with ``timing="performances"``, go to the real-motion learner
    (:func:`~psgs.induce.pal.motion.learner.learn_performances`). The Induction
    is PAL's either way (``inducer="pal"``, PAL's parameters recorded). The
    parameters are the two learners' (each documented on its learner, and
    listed here from there), ``timing`` also taking ``"performances"``.

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


PAL.__doc__ = PAL.__doc__.replace(
    "    Examples\n    --------\n",
    _parameters_section(ContentPAL, MotionPAL, own={"timing": _TIMING}) +
    "\n    Examples\n    --------\n", 1)
