"""Real motion: which joints perform an action, from several performances of it.

The recipe, on kineteme strings grouped by joint:

1. **copies at two levels.** Whole performances, time-normalised and aligned
   by a small shift; and cycles within each performance, timed on the leader's
   period in that performance.
2. **agreement corrected for chance.** Where two copies are in the same state,
   weighted by the speed of the motion there, minus what the two copies' own
   state shares give by chance (Cohen's kappa). A large limb doing something
   different in each performance agrees by chance, and scores nothing.
   For cycles the null is the agreement at half the period (an oscillation is
   in anti-phase there, mere stillness or a slow drift is not).
3. **repeated motion.** Per channel, its angular path length times that
   corrected agreement; per joint, the sum over its channels.
4. **a significance test per joint.** Binomial tail of the agreeing segments
   at the chance level, Bonferroni over channels and joints.
5. **the leader**: the significant joint that carries the most repeated motion
   across performances; the cycles are timed on its period (median over
   performances: most must be in step).
6. **shares relative to the leader.** A significant joint at ``joint_share``
   of the leader's repeated motion is a component; a skeleton neighbour (one
   hop) of a component joins at ``neighbour_share``.

With ``evidence="path"`` the same selection runs on plain angular path length
(no kinetemes, no test): the ablation the benchmark reports.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ....actiongram import Actiongram
from ...results import NO_REPETITION
from .cycles import CycleEvidence, joint_period, lag_scores
from .grids import (Grid, agreement, agreement_counts, grid_points, grid_step, kappa, resample,
                    sample)
from .morphemes import read_patterns
from .results import JointEvidence, MotionResult
from ..conf import NO_BOUND
from ..statistics import log10_binom_sf

if TYPE_CHECKING:
    from ....budget import Budget
    from ..conf import Bounds
    from .conf import MotionConf


#: The bytes a channel's grid point of one performance is counted at against ``max_bytes``:
#: its state and velocity (8 bytes each) and a cycle score at one lag (8), the lags of a
#: performance being fewer than its points (at most 4096: every other array is smaller)
GRID_BYTES = 24

#: A joint may lead from its cycles when they are at least this share of the strongest
#: joint's (measured: the waving arm of the benchmark's composite has 0.16 of its foreign arm's).
LEADER_SHARE = 0.1


def learn_motion(takes: tuple[Actiongram, ...], conf: MotionConf, clock: Bounds = NO_BOUND
                 ) -> MotionResult:
    """Steps 1-6 of the module docstring on ``takes`` (same strings, same order).

    ``clock`` is read for each performance sampled, aligned and scored, and for each
    leader tried; past its deadline it raises :class:`~psgs.errors.BoundReached`, as it
    does before a performance is sampled when its :data:`GRID_BYTES` would pass its
    ``max_bytes``.
    """
    codes: dict[str, int] = {}
    step = grid_step(takes)
    grids = []
    for ag in takes:
        clock.check()
        clock.keep(GRID_BYTES * len(ag) * grid_points(ag, step))
        grids.append(sample(ag, codes, step))
    size = max(len(codes), 1)
    first = takes[0]
    joints = [JointEvidence(a, tuple(first.index(c) for c in first.channels(a)))
              for a in first.actuators]
    if not first.names:  # no string: nothing repeats, and the arrays below have no channel
        return MotionResult(NO_REPETITION, joints, None, list(codes))
    segments = np.array([[len(s) for s in ag.symbols] for ag in takes], dtype=float)
    paths = np.array([(g.speed.sum(axis=1) * g.step) for g in grids])  # (takes, channels)
    for j in joints:
        j.path = float(paths[:, list(j.channels)].sum(axis=1).mean())
    symbols = list(codes)
    if conf.evidence == "path":  # the ablation: magnitude only, whole performances
        result = _select(joints, paths.mean(axis=0), np.zeros(len(first)), first, conf,
                         symbols, tested=False)
        if result.verdict == "":
            read_patterns(result, grids, None, [0] * len(grids), takes)
        return result

    repeated = np.zeros(len(first))
    log_p = np.zeros(len(first))
    shifts: list[int] = []
    if len(takes) >= 2:
        shifts, cross, cross_p = _across(grids, size, paths, segments, conf, clock)
        repeated, log_p = cross, cross_p
    scored = []
    for g in grids:
        clock.check()
        scored.append(lag_scores(g, size, conf))
    evidence = CycleEvidence(grids, scored, size, paths, segments)
    clock.check()
    leaders = _first_leaders(joints, repeated, log_p, evidence, conf) or [None]
    result = None
    for k, leader in enumerate(leaders[:3]):  # a leader alone (none in step) gives way
        clock.check()
        # each further try is held to a 100 times stricter test (it is one more look)
        tried = _with_cycles(leader, joints, repeated, log_p, evidence, first, conf,
                             symbols, extra=2.0 * k)
        if result is None or (result[0].verdict and not tried[0].verdict):
            result = tried
        if not tried[0].verdict:
            break
    found, periods = result
    if found.verdict == "":
        clock.check()
        read_patterns(found, grids, periods, shifts, takes)
        if periods:
            found.period = float(np.median([p for p in periods if p])) * step
    return found


def _with_cycles(leader, joints, repeated, log_p, evidence: CycleEvidence, first, conf,
                 symbols, extra: float = 0.0):
    """The selection with the cycles timed on ``leader`` (when most performances cycle)."""
    periods = None
    if leader is not None:
        periods = [joint_period(sc, leader.channels, conf) for sc in evidence.scored]
        found = [p for p in periods if p]
        if len(found) * 2 > len(evidence.grids):  # most performances cycle on that period
            cyc, cyc_p = evidence.cycles(periods)
            repeated = np.maximum(repeated, cyc)
            log_p = np.minimum(log_p, cyc_p)
        else:
            periods = None
    for j in joints:
        j.status, j.share = "not significant", 0.0
    return _select(joints, repeated, log_p, first, conf, symbols, tested=True,
                   extra=extra), periods


# -- evidence across performances ----------------------------------------------------------
def _across(grids: list[Grid], size: int, paths: np.ndarray, segments: np.ndarray,
            conf: MotionConf, clock: Budget = NO_BOUND
            ) -> tuple[list[int], np.ndarray, np.ndarray]:
    """Per channel: repeated motion and log10 p across aligned, time-normalised performances."""
    length = int(np.median([g.points for g in grids]))
    states = [resample(g.states, length) for g in grids]
    speeds = [resample(g.speed, length) for g in grids]
    reach = int(round(conf.max_shift * length))
    reference = states[0]
    shifts = [0]
    for s in states[1:]:
        clock.check()
        shifts.append(_best_shift(reference, s, reach, size))
    clock.check()
    channels = reference.shape[0]
    pairs = [(p, q) for p in range(len(grids)) for q in range(p + 1, len(grids))]
    # pairs at one relative shift overlap over the same length: one agreement call for them
    # all (rows stacked; each row's sums are the ones a call per pair makes)
    kappas: dict[tuple[int, int], np.ndarray] = {}
    by_shift: dict[int, list[tuple[int, int]]] = {}
    for p, q in pairs:
        by_shift.setdefault(shifts[q] - shifts[p], []).append((p, q))
    for shift, group in by_shift.items():
        parts = [(_overlap(states[p], states[q], shift), _overlap(speeds[p], speeds[q], shift))
                 for p, q in group]
        obs_w, chance_w, _ = agreement(np.vstack([a for (a, _), _ in parts]),
                                       np.vstack([b for (_, b), _ in parts]),
                                       np.vstack([(wa + wb) / 2 for _, (wa, wb) in parts]), size)
        for k, pair in enumerate(group):
            rows = slice(k * channels, (k + 1) * channels)
            kappas[pair] = kappa(obs_w[rows], chance_w[rows])
    repeated = np.zeros(channels)
    for p, q in pairs:  # summed in the order of the pairs
        repeated += np.clip(kappas[p, q], 0, None) * (paths[p] + paths[q]) / 2
    pairs = len(pairs)
    repeated /= max(pairs, 1)
    pairwise = _pairwise_test(states, shifts, segments, size)
    consensus = _consensus_test(states, shifts, segments, size)
    # both must hold: the leave-one-out consensus (powerful where copies are few) and the
    # pairs (a limb that agrees with a noisy consensus but with no single other take fails)
    return shifts, repeated, np.maximum(pairwise, consensus)


def _pairwise_test(states, shifts, segments, size) -> np.ndarray:
    """Per channel, log10 p of the agreement between every pair of aligned performances,
    each pair's segments as trials (liberal: the pairs share performances)."""
    channels = states[0].shape[0]
    agreeing, trials, chance_sum, pairs = np.zeros(channels), np.zeros(channels), \
        np.zeros(channels), 0
    index = [(p, q) for p in range(len(states)) for q in range(p + 1, len(states))]
    if index:  # every pair in one call: counts over the overlap, the rest absent
        obs_all, chance_all, _ = agreement_counts(
            np.array([states[p] for p, _ in index]),
            np.array([_placed(states[q], shifts[q] - shifts[p]) for p, q in index]), size)
    for k, (p, q) in enumerate(index):
        n = (segments[p] + segments[q]) / 2
        agreeing += np.round(obs_all[k] * n)
        trials += n
        chance_sum += chance_all[k]
        pairs += 1
    chance_mean = chance_sum / max(pairs, 1)
    return np.array([log10_binom_sf(int(k), int(n), float(c)) if n > 0 else 0.0
                     for k, n, c in zip(agreeing, trials, chance_mean)])


