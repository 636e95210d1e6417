"""Reading input files whole: a device refused, a pipe read to its end up to a limit, lines
broken where an editor breaks them, numbers as data files write them."""

from __future__ import annotations

import os

import pytest

import psgs
from psgs._foundation import files
from psgs._foundation.text import decimal, split_lines
from psgs.errors import FormatError

needs_fifo = pytest.mark.skipif(not hasattr(os, "mkfifo") or not os.path.isdir("/dev/fd"),
                                reason="named pipes and /dev/fd are POSIX")


def _pipe(data: bytes) -> str:
    """A pipe holding ``data``, its writer done, named as a shell's ``<(cmd)`` names one."""
    read_end, write_end = os.pipe()
    os.write(write_end, data)  # small: the pipe's buffer holds it
    os.close(write_end)
    return f"/dev/fd/{read_end}"


@needs_fifo
def test_a_pipe_is_read_to_its_end():
    # `psgs show <(cat g.psgs)` read the grammar before files.py: it must still
    path = _pipe(b'psgs P\ncomponent G start S\n  p: S -> "a"\n')
    try:
        assert psgs.load(path).name == "P"
    finally:
        os.close(int(path.rsplit("/", 1)[1]))


@needs_fifo
def test_a_pipe_past_the_limit_is_an_error_not_read_further(monkeypatch):
    monkeypatch.setattr(files, "PIPE_LIMIT", 10)
    path = _pipe(b"x" * 100)
    try:
        with pytest.raises(FormatError, match="the pipe gave more than 10 bytes"):
            files.read_bytes(path)
    finally:
        os.close(int(path.rsplit("/", 1)[1]))


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


def test_a_large_regular_file_is_held_once_while_read(tmp_path):
    # read in 16 MiB pieces and joined, a file of 20 MiB was held twice at the join
    import tracemalloc

    path = tmp_path / "large.bin"
    data = os.urandom(20 << 20)
    path.write_bytes(data)
    tracemalloc.start()
    try:
        got = files.read_bytes(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert got == data
    assert peak < 1.1 * len(data), f"peak {peak / len(data):.2f} times the file"
