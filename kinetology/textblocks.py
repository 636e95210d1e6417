"""Parsing blocks of numbers fast, and naming the bad line when they are malformed."""

from __future__ import annotations

import itertools
import re
from collections.abc import Callable

import numpy as np

from psgs._foundation.text import decimal

from ._frame_block import line_pieces
from .motion import MotionFormatError

__all__ = ["parse_rows", "RowReader", "read_block", "token_column"]

_TOKEN = re.compile(r"\S+")


def parse_rows(lines: list[str], width: int, *, source: str, first_line: int = 1,
               line_of: Callable[[int], int] | None = None,
               indent_of: Callable[[int], int] | None = None) -> np.ndarray:
    """Parse ``lines`` (each ``width`` numbers) into a ``len(lines) x width`` array.

    One vectorised pass (``str.split`` then one ``numpy`` conversion) when the
    block is well formed; otherwise the lines are checked one by one so that
    the error names the first bad one (``first_line`` is the file line number
    of ``lines[0]``, or ``line_of(i)`` gives the file line of ``lines[i]``). Values that
    are not finite (``nan``, ``inf``) are errors too.

    Parameters
    ----------
    lines : list of str
        The lines of the block, numbers separated by white space.
    width : int
        How many numbers each line must hold.
    source : str
        The file name that errors name.
    first_line : int, default 1
        The file line number of ``lines[0]``.
    line_of : callable, optional
        ``line_of(i)`` is the file line number of ``lines[i]`` (for blocks whose lines are not
        consecutive in the file); overrides ``first_line``.
    indent_of : callable, optional
        ``indent_of(i)`` is the number of characters of its file line before ``lines[i]``
        (an AMC bone's name), so that a column is the file's; called only to raise.

    Returns
    -------
    numpy.ndarray
        Floats, shape ``(len(lines), width)``.

    Raises
    ------
    MotionFormatError
        Naming the file, the first bad line and column: a line with the wrong count of
        numbers (column 1), a value that is not a number or one that is not finite (its
        column).

    Examples
    --------
    >>> parse_rows(["1 2", "3 4.5"], 2, source="walk.amc", first_line=10)
    array([[1. , 2. ],
           [3. , 4.5]])
    >>> parse_rows(["1 2", "3 x"], 2, source="walk.amc", first_line=10)
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: walk.amc:11:3: not a number: 'x'
    >>> parse_rows(["1 2", "3 inf"], 2, source="walk.amc", first_line=10)
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: walk.amc:11:3: value 2 is not finite (inf)
    >>> parse_rows(["1 2 3", "4"], 2, source="walk.amc", first_line=10)
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: walk.amc:10:1: expected 2 numbers, found 3
    """
    def where(i: int) -> int:
        return line_of(i) if line_of is not None else first_line + i

    def column(i: int, k: int) -> int:  # of the k-th value of lines[i], in the file's line
        return token_column(lines[i], k) + (indent_of(i) if indent_of is not None else 0)

    # a line of ``width`` numbers takes 2 * width characters with its break: fewer in all, and
    # a line is short of numbers (an error), so no array is allocated for the lines' claim
    room = len(lines) * width * 2 <= sum(len(line) + 1 for line in lines)
    reader = RowReader(width, source, np.empty((len(lines), width)) if room else None)
    reader.add(lines, where, column)
    if reader.error is not None:
        raise reader.error
    return reader.out