def _consensus_test(states: list[np.ndarray], shifts: list[int], segments: np.ndarray,
                    size: int) -> np.ndarray:
    """Per channel, log10 p that the performances agree with each other only by chance.

    Each performance is compared with the plurality of the others (leave one
    out, on the reference's time axis); its segments are the trials, each
    counted once; the binomial tail of the agreeing ones at the chance level.
    """
    placed = np.array([_placed(s, shift) for s, shift in zip(states, shifts)])
    # per performance, the state counts of all the others: every leave-one-out at once
    mine = (placed[:, None] == np.arange(size)[None, :, None, None]).astype(np.int64)
    others = mine.sum(axis=0)[None] - mine                  # (performance, state, row, point)
    consensus = np.where(others.max(axis=1) > 0, others.argmax(axis=1), -1)
    obs_all, chance_all, _ = agreement_counts(placed, consensus, size)
    channels = placed.shape[1]
    agreeing, trials, chance_sum = np.zeros(channels), np.zeros(channels), np.zeros(channels)
    for k in range(len(placed)):
        agreeing += np.round(obs_all[k] * segments[k])
        trials += segments[k]
        chance_sum += chance_all[k] * segments[k]
    chance_mean = chance_sum / np.maximum(trials, 1)
    return np.array([log10_binom_sf(int(k), int(n), float(c)) if n > 0 and c < 1 else 0.0
                     for k, n, c in zip(agreeing, trials, chance_mean)])


