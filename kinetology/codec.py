"""Compression by segments, and reconstruction by one quartic per segment (SPEC §7).

Encoding. Every channel is segmented (:func:`kinetology.segmentation.segments`
with ``min_range=0``). A channel with ``n`` segments has ``n + 1`` *knots*:
the first frame of each segment and the last frame. Decoding (below) is
linear in the knot values, so the encoder picks the knot values that make the
decoded curve closest to the original in least squares (a tridiagonal
system), then rounds them to multiples of ``quantum`` degrees. What is stored
per segment is its state, its duration in frames and its angular
displacement (the difference of its two knot values, in quanta).

Decoding. Segment ``i`` runs from knot ``i`` to knot ``i + 1``; on it the
angle is a polynomial of degree 4 in ``s`` (0 to 1 across the segment) with

* the knot values at both ends (2 equations);
* at each border with a neighbour segment, the conditions its state change
  implies: the sign of the velocity changes -> ``θ' = 0`` there; the sign of
  the acceleration changes -> ``θ'' = 0`` there (the paper's "two equations
  for the particular sequence of kinetemes"; a border where both signs change
  gives both, and when that over-determines the quartic the acceleration
  conditions are dropped);
* the last free coefficient(s) chosen to minimise the jerk ``∫ θ'''² ds``
  (with a 1e-6 weight on ``∫ θ''² ds`` so the answer is unique when fewer
  conditions apply).

At the two ends of a recording there is no neighbour: the first segment is
treated as entered from its predecessor in the cycle ``B G R Y B`` and the
last as left towards its successor (``Y -> B`` changes the sign of the
velocity, so a first segment in state ``B`` starts with ``θ' = 0``).

Binary format (all integers unsigned LEB128 varints, signed ones zigzag
encoded first; floats little-endian IEEE 754 doubles)::

    b"KIN1"                               magic, then one raw LZMA2 stream of:
    varint  version (1)
    f64     frame rate
    varint  frames
    f64     quantum (degrees per unit of displacement)
    varint  channels C
    C x     varint byte length, UTF-8 channel name
    C x     varint segment count n_c
    C x     zigzag first knot value (quanta)
    for each channel: first state code, then (state - previous state) mod 4
                      per later segment, one byte each
    for each channel: n_c durations in frames (varints; they sum to frames - 1,
                      the last segment including the last frame)
    for each channel: n_c zigzag displacements (quanta)

Grouping like fields lets LZMA find their regularities (the state deltas
are almost all 1: ``B G R Y B ...``).
"""

from __future__ import annotations

import lzma
import struct
from functools import lru_cache
from itertools import product
from types import MappingProxyType

import numpy as np

from .motion import Motion, MotionFormatError
from .segmentation import DEFAULTS, segments

__all__ = ["compress", "decompress", "encode_segments", "reconstruct", "basis",
           "CODEC_DEFAULTS"]

_MAGIC = b"KIN1"
_VERSION = 1
_FILTERS = [{"id": lzma.FILTER_LZMA2, "preset": 9 | lzma.PRESET_EXTREME}]

#: Codec defaults: the segmentation's, plus the knot quantum in degrees.
CODEC_DEFAULTS = MappingProxyType({**DEFAULTS, "min_range": 0.0, "quantum": 0.5})


# -- the per-segment quartic ------------------------------------------------
def _gram(derivative: int) -> np.ndarray:
    """``G[i, j] = ∫_0^1 (d^k s^i)(d^k s^j) ds`` for monomials s^0..s^4."""
    gram = np.zeros((5, 5))
    for i, j in product(range(5), repeat=2):
        if i >= derivative and j >= derivative:
            ci = np.prod(np.arange(i - derivative + 1, i + 1))
            cj = np.prod(np.arange(j - derivative + 1, j + 1))
            power = i + j - 2 * derivative
            gram[i, j] = ci * cj / (power + 1)
    return gram


def _row(at: float, derivative: int) -> np.ndarray:
    row = np.zeros(5)
    for i in range(derivative, 5):
        row[i] = np.prod(np.arange(i - derivative + 1, i + 1)) * at ** (i - derivative)
    return row


