"""Every file or folder a ``psgs praxicon`` command writes is checked before its work: a
read-only file in the place of ``--plot`` or ``-o`` (the timeline was printed, the motion
generated, and then the error), a ``build -o`` or ``draw -o`` folder that cannot be written
(an action was learnt first) or made. One line naming the path, status 2, nothing done.

The tests run as any user (root may write a read-only file): what cannot be written is the
answer ``os.access`` gives for that one path, as it gives it to a user without the right."""

from __future__ import annotations

import os
from pathlib import Path

import pytest

import praxicon.outputs as outputs
from praxicon_fixtures import refused


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    """The manifest fixture's praxicon (moves.wave, moves.step, ...), built once."""
    from praxicon_fixtures import build_wave_and_step

    return build_wave_and_step(tmp_path_factory.mktemp("data"))


def _read_only(monkeypatch, *paths) -> None:
    """``os.access`` answers no write to ``paths`` (the others as they are)."""
    real = os.access
    denied = {os.fspath(p) for p in paths}

    def access(path, mode, *args, **kwargs):
        if os.fspath(path) in denied and mode & os.W_OK:
            return False
        return real(path, mode, *args, **kwargs)

    monkeypatch.setattr(outputs.os, "access", access)


def _existing(path: Path, text: str = "was here\n") -> Path:
    path.write_text(text)
    return path


def test_a_read_only_plot_is_refused_before_the_timeline(built, tmp_path, monkeypatch, capsys):
    take = built.parent / "wave_1.bvh"
    plot = _existing(tmp_path / "t.png")
    _read_only(monkeypatch, plot)
    assert refused(capsys, ["parse", str(built), str(take), "--plot", str(plot)]) == \
        f"{plot}: the file is not writable (it is there, read-only)"
    assert refused(capsys, ["recognise", str(built), str(take), "--plot", str(plot)]) == \
        f"{plot}: the file is not writable (it is there, read-only)"
    assert plot.read_text() == "was here\n"


def test_generate_refuses_a_read_only_output_before_the_motion(built, tmp_path, monkeypatch,
                                                               capsys):
    from praxicon import generate

    out = _existing(tmp_path / "w.bvh")
    _read_only(monkeypatch, out)
    assert refused(capsys, ["generate", str(built), "moves.wave", "-o", str(out)]) == \
        f"{out}: the file is not writable (it is there, read-only)"
    # the function too: it checked its picture's place first, not its motion's
    with pytest.raises(ValueError, match="^.*w.bvh: the file is not writable"):
        generate(built, "moves.wave", output=out)
    with pytest.raises(ValueError, match="^the motion is written to a file's path, not int$"):
        generate(built, "moves.wave", output=5)
    assert out.read_text() == "was here\n"


def test_build_refuses_a_folder_it_cannot_write_before_learning(built, tmp_path, monkeypatch,
                                                                capsys):
    manifest = built.parent / "moves.csv"
    locked = tmp_path / "locked"
    locked.mkdir()
    _read_only(monkeypatch, locked)
    assert refused(capsys, ["build", str(manifest), "-o", str(locked)]) == \
        f"{locked}: the folder is not writable"
    # made inside a folder that cannot be written: named too
    assert refused(capsys, ["build", str(manifest), "-o", str(locked / "a" / "px")]) == \
        f"{locked / 'a' / 'px'}: the folder {locked} is not writable (to make a praxicon " \
        f"folder in)"
    assert list(locked.iterdir()) == []
    # a file in its place, as before
    afile = _existing(tmp_path / "afile")
    assert refused(capsys, ["build", str(manifest), "-o", str(afile)]) == \
        f"{afile}: a file, not a praxicon folder"
    assert refused(capsys, ["build", str(manifest), "-o", str(afile / "px")]) == \
        f"{afile / 'px'}: {afile} is not a folder to make a praxicon folder in"


def test_draw_refuses_a_folder_it_cannot_write_before_drawing(built, tmp_path, monkeypatch,
                                                              capsys):
    locked = tmp_path / "locked"
    locked.mkdir()
    _read_only(monkeypatch, locked)
    assert refused(capsys, ["draw", str(built), "-o", str(locked)]) == \
        f"{locked}: the folder is not writable"
    assert refused(capsys, ["draw", str(built), "-o", str(locked / "pictures")]) == \
        f"{locked / 'pictures'}: the folder {locked} is not writable (to make a folder for " \
        f"the pictures in)"
    assert list(locked.iterdir()) == []
