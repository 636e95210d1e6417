"""Performances sampled on time grids: kineteme states, speeds, chance-corrected agreement.

Real motion arrives as several performances of one action, each an actiongram
whose strings are a joint's channels. Everything the real-motion learner
measures is read from three arrays per performance, sampled on one time step:
the state code of every channel (-1 outside its string), its signed angular
velocity (a segment's displacement over its duration; 1 when the actiongram
carries no displacements, so that "motion" is then time) and the speed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...actiongram import Actiongram


@dataclass(frozen=True, eq=False)
class Grid:
    """One performance on a time grid of ``step`` seconds starting at ``t0``."""

    states: np.ndarray    # (channels, points) int: state code, -1 where the string is absent
    velocity: np.ndarray  # (channels, points) float: signed displacement per second (or 1)
    step: float
    t0: float

    @property
    def points(self) -> int:
        return self.states.shape[1]

    @property
    def speed(self) -> np.ndarray:
        return np.abs(self.velocity)


def grid_step(performances: tuple[Actiongram, ...], max_points: int = 4096) -> float:
    """One time step for all performances: half the lower quartile of segment durations.

    Most segments then span two points or more; the step is coarser when a
    performance would need more than ``max_points`` points (a time bound).
    """
    durations = np.concatenate([np.asarray(d, dtype=float) for ag in performances
                                for d in ag.segment_durations if len(d)] or [np.ones(1)])
    step = float(np.quantile(durations, 0.25)) / 2
    longest = max(_span(ag)[1] - _span(ag)[0] for ag in performances)
    return max(step, longest / max_points, 1e-12)


def _span(ag: Actiongram) -> tuple[float, float]:
    present = [(o, o + sum(d)) for o, d in zip(ag.origins, ag.segment_durations) if len(d)]
    if not present:
        return 0.0, 0.0
    return min(a for a, _ in present), max(b for _, b in present)


def sample(ag: Actiongram, codes: dict[str, int], step: float) -> Grid:
    """The states and velocities of every string of ``ag`` at the grid points."""
    t0, t1 = _span(ag)
    count = max(1, int((t1 - t0) / step + 1e-9))
    times = t0 + step * (np.arange(count) + 0.5)
    states = np.full((len(ag), count), -1, dtype=np.int64)
    velocity = np.zeros((len(ag), count))
    for row, (syms, durs, origin, disps) in enumerate(zip(
            ag.symbols, ag.segment_durations, ag.origins, ag.segment_displacements)):
        if not syms:
            continue
        durs_a = np.asarray(durs, dtype=float)
        ends = origin + np.cumsum(durs_a)
        index = np.searchsorted(ends, times, side="right")
        inside = (times >= origin) & (index < len(syms))
        symbol_codes = np.array([codes.setdefault(s, len(codes)) for s in syms], dtype=np.int64)
        states[row, inside] = symbol_codes[index[inside]]
        rate = np.ones(len(syms)) if disps is None else np.asarray(disps) / durs_a
        velocity[row, inside] = rate[index[inside]]
    return Grid(states, velocity, step, t0)


def resample(values: np.ndarray, length: int) -> np.ndarray:
    """``values`` (rows, points) stretched or squeezed in time to ``length`` points (nearest)."""
    points = values.shape[1]
    index = np.minimum((np.arange(length) + 0.5) * points / length, points - 1).astype(np.int64)
    return values[:, index]


def agreement(a: np.ndarray, b: np.ndarray, weight: np.ndarray, size: int
              ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per row: weighted share of points where ``a`` and ``b`` agree, its chance level, weight.

    The chance level is what two strings with these state shares (weighted the
    same way) would reach by chance: the sum over states of the product of
    their shares. Points where either is absent (-1) do not count.
    """
    valid = (a >= 0) & (b >= 0)
    w = np.where(valid, weight, 0.0)
    total = w.sum(axis=1)
    same = ((a == b) & valid) * w
    observed = same.sum(axis=1) / np.maximum(total, 1e-300)
    chance = np.zeros(a.shape[0])
    for sym in range(size):
        share_a = ((a == sym) * w).sum(axis=1) / np.maximum(total, 1e-300)
        share_b = ((b == sym) * w).sum(axis=1) / np.maximum(total, 1e-300)
        chance += share_a * share_b
    return observed, chance, total


def kappa(observed: np.ndarray, chance: np.ndarray) -> np.ndarray:
    """Agreement corrected for chance: (observed - chance) / (1 - chance); 0 where chance is 1."""
    room = 1.0 - chance
    return np.where(room > 1e-9, (observed - chance) / np.maximum(room, 1e-9), 0.0)
