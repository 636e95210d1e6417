"""Cycles within a performance: self-agreement at every lag, a joint's period, its evidence.

A performance that cycles agrees with itself one period later, and less at
half the period (an oscillation is in anti-phase there, stillness or a slow
drift is not). Everything here is read from the performance's grid
(:mod:`psgs.induce.pal.motion.grids`): a channel's speed-weighted kappa at every
candidate lag is computed once, when a joint of it is first timed
(:class:`LagScores`), and reused by the period search, the cycle evidence and
the leader's choice.

Speed without changing answers: comparisons that share a length are batched
into one array operation (the sums along time are then the very sums the
one-at-a-time form makes), unweighted agreements are integer counts, and
:class:`CycleEvidence` remembers what one set of periods gives, as the
leader search asks again for the periods of joints that share them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from .grids import Grid, agreement_counts, from_tallies, kappa, plurality
from ..statistics import log10_binom_sf

if TYPE_CHECKING:
    from .conf import MotionConf


def _lags(grid: Grid, conf: MotionConf) -> range:
    low = max(2, int(conf.min_cycle / grid.step))
    return range(low, grid.points // conf.min_copies + 1)


def _present(states: np.ndarray) -> np.ndarray:
    """The states that occur in ``states``, ascending (absent ones add exactly 0 to chance)."""
    return np.unique(states[states >= 0])


def _weighted_kappa(states: np.ndarray, weight: np.ndarray, lag: int, size: int,
                    onehot: np.ndarray | None = None) -> np.ndarray:
    """Per row, the kappa of the states with themselves ``lag`` points later, weighted by
    the mean of the two points' speeds: :func:`~psgs.induce.pal.motion.grids.agreement` on the
    two slices, with the indicator ``onehot`` (state, row, point) of the states present in
    ``states`` (ascending) made once. A state that does not occur has share 0 and adds
    exactly 0 to chance, so leaving it out changes no number and keeps the cost
    independent of the size of the alphabet."""
    if onehot is None:
        onehot = states[None] == _present(states)[:, None, None]
    valid = states >= 0
    w = np.where(valid[:, :-lag] & valid[:, lag:], (weight[:, :-lag] + weight[:, lag:]) / 2,
                 0.0)
    div = np.maximum(w.sum(axis=1), 1e-300)
    observed = ((states[:, :-lag] == states[:, lag:]) * w).sum(axis=1) / div
    share_a = (onehot[:, :, :-lag] * w).sum(axis=2) / div
    share_b = (onehot[:, :, lag:] * w).sum(axis=2) / div
    # summed state after state, in the order agreement sums them (accumulate is sequential)
    chance = np.add.accumulate(share_a * share_b, axis=0)[-1] if len(onehot) \
        else np.zeros(states.shape[0])
    return kappa(observed, chance)


def _kappa_by_rows(states: np.ndarray, weight: np.ndarray, lag: int, size: int
                   ) -> np.ndarray:
    """:func:`_weighted_kappa` of every row; rows with different states apart, so that
    many channels over a large alphabet cost what each channel's own states cost (rows are
    independent: the numbers are those of one call over every row)."""
    out = np.zeros(states.shape[0])
    for group in _alike_rows(states, list(range(states.shape[0]))):
        out[group] = _weighted_kappa(states[group], weight[group], lag, size)
    return out


@dataclass(eq=False)
class LagScores:
    """One performance's cycle scores at every candidate lag, computed channel by channel
    as they are asked for (a working record of one learning run).

    A channel's score at a lag is its speed-weighted kappa there minus that at
    half the lag (clipped at 0); 0 for channels that hardly move (path under 1%
    of the most moving channel's). Each channel's row of kappas is computed once,
    over every lag and half lag, when a joint of it is first timed: a run that
    times only the leader's channels never pays for the others. Rows are
    independent, so a channel's numbers do not depend on which others were asked.
    """

    grid: Grid
    size: int
    lags: range
    _union: dict = field(default_factory=dict)     # lag or half lag -> row of _kappa
    _kappa: np.ndarray | None = None               # (lag or half lag, channel)
    _done: np.ndarray | None = None                # channels computed
    _moving: np.ndarray | None = None
    _full: dict = field(default_factory=dict)      # lag -> every channel's kappa

    def __post_init__(self):
        channels = self.grid.states.shape[0]
        wanted = sorted(set(self.lags) | {max(1, lag // 2) for lag in self.lags})
        self._union = {lag: k for k, lag in enumerate(wanted)}
        self._kappa = np.zeros((len(wanted), channels))
        self._done = np.zeros(channels, dtype=bool)
        path = self.grid.speed.sum(axis=1)
        self._moving = path >= 0.01 * max(float(path.max(initial=0.0)), 1e-300)

    def table(self, rows) -> np.ndarray:
        """Scores ``(lag, channel)`` of the channels ``rows``, in that order."""
        rows = list(rows)
        todo = [r for r in dict.fromkeys(rows) if not self._done[r]]
        if todo and self._union:
            for group in _alike_rows(self.grid.states, todo):
                states, speed = self.grid.states[group], self.grid.speed[group]
                onehot = states[None] == _present(states)[:, None, None]
                for lag, k in self._union.items():
                    self._kappa[k, group] = _weighted_kappa(states, speed, lag, self.size,
                                                            onehot)
        self._done[todo] = True
        at = [self._union[lag] for lag in self.lags]
        half = [self._union[max(1, lag // 2)] for lag in self.lags]
        out = self._kappa[at][:, rows] - np.clip(self._kappa[half][:, rows], 0, None)
        out[:, ~self._moving[rows]] = 0.0
        return out

    def kappa_at(self, lag: int) -> np.ndarray:
        """Every channel's speed-weighted kappa at ``lag``."""
        if lag not in self._full:
            grid = self.grid
            if lag in self._union and self._done.all():  # rows are independent: the same
                self._full[lag] = self._kappa[self._union[lag]].copy()
            else:
                self._full[lag] = _kappa_by_rows(grid.states, grid.speed, lag, self.size)
        return self._full[lag]


#: Most (state, row, point) cells one batch of :func:`_weighted_kappa` spans: its float
#: temporaries take 8 bytes a cell, so a batch stays near 32 MiB however many channels a
#: long take has (rows are independent: batching changes no number).
_BATCH_CELLS = 1 << 22


def _alike_rows(states: np.ndarray, rows: list[int]) -> list[list[int]]:
    """``rows`` in batches when together they hold few states (as many rows a batch as
    :data:`_BATCH_CELLS` allows), else one row a batch."""
    present = len(_present(states[rows]))
    if present > 16:
        return [[r] for r in rows]
    per = max(1, _BATCH_CELLS // (max(present, 1) * max(states.shape[1], 1)))
    return [rows[i:i + per] for i in range(0, len(rows), per)]


def lag_scores(grid: Grid, size: int, conf: MotionConf) -> LagScores:
    """The cycle scores of one performance at every candidate lag (see :class:`LagScores`)."""
    return LagScores(grid, size, _lags(grid, conf))


def joint_period(scored: LagScores, rows: tuple[int, ...], conf: MotionConf) -> int | None:
    """A joint's period in one performance (grid points), or None when it does not cycle.

    ``scored`` is :func:`lag_scores` of the performance; the joint's score at
    a lag is the mean over its channels. The period is the shortest peak
    within 15% of the highest (a peak at twice the period is as high).
    """
    lags = scored.lags
    if len(lags) < 2:
        return None
    scores = scored.table(rows).mean(axis=1)
    top = float(scores.max())
    if top <= conf.min_cycle_score:
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
    weighted, half_weighted = scored.kappa_at(lag), scored.kappa_at(half)
    score = weighted - np.clip(half_weighted, 0, None)
    s = grid.states
    obs, chance, _ = agreement_counts(np.stack([s, s]),
                                      np.stack([_later(s, lag), _later(s, half)]), size)
    return score, obs[0], np.maximum(chance[0], obs[1])


def cycle_evidence(grids: list[Grid], scored: list[LagScores], periods: list[int | None],
                   size: int, paths: np.ndarray, segments: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray]:
    """Per channel: median over performances of repeated motion and log10 p at the periods."""
    repeated, counts = cycle_counts(grids, scored, periods, size, paths, segments)
    return repeated, np.array([tail(*c) for c in counts])


def cycle_counts(grids: list[Grid], scored: list[LagScores], periods: list[int | None],
                 size: int, paths: np.ndarray, segments: np.ndarray
                 ) -> tuple[np.ndarray, list[tuple[int, int, float]]]:
    """Per channel: the median repeated motion, and the (agreeing, trials, null) that its
    test takes (:func:`tail`)."""
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
    counts = [(int(k), int(n), float(c)) for k, n, c in zip(agreeing, trials, null)]
    return np.median(repeated, axis=0), counts


def tail(k: int, n: int, c: float) -> float:
    """log10 p of ``k`` agreeing of ``n`` trials at the null level ``c`` (0 when untestable)."""
    return log10_binom_sf(k, n, c) if n > 0 and c < 1 else 0.0


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
    # indicators (performance, row, state, point); for every circular shift k the other
    # copy's indicators at point j - k: the joint tallies of a pair at every shift are one
    # matrix product of zeros and ones (exact)
    # only the states the cycles hold: an absent one tallies nothing and adds exactly 0
    present = _present(np.array(means))
    if len(present) == 0:
        present = np.zeros(1, dtype=np.int64)
    size = len(present)
    states = present[:, None]
    mine = (np.array(means)[:, :, None, :] == states).astype(float)
    turn = (np.arange(width)[None, :] - np.arange(width)[:, None]) % width  # (shift, point)
    others = mine[..., turn].reshape(len(means), len(rows), size * width, width)
    others = np.swapaxes(others, 2, 3)                 # (performance, row, point, b x shift)
    scores: list[float] = []
    for p in range(len(means) - 1):                    # the pairs in the loop's order
        joint = mine[p][None] @ others[p + 1:]        # whole numbers, exactly
        joint = joint.reshape(-1, len(rows), size, size, width)        # (q, row, a, b, shift)
        obs, chance, _ = from_tallies(np.ascontiguousarray(np.moveaxis(joint, 4, 1)))
        per_shift = kappa(obs, chance).mean(axis=-1)   # (q, shift): mean over the rows
        scores.extend(np.maximum(per_shift.max(axis=1), -1.0).tolist())
    return float(np.mean(scores))


@dataclass
class CycleEvidence:
    """Cycle evidence of one learning run, remembered per set of periods (a working record:
    the leader search asks for the same periods once per joint that has them)."""

    grids: list[Grid]
    scored: list[LagScores]
    size: int
    paths: np.ndarray
    segments: np.ndarray
    _counts: dict = field(default_factory=dict)
    _alike: dict = field(default_factory=dict)
    _tails: dict = field(default_factory=dict)

    def cycles(self, periods: list[int | None], rows: tuple[int, ...] | None = None
               ) -> tuple[np.ndarray, np.ndarray]:
        """:func:`cycle_evidence` at ``periods``; with ``rows``, log10 p is computed for
        those channels only (0 elsewhere: a joint's test looks at its own channels)."""
        key = tuple(periods)
        if key not in self._counts:
            self._counts[key] = cycle_counts(self.grids, self.scored, periods, self.size,
                                             self.paths, self.segments)
        repeated, counts = self._counts[key]
        log_p = np.zeros(len(counts))
        for c in range(len(counts)) if rows is None else rows:
            if (key, c) not in self._tails:
                self._tails[key, c] = tail(*counts[c])
            log_p[c] = self._tails[key, c]
        return repeated, log_p

    def alike(self, periods: list[int | None], rows: tuple[int, ...]) -> float:
        """:func:`cycles_alike` at ``periods`` on ``rows``."""
        key = (tuple(periods), tuple(rows))
        if key not in self._alike:
            self._alike[key] = cycles_alike(self.grids, periods, rows, self.size)
        return self._alike[key]
