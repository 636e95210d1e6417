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

from ....actiongram import Actiongram


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
    longest = max(b - a for a, b in map(_span, performances))
    return max(step, longest / max_points, 1e-12)


def grid_points(ag: Actiongram, step: float) -> int:
    """How many points :func:`sample` samples ``ag`` at, ``step`` seconds apart (one at least).

    Examples
    --------
    >>> grid_points(Actiongram.from_strings({"knee": "abab"}), 0.5)
    8
    """
    t0, t1 = _span(ag)
    return max(1, int((t1 - t0) / step + 1e-9))


def _span(ag: Actiongram) -> tuple[float, float]:
    present = [(o, o + sum(d)) for o, d in zip(ag.origins, ag.segment_durations) if len(d)]
    if not present:
        return 0.0, 0.0
    return min(a for a, _ in present), max(b for _, b in present)


def sample(ag: Actiongram, codes: dict[str, int], step: float) -> Grid:
    """The states and velocities of every string of ``ag`` at the grid points.

    All strings at once: segment ends padded into one array (row, segment),
    each grid time looked up in its own row by one sorted search over
    (row, end) pairs; the same ends, comparisons and rates as string by string.
    """
    t0, _ = _span(ag)
    count = grid_points(ag, step)
    times = t0 + step * (np.arange(count) + 0.5)
    states = np.full((len(ag), count), -1, dtype=np.int64)
    velocity = np.zeros((len(ag), count))
    present = [r for r, syms in enumerate(ag.symbols) if syms]
    if not present:
        return Grid(states, velocity, step, t0)
    for r in present:  # new symbols coded in order of first appearance
        for sym in dict.fromkeys(ag.symbols[r]):
            codes.setdefault(sym, len(codes))
    lengths = np.array([len(ag.symbols[r]) for r in present])
    width = int(lengths.max())
    filled = np.arange(width)[None, :] < lengths[:, None]
    durations = np.zeros((len(present), width))
    durations[filled] = np.concatenate([np.asarray(ag.segment_durations[r], dtype=float)
                                        for r in present])
    origins = np.array([float(ag.origins[r]) for r in present])
    ends = origins[:, None] + np.cumsum(durations, axis=1)   # a running sum: as per string
    ends[~filled] = np.inf
    # (row, time) pairs ordered row first: complex numbers compare that way
    keys = np.empty(ends.shape, dtype=complex)
    keys.real, keys.imag = np.arange(len(present))[:, None], ends
    probes = np.empty((len(present), count), dtype=complex)
    probes.real, probes.imag = np.arange(len(present))[:, None], times[None, :]
    index = np.searchsorted(keys.ravel(), probes.ravel(), side="right").reshape(probes.shape) \
        - (np.arange(len(present)) * width)[:, None]
    inside = (times[None, :] >= origins[:, None]) & (index < lengths[:, None])
    symbol_codes = np.zeros((len(present), width), dtype=np.int64)
    symbol_codes[filled] = _coded([ag.symbols[r] for r in present], codes)
    rates = np.ones((len(present), width))
    for i, r in enumerate(present):
        disps = ag.segment_displacements[r]
        if disps is not None:
            rates[i, :lengths[i]] = np.asarray(disps) / durations[i, :lengths[i]]
    at = np.minimum(index, width - 1)
    rows = np.array(present)
    states[rows] = np.where(inside, np.take_along_axis(symbol_codes, at, axis=1), -1)
    velocity[rows] = np.where(inside, np.take_along_axis(rates, at, axis=1), 0.0)
    return Grid(states, velocity, step, t0)


def _coded(strings: list[tuple[str, ...]], codes: dict[str, int]) -> np.ndarray:
    """The codes of every symbol of ``strings``, one after another. Symbols of one ASCII
    character each (kinetemes are) go through a lookup table, the others through the dict."""
    if all(len(sym) == 1 and sym.isascii() for sym in codes):
        text = "".join("".join(syms) for syms in strings).encode("ascii")
        table = np.zeros(128, dtype=np.int64)
        for sym, code in codes.items():
            table[ord(sym)] = code
        return table[np.frombuffer(text, dtype=np.uint8)]
    return np.fromiter(map(codes.__getitem__, (sym for syms in strings for sym in syms)),
                       np.int64, sum(len(syms) for syms in strings))


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
    # only the states that occur: an absent one has share 0 and adds exactly 0 to chance
    syms = np.union1d(a[a >= 0], b[b >= 0])[:, None, None]
    share_a = ((a[None] == syms) * w[None]).sum(axis=2) / div
    share_b = ((b[None] == syms) * w[None]).sum(axis=2) / div
    # summed state after state (accumulate is sequential)
    chance = np.add.accumulate(share_a * share_b, axis=0)[-1] if len(syms) \
        else np.zeros(a.shape[0])
    return observed, chance, total


def agreement_counts(a: np.ndarray, b: np.ndarray, size: int
                     ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`agreement` with every weight 1, from integer counts (the same numbers).

    The last axis is time; any leading axes (rows, shifts, pairs) are kept, so
    many comparisons are one call. Counts are exact, so the shares, and the
    chance level summed over the states in the same order, are bit for bit
    those of ``agreement(a, b, np.ones(a.shape), size)``. States are below ``size``.
    """
    a, b = np.asarray(a), np.asarray(b)
    lead = np.broadcast_shapes(a.shape, b.shape)[:-1]
    rows = int(np.prod(lead, dtype=np.int64))
    shape = lead + (max(a.shape[-1], b.shape[-1]),)
    a = np.broadcast_to(a, shape).reshape(rows, -1)
    b = np.broadcast_to(b, shape).reshape(rows, -1)
    # the margins of the joint tally, counted directly (not the tally itself, whose
    # size * size cells per row would make the cost grow with the square of the alphabet)
    valid = (a >= 0) & (b >= 0)
    base = (np.arange(rows, dtype=np.int64) * size)[:, None]
    of_a = np.bincount((a + base)[valid], minlength=rows * size).reshape(rows, size)
    of_b = np.bincount((b + base)[valid], minlength=rows * size).reshape(rows, size)
    same = ((a == b) & valid).sum(axis=1)
    observed, chance, total = _from_margins(of_a, of_b, same)
    return observed.reshape(lead), chance.reshape(lead), total.reshape(lead)


def from_tallies(joint: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`agreement_counts` from joint tallies ``(..., state of a, state of b)``."""
    size = joint.shape[-1]
    lead = joint.shape[:-2]
    joint = joint.reshape(-1, size, size)
    # the margins and the diagonal are sums of whole numbers: exact in any order
    observed, chance, total = _from_margins(joint.sum(axis=2), joint.sum(axis=1),
                                            np.trace(joint, axis1=1, axis2=2))
    return observed.reshape(lead), chance.reshape(lead), total.reshape(lead)


def _from_margins(of_a: np.ndarray, of_b: np.ndarray, same: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Observed share, chance level and total from the counts of each state (rows, state)
    in ``a`` and in ``b`` over the points where both are present, and of agreeing points."""
    of_a, of_b = of_a.astype(float), of_b.astype(float)
    total = of_a.sum(axis=1)
    div = np.maximum(total, 1e-300)
    products = (of_a / div[:, None]) * (of_b / div[:, None])
    # summed state after state, in the order agreement sums them (accumulate is sequential)
    chance = np.add.accumulate(products, axis=1)[:, -1] if products.shape[1] \
        else np.zeros(len(total))
    return np.asarray(same, dtype=float) / div, chance, total


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
