"""The defaults of parsing a performance that ``praxicon parse`` prints in its help: plain
values, without numpy, so that the command's parser is made without importing
:mod:`praxicon.parsing`, which imports them from here under the names it documents."""

from __future__ import annotations

__all__ = ["SUPPORT", "UNFIT"]

# the share of a span's windows that must pass its action's feature-group test: a quarter,
# so that a performance of a style not learnt, whose windows pass the test at times only,
# keeps its span, and a stretch of an action never learnt, nearest to a learnt one by distance
# but passing its test in no window or a few, does not
SUPPORT = 0.25
# seconds: a stretch of a span this long whose every window fails the action's test (two and
# a half windows) is none of these, where an action never learnt is absorbed by a learnt
# neighbour's span. On the parsing benchmark (30 fps, a hop of 8 frames) stretches of 16 to 24
# windows (4.3 to 6.4 s) answer the same; 15 loses a learnt action's odd stretch in cmu-mocap6,
# 28 and more catch less of the actions never learnt
UNFIT = 5.0
