"""Reading input files whole: a device refused, a pipe read to its end up to a limit, lines
broken where an editor breaks them, numbers as data files write them."""

from __future__ import annotations

import os
import sys
import threading

import pytest

import psgs
from psgs._foundation import files
from psgs._foundation.text import decimal, split_lines
from psgs.errors import FormatError

needs_fifo = pytest.mark.skipif(not hasattr(os, "mkfifo") or sys.platform == "win32",
                                reason="named pipes are POSIX")


def _fifo(tmp_path, data: bytes):
    """A named pipe at tmp_path/p.psgs that a thread fills with ``data``."""
    path = tmp_path / "p.psgs"
    os.mkfifo(path)

    def write():
        with open(path, "wb") as handle:  # waits for the reader
            handle.write(data)

    threading.Thread(target=write, daemon=True).start()
    return path


@needs_fifo
def test_a_pipe_is_read_to_its_end(tmp_path):
    # a shell's <(cmd) is such a pipe: `psgs show <(cat g.psgs)` read it before files.py
    data = b'psgs P\ncomponent G start S\n  p: S -> "a"\n'
    assert psgs.load(_fifo(tmp_path, data)).name == "P"


@needs_fifo
def test_a_pipe_past_the_limit_is_an_error_not_read_further(tmp_path, monkeypatch):
    monkeypatch.setattr(files, "PIPE_LIMIT", 10)
    with pytest.raises(FormatError, match="the pipe gave more than 10 bytes"):
        files.read_bytes(_fifo(tmp_path, b"x" * 100))


@needs_fifo
def test_a_pipe_with_no_writer_is_empty_not_a_hang(tmp_path):
    path = tmp_path / "quiet"
    os.mkfifo(path)
    assert files.read_bytes(path) == b""


@pytest.mark.skipif(not os.path.exists("/dev/zero"), reason="no /dev/zero here")
def test_a_device_is_refused():
    with pytest.raises(FormatError, match="not a regular file but a device"):
        files.read_bytes("/dev/zero")


@pytest.mark.parametrize("text, lines", [
    ("a\nb\n", ["a", "b"]), ("a\r\nb", ["a", "b"]), ("a\rb\r", ["a", "b"]),  # the old Mac's
    ("a\x0cb\u2028c\n", ["a\x0cb\u2028c"]), ("", []), ("\n", [""]),
])
def test_lines_break_at_newlines_only(text, lines):
    assert split_lines(text) == lines


@pytest.mark.parametrize("text, value", [
    ("1", 1.0), ("-1.5e3", -1500.0), ("1.", 1.0), (".5", 0.5), ("+3", 3.0), ("1E-5", 1e-5),
    ("Infinity", float("inf")), ("1_0", None), ("\uff11", None), ("\u0661", None), ("", None),
    (" 1", None), ("0x10", None),
])
def test_numbers_as_data_files_write_them(text, value):
    assert decimal(text) == value
