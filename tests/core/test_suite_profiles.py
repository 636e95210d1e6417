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

import psgs

TESTS = Path(__file__).resolve().parents[1]
# the probe imports the psgs this process imported (a checkout or the installed copy): the
# conftest's warm-up then finds numba's compiled engines in that copy's cache instead of
# compiling them again for another copy (some 25 s in a fresh virtual environment)
SOURCE = str(Path(psgs.__file__).resolve().parents[1])

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
    path = os.pathsep.join(filter(None, (SOURCE, os.environ.get("PYTHONPATH"))))
    done = subprocess.run([sys.executable, "-m", "pytest", "-q", "-s", "-p", "no:cacheprovider",
                           "test_probe.py", *option], cwd=tmp_path, capture_output=True,
                          text=True, timeout=120, env={**os.environ, "PYTHONPATH": path})
    assert done.returncode == 0, done.stdout + done.stderr
    assert f"PROFILE {expected}" in done.stdout
