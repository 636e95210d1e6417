"""Reading BVH (Biovision hierarchy) files into a :class:`~kinetology.motion.Motion`.

Channels are renamed ``joint.tx`` .. ``joint.rz`` (``Xposition`` -> ``tx``,
``Zrotation`` -> ``rz``); a joint's rotation order is the order its rotation
channels are listed in (``Zrotation Yrotation Xrotation`` -> ``"ZYX"``, the
matrix ``Rz @ Ry @ Rx``). The frame block is read a chunk of frames at a time
(:mod:`kinetology._frame_block`: about twice the file's size in memory); only when it is
malformed is it walked line by line (a piece of lines at a time) to name the bad line.
"""

from __future__ import annotations

import math
import re
from collections import deque
from pathlib import Path

import numpy as np

from psgs._foundation.text import decimal

from ._file_motion import build_motion, file_text
from ._frame_block import Lines, content_end, file_end, read_records
from .motion import (FRAME_RATE_RANGE, Joint, Motion, MotionFormatError, Skeleton, as_path,
                     counted)
from .textblocks import read_block

__all__ = ["read_bvh", "parse_bvh", "FRAME_TIME_RANGE"]

_CHANNEL_AXES = {"xposition": "tx", "yposition": "ty", "zposition": "tz",
                 "xrotation": "rx", "yrotation": "ry", "zrotation": "rz"}
_TOKEN = re.compile(r"\S+")
#: The frame times (seconds) a BVH file may state, bounds included: 0.0001 s to 10 s, the
#: frame rates of :data:`~kinetology.motion.FRAME_RATE_RANGE` (10,000 fps to 0.1 fps).
FRAME_TIME_RANGE = (1 / FRAME_RATE_RANGE[1], 1 / FRAME_RATE_RANGE[0])


def read_bvh(path: str | Path) -> Motion:
    """Read a BVH file (errors name ``file:line:col``).

    Every joint's channels become columns named ``joint.tx`` .. ``joint.rz`` in file
    order; the frame rate is ``1 / Frame Time``, rounded when within 0.01 of a whole number
    (``0.0083333`` is 120 fps). The frame time must lie in :data:`FRAME_TIME_RANGE`, from
    0.0001 s (10,000 fps, beyond high-speed optical capture) to 10 s (0.1 fps, slower than
    any key-framed animation): a time outside it is an error at its line and column, since
    velocities grow with the rate and accelerations with its square, and ``Frame Time:
    1e-300`` overflowed both. The file must be UTF-8 (a byte that is not is an error at its
    line and column, never replaced: it would rename a joint), and a path to a device is
    refused before anything is read.

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    Motion
        With a :class:`Skeleton` (``End Site`` joints included) and ``meta["format"] == "bvh"``.

    Raises
    ------
    MotionFormatError
        For malformed text, naming ``file:line:col``; for a file that is not UTF-8 or not a
        regular file.
    FileNotFoundError
        When the file does not exist.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> path = Path(tempfile.mkdtemp()) / "knee.bvh"
    >>> _ = path.write_text('''HIERARCHY
    ... ROOT knee
    ... { OFFSET 0 0 0
    ...   CHANNELS 1 Xrotation
    ...   End Site
    ...   { OFFSET 0 -10 0 } }
    ... MOTION
    ... Frames: 3
    ... Frame Time: 0.0083333
    ... 0
    ... 45
    ... 90
    ... ''')
    >>> knee = read_bvh(path)
    >>> knee.frames, knee.frame_rate, knee.skeleton.names
    (3, 120.0, ('knee', 'knee.end'))
    """
    path = as_path(path)
    return parse_bvh(file_text(path), source=str(path))


