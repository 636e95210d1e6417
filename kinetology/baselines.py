"""The codecs ours is compared with: quantise-and-delta (the usual peer of a segment codec).

Quantise-and-delta is what a user would pick without kinetology: round each
channel to multiples of ``step`` degrees, take frame-to-frame differences
(mostly tiny integers), and xz-compress them channel by channel. Its error is
pure rounding (mean ``step / 4``).
"""

from __future__ import annotations

import lzma
import struct

import numpy as np

from psgs.errors import ValidationError

from .motion import Motion, MotionFormatError

__all__ = ["quantise_delta_compress", "quantise_delta_decompress"]

_MAGIC = b"QDL1"


def quantise_delta_compress(motion: Motion, step: float) -> bytes:
    """Round to ``step``, difference along time, xz (preset 9e). Channel names are not kept.

    Parameters
    ----------
    motion : Motion
        The motion to encode.
    step : float
        The quantisation step, in the channels' units (degrees for angles).

    Returns
    -------
    bytes
        A header (frame rate, frames, channels, step) and the xz-compressed deltas.

    Raises
    ------
    ValueError
        When ``step`` is not positive.

    Examples
    --------
    >>> import kinetology
    >>> walk = kinetology.synthetic_motion(4, seed=0)
    >>> data = quantise_delta_compress(walk, 0.5)
    >>> decoded = quantise_delta_decompress(data)
    >>> bool(abs(decoded.values - walk.values).max() <= 0.25 + 1e-9)
    True
    """
    if not step > 0:
        raise ValidationError(f"step must be positive, not {step!r}")
    q = np.round(motion.values / step).astype(np.int64)
    deltas = np.diff(q, axis=0, prepend=np.zeros((1, q.shape[1]), np.int64))
    dtype = np.int16 if np.abs(deltas).max(initial=0) < 2 ** 15 else np.int32
    header = struct.pack("<4sdIIdc", _MAGIC, motion.frame_rate, motion.frames,
                         q.shape[1], step, b"h" if dtype == np.int16 else b"i")
    body = np.ascontiguousarray(deltas.T.astype(dtype)).tobytes()
    return header + lzma.compress(body, preset=9 | lzma.PRESET_EXTREME)


def quantise_delta_decompress(data: bytes) -> Motion:
    """Inverse of :func:`quantise_delta_compress` (channels named ``c0`` ..).

    Parameters
    ----------
    data : bytes
        What :func:`quantise_delta_compress` wrote.

    Returns
    -------
    Motion
        The quantised values, channels named ``c0``, ``c1``, ..., no skeleton.

    Raises
    ------
    MotionFormatError
        When ``data`` does not start like a quantise-and-delta stream.

    Examples
    --------
    >>> import kinetology
    >>> data = quantise_delta_compress(kinetology.synthetic_motion(3, seed=0), 1.0)
    >>> quantise_delta_decompress(data).channels
    ('c0', 'c1', 'c2')
    >>> quantise_delta_decompress(b"junk")
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: <data>: not a quantise-and-delta stream
    """
    size = struct.calcsize("<4sdIIdc")
    if len(data) < size or data[:4] != _MAGIC:
        raise MotionFormatError("not a quantise-and-delta stream")
    _, rate, frames, channels, step, kind = struct.unpack_from("<4sdIIdc", data)
    dtype = np.int16 if kind == b"h" else np.int32
    deltas = np.frombuffer(lzma.decompress(data[size:]), dtype=dtype).reshape(channels, frames).T
    values = np.cumsum(deltas.astype(np.int64), axis=0) * step
    return Motion(values, tuple(f"c{i}" for i in range(channels)), rate)
