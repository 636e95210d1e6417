"""Cycles within a performance: self-agreement at every lag, a joint's period, its evidence.

A performance that cycles agrees with itself one period later, and less at
half the period (an oscillation is in anti-phase there, stillness or a slow
drift is not). Everything here is read from the performance's grid
(:mod:`psgs.induce.pal.grids`): the speed-weighted kappa at every candidate
lag is computed once per performance (:func:`lag_scores`) and reused by the
period search, the cycle evidence and the leader's choice.

Speed without changing answers: comparisons that share a length are batched
into one array operation (the sums along time are then the very sums the
one-at-a-time form makes), unweighted agreements are integer counts, and
:class:`CycleEvidence` remembers what one set of periods gives, as the
leader search asks again for the periods of joints that share them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from .grids import Grid, agreement, agreement_counts, kappa, plurality
from .statistics import log10_binom_sf

if TYPE_CHECKING:
    from .learner import PAL


class LagScores(NamedTuple):
    """One performance's cycle scores: ``table[k, c]`` is channel ``c``'s at ``lags[k]``;
    ``kappas[lag]`` the speed-weighted kappa of every channel at ``lag`` (or half a lag)."""

    lags: range
    table: np.ndarray
    kappas: dict


def _lags(grid: Grid, params: PAL) -> range:
    low = max(2, int(params.min_cycle / grid.step))
    return range(low, grid.points // params.min_copies + 1)


def _weighted_kappa(states: np.ndarray, weight: np.ndarray, lag: int, size: int,
                    onehot: np.ndarray | None = None) -> np.ndarray:
    """Per row, the kappa of the states with themselves ``lag`` points later, weighted by
    the mean of the two points' speeds: :func:`~psgs.induce.pal.grids.agreement` on the
    two slices, with the states' indicator ``onehot`` (state, row, point) made once."""
    if onehot is None:
        onehot = states[None] == np.arange(size)[:, None, None]
    valid = states >= 0
    w = np.where(valid[:, :-lag] & valid[:, lag:], (weight[:, :-lag] + weight[:, lag:]) / 2,
                 0.0)
    div = np.maximum(w.sum(axis=1), 1e-300)
    observed = ((states[:, :-lag] == states[:, lag:]) * w).sum(axis=1) / div
    share_a = (onehot[:, :, :-lag] * w).sum(axis=2) / div
    share_b = (onehot[:, :, lag:] * w).sum(axis=2) / div
    chance = np.zeros(states.shape[0])
    for sym in range(size):  # in the order agreement sums them
        chance += share_a[sym] * share_b[sym]
    return kappa(observed, chance)


