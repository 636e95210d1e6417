"""Reading the frame block of a motion file into its array, a chunk of frames at a time.

Splitting the block into lines and numbers made a Python string per line and per number,
about 60 bytes for a number written in 9: reading a BVH file took eleven times its size.
:func:`read_records` instead reads a chunk of whole frames at a time (64 KiB of text) straight
from the text into one array allocated once: numpy checks the chunk (its characters, the count
of numbers on every line, the bone name that starts each AMC line, the frame numbers) and its
C table reader (``numpy.loadtxt``) converts it, each number as ``float`` reads it. Reading then
takes about twice the file's size (its bytes and its text while they are decoded, then the text
and the values, which the motion keeps without a copy), and is faster than splitting was.

Only well-formed blocks are read here. For anything else (white space other than spaces and
tabs, an indented AMC line, a number the checks cannot vouch for, a value that is not finite,
...) the answer is None and the reader splits the lines (a piece at a time, :func:`line_pieces`,
also into one array), which gives the same values or the error at its line and column: this
changes no value read and no message, only the memory and the time of reading well-formed
files.
"""

from __future__ import annotations

import io

import numpy as np

__all__ = ["Lines", "content_end", "file_end", "line_pieces", "read_records", "FRAME", "CHUNK",
           "SMALL"]

#: Characters of text per chunk converted at once: its copies and checks take a few times
#: this, whatever the file's size.
CHUNK = 1 << 16
#: Blocks of fewer characters are left to the first way: their memory is no matter, and
#: splitting them is quicker than setting numpy's reader up.
SMALL = 1 << 15
#: In a record's layout, the line holding the frame's number (an AMC file's).
FRAME = object()
#: What a chunk may hold once the names are blanked: the characters of decimal numbers
#: (``inf`` and ``nan`` are left to the checks of the first way) and the white space that
#: ``str.split`` and numpy's reader agree on.
_ALLOWED = b"0123456789+-.eE \t\r\n"


class Lines:
    """The lines of ``text`` as :func:`psgs._foundation.text.split_lines` gives them, made
    only when asked for: a reader walks its header line by line and the frames after it
    are read from the text itself, without a string per line.

    Examples
    --------
    >>> lines = Lines("HIERARCHY\\r\\nROOT hip\\n0 1\\n")
    >>> len(lines), lines[1], lines.offset(2), lines.tail(1)
    (3, 'ROOT hip', 20, ['ROOT hip', '0 1'])
    """

    def __init__(self, text: str) -> None:
        if "\r" in text and "\n" not in text:  # the old Mac's breaks, as split_lines reads them
            text = text.replace("\r", "\n")
        self.text = text
        self._count = text.count("\n") + (1 if text and not text.endswith("\n") else 0)
        self._lines: list[str] = []  # the lines split so far, from the first
        self._split = 0  # where the text not split yet starts
        self._starts = [0]  # where each line whose offset was asked for starts

    def __len__(self) -> int:
        return self._count

    def offset(self, index: int) -> int:
        """Where line ``index`` (from 0) starts in the text; its length past the last line."""
        starts, text = self._starts, self.text
        while len(starts) <= index:
            at = text.find("\n", starts[-1])
            starts.append(len(text) if at < 0 else at + 1)
        return starts[index]

    def __getitem__(self, index: int) -> str:
        lines = self._lines
        if index < 0:
            index += self._count
        if 0 <= index < len(lines):
            return lines[index]
        if not 0 <= index < self._count:
            raise IndexError(index)
        text = self.text
        while len(lines) <= index:  # split on, some 8 KiB of whole lines at a time
            stop = text.find("\n", self._split + 8192)
            stop = len(text) if stop < 0 else stop + 1
            piece = text[self._split:stop]
            parts = piece.split("\n")
            if piece.endswith("\n"):
                parts.pop()  # the break that ends the piece starts no line
            lines.extend(line[:-1] if line.endswith("\r") else line for line in parts)
            self._split = stop
        return lines[index]

    def tail(self, index: int) -> list[str]:
        """The lines from ``index`` on, as a list (what the first way of reading reads)."""
        lines = self.text[self.offset(index):].split("\n")
        if lines[-1] == "":
            lines.pop()
        return [line[:-1] if line.endswith("\r") else line for line in lines]


def file_end(lines: Lines) -> dict:
    """Where the text of ``lines`` ends, as an error names it: the last line, the column after
    its last character (line 1, column 1 for no text), for what a file ends without.

    Examples
    --------
    >>> file_end(Lines("HIERARCHY\\nROOT hip\\n")), file_end(Lines(""))
    ({'line': 2, 'column': 9}, {'line': 1, 'column': 1})
    """
    count = len(lines)
    return {"line": max(1, count), "column": len(lines[count - 1]) + 1 if count else 1}


