"""Rules for every test of the suite, the doctests of the packages included.

* A test phase (setup, call or teardown) that passes but takes more than
  :data:`TEST_SECONDS` of CPU fails, its time in the report: the suite must stay short on a
  2-core machine, and a slow test is a finding, not something to wait for. CPU time (the
  worker's and that of the subprocesses it waited for), not wall time: the same test on a
  machine loaded by other work takes longer by the clock but not by the CPU, so the rule
  does not depend on what else runs (a flaky limit would be a bug of its own).
* A doctest's temporary folders (``tempfile.mkdtemp()``, as the examples write them for a
  reader to run) go under pytest's own, which it prunes: otherwise every run of the suite
  left some forty folders in the system's temporary directory.
* A doctest that reads the real data (``../shared/data/mocap``, beside the repository) is
  skipped, with that reason, when the data is not there.

Here, at the top, rather than in ``tests/conftest.py``: pytest applies a conftest's hooks to
the tests below it, and the doctests live in ``psgs/``, ``kinetology/`` and ``praxicon/``.
"""

import os
import tempfile
from pathlib import Path

import pytest

#: The most one phase of one test may take, in seconds.
TEST_SECONDS = 15.0
#: Where the doctests find the real data (relative to the directory pytest runs in).
SHARED = Path("../shared/data/mocap")


def pytest_collection_modifyitems(config, items):
    """Skip, with a reason, the doctests that read ``../shared`` when it is absent."""
    if SHARED.is_dir():
        return
    reason = f"reads the real motion data at {SHARED} (beside the repository): not there"
    for item in items:
        test = getattr(item, "dtest", None)  # a doctest item
        if test is not None and any("../shared" in example.source for example in test.examples):
            item.add_marker(pytest.mark.skip(reason=reason))


@pytest.fixture
def examples_tempdir(tmp_path, monkeypatch):
    """Examples written for a reader make their folders with ``tempfile.mkdtemp()``; run by a
    test, those go under the test's own temporary folder, which pytest prunes, rather than
    staying in the system's temporary directory after every run."""
    monkeypatch.setattr(tempfile, "tempdir", str(tmp_path))
    return tmp_path


@pytest.fixture(autouse=True)
def _doctest_temporary_folders(request):
    """Every doctest's examples get :func:`examples_tempdir`."""
    if getattr(request.node, "dtest", None) is not None:
        request.getfixturevalue("examples_tempdir")


def _cpu_seconds() -> float:
    t = os.times()
    return t.user + t.system + t.children_user + t.children_system


def _timed(phase: str):
    @pytest.hookimpl(hookwrapper=True)
    def hook(item, *args):
        start = _cpu_seconds()
        yield
        item.stash.setdefault(_CPU, {})[phase] = _cpu_seconds() - start
    hook.__doc__ = f"Measure the CPU time of a test's {phase} phase."
    return hook


_CPU = pytest.StashKey[dict]()
pytest_runtest_setup = _timed("setup")
pytest_runtest_call = _timed("call")
pytest_runtest_teardown = _timed("teardown")


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """Fail a test phase that passed but took more than :data:`TEST_SECONDS` of CPU."""
    outcome = yield
    report = outcome.get_result()
    cpu = item.stash.get(_CPU, {}).get(report.when, 0.0)
    if report.passed and cpu > TEST_SECONDS:
        report.outcome = "failed"
        report.longrepr = (f"{item.nodeid} {report.when} took {cpu:.1f} s of CPU "
                           f"({report.duration:.1f} s by the clock), more than the suite's "
                           f"{TEST_SECONDS:g} s a test (conftest.py)")
