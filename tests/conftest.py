"""Suite-wide settings: hypothesis runs the same examples on every run.

The ``ci`` profile (the default) derandomises hypothesis (the examples follow from each test's
source, not from a random seed), keeps no example database between runs (a failure found once is
not replayed forever after, and a clean checkout behaves like any other) and sets no deadline (a
2-core machine under load times single examples unevenly). ``--hypothesis-profile=thorough``
draws ten times as many random examples for a long, opt-in run.
"""

from hypothesis import HealthCheck, settings

settings.register_profile(
    "ci",
    derandomize=True,
    database=None,
    deadline=None,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.register_profile(
    "thorough",
    derandomize=False,
    database=None,
    deadline=None,
    max_examples=1000,
    suppress_health_check=[HealthCheck.too_slow],
)
settings.load_profile("ci")


def pytest_sessionstart(session):
    """Build kinetology's compiled segmentation engine before any test is timed.

    numba compiles it on first use: 4-6 s with an empty cache (a fresh install, as in CI),
    which would otherwise land on whichever test segments first and push it towards the
    suite's 15 s a test. Here it is built once per process before the tests (or found in
    numba's cache); without numba there is nothing to build.
    """
    try:
        import numpy as np

        import kinetology
    except ImportError:
        return
    walk = np.cumsum(np.random.default_rng(0).normal(size=(64, 2)), axis=0)
    try:
        kinetology.segments(kinetology.Motion(walk, ("a.rx", "b.rx"), 120.0), engine="numba")
    except ImportError:
        pass
