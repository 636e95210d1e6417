"""How much of a group's core a string plays again at the core's shift, and how unlikely that is.

A group of sections in step (:mod:`~psgs.induce.pal.in_step`) reads the strings that did
not join at its lead's copies once more where the lead and its members all are: the
**core**, two copies' times. There the question is narrower than at the lead's copies:
not whether a string holds a repeat lying as close to two copies as it does, wherever and
however long, but whether the string plays the core's first copy again at the very shift
of the core, the one thing a section played twice at the same times does. The members'
own repeats reach past the core by the symbols that agree by chance around each copy (a
symbol before or after both copies agrees one time in ``1 / r`` or so), and where every
member so far happens to reach past the true section on the same side, the core does too
and an exact member lies off it by a symbol; weighed by how close it lies, it pays for that
symbol as if its copies could have been any windows near the core. Weighed by what it
covers, it pays only for the core's symbols it does not play.

:func:`cover_reading` weighs the longest stretch of consecutive segments under the core's
first copy that the string plays again exactly ``D`` later (``D`` the core's shift: the
second copy's start less the first's), each segment's partner starting ``D`` after it:
``log10((S - c + 1) * q * r^(c - 1))`` for ``c`` of the ``S`` segments under the first
copy, ``q`` the string's match rate and ``r`` its follow rate (the chance that one
window of ``c`` segments agrees, times the windows of ``c`` among ``S``: a bound on the
chance that a random string plays ``c`` or more of the core again, chosen after seeing
it; nothing for the symbols outside the core, which the core does not ask about).
"""

from __future__ import annotations

import math

import numpy as np

from .motifs import Timed
from .pairing import lead_segments, spans_pair
from .sections import Section, _cycles

__all__: list[str] = []  # private: in_step.py is the caller


def cover_reading(string: Timed, core: np.ndarray, follow: float | None
                  ) -> tuple[float, Section] | None:
    """The weight (log10) of the longest stretch of the core's first copy that ``string``
    plays again at the core's shift, and the exact repeat that holds it; None when it
    plays none of it again, or only as part of a cycle.

    The repeat reported is that stretch widened on both sides while the string keeps
    playing its symbols again at the same shift in time (and its copies do not overlap):
    the string's own section, which may reach past the core. Its copies must pair with the
    core's, each pair sharing half of the time the two cover together, or there is no
    reading. ``core`` is a (2, 2) array of
    times, the copies' ``[[start, end], [start, end]]``.

    Examples
    --------
    >>> codes = np.array([5, 0, 1, 2, 3, 4, 7, 0, 1, 2, 3, 4, 6, 5])
    >>> string = Timed.from_codes(codes, np.ones(14), 0.0)
    >>> weight, found = cover_reading(string, np.array([[1.0, 6.0], [7.0, 12.0]]), None)
    >>> found.motif.tolist(), found.starts.tolist()
    ([0, 1, 2, 3, 4], [1, 7])
    >>> round(weight, 2)  # one window of five among five, q = r = 26 / 196: log10(q ** 5)
    -4.39
    >>> cover_reading(string, np.array([[1.0, 6.0], [8.0, 13.0]]), None) is None  # shift 7
    True
    """
    segments = lead_segments(string, core)
    if segments is None:
        return None
    first = segments[0]
    q, r = string.chance_rates(follow)
    if q <= 0 or r <= 0:
        return None
    codes, starts = string.codes, string.starts
    (a1, _), (a2, _) = core.tolist()
    shift = a2 - a1
    slack = 1e-9 * max(1.0, abs(a1), abs(a2))
    # each segment's partner: the segment starting ``shift`` later, if one does
    target = starts[first] + shift
    partner = np.minimum(np.searchsorted(starts, target - slack), len(starts) - 1)
    plays = ((np.abs(starts[partner] - target) <= slack) & (partner > first)
             & (codes[partner] == codes[first]))
    # stretches of consecutive segments played again at one index shift
    steps = partner - first
    best, at = 0, -1
    run = 0
    for k in range(len(first)):
        if plays[k] and run and steps[k] == steps[k - 1]:
            # (no longer than the shift: the copies of a longer stretch would overlap)
            run = min(run + 1, int(steps[k]))
        else:
            run = int(plays[k])
        if run > best:
            best, at = run, k - run + 1
    if best == 0:
        return None
    weight = (math.log10(len(first) - best + 1) + math.log10(q)
              + (best - 1) * math.log10(r))
    lo = int(first[at])
    step = int(steps[at])
    hi = lo + best
    n = len(codes)

    def again(p: int) -> bool:
        return (0 <= p and p + step < n and codes[p] == codes[p + step]
                and abs(starts[p + step] - starts[p] - shift) <= slack)

    while hi - lo < step and again(lo - 1):
        lo -= 1
    while hi - lo < step and again(hi):
        hi += 1
    if _cycles(codes, (lo, lo + step), hi - lo):
        return None
    # a member's copies pair with the core's (each pair sharing half of the time the two
    # cover together), as copies in step do everywhere else: a string playing a few of the
    # core's symbols again is no member, however unlikely those few
    found = np.array([[starts[lo], string.ends[hi - 1]],
                      [starts[lo + step], string.ends[hi - 1 + step]]])
    if not all(spans_pair(copy, mate) for copy, mate in zip(found.tolist(), core.tolist())):
        return None
    return weight, Section(codes[lo:hi].copy(), np.array([lo, lo + step], dtype=np.int64), 0.0)
