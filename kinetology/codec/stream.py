"""The codec's bytes: writing and reading the ``KIN2`` layout (``KIN1`` still read).

All integers are unsigned LEB128 varints, signed ones zigzag encoded first;
floats are little-endian IEEE 754 doubles::

    b"KIN2"                               magic
    varint  byte length L of the base part
    L bytes one raw LZMA2 stream (the base part) of:
      varint  version (2)
      f64     frame rate
      varint  frames
      f64     quantum (degrees per unit of knot value)
      varint  channels C
      C x     varint byte length, UTF-8 channel name
      C x     varint segment count n_c
      C x     zigzag first knot value (quanta)
      for each channel: first state code, then (state - previous state) mod 4
                        per later segment, one byte each
      for each channel: n_c durations in frames (varints; they sum to frames - 1,
                        the last segment including the last frame)
      for each channel: n_c zigzag displacements (quanta)
      f64     residual step (0: no residual layer)
    rest    the residual layer when its step is not 0
            (:mod:`kinetology.codec.entropy` bytes of frames x C levels' frame deltas)

``KIN1`` (the first version) is ``b"KIN1"`` and the LZMA2 stream alone, with
version 1 and no residual step. Grouping like fields lets LZMA find their
regularities (the state deltas are almost all 1: ``B G R Y B ...``).

**What a stream may claim.** A header can claim any number of frames and
LZMA can expand a few bytes into gigabytes, so :func:`read` checks every
claim against the stream's own size before it allocates or decodes:

* frames x channels (frames alone with no channels) at most
  ``max(MIN_SAMPLES, SAMPLES_PER_BYTE * len(data))`` samples (2^22, 64 a
  byte: the CMU takes need about 12 a byte);
* the decompressed base part at most ``max(MIN_BODY, BODY_PER_BYTE *
  len(data))`` bytes (1 MiB, 16 a byte) -- parsing is linear in it;
* a residual layer at most ``max(MIN_RESIDUAL_FRAMES, RESIDUAL_FRAMES_PER_BYTE
  * its bytes)`` frames (2^16, 256 a byte) -- it decodes one frame at a time;
* durations, displacements and knot values below 2^62 in magnitude (the
  knot values' running sums included), durations adding up to the frames.

A stream beyond the first three is a :class:`MotionFormatError` that says so;
``max_samples=`` (on :func:`read` and :func:`kinetology.codec.decompress`)
allows a longer one (a still motion of millions of frames compresses to a few
bytes), and then bounds the base part and the residual frames by it too.
"""

from __future__ import annotations

import lzma
import struct
from dataclasses import dataclass

import numpy as np

from psgs.errors import ValidationError

from ..motion import MotionFormatError, counted, is_whole
from .varint import VarintError, decode
from .varint import encode as varints

__all__ = ["Layout", "write", "read", "MIN_SAMPLES", "SAMPLES_PER_BYTE", "MIN_BODY",
           "BODY_PER_BYTE", "MIN_RESIDUAL_FRAMES", "RESIDUAL_FRAMES_PER_BYTE"]

#: Samples (frames x channels) any stream may claim, and how many more per byte of it.
MIN_SAMPLES = 1 << 22
SAMPLES_PER_BYTE = 64
#: Bytes the base part may decompress to, and how many more per byte of the stream.
MIN_BODY = 1 << 20
BODY_PER_BYTE = 16
#: Frames a residual layer may claim, and how many more per byte of the layer.
MIN_RESIDUAL_FRAMES = 1 << 16
RESIDUAL_FRAMES_PER_BYTE = 256
_INT_LIMIT = 1 << 62  # durations, displacements, knot values: int64 with room to add

MAGIC = b"KIN2"
OLD_MAGIC = b"KIN1"
VERSION = 2
FILTERS = [{"id": lzma.FILTER_LZMA2, "preset": 9 | lzma.PRESET_EXTREME}]


@dataclass(frozen=True, eq=False)
class Layout:
    """Everything a compressed motion stores, before decoding to values.

    Examples
    --------
    >>> import kinetology
    >>> walk = kinetology.synthetic_motion(3, seed=0)
    >>> layout = read(bytes(kinetology.compress(walk)), "walk.kin")
    >>> layout.frames, layout.names
    (961, ('j0.rx', 'j1.rx', 'j2.rx'))
    """

    frame_rate: float
    frames: int
    quantum: float
    names: tuple[str, ...]
    codes: tuple[np.ndarray, ...]          # per channel: segment state codes
    durations: tuple[np.ndarray, ...]      # per channel: segment lengths in frames
    firsts: tuple[int, ...]                # per channel: first knot value (quanta)
    displacements: tuple[np.ndarray, ...]  # per channel: knot value steps (quanta)
    residual_step: float = 0.0
    residual: bytes = b""




def zigzag(numbers) -> list[int]:
    return [(2 * int(n)) if n >= 0 else (-2 * int(n) - 1) for n in numbers]


