"""The suite's hypothesis profiles: ``ci`` by default, ``--hypothesis-profile=thorough`` on request.

tests/conftest.py loads ``ci`` when it is imported; the hypothesis pytest plugin applies
``--hypothesis-profile`` later (at configure time), so the option must win. Checked in a
subprocess on a one-test copy of the suite's conftest.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import settings

TESTS = Path(__file__).resolve().parents[1]

PROBE = '''
from hypothesis import settings

def test_probe():
    s = settings()
    print(f"PROFILE max_examples={s.max_examples} derandomize={s.derandomize} "
          f"database={s.database} deadline={s.deadline}")
'''


def test_the_ci_profile_is_loaded_by_default():
    current = settings()
    assert current.derandomize is True
    assert current.database is None
    assert current.deadline is None


@pytest.mark.parametrize("option, expected", [
    ([], "max_examples=100 derandomize=True database=None deadline=None"),
    (["--hypothesis-profile=thorough"],
     "max_examples=1000 derandomize=False database=None deadline=None"),
])
def test_the_profile_option_overrides_the_default(tmp_path, option, expected):
    shutil.copy(TESTS / "conftest.py", tmp_path / "conftest.py")
    (tmp_path / "test_probe.py").write_text(PROBE)
    # the probe runs no compiled engine: the copy need not build them (tests/conftest.py)
    env = {**os.environ, "PSGS_TESTS_NO_WARM_UP": "1"}
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-s", "-p", "no:cacheprovider",
                           "test_probe.py", *option], cwd=tmp_path, capture_output=True,
                          text=True, timeout=120, env=env)
    assert done.returncode == 0, done.stdout + done.stderr
    assert f"PROFILE {expected}" in done.stdout
