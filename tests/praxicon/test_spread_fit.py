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


@settings(max_examples=30, deadline=None)
@given(rows=st.integers(1, 12), columns=st.integers(1, 12), seed=st.integers(0, 2**32 - 1),
       fails=st.sampled_from(["plain", "transposed too"]))
def test_the_singular_values_and_vectors_survive_a_failed_svd(rows, columns, seed, fails):
    a = np.random.default_rng(seed).normal(size=(rows, columns))
    _, expected, vt = np.linalg.svd(a, full_matrices=False)
    shapes = {(rows, columns)} | ({(columns, rows)} if fails == "transposed too" else set())
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(np.linalg, "svd", _failing_on(shapes))
        singular, vectors = _singular(a)
    np.testing.assert_allclose(singular, expected, atol=1e-9)
    kept = expected > 1e-6 * max(1.0, expected[0])  # a vector of a zero value is any
    # each vector the same up to its sign
    np.testing.assert_allclose(np.abs((vectors[kept] * vt[kept]).sum(axis=1)), 1.0, atol=1e-7)


def test_the_spread_is_fitted_alike_when_the_svd_fails(monkeypatch):
    rng = np.random.default_rng(7)
    groups = [rng.normal(size=(n, 9)) + k for k, n in enumerate((5, 6, 4))]
    expected = fit_spread(groups, 3)
    monkeypatch.setattr(np.linalg, "svd", _failing_on({(15, 9)}))
    found = fit_spread(groups, 3)
    for e, f in zip(expected, found):
        np.testing.assert_allclose(np.abs(f) if f.ndim == 2 else f,
                                   np.abs(e) if e.ndim == 2 else e, atol=1e-9)