def parse_bvh(text: str, source: str = "<bvh>") -> Motion:
    """Parse BVH text; see :func:`read_bvh`.

    Parameters
    ----------
    text : str
        The contents of a BVH file.
    source : str, default "<bvh>"
        The name errors give.

    Returns
    -------
    Motion

    Raises
    ------
    MotionFormatError
        For malformed text, naming ``source:line:col``.

    Examples
    --------
    >>> parse_bvh("HIERARCHY\\nROOT hip\\n{ OFFSET 0 0 }", source="hip.bvh")
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: hip.bvh:3:...
    """
    if text.startswith("\ufeff"):  # a UTF-8 byte-order mark is not part of the first word
        text = text[1:]
    lines = Lines(text)  # the header's lines: the frames are read from the text
    tokens = _HierarchyTokens(lines, source)
    tokens.expect("HIERARCHY")
    joints: list[Joint] = []
    channels: list[str] = []
    kind = tokens.next("ROOT")
    if kind.upper() != "ROOT":
        tokens.fail(f"expected ROOT, found {kind!r}")
    try:
        _read_joint(tokens, joints, channels, parent=None)
    except RecursionError:  # joints nest by recursion; no real skeleton comes near the limit
        raise MotionFormatError("joints nested too deeply", source=source,
                                line=tokens.last[0], column=tokens.last[1]) from None
    if tokens.peek().upper() == "ROOT":
        tokens.fail("only one ROOT is supported")
    tokens.expect("MOTION")
    frames, frames_at = _read_header_number(lines, tokens, "Frames:", source, integer=True)
    frame_time, time_at = _read_header_number(lines, tokens, "Frame Time:", source,
                                              integer=False)
    # nan, inf and 0 are no time at all; a time far below capture's (1e-300 s) gives a rate
    # whose square, in every acceleration, overflows, and 1e-320 s a rate that is inf itself
    if not (math.isfinite(frame_time) and frame_time > 0):
        raise MotionFormatError(f"frame time must be a positive finite number of seconds, "
                                f"not {frame_time}", source=source, line=time_at[0],
                                column=time_at[1])
    shortest, longest = FRAME_TIME_RANGE
    if not shortest <= frame_time <= longest:
        raise MotionFormatError(f"frame time {frame_time:g} s is outside {shortest:g} .. "
                                f"{longest:g} s ({1 / longest:g} to {1 / shortest:g} frames a "
                                f"second)", source=source, line=time_at[0], column=time_at[1])
    first_data = tokens.line_index + 1
    start = lines.offset(first_data - 1)
    # trailing blank lines are common; anything else beyond the frames is an error
    end = content_end(lines.text, start)
    # a chunk at a time, about twice the file's size in all; a block that way does not read
    # (a malformed one) is split into lines, a piece at a time, to name the bad line
    values = read_records(lines.text, start, end, ((None, len(channels)),))
    if values is None:
        values = read_block(lines.text, start, end, len(channels), source=source,
                            first_line=first_data)
    if values.shape[0] != frames:
        raise MotionFormatError(
            f"header says {counted(frames, 'frame')} but {counted(values.shape[0], 'frame line')} "
            f"follow{'s' * (values.shape[0] == 1)}",
            source=source, line=frames_at[0], column=frames_at[1])
    # the text is let go before the motion is built (read_bvh holds it nowhere else)
    del text, lines, tokens
    skeleton = Skeleton(tuple(joints), length_unit="BVH file units")
    rate = 1.0 / frame_time
    # "Frame Time: .0083333" means 120 fps; below 1 fps (a frame every 100 s) rounding would
    # make the rate 0, so slow rates are kept as they are
    if rate >= 1 and abs(rate - round(rate)) < 0.01:
        rate = float(round(rate))
    return build_motion(values, tuple(channels), rate, skeleton, source, {"format": "bvh"})


def _read_header_number(lines, tokens, label: str, source: str, *, integer: bool):
    """The number after ``label`` on the next header line, and its ``(line, column)``."""
    index = tokens.line_index  # 1-based line of the current token position
    # the header lines follow MOTION; skip blank lines
    while index < len(lines) and not lines[index].strip():
        index += 1
    if index >= len(lines):
        raise MotionFormatError(f"file ends before '{label}'", source=source,
                                **file_end(lines))
    text = lines[index]
    line = text.strip()
    if not line.lower().startswith(label.lower()):
        raise MotionFormatError(f"expected '{label}', found {line[:40]!r}", source=source,
                                line=index + 1, column=len(text) - len(text.lstrip()) + 1)
    after = text.lstrip()[len(label):]  # the file's text after the label, to the line's end
    raw = after.strip()
    # where the number starts (or the label ends when there is none), counted in the file
    at = (index + 1, len(text) - len(after.lstrip()) + 1 if raw else len(text) - len(after) + 1)
    try:
        value = int(raw) if integer else float(raw)
        if decimal(raw) is None:  # int() and float() take '1_0' and other scripts' digits
            raise ValueError(raw)
    except ValueError:
        raise MotionFormatError(f"'{label}' needs a number, not {raw!r}", source=source,
                                line=at[0], column=at[1]) from None
    if integer and value < 0:
        raise MotionFormatError(f"negative frame count {value}", source=source, line=at[0],
                                column=at[1])
    tokens.line_index = index + 1
    return value, at


