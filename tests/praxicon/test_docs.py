"""docs/praxicon.md: its Python example runs and prints what the page says."""

from __future__ import annotations

import os
import re
from pathlib import Path

from praxicon_fixtures import needs_mocap

ROOT = Path(__file__).resolve().parents[2]


@needs_mocap()
def test_praxicon_page_example_runs(capsys):
    text = (ROOT / "docs" / "praxicon.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert blocks
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        namespace: dict = {}
        for block in blocks:
            exec(compile(block, "docs/praxicon.md", "exec"), namespace)
    finally:
        os.chdir(cwd)
    out = capsys.readouterr().out.splitlines()
    assert out == ["bye.byebye ok True", "True ('joint_Root', 'Hips')"]


def test_praxicon_page_is_linked_from_the_index():
    assert "praxicon.md" in (ROOT / "docs" / "index.md").read_text(encoding="utf-8")
