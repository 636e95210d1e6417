"""Suite-wide settings: hypothesis runs the same examples on every run.

The ``ci`` profile (the default) derandomises hypothesis (the examples follow from each test's
source, not from a random seed), keeps no example database between runs (a failure found once is
not replayed forever after, and a clean checkout behaves like any other) and sets no deadline (a
2-core machine under load times single examples unevenly). ``--hypothesis-profile=thorough``
draws ten times as many random examples for a long, opt-in run.

The suite-wide rules for every test and doctest (15 s a test, doctests of the real data
skipped when it is absent) are in the repository's top-level ``conftest.py``, whose hooks
reach the doctests of the packages too.
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
    """Build the compiled engines (kinetology's segmentation, PAL's motif search) before any
    test is timed.

    numba compiles them on first use: 4-6 s for kinetology's and about 20 s for PAL's with an
    empty cache (a fresh install, as in CI), which would otherwise land on whichever test uses
    them first and push it past the suite's 15 s a test. Here each is built once per process
    before the tests (or found in numba's cache); without numba there is nothing to build.
    """
    _warm_kinetology()
    _warm_pal()


def _warm_kinetology():
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


def _warm_pal():
    try:
        from psgs.induce import PAL
        from psgs.induce.synthetic import generate
    except ImportError:
        return
    try:  # four patterned strings: both kernels run (motifs, then pairs of candidates)
        PAL(engine="numba").induce(generate(seed=1, noise=0.1).actiongram)
    except ImportError:
        pass

