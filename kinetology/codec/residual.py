"""The residual layer: what the quartic base misses, on a grid, where fidelity asks for it.

The base curve (one quartic per segment) follows the motion's shape but not
its fine detail or the capture's frame-to-frame jitter. For errors below
about 0.4° the codec adds, per channel and frame, ``step * e[t]`` to the
decoded base, with ``e`` an integer chosen by a *hysteresis* quantiser of the
residual ``d = original - base``: ``e`` keeps its previous value while
``|d - step * e| <= hysteresis * step`` and otherwise jumps to
``round(d / step)``. With ``hysteresis = 0.5`` this is plain rounding; a
little more (the codec uses 0.7, the best of 0.6, 0.7 and 0.8 measured)
stops sensor noise near a grid boundary from toggling ``e`` every frame,
which costs bits and buys almost no accuracy. Every decoded value is
within ``hysteresis * step`` of the original.

The layer stores ``e[t] - e[t - 1]`` (mostly 0) with the adaptive rANS
coder of :mod:`kinetology.codec.entropy`, one lane per channel.
"""

from __future__ import annotations

import numpy as np

from psgs.errors import ValidationError

from . import entropy

__all__ = ["quantise", "encode", "decode"]


def quantise(residual: np.ndarray, step: float, hysteresis: float) -> np.ndarray:
    """Integers ``e`` (frames x channels) with ``|residual - step * e| <= hysteresis * step``.

    Examples
    --------
    >>> import numpy as np
    >>> d = np.array([[0.0], [0.6], [0.4], [0.7], [1.8]])
    >>> quantise(d, 1.0, 0.5)[:, 0].tolist()    # rounding
    [0, 1, 0, 1, 2]
    >>> quantise(d, 1.0, 0.65)[:, 0].tolist()   # 0.6 and 0.4 stay near 0: no toggling
    [0, 0, 0, 1, 2]
    """
    residual = np.asarray(residual, dtype=float)
    if not (step > 0 and 0.5 <= hysteresis):
        raise ValidationError(f"need step > 0 and hysteresis >= 0.5, not {step!r}, {hysteresis!r}")
    out = np.empty(residual.shape, np.int64)
    if residual.shape[0] == 0:
        return out
    scaled = residual / step
    nearest = np.round(scaled)
    if not (np.abs(nearest) < 2.0 ** 62).all():  # before the int64 cast, which would wrap
        raise ValidationError(f"residual step {step!r} is too small (or the residuals not "
                         f"finite): residuals need more than 62 bits")
    current = nearest[0].copy()
    out[0] = current
    for t in range(1, residual.shape[0]):
        jump = np.abs(scaled[t] - current) > hysteresis
        current = np.where(jump, nearest[t], current)
        out[t] = current
    return out


def encode(levels: np.ndarray) -> bytes:
    """The layer's bytes for the integer residual levels (frames x channels).

    Examples
    --------
    >>> import numpy as np
    >>> levels = np.array([[0, 1], [2, -1], [0, 0]])
    >>> decode(encode(levels), 3, 2).tolist()
    [[0, 1], [2, -1], [0, 0]]
    """
    return entropy.encode(np.diff(levels, axis=0, prepend=0) if levels.size else levels)


def decode(data: bytes, frames: int, channels: int) -> np.ndarray:
    """Inverse of :func:`encode` (raises :class:`entropy.EntropyError` on bad data).

    Examples
    --------
    >>> import numpy as np
    >>> decode(encode(np.zeros((2, 2), int)), 2, 2).tolist()
    [[0, 0], [0, 0]]
    """
    deltas = entropy.decode(data, frames, channels)
    # the running sums must stay in int64: bound them in floats first (exact enough here)
    if deltas.size and np.abs(np.cumsum(deltas, axis=0, dtype=float)).max() >= 2.0 ** 62:
        raise entropy.EntropyError("residual levels out of range (2^62 or more)")
    return np.cumsum(deltas, axis=0)