def lag_scores(grid: Grid, size: int, params: PAL) -> LagScores:
    """Every channel's cycle score at every candidate lag.

    The score is the speed-weighted kappa at the lag minus that at half the
    lag (clipped at 0); it is computed once per lag (the half lags are lags
    too) and kept in ``kappas`` for every channel. In the table, channels that
    hardly move (path under 1% of the most moving channel's) score 0.
    """
    lags = _lags(grid, params)
    channels = grid.states.shape[0]
    if not len(lags):
        return LagScores(lags, np.zeros((0, channels)), {})
    speed = grid.speed
    path = speed.sum(axis=1)
    rows = np.flatnonzero(path >= 0.01 * max(float(path.max()), 1e-300))
    kappas: dict[int, np.ndarray] = {}
    onehot = grid.states[None] == np.arange(size)[:, None, None]
    for lag in sorted(set(lags) | {max(1, lag // 2) for lag in lags}):
        if lag < grid.points:
            kappas[lag] = _weighted_kappa(grid.states, speed, lag, size, onehot)
    table = np.zeros((len(lags), channels))
    for k, lag in enumerate(lags):
        table[k, rows] = kappas[lag][rows] - np.clip(kappas[max(1, lag // 2)][rows], 0, None)
    return LagScores(lags, table, kappas)


def joint_period(scored: LagScores, rows: tuple[int, ...], params: PAL) -> int | None:
    """A joint's period in one performance (grid points), or None when it does not cycle.

    ``scored`` is :func:`lag_scores` of the performance; the joint's score at
    a lag is the mean over its channels. The period is the shortest peak
    within 15% of the highest (a peak at twice the period is as high).
    """
    lags, table = scored.lags, scored.table
    if len(lags) < 2:
        return None
    scores = table[:, list(rows)].mean(axis=1)
    top = float(scores.max())
    if top <= params.min_cycle_score:
        return None
    high = scores >= 0.85 * top
    rising = np.concatenate([[True], scores[1:] >= scores[:-1]])
    falling = np.concatenate([scores[:-1] >= scores[1:], [True]])
    peaks = np.flatnonzero(high & rising & falling)
    return lags[int(peaks[0])] if len(peaks) else None


def _later(states: np.ndarray, lag: int) -> np.ndarray:
    """``states`` ``lag`` points later, absent (-1) past the end: compared with
    ``states`` it counts exactly the points ``states[:, :-lag]`` and ``states[:, lag:]`` do."""
    out = np.full(states.shape, -1, dtype=np.int64)
    if lag < states.shape[1]:
        out[:, :states.shape[1] - lag] = states[:, lag:]
    return out


def self_scores(grid: Grid, scored: LagScores, lag: int, size: int
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every channel's speed-weighted kappa at ``lag`` minus that at half the lag (clipped
    at 0), its unweighted agreement at ``lag``, and the null: the larger of chance and
    the unweighted agreement at half the lag."""
    half = max(1, lag // 2)
    weighted = scored.kappas.get(lag)
    if weighted is None:
        weighted = _weighted_kappa(grid.states, grid.speed, lag, size)
    half_weighted = scored.kappas.get(half)
    if half_weighted is None:
        half_weighted = _weighted_kappa(grid.states, grid.speed, half, size)
    score = weighted - np.clip(half_weighted, 0, None)
    s = grid.states
    obs, chance, _ = agreement_counts(np.stack([s, s]),
                                      np.stack([_later(s, lag), _later(s, half)]), size)
    return score, obs[0], np.maximum(chance[0], obs[1])


def cycle_evidence(grids: list[Grid], scored: list[LagScores], periods: list[int | None],
                   size: int, paths: np.ndarray, segments: np.ndarray,
                   tails: dict | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Per channel: median over performances of repeated motion and log10 p at the periods."""
    channels = grids[0].states.shape[0]
    repeated = np.zeros((len(grids), channels))
    agreeing, trials, nulls = np.zeros(channels), np.zeros(channels), np.zeros(channels)
    for k, (grid, lag) in enumerate(zip(grids, periods)):
        if not lag:
            continue
        score, raw, null = self_scores(grid, scored[k], lag, size)
        repeated[k] = np.clip(score, 0, None) * paths[k]
        agreeing += np.round(raw * segments[k])
        trials += segments[k]
        nulls += null * segments[k]
    # the share is the median over performances (most must be in step); the test pools the
    # segments of every performance (the null: chance, or the agreement at half the period)
    null = nulls / np.maximum(trials, 1)
    log_p = np.array([_tail(int(k), int(n), float(c), tails) if n > 0 and c < 1 else 0.0
                      for k, n, c in zip(agreeing, trials, null)])
    return np.median(repeated, axis=0), log_p


def _tail(k: int, n: int, c: float, tails: dict | None) -> float:
    """:func:`log10_binom_sf`, remembered in ``tails`` when given (a pure function that
    every joint sharing a period asks again for the same counts)."""
    if tails is None:
        return log10_binom_sf(k, n, c)
    key = (k, n, c)
    if key not in tails:
        tails[key] = log10_binom_sf(k, n, c)
    return tails[key]


def mean_cycles(grids: list[Grid], periods: list[int | None], rows: tuple[int, ...],
                width: int = 24) -> list[np.ndarray]:
    """Per performance that cycles, each channel's plurality state at ``width`` points
    over its cycles of that performance's period, (rows, width)."""
    rows_l = list(rows)
    means = []
    for grid, lag in zip(grids, periods):
        if not lag:
            continue
        count = grid.points // lag
        cycles = grid.states[rows_l, :count * lag].reshape(len(rows_l), count, lag)
        index = np.minimum((np.arange(width) + 0.5) * lag / width, lag - 1).astype(np.int64)
        means.append(plurality(cycles[:, :, index]))
    return means


def cycles_alike(grids: list[Grid], periods: list[int | None], rows: tuple[int, ...],
                 size: int, width: int = 24) -> float:
    """Chance-corrected agreement of a joint's mean cycle between performances.

    Per performance, each channel's cycle is the plurality state at each of
    ``width`` points over its cycles (of that performance's period); pairs of
    performances are compared at the circular shift, common to the joint's
    channels, that agrees best; the mean kappa over pairs. Every pair at every
    shift is one array operation.
    """
    means = mean_cycles(grids, periods, rows, width)
    if len(means) < 2:
        return 0.0
    m = np.array(means)                                       # (performances, rows, width)
    # rolled[..., s, :, j] = np.roll(m, s, axis=-1)[..., j] = m[..., (j - s) % width]
    turn = (np.arange(width)[None, :] - np.arange(width)[:, None]) % width
    rolled = np.moveaxis(m[:, :, turn], 2, 1)                 # (performances, shift, rows, width)
    p, q = np.triu_indices(len(means), 1)                     # the pairs in the loop's order
    obs, chance, _ = agreement_counts(m[p][:, None], rolled[q], size)
    per_shift = kappa(obs, chance).mean(axis=-1)              # (pairs, shifts)
    scores = np.maximum(per_shift.max(axis=1), -1.0)
    return float(np.mean(scores.tolist()))


@dataclass
class CycleEvidence:
    """Cycle evidence of one learning run, remembered per set of periods (a working record:
    the leader search asks for the same periods once per joint that has them)."""

    grids: list[Grid]
    scored: list[LagScores]
    size: int
    paths: np.ndarray
    segments: np.ndarray
    _evidence: dict = field(default_factory=dict)
    _alike: dict = field(default_factory=dict)
    _tails: dict = field(default_factory=dict)

    def cycles(self, periods: list[int | None]) -> tuple[np.ndarray, np.ndarray]:
        """:func:`cycle_evidence` at ``periods``."""
        key = tuple(periods)
        if key not in self._evidence:
            self._evidence[key] = cycle_evidence(self.grids, self.scored, periods, self.size,
                                                 self.paths, self.segments, self._tails)
        return self._evidence[key]

    def alike(self, periods: list[int | None], rows: tuple[int, ...]) -> float:
        """:func:`cycles_alike` at ``periods`` on ``rows``."""
        key = (tuple(periods), tuple(rows))
        if key not in self._alike:
            self._alike[key] = cycles_alike(self.grids, periods, rows, self.size)
        return self._alike[key]
