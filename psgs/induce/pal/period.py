"""The period mode: copies located by time windows pooled over all strings."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .conf import NO_BOUND
from .motifs import Timed
from .statistics import log10_binom_sf
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ...budget import Budget
    from .conf import Bounds, ContentConf


@dataclass(frozen=True)
class PeriodResult:
    """Components found by the period mode: pattern codes and copy times per string."""

    period: float
    patterns: dict
    occurrences: dict
    agreement: dict


def time_grid(strings: list[Timed], max_points: int = 1 << 14, clock: Bounds = NO_BOUND):
    """Sample every string's symbol code on one time grid (-1 outside the string).

    The step is half the lower quartile of the segment durations (so most
    segments span two points or more; the quickest flickers fall between
    points), coarser if the
    actiongram would need more than ``max_points`` points. The grid and what the period
    mode computes from it are counted against ``clock``'s ``max_bytes`` before they are
    made (:func:`grid_bytes`).
    """
    present = [s for s in strings if len(s.codes)]
    t0 = min(float(s.starts[0]) for s in present)
    t1 = max(float(s.ends[-1]) for s in present)
    durations = np.concatenate([s.ends - s.starts for s in present])
    step = max(float(np.quantile(durations, 0.25)) / 2, (t1 - t0) / max_points)
    times = t0 + step * (np.arange(int((t1 - t0) / step + 1e-9)) + 0.5)
    clock.keep(grid_bytes(len(strings), len(times)))
    grid = np.full((len(strings), len(times)), -1, dtype=np.int64)
    for row, s in enumerate(strings):
        if len(s.codes) == 0:
            continue
        index = np.searchsorted(s.ends, times, side="right")
        inside = (times >= s.starts[0]) & (index < len(s.codes))
        grid[row, inside] = s.codes[index[inside]]
    return times, step, grid


def _transform_size(points: int) -> int:
    """The length of the FFTs of :func:`_self_agreement` on a grid of ``points`` points."""
    return 1 << max(1, (2 * points - 1).bit_length())


#: Bytes a point of the transform that one row's symbol pairs take in :func:`_self_agreement`
#: at most: fewer than 4 pairs a point held before they are counted, and a symbol's own
#: (its pairs both ways, 8 bytes each, at most 4 a point; the half kept, then joined to the
#: rest), 8 bytes each held and 8 joined
_ROW_BYTES = 136


def grid_bytes(strings: int, points: int) -> int:
    """The bytes the period mode is counted at: its time grid of ``strings`` rows of
    ``points`` points (8 bytes a point), the FFTs of :func:`_self_agreement` with the
    arrays beside them (32 bytes a row a point of the transform) and one row's symbol pairs
    (:data:`_ROW_BYTES` a point of the transform, once: the rows are read one at a time).
    A bound, not a measurement: the traced peak of :func:`period_mode` was 0.3 to 0.8 of
    it (2 to 100 strings of 10 to 400 symbols on 16,384 points).

    Examples
    --------
    >>> grid_bytes(100, 16384)  # 100 strings on the finest grid: about 122 MB
    122421248
    """
    transform = _transform_size(points)
    return strings * (8 * points + 32 * transform) + _ROW_BYTES * transform


def _self_agreement(grid: np.ndarray, size: int, clock: Budget = NO_BOUND
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Per string and lag (in grid points): share of times whose symbol recurs one lag later.

    Also each string's chance rate, the sum of its squared symbol time shares
    (what a string whose symbols were drawn independently would reach).
    Computed with FFTs of one indicator per symbol.
    """
    n = grid.shape[1]
    nfft = _transform_size(n)
    valid = grid >= 0

    def correlate(indicator):
        spectrum = np.fft.rfft(indicator.astype(np.float64), nfft, axis=1)
        return np.fft.irfft(spectrum * spectrum.conj(), nfft, axis=1)[:, :n]

    pairs = np.round(correlate(valid))
    same = np.zeros_like(pairs)
    chance = np.zeros(grid.shape[0])
    counted = np.maximum(valid.sum(axis=1), 1)
    for row in range(grid.shape[0]):
        clock.check()
        # only the symbols this string holds: the cost follows its own alphabet, not the
        # actiongram's; a symbol at few points is counted pair by pair (whole numbers, as
        # the rounded correlation gives them), a frequent one by an FFT
        values = grid[row]
        order = np.argsort(values, kind="stable")
        order = order[values[order] >= 0]
        syms, first, counts = np.unique(values[order], return_index=True, return_counts=True)
        gaps, held = [], 0
        for sym, start, count in zip(syms.tolist(), first.tolist(), counts.tolist()):
            if count * count <= 4 * nfft:
                at = order[start:start + count]
                pairs_of = (at[None, :] - at[:, None]).ravel()
                gaps.append(pairs_of[pairs_of >= 0])
                held += len(gaps[-1])
                if held >= 4 * nfft:
                    # counted as they come, so a row's pairs held stay under what
                    # _ROW_BYTES counts (whole numbers: the sum is the same in any order)
                    same[row] += np.bincount(np.concatenate(gaps), minlength=n)[:n]
                    gaps, held = [], 0
            else:
                same[row] += np.round(correlate((values == sym)[None]))[0]
        if gaps:
            same[row] += np.bincount(np.concatenate(gaps), minlength=n)[:n]
        shares = counts / counted[row]
        # summed symbol after symbol, as a loop over the alphabet would (absent ones add 0)
        chance[row] = np.add.accumulate(shares ** 2)[-1] if len(shares) else 0.0
    return same / np.maximum(pairs, 1), chance


