"""PAL: learn a parallel synchronous grammar system from an actiongram.

From the paper: each string is learnt on its own from its digram
frequencies, growing rules N -> X Y; a string's structure is kept only when it
is synchronised with the structure of other strings (a string with nothing
synchronised is spurious and is not a component); the highest synchronised
level of each component is its motion pattern; the axiom has
S_i -> N_i S_i | N_i, synchronised across the components.

Ours (the paper's algorithm figure is lost), built to survive noise and
irregular repetition -- ``docs/pal.md`` gives the details and every parameter:

1. a motif per string, seeded by its most frequent digrams and grown one
   conserved column at a time (past a column noise damaged when the one
   beyond is conserved), its copies located again by a tolerant scan after
   every step (damaged copies keep voting);
2. a significance screen against random strings of the same length and
   symbol frequencies;
3. synchronisation in time: two strings are in step when most clusters of
   their overlapping copies hold copies of both;
4. copies pooled over each group of synchronised strings: shared time
   windows, one copy per member and window, the pattern by plurality vote
   over every copy (one a symbol too short or long for its window included),
   copies located again with the voted pattern (not a fixed period);
5. strings too damaged to be significant alone join a group when, read in
   its windows, they repeat beyond chance; members that do not are dropped;
6. end columns not conserved across the group are trimmed.

When content finds nothing (``timing="auto"``, the default) or on request
(``timing="period"``), copies are instead time windows of the action's period,
pooled over all strings and tracked through tempo changes; a string is a
component when its symbols recur window after window (for real motion capture).

Two learners, each an inducer with its own frozen parameter table handed to
its phases: the paper's learner above, :class:`~psgs.induce.pal.learner.ContentPAL`
(``"pal_content"``, :class:`~psgs.induce.pal.conf.ContentConf`, the modules of
this package), and the real-motion learner for several performances,
:class:`~psgs.induce.pal.motion.MotionPAL` (``"pal_motion"``,
:class:`~psgs.induce.pal.motion.MotionConf`, the subpackage
:mod:`psgs.induce.pal.motion`, with :func:`~psgs.induce.pal.motion.locate`).
:class:`PAL` (``"pal"``, :mod:`psgs.induce.pal.entry`) is the name users know:
it hands one actiongram to the first and several performances to the second.
No phase module imports a learner: each reads the frozen table it is handed.
"""

from .conf import ContentConf
from .entry import PAL, PALConf
from .learner import ContentPAL
from .motion import MotionConf, MotionPAL

__all__ = ["PAL", "PALConf", "ContentPAL", "ContentConf", "MotionPAL", "MotionConf"]
