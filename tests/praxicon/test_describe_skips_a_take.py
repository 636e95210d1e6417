"""A take whose features cannot be computed (a value too large to compute with) is left out of
the build's descriptions, named, and the other takes are described without it."""

from __future__ import annotations

from pathlib import Path

from praxicon import build, load, read_dataset
from praxicon.builder import describe_praxicon


def _spoil(path: Path) -> None:
    """The first frame's first value made 1e300: finite, but its square is not."""
    lines = path.read_text().splitlines()
    first = next(i for i, line in enumerate(lines) if line.startswith("Frame Time")) + 1
    values = lines[first].split()
    lines[first] = " ".join(["1e300", *values[1:]])
    path.write_text("\n".join(lines) + "\n")


def test_a_take_too_large_to_describe_is_left_out_and_named(manifest, tmp_path):
    built = build(read_dataset(manifest), tmp_path / "px", progress=False).praxicon
    spoilt = manifest.parent / "wave_2.bvh"
    _spoil(spoilt)
    said: list[str] = []
    takes, windows = describe_praxicon(built, log=said.append)
    assert takes.names == windows.names == ("moves.step", "moves.wave")
    assert [line.split(": feature ")[0] for line in said] == [
        f"moves.wave: not described from {spoilt}"]
    assert "too large to square" in said[0] and said[0].count(str(spoilt)) == 1
    assert load(tmp_path / "px").descriptions is not None
