"""The batched kernels of PAL's real-motion learner give the numbers of the plain forms.

Each kernel replaced a loop of small array operations (one per state, shift,
lag or pair) by one operation over all of them. The plain form is written out
here, as it was, and the two are compared on small random arrays: equal bit
for bit, since a learner's answers must not depend on how fast it runs.
"""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st
from hypothesis.extra.numpy import arrays

from psgs.induce.pal.motion.cycles import _weighted_kappa, cycles_alike
from psgs.induce.pal.motion.grids import Grid, agreement, agreement_counts, kappa, plurality, resample
from psgs.induce.pal.motion.morphemes import _cycle_phases, _rolled
from psgs.induce.pal.motion.performances import _best_shift, _consensus_test, _overlap, _pairwise_test


# -- the plain forms -----------------------------------------------------------------------
def plain_agreement(a, b, weight, size):
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


def plain_plurality(copies):
    out = np.full(copies.shape[1], -1, dtype=np.int64)
    for c in range(copies.shape[1]):
        values = copies[:, c]
        values = values[values >= 0]
        if len(values):
            out[c] = int(np.argmax(np.bincount(values)))
    return out


def plain_cycles_alike(grids, periods, rows, size, width=24):
    means = []
    for grid, lag in zip(grids, periods):
        if not lag:
            continue
        count = grid.points // lag
        cycles = grid.states[list(rows), :count * lag].reshape(len(rows), count, lag)
        means.append(np.array([plain_plurality(resample(c, width)) for c in cycles]))
    if len(means) < 2:
        return 0.0
    scores = []
    for p in range(len(means)):
        for q in range(p + 1, len(means)):
            best = -1.0
            for shift in range(width):
                obs, chance, _ = plain_agreement(means[p], np.roll(means[q], shift, axis=1),
                                                 np.ones(means[p].shape), size)
                best = max(best, float(kappa(obs, chance).mean()))
            scores.append(best)
    return float(np.mean(scores))


def plain_cycle_phases(channels):
    copies, width = channels[0].shape
    roll = np.zeros(copies, dtype=np.int64)
    for _ in range(2):
        reference = [plain_plurality(_rolled(c, roll)) for c in channels]
        best = np.full(copies, -1.0)
        chosen = roll.copy()
        for shift in range(width):
            score = sum(((np.roll(c, -shift, axis=1) == ref[None, :]) & (c >= 0)).sum(axis=1)
                        for c, ref in zip(channels, reference))
            better = score > best
            best[better] = score[better]
            chosen[better] = shift
        roll = chosen
    return roll


def plain_best_shift(a, b, reach, size):
    best, best_score = 0, -math.inf
    for shift in sorted(range(-reach, reach + 1), key=abs):
        x, y = _overlap(a, b, shift)
        obs, chance, _ = plain_agreement(x, y, np.ones(x.shape), size)
        score = float((obs - chance).sum())
        if score > best_score + 1e-12:
            best, best_score = shift, score
    return best


# -- strategies ------------------------------------------------------------------------------
SIZE = st.integers(1, 5)


@st.composite
def state_pairs(draw):
    """Two state arrays (rows, points) over ``size`` states, -1 where absent, and weights."""
    size = draw(SIZE)
    rows, points = draw(st.integers(1, 4)), draw(st.integers(1, 40))
    states = st.integers(-1, size - 1)
    a = draw(arrays(np.int64, (rows, points), elements=states))
    b = draw(arrays(np.int64, (rows, points), elements=states))
    w = draw(arrays(np.float64, (rows, points),
                    elements=st.floats(0, 1e3, allow_nan=False, allow_subnormal=False)))
    return size, a, b, w


def same(x, y):
    return all(np.array_equal(u, v) for u, v in zip(x, y))


# -- the checks ------------------------------------------------------------------------------
@given(state_pairs())
def test_agreement_equals_the_loop_over_states(case):
    size, a, b, w = case
    assert same(agreement(a, b, w, size), plain_agreement(a, b, w, size))


@given(state_pairs())
def test_agreement_counts_equal_unit_weights(case):
    size, a, b, _ = case
    assert same(agreement_counts(a, b, size), plain_agreement(a, b, np.ones(a.shape), size))
    # leading axes are many comparisons at once: each the same as alone
    stacked = agreement_counts(np.stack([a, b]), np.stack([b, a]), size)
    assert same([x[1] for x in stacked], plain_agreement(b, a, np.ones(a.shape), size))


