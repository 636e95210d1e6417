"""Where the codec puts its knots: its own, pinned copy of the state segmentation.

The codec's knots are the segment borders of kinetology's segmentation (states
``B G R Y`` from the signs of velocity and acceleration, after Gaussian
smoothing, with dead bands). :mod:`kinetology.segmentation` is tuned for
actiongrams and its defaults (and its rules) may change; a change there must
not move what the codec writes or the rate-distortion figures it was measured
at. So the codec computes its borders here, with the rules and parameters it
was measured with (:data:`PINNED`), and never reads the segmentation's
defaults. The rules match ``kinetology.segmentation`` as of the codec's
format version 2: smoothing by a Gaussian of ``smoothing`` seconds (odd
reflection at the ends), central differences, and runs of one sign whose
peak stays inside the dead band taking the sign of the run before.

Rotation channels are unwrapped (period 360°) first, so an angle that crosses
±180° is one smooth curve, not a jump of 360° (see :func:`unwrap`).
"""

from __future__ import annotations

import numpy as np

# PINNED, the codec's segmentation parameters: defined with numpy-free values that the
# commands' help texts read without this module
from .._defaults import PINNED
from .._kinetemes import _weights

__all__ = ["PINNED", "unwrap", "is_rotation", "channel_knots"]

def is_rotation(channel: str) -> bool:
    """Whether a channel is an angle (axis ``rx``, ``ry`` or ``rz``), so periodic.

    Examples
    --------
    >>> is_rotation("ltibia.rx"), is_rotation("root.tx")
    (True, False)
    """
    return channel.rsplit(".", 1)[-1] in ("rx", "ry", "rz")


def unwrap(values: np.ndarray, channels) -> np.ndarray:
    """Rotation channels unwrapped along time (period 360°); other channels as they are.

    Examples
    --------
    >>> import numpy as np
    >>> v = np.array([[170.0, 5.0], [179.0, 6.0], [-172.0, 7.0]])
    >>> unwrap(v, ("neck.rz", "root.tx"))[:, 0].tolist()
    [170.0, 179.0, 188.0]
    """
    out = np.array(values, dtype=float, copy=True)
    rotation = [c for c, name in enumerate(channels) if is_rotation(name)]
    if rotation and out.shape[0] > 1:
        out[:, rotation] = np.unwrap(out[:, rotation], period=360.0, axis=0)
    return out


def _smooth(signal: np.ndarray, sigma_frames: float) -> np.ndarray:
    if sigma_frames <= 0 or signal.size < 2:
        return signal.astype(float, copy=True)
    # bounded by the signal before int(): a sigma of 1e308 s is infinitely many frames
    radius = min(max(1, int(np.ceil(min(3 * sigma_frames, signal.size)))), signal.size - 1)
    kernel = _weights(sigma_frames, radius)  # the segmentation's: the same on every CPU
    padded = np.pad(signal, radius, mode="reflect", reflect_type="odd")
    out = np.zeros(signal.size)
    for weight, shift in zip(kernel, range(2 * radius + 1)):
        out += weight * padded[shift:shift + signal.size]
    return out


def _significant_sign(signal: np.ndarray, deadband: float) -> np.ndarray:
    """+1/-1 per sample; runs whose peak stays inside the dead band take the sign before."""
    raw = signal >= 0
    starts = np.concatenate(([0], np.flatnonzero(raw[1:] != raw[:-1]) + 1))
    lengths = np.diff(np.append(starts, signal.size))
    counting = np.maximum.reduceat(np.abs(signal), starts) > deadband
    if not counting.any():
        return np.ones(signal.size, dtype=np.int8)
    run_sign = np.where(raw[starts], 1, -1)
    last = np.maximum.accumulate(np.where(counting, np.arange(starts.size), -1))
    last[last < 0] = np.flatnonzero(counting)[0]
    return np.repeat(run_sign[last], lengths).astype(np.int8)


def channel_knots(signal: np.ndarray, frame_rate: float, smoothing: float,
                  velocity_deadband: float, acceleration_deadband: float):
    """Knot frames and segment state codes of one channel (at least 2 frames).

    Returns ``(knots, codes)``: ``knots`` starts at 0 and ends at the last
    frame; a last segment of a single frame is folded into the one before,
    so every segment spans at least one frame step.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(240) / 120
    >>> knots, codes = channel_knots(30 * np.sin(2 * np.pi * t), 120, **PINNED)
    >>> "".join("BGRY"[c] for c in codes), int(knots[0]), int(knots[-1])
    ('GRYBGRYB', 0, 239)
    """
    frames = signal.size
    smoothed = _smooth(np.asarray(signal, dtype=float), smoothing * frame_rate)
    if frames < 3:
        velocity = acceleration = np.zeros(frames)
    else:
        velocity = np.gradient(smoothed) * frame_rate
        acceleration = np.gradient(velocity) * frame_rate
    v_sign = _significant_sign(velocity, velocity_deadband)
    a_sign = _significant_sign(acceleration, acceleration_deadband)
    falling = v_sign < 0
    braking = (v_sign > 0) == (a_sign < 0)
    column = (2 * falling + braking).astype(np.int8)
    starts = np.concatenate(([0], np.flatnonzero(column[1:] != column[:-1]) + 1))
    codes = column[starts]
    knots = np.append(starts, frames - 1)
    if knots.size > 2 and knots[-2] == knots[-1]:
        knots = np.delete(knots, -2)  # a last segment of one frame joins the one before
        codes = codes[:-1]
    return knots, codes
