"""follow_rate on strings that keep equal neighbours, and PAL's chance claims on them."""

from __future__ import annotations

import numpy as np
import pytest

from psgs import Actiongram
from psgs.induce import PAL
from psgs.induce.pal.sections import follow_rate


def _chain(rng: np.random.Generator, moves: np.ndarray, count: int) -> np.ndarray:
    """``count`` symbols of the Markov chain ``moves`` (rows sum to 1), from its stationary
    distribution."""
    start = _stationary(moves)
    out = np.empty(count, dtype=np.int64)
    out[0] = rng.choice(len(moves), p=start)
    ahead = np.cumsum(moves, axis=1)
    for t, u in enumerate(rng.random(count - 1), start=1):
        out[t] = min(int(np.searchsorted(ahead[out[t - 1]], u, side="right")), len(moves) - 1)
    return out


def _stationary(moves: np.ndarray) -> np.ndarray:
    shares = np.full(len(moves), 1 / len(moves))
    for _ in range(2000):  # (every chain below is aperiodic: it stays with chance > 0)
        shares = shares @ moves
    return shares / shares.sum()


def _true_rate(moves: np.ndarray) -> float:
    """The chance that the symbols after two equal ones, far apart, agree too:
    ``sum_a pi_a^2 sum_b P_ab^2 / sum_a pi_a^2``."""
    pi = _stationary(moves)
    return float(np.sum(pi ** 2 * np.sum(moves ** 2, axis=1)) / np.sum(pi ** 2))


def _independent(shares) -> np.ndarray:
    shares = np.asarray(shares, dtype=np.float64)
    return np.tile(shares / shares.sum(), (len(shares), 1))


def _persistent(rng: np.random.Generator, letters: int) -> np.ndarray:
    """Each letter its own chance to stay (0 to 0.9), the moves by uneven weights."""
    stay = rng.uniform(0, 0.9, letters)
    weights = rng.dirichlet(np.full(letters, 0.7))
    moves = np.empty((letters, letters))
    for a in range(letters):
        other = weights.copy()
        other[a] = 0
        moves[a] = (1 - stay[a]) * other / other.sum()
        moves[a, a] = stay[a]
    return moves


@pytest.mark.parametrize("kind", ["uneven", "sticky", "persistent"])
def test_the_follow_rate_of_kept_repeats_is_near_the_true_rate(kind):
    # 40 strings of 400 symbols over 8 letters a kind; the mean of log(estimate / true rate).
    # One equal-neighbour rate for every letter gave -0.57 (0.29 for 0.50), -0.15 and -0.17;
    # now -0.01, -0.01 and -0.05. A string's log ratio scatters by 0.07 (0.12 persistent), so
    # the mean of 40 by 0.011 (0.019): 0.05 is over 4 of those from what the first two kinds
    # gave. The persistent strings' moves follow weights of their own, not the symbol shares
    # the letter models move by (only the chain, with 56 parameters, holds them): 0.1 for them
    rng = np.random.default_rng(7)
    ratios = []
    for _ in range(40):
        if kind == "uneven":  # symbols drawn independently, one letter 0.7 of them
            moves = _independent([0.7] + [0.3 / 7] * 7)
        elif kind == "sticky":  # uneven, and staying on a letter more than that
            moves = 0.3 * np.eye(8) + 0.7 * _independent(rng.dirichlet(np.full(8, 0.5)))
        else:
            moves = _persistent(rng, 8)
        codes = _chain(rng, moves, 400)
        _, codes = np.unique(codes, return_inverse=True)
        ratios.append(np.log(follow_rate(codes.astype(np.int64)) / _true_rate(moves)))
    bound = 0.1 if kind == "persistent" else 0.05
    assert abs(float(np.mean(ratios))) < bound, (kind, float(np.mean(ratios)))


def test_random_strings_with_kept_repeats_over_uneven_letters_are_claimed_at_alpha():
    # 150 actiongrams of 2 to 12 random strings (60 to 200 symbols over 8 to 12 letters,
    # one letter 0.7 or 0.8 of them, drawn independently, equal neighbours kept), PAL with
    # min_copies=2 at alpha = 1 %. A claim in an actiongram is a false one. With one
    # equal-neighbour rate for every letter, 14 of these 150 were claimed (9.3 %); now 0.
    # At the stated level the claims are at most Binomial(150, 0.01), mean 1.5, and 6 or
    # more come with chance 0.42 %: the bound of 5 fails a learner at the level that rarely,
    # one that claims 9.3 % as rarely passes it (0.42 % again), one at 5 % passes in 23 %
    rng = np.random.default_rng(33)
    letters_used = "abcdefghijkl"
    claimed = 0
    for _ in range(150):
        letters = int(rng.integers(8, 13))
        top = float(rng.choice([0.7, 0.8]))
        shares = [top] + [(1 - top) / (letters - 1)] * (letters - 1)
        length, count = int(rng.choice([60, 100, 200])), int(rng.integers(2, 13))
        strings = {f"r{i}": [letters_used[c] for c in rng.choice(letters, length, p=shares)]
                   for i in range(count)}
        result = PAL(min_copies=2).induce(Actiongram.from_strings(strings, keep_repeats=True))
        claimed += bool(result.components)
    assert claimed <= 5, claimed