def write(layout: Layout) -> bytes:
    """The ``KIN2`` bytes of ``layout``.

    Examples
    --------
    >>> import kinetology
    >>> walk = kinetology.synthetic_motion(3, seed=0)
    >>> data = bytes(kinetology.compress(walk))
    >>> write(read(data, "walk.kin")) == data
    True
    """
    body = bytearray()
    body += varints([VERSION])
    body += struct.pack("<d", layout.frame_rate)
    body += varints([layout.frames])
    body += struct.pack("<d", layout.quantum)
    body += varints([len(layout.names)])
    for name in layout.names:
        encoded = name.encode("utf-8")
        body += varints([len(encoded)]) + encoded
    body += varints([codes.size for codes in layout.codes])
    body += varints(zigzag(layout.firsts))
    for codes in layout.codes:
        if codes.size:
            body += bytes([int(codes[0])]) + bytes((np.diff(codes.astype(int)) % 4).tolist())
    for durations in layout.durations:
        body += varints(durations)
    for steps in layout.displacements:
        body += varints(zigzag(steps))
    body += struct.pack("<d", layout.residual_step)
    base = lzma.compress(bytes(body), format=lzma.FORMAT_RAW, filters=_filters_for(len(body)))
    return MAGIC + varints([len(base)]) + base + layout.residual


def _filters_for(size: int) -> list[dict]:
    """:data:`FILTERS` with the dictionary cut to the body's size (a power of two, 4 KiB at
    least): the same bytes (a raw LZMA2 stream does not record its dictionary, and no match
    reaches further back than the body's start), but preset 9's 64 MiB dictionary made every
    encoder allocate some 670 MB and take 70 ms on a body of a hundred bytes."""
    dictionary = max(4096, 1 << max(size - 1, 1).bit_length())
    return [{**FILTERS[0], "dict_size": min(dictionary, 64 << 20)}]


class _Reader:
    def __init__(self, data: bytes, source: str, where: str) -> None:
        self.data, self.pos, self.source, self.where = data, 0, source, where

    def fail(self, message: str):
        raise MotionFormatError(f"{message} (at byte {self.pos} of {self.where})",
                                source=self.source)

    def varint(self) -> int:
        try:
            value, self.pos = decode(self.data, self.pos)
        except VarintError as exc:
            self.pos = exc.pos
            self.fail(str(exc))
        return value

    def integers(self, count: int, signed: bool) -> list[int]:
        """``count`` varints (zigzag ``signed`` ones), each below 2^62 in magnitude."""
        out = [self.signed() if signed else self.varint() for _ in range(count)]
        if out and max(max(out), -min(out)) >= _INT_LIMIT:
            self.fail("a duration or displacement is out of range (2^62 or more)")
        return out

    def signed(self) -> int:
        n = self.varint()
        return (n >> 1) if not n & 1 else -((n + 1) >> 1)

    def short(self, count: int, what: str):
        """Fail at the byte where the data runs out (not where the read began), saying how
        much was wanted from where: a file cut anywhere inside a part read the same before."""
        start, self.pos = self.pos, len(self.data)
        self.fail(f"data ends {what}: {counted(count, 'byte')} wanted from byte {start}, "
                  f"{self.pos - start} there")

    def double(self) -> float:
        if self.pos + 8 > len(self.data):
            self.short(8, "inside a float")
        (value,) = struct.unpack_from("<d", self.data, self.pos)
        self.pos += 8
        return value

    def raw(self, count: int) -> bytes:
        if self.pos + count > len(self.data):
            self.short(count, "early")
        chunk = self.data[self.pos:self.pos + count]
        self.pos += count
        return chunk