@lru_cache(maxsize=None)
def basis(left_velocity: bool, left_acceleration: bool, right_velocity: bool,
          right_acceleration: bool) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients ``(U, W)`` of ``θ(s) = y0 U(s) + y1 W(s)`` for one border pattern.

    The flags say which derivatives vanish at the left (s=0) and right (s=1)
    border. Coefficients are for ``s^0 .. s^4``.
    """
    rows, kinds = [_row(0, 0), _row(1, 0)], []
    wanted = [(left_velocity, 0, 1), (right_velocity, 1, 1), (left_acceleration, 0, 2),
              (right_acceleration, 1, 2)]
    for flag, at, derivative in wanted:
        if flag and len(rows) < 5:
            rows.append(_row(at, derivative))
            kinds.append(derivative)
    constraints = np.array(rows)
    cost = _gram(3) + 1e-6 * _gram(2)
    m = len(rows)
    kkt = np.zeros((5 + m, 5 + m))
    kkt[:5, :5] = 2 * cost
    kkt[:5, 5:] = constraints.T
    kkt[5:, :5] = constraints
    out = []
    for y0, y1 in ((1.0, 0.0), (0.0, 1.0)):
        rhs = np.zeros(5 + m)
        rhs[5], rhs[6] = y0, y1
        coefficients = np.linalg.lstsq(kkt, rhs, rcond=None)[0][:5]
        coefficients.setflags(write=False)  # cached: shared by every caller
        out.append(coefficients)
    return out[0], out[1]


def _border_flags(codes: np.ndarray) -> np.ndarray:
    """Per segment, its flag pattern index 0..15 (bits: lv, la, rv, ra)."""
    falling = codes >> 1
    braking = (codes == 1) | (codes == 2)  # acceleration negative in G and R
    velocity_flip = falling[1:] != falling[:-1]
    acceleration_flip = braking[1:] != braking[:-1]
    n = codes.size
    lv = np.zeros(n, bool)
    la = np.zeros(n, bool)
    rv = np.zeros(n, bool)
    ra = np.zeros(n, bool)
    lv[1:], la[1:] = velocity_flip, acceleration_flip
    rv[:-1], ra[:-1] = velocity_flip, acceleration_flip
    if n:
        # the recording's ends: as if the cycle B -> G -> R -> Y -> B went on, so the
        # first segment enters as its predecessor leaves, the last leaves towards its
        # successor (B->G and R->Y flip the acceleration, G->R and Y->B the velocity)
        first, last = int(codes[0]), int(codes[-1])
        lv[0], la[0] = first in (0, 2), first in (1, 3)
        rv[-1], ra[-1] = last in (1, 3), last in (0, 2)
    return lv * 8 + la * 4 + rv * 2 + ra


_TABLE_U = np.array([basis(*(bool(k >> b & 1) for b in (3, 2, 1, 0)))[0] for k in range(16)])
_TABLE_W = np.array([basis(*(bool(k >> b & 1) for b in (3, 2, 1, 0)))[1] for k in range(16)])


def _design(knots: np.ndarray, codes: np.ndarray):
    """For every frame: its segment, and the weights of its left and right knot."""
    lengths = np.diff(knots)
    frames = knots[-1] + 1
    seg = np.repeat(np.arange(lengths.size), lengths)
    seg = np.append(seg, lengths.size - 1)  # the last frame ends the last segment
    offset = np.arange(frames) - knots[seg]
    s = offset / lengths[seg]
    powers = s[:, None] ** np.arange(5)
    pattern = _border_flags(codes)[seg]
    u = np.einsum("fk,fk->f", powers, _TABLE_U[pattern])
    w = np.einsum("fk,fk->f", powers, _TABLE_W[pattern])
    return seg, u, w


def reconstruct(knots: np.ndarray, codes: np.ndarray, values: np.ndarray) -> np.ndarray:
    """The decoded curve of one channel: knot frames, segment states, knot values."""
    knots = np.asarray(knots)
    if knots.size == 1:
        return np.full(1, float(values[0]))
    seg, u, w = _design(knots, np.asarray(codes))
    values = np.asarray(values, dtype=float)
    return values[seg] * u + values[seg + 1] * w


def _fit_knots(knots, codes, signal) -> np.ndarray:
    """Knot values minimising the squared error of :func:`reconstruct` (tridiagonal solve)."""
    n = knots.size
    if n == 1:
        return np.array([signal[0]], dtype=float)
    seg, u, w = _design(knots, codes)
    diag = np.bincount(seg, u * u, n) + np.bincount(seg + 1, w * w, n)
    off = np.bincount(seg, u * w, n - 1)[: n - 1]
    rhs = np.bincount(seg, u * signal, n) + np.bincount(seg + 1, w * signal, n)
    # Thomas algorithm (the matrix is symmetric positive definite: every knot has
    # a frame where it alone sets the value)
    c_prev, d_prev = 0.0, 0.0
    diag_l, off_l, rhs_l = diag.tolist(), off.tolist() + [0.0], rhs.tolist()
    cl, dl = [0.0] * n, [0.0] * n
    for i in range(n):
        lower = off_l[i - 1] if i else 0.0
        denominator = diag_l[i] - lower * c_prev
        c_prev = off_l[i] / denominator
        d_prev = (rhs_l[i] - lower * d_prev) / denominator
        cl[i], dl[i] = c_prev, d_prev
    x = [0.0] * n
    x[-1] = dl[-1]
    for i in range(n - 2, -1, -1):
        x[i] = dl[i] - cl[i] * x[i + 1]
    return np.array(x)


def encode_segments(motion: Motion, **params):
    """Per channel: knot frames, segment state codes, and quantised knot values (ints).

    ``params``: the segmentation parameters and ``quantum`` (see
    :data:`CODEC_DEFAULTS`).
    """
    p = {**CODEC_DEFAULTS, **params}
    quantum = float(p.pop("quantum"))
    if not quantum > 0:
        raise ValueError(f"quantum must be positive, not {quantum!r}")
    seg = segments(motion, channels=motion.channels, **p)
    by_name = dict(zip(seg.channels, range(len(seg.channels))))
    out = []
    for c, name in enumerate(motion.channels):
        signal = motion.values[:, c]
        if motion.frames <= 1:
            knots, codes = np.zeros(1, int), np.zeros(0, np.int8)
        elif name in by_name:
            k = by_name[name]
            knots = seg.borders[k].copy()
            codes = seg.codes[k].copy()
            knots[-1] = motion.frames - 1
            if knots.size > 2 and knots[-2] == knots[-1]:
                # a last segment of one frame: fold it into the one before
                knots = np.delete(knots, -2)
                codes = codes[:-1]
        else:
            knots, codes = np.array([0, motion.frames - 1]), np.zeros(1, np.int8)
        if codes.size:
            values = _fit_knots(knots, codes, signal)
        else:  # one frame (its value) or none (a placeholder 0 the decoder never uses)
            values = signal[:1].astype(float) if motion.frames else np.zeros(1)
        steps = np.round(values / quantum)
        if not np.all(np.abs(steps) < 2.0 ** 62):
            # beyond this the int64 cast (and the zigzag varints) would silently wrap
            raise ValueError(f"quantum {quantum!r} is too small for channel {name!r}: knot "
                             f"values would need more than 62 bits")
        out.append((knots, codes, steps.astype(np.int64)))
    return out, quantum


# -- bytes -----------------------------------------------------------------
def _varints(numbers) -> bytes:
    out = bytearray()
    for n in numbers:
        n = int(n)
        if n < 0:
            raise ValueError("varints are unsigned")
        while n >= 0x80:
            out.append((n & 0x7F) | 0x80)
            n >>= 7
        out.append(n)
    return bytes(out)


def _zigzag(numbers) -> list[int]:
    return [(2 * int(n)) if n >= 0 else (-2 * int(n) - 1) for n in numbers]


class _Reader:
    def __init__(self, data: bytes, source: str) -> None:
        self.data, self.pos, self.source = data, 0, source

    def fail(self, message: str):
        raise MotionFormatError(f"{message} (at byte {self.pos} of the decompressed body)",
                                source=self.source)

    def varint(self) -> int:
        shift = result = 0
        while True:
            if self.pos >= len(self.data):
                self.fail("data ends inside a number")
            byte = self.data[self.pos]
            self.pos += 1
            result |= (byte & 0x7F) << shift
            if byte < 0x80:
                return result
            shift += 7
            if shift > 63:
                self.fail("number too long")

    def signed(self) -> int:
        n = self.varint()
        return (n >> 1) if not n & 1 else -((n + 1) >> 1)

    def double(self) -> float:
        if self.pos + 8 > len(self.data):
            self.fail("data ends inside a float")
        (value,) = struct.unpack_from("<d", self.data, self.pos)
        self.pos += 8
        return value

    def raw(self, count: int) -> bytes:
        if self.pos + count > len(self.data):
            self.fail("data ends early")
        chunk = self.data[self.pos:self.pos + count]
        self.pos += count
        return chunk


def compress(motion: Motion, **params) -> bytes:
    """Encode every channel of ``motion`` as segments (the format in the module docstring).

    ``params``: segmentation parameters (``smoothing``, ``velocity_deadband``,
    ``acceleration_deadband``) and ``quantum`` (degrees); defaults in
    :data:`CODEC_DEFAULTS`. Smaller dead bands and quantum: larger, closer.
    """
    channels, quantum = encode_segments(motion, **params)
    body = bytearray()
    body += _varints([_VERSION])
    body += struct.pack("<d", motion.frame_rate)
    body += _varints([motion.frames])
    body += struct.pack("<d", quantum)
    body += _varints([len(motion.channels)])
    for name in motion.channels:
        encoded = name.encode("utf-8")
        body += _varints([len(encoded)]) + encoded
    body += _varints([codes.size for _, codes, _ in channels])
    body += _varints(_zigzag([values[0] for _, _, values in channels]))
    for _, codes, _ in channels:
        if codes.size:
            body += bytes([int(codes[0])]) + bytes(((np.diff(codes.astype(int))) % 4).tolist())
    for knots, codes, _ in channels:
        body += _varints(np.diff(knots)[: codes.size])
    for _, codes, values in channels:
        body += _varints(_zigzag(np.diff(values)[: codes.size]))
    return _MAGIC + lzma.compress(bytes(body), format=lzma.FORMAT_RAW, filters=_FILTERS)


def decompress(data: bytes, source: str = "<compressed motion>") -> Motion:
    """Decode :func:`compress` output to a :class:`Motion` (same channels and frames).

    Malformed data raises :class:`MotionFormatError`.
    """
    if not isinstance(data, (bytes, bytearray)) or data[:4] != _MAGIC:
        raise MotionFormatError("not a kinetology compressed motion (bad magic bytes)",
                                source=source)
    try:
        body = lzma.decompress(bytes(data[4:]), format=lzma.FORMAT_RAW, filters=_FILTERS)
    except lzma.LZMAError as exc:
        raise MotionFormatError(f"corrupt compressed data ({exc})", source=source) from None
    r = _Reader(body, source)
    version = r.varint()
    if version != _VERSION:
        r.fail(f"unsupported version {version}")
    rate = r.double()
    frames = r.varint()
    quantum = r.double()
    count = r.varint()
    if not (rate > 0 and quantum > 0 and np.isfinite(rate) and np.isfinite(quantum)):
        r.fail("bad frame rate or quantum")
    names = []
    for _ in range(count):
        length = r.varint()
        try:
            names.append(r.raw(length).decode("utf-8"))
        except UnicodeDecodeError:
            r.fail("channel name is not UTF-8")
    seg_counts = [r.varint() for _ in range(count)]
    firsts = [r.signed() for _ in range(count)]
    codes_list = []
    for n in seg_counts:
        raw = np.frombuffer(r.raw(n), dtype=np.uint8).astype(int)
        if n and (raw[0] > 3 or (raw[1:] > 3).any()):
            r.fail("bad state code")
        codes_list.append((np.cumsum(raw) % 4).astype(np.int8) if n else raw.astype(np.int8))
    durations = [[r.varint() for _ in range(n)] for n in seg_counts]
    displacements = [[r.signed() for _ in range(n)] for n in seg_counts]
    if r.pos != len(body):
        r.fail("trailing bytes")
    for c in range(count):  # check the layout before allocating frames x channels
        n = seg_counts[c]
        if frames and n == 0 and frames != 1:
            r.fail(f"channel {names[c]!r} has no segments for {frames} frames")
        if frames and n and (sum(durations[c]) != frames - 1 or min(durations[c]) <= 0):
            r.fail(f"channel {names[c]!r}: durations do not add up to {frames - 1} frames")
    try:
        return _decode_values(frames, count, names, seg_counts, firsts, codes_list, durations,
                              displacements, quantum, rate, source)
    except MemoryError:
        # a header can claim any frame count; say so instead of a traceback
        raise MotionFormatError(f"{frames} frames x {count} channels do not fit in memory",
                                source=source) from None


def _decode_values(frames, count, names, seg_counts, firsts, codes_list, durations,
                   displacements, quantum, rate, source) -> Motion:
    values = np.empty((frames, count))
    for c in range(count):
        n = seg_counts[c]
        if frames == 0:
            continue
        if n == 0:
            values[:, c] = firsts[c] * quantum
            continue
        knots = np.concatenate(([0], np.cumsum(durations[c])))
        knot_values = (firsts[c] + np.concatenate(([0], np.cumsum(displacements[c])))) * quantum
        values[:, c] = reconstruct(knots, codes_list[c], knot_values)
    try:
        return Motion(values, tuple(names), rate, None, source,
                      {"format": "kinetology-compressed"})
    except ValueError as exc:  # repeated channel names, values that overflow
        raise MotionFormatError(str(exc), source=source) from None
