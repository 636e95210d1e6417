"""The codecs ours is compared with: quantise-and-delta (SPEC §7's peer).

Quantise-and-delta is what a user would pick without kinetology: round each
channel to multiples of ``step`` degrees, take frame-to-frame differences
(mostly tiny integers), and xz-compress them channel by channel. Its error is
pure rounding (mean ``step / 4``).
"""

from __future__ import annotations

import lzma
import struct

import numpy as np

from .motion import Motion, MotionFormatError

__all__ = ["quantise_delta_compress", "quantise_delta_decompress"]

_MAGIC = b"QDL1"


def quantise_delta_compress(motion: Motion, step: float) -> bytes:
    """Round to ``step``, difference along time, xz (preset 9e). Channel names are not kept."""
    if not step > 0:
        raise ValueError(f"step must be positive, not {step!r}")
    q = np.round(motion.values / step).astype(np.int64)
    deltas = np.diff(q, axis=0, prepend=np.zeros((1, q.shape[1]), np.int64))
    dtype = np.int16 if np.abs(deltas).max(initial=0) < 2 ** 15 else np.int32
    header = struct.pack("<4sdIIdc", _MAGIC, motion.frame_rate, motion.frames,
                         q.shape[1], step, b"h" if dtype == np.int16 else b"i")
    body = np.ascontiguousarray(deltas.T.astype(dtype)).tobytes()
    return header + lzma.compress(body, preset=9 | lzma.PRESET_EXTREME)


def quantise_delta_decompress(data: bytes) -> Motion:
    """Inverse of :func:`quantise_delta_compress` (channels named ``c0`` ..)."""
    size = struct.calcsize("<4sdIIdc")
    if len(data) < size or data[:4] != _MAGIC:
        raise MotionFormatError("not a quantise-and-delta stream")
    _, rate, frames, channels, step, kind = struct.unpack_from("<4sdIIdc", data)
    dtype = np.int16 if kind == b"h" else np.int32
    deltas = np.frombuffer(lzma.decompress(data[size:]), dtype=dtype).reshape(channels, frames).T
    values = np.cumsum(deltas.astype(np.int64), axis=0) * step
    return Motion(values, tuple(f"c{i}" for i in range(channels)), rate)
