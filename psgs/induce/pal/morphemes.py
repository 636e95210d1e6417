"""The motion pattern of each component channel, and its morphemes (kinetemes, times, angles).

Copies are the leader's cycles in every performance when the action cycles,
else the whole performances (time-normalised and aligned). Every copy is
stretched to a common number of points; each point takes the state most
copies agree on; runs of one state are the pattern's kinetemes (runs under
two points dropped, as noise). A kineteme's typical duration and angular
displacement are the medians over the copies of its run's duration and of
the angle the channel turns through in it.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .grids import Grid, plurality, resample
from .period import track_windows

if TYPE_CHECKING:
    from .performances import MotionResult


def copy_windows(grids: list[Grid], periods: list[int | None] | None, shifts: list[int],
                 leader_rows: tuple[int, ...]) -> list[tuple[int, int, int]]:
    """``(performance, first point, points)`` of every copy."""
    out = []
    if periods:
        for k, (grid, lag) in enumerate(zip(grids, periods)):
            if not lag:
                continue
            for a in track_windows(grid.states[list(leader_rows)], lag).tolist():
                out.append((k, a, lag))
        if out:
            return out
    length = int(np.median([g.points for g in grids]))
    for k, grid in enumerate(grids):
        # undo the alignment shift (measured on the time-normalised copies)
        start = int(round((shifts[k] if k < len(shifts) else 0) * grid.points / length))
        start = min(max(start, 0), grid.points - 1)
        out.append((k, start, grid.points - start))
    return out


def read_patterns(result: MotionResult, grids: list[Grid], periods, shifts) -> None:
    """Fill the result's patterns, occurrences, typical durations and displacements."""
    leader = next(j for j in result.joints if j.name == result.leader)
    windows = copy_windows(grids, periods, shifts, leader.channels)
    width = int(np.median([n for _, _, n in windows]))
    rows_all = [row for rows in result.channels.values() for row in rows]
    # every copy of every component channel stretched to ``width`` points, one gather per copy
    states = np.array([resample(grids[k].states[rows_all, a:a + n], width)
                       for k, a, n in windows]).reshape(len(windows), len(rows_all), width)
    # the angle turned through at each stretched point: velocity x the time it stands for
    turned = np.array([resample(grids[k].velocity[rows_all, a:a + n], width)
                       * (n * grids[k].step / width) for k, a, n in windows]
                      ).reshape(len(windows), len(rows_all), width)
    seconds = np.array([n * grids[k].step / width for k, _, n in windows])
    if periods and rows_all:
        # cycles start at an arbitrary phase of the action: turn each copy (all its channels
        # together) to agree best with the plurality of the copies
        roll = _cycle_phases([states[:, i] for i in range(len(rows_all))])
        states = np.stack([_rolled(states[:, i], roll) for i in range(len(rows_all))], axis=1)
        turned = np.stack([_rolled(turned[:, i], roll) for i in range(len(rows_all))], axis=1)
    columns = plurality(np.moveaxis(states, 1, 0)) if rows_all else None  # (rows, width)
    for i, row in enumerate(rows_all):
        runs = _runs(columns[i])
        if len(runs) < 2:
            continue
        result.patterns[row] = tuple(sym for sym, _, _ in runs)
        lengths = np.array([b - a for _, a, b in runs])
        result.durations[row] = tuple(
            float(x) for x in np.median(lengths[:, None] * seconds[None, :], axis=1))
        angles = np.array([turned[:, i, a:b].sum(axis=1) for _, a, b in runs])
        result.displacements[row] = tuple(float(x) for x in np.median(angles, axis=1))
        result.occurrences[row] = [(grids[k].t0 + a * grids[k].step,
                                    grids[k].t0 + (a + n) * grids[k].step)
                                   for k, a, n in windows]
        result.occurrence_performance[row] = [k for k, _, _ in windows]


def _runs(column: np.ndarray) -> list[tuple[int, int, int]]:
    """``(state, first, end)`` of each run of one state, runs under two points merged away."""
    runs: list[list[int]] = []
    for k, sym in enumerate(column.tolist()):
        if runs and runs[-1][0] == sym:
            runs[-1][2] = k + 1
        else:
            runs.append([sym, k, k + 1])
    kept = [r for r in runs if r[0] >= 0 and r[2] - r[1] >= 2] or [r for r in runs if r[0] >= 0]
    out: list[list[int]] = []
    for sym, a, b in kept:
        if out and out[-1][0] == sym:
            out[-1][2] = b
        else:
            out.append([sym, a, b])
    # the dropped short runs' points go to the run before them, so times add up
    for k in range(len(out) - 1):
        out[k][2] = out[k + 1][1]
    return [(s, a, b) for s, a, b in out]


def _cycle_phases(channels: list[np.ndarray]) -> np.ndarray:
    """Per copy, the circular shift that best matches the channels' plurality (two passes);
    the first best shift when several match as well."""
    copies, width = channels[0].shape
    roll = np.zeros(copies, dtype=np.int64)
    # turns[s, j] = (j + s) % width: np.roll(c, -s, axis=1)[:, j] = c[:, turns[s, j]]
    turns = (np.arange(width)[None, :] + np.arange(width)[:, None]) % width
    for _ in range(2):
        score = np.zeros((copies, width), dtype=np.int64)
        for c in channels:
            reference = plurality(_rolled(c, roll))
            score += ((c[:, turns] == reference) & (c >= 0)[:, None, :]).sum(axis=2)
        roll = score.argmax(axis=1)
    return roll


def _rolled(values: np.ndarray, roll: np.ndarray) -> np.ndarray:
    """Each row of ``values`` turned left by its ``roll``."""
    index = (np.arange(values.shape[1])[None, :] + roll[:, None]) % values.shape[1]
    return np.take_along_axis(values, index, axis=1)
