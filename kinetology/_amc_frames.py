"""The frame layout of an AMC file: numbered frames, each the same bones in the same order.

:func:`frame_layout` checks the layout line by line before any number is converted, so that
a frame lost, doubled or renumbered is an error at its line and column, not a motion with
frames missing or repeated.
"""

from __future__ import annotations

import itertools
import operator
import re

import numpy as np

from psgs._foundation.text import decimal

from . import _frame_block
from ._frame_block import FRAME, Lines, content_end, file_end, line_pieces, read_records
from .motion import MotionFormatError
from .textblocks import RowReader, token_column

__all__ = ["frame_layout", "indent", "read_at_once", "read_by_lines", "to_degrees",
           "default_dofs", "angle_columns"]

_FRAME_NUMBER = re.compile(r"[+-]?[0-9]+")  # ASCII digits: str.isdigit takes '²' as well


def frame_layout(data: list[str], source: str, first_line: int,
                 skeleton=None) -> tuple[list[str], int]:
    """The bones of every frame, in order, and the lines a frame takes (its number's and its
    bones').

    Frame 1 sets the bones and their order; no bone appears twice in it, and each is one of
    ``skeleton``'s bones when there is one (a bone misspelt in frame 1 alone is named at its
    line, not as the good bone of frame 2 that differs from it). Every frame is its number,
    then those bones in that order. Frames are numbered one after another from
    the first frame's number (usually 1): a jump (``1000000000000`` for ``2``) or a repeat
    would lose or double frames without a word.

    Parameters
    ----------
    data : iterable of str
        The AMC lines from the first frame number to the last line that is not blank (read
        once, in order: a list, or the lines of :func:`~kinetology._frame_block.line_pieces`).
    source : str
        The file named in errors.
    first_line : int
        The file line number of ``data[0]``.
    skeleton : container of str, optional
        The skeleton's bones (an ASF file's dofs per bone); None: any bone.

    Returns
    -------
    bones : list of str
        The bones of a frame, in order.
    per_frame : int
        Lines per frame: ``1 + len(bones)``.

    Raises
    ------
    MotionFormatError
        At the line and column of the first frame number that is not the next one, the bone
        that is not the expected one (or appears twice in frame 1, or is not in
        ``skeleton``), or the truncated frame.

    Examples
    --------
    >>> frame_layout(["1", "root 0", "femur 0", "2", "root 1", "femur 2"], "w.amc", 3)
    (['root', 'femur'], 3)
    >>> frame_layout(["1", "root 0", "1", "root 1"], "w.amc", 3)
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: w.amc:5:1: expected frame number 2, found '1' (frames are numbered one after another from 1)
    >>> frame_layout(["1", "root 0", "femur 0", "  root 1"], "w.amc", 3)
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: w.amc:6:3: bone 'root' appears twice in frame 1 (first at line 4)
    >>> frame_layout(["1", "root 0", "femr 0", "2", "root 1", "femur 2"], "w.amc", 3,
    ...              {"root": ("tx",), "femur": ("rx",)})
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: w.amc:5:1: bone 'femr' is not in the skeleton
    """
    def fail(message: str, i: int, text: str, column: int | None = None):
        raise MotionFormatError(message, source=source, line=first_line + i,
                                column=column or len(text) - len(text.lstrip()) + 1)

    lines = iter(data)  # a line at a time: the lines of a long take are never all held
    last = next(lines, "")
    first_text = last.strip()
    if not (_FRAME_NUMBER.fullmatch(first_text) and first_text[0] not in "+-"
            and len(first_text) <= 18):
        fail(f"expected a frame number, found {first_text[:30]!r}", 0, last)
    first = int(first_text)  # usually 1; every next frame's number is one more
    bones: list[str] = []
    seen: dict[str, int] = {}
    per_frame, i, line = None, 0, last  # per_frame: known once frame 2's number comes
    for i, line in enumerate(lines, 1):
        if per_frame is None:
            # a frame number ends frame 1's bone lines, a negative one too (then refused in
            # its place)
            if not _FRAME_NUMBER.fullmatch(line.strip()):
                if not line.strip():  # a blank line inside a frame (they only lead or trail)
                    fail("expected a bone line, found an empty line", i, line, 1)
                bone = line.split(None, 1)[0]
                if decimal(bone) is not None:  # a number where frame 2's should be ('2.0')
                    fail(f"expected frame number {first + 1}, found {line.strip()[:30]!r} "
                         f"(frames are numbered one after another from {first})", i, line)
                if bone in seen:  # its second line would be read as the next frame's bone
                    fail(f"bone {bone!r} appears twice in frame {first} (first at line "
                         f"{first_line + seen[bone]})", i, line)
                if skeleton is not None and bone not in skeleton:
                    fail(f"bone {bone!r} is not in the skeleton", i, line)
                seen[bone] = i
                bones.append(bone)
                continue
            per_frame = i
        slot = i % per_frame
        if slot == 0:
            number = first + i // per_frame
            text = line.strip()
            if text != str(number) and not (_FRAME_NUMBER.fullmatch(text) and len(text) <= 30
                                             and int(text) == number):  # "002" is frame 2
                fail(f"expected frame number {number}, found {text[:30] or 'an empty line'!r} "
                     f"(frames are numbered one after another from {first})", i, line)
        else:
            head = line.split(None, 1)
            if not head or head[0] != bones[slot - 1]:
                fail(f"expected bone {bones[slot - 1]!r}, found "
                     f"{head[0] if head else 'an empty line'!r}", i, line)
    count, last = i + 1, line  # the lines, and the last of them
    if per_frame is None:  # one frame
        per_frame = count
    if count % per_frame:
        fail(f"last frame is truncated (it has {count % per_frame - 1} of "
             f"{per_frame - 1} bone lines)", count - 1, last)
    return bones, per_frame


