"""Shared helpers for the kinetology tests: where the real motion data is, and a skip mark."""

from __future__ import annotations

from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
MOCAP = REPO.parent / "shared" / "data" / "mocap"

needs_mocap = pytest.mark.skipif(
    not MOCAP.is_dir(),
    reason=f"real motion data not found at {MOCAP} (../shared/data/mocap beside the repo)")
