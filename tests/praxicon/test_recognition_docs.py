"""docs/praxicon.md, "Recognising and parsing": its example runs and prints what the page says."""

from __future__ import annotations

import os
import re
from pathlib import Path

import pytest
from praxicon_fixtures import needs_mocap

ROOT = Path(__file__).resolve().parents[2]


@needs_mocap()
@pytest.mark.usefixtures("examples_tempdir")
def test_recognition_example_runs(capsys):
    text = (ROOT / "docs" / "praxicon.md").read_text(encoding="utf-8")
    (block,) = re.findall(r"```py\n(.*?)```", text, flags=re.S)
    promised = re.search(r"prints `(.*?)` and `(.*?)`", text.split("```py\n", 1)[1])
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        exec(compile(block, "docs/praxicon.md", "exec"), {})
    finally:
        os.chdir(cwd)
    assert capsys.readouterr().out.splitlines() == list(promised.groups())
