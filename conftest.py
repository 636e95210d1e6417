"""Rules for every test of the suite, the doctests of the packages included.

* A test phase (setup, call or teardown) that passes but takes more than
  :data:`TEST_SECONDS` fails, its time in the report: the suite must stay short on a loaded
  2-core machine, and a slow test is a finding, not something to wait for.
* A doctest that reads the real data (``../shared/data/mocap``, beside the repository) is
  skipped, with that reason, when the data is not there.

Here, at the top, rather than in ``tests/conftest.py``: pytest applies a conftest's hooks to
the tests below it, and the doctests live in ``psgs/``, ``kinetology/`` and ``praxicon/``.
"""

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


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    """Fail a test phase that passed but took more than :data:`TEST_SECONDS`."""
    outcome = yield
    report = outcome.get_result()
    if report.passed and report.duration > TEST_SECONDS:
        report.outcome = "failed"
        report.longrepr = (f"{item.nodeid} {report.when} took {report.duration:.1f} s, more "
                           f"than the suite's {TEST_SECONDS:g} s a test (conftest.py)")