@given(st.integers(1, 6).flatmap(lambda n: arrays(
    np.int64, st.tuples(st.integers(1, 3), st.integers(1, 7), st.just(n)),
    elements=st.integers(-1, 4))))
def test_plurality_equals_the_loop_over_columns(copies):
    assert np.array_equal(plurality(copies), np.array([plain_plurality(c) for c in copies]))
    assert np.array_equal(plurality(copies[0]), plain_plurality(copies[0]))


@given(state_pairs(), st.integers(1, 39))
def test_weighted_kappa_at_a_lag_equals_agreement_on_the_slices(case, lag):
    size, states, _, w = case
    lag = min(lag, states.shape[1] - 1)
    if lag < 1:
        return
    obs, chance, _ = plain_agreement(states[:, :-lag], states[:, lag:],
                                     (w[:, :-lag] + w[:, lag:]) / 2, size)
    assert np.array_equal(_weighted_kappa(states, w, lag, size), kappa(obs, chance))


@settings(max_examples=40)
@given(st.data())
def test_cycles_alike_equals_the_loop_over_pairs_and_shifts(data):
    size = data.draw(SIZE)
    rows = data.draw(st.integers(1, 3))
    grids, periods = [], []
    for _ in range(data.draw(st.integers(2, 4))):
        points = data.draw(st.integers(6, 60))
        states = data.draw(arrays(np.int64, (rows, points), elements=st.integers(-1, size - 1)))
        grids.append(Grid(states, np.ones(states.shape), 0.1, 0.0))
        periods.append(data.draw(st.one_of(st.none(), st.integers(2, points // 2))))
    chosen = tuple(range(rows))
    assert cycles_alike(grids, periods, chosen, size) == \
        plain_cycles_alike(grids, periods, chosen, size)


@settings(max_examples=60)
@given(st.data())
def test_cycle_phases_equal_the_loop_over_shifts(data):
    copies, width = data.draw(st.integers(1, 5)), data.draw(st.integers(1, 12))
    channels = [data.draw(arrays(np.int64, (copies, width), elements=st.integers(-1, 3)))
                for _ in range(data.draw(st.integers(1, 3)))]
    assert np.array_equal(_cycle_phases(channels), plain_cycle_phases(channels))


@settings(max_examples=60)
@given(state_pairs(), st.integers(0, 5), st.integers(8, 2000))
def test_best_shift_equals_the_loop_over_shifts(case, reach, budget):
    size, a, b, _ = case
    reach = min(reach, a.shape[1] - 1)
    assert _best_shift(a, b, reach, size, budget) == plain_best_shift(a, b, reach, size)


@settings(max_examples=40)
@given(st.data())
def test_tests_across_performances_equal_their_loops(data):
    size, rows, points = data.draw(SIZE), data.draw(st.integers(1, 3)), data.draw(st.integers(4, 30))
    count = data.draw(st.integers(2, 4))
    states = [data.draw(arrays(np.int64, (rows, points), elements=st.integers(-1, size - 1)))
              for _ in range(count)]
    shifts = [0] + [data.draw(st.integers(-(points // 4), points // 4)) for _ in states[1:]]
    segments = np.array([[data.draw(st.integers(0, 20)) for _ in range(rows)]
                         for _ in states], dtype=float)
    from psgs.induce.pal.statistics import log10_binom_sf

    # the pairs: each pair's overlap counted on its own
    agreeing, trials, chance_sum, pairs = np.zeros(rows), np.zeros(rows), np.zeros(rows), 0
    for p in range(count):
        for q in range(p + 1, count):
            a, b = _overlap(states[p], states[q], shifts[q] - shifts[p])
            obs, chance, _ = plain_agreement(a, b, np.ones(a.shape), size)
            n = (segments[p] + segments[q]) / 2
            agreeing += np.round(obs * n)
            trials += n
            chance_sum += chance
            pairs += 1
    expected = [log10_binom_sf(int(k), int(n), float(c)) if n > 0 else 0.0
                for k, n, c in zip(agreeing, trials, chance_sum / pairs)]
    assert _pairwise_test(states, shifts, segments, size).tolist() == expected
    # the consensus: each performance against the plurality of the others
    placed = []
    for s, shift in zip(states, shifts):
        row = np.full(s.shape, -1, dtype=np.int64)
        row[:, max(shift, 0):points + min(shift, 0)] = s[:, max(-shift, 0):points - max(shift, 0)]
        placed.append(row)
    agreeing, trials, chance_sum = np.zeros(rows), np.zeros(rows), np.zeros(rows)
    for k, row in enumerate(placed):
        others = np.zeros((size,) + row.shape)
        for j, other in enumerate(placed):
            if j != k:
                for sym in range(size):
                    others[sym] += other == sym
        consensus = np.where(others.max(axis=0) > 0, others.argmax(axis=0), -1)
        obs, chance, _ = plain_agreement(row, consensus, np.ones(row.shape), size)
        agreeing += np.round(obs * segments[k])
        trials += segments[k]
        chance_sum += chance * segments[k]
    chance_mean = chance_sum / np.maximum(trials, 1)
    expected = [log10_binom_sf(int(k), int(n), float(c)) if n > 0 and c < 1 else 0.0
                for k, n, c in zip(agreeing, trials, chance_mean)]
    assert _consensus_test(states, shifts, segments, size).tolist() == expected


def plain_sample(ag, codes, step):
    from psgs.induce.pal.motion.grids import _span

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
    return states, velocity


@settings(max_examples=60)
@given(st.data())
def test_sampling_all_strings_at_once_equals_string_by_string(data):
    from psgs import Actiongram
    from psgs.induce.pal.motion.grids import sample

    alphabet = data.draw(st.sampled_from(["YBGR", "ab", ["up", "down", "hold"]]))
    strings, durations, starts, displacements = {}, {}, {}, {}
    for k in range(data.draw(st.integers(1, 4))):
        n = data.draw(st.integers(0, 8))
        strings[f"j{k}.rx"] = [data.draw(st.sampled_from(list(alphabet))) for _ in range(n)]
        durations[f"j{k}.rx"] = [data.draw(st.floats(0.01, 2.0)) for _ in range(n)]
        starts[f"j{k}.rx"] = data.draw(st.floats(0, 1.0))
        if data.draw(st.booleans()):
            displacements[f"j{k}.rx"] = [data.draw(st.floats(-90, 90)) for _ in range(n)]
    ag = Actiongram.from_strings(strings, durations, starts, displacements=displacements)
    step = data.draw(st.floats(0.005, 0.5))
    known = {"Y": 0} if alphabet == "YBGR" else {}  # codes of earlier performances go on
    codes, plain_codes = dict(known), dict(known)
    grid = sample(ag, codes, step)
    states, velocity = plain_sample(ag, plain_codes, step)
    assert np.array_equal(grid.states, states) and np.array_equal(grid.velocity, velocity)
    assert list(codes.items()) == list(plain_codes.items())


@settings(max_examples=40)
@given(state_pairs(), st.data())
def test_lag_scores_asked_channel_by_channel_equal_the_whole_table(case, data):
    from psgs.induce import PAL
    from psgs.induce.pal.motion.cycles import lag_scores

    size, states, _, speed = case
    grid = Grid(states, speed, 0.05, 0.0)
    params = PAL(min_cycle=0.1)
    whole = lag_scores(grid, size, params)
    rows = data.draw(st.lists(st.integers(0, states.shape[0] - 1), max_size=6))
    piecewise = lag_scores(grid, size, params)
    # the plain table: every lag's kappa minus that at half the lag, 0 where still
    path = speed.sum(axis=1)
    moving = path >= 0.01 * max(float(path.max()), 1e-300)
    plain = np.zeros((len(whole.lags), states.shape[0]))
    for k, lag in enumerate(whole.lags):
        at = _weighted_kappa(states, speed, lag, size)
        half = _weighted_kappa(states, speed, max(1, lag // 2), size)
        plain[k] = np.where(moving, at - np.clip(half, 0, None), 0.0)
    assert np.array_equal(piecewise.table(rows), plain[:, rows])
    assert np.array_equal(whole.table(range(states.shape[0])), plain)


@given(state_pairs(), st.integers(1, 39))
def test_kappa_at_a_lag_is_the_same_before_and_after_the_table(case, lag):
    from psgs.induce import PAL
    from psgs.induce.pal.motion.cycles import lag_scores

    size, states, _, speed = case
    lag = min(lag, states.shape[1] - 1)
    if lag < 1:
        return
    grid = Grid(states, speed, 0.05, 0.0)
    fresh = lag_scores(grid, size, PAL(min_cycle=0.1)).kappa_at(lag)
    scored = lag_scores(grid, size, PAL(min_cycle=0.1))
    scored.table(range(states.shape[0]))  # every channel scored first: its kappas reused
    assert np.array_equal(scored.kappa_at(lag), fresh)
    assert np.array_equal(fresh, _weighted_kappa(states, speed, lag, size))