def content_end(text: str, start: int) -> int:
    """Where the text after ``start`` ends once the white space at its end is left out: the
    blank lines after the frames, which the readers allow (looked at a piece at a time, so
    that nothing the size of the text is copied).

    Examples
    --------
    >>> content_end("1 2\\n3 4 \\n\\n", 0)
    7
    """
    end = len(text)
    while end > start:
        piece = text[max(start, end - 4096):end]
        kept = piece.rstrip()
        if kept:
            return end - len(piece) + len(kept)
        end -= len(piece)
    return start


def line_pieces(text: str, start: int, end: int, per: int = 1, size: int | None = None):
    """The lines of ``text[start:end]`` (``start`` at a line's start), as :class:`Lines` gives
    them, a piece of about :data:`CHUNK` characters at a time: the first way of reading holds
    a piece's lines and numbers, never the block's (a Python string per line and per number
    took 7 to 12 times the file's size).

    Parameters
    ----------
    text : str
        The file's text.
    start, end : int
        The block.
    per : int, default 1
        The lines of a record (an AMC frame's): every piece but the last holds whole records.
    size : int, optional
        Characters of a piece, :data:`CHUNK` unless given.

    Yields
    ------
    tuple of (int, list of str)
        The index of the piece's first line (0 for the line at ``start``) and its lines.

    Examples
    --------
    >>> text = "1\\nroot 0\\n2\\nroot 1\\r\\n3\\nroot 2\\n"
    >>> list(line_pieces(text, 0, len(text) - 1, per=2))
    [(0, ['1', 'root 0', '2', 'root 1', '3', 'root 2'])]
    """
    index, at, size = 0, start, CHUNK if size is None else size
    while at < end:
        stop = text.find("\n", min(at + size, end), end)
        stop = end if stop < 0 else stop
        for _ in range(-(text.count("\n", at, stop) + 1) % per):  # on to a record's end
            found = text.find("\n", stop + 1, end) if stop < end else -1
            stop = end if found < 0 else found
        piece = text[at:stop]
        if "\r" in piece:  # one '\r' that ends a line is dropped, as Lines drops it
            piece = piece.replace("\r\n", "\n")
            piece = piece[:-1] if piece.endswith("\r") else piece  # before the break at stop
        lines = piece.split("\n")
        yield index, lines
        index += len(lines)
        at = stop + 1


def read_records(text: str, start: int, end: int, layout, first: int = 1):
    """The values of the frames in ``text[start:end]``, one row per frame; None when the
    block is not one this way reads (the caller then reads it the first way).

    Parameters
    ----------
    text : str
        The file's text.
    start, end : int
        The frame block: ``start`` at the start of a line, ``end`` after its last number.
    layout : sequence of (name, count)
        A frame's lines in order: ``name`` the bytes that start the line (an AMC bone's), None
        for a line of numbers only, or :data:`FRAME` for the line of the frame's number;
        ``count`` the numbers the line holds after the name (1 for :data:`FRAME`).
    first : int, default 1
        The number of the first frame (:data:`FRAME` lines count on from it).

    Returns
    -------
    numpy.ndarray or None
        Frames x (the counts of the lines that are not :data:`FRAME`), floats.

    Examples
    --------
    >>> text = "".join(f"{n}\\nroot 1 2\\nknee {n}\\n" for n in range(1, 3001))
    >>> layout = ((FRAME, 1), (b"root", 2), (b"knee", 1))
    >>> values = read_records(text, 0, len(text) - 1, layout)
    >>> values.shape, values[-1].tolist()
    ((3000, 3), [1.0, 2.0, 3000.0])
    >>> read_records(text.replace("\\n7\\n", "\\n8\\n"), 0, len(text) - 1, layout) is None
    True
    """
    per_frame = len(layout)
    counts = np.array([count for _, count in layout], dtype=np.intp)
    # which of a frame's numbers are values: all but its frame number
    kept = np.concatenate([np.full(count, name is not FRAME) for name, count in layout])
    width = int(kept.sum())
    # frame numbers are compared as floats, exact below 2**53
    if end - start < max(SMALL, 1) or not width or first + len(text) >= 2 ** 53:
        return None
    lines = text.count("\n", start, end) + 1
    if lines % per_frame:
        return None
    frames = lines // per_frame
    # every number takes a character and a separator: a block too short for its frames is
    # malformed, and is refused before its array is allocated
    if frames * int(counts.sum()) * 2 > end - start + 1:
        return None
    out = np.empty((frames, width))
    row, at = 0, start
    while row < frames:
        stop = text.find("\n", min(at + CHUNK, end), end)
        stop = end if stop < 0 else stop
        for _ in range(-(text.count("\n", at, stop) + 1) % per_frame):  # on to a frame's end
            if stop >= end:
                return None
            found = text.find("\n", stop + 1, end)
            stop = end if found < 0 else found
        try:  # UTF-8, as the names are: a number is ASCII, and the checks refuse other bytes
            chunk = (text[at:stop] + "\n").encode("utf-8")
        except UnicodeEncodeError:  # a lone surrogate, in a text not read from a file
            return None
        values = _chunk_values(chunk, layout, counts, first + row)
        if values is None:
            return None
        out[row:row + values.shape[0]] = values[:, kept] if not kept.all() else values
        row += values.shape[0]
        at = stop + 1
    return out if at >= end else None