def _overlap(a: np.ndarray, b: np.ndarray, shift: int) -> tuple[np.ndarray, np.ndarray]:
    """The parts of ``a`` and of ``b`` shifted by ``shift`` points that cover the same times."""
    n = a.shape[1]
    if shift >= 0:
        return a[:, shift:], b[:, :n - shift]
    return a[:, :n + shift], b[:, -shift:]


def _placed(b: np.ndarray, shift: int) -> np.ndarray:
    """``b`` on the time axis of ``a``: column ``t`` holds ``b[:, t - shift]``, -1 where
    there is none. Compared with ``a`` it counts the points of ``_overlap(a, b, shift)``."""
    out = np.full(b.shape, -1, dtype=np.int64)
    n = b.shape[1]
    if abs(shift) >= n:
        return out
    if shift >= 0:
        out[:, shift:] = b[:, :n - shift]
    else:
        out[:, :n + shift] = b[:, -shift:]
    return out


def _best_shift(a: np.ndarray, b: np.ndarray, reach: int, size: int,
                budget: int = 1 << 21) -> int:
    """The shift (|shift| <= reach) at which the channels of ``b`` agree best with ``a``
    (the smallest shift among equals; shifts compared in batches of at most ``budget``
    points)."""
    order = sorted(range(-reach, reach + 1), key=abs)
    batch = max(1, budget // max(a.size, 1))
    scores: list[float] = []
    for start in range(0, len(order), batch):
        chunk = order[start:start + batch]
        obs, chance, _ = agreement_counts(a[None], np.array([_placed(b, s) for s in chunk]),
                                          size)
        scores.extend((obs - chance).sum(axis=1).tolist())
    best, best_score = 0, -math.inf
    for shift, score in zip(order, scores):
        if score > best_score + 1e-12:
            best, best_score = shift, score
    return best


# -- the leader and the selection ------------------------------------------------------------
def _significant(joint: JointEvidence, log_p: np.ndarray, joints: int, conf: MotionConf,
                 extra: float = 0.0) -> bool:
    """Whether the joint's best channel beats chance at ``alpha`` (Bonferroni over its
    channels and ``joints``; ``extra`` orders of magnitude stricter)."""
    best = float(min(log_p[list(joint.channels)])) if joint.channels else 0.0
    joint.log10_p = best + math.log10(max(len(joint.channels), 1))
    return joint.log10_p + math.log10(max(joints, 1)) + extra <= math.log10(conf.alpha)


def _first_leaders(joints, repeated, log_p, evidence: CycleEvidence, conf):
    """Joints the cycles may be timed on, best first: most repeated motion across
    performances, else (one performance, or nothing repeats across them) within."""
    across = [(float(repeated[list(j.channels)].sum()), -k, j) for k, j in enumerate(joints)
              if _significant(j, log_p, len(joints), conf)]
    across = [x for x in across if x[0] > 0]
    if across:
        return [j for _, _, j in sorted(across, key=lambda x: x[:2], reverse=True)]
    ranked = []
    grids = evidence.grids
    typical = evidence.paths.mean(axis=0)
    moving = tuple(int(c) for c in np.flatnonzero(typical >= 0.05 * typical.max()))
    every = [c for j in joints for c in j.channels]
    for sc in evidence.scored:  # every joint is timed: every channel's scores in one pass
        sc.table(every)
    for k, j in enumerate(joints):
        periods = [joint_period(sc, j.channels, conf) for sc in evidence.scored]
        if sum(1 for p in periods if p) * 2 <= len(grids):
            continue
        cyc, cyc_p = evidence.cycles(periods, j.channels)  # the joint's own test only
        probe = JointEvidence(j.name, j.channels)
        if not _significant(probe, cyc_p, len(joints), conf):
            continue
        # a leader repeats across performances: its cycles must look alike from one
        # performance to the next (a limb doing another thing in each take does not)
        # timed on this joint, the whole moving body's cycle: the action's joints come out
        # the same in every performance, a limb doing its own thing blurs
        alike = evidence.alike(periods, moving) if len(grids) > 1 else 1.0
        strength = float(cyc[list(j.channels)].sum())
        if strength > 0:
            ranked.append((max(alike, 0.0) if len(grids) > 1 else strength, -k, strength, j))
    if not ranked:
        return []
    # among the joints that cycle with at least LEADER_SHARE of the strongest, the one whose
    # cycles are most alike across performances leads (a foreign limb may cycle more)
    strongest = max(r[2] for r in ranked)
    ranked = [r for r in ranked if r[2] >= LEADER_SHARE * strongest]
    return [r[3] for r in sorted(ranked, key=lambda x: x[:2], reverse=True)]


def _select(joints: list[JointEvidence], repeated: np.ndarray, log_p: np.ndarray,
            first: Actiongram, conf: MotionConf, symbols: list[str], *, tested: bool,
            extra: float = 0.0) -> MotionResult:
    """Leader, shares, components and their skeleton neighbours; the verdict."""
    strict = set()
    for j in joints:
        j.repeated = float(repeated[list(j.channels)].sum())
        if tested:
            if _significant(j, log_p, len(joints), conf, extra):
                strict.add(j.name)
            # beside a significant leader, a joint is tested on its own (Bonferroni over its
            # channels only): the share of the leader's repeated motion is the second gate
            passed = _significant(j, log_p, 1, conf)
        else:
            passed = j.repeated > 0
            strict.add(j.name)
        j.status = "candidate" if passed else "not significant"
    candidates = [j for j in joints if j.status == "candidate" and j.repeated > 0]
    leaders = [j for j in candidates if j.name in strict]
    if not leaders:
        for j in joints:
            j.status = "not significant"
        return MotionResult(NO_REPETITION, joints, None, symbols)
    leader = max(leaders, key=lambda j: (j.repeated, -joints.index(j)))
    for j in joints:
        j.share = j.repeated / leader.repeated
    core = {j.name for j in candidates if j.share >= conf.joint_share}
    for j in joints:
        if j.name in core:
            j.status = "component"
        elif j.status == "candidate":
            j.status = "below the share of the leader"
    near = set()
    for name in core:
        near.update(first.neighbours(name))
    for j in joints:
        if j.name in near and j.name not in core and j.share >= conf.neighbour_share:
            j.status = "component (skeleton neighbour)"
    chosen = [j for j in joints if j.status.startswith("component")]
    if len(chosen) < 2:  # synchronisation needs two joints
        for j in chosen:
            j.status = "alone: no other joint in step"
        return MotionResult(NO_REPETITION, joints, leader.name, symbols)
    result = MotionResult("", joints, leader.name, symbols)
    for j in chosen:
        values = repeated[list(j.channels)]
        keep = [c for c, v in zip(j.channels, values)
                if v > 0 and v >= conf.channel_share * float(values.max())]
        result.channels[j.name] = tuple(keep)
    return result