class RowReader:
    """The rows of a block of numbers, read a batch of rows at a time into one array as
    :func:`parse_rows` reads them all at once: the same floats, and the same error.

    A batch is split into numbers and converted by one ``numpy`` call when every row holds
    ``width`` of them; otherwise its rows are checked one by one. The first row that does not
    hold ``width`` decimal numbers is kept (:attr:`bad`), and so is the first value that is
    not finite (:attr:`unfinite`): :attr:`error`, the first row's error or else the first
    value's, is what :func:`parse_rows` raises for the rows added so far.

    Parameters
    ----------
    width : int
        The numbers of a row.
    source : str
        The file errors name.
    out : numpy.ndarray, optional
        Where the rows go, in order (rows x ``width``, or columns of a wider array); None
        when only the errors are wanted (a block that cannot be well formed).

    Examples
    --------
    >>> reader = RowReader(2, "walk.bvh", np.empty((3, 2)))
    >>> reader.add(["1 2", "3 4"], lambda j: 10 + j, lambda j, k: 2 * k + 1)
    >>> reader.add(["5 nan"], lambda j: 12 + j, lambda j, k: 2 * k + 1)
    >>> reader.out.tolist()[:2], str(reader.error)
    ([[1.0, 2.0], [3.0, 4.0]], 'walk.bvh:12:3: value 2 is not finite (nan)')
    """

    def __init__(self, width: int, source: str, out: np.ndarray | None = None) -> None:
        self.width, self.source, self.out = width, source, out
        self.rows = 0  # the rows added so far
        self.bad: MotionFormatError | None = None
        self.unfinite: MotionFormatError | None = None

    @property
    def error(self) -> MotionFormatError | None:
        """The error of the rows added so far: the first bad row's, else the first value's
        that is not finite; None for none."""
        return self.bad if self.bad is not None else self.unfinite

    def add(self, rows: list[str], line_of: Callable[[int], int],
            column_of: Callable[[int, int], int]) -> None:
        """Read the next ``rows`` (their text of numbers); ``line_of(j)`` is the file line of
        ``rows[j]`` and ``column_of(j, k)`` the file column of its ``k``-th number, both
        called only for an error. Nothing more is read once a row is bad."""
        if self.bad is not None:
            return
        width = self.width
        # each row split once: its count checked, its numbers read (a block of the right count
        # of numbers that is not right on every row would shift every value after a moved one)
        split = [row.split() for row in rows]
        values = None
        if all(len(parts) == width for parts in split):
            joined = " ".join(rows)
            # numpy, as float(), takes '1_0' and other scripts' digits: such text goes the slow
            # way (numpy reads a number as float() does, so either way gives the same floats)
            if joined.isascii() and "_" not in joined:
                try:
                    values = np.array(list(itertools.chain.from_iterable(split)), dtype=float)
                except ValueError:
                    values = None
        if values is None:
            for j, parts in enumerate(split):
                if len(parts) != width:
                    self.bad = MotionFormatError(f"expected {width} number{'s' * (width != 1)}, "
                                                 f"found {len(parts)}", source=self.source,
                                                 line=line_of(j), column=1)
                    return
                for k, part in enumerate(parts):
                    if decimal(part) is None:
                        self.bad = MotionFormatError(f"not a number: {part!r}",
                                                     source=self.source, line=line_of(j),
                                                     column=column_of(j, k))
                        return
            # every token is a decimal number (the text held other white space, say)
            values = np.array(list(itertools.chain.from_iterable(split)), dtype=float)
        values = values.reshape(len(rows), width)
        if self.unfinite is None and not np.isfinite(values).all():
            j, k = (int(n) for n in np.argwhere(~np.isfinite(values))[0])
            self.unfinite = MotionFormatError(f"value {k + 1} is not finite ({split[j][k]})",
                                              source=self.source, line=line_of(j),
                                              column=column_of(j, k))
        if self.out is not None:
            self.out[self.rows:self.rows + len(rows)] = values
        self.rows += len(rows)


def read_block(text: str, start: int, end: int, width: int, *, source: str,
               first_line: int) -> np.ndarray:
    """The lines of ``text[start:end]`` read as :func:`parse_rows` reads them (the same floats,
    the same error at the same line and column), a piece of lines at a time
    (:func:`~kinetology._frame_block.line_pieces`) into one array allocated once: about the
    text and the values in all, where splitting the block's lines at once took 7 to 12 times
    the text.

    Parameters
    ----------
    text : str
        The file's text.
    start, end : int
        The block: ``start`` at the start of a line (the file's line ``first_line``), ``end``
        after its last number.
    width : int
        The numbers of a line.
    source : str
        The file named in errors.
    first_line : int
        The file line number of the line at ``start``.

    Returns
    -------
    numpy.ndarray
        Floats, lines x ``width``.

    Raises
    ------
    MotionFormatError
        As :func:`parse_rows`: the first line that does not hold ``width`` numbers, else the
        first value that is not finite.

    Examples
    --------
    >>> text = "MOTION\\n1 2\\n3 4.5\\n\\n"
    >>> read_block(text, 7, 16, 2, source="walk.bvh", first_line=2).tolist()
    [[1.0, 2.0], [3.0, 4.5]]
    >>> read_block(text.replace("4.5", "x"), 7, 14, 2, source="walk.bvh", first_line=2)
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: walk.bvh:3:3: not a number: 'x'
    """
    count = text.count("\n", start, end) + 1 if end > start else 0
    # see parse_rows: a block too short for its lines' numbers is an error, not an allocation
    room = count * width * 2 <= end - start + 1
    reader = RowReader(width, source, np.empty((count, width)) if room else None)
    for first, rows in line_pieces(text, start, end):
        reader.add(rows, lambda j, first=first: first_line + first + j,
                   lambda j, k, rows=rows: token_column(rows[j], k))
        if reader.bad is not None:  # no later line comes before it
            raise reader.bad
    if reader.unfinite is not None:
        raise reader.unfinite
    return reader.out


def token_column(line: str, k: int) -> int:
    """The column (from 1) where the ``k``-th white-space separated token of ``line`` starts
    (``k`` from 0); found only when an error names it, so reading stays one pass.

    Examples
    --------
    >>> token_column("  root 1  nan", 2)
    11
    """
    return next(itertools.islice(_TOKEN.finditer(line), k, None)).start() + 1