def read(data: bytes, source: str, max_samples: int | None = None) -> Layout:
    """Parse and check ``KIN2`` (or ``KIN1``) bytes; malformed ones raise MotionFormatError.

    ``max_samples``: how many samples (frames x channels) the stream may claim; by default
    what its size allows (the module's "What a stream may claim").

    Examples
    --------
    >>> import kinetology
    >>> walk = kinetology.synthetic_motion(3, seed=0)
    >>> data = bytes(kinetology.compress(walk))
    >>> write(read(data, "walk.kin")) == data
    True
    """
    # a str, or a memoryview of good bytes, was "bad magic bytes": a wrong type is named
    if not isinstance(data, (bytes, bytearray, memoryview)):
        raise ValidationError(f"a compressed motion is bytes, not {type(data).__name__}")
    data = bytes(data)
    if data[:4] not in (MAGIC, OLD_MAGIC):
        raise MotionFormatError("not a kinetology compressed motion (bad magic bytes)",
                                source=source)
    if max_samples is None:
        samples_limit = max(MIN_SAMPLES, SAMPLES_PER_BYTE * len(data))
        body_limit = max(MIN_BODY, BODY_PER_BYTE * len(data))
    else:
        # int("5") and True passed for a count, 10**30 overflowed numpy's sizes; 1e6 and
        # np.int64 are whole numbers, as int() read them before
        if not is_whole(max_samples) or max_samples < 0:
            raise ValidationError(f"max_samples must be a whole number of samples, 0 or more, "
                                  f"not {max_samples!r}")
        samples_limit = min(int(max_samples), 1 << 56)  # 32 bytes each: still a size lzma takes
        body_limit = max(MIN_BODY, BODY_PER_BYTE * len(data), 32 * samples_limit + (1 << 16))
    if data[:4] == MAGIC:
        head = _Reader(data, source, "the file")
        head.pos = 4
        length = head.varint()
        packed = head.raw(length)
        residual = data[head.pos:]
    else:
        packed, residual = data[4:], b""
    body = _inflate(packed, body_limit, source)
    r = _Reader(body, source, "the decompressed base part")
    version = r.varint()
    if version != (VERSION if data[:4] == MAGIC else 1):
        r.fail(f"unsupported version {version}")
    rate = r.double()
    frames = r.varint()
    quantum = r.double()
    count = r.varint()
    if not (rate > 0 and quantum > 0 and np.isfinite(rate) and np.isfinite(quantum)):
        r.fail("bad frame rate or quantum")
    if count > len(body):
        r.fail(f"{counted(count, 'channel')} cannot fit in {counted(len(body), 'byte')}")
    if frames * max(count, 1) > samples_limit:
        r.fail(f"{counted(frames, 'frame')} x {counted(count, 'channel')} is more than a "
               f"stream of {len(data)} bytes may claim ({samples_limit} samples; "
               f"decompress(..., max_samples=N) allows more)")
    names = []
    for _ in range(count):
        length = r.varint()
        try:
            names.append(r.raw(length).decode("utf-8"))
        except UnicodeDecodeError:
            r.fail("channel name is not UTF-8")
    seg_counts = [r.varint() for _ in range(count)]
    if sum(seg_counts) > len(body):
        r.fail("more segments than bytes")
    firsts = [r.signed() for _ in range(count)]
    codes_list = []
    for n in seg_counts:
        raw = np.frombuffer(r.raw(n), dtype=np.uint8).astype(int)
        if n and (raw > 3).any():
            r.fail("bad state code")
        codes_list.append((np.cumsum(raw) % 4).astype(np.int8))
    durations = [r.integers(n, False) for n in seg_counts]
    displacements = [r.integers(n, True) for n in seg_counts]
    step = r.double() if version >= 2 else 0.0
    if r.pos != len(body):
        r.fail("trailing bytes")
    if not (np.isfinite(step) and step >= 0):
        r.fail(f"bad residual step {step!r}")
    if step == 0 and residual:
        raise MotionFormatError("trailing bytes after the base part (no residual layer)",
                                source=source)
    if step > 0 and frames:
        frames_limit = max(MIN_RESIDUAL_FRAMES, RESIDUAL_FRAMES_PER_BYTE * len(residual))
        if max_samples is not None:
            frames_limit = max(frames_limit, samples_limit)
        if frames > frames_limit:
            raise MotionFormatError(
                f"a residual layer of {counted(len(residual), 'byte')} cannot hold {frames} "
                f"frames (at most {frames_limit}; decompress(..., max_samples=N) allows more)",
                source=source)
    for c in range(count):  # check the layout before allocating frames x channels
        n = seg_counts[c]
        if frames and n == 0 and frames != 1:
            r.fail(f"channel {names[c]!r} has no segments for {frames} frames")
        if frames and n and (sum(durations[c]) != frames - 1 or min(durations[c]) <= 0):
            r.fail(f"channel {names[c]!r}: durations do not add up to "
                   f"{counted(frames - 1, 'frame')}")
        if abs(firsts[c]) >= _INT_LIMIT:
            r.fail(f"channel {names[c]!r}: first knot value {firsts[c]} is out of range")
        knot = firsts[c]
        for step_value in displacements[c]:  # the running sums the decoder forms
            knot += step_value
            if abs(knot) >= _INT_LIMIT:
                r.fail(f"channel {names[c]!r}: a knot value is out of range (2^62 or more)")
    return Layout(rate, frames, quantum, tuple(names), tuple(codes_list),
                  tuple(np.array(d, dtype=np.int64) for d in durations), tuple(firsts),
                  tuple(np.array(d, dtype=np.int64) for d in displacements), step, residual)


def _inflate(packed: bytes, limit: int, source: str) -> bytes:
    """The LZMA base part, refused once it passes ``limit`` bytes (a decompression bomb)."""
    # a dictionary as large as the most the body may be: no match reaches further back than
    # its start, and preset 9's 64 MiB would be allocated for every small stream
    inflater = lzma.LZMADecompressor(format=lzma.FORMAT_RAW, filters=_filters_for(limit + 1))
    try:
        body = inflater.decompress(packed, max_length=limit + 1)
    except lzma.LZMAError as exc:
        raise MotionFormatError(f"corrupt compressed data ({exc})", source=source) from None
    if len(body) > limit:
        raise MotionFormatError(f"the base part decompresses to more than {limit} bytes, "
                                f"more than a stream of this size may hold (decompress(..., "
                                f"max_samples=N) allows more)", source=source)
    if not inflater.eof:
        raise MotionFormatError("corrupt compressed data (it ends before the end-of-stream "
                                "marker)", source=source)
    if inflater.unused_data:
        raise MotionFormatError("trailing bytes after the compressed base part",
                                source=source)
    return body
