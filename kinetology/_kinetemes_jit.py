"""The compiled segmentation engine: one fused loop per channel (numba), channels in threads.

:mod:`kinetology._kinetemes` segments in numpy array passes, each a trip through memory over
every sample; here the work of a channel after its smoothing is one compiled function, run
while the channel's frames are in the processor's cache: both derivatives, the dead bands, the
sign runs of both, the segment borders, codes and displacements. The arithmetic is the numpy
engine's, operation for operation and in the same order (``(x[t+1] - x[t-1]) * 0.5 * rate``;
numba without ``fastmath`` neither reorders nor fuses multiply-adds), and the dead band's 95th
percentile is numpy's linear interpolation between the same two order statistics, so the
output is the same to the bit (``tests/kinetology/test_kinetology_jit_engine.py`` checks it
against the numpy engine, and every file of ``../shared/data/mocap`` was compared).

The smoothing is the numpy engine's direct sum in one loop, in the same order (BLAS, which
this used to take for long kernels, adds in an order that depends on the CPU, the matrix
shape and the library's version). Large takes are cut into groups of channels that threads
smooth and segment side by side: the compiled functions (``nogil``) release the GIL, and no
numba threading layer is involved; a channel's numbers do not depend on its group.

Without numba this module still imports (the functions are then plain Python, which
:mod:`kinetology._engines` never offers), so that the doctests collect everywhere.
"""

from __future__ import annotations

import math
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from psgs._foundation.engines import jit as _jit
from psgs._foundation.engines import usable_cores

from ._kinetemes import _PERCENTILE_SAMPLES, gaussian_kernel, pad_odd

try:
    import numba
except ImportError:  # pragma: no cover - kinetology._engines then offers the numpy engine
    numba = None

__all__: list[str] = []  # private: kinetology.segmentation is the interface

#: below this many samples a call stays in one thread: starting a pool of threads for each
#: step costs more than it saves on the CMU takes (10,000 to 290,000 samples: 45 ms in one
#: thread for all 16, 68 ms with threads from 65,536 samples up)
_THREADED_SAMPLES = 1 << 19


@_jit
def _largest_steps(values):
    """Per column of ``values`` (frames x channels), the largest ``|x[t + 1] - x[t]|``."""
    frames, channels = values.shape
    out = np.zeros(channels)
    for t in range(frames - 1):
        for c in range(channels):
            step = abs(values[t + 1, c] - values[t, c])
            if step > out[c]:
                out[c] = step
    return out


@_jit
def _direct_sum(padded, kernel, frames, out):
    """:func:`kinetology._kinetemes.direct_sum` of each column into ``out`` (channels x frames).

    Per output: the centre tap, then the pairs ``(x[k] + x[2r - k]) * kernel[k]`` added in
    the order ``k = 0, 1, ...``, each rounded as numpy rounds its array passes (no
    ``fastmath``: LLVM may vectorise across channels, which changes no output's operations).
    """
    radius = kernel.size // 2
    channels = padded.shape[1]
    acc = np.empty(channels)
    for t in range(frames):
        for c in range(channels):
            acc[c] = kernel[radius] * padded[radius + t, c]
        for k in range(radius):
            weight = kernel[k]
            for c in range(channels):
                acc[c] += (padded[k + t, c] + padded[2 * radius - k + t, c]) * weight
        for c in range(channels):
            out[c, t] = acc[c]


@_jit
def _derivatives(signal, rate, velocity, acceleration):
    """``np.gradient(signal) * rate`` into ``velocity`` and the same of ``velocity`` into
    ``acceleration``, as :func:`kinetology._kinetemes._gradient` computes it:
    ``(x[t + 1] - x[t - 1]) * 0.5``, then ``* rate``; one-sided at the ends. (Both in one
    function: one derivative a call compiled twice, for the take's read-only rows and for
    the writable velocity.)"""
    n = signal.size
    for t in range(1, n - 1):
        velocity[t] = ((signal[t + 1] - signal[t - 1]) * 0.5) * rate
    velocity[0] = (signal[1] - signal[0]) * rate
    velocity[n - 1] = (signal[n - 1] - signal[n - 2]) * rate
    for t in range(1, n - 1):
        acceleration[t] = ((velocity[t + 1] - velocity[t - 1]) * 0.5) * rate
    acceleration[0] = (velocity[1] - velocity[0]) * rate
    acceleration[n - 1] = (velocity[n - 1] - velocity[n - 2]) * rate


