"""Chance levels PAL tests against: binomial and Poisson tails, the scan threshold."""

from __future__ import annotations

import functools
import math
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .conf import ContentConf


#: log(10), once
_LN10 = math.log(10)


def log10_choose(n: int, k: int) -> float:
    """log10 of the binomial coefficient ``C(n, k)`` (-inf when ``k`` is out of range).

    >>> round(log10_choose(10, 3), 6) == round(math.log10(120), 6)
    True
    """
    if k < 0 or k > n:
        return -math.inf
    return (math.lgamma(n + 1) - math.lgamma(k + 1) - math.lgamma(n - k + 1)) / _LN10


#: log(j!) = lgamma(j + 1) for j = 0 .. 4096, the very floats math.lgamma gives: the tails of
#: up to that many trials read them from here instead of calling it twice a term
_LOG_FACTORIALS = [math.lgamma(j + 1) for j in range(4097)]


class _LogFactorials:
    """log(j!) past the table, read as the table is: ``math.lgamma(j + 1)``."""

    def __getitem__(self, j: int) -> float:
        return math.lgamma(j + 1)


def log10_binom_sf(k: int, m: int, p: float) -> float:
    """log10 P(X >= k) for X ~ Binomial(m, p).

    >>> round(log10_binom_sf(2, 3, 0.5), 6) == round(math.log10(0.5), 6)
    True
    """
    if k <= 0:
        return 0.0
    if k > m or p <= 0:
        return -math.inf
    if p >= 1:
        return 0.0
    # (the sums run in a fixed order: the compiled motif search's results are checked
    # against these, to the bit; names bound locally only for speed)
    lp, lq, mp = math.log(p), math.log1p(-p), m * p
    log_factorial = _LOG_FACTORIALS if m < len(_LOG_FACTORIALS) else _LogFactorials()
    whole = log_factorial[m]
    # (the first term sets the cut and never meets it)
    t = whole - log_factorial[k] - log_factorial[m - k] + k * lp + (m - k) * lq
    terms, floor = [t], t - 30
    for i in range(k + 1, m + 1):
        t = whole - log_factorial[i] - log_factorial[m - i] + i * lp + (m - i) * lq
        terms.append(t)
        if i > mp and t < floor:
            break
    top = max(terms)
    exp = math.exp
    return (top + math.log(sum([exp(t - top) for t in terms]))) / _LN10


def log10_poisson_sf(k: int, lam: float) -> float:
    """log10 P(Y >= k) for Y ~ Poisson(lam)."""
    if k <= 0:
        return 0.0
    if lam <= 0:
        return -math.inf
    lgamma, exp, log_lam = math.lgamma, math.exp, math.log(lam)
    if k <= lam:  # the tail is at least about a half: one minus the few terms below k
        below = math.fsum([exp(-lam + i * log_lam - lgamma(i + 1)) for i in range(k)])
        if below < 0.9:
            return math.log10(1.0 - below)
    first = -lam + k * log_lam - lgamma(k + 1)
    terms, i, floor, last = [first], k, first - 30, k + 10_000
    t = first
    while not ((i > lam and t < floor) or i > last):
        i += 1
        t = -lam + i * log_lam - lgamma(i + 1)
        terms.append(t)
    top = max(terms)
    return (top + math.log(sum([exp(t - top) for t in terms]))) / _LN10


def scan_threshold(length: int, windows: int, match_rate: float, conf: ContentConf) -> int:
    """Fewest matching positions a window needs to count as a copy."""
    return _threshold(length, windows, match_rate, conf.match_fraction, conf.scan_alpha)


def chance_threshold(length: int, windows: int, match_rate: float, conf: ContentConf) -> int:
    """Fewest matching positions a window needs to pass as beyond chance alone.

    As :func:`scan_threshold` without its floor of ``match_fraction`` of the
    positions (two at least).
    """
    return _threshold(length, windows, match_rate, 0.0, conf.scan_alpha)


@functools.lru_cache(maxsize=4096)
def _threshold(length: int, windows: int, match_rate: float, match_fraction: float,
               scan_alpha: float) -> int:
    """The first ``t`` from the floor up whose ``windows`` tails ``P(X >= t)`` are at most
    ``scan_alpha`` (``length`` when none is).

    Found by halving when the answer is the same as trying each ``t`` in turn, as it is
    when ``scan_alpha < windows / 4``: at ``t <= m p`` (``m = length``, ``p`` the match
    rate) the tail is at least a half (the binomial's median is ``floor(m p)`` or
    ``ceil(m p)``), so no ``t`` there passes; past ``m p``, at or past the mode, each tail
    is more than ``1 + 1 / m`` times the next (the terms only fall), far beyond what the
    sum's rounding and its cut at ``e^-30`` of its first term can move, so the ``t`` that
    pass are the ones from the first that does on. Else (a bound as large as the
    windows, where a tail of about 1 decides by its last bits) each ``t`` in turn.

    Examples
    --------
    >>> _threshold(10, 100, 0.25, 0.5, 0.05) == _linear_threshold(10, 100, 0.25, 0.5, 0.05)
    True
    """
    low = max(2, math.ceil(match_fraction * length))
    if not scan_alpha < windows / 4 or not 0 < match_rate < 1:
        return _linear_threshold(length, windows, match_rate, match_fraction, scan_alpha)
    # (below m p every t fails; the t are tried from the last whole number at or under it)
    low = max(low, math.floor(length * match_rate))
    high = length + 1  # (length + 1: no t passes)
    while low < high:
        middle = (low + high) // 2
        if windows * 10 ** log10_binom_sf(middle, length, match_rate) <= scan_alpha:
            high = middle
        else:
            low = middle + 1
    return min(low, length)


def _linear_threshold(length: int, windows: int, match_rate: float, match_fraction: float,
                      scan_alpha: float) -> int:
    """:func:`_threshold`, each ``t`` tried in turn from the floor up."""
    low = max(2, math.ceil(match_fraction * length))
    for t in range(low, length + 1):
        if windows * 10 ** log10_binom_sf(t, length, match_rate) <= scan_alpha:
            return t
    return length


