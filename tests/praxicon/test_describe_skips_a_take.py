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


def test_takes_cut_from_one_recording_are_told_apart(monkeypatch):
    # one recording holds takes of both actions (as a cmu-mocap6 AMC file does), so every take
    # has its name: the take left out is the one whose features fail, not the first of that
    # name (which left out every good take before the bad one, and then every action)
    import types

    import numpy as np

    import praxicon.learn as learn
    from kinetology import Motion, synthetic_motion

    def take(seed, joint, huge=False):
        m = synthetic_motion(2, (joint,), seed=seed, noise=0.3)
        values = m.values.copy()
        if huge:
            values[0, 0] = 1e300
        return Motion(values, m.channels, m.frame_rate, m.skeleton, "session.bvh")

    table = {("a", 0): take(1, 0), ("a", 1): take(2, 0), ("a", 2): take(3, 0),
             ("b", 0): take(4, 1), ("b", 1): take(5, 1), ("b", 2): take(6, 1, huge=True)}
    monkeypatch.setattr(learn, "_load_performance",
                        lambda p: (table[p.label, p.start], None))
    actions = [types.SimpleNamespace(
        name=n, learnt=True, dataset="d", content=n,
        performances=[types.SimpleNamespace(file="session.bvh", start=k, stop=None, label=n,
                                            used=True) for k in range(3)]) for n in "ab"]
    said: list[str] = []
    takes, _ = describe_praxicon(types.SimpleNamespace(actions=actions), log=said.append)
    assert {a.name: a.takes for a in takes.actions} == {"a": 3, "b": 2}
    assert len(said) == 1 and said[0].startswith("b: not described from session.bvh: feature ")
    assert np.isfinite(takes.spread.scale).all()