def _chunk_values(chunk: bytes, layout, counts: np.ndarray, number: int):
    """The frames of one chunk (whole frames, each line ending in ``\\n``), every number of
    a frame in its row; None unless every check holds. ``number``: its first frame's."""
    per_frame = len(layout)
    data = np.frombuffer(chunk, dtype=np.uint8)
    ends = np.flatnonzero(data == 10)
    frames = ends.size // per_frame
    if ends.size % per_frame:
        return None
    starts = np.empty_like(ends)
    starts[0], starts[1:] = 0, ends[:-1] + 1
    if per_frame > 1:  # names are blanked and a frame's lines joined: a copy to write on
        chunk = bytearray(chunk)
        data = np.frombuffer(chunk, dtype=np.uint8)
    for k, (name, _) in enumerate(layout):
        if not isinstance(name, bytes):
            continue
        begin, length = starts[k::per_frame], len(name)
        if ((ends[k::per_frame] - begin) < length).any():
            return None
        at = begin[:, None] + np.arange(length)
        # the name, then white space or the line's end (data[end] is its newline)
        if not ((data[at] == np.frombuffer(name, dtype=np.uint8)).all()
                and (data[begin + length] <= 32).all()):
            return None
        data[at] = 32  # blanked: the rest of the line is its numbers
    if chunk.translate(None, _ALLOWED):
        return None
    for k, (name, _) in enumerate(layout):
        if name is FRAME and not _digits_only(data, starts[k::per_frame], ends[k::per_frame]):
            return None
    # the count of numbers on every line: the numbers (runs of non-space) before each line's
    # end are exactly those of the lines up to it (a blank line, which numpy would skip,
    # has none)
    space = data <= 32
    begins = np.flatnonzero(space[:-1] & ~space[1:]) + 1
    if not space[0]:
        begins = np.concatenate(([0], begins))
    expected = (np.arange(frames)[:, None] * counts.sum() + np.cumsum(counts)).ravel()
    if begins.size != expected[-1] or (np.searchsorted(begins, ends) != expected).any():
        return None
    # a '\r' is white space to str.split wherever it is, a line break to numpy's reader
    if per_frame > 1:  # one line per frame, as numpy reads a table
        data[ends.reshape(frames, per_frame)[:, :-1]] = 32
        data[data == 13] = 32
    else:
        chunk = chunk.replace(b"\r", b" ")
    try:  # numpy's C reader, over twice as fast as splitting; its floats are float()'s
        values = np.loadtxt(io.BytesIO(chunk), dtype=float, comments=None, ndmin=2,
                            encoding="ascii")
    except ValueError:  # a number it does not read: '1e5e5', '1-2'
        return None
    if values.shape != (frames, counts.sum()) or not np.isfinite(values).all():
        return None
    for k, (name, _) in enumerate(layout):
        if name is FRAME:
            column = int(counts[:k].sum())
            if (values[:, column] != number + np.arange(frames)).any():
                return None
    return values


def _digits_only(data: np.ndarray, starts: np.ndarray, ends: np.ndarray) -> bool:
    """Whether each line ``data[starts[i]:ends[i]]`` is ASCII digits and spaces, 30 at most (a
    frame number; ``2.0``, ``+2`` or ``2e0`` are left to the first way, which names them)."""
    lengths = ends - starts
    if lengths.max() > 30:
        return False
    at = starts[:, None] + np.arange(int(lengths.max()))
    inside = np.arange(at.shape[1]) < lengths[:, None]
    found = data[np.minimum(at, data.size - 1)]
    return bool((~inside | (found <= 32) | ((found >= 48) & (found <= 57))).all())