def indent(line: str, words: int) -> int:
    """Characters of ``line`` before its word ``words`` (from 0): the bone name's and the
    spaces' before the values of an AMC frame line (``words=1``); all of them when there is
    no such word.

    Examples
    --------
    >>> indent("  root 1 2", 1), indent("  root 1 2", 0), indent("root", 1)
    (7, 2, 4)
    """
    parts = line.split(None, words)
    return len(line) - len(parts[words]) if len(parts) > words else len(line)


def read_at_once(lines: Lines, start: int, dofs: dict | None, degrees: bool):
    """The values (degrees) and channel names of the AMC frames from line ``start`` (from 0) on,
    read a chunk at a time by :func:`~kinetology._frame_block.read_records`; None for frames
    that way does not read, which the first way then reads or names the error of.

    Frame 1 is checked by :func:`frame_layout` and sets the bones and their counts of values
    (from ``dofs``, else from frame 1's lines, named as :func:`default_dofs` names them).

    Examples
    --------
    >>> text = ":DEGREES\\n" + "".join(f"{n}\\nroot {n} 2\\n" for n in range(1, 4001))
    >>> values, names = read_at_once(Lines(text), 1, None, True)
    >>> values.shape, values[-1].tolist(), names
    ((4000, 2), [4000.0, 2.0], ('root.1', 'root.2'))
    """
    text = lines.text
    begin = lines.offset(start)
    end = content_end(text, begin)
    if end <= begin:
        return None
    last = start + text.count("\n", begin, end)  # the last line of the frames
    per_frame = 1
    while (start + per_frame <= last
           and not _FRAME_NUMBER.fullmatch(lines[start + per_frame].strip())):
        per_frame += 1
    frame = [lines[i] for i in range(start, start + per_frame)]
    try:
        bones, per_frame = frame_layout(frame, "", start + 1)
    except MotionFormatError:
        return None
    layout, names = [(FRAME, 1)], []
    for bone, line in zip(bones, frame[1:]):
        if dofs is not None and bone not in dofs:
            return None
        bone_dofs = dofs[bone] if dofs is not None else default_dofs(bone, len(line.split()) - 1)
        try:
            layout.append((bone.encode("utf-8"), len(bone_dofs)))
        except UnicodeEncodeError:  # a lone surrogate, in a text not read from a file
            return None
        names.extend(f"{bone}.{d}" for d in bone_dofs)
    values = read_records(text, begin, end, layout, int(frame[0].strip()))
    if values is not None and not degrees and to_degrees(values, angle_columns(names)):
        return None  # a value too large in degrees: the first way names it
    return None if values is None else (values, tuple(names))


