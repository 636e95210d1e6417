"""The shared spread's fit when LAPACK's SVD does not converge on a finite matrix."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from praxicon.calibration import _singular, fit_spread


def _failing_on(shapes):
    """numpy's svd, raising LinAlgError for a matrix of one of ``shapes`` (as LAPACK's
    divide-and-conquer did on a praxicon's residuals of 139 takes x 557 features)."""
    svd = np.linalg.svd

    def failing(a, *args, **kwargs):
        if np.shape(a) in shapes:
            raise np.linalg.LinAlgError("SVD did not converge")
        return svd(a, *args, **kwargs)
    return failing


@settings(max_examples=40, deadline=None)
@given(rows=st.integers(1, 12), columns=st.integers(1, 12), rank=st.integers(0, 12),
       seed=st.integers(0, 2**32 - 1), fails=st.sampled_from(["plain", "transposed too"]))
def test_the_singular_values_and_vectors_survive_a_failed_svd(rows, columns, rank, seed, fails):
    rng = np.random.default_rng(seed)
    # of rank at most ``rank``: values of 0 (a praxicon's residuals have fewer directions than
    # features) whose vectors the fallback must not divide by
    a = rng.normal(size=(rows, rank)) @ rng.normal(size=(rank, columns))
    _, expected, vt = np.linalg.svd(a, full_matrices=False)
    shapes = {(rows, columns)} | ({(columns, rows)} if fails == "transposed too" else set())
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(np.linalg, "svd", _failing_on(shapes))
        singular, vectors = _singular(a)
    assert singular.shape == expected.shape and vectors.shape == vt.shape
    assert np.isfinite(vectors).all()
    # through the Gram matrix a value is exact to about sqrt(eps) times the largest
    np.testing.assert_allclose(singular, expected, atol=1e-6 * max(1.0, expected.max(initial=0)))
    kept = expected > 1e-4 * max(1.0, expected.max(initial=0))  # a vector of a zero value is any
    # each vector the same up to its sign
    np.testing.assert_allclose(np.abs((vectors[kept] * vt[kept]).sum(axis=1)), 1.0, atol=1e-6)


@pytest.mark.parametrize("fails", ["plain", "transposed too"])
@pytest.mark.parametrize("takes, features", [(5, 9), (40, 9)])
def test_the_spread_is_fitted_alike_when_the_svd_fails(monkeypatch, fails, takes, features):
    # wide (fewer takes than features, as the shared data's residuals are) and tall; the
    # factors compared as the outer products the scores read (a vector's sign is free)
    rng = np.random.default_rng(7)
    sizes = (takes // 3, takes // 3, takes - 2 * (takes // 3))
    groups = [rng.normal(size=(n, features)) + k for k, n in enumerate(sizes)]
    expected = fit_spread(groups, 3)
    shape = (takes, features)
    monkeypatch.setattr(np.linalg, "svd", _failing_on(
        {shape} | ({shape[::-1]} if fails == "transposed too" else set())))
    found = fit_spread(groups, 3)
    for k in (0, 1, 3):  # scale, means, noise
        np.testing.assert_allclose(found[k], expected[k], atol=1e-9)
    np.testing.assert_allclose(found[2].T @ found[2], expected[2].T @ expected[2], atol=1e-9)
