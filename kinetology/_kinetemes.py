"""The segmentation engine: smoothing, dead-band signs and segments of many channels at once.

:mod:`kinetology.segmentation` states the rules one channel at a time; this module computes
the same answers for a whole motion in a few array passes, which is what makes segmentation
run at tens of millions of samples a second. The arithmetic is the same operation for
operation (the same kernel, padding, differences and percentiles), so the segments are the
same as the per-channel rules give (``tests/kinetology/test_kinetemes.py`` checks it against a
plain per-channel reference, and every file of the real data against the former code).

Layout: channels x frames, C order (one channel's frames contiguous), so that the runs of
every channel are found in one pass over the flattened array; channels are processed in groups
of about a megabyte so that the passes stay in the processor's cache.
"""

from __future__ import annotations

import decimal
from functools import lru_cache

import numpy as np

__all__: list[str] = []  # private: kinetology.segmentation is the interface

_GROUP_SAMPLES = 1 << 19  # samples per group of channels: ~4 MB of doubles per array
_SMOOTH_SAMPLES = 1 << 14  # samples per block of the smoothing's passes: they stay in cache
_PERCENTILE_SAMPLES = 8192


def gaussian_kernel(frame_rate: float, sigma: float, frames: int) -> tuple[int, np.ndarray]:
    """``(radius, kernel)`` of the smoothing: 3 sigma each side, at most ``frames - 1``.

    The weights come from decimal arithmetic (40 digits, each ``exp`` and the normalising sum
    correctly rounded), then one rounding to float each: ``np.exp`` and a float sum would
    depend on the CPU's math routines (numpy has its own AVX-512 ``exp``) and could give
    another last bit on another machine. The array is read-only (it is cached).

    Examples
    --------
    >>> radius, kernel = gaussian_kernel(120.0, 0.05, 1000)
    >>> radius, kernel.size, bool(kernel[radius] == kernel.max())
    (18, 37, True)
    """
    sigma_frames = sigma * frame_rate
    # bounded by the take before int(): a sigma of 1e308 s is infinitely many frames
    radius = max(1, int(np.ceil(min(3 * sigma_frames, frames))))
    radius = min(radius, frames - 1)
    return radius, _weights(sigma_frames, radius)


@lru_cache(maxsize=64)
def _weights(sigma_frames: float, radius: int) -> np.ndarray:
    """The normalised weights of offsets ``-radius .. radius`` (read-only)."""
    with decimal.localcontext() as context:
        context.prec = 40
        spread = decimal.Decimal(sigma_frames)
        weights = [(-(decimal.Decimal(k) / spread) ** 2 / 2).exp()
                   for k in range(-radius, radius + 1)]
        total = sum(weights)
        kernel = np.array([float(w / total) for w in weights])
    kernel.flags.writeable = False
    return kernel


def pad_odd(values: np.ndarray, radius: int, extra: int = 0) -> np.ndarray:
    """``values`` (frames first) padded by odd reflection (``2 x[0] - x[k]``), ``extra`` zeros
    after; the same numbers as ``np.pad(..., mode="reflect", reflect_type="odd")``."""
    frames = values.shape[0]
    padded = np.empty((frames + 2 * radius + extra,) + values.shape[1:])
    padded[radius:radius + frames] = values
    np.subtract(2 * values[0], values[radius:0:-1], out=padded[:radius])
    np.subtract(2 * values[-1], values[-2:-radius - 2:-1], out=padded[radius + frames:
                                                                       2 * radius + frames])
    padded[2 * radius + frames:] = 0.0
    return padded