def read_by_lines(lines: Lines, start: int, dofs: dict | None, degrees: bool, source: str):
    """The values (degrees) and channel names of the AMC frames from line ``start`` (from 0)
    on, read a piece of whole frames at a time (:func:`~kinetology._frame_block.line_pieces`)
    into one array, as splitting all the lines at once read them: the same floats and the same
    error, where that took 7 times the file's size. The first way, for frames
    :func:`read_at_once` does not read.

    Errors come in the order splitting the lines met them: the frames' layout, a bone of
    frame 1 not in ``dofs`` among them (:func:`frame_layout`); then bone by bone, in frame
    1's order, the first of its lines that does not hold its count of numbers, else the first
    of its values that is not finite; then (``degrees`` False) the first value too large in
    degrees.

    Examples
    --------
    >>> text = ":RADIANS\\n1\\nroot 0 3.14159\\n2\\nroot 1 -3.14159\\n"
    >>> values, names = read_by_lines(Lines(text), 1, {"root": ("tx", "rx")}, False, "w.amc")
    >>> values.round(3).tolist(), names
    ([[0.0, 180.0], [1.0, -180.0]], ('root.tx', 'root.rx'))
    >>> read_by_lines(Lines(text.replace("-3.14159", "x")), 1, None, True, "w.amc")
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: w.amc:5:8: not a number: 'x'
    """
    text = lines.text
    begin = lines.offset(start)
    end = content_end(text, begin)  # the blank lines after the frames left out
    if end <= begin:
        raise MotionFormatError("no frames", source=source, **file_end(lines))
    def each_line():
        return itertools.chain.from_iterable(piece for _, piece in line_pieces(text, begin, end))

    bones, per_frame = frame_layout(each_line(), source, start + 1, dofs)
    frame = list(itertools.islice(each_line(), per_frame))  # frame 1's lines
    frames = (text.count("\n", begin, end) + 1) // per_frame
    names, slots, widths = [], [], []  # slots: the frame line (1..) of each column
    for b, bone in enumerate(bones):
        bone_dofs = (dofs[bone] if dofs is not None
                     else default_dofs(bone, len(_numbers_text(frame[b + 1]).split())))
        names.extend(f"{bone}.{d}" for d in bone_dofs)
        slots.extend([b + 1] * len(bone_dofs))
        widths.append(len(bone_dofs))
    # every number takes a character and a separator: frames too short for theirs hold an
    # error, found without allocating their array
    room = frames * len(names) * 2 <= end - begin + 1
    out = np.empty((frames, len(names))) if room else None
    readers, at = [], 0
    for width in widths:
        readers.append(RowReader(width, source, None if out is None else out[:, at:at + width]))
        at += width
    rotation = angle_columns(names) if not degrees and out is not None else None
    too_large = None
    at_once = _FramesAtOnce(widths, per_frame)
    # pieces of a quarter of the chunk: a piece read at once holds a string per number
    for first, piece in line_pieces(text, begin, end, per_frame, max(1, _frame_block.CHUNK // 4)):
        row = first // per_frame
        values = (at_once.values(piece) if out is not None
                  and all(reader.error is None for reader in readers) else None)
        if values is not None:  # well formed: its rows are read, as bone by bone
            out[row:row + values.shape[0]] = values
            for reader in readers:
                reader.rows += values.shape[0]
        for b, reader in enumerate(readers if values is None else ()):
            mine = piece[b + 1::per_frame]
            # the text after the bone's name (split here, not by a function called per line)
            rows = [parts[1] if len(parts) > 1 else ""
                    for parts in (line.split(None, 1) for line in mine)]
            reader.add(rows, lambda j, s=first + b + 1: start + s + j * per_frame + 1,
                       lambda j, k, rows=rows, mine=mine: token_column(rows[j], k)
                       + indent(mine[j], 1))
        # converted while every value so far is a finite number: after a bad line or value an
        # error is certain, and the rows of a bad line hold no values to name
        if (rotation is not None and too_large is None
                and all(reader.error is None for reader in readers)):
            block = out[row:(first + len(piece)) // per_frame]
            found = to_degrees(block, rotation)
            if found is not None:  # its block left in radians, the value to name
                row, k = found
                col = rotation[k]
                line = row * per_frame + slots[col]
                too_large = MotionFormatError(
                    f"{names[col]}: {block[row, col]:g} radians is too large to convert to "
                    f"degrees", source=source, line=start + first + line + 1,
                    column=token_column(piece[line], 1 + col - slots.index(slots[col])))
    for reader in readers:
        if reader.error is not None:
            raise reader.error
    if too_large is not None:
        raise too_large
    return out, tuple(names)


class _FramesAtOnce:
    """The values of a piece of whole AMC frames by one conversion, when every bone line holds
    its bone's count of numbers, all decimal and finite: the floats reading bone by bone gives
    (each number as ``float`` reads it), without a conversion per bone; None for any other
    piece, which is then read bone by bone to keep the errors in their order.
    """

    def __init__(self, widths: list[int], per_frame: int) -> None:
        self.per_frame = per_frame
        self.counts = [width + 1 for width in widths]  # a bone line's words, its name's too
        self.numbers: list[int] = []  # where a frame's numbers are among its bone lines' words
        words = 0
        for count in self.counts:
            self.numbers.extend(range(words + 1, words + count))
            words += count
        self.words = words

    def values(self, piece: list[str]):
        frames = len(piece) // self.per_frame
        lines = piece.copy()
        del lines[::self.per_frame]  # the frame numbers (checked by frame_layout)
        if list(map(len, map(str.split, lines))) != self.counts * frames:
            return None
        joined = " ".join(lines)
        # numpy, as float(), takes '1_0' and other scripts' digits: such text goes bone by bone
        if not joined.isascii() or "_" in joined:
            return None
        words = joined.split()
        numbers = [f * self.words + k for f in range(frames) for k in self.numbers]
        try:
            values = np.array(operator.itemgetter(*numbers)(words) if len(numbers) > 1
                              else [words[n] for n in numbers], dtype=float)
        except ValueError:
            return None
        values = values.reshape(frames, len(self.numbers))
        return values if np.isfinite(values).all() else None


def _numbers_text(line: str) -> str:
    """The text of an AMC bone line after the bone's name."""
    parts = line.split(None, 1)
    return parts[1] if len(parts) > 1 else ""


def to_degrees(values: np.ndarray, columns: list[int], rows: int = 4096):
    """Convert ``values[:, columns]`` from radians to degrees in place, a block of ``rows``
    rows at a time (all at once took a copy of those columns); the ``(row, k)`` of the first
    value (by rows, then ``columns``) whose degrees a float cannot hold (1e307 radians), its
    block left in radians; None when all are converted.

    Examples
    --------
    >>> values = np.array([[1.0, np.pi], [2.0, 1e307]])
    >>> to_degrees(values, [1], rows=1), values[:, 1].tolist()
    ((1, 0), [180.0, 1e+307])
    """
    for at in range(0, values.shape[0], rows):
        block = values[at:at + rows]
        with np.errstate(over="ignore"):
            converted = np.degrees(block[:, columns])
        if not np.isfinite(converted).all():
            row, k = (int(n) for n in np.argwhere(~np.isfinite(converted))[0])
            return at + row, k
        block[:, columns] = converted
    return None


def default_dofs(bone: str, width: int) -> tuple[str, ...]:
    """The dof names of a bone of ``width`` values when no skeleton names them: ``root``'s six
    its standard ``tx ty tz rx ry rz``, any other's ``1``, ``2``, ...

    Examples
    --------
    >>> default_dofs("root", 6), default_dofs("femur", 2)
    (('tx', 'ty', 'tz', 'rx', 'ry', 'rz'), ('1', '2'))
    """
    return (("tx", "ty", "tz", "rx", "ry", "rz") if bone == "root" and width == 6
            else tuple(str(k + 1) for k in range(width)))


def angle_columns(names) -> list[int]:
    """The columns of ``names`` that are angles: every one but a translation (``bone.1`` ..
    without a skeleton too), converted from radians in a ``:RADIANS`` file.

    Examples
    --------
    >>> angle_columns(["root.tx", "root.rx", "femur.1"])
    [1, 2]
    """
    return [i for i, n in enumerate(names) if n.rsplit(".", 1)[1] not in ("tx", "ty", "tz")]