def _candidate_periods(excess: np.ndarray, conf: ContentConf, most: int = 4) -> list[int]:
    """Lags (grid points) at which the strings that repeat recur: candidates for the action's period.

    Pooled over the strings as the upper ``period_quantile`` of their excess
    agreement (agreement minus chance) at each lag, so the few joints that
    drive an action decide and the many still or jittering ones do not
    dilute them. Lags are searched from the end of the first decline (a
    symbol agrees with itself a moment later) to a length leaving
    ``min_copies`` copies. The candidates are the peaks of that curve: first
    the shortest within 15% of the highest (a peak at twice the period is as
    high), then the others, highest first, at most ``most``.
    """
    n = excess.shape[1]
    longest = n // conf.min_copies + 1
    if longest < 3:
        return []
    pooled = np.quantile(excess[:, :longest], conf.period_quantile, axis=0)
    rises = np.flatnonzero(np.diff(pooled) > 0)
    if len(rises) == 0:
        return []
    first = max(int(rises[0]), 2)
    if first >= longest:
        return []
    top = float(pooled[first:].max())
    if top <= 0:
        return []
    peaks = [lag for lag in range(first, longest)
             if pooled[lag] > 0 and pooled[lag] >= pooled[lag - 1]
             and (lag + 1 >= longest or pooled[lag] >= pooled[lag + 1])]
    shortest = [lag for lag in peaks if pooled[lag] >= 0.85 * top][:1]
    others = sorted((lag for lag in peaks if lag not in shortest), key=lambda l: (-pooled[l], l))
    return (shortest + others)[:most]


def _window_agreement(grid: np.ndarray, a: int, b: int, length: int) -> float:
    """Mean over rows of the share of points of windows at ``a`` and ``b`` with equal symbols."""
    n = grid.shape[1]
    span = min(length, n - b)
    left, right = grid[:, a:a + span], grid[:, b:b + span]
    valid = (left >= 0) & (right >= 0)
    counts = valid.sum(axis=1)
    share = ((left == right) & valid).sum(axis=1) / np.maximum(counts, 1)
    return float(share[counts > 0].mean()) if np.any(counts > 0) else 0.0