def direct_sum(padded: np.ndarray, kernel: np.ndarray, frames: int) -> np.ndarray:
    """The convolution as shifted copies, two taps at a time (the kernel is symmetric),
    returned frames first like ``padded``.

    Every output is the same sequence of IEEE operations whatever the CPU, the number of
    channels or the block: the centre tap, then ``+ (x[k] + x[2r - k]) * kernel[k]`` for
    ``k = 0, 1, ...`` (elementwise passes, no reduction whose order a library chooses).
    :mod:`kinetology._kinetemes_jit` sums in the same order. Blocks of
    ``_SMOOTH_SAMPLES`` samples keep the ``radius`` passes in the processor's cache.
    """
    radius = kernel.size // 2
    out = np.empty((frames,) + padded.shape[1:])
    width = max(1, padded[0].size)
    step = max(16, _SMOOTH_SAMPLES // width)
    pair = np.empty((min(step, frames),) + padded.shape[1:])
    for a in range(0, frames, step):
        b = min(frames, a + step)
        block, scratch = out[a:b], pair[:b - a]
        np.multiply(padded[radius + a:radius + b], kernel[radius], out=block)
        for k in range(radius):
            np.add(padded[k + a:k + b], padded[2 * radius - k + a:2 * radius - k + b],
                   out=scratch)
            scratch *= kernel[k]
            block += scratch
    return out


def smooth_channels(values: np.ndarray, frame_rate: float, sigma: float) -> np.ndarray:
    """Gaussian smoothing of ``values`` (frames x channels), returned channels x frames."""
    frames, channels = values.shape
    if sigma * frame_rate <= 0 or frames < 2 or channels == 0:
        return np.ascontiguousarray(values.T, dtype=float)
    radius, kernel = gaussian_kernel(frame_rate, sigma, frames)
    return np.ascontiguousarray(direct_sum(pad_odd(values, radius), kernel, frames).T)


def largest_step(values: np.ndarray) -> np.ndarray:
    """Per column, the largest ``|x[t + 1] - x[t]|`` (in blocks of frames that stay in cache)."""
    out = np.zeros(values.shape[1])
    for first in range(0, values.shape[0] - 1, 4096):
        part = values[first:first + 4097]
        np.maximum(out, np.abs(np.diff(part, axis=0)).max(axis=0), out=out)
    return out


def _gradient(signal: np.ndarray, frame_rate: float) -> np.ndarray:
    """``np.gradient(signal, axis=1) * frame_rate``, in place passes (the same numbers)."""
    out = np.empty_like(signal)
    np.subtract(signal[:, 2:], signal[:, :-2], out=out[:, 1:-1])
    out[:, 1:-1] *= 0.5  # np.gradient divides by 2.0: the same number
    np.subtract(signal[:, 1], signal[:, 0], out=out[:, 0])
    np.subtract(signal[:, -1], signal[:, -2], out=out[:, -1])
    out *= frame_rate
    return out


def _bands(signal: np.ndarray, absolute: float, relative: float) -> np.ndarray:
    """:func:`kinetology.segmentation.channel_deadbands` of each row."""
    frames = signal.shape[1]
    if relative <= 0 or frames == 0:
        return np.full(signal.shape[0], float(absolute))
    step = max(1, frames // _PERCENTILE_SAMPLES)
    scale = np.percentile(np.abs(signal[:, ::step]), 95, axis=1)
    with np.errstate(over="ignore"):  # a band past the floats is infinite: all of it absorbed
        return np.maximum(absolute, relative * scale)


def _sign_changes(signal: np.ndarray, band: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where each row's dead-band sign flips (flat positions), and each row's first sign.

    The rules of :func:`kinetology.segmentation.significant_sign`, for all rows at once: a
    run of one raw sign counts when some ``|x|`` in it exceeds the row's band (its peak does);
    other runs take the sign of the last counting run (before the first: the first's; +1 in
    a row without one). Returns the positions (never a row's first frame) where the resolved
    sign differs from the frame before, and per row whether it starts >= 0.
    """
    rows, frames = signal.shape
    raw = signal >= 0
    start = np.empty((rows, frames), dtype=bool)
    start[:, 0] = True
    np.not_equal(raw[:, 1:], raw[:, :-1], out=start[:, 1:])
    starts = np.flatnonzero(start)
    row = starts // frames
    above = np.abs(signal) > band[:, None]
    counting = np.logical_or.reduceat(above.ravel(), starts)
    runs = np.arange(starts.size)
    first = np.searchsorted(starts, np.arange(rows + 1) * frames)  # each row's first run
    # the last counting run so far, or (before the first) the row's first counting run
    last = np.maximum.accumulate(np.where(counting, runs, -1))
    ahead = np.minimum.accumulate(np.where(counting, runs, starts.size)[::-1])[::-1]
    pick = np.where(last >= first[row], last, np.where(ahead < first[row + 1], ahead, -1))
    positive = raw.ravel()[starts]
    resolved = np.where(pick >= 0, positive[np.maximum(pick, 0)], True)  # none counts: +1
    flips = np.flatnonzero((resolved[1:] != resolved[:-1]) & (row[1:] == row[:-1])) + 1
    return starts[flips], resolved[first[:-1]]


def _group(smoothed, frame_rate, velocity_deadband, acceleration_deadband, relative_deadband):
    """Segment starts (flat), state codes and displacements of a group of channels."""
    rows, frames = smoothed.shape
    # bit 4: a row's first frame; bits 1 and 2: the velocity's, the acceleration's sign flips
    marks = np.zeros(rows * frames, dtype=np.int8)
    marks[::frames] = 4
    if frames < 3:  # no derivative: every channel is one rising, speeding-up segment
        seg = np.flatnonzero(marks)
        falling = braking = np.zeros(rows, dtype=bool)
    else:
        velocity = _gradient(smoothed, frame_rate)
        acceleration = _gradient(velocity, frame_rate)
        firsts = []
        for bit, signal, floor in ((1, velocity, velocity_deadband),
                                   (2, acceleration, acceleration_deadband)):
            flips, up = _sign_changes(signal, _bands(signal, floor, relative_deadband))
            marks[flips] |= bit
            firsts.append(up)
        seg = np.flatnonzero(marks)
        kind = marks[seg]
        row_start = np.flatnonzero(kind & 4)
        row = np.cumsum(kind >= 4) - 1
        signs = []
        for bit, up in zip((1, 2), firsts):
            flipped = np.cumsum(kind & bit, dtype=np.int64)  # bit > 1: parity still counts
            flipped //= bit
            signs.append((~up)[row] ^ ((flipped - flipped[row_start][row]) & 1).astype(bool))
        falling = signs[0]
        braking = falling ^ signs[1]
    codes = (2 * falling + braking).astype(np.int8)
    # each segment's change: from its first frame to the next segment's (the last: to the end)
    flat = smoothed.ravel()
    following = np.append(seg[1:], rows * frames)
    last = np.append(seg[1:] % frames == 0, True)
    following[last] -= 1
    return seg, codes, flat[following] - flat[seg]


def segment_columns(smoothed: np.ndarray, frame_rate: float, velocity_deadband: float,
                    acceleration_deadband: float, relative_deadband: float):
    """Per channel (rows of ``smoothed``, channels x frames): borders, codes, displacements.

    The borders of a channel are the first frame of each segment followed by the frame count,
    as :class:`kinetology.segmentation.Segmentation` holds them.
    """
    channels, frames = smoothed.shape
    borders, codes, moves = [], [], []
    if channels == 0:
        return borders, codes, moves
    size = max(1, _GROUP_SAMPLES // max(frames, 1))
    for first in range(0, channels, size):
        part = smoothed[first:first + size]
        seg, code, move = _group(part, frame_rate, velocity_deadband, acceleration_deadband,
                                 relative_deadband)
        cuts = np.searchsorted(seg, np.arange(part.shape[0] + 1) * frames).tolist()
        local = seg - (seg // frames) * frames
        for a, b in zip(cuts[:-1], cuts[1:]):
            ends = np.empty(b - a + 1, dtype=local.dtype)
            ends[:-1] = local[a:b]
            ends[-1] = frames
            borders.append(ends)
            codes.append(code[a:b])
            moves.append(move[a:b])
    return borders, codes, moves


def round_half_even(values: np.ndarray, digits: int) -> np.ndarray:
    """``[round(float(x), digits) for x in values]`` as an array, bit for bit, in array passes.

    Python rounds the exact binary value to ``digits`` decimals (half to even) and returns the
    float nearest that decimal. ``rint(x * 10**digits) / 10**digits`` is the same float (the
    division is correctly rounded) unless ``x * 10**digits`` lies within its rounding error of
    a half (or is too large for exact integers): those few values take Python's ``round``.
    """
    values = np.asarray(values, dtype=float)
    if not 0 <= digits <= 22:  # 10**digits is not an exact float: Python's round for all
        return np.array([round(float(x), digits) for x in values.tolist()], dtype=float)
    scale = 10.0 ** digits
    with np.errstate(invalid="ignore", over="ignore"):  # inf and nan: Python's round below
        scaled = values * scale
        out = np.rint(scaled) / scale
        half_way = np.abs(scaled - np.floor(scaled) - 0.5) <= 4 * np.spacing(np.abs(scaled))
    doubtful = np.flatnonzero(half_way | ~(np.abs(scaled) < 2.0 ** 50))
    for i in doubtful.tolist():
        out[i] = round(float(values[i]), digits)
    return out
