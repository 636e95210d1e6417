"""Shared helpers for the kinetology tests: where the real motion data is, a skip mark, and the
real takes read once per test process."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
MOCAP = REPO.parent / "shared" / "data" / "mocap"

needs_mocap = pytest.mark.skipif(
    not MOCAP.is_dir(),
    reason=f"real motion data not found at {MOCAP} (../shared/data/mocap beside the repo)")


@lru_cache(maxsize=None)
def real_take(path: Path):
    """``kinetology.read(path)`` of a file of the real data, read once per test process.

    Several tests sweep the same 330 takes (70 MB of text, 2-3 s of reading each time): the
    test of the readers reads every one, others check labels or performances against them. A
    :class:`kinetology.Motion` is frozen (its arrays and meta read-only), so the tests can share
    one. Tests of how a file is read (its memory, its time, its errors) call the reader
    themselves.
    """
    import kinetology

    return kinetology.read(path)
