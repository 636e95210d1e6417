"""The motion pattern of each component channel, and its morphemes (kinetemes, times, angles).

Copies are the leader's cycles in every performance when the action cycles,
else the whole performances (time-normalised and aligned). Every copy is
stretched to a common number of points (cycles turned to a common phase);
each point's plurality (the state most copies agree on) picks the medoid
copy, the copy agreeing with it at most points (among copies whose changes
other copies make too and whose length is within a quarter of the median).
The pattern is the medoid's own segments in its performance
(:func:`copy_segments`): from the segment border where the copy begins to
where its first kineteme begins again, about a copy later, so that the
pattern repeated makes only changes a performance makes, never a splice no
copy shows (a point-wise plurality, or the grid itself, which can step over a
one-frame segment, can splice them). A kineteme's typical duration is its
segment's, the stretch brought to the median copy's length; its angular
displacement is its segment's own.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ....actiongram import Actiongram
from .grids import Grid, plurality, resample
from ..period import track_windows

if TYPE_CHECKING:
    from .results import MotionResult


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


def read_patterns(result: MotionResult, grids: list[Grid], periods, shifts,
                  takes: tuple[Actiongram, ...] | None = None) -> None:
    """Fill the result's patterns, occurrences, typical durations and displacements.

    With ``takes`` (the performances the grids sample), each pattern is read from the
    medoid copy's own segments (:func:`copy_segments`), else from its grid points.
    """
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
    typical = float(np.median(seconds)) * width  # the median copy's length, seconds
    code = {sym: c for c, sym in enumerate(result.symbols)}
    # copies within a quarter of the median length: the medoid is one of them when it can
    # be, so that its own segments, brought to the median tempo, keep their proportions
    # at a tempo the action is performed at (a slow performance's kineteme of one frame,
    # at a faster tempo, lasts less than a frame)
    usual = np.abs(np.log(seconds * width / typical)) <= np.log(1.25)
    # a cycle may close anywhere from half to three copies on (a joint can cycle once in two
    # of the leader's cycles); a whole performance likewise: asking it to keep most of itself
    # (0.8 to 1.25) gave one shared-data channel a change generation cannot make at K = 3
    closing = (0.5, 3.0)
    for i, row in enumerate(rows_all):
        ordinary = ordinary_copies(states[:, i], cyclic=bool(periods))
        medoid = medoid_copy(states[:, i], columns[i],
                             ordinary & usual if (ordinary & usual).any() else ordinary)
        k, a, n = windows[medoid]
        phase = (roll[medoid] * n / width) if periods else 0.0
        start = grids[k].t0 + (a + phase) * grids[k].step
        exact = None
        if takes is not None:
            exact = copy_segments(takes[k], row, start, n * grids[k].step, closing)
            if exact is None or len(exact[0]) < 2:  # one kineteme from the phase on: the window
                exact = copy_segments(takes[k], row, grids[k].t0 + a * grids[k].step,
                                      n * grids[k].step, closing)
        if exact is not None and len(exact[0]) >= 2:
            # the medoid's own segments, whole, as the segmentation found them (the grid can
            # step over a one-frame segment and join its neighbours by a change never made)
            symbols, spans, turns = exact
            result.patterns[row] = tuple(code[s] for s in symbols)
            # the stretch brought to the median copy's length: generation gives every channel's
            # morpheme one period of the action (scaling by the copy's tempo instead, a stretch
            # of three copies kept three times the length and squeezed the action's period:
            # four shared-data channels then could not be made at K = 3)
            result.durations[row] = tuple(float(x) for x in spans * (typical / spans.sum()))
            result.displacements[row] = tuple(float(x) for x in turns)
        else:
            runs = copy_runs(states[medoid, i])
            if len(runs) < 2:
                continue
            result.patterns[row] = tuple(sym for sym, _, _ in runs)
            # each kineteme's span on the medoid copy, read on every copy (they are aligned)
            lengths = np.array([b - a for _, a, b in runs])
            # durations: the medoid's proportions at the median tempo (the median over the
            # copies of each span's seconds); angles: the medoid's own, so that the kinetemes,
            # their times and their angles are one real motion's (medians of angles over
            # copies of other strings need not fit the string: measured in docs/praxicon.md)
            result.durations[row] = tuple(
                float(x) for x in np.median(lengths[:, None] * seconds[None, :], axis=1))
            result.displacements[row] = tuple(float(turned[medoid, i, a:b].sum())
                                              for _, a, b in runs)
        result.occurrences[row] = [(grids[k].t0 + a * grids[k].step,
                                    grids[k].t0 + (a + n) * grids[k].step)
                                   for k, a, n in windows]
        result.occurrence_performance[row] = [k for k, _, _ in windows]


def copy_segments(take: Actiongram, row: int, start: float, length: float,
                  closing: tuple[float, float] = (0.5, 3.0)
                  ) -> tuple[tuple[str, ...], np.ndarray, np.ndarray] | None:
    """One channel's whole segments over one copy: ``(symbols, durations, displacements)``.

    The copy begins at the segment border nearest ``start`` and ends at the border where
    the same kineteme begins again, about ``length`` seconds away (before or after; the
    nearest to ``length`` within ``closing`` times it), so that the string repeated
    makes only changes the take makes: its last kineteme runs into its first there.
    Without such a border it ends at the border nearest ``start + length``.

    Parameters
    ----------
    take : Actiongram
        The performance the copy is in.
    row : int
        The channel's string in ``take``.
    start, length : float
        Where the copy begins and how long it is, seconds.
    closing : (float, float)
        How far, in copy lengths, the border where the first kineteme begins again may be
        (default half to three).

    Returns
    -------
    tuple or None
        The kinetemes, and per kineteme its duration and angle (the duration again
        when the take has no displacements: the grid's velocity is then 1); None for a
        string of fewer than two kinetemes.

    Examples
    --------
    >>> from psgs.actiongram import Actiongram
    >>> take = Actiongram(("x",), (tuple("BGRYBGRYB"),), ((1.0,) * 9,))
    >>> copy_segments(take, 0, 1.2, 4.0)[0]
    ('G', 'R', 'Y', 'B')
    >>> copy_segments(take, 0, 0.0, 2.9)[0]  # B begins again 4 s on
    ('B', 'G', 'R', 'Y')
    >>> once = Actiongram(("x",), (tuple("BGRY"),), ((1.0,) * 4,))
    >>> copy_segments(once, 0, 0.0, 2.9)[0]  # no B again: to the border nearest 2.9 s
    ('B', 'G', 'R')
    """
    symbols = take.symbols[row]
    durations = np.asarray(take.segment_durations[row], dtype=float)
    if len(symbols) < 2:
        return None
    moves = take.segment_displacements[row] if take.segment_displacements else None
    moves = durations if moves is None else np.asarray(moves, dtype=float)
    borders = take.origins[row] + np.concatenate(([0.0], np.cumsum(durations)))
    first = int(np.argmin(np.abs(borders[:-1] - start)))
    # where the first kineteme begins again, before or after, within ``closing`` lengths
    # away: the copy repeated then makes only changes the take makes
    again = np.array([j for j in range(len(symbols)) if j != first and symbols[j] == symbols[first]],
                     dtype=np.int64)
    spans = np.abs(borders[again] - borders[first])
    fits = (spans >= closing[0] * length) & (spans <= closing[1] * length)
    if fits.any():
        other = int(again[fits][np.argmin(np.abs(spans[fits] - length))])
        first, last = min(first, other), max(first, other)
    else:  # none: to the border nearest ``start + length`` (changes made, but the last
        # kineteme need not run into the first)
        later = borders[first + 1:]
        last = first + 1 + int(np.argmin(np.abs(later - (borders[first] + length))))
    return tuple(symbols[first:last]), durations[first:last], moves[first:last]


def ordinary_copies(copies: np.ndarray, cyclic: bool = True) -> np.ndarray:
    """Which copies make only changes of state that other copies make too.

    A change (one state's run followed by another's; for cycles, the last run into the
    first as well) is ordinary when at least two copies and a tenth of them make it.
    A copy with a change no other copy makes carries a rare event of its take (a
    segmentation's ~1 in 1,000 change across a dead band), not the action.

    Parameters
    ----------
    copies : numpy.ndarray
        One channel's stretched copies, ``(copies, points)`` state codes, -1 absent.
    cyclic : bool, optional
        Whether the copies are cycles (their end runs into their start).

    Returns
    -------
    numpy.ndarray
        ``(copies,)`` booleans; every copy when there is only one.

    Examples
    --------
    >>> import numpy as np
    >>> ordinary_copies(np.array([[0, 1, 2], [0, 1, 2], [0, 2, 2]])).tolist()
    [True, True, False]
    """
    changes = [_changes(c, cyclic) for c in copies]
    counts: dict[tuple[int, int], int] = {}
    for made in changes:
        for change in made:
            counts[change] = counts.get(change, 0) + 1
    enough = max(2, -(-len(copies) // 10))
    if len(copies) < 2:
        return np.ones(len(copies), dtype=bool)
    return np.array([all(counts[c] >= enough for c in made) for made in changes], dtype=bool)


def _changes(states: np.ndarray, cyclic: bool) -> set[tuple[int, int]]:
    """The changes of state of one copy, a cycle's wrap (last state into first) included."""
    runs = [s for s, _, _ in copy_runs(states)]
    if cyclic and len(runs) > 1 and runs[-1] != runs[0]:
        runs.append(runs[0])
    return set(zip(runs, runs[1:]))


def medoid_copy(copies: np.ndarray, column: np.ndarray, allowed: np.ndarray | None = None
                ) -> int:
    """The copy (row of ``copies``, copies x points) agreeing with ``column`` at most points.

    Points where the column is absent (-1) do not count; among equals the first copy
    (earliest performance, then earliest cycle) wins, so the choice is deterministic. With
    ``allowed``, only those copies compete (all of them when none is allowed).

    Parameters
    ----------
    copies : numpy.ndarray
        One channel's stretched copies, ``(copies, points)`` state codes, -1 absent.
    column : numpy.ndarray
        Their plurality, ``(points,)`` (:func:`psgs.induce.pal.motion.grids.plurality`).
    allowed : numpy.ndarray, optional
        ``(copies,)`` booleans, e.g. :func:`ordinary_copies`.

    Returns
    -------
    int
        The index of the medoid copy.

    Examples
    --------
    >>> import numpy as np
    >>> copies = np.array([[0, 0, 1, 1], [0, 1, 1, 2], [0, 0, 1, 2]])
    >>> medoid_copy(copies, np.array([0, 0, 1, 2]))
    2
    """
    agree = ((copies == column[None, :]) & (column >= 0)[None, :]).sum(axis=1)
    if allowed is not None and allowed.any():
        agree = np.where(allowed, agree, -1)
    return int(np.argmax(agree))


def copy_runs(states: np.ndarray) -> list[tuple[int, int, int]]:
    """``(state, first, end)`` of each run of one copy's states, every run kept.

    Absent points (-1) join the run before them (the first run when they lead), so the
    spans tile the copy and times add up. No run is dropped, however short: dropping one
    would join its neighbours by a transition the copy never made (the fault of the
    plurality pattern this replaces), so the kineteme string is exactly the copy's.

    Parameters
    ----------
    states : numpy.ndarray
        One copy's state codes, ``(points,)``, -1 absent.

    Returns
    -------
    list of tuple of int
        ``(state, first point, end point)`` per run; empty when every point is absent.

    Examples
    --------
    >>> import numpy as np
    >>> copy_runs(np.array([-1, 0, 0, 2, -1, 1, 1]))
    [(0, 0, 3), (2, 3, 5), (1, 5, 7)]
    """
    runs: list[list[int]] = []
    for k, sym in enumerate(states.tolist()):
        if sym < 0 or (runs and runs[-1][0] == sym):
            if runs:
                runs[-1][2] = k + 1
            continue
        runs.append([sym, k, k + 1])
    if runs:
        runs[0][1] = 0
    return [(s, a, b) for s, a, b in runs]


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
