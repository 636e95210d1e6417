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

import os
import tempfile
from pathlib import Path

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
    """Start building the compiled engines (kinetology's segmentation, PAL's motif search)
    before any test is timed.

    numba compiles them on first use: 4-6 s for kinetology's and about 20 s for PAL's with an
    empty cache (a fresh install, as in CI), which would otherwise land on whichever test uses
    them first and push it past the suite's 15 s a test. Each process that runs tests builds
    them (or finds them in numba's cache) once, after its collection (see
    :func:`pytest_collection_finish`). Under pytest-xdist the controller runs no test: it
    forks builders at the start, which fill numba's cache while the workers start and
    collect, so that the compilation is done once and beside the workers' start (each
    worker compiling for itself would double the work; the controller compiling before the
    workers started left a core idle for half a minute).
    """
    config = session.config
    if _is_xdist_controller(config) and not config.option.collectonly and _warm_wanted():
        _start_builders()


def pytest_collection_finish(session):
    """Build the compiled engines in this process, after the builders (if any) have filled
    numba's cache: loading them from there takes a second or two, compiling them again 25 s.
    Without numba there is nothing to build."""
    if session.config.option.collectonly or not session.items or not _warm_wanted():
        return
    _wait_for_builders()
    _warm_kinetology()
    _warm_pal()


#: The environment variable naming the lock file the builders hold while they compile.
_BUILDER_LOCK = "PSGS_TESTS_NUMBA_BUILDER_LOCK"


def _warm_wanted() -> bool:
    # a test that runs pytest on a copy of this file in a subprocess (the hypothesis
    # profiles) sets this: its probe uses no compiled engine
    return os.environ.get("PSGS_TESTS_NO_WARM_UP") != "1"


def _is_xdist_controller(config) -> bool:
    return (getattr(config.option, "dist", "no") != "no"
            and not hasattr(config, "workerinput"))


def _start_builders():
    """Fork the builders, one for PAL's engines and one for kinetology's, that compile them
    into numba's cache holding a lock (a ``flock`` on a file, whose name the workers find in
    the environment variable :data:`_BUILDER_LOCK`) until both end. Forked rather than
    started afresh, so that they import the very modules (and so fill the very cache) the
    workers will; where there is no fork or no ``flock``, there is no builder and every
    worker compiles for itself."""
    try:
        import fcntl
        import multiprocessing
        context = multiprocessing.get_context("fork")
    except (ImportError, ValueError):
        return
    fd, path = tempfile.mkstemp(prefix="psgs-numba-builder-", suffix=".lock")
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)  # each fork shares this lock and keeps it while it runs
        for warm in (_warm_pal, _warm_kinetology):  # two cores: the two at once
            _BUILDERS.append(context.Process(target=warm, name="psgs-numba-builder", daemon=True))
            _BUILDERS[-1].start()
    finally:
        os.close(fd)  # only the builders hold the lock now
    os.environ[_BUILDER_LOCK] = path


#: The longest a worker waits for the builders (then it compiles what it needs itself).
_BUILDER_WAIT = 300.0


def _wait_for_builders():
    path = os.environ.get(_BUILDER_LOCK)
    if not path:
        return
    import fcntl
    import time
    deadline = time.monotonic() + _BUILDER_WAIT
    try:
        with open(path) as lock:
            while True:  # the lock is free once both builders have ended
                try:
                    fcntl.flock(lock, fcntl.LOCK_SH | fcntl.LOCK_NB)
                    return
                except BlockingIOError:
                    if time.monotonic() > deadline:
                        return
                    time.sleep(0.1)
    except OSError:
        pass


def pytest_sessionfinish(session):
    """Remove the builders' lock file (they ended long before)."""
    if _BUILDERS:
        for builder in _BUILDERS:
            builder.join()
        path = os.environ.pop(_BUILDER_LOCK, None)
        if path:
            Path(path).unlink(missing_ok=True)


#: The builder processes this controller started.
_BUILDERS: list = []


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

