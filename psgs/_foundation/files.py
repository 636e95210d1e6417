"""Reading an input file whole: no more bytes than its size, strict UTF-8 with the place.

Every reader of the distribution (grammars, actiongrams, events tables, motion capture,
praxicon folders) reads its file through :func:`read_bytes`, so that a path to a device
(``/dev/zero``) is refused at once instead of read until memory runs out and a pipe is read
to a stated limit at most; and through :func:`decode_utf8`, so that bytes that are not UTF-8
are an error at their line and column instead of replaced without a word.
"""

from __future__ import annotations

import errno
import os
import stat

from psgs.errors import FormatError

__all__ = ["read_bytes", "decode_utf8", "read_text", "PIPE_LIMIT"]


#: The most a pipe (``<(cmd)``, a FIFO) is read: its size is not known before it ends.
PIPE_LIMIT = 1 << 30


def read_bytes(path) -> bytes:
    """The bytes of the file ``path``: a regular file at most its size, read once; a pipe
    (a FIFO, the ``/dev/fd/N`` of a shell's ``<(cmd)``) to its end, at most
    :data:`PIPE_LIMIT` bytes.

    Raises
    ------
    FormatError
        When ``path`` is a device or a socket (``/dev/zero`` never ends: its size says
        nothing of how much it would give), or a pipe gives more than :data:`PIPE_LIMIT`.
    OSError
        As :func:`open` does for a missing file or a folder (``IsADirectoryError``), so the
        callers' handling of those stays as it is; for an empty name a ``FileNotFoundError``
        that says so (``open`` says only "No such file or directory", naming nothing).

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "a.txt"
    >>> _ = path.write_bytes(b"abc")
    >>> read_bytes(path)
    b'abc'
    >>> read_bytes("")
    Traceback (most recent call last):
    ...
    FileNotFoundError: [Errno 2] the file name is empty: ''
    >>> read_bytes("/dev/zero")
    Traceback (most recent call last):
    ...
    psgs.errors.FormatError: /dev/zero: not a regular file but a device or a socket: its size cannot be known, so it is not read
    """
    name = os.fspath(path)
    if name in ("", b""):  # (Path("") is ".": a folder, refused as one below)
        raise FileNotFoundError(errno.ENOENT, "the file name is empty", name)
    # non-blocking, so that opening a FIFO with no writer does not wait for one; binary, so
    # that Windows neither turns CRLF into LF nor stops at a Ctrl-Z
    handle = os.open(name, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0)
                     | getattr(os, "O_BINARY", 0))
    try:
        info = os.fstat(handle)
        if stat.S_ISDIR(info.st_mode):
            raise IsADirectoryError(errno.EISDIR, os.strerror(errno.EISDIR), name)
        if stat.S_ISFIFO(info.st_mode):
            if hasattr(os, "set_blocking"):
                os.set_blocking(handle, True)  # now wait for the writer's data
            return _read(handle, PIPE_LIMIT + 1, name, pipe=True)
        if not stat.S_ISREG(info.st_mode):
            raise FormatError("not a regular file but a device or a socket: its size cannot "
                              "be known, so it is not read", source=str(name))
        return _read(handle, info.st_size, name, pipe=False)
    finally:
        os.close(handle)


def _read(handle: int, most: int, name, *, pipe: bool) -> bytes:
    """Up to ``most`` bytes of ``handle``, to its end; a pipe that gives them all is too long
    (``most`` is one past the limit)."""
    chunks, left = [], most
    # os.read allocates what it is asked for: a pipe is read in pieces (its limit is no size
    # it has), a regular file whole (its size is known, and pieces joined would hold it twice)
    piece = 1 << 24 if pipe else 1 << 30
    while left > 0:
        chunk = os.read(handle, min(left, piece))
        if not chunk:  # the end (a regular file that shrank while read: what is there is all)
            break
        chunks.append(chunk)
        left -= len(chunk)
    if pipe and left == 0:
        raise FormatError(f"the pipe gave more than {PIPE_LIMIT:,} bytes: not read further",
                          source=str(name))
    return b"".join(chunks)


def decode_utf8(data: bytes, source: str, *, signature: bool = False) -> str:
    """``data`` as UTF-8 text, or a :class:`~psgs.errors.FormatError` at the first byte that
    is not, with its line and column (counted in characters).

    ``signature=True`` drops a leading byte-order mark (``utf-8-sig``), which spreadsheet
    programs write and which is no part of the first word.

    Examples
    --------
    >>> decode_utf8(b"a\\nb\\xffc", "x.txt")
    Traceback (most recent call last):
    ...
    psgs.errors.FormatError: x.txt:2:2: not UTF-8 text: byte 0xff cannot be decoded (is this a binary file?)
    >>> decode_utf8(b"\\xef\\xbb\\xbfname", "x.csv", signature=True)
    'name'
    """
    body = data[3:] if signature and data.startswith(b"\xef\xbb\xbf") else data
    try:
        return body.decode("utf-8")
    except UnicodeDecodeError as exc:
        line_start = body.rfind(b"\n", 0, exc.start) + 1
        line = body.count(b"\n", 0, exc.start) + 1
        column = len(body[line_start:exc.start].decode("utf-8", errors="replace")) + 1
        raise FormatError(f"not UTF-8 text: byte 0x{body[exc.start]:02x} cannot be decoded "
                          f"(is this a binary file?)", source=source, line=line,
                          column=column) from None


def read_text(path, *, signature: bool = False) -> str:
    """:func:`read_bytes` then :func:`decode_utf8`, the file's name as the source.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "a.txt"
    >>> _ = path.write_text("héllo", encoding="utf-8")
    >>> read_text(path)
    'héllo'
    """
    return decode_utf8(read_bytes(path), str(os.fspath(path)), signature=signature)
