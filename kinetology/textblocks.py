"""Parsing blocks of numbers fast, and naming the bad line when they are malformed."""

from __future__ import annotations

import itertools
import re
from collections.abc import Callable

import numpy as np

from psgs._foundation.text import decimal

from .motion import MotionFormatError

__all__ = ["parse_rows", "token_column"]

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

    # each line split once: its count checked, its numbers read (a block of the right count of
    # numbers that is not right on every line would shift every value after a moved number)
    rows = [line.split() for line in lines]
    values = None
    if all(len(row) == width for row in rows):
        joined = " ".join(lines)
        # numpy, as float(), takes '1_0' and other scripts' digits: such text goes the slow way
        if joined.isascii() and "_" not in joined:
            try:
                values = np.array(list(itertools.chain.from_iterable(rows)),
                                  dtype=float).reshape(len(lines), width)
            except ValueError:
                values = None
    if values is None:
        for i, parts in enumerate(rows):
            if len(parts) != width:
                raise MotionFormatError(f"expected {width} number{'s' * (width != 1)}, "
                                        f"found {len(parts)}",
                                        source=source, line=where(i), column=1)
            for k, part in enumerate(parts):
                if decimal(part) is None:
                    raise MotionFormatError(f"not a number: {part!r}", source=source,
                                            line=where(i), column=column(i, k))
        # every token is a decimal number (the text held other white space, say)
        values = np.array(list(itertools.chain.from_iterable(rows)),
                          dtype=float).reshape(len(lines), width)
    if not np.isfinite(values).all():
        row, col = (int(n) for n in np.argwhere(~np.isfinite(values))[0])
        raise MotionFormatError(f"value {col + 1} is not finite ({rows[row][col]})",
                                source=source, line=where(row), column=column(row, col))
    return values


def token_column(line: str, k: int) -> int:
    """The column (from 1) where the ``k``-th white-space separated token of ``line`` starts
    (``k`` from 0); found only when an error names it, so reading stays one pass.

    Examples
    --------
    >>> token_column("  root 1  nan", 2)
    11
    """
    return next(itertools.islice(_TOKEN.finditer(line), k, None)).start() + 1
