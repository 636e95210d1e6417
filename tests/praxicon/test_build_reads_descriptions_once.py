"""A resumed build that learns no action reads ``descriptions.json`` once: its check that no
later psgs wrote the folder read the whole file, and its last step, which keeps the
descriptions when they were learnt from the same actions, read it again (megabytes, on a
praxicon of the shared data). What the build keeps or learns again is as before."""

from __future__ import annotations

from pathlib import Path

import pytest

import praxicon.jsonvalues as jsonvalues
from praxicon import build, read_dataset
from praxicon.description_store import FILE


@pytest.fixture
def built(manifest) -> Path:
    out = manifest.parent / "px"
    build(read_dataset(manifest), out, progress=False, log=lambda line: None)
    return out


def _counting(monkeypatch) -> list[str]:
    """The names of the files read through the praxicon's JSON reader, from now on."""
    reads: list[str] = []
    real = jsonvalues.read_text

    def read_text(path, *args, **kwargs):
        reads.append(Path(path).name)
        return real(path, *args, **kwargs)

    monkeypatch.setattr(jsonvalues, "read_text", read_text)
    return reads


def test_a_resumed_build_reads_the_descriptions_once(built, manifest, monkeypatch):
    before = (built / FILE).read_bytes()
    reads = _counting(monkeypatch)
    again = build(read_dataset(manifest), built, progress=False, log=lambda line: None)
    assert not again.learnt and again.skipped
    assert reads.count(FILE) == 1
    # kept, not learnt again: the file is as it was, and the praxicon holds its descriptions
    assert (built / FILE).read_bytes() == before
    assert again.praxicon.descriptions is not None
    assert again.praxicon.window_descriptions is not None


def test_damaged_descriptions_are_said_once_and_learnt_again(built, manifest, monkeypatch):
    before = (built / FILE).read_bytes()
    (built / FILE).write_text('{"format": ')
    reads = _counting(monkeypatch)
    said: list[str] = []
    build(read_dataset(manifest), built, progress=False, log=said.append)
    assert reads.count(FILE) == 1
    assert [line for line in said if FILE in line] == \
        [f"{built / FILE}:1:12: not JSON (Expecting value): learnt again"]
    assert (built / FILE).read_bytes() == before  # learnt from the same actions: the same file