def track_windows(grid: np.ndarray, lag: int) -> np.ndarray:
    """Start points of consecutive copy windows of ``lag`` points, following tempo changes.

    The phase is where the fewest segments of the given rows run across a
    window boundary, among the phases that lose no whole window; each next window starts within 20% of ``lag`` after the
    previous one, where the rows agree best with it (nearest to ``lag``
    among equals), so a repetition that slows or speeds up stays in step.
    """
    n = grid.shape[1]
    if n < 2 * lag:
        return np.zeros(0, dtype=np.int64)
    # phases that keep as many whole windows as the string holds
    crossing = np.zeros(min(lag, n - (n // lag) * lag + 1))
    for phase in range(len(crossing)):
        cuts = np.arange(max(phase, 1), n, lag)
        crossing[phase] = np.count_nonzero((grid[:, cuts - 1] == grid[:, cuts])
                                           & (grid[:, cuts] >= 0)) / len(cuts)
    starts = [int(np.argmin(crossing))]
    slack = max(1, lag // 5)
    # at most 41 tried lengths per window bounds the cost on long, finely sampled input
    tried = np.unique(np.round(np.linspace(lag - slack, lag + slack, min(2 * slack + 1, 41))))
    candidates = sorted(tried.astype(int).tolist(), key=lambda l: (abs(l - lag), l))
    while True:
        here = starts[-1]
        options = [l for l in candidates if here + l + lag <= n]
        if not options:
            break
        scores = [_window_agreement(grid, here, here + l, lag) for l in options]
        starts.append(here + options[int(np.argmax(scores))])
    return np.asarray(starts, dtype=np.int64)


def period_mode(strings: list[Timed], size: int, conf: ContentConf, clock: Bounds = NO_BOUND
                ) -> PeriodResult | None:
    """Components whose symbols recur with the action's period, read in tracked windows.

    For real motion: joints cycle through the same few states at different
    rates and phases, so copies found by content in each string do not
    cluster; here the copies are time windows shared by all strings. A string
    is a component when, window after window, its symbols at the same time
    offset agree in a share ``period_agreement`` of the times, beyond chance
    (binomial tail on its segments, at its chance rate, times the number of
    strings, below ``alpha``); at least two are needed (synchronisation). Its
    pattern is the plurality symbol at each time offset, runs shorter than
    two grid points dropped. ``clock`` is read for each string and each period tried, and
    raises :class:`~psgs.errors.BoundReached` past its deadline, or before the grid is made
    when :func:`grid_bytes` would pass its ``max_bytes``.
    """
    if sum(len(s.codes) > 0 for s in strings) < 2:
        return None
    times, step, grid = time_grid(strings, clock=clock)
    if grid.shape[1] < 2 * conf.min_copies:
        return None
    agreement, chance = _self_agreement(grid, size, clock)
    lags = _candidate_periods(agreement - chance[:, None], conf)
    best = None
    for lag in lags:
        clock.check()
        found = _read_period(strings, size, times, step, grid, agreement, chance, lag,
                             len(lags), conf, clock)
        if found is not None and (best is None or len(found.patterns) > len(best.patterns)):
            best = found
    return best


def _read_period(strings, size, times, step, grid, agreement, chance, lag, tried,
                 conf: ContentConf, clock: Budget = NO_BOUND) -> PeriodResult | None:
    """The components of one candidate period (see :func:`period_mode`)."""
    drivers = np.flatnonzero(agreement[:, lag] >= conf.period_agreement)
    if len(drivers) < 2:
        return None
    starts = track_windows(grid[drivers], lag)
    if len(starts) < conf.min_copies:
        return None
    windows = grid[:, starts[:, None] + np.arange(lag)]   # (strings, copies, lag)
    penalty = math.log10(len(strings) * tried)
    patterns, occurrences, agreed = {}, {}, {}
    kept: dict[int, set[int]] = {}  # per component, the windows it holds
    for row, s in enumerate(strings):
        clock.check()
        copies = windows[row]
        valid = (copies[:-1] >= 0) & (copies[1:] >= 0)
        if valid.sum() == 0:
            continue
        share = float(((copies[:-1] == copies[1:]) & valid).sum() / valid.sum())
        if share < conf.period_agreement:
            continue
        low = times[starts[0]] - step / 2
        high = times[starts[-1] + lag - 1] + step / 2
        segments = int(np.count_nonzero((s.ends > low) & (s.starts < high)))
        if log10_binom_sf(round(share * segments), segments, float(chance[row])) + penalty \
                > math.log10(conf.alpha):
            continue
        pattern = _plurality_runs(copies, size)
        if len(pattern) < 2:
            continue
        # the windows the string is there for (half their points or more): a copy of a
        # string is never reported where it has no symbol
        held = np.flatnonzero(2 * (copies >= 0).sum(axis=1) >= lag)
        if len(held) < conf.min_copies:
            continue
        patterns[row] = pattern
        agreed[row] = share
        occurrences[row] = tuple((float(times[a] - step / 2), float(times[a + lag - 1] + step / 2))
                                 for a in starts[held].tolist())
        kept[row] = set(held.tolist())
    # in step: a component shares min_copies windows with another one (strings that repeat
    # at one period but at other times are not synchronised)
    while True:
        alone = [row for row in kept if not any(
            len(kept[row] & kept[other]) >= conf.min_copies for other in kept if other != row)]
        if not alone:
            break
        for row in alone:
            del kept[row], patterns[row], occurrences[row], agreed[row]
    if len(patterns) < 2:
        return None
    return PeriodResult(float(lag * step), patterns, occurrences, agreed)


def _plurality_runs(copies: np.ndarray, size: int) -> tuple[int, ...]:
    """The symbols of the column-wise plurality of ``copies``, runs under two points dropped."""
    column = []
    for values in copies.T:
        values = values[values >= 0]
        if len(values) == 0:
            column.append(-1)
            continue
        tally = np.bincount(values)  # up to the largest present symbol: the same argmax
        column.append(int(column[-1]) if column and 0 <= column[-1] < len(tally)
                      and tally[column[-1]] == tally.max() else int(np.argmax(tally)))
    runs: list[list[int]] = []
    for sym in column:
        if runs and runs[-1][0] == sym:
            runs[-1][1] += 1
        else:
            runs.append([sym, 1])
    kept = [sym for sym, width in runs if sym >= 0 and width >= 2] or \
        [sym for sym, _ in runs if sym >= 0]
    out: list[int] = []
    for sym in kept:
        if not out or out[-1] != sym:
            out.append(sym)
    return tuple(out)