def _read_joint(tokens, joints, channels, parent, end_site=False, name=None):
    if name is None:
        name = tokens.next("joint name")
    if not end_site:
        if name in tokens.joint_names:  # its channels would share names with the first one's
            tokens.fail(f"two joints are named {name!r}")
        tokens.joint_names.add(name)
    tokens.expect("{")
    offset = (0.0, 0.0, 0.0)
    own_channels: tuple[str, ...] = ()
    order = ""
    index = len(joints)
    joints.append(None)  # reserve the slot so children come after their parent
    children = []
    while True:
        word = tokens.next("'}'")
        upper = word.upper()
        if upper == "OFFSET":
            offset = tuple(tokens.number() for _ in range(3))
        elif upper == "CHANNELS":
            if end_site:
                tokens.fail("an End Site has no channels")
            count_text = tokens.next("channel count")
            try:
                count = int(count_text)
                if decimal(count_text) is None:
                    raise ValueError(count_text)
            except ValueError:
                tokens.fail(f"channel count must be an integer, not {count_text!r}")
            names = []
            for _ in range(count):
                raw = tokens.next("channel name")
                axis = _CHANNEL_AXES.get(raw.lower())
                if axis is None:
                    tokens.fail(f"unknown channel {raw!r} (expected Xposition .. Zrotation)")
                names.append(f"{name}.{axis}")
                if axis.startswith("r"):
                    order += axis[1].upper()
            if len(set(names)) != len(names):
                tokens.fail(f"joint {name!r} lists a channel twice")
            own_channels = tuple(names)
            channels.extend(names)
        elif upper == "JOINT":
            children.append(tokens.next("joint name"))
            _read_joint(tokens, joints, channels, index, name=children[-1])
        elif upper == "END":
            site = tokens.next("Site")
            if site.upper() != "SITE":
                tokens.fail(f"expected 'End Site', found 'End {site}'")
            _read_joint(tokens, joints, channels, index, end_site=True, name=f"{name}.end")
        elif word == "}":
            break
        else:
            tokens.fail(f"unexpected {word!r} in joint {name!r}")
    if len(order) not in (0, 3) and not end_site:
        # fewer than three rotation channels: the missing ones are zero, order as listed
        order = order + "".join(a for a in "ZYX" if a not in order)
    joints[index] = Joint(name, parent, offset, own_channels, order or "ZYX", (0.0, 0.0, 0.0),
                          end_site)


class _HierarchyTokens:
    """White-space tokens of the hierarchy part, with their line and column."""

    def __init__(self, lines: Lines, source: str) -> None:
        self.lines = lines
        self.count = len(lines)  # asked for at every line
        self.source = source
        self.line_index = 0  # number of lines fully consumed
        # a deque: one line may hold the whole hierarchy (12,000 joints), and list.pop(0)
        # per token made reading it quadratic
        self.pending: deque[tuple[str, int]] = deque()
        self.last = (1, 1)
        self.joint_names: set[str] = set()

    def _fill(self) -> bool:
        while not self.pending:
            if self.line_index >= self.count:
                return False
            line = self.lines[self.line_index]
            self.line_index += 1
            self.pending = deque((m.group(), m.start() + 1) for m in _TOKEN.finditer(line))
            self.current_line = self.line_index
        return True

    def peek(self) -> str:
        return self.pending[0][0] if self._fill() else ""

    def next(self, what: str) -> str:
        if not self._fill():
            raise MotionFormatError(f"file ends where {what} was expected", source=self.source,
                                    **file_end(self.lines))
        token, column = self.pending.popleft()
        self.last = (self.current_line, column)
        return token

    def expect(self, word: str) -> None:
        token = self.next(repr(word))
        if token.upper() != word.upper():
            self.fail(f"expected {word!r}, found {token!r}")

    def number(self) -> float:
        token = self.next("a number")
        value = decimal(token)  # not float(): it takes '1_0' and other scripts' digits
        if value is None:
            self.fail(f"expected a number, found {token!r}")
        if not np.isfinite(value):
            self.fail(f"offset {token!r} is not finite")
        return value

    def fail(self, message: str):
        raise MotionFormatError(message, source=self.source, line=self.last[0],
                                column=self.last[1])
