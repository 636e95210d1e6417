"""The frame layout of an AMC file: numbered frames, each the same bones in the same order.

:func:`frame_layout` checks the layout line by line before any number is converted, so that
a frame lost, doubled or renumbered is an error at its line and column, not a motion with
frames missing or repeated.
"""

from __future__ import annotations

import re

import numpy as np

from psgs._foundation.text import decimal

from ._frame_block import FRAME, Lines, content_end, read_records
from .motion import MotionFormatError

__all__ = ["frame_layout", "indent", "read_at_once", "default_dofs", "angle_columns"]

_FRAME_NUMBER = re.compile(r"[+-]?[0-9]+")  # ASCII digits: str.isdigit takes '²' as well


def frame_layout(data: list[str], source: str, first_line: int) -> tuple[list[str], int]:
    """The bones of every frame, in order, and the lines a frame takes (its number's and its
    bones').

    Frame 1 sets the bones and their order; no bone appears twice in it. Every frame is
    its number, then those bones in that order. Frames are numbered one after another from
    the first frame's number (usually 1): a jump (``1000000000000`` for ``2``) or a repeat
    would lose or double frames without a word.

    Parameters
    ----------
    data : list of str
        The AMC lines from the first frame number to the last line that is not blank.
    source : str
        The file named in errors.
    first_line : int
        The file line number of ``data[0]``.

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
        that is not the expected one (or appears twice in frame 1), or the truncated frame.

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
    """
    def fail(message: str, i: int, column: int | None = None):
        text = data[i]
        raise MotionFormatError(message, source=source, line=first_line + i,
                                column=column or len(text) - len(text.lstrip()) + 1)

    first_text = data[0].strip()
    if not (_FRAME_NUMBER.fullmatch(first_text) and first_text[0] not in "+-"
            and len(first_text) <= 18):
        fail(f"expected a frame number, found {first_text[:30]!r}", 0)
    first = int(first_text)  # usually 1; every next frame's number is one more
    per_frame = 1
    # a frame number ends frame 1's bone lines, a negative one too (then refused in its place)
    while per_frame < len(data) and not _FRAME_NUMBER.fullmatch(data[per_frame].strip()):
        per_frame += 1
    bones: list[str] = []
    seen: dict[str, int] = {}
    for i in range(1, per_frame):
        if not data[i].strip():  # a blank line inside a frame (blank lines only lead or trail)
            fail("expected a bone line, found an empty line", i, 1)
        bone = data[i].split(None, 1)[0]
        if decimal(bone) is not None:  # a number where frame 2's should be ('2.0', '1e0')
            fail(f"expected frame number {first + 1}, found {data[i].strip()[:30]!r} (frames "
                 f"are numbered one after another from {first})", i)
        if bone in seen:  # its second line would be read as the next frame's bone
            fail(f"bone {bone!r} appears twice in frame {first} (first at line "
                 f"{first_line + seen[bone]})", i)
        seen[bone] = i
        bones.append(bone)
    heads = [ln.split(None, 1)[0] if ln.strip() else "" for ln in data]
    expected = ([None] + bones) * (len(data) // per_frame + 1)
    for i, head in enumerate(heads):
        if i % per_frame == 0:
            number = first + i // per_frame
            text = data[i].strip()
            if text != str(number) and not (_FRAME_NUMBER.fullmatch(text) and len(text) <= 30
                                             and int(text) == number):  # "002" is frame 2
                fail(f"expected frame number {number}, found {text[:30] or 'an empty line'!r} "
                     f"(frames are numbered one after another from {first})", i)
        elif head != expected[i]:
            fail(f"expected bone {expected[i]!r}, found {head or 'an empty line'!r}", i)
    if len(data) % per_frame:
        fail(f"last frame is truncated (it has {len(data) % per_frame - 1} of "
             f"{per_frame - 1} bone lines)", len(data) - 1)
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
    if values is not None and not degrees:
        rotation = angle_columns(names)
        with np.errstate(over="ignore"):
            converted = np.degrees(values[:, rotation])
        if not np.isfinite(converted).all():  # the first way names the value
            return None
        values[:, rotation] = converted
    return None if values is None else (values, tuple(names))


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
