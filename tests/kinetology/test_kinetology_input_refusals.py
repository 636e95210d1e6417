"""Bad input to the kinetology command and API: one line (or a note) naming what is wrong, never
a traceback or silence. Each test fails before its fix."""

from __future__ import annotations

import numpy as np
import pytest

import kinetology
from kinetology import Joint, Motion, Skeleton
from kinetology.cli import main

from test_kinetology_review_fixes import _write_bvh


def _one_line(capsys) -> str:
    captured = capsys.readouterr()
    err = captured.err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("kinetology: error:"), captured.err
    assert captured.out == "", captured.out  # said before any output: no tail of a report
    return err[0]


# -- an empty file name ----------------------------------------------------------------------

@pytest.mark.parametrize("argv, argument", [
    (["segment", ""], "FILE"),                      # was ".: unknown motion format"
    (["compress", ""], "file"),                     # was a traceback (Path('.').with_suffix)
    (["decompress", ""], "file"),                   # was "No such file or directory", unnamed
    (["evaluate", ""], "FILE"),
    (["plot", "", "--channel", "Knee.rz", "-o", "{tmp}/a.png"], "file"),
    (["view", "", "-o", "{tmp}/a.html"], "FILE"),
    (["segment", "{take}", "--labels", "", "-o", "{tmp}/spans/"], "--labels"),
    (["decompress", "{tmp}/t.kin", "--against", ""], "--against"),
    (["evaluate", "--mocap6", ""], "--mocap6"),     # was "nothing to evaluate"
    (["segment", "{take}", "-o", ""], "-o/--output"),
    (["compress", "{take}", "-o", ""], "-o/--output"),  # was written to take.kin in silence
    (["decompress", "{tmp}/t.kin", "-o", ""], "-o/--output"),
])
def test_an_empty_file_name_is_one_line_naming_the_argument(argv, argument, tmp_path, capsys):
    take = _write_bvh(tmp_path / "take.bvh")
    assert main(["compress", str(take), "-o", str(tmp_path / "t.kin")]) == 0
    capsys.readouterr()
    argv = [a.format(tmp=tmp_path, take=take) for a in argv]
    assert main(argv) == 2
    assert _one_line(capsys) == \
        f"kinetology: error: argument {argument}: the file name is empty ('')"
    assert not (tmp_path / "take.kin").exists()


def test_the_readers_refuse_an_empty_name():
    with pytest.raises(ValueError, match="path must be a file's path, not the empty name ''"):
        kinetology.read("")  # was ".: unknown motion format '(no suffix)'": the folder
