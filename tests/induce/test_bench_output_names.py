"""psgs bench noise refuses an output it could not write before any trial runs: a picture
format matplotlib has not, one file named by both --csv and --plot, a folder it cannot write."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

from psgs.cli import main
from psgs.errors import ValidationError

RUN = ["bench", "noise", "--trials", "1", "--levels", "0:0:0.1", "--jobs", "1"]


def _refused_before_any_trial(capsys, argv, said):
    assert main(argv) == 2
    captured = capsys.readouterr()
    # no table, no progress bar: the sweep never started
    assert captured.out == "" and "cells" not in captured.err
    assert captured.err == f"psgs: error: {said}\n"


@pytest.mark.parametrize("name, what", [
    ("x.txt", "'.txt' pictures"), ("noise.CSV", "'.csv' pictures"),
    # matplotlib wrote NAME.png beside the name given
    ("noise", "a picture without a suffix"),
])
def test_a_plot_name_matplotlib_cannot_write_is_refused_before_the_sweep(tmp_path, capsys,
                                                                          name, what):
    pytest.importorskip("matplotlib", reason="matplotlib (the plot extra) is not installed")
    out = tmp_path / name
    _refused_before_any_trial(capsys, [*RUN, "--plot", str(out)],
                              f"{out}: matplotlib cannot write {what}; give one of .png, .svg, "
                              f".pdf, " + _rest_of_the_formats())
    assert list(tmp_path.iterdir()) == []


def _rest_of_the_formats() -> str:
    from matplotlib.backend_bases import FigureCanvasBase

    known = set(FigureCanvasBase.get_supported_filetypes()) - {"png", "svg", "pdf"}
    return ", ".join(f".{n}" for n in sorted(known))


def test_the_command_says_it_in_one_line_with_status_2(tmp_path):
    pytest.importorskip("matplotlib", reason="matplotlib (the plot extra) is not installed")
    # the whole sweep ran, then matplotlib's ValueError was a traceback with status 1 ("no")
    done = subprocess.run([sys.executable, "-m", "psgs", *RUN, "--plot", str(tmp_path / "x.txt")],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.count("\n") == 1 and "cannot write '.txt' pictures" in done.stderr


def test_a_picture_in_capitals_is_written(tmp_path, capsys):
    pytest.importorskip("matplotlib", reason="matplotlib (the plot extra) is not installed")
    out = tmp_path / "noise.PNG"
    assert main([*RUN, "--inducer", "pal", "--plot", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_plot_noise_refuses_the_name_before_drawing(tmp_path):
    pytest.importorskip("matplotlib", reason="matplotlib (the plot extra) is not installed")
    from psgs.cli.bench import plot_noise
    from psgs.induce.sweep import SweepRow

    with pytest.raises(ValidationError, match=r"x\.txt: matplotlib cannot write '\.txt'"):
        plot_noise([SweepRow("pal", 0.0, 1, 1, 0.1)], str(tmp_path / "x.txt"))
    assert list(tmp_path.iterdir()) == []


def test_one_file_named_by_csv_and_plot_is_refused(tmp_path, capsys, monkeypatch):
    # the picture was written over the table, once every trial had run
    monkeypatch.chdir(tmp_path)
    _refused_before_any_trial(capsys, [*RUN, "--csv", "n.png", "--plot", "./n.png"],
                              "--csv and --plot name one file, ./n.png: the plot would be "
                              "written over the table")


@pytest.mark.parametrize("flag", ["--csv", "--plot"])
def test_a_folder_that_cannot_be_written_is_refused_before_the_sweep(tmp_path, capsys,
                                                                      monkeypatch, flag):
    pytest.importorskip("matplotlib", reason="matplotlib (the plot extra) is not installed")
    # (as root every folder is writable: the permission is what os.access says)
    monkeypatch.setattr(os, "access", lambda path, mode: False)
    out = tmp_path / "n.png"
    _refused_before_any_trial(capsys, [*RUN, flag, str(out)],
                              f"{out}: the folder {tmp_path.resolve()} is not writable")