@_jit
def _sift_down(heap, i, size):
    """Restore the min-heap order of ``heap[:size]`` below position ``i``."""
    x = heap[i]
    while True:
        child = 2 * i + 1
        if child >= size:
            break
        if child + 1 < size and heap[child + 1] < heap[child]:
            child += 1
        if heap[child] < x:
            heap[i] = heap[child]
            i = child
        else:
            break
    heap[i] = x


@_jit
def _order_statistics(sample, lower, heap):
    """The ``lower``-th and ``lower + 1``-th smallest of ``sample`` (0-based; the same value
    twice when ``lower`` is the last). A min-heap keeps the ``len(sample) - lower`` largest
    values seen: near the top (95%) that is a few hundred, and most values fail the one,
    well-predicted comparison with the heap's least (a quickselect measured 4x slower)."""
    m = sample.size
    size = m - lower
    for i in range(size):
        heap[i] = sample[i]
    for i in range(size // 2 - 1, -1, -1):
        _sift_down(heap, i, size)
    for i in range(size, m):
        x = sample[i]
        if x > heap[0]:
            heap[0] = x
            _sift_down(heap, np.int64(0), size)  # (a literal 0 would compile it again)
    a = heap[0]
    if size == 1:
        return a, a
    b = heap[1]
    if size > 2 and heap[2] < b:
        b = heap[2]
    return a, b


@_jit
def _percentile(sample, lower, gamma, heap, kept):
    """``np.percentile(sample, 95)`` from its plan (:func:`_percentile_plan`), bit for bit.

    numpy's linear method: the order statistics ``lower`` and ``lower + 1`` (the last one
    twice when ``lower`` is the last), interpolated as ``numpy.lib``'s ``_lerp`` does (from
    the upper one when ``gamma >= 0.5``); a sample with a NaN gives NaN. The order statistics
    come from the values at or above a threshold that about twice as many as needed pass (the
    matching value of every 16th one): when enough pass, they hold the top values exactly;
    otherwise (rarely) the whole sample is searched. ``heap`` and ``kept`` are scratch.
    """
    for x in sample:
        if x != x:
            return math.nan
    m = sample.size
    size = m - lower  # the values from the order statistic ``lower`` up
    found = False
    a = b = 0.0
    probes = (m + 15) // 16
    top = (2 * size) // 16
    if 1 <= top < probes:
        for j in range(probes):
            kept[j] = sample[16 * j]
        threshold, _ = _order_statistics(kept[:probes], probes - top, heap)
        count = 0
        for x in sample:  # a branch-free append: most values do not pass
            kept[count] = x
            count += x >= threshold
        if count >= size:
            a, b = _order_statistics(kept[:count], count - size, heap)
            found = True
    if not found:
        a, b = _order_statistics(sample, lower, heap)
    diff = b - a
    if gamma >= 0.5:
        return b - diff * (1.0 - gamma)
    return a + diff * gamma


@_jit
def _band(signal, floor, relative, step, lower, gamma, sample, heap, kept):
    """:func:`kinetology._kinetemes._bands` of one signal: ``np.maximum(floor, relative *``
    the 95th percentile of every ``step``-th ``|x|``) (NaN propagates, as there)."""
    if relative <= 0:
        return floor
    for j in range(sample.size):
        sample[j] = abs(signal[j * step])
    scale = relative * _percentile(sample, lower, gamma, heap, kept)
    return scale if scale != scale or scale > floor else floor


@_jit
def _flips(x, band, flips):
    """The dead-band sign flips of one signal (:func:`kinetology._kinetemes._sign_changes`).

    A run of one raw sign (``x >= 0``) counts once some ``|x|`` in it exceeds ``band``; the
    resolved sign changes exactly at the start of a counting run whose sign differs from the
    counting run before it. Writes those starts into ``flips``; returns their count and
    whether the signal starts >= 0 (its first counting run's sign; True without one). (The
    velocity and the acceleration in one loop measured no faster than one after the other.)
    """
    sign = x[0] >= 0
    start = 0
    counted = abs(x[0]) > band
    seen = counted
    last = sign
    first = sign if counted else True
    count = 0
    for t in range(1, x.size):
        value = x[t]
        now = value >= 0
        changed = now != sign
        sign = now
        start = t if changed else start  # a select, not a branch: runs are short in noise
        counted = counted and not changed
        if not counted and abs(value) > band:
            counted = True
            if not seen:
                seen = True
                first = sign
            elif sign != last:
                flips[count] = start
                count += 1
            last = sign
    return count, first


@_jit
def _merge(s, v_flips, nv, v_up, a_flips, na, a_up, borders, codes, moves):
    """Segment starts (frame 0 and the union of both flip lists), codes and displacements
    (to the next start; the last to the last frame); returns the number of segments."""
    n = s.size
    falling = not v_up
    a_negative = not a_up
    i = 0
    j = 0
    count = 0
    at = 0
    following = 0
    while following < n:
        following = n
        if i < nv:
            following = v_flips[i]
        if j < na and a_flips[j] < following:
            following = a_flips[j]
        borders[count] = at
        codes[count] = 2 * falling + (falling != a_negative)
        moves[count] = s[min(following, n - 1)] - s[at]
        count += 1
        if i < nv and v_flips[i] == following:
            falling = not falling
            i += 1
        if j < na and a_flips[j] == following:
            a_negative = not a_negative
            j += 1
        at = following
    borders[count] = n
    return count


@_jit
def _segment_rows(flat, row_stride, rows, frames, rate, v_floor, a_floor, relative, step,
                  lower, gamma, samples, counts, first, stride):
    """Rows ``first, first + stride, ...`` (row ``r`` is ``flat[r * row_stride:][:frames]``,
    >= 3 frames), one after the other into growing output arrays: borders (``count + 1``
    entries a row), codes and displacements (``count``), returned; ``counts[r]`` set."""
    velocity = np.empty(frames)
    acceleration = np.empty(frames)
    v_flips = np.empty(frames, dtype=np.int64)
    a_flips = np.empty(frames, dtype=np.int64)
    sample = np.empty(samples)
    heap = np.empty(samples - lower)
    kept = np.empty(samples)
    capacity = ((rows - first + stride - 1) // stride) * (frames // 8 + 2)
    borders = np.empty(capacity, dtype=np.int64)
    codes = np.empty(capacity, dtype=np.int8)
    moves = np.empty(capacity)
    used = 0  # codes and displacements written; borders: one more per row done
    done = 0
    for r in range(first, rows, stride):
        s = flat[r * row_stride:r * row_stride + frames]
        _derivatives(s, rate, velocity, acceleration)
        v_band = _band(velocity, v_floor, relative, step, lower, gamma, sample, heap, kept)
        a_band = _band(acceleration, a_floor, relative, step, lower, gamma, sample, heap, kept)
        nv, v_up = _flips(velocity, v_band, v_flips)
        na, a_up = _flips(acceleration, a_band, a_flips)
        need = used + done + nv + na + 2  # at most nv + na + 1 segments
        if need > capacity:  # grow (rarely: the first guess is a segment per 8 frames)
            capacity = max(2 * capacity, need)
            # element loops: numba compiles slice assignment ten times slower
            grown_borders = np.empty(capacity, dtype=np.int64)
            for i in range(used + done):
                grown_borders[i] = borders[i]
            borders = grown_borders
            grown_codes = np.empty(capacity, dtype=np.int8)
            grown_moves = np.empty(capacity)
            for i in range(used):
                grown_codes[i] = codes[i]
                grown_moves[i] = moves[i]
            codes = grown_codes
            moves = grown_moves
        count = _merge(s, v_flips, nv, v_up, a_flips, na, a_up, borders[used + done:],
                       codes[used:], moves[used:])
        counts[r] = count
        used += count
        done += 1
    return borders, codes, moves


def _percentile_plan(m: int) -> tuple[int, float]:
    """``(lower, gamma)`` of numpy's 95th percentile of ``m`` values (method "linear").

    numpy: the virtual index ``(m - 1) * q`` with ``q = 95 / 100``, the order statistic at its
    floor and ``gamma = virtual - floor``; at or past the last value (``m == 1``) numpy takes
    the last value twice with the index -1, so that ``gamma = virtual + 1``.
    """
    virtual = (m - 1) * (95 / 100)
    if virtual >= m - 1:
        return m - 1, virtual + 1.0
    lower = math.floor(virtual)
    return lower, virtual - lower


def thread_count(channels: int, frames: int) -> int:
    """Threads for a take: the cores this process may use (and at most numba's
    ``NUMBA_NUM_THREADS``), one for small takes, and at least two channels a thread."""
    if channels * frames < _THREADED_SAMPLES:
        return 1
    return max(1, min(usable_cores(), numba.config.NUMBA_NUM_THREADS, channels // 2))


def _in_threads(threads: int, job) -> list:
    """``[job(k) for k in range(threads)]``, side by side; the first error is raised."""
    if threads == 1:
        return [job(0)]
    with ThreadPoolExecutor(threads) as pool:
        return [done.result() for done in [pool.submit(job, k) for k in range(threads)]]


def largest_step(values: np.ndarray) -> np.ndarray:
    """:func:`kinetology._kinetemes.largest_step`, one pass (blocks of frames in threads)."""
    values = np.ascontiguousarray(values, dtype=float).view()
    # read-only whatever the caller's array (a take's are): one compiled signature, where a
    # writable array compiled _largest_steps a second time
    values.flags.writeable = False
    frames, channels = values.shape
    threads = thread_count(frames, channels)  # the frames are cut, not the channels
    if threads == 1:
        return _largest_steps(values)
    cuts = np.linspace(0, frames - 1, threads + 1).astype(int).tolist()
    parts = _in_threads(threads, lambda k: _largest_steps(values[cuts[k]:cuts[k + 1] + 1]))
    return np.maximum.reduce(parts)


def row_ranges(rows: np.ndarray) -> np.ndarray:
    """``np.ptp(rows, axis=1)``, groups of rows in threads (numpy's reductions let go of
    the GIL)."""
    channels, frames = rows.shape
    threads = thread_count(channels, frames)
    if threads == 1 or frames == 0:
        return np.ptp(rows, axis=1)
    cuts = np.linspace(0, channels, threads + 1).astype(int).tolist()
    return np.concatenate(_in_threads(threads, lambda k: np.ptp(rows[cuts[k]:cuts[k + 1]],
                                                                axis=1)))


def smooth_channels(values: np.ndarray, frame_rate: float, sigma: float) -> np.ndarray:
    """:func:`kinetology._kinetemes.smooth_channels`: the direct sum in one compiled loop,
    groups of channels in threads (each output's operations are the same in every split)."""
    frames, channels = values.shape
    if sigma * frame_rate <= 0 or frames < 2 or channels == 0:
        return np.ascontiguousarray(values.T, dtype=float)
    radius, kernel = gaussian_kernel(frame_rate, sigma, frames)
    out = np.empty((channels, frames))
    threads = thread_count(channels, frames)
    cuts = np.linspace(0, channels, threads + 1).astype(int).tolist()
    _in_threads(threads, lambda k: _direct_sum(
        pad_odd(values[:, cuts[k]:cuts[k + 1]], radius), kernel, frames,
        out[cuts[k]:cuts[k + 1]]))
    return out


def segment_columns(smoothed: np.ndarray, frame_rate: float, velocity_deadband: float,
                    acceleration_deadband: float, relative_deadband: float):
    """:func:`kinetology._kinetemes.segment_columns`, one compiled pass per channel."""
    channels, frames = smoothed.shape
    if channels == 0:
        return [], [], []
    if frames < 3:  # no derivative: every channel is one rising, speeding-up segment
        return ([np.array([0, frames], dtype=np.int64) for _ in range(channels)],
                [np.zeros(1, dtype=np.int8) for _ in range(channels)],
                [np.asarray(smoothed[c, -1:] - smoothed[c, :1], dtype=float)
                 for c in range(channels)])
    if smoothed.dtype != np.float64 or smoothed.strides[1] != 8 or smoothed.strides[0] % 8:
        smoothed = np.ascontiguousarray(smoothed, dtype=float)
    # the rows as one flat buffer and a row stride (the smoothing's rows may be padded)
    row_stride = smoothed.strides[0] // 8
    flat = np.lib.stride_tricks.as_strided(smoothed, ((channels - 1) * row_stride + frames,),
                                           (8,), writeable=False)
    step = max(1, frames // _PERCENTILE_SAMPLES)
    samples = (frames - 1) // step + 1
    lower, gamma = _percentile_plan(samples)
    counts = np.empty(channels, dtype=np.int64)
    threads = thread_count(channels, frames)
    parts = _in_threads(threads, lambda k: _segment_rows(
        flat, row_stride, channels, frames, float(frame_rate), float(velocity_deadband),
        float(acceleration_deadband), float(relative_deadband), step, lower, gamma, samples,
        counts, k, threads))
    out_borders, out_codes, out_moves = [None] * channels, [None] * channels, [None] * channels
    counts_list = counts.tolist()
    for k, (borders, codes, moves) in enumerate(parts):
        at = 0
        for done, c in enumerate(range(k, channels, threads)):
            count = counts_list[c]
            out_borders[c] = borders[at + done:at + done + count + 1]
            out_codes[c] = codes[at:at + count]
            out_moves[c] = moves[at:at + count]
            at += count
    return out_borders, out_codes, out_moves
