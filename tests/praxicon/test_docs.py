"""docs/praxicon.md: its Python example runs and prints what the page says."""

from __future__ import annotations

import json
import os
import re
from pathlib import Path

import pytest
from praxicon_fixtures import needs_mocap

ROOT = Path(__file__).resolve().parents[2]


@needs_mocap()
@pytest.mark.usefixtures("examples_tempdir")
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
    assert out == ["bye.byebye ok True", "True ('joint_Root', 'Hips')", "True"]


def test_praxicon_page_is_linked_from_the_index():
    assert "praxicon.md" in (ROOT / "docs" / "index.md").read_text(encoding="utf-8")


def test_what_is_on_disk_names_every_file_and_the_versions_written(tmp_path):
    """The page's "What is on disk" lists every file a praxicon folder holds (dump writes all
    but timings.json, which only a build times) and the versions the code writes."""
    from fuzz_support import praxicon_seed
    from praxicon import dump
    from praxicon.description import FORMAT_VERSION as DESCRIPTIONS_VERSION
    from praxicon.records import FORMAT_VERSION

    text = (ROOT / "docs" / "praxicon.md").read_text(encoding="utf-8")
    section = text[text.index("## What is on disk"):text.index("### Bad input")]
    listing = re.search(r"```text\n(.*?)```", section, flags=re.S).group(1)
    praxicon = praxicon_seed()
    dump(praxicon, tmp_path)
    written = {p.relative_to(tmp_path).as_posix() for p in tmp_path.rglob("*") if p.is_file()}
    for name in sorted(written | {"timings.json"}):
        for action in praxicon.names:
            name = name.replace(action, "ACTION")
        assert f"out/praxicon/{name} " in listing, name
    assert f'`"version": {FORMAT_VERSION}`' in section
    assert f"`praxicon.records.FORMAT_VERSION`, {FORMAT_VERSION};" in section
    assert f"`praxicon.description.FORMAT_VERSION`, {DESCRIPTIONS_VERSION})" in section
    index = json.loads((tmp_path / "index.json").read_text())
    assert index["version"] == FORMAT_VERSION
