"""An empty file name (``psgs induce ''``) is one line naming the argument, not ``.: Is a
directory`` (``Path("")`` is the current folder) nor a write taken for no output at all."""

from __future__ import annotations

import pytest

from psgs._foundation.files import read_bytes, read_text
from psgs.cli import main


@pytest.mark.parametrize("argv, argument", [
    (["induce", ""], "FILE"),                       # was ".: Is a directory"
    (["induce", "--events", ""], "--events"),       # was "No such file or directory", unnamed
    (["locate", "", "--learn", "x.actiongram"], "FILE"),
    (["locate", "x.actiongram", "--learn", ""], "--learn"),
    (["show", ""], "FILE"),                         # was ": no such file (the shipped ...)"
    (["derive", ""], "FILE"),
    (["check", "", "a"], "FILE"),
    (["export", ""], "FILE"),
    (["draw", "", "-o", "x.svg"], "FILE"),
    (["draw", "paper_example", "-o", ""], "-o/--output"),
    (["synth", "-o", ""], "-o/--output"),           # was written to stdout without a word
    (["bench", "noise", "--csv", ""], "--csv"),     # was not written, without a word
    (["kinetology", "segment", ""], "FILE"),
    # the praxicon's folders and files: '' was the current folder (".: not a praxicon folder")
    (["praxicon", "build", "", "-o", "px"], "DATASET"),
    (["praxicon", "build", "d", "-o", ""], "-o/--output"),
    (["praxicon", "draw", "", "-o", "img"], "DIR"),
    (["praxicon", "generate", "px", "a", "-o", ""], "-o/--output"),
    (["praxicon", "generate", "px", "a", "-o", "a.bvh", "--view", ""], "--view"),
    (["praxicon", "verify", ""], "DIR"),
    (["praxicon", "recognise", "px", "a.bvh", ""], "FILE"),
    (["praxicon", "parse", "", "a.bvh"], "PX"),
    (["praxicon", "parse", "px", "a.bvh", "--plot", ""], "--plot"),
])
def test_an_empty_file_name_is_one_line_naming_the_argument(argv, argument, capsys):
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    assert captured.err == f"psgs: error: argument {argument}: the file name is empty ('')\n"


def test_an_empty_output_name_keeps_its_own_message(capsys):
    # these two said what was wrong before: their words stay
    assert main(["induce", "--example", "-o", ""]) == 2
    assert capsys.readouterr().err == "psgs: error: -o needs a file name\n"


def test_the_reader_says_an_empty_name_is_empty():
    for read in (read_bytes, read_text):
        with pytest.raises(FileNotFoundError, match="the file name is empty") as info:
            read("")
        assert info.value.filename == ""
