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
        for s in dict.fromkeys(syms):  # new symbols coded in order of first appearance
            codes.setdefault(s, len(codes))
        symbol_codes = np.fromiter(map(codes.__getitem__, syms), np.int64, len(syms))
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
    div = np.maximum(total, 1e-300)
    observed = same.sum(axis=1) / div
    # every state's weighted share in one array (state, row, point): each (state, row) is
    # summed along its points exactly as a per-state loop would, so the numbers are the same
    syms = np.arange(size)[:, None, None]
    share_a = ((a[None] == syms) * w[None]).sum(axis=2) / div
    share_b = ((b[None] == syms) * w[None]).sum(axis=2) / div
    chance = np.zeros(a.shape[0])
    for sym in range(size):
        chance += share_a[sym] * share_b[sym]
    return observed, chance, total


def agreement_counts(a: np.ndarray, b: np.ndarray, size: int
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`agreement` with every weight 1, from integer counts (the same numbers).

    The last axis is time; any leading axes (rows, shifts, pairs) are kept, so
    many comparisons are one call. Counts are exact, so the shares, and the
    chance level summed over the states in the same order, are bit for bit
    those of ``agreement(a, b, np.ones(a.shape), size)``. States are below ``size``.
    """
    a, b = np.broadcast_arrays(np.asarray(a), np.asarray(b))
    lead, points = a.shape[:-1], a.shape[-1]
    rows = int(np.prod(lead, dtype=np.int64))
    a2, b2 = a.reshape(rows, points), b.reshape(rows, points)
    valid = (a2 >= 0) & (b2 >= 0)
    total = valid.sum(axis=1).astype(float)
    same = ((a2 == b2) & valid).sum(axis=1)
    base = np.arange(rows, dtype=np.int64)[:, None] * size
    div = np.maximum(total, 1e-300)
    share_a = np.bincount((base + a2)[valid], minlength=rows * size).reshape(rows, size) \
        / div[:, None]
    share_b = np.bincount((base + b2)[valid], minlength=rows * size).reshape(rows, size) \
        / div[:, None]
    chance = np.zeros(rows)
    for sym in range(size):  # in the order agreement sums them
        chance += share_a[:, sym] * share_b[:, sym]
    return (same / div).reshape(lead), chance.reshape(lead), total.reshape(lead)


def plurality(copies: np.ndarray) -> np.ndarray:
    """Per column of ``copies`` (copies, columns) the most common state, the lowest among
    equals; -1 where every copy is absent (-1). Leading axes before the copies are kept."""
    copies = np.asarray(copies)
    lead, count, columns = copies.shape[:-2], copies.shape[-2], copies.shape[-1]
    flat = np.moveaxis(copies.reshape((-1, count, columns)), 1, 2).reshape(-1, count)
    top = int(flat.max(initial=-1)) + 1
    if top == 0:
        return np.full(lead + (columns,), -1, dtype=np.int64)
    valid = flat >= 0
    base = np.arange(flat.shape[0], dtype=np.int64)[:, None] * top
    tally = np.bincount((base + flat)[valid], minlength=flat.shape[0] * top) \
        .reshape(flat.shape[0], top)
    out = np.where(valid.any(axis=1), tally.argmax(axis=1), -1).astype(np.int64)
    return out.reshape(lead + (columns,))


def kappa(observed: np.ndarray, chance: np.ndarray) -> np.ndarray:
    """Agreement corrected for chance: (observed - chance) / (1 - chance); 0 where chance is 1."""
    room = 1.0 - chance
    return np.where(room > 1e-9, (observed - chance) / np.maximum(room, 1e-9), 0.0)
