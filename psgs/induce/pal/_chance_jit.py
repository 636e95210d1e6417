"""Chance levels for the compiled motif search, approximately: only ever compared, with a
margin (see :mod:`psgs.induce.pal._motifs_jit`), never returned.

numba's ``lgamma`` is the C library's, CPython's ``math.lgamma`` its own, and the sums here
run as a running log-sum-exp: the values differ from :mod:`psgs.induce.pal.statistics`'s by
some 1e-12, which is why a decision within a relative ``_MARGIN`` of its boundary is left to
the numpy engine. Without numba this module still imports (plain Python functions).
"""

from __future__ import annotations

import math

# compiled on first use, once per installed copy; plain Python where numba does not import
from ..._foundation.engines import jit as _jit

__all__: list[str] = []  # private: the PAL parameter ``engine`` is the interface

#: a chance level this close (relative) to a boundary is left to the numpy engine
_MARGIN = 1e-6


@_jit
def _log10_binom_sf(k, m, p, lp, lq):
    """About log10 P(X >= k), X ~ Binomial(m, p) (statistics.log10_binom_sf's sum)."""
    if k <= 0:
        return 0.0
    if k > m or p <= 0:
        return -math.inf
    if p >= 1:
        return 0.0
    first = top = -math.inf
    total = 0.0
    for i in range(k, m + 1):
        t = math.lgamma(m + 1) - math.lgamma(i + 1) - math.lgamma(m - i + 1) \
            + i * lp + (m - i) * lq
        if i == k:
            first = t
        if t > top:  # a running log-sum-exp: the same sum up to rounding
            total = total * math.exp(top - t) + 1.0 if top > -math.inf else 1.0
            top = t
        else:
            total += math.exp(t - top)
        if i > m * p and t < first - 30:
            break
    return (top + math.log(total)) / math.log(10.0)


@_jit
def _log10_poisson_sf(k, lam):
    """About log10 P(Y >= k), Y ~ Poisson(lam) (statistics.log10_poisson_sf's sums)."""
    if k <= 0:
        return 0.0
    if lam <= 0:
        return -math.inf
    log_lam = math.log(lam)
    if k <= lam:
        below = 0.0
        for i in range(k):
            below += math.exp(-lam + i * log_lam - math.lgamma(i + 1))
        if below < 0.9:
            return math.log10(1.0 - below)
    first = top = -math.inf
    total = 0.0
    i = k
    while True:
        t = -lam + i * log_lam - math.lgamma(i + 1)
        if i == k:
            first = t
        if t > top:
            total = total * math.exp(top - t) + 1.0 if top > -math.inf else 1.0
            top = t
        else:
            total += math.exp(t - top)
        if (i > lam and t < first - 30) or i > k + 10_000:
            break
        i += 1
    return (top + math.log(total)) / math.log(10.0)


@_jit
def _threshold(length, windows, p, lp, lq, match_fraction, scan_alpha):
    """statistics.scan_threshold, or -1 when a tail lies within the margin of ``scan_alpha``."""
    low = max(2, math.ceil(match_fraction * length))
    for t in range(low, length + 1):
        x = _log10_binom_sf(t, length, p, lp, lq)
        chance = windows * 10.0 ** x
        if abs(chance - scan_alpha) <= _MARGIN * scan_alpha:
            return -1
        if chance <= scan_alpha:
            return t
    return length
