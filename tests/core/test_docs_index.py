"""The tour in docs/index.md runs as written (its python blocks, in order, in one namespace)."""

import os
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_index_tour_runs(capsys):
    text = (ROOT / "docs" / "index.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) >= 5
    namespace: dict = {}
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        for block in blocks:
            exec(compile(block, "docs/index.md", "exec"), namespace)
    finally:
        os.chdir(cwd)
    out = capsys.readouterr().out
    assert "parallel free 4 8" in out
    assert "(S1, S2, S3, S4) ⇒" in out


def test_semantics_examples_run():
    text = (ROOT / "docs" / "semantics.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert blocks, "docs/semantics.md has no python example"
    namespace: dict = {}
    cwd = os.getcwd()
    os.chdir(ROOT)
    try:
        for block in blocks:
            exec(compile(block, "docs/semantics.md", "exec"), namespace)  # its asserts check
    finally:
        os.chdir(cwd)
