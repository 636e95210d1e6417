"""What every reader shares: the text of a file, and the :class:`~kinetology.motion.Motion` it
builds from the values it read.

Kept apart from :mod:`kinetology.motion` (the value and its error), which is near the module
line cap.
"""

from __future__ import annotations

import os

from psgs._foundation.files import decode_utf8, read_bytes
from psgs.errors import FormatError

from .motion import Motion, MotionFormatError, _Owned

__all__ = ["build_motion", "file_text"]


def build_motion(values, channels, frame_rate, skeleton=None, source="<motion>",
                 meta=None) -> Motion:
    """A :class:`Motion` for a reader: what :class:`Motion` refuses becomes a :class:`MotionFormatError`.

    Readers check their input as they go; this is the last line of that defence, so that a
    file the checks missed still gives the documented error naming the file, never the plain
    ``ValueError`` of the constructor.

    ``values`` is the reader's own new array, which it holds nowhere else: the motion keeps it
    (made read-only) instead of copying it (``kinetology.motion._Owned``), so that reading
    takes the text and the values once, not the values twice.

    Examples
    --------
    >>> import numpy as np
    >>> build_motion(np.zeros((2, 2)), ("knee.rx",), 120, source="bad.bvh")
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: bad.bvh: 1 channel names for 2 columns
    >>> values = np.zeros((2, 1))
    >>> motion = build_motion(values, ("knee.rx",), 120)
    >>> np.shares_memory(motion.values, values), motion.values.flags.writeable
    (True, False)
    """
    try:
        return Motion(_Owned(values), channels, frame_rate, skeleton, source, meta or {})
    except ValueError as exc:
        raise MotionFormatError(str(exc), source=source) from None


def file_text(path, *, until: bytes | None = None) -> str:
    """The text of a motion or label file, as every kinetology reader reads one.

    Through :func:`psgs._foundation.files.read_bytes` and ``decode_utf8``: a device
    (``/dev/zero``) is refused before a byte is read, a regular file is read once and no
    further than its size (a pipe to its end, 1 GiB at most), and its bytes must be UTF-8 (a
    leading byte-order mark is dropped). A byte that is not UTF-8 is an error at its line and column, never replaced: a replaced byte in a joint's
    name would rename the joint without a word.

    Parameters
    ----------
    path : str or Path
        The file.
    until : bytes, optional
        Only the text up to the end of the first line holding these bytes (all of it when
        none does): a header, without decoding the frames after it.

    Returns
    -------
    str
        Its text.

    Raises
    ------
    MotionFormatError
        For a file that is not a regular file, or bytes that are not UTF-8 (``file:line:col``).
    FileNotFoundError, IsADirectoryError
        As :func:`open` raises them.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> path = pathlib.Path(tempfile.mkdtemp()) / "hips.bvh"
    >>> _ = path.write_bytes(b"ROOT Hips\\nJOINT H\\xe4ps\\n")
    >>> file_text(path)
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: ...hips.bvh:2:8: not UTF-8 text: byte 0xe4 cannot be decoded (is this a binary file?)
    """
    try:
        data = read_bytes(path)
        if until is not None and (at := data.find(until)) >= 0:
            end = data.find(b"\n", at)
            data = data[:end] if end >= 0 else data
        return decode_utf8(data, os.fspath(path), signature=True)
    except FormatError as exc:  # the shared reader's error, as the readers document theirs
        raise MotionFormatError(exc.message, source=exc.source, line=exc.line,
                                column=exc.column) from None
