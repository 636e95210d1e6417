"""The frame layout of an AMC file: numbered frames, each the same bones in the same order.

:func:`frame_layout` checks the layout line by line before any number is converted, so that
a frame lost, doubled or renumbered is an error at its line and column, not a motion with
frames missing or repeated.
"""

from __future__ import annotations

import re

from psgs._foundation.text import decimal

from .motion import MotionFormatError

__all__ = ["frame_layout", "indent"]

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
