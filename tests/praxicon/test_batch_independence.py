"""A take's numbers do not depend on the takes it is recognised with.

A take recognised alone differed from the same take recognised among others in the last bits:
the squared distances were a matrix product, which BLAS computes one way for one row and
another for several. They are now each row's own dot products in a fixed order, so that
``recognise`` and ``recognise_many`` (and the chunks of ``psgs praxicon recognise``) agree to
the last bit.
"""

from __future__ import annotations

import numpy as np
import pytest

from praxicon import recognise, recognise_many
from praxicon.scoring import distances


def _praxicon_of_two_skeletons():
    """Descriptions of three actions of eight joints, two of them one family, and one of six
    (learnt from another skeleton), and new takes of both skeletons."""
    from kinetology import synthetic_motion
    from praxicon.description import describe

    def motion(joints, moving, period, seed):
        return synthetic_motion(joints, moving, period=period, seed=seed, frame_rate=30.0,
                                noise=0.5)

    takes = {name: [motion(joints, moving, period, s) for s in seeds]
             for name, joints, moving, period, seeds in (
                 ("a.slow", 8, (0, 1), 1.3, (1, 2, 3, 4)), ("a.fast", 8, (0, 1), 0.8, (5, 6, 7, 8)),
                 ("b", 8, (2, 3, 4), 1.0, (9, 10, 11, 12)), ("c", 6, (5,), 1.0, (13, 14, 15)))}
    d = describe(takes, families={"a.slow": "a", "a.fast": "a"})
    new = [motion(joints, moving, period, 20 + k) for k, (joints, moving, period) in enumerate(
        [(8, (0, 1), 1.0), (8, (2, 3, 4), 1.0), (6, (5,), 1.1), (8, (6,), 1.0),
         (6, (0, 1), 1.3), (8, (2, 3, 4), 0.9), (8, (0, 1), 0.8)])]
    return d, new


def test_a_take_has_the_same_numbers_alone_and_in_any_batch():
    d, new = _praxicon_of_two_skeletons()
    alone = [recognise(d, m) for m in new]
    # answers of every kind: each action, a family's, none of these, the other skeleton's
    assert {r.action for r in alone} >= {"a.slow", "b", "c", None}
    assert any(r.family for r in alone) and any(r.missing for r in alone)
    order = np.random.default_rng(0).permutation(len(new))
    for size in (2, 3, 4, len(new)):
        for start in range(0, len(new), size):
            batch = [int(k) for k in order[start:start + size]]
            # every float of the answer equal to the last bit: probabilities, distances, terms
            assert recognise_many(d, [new[k] for k in batch]) == [alone[k] for k in batch]


@pytest.mark.parametrize("factors", range(1, 17))
@pytest.mark.parametrize("features", [3, 17, 70])
def test_distances_are_each_rows_own_whatever_the_batch_and_its_layout(features, factors):
    # every count of shared directions: with two, a three-operand einsum's loop order
    # followed the number of rows
    rng = np.random.default_rng(1)
    w = rng.normal(size=(factors, features))
    inner = np.linalg.inv(np.eye(factors) + w @ w.T)
    parts = (rng.uniform(0.5, 2.0, features), rng.uniform(0.5, 2.0, features), w, inner)
    means = rng.normal(size=(4, features))
    x = rng.normal(size=(33, features))
    together = distances(x, means, parts)
    alone = np.concatenate([distances(x[i:i + 1], means, parts) for i in range(len(x))])
    wide = rng.normal(size=(33, features + 5))
    wide[:, 2:2 + features] = x
    cut = wide[:, 2:2 + features][:, np.arange(features)]  # chosen columns: Fortran order
    assert cut.flags.f_contiguous and not cut.flags.c_contiguous
    assert np.array_equal(together, alone)
    assert np.array_equal(distances(cut, means, parts), together)
    assert np.array_equal(distances(np.asfortranarray(x[5:9]), means, parts), together[5:9])
    # the same distance as the matrix algebra says, to rounding
    d = (x[:, None, :] - means[None]) / parts[0]
    precision = np.diag(parts[1]) - (w * parts[1]).T @ inner @ (w * parts[1])
    assert np.allclose(together, np.einsum("nai,ij,naj->na", d, precision, d), rtol=1e-10)
