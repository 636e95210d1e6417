"""Compression by segments, reconstruction by one quartic per segment, rate control.

Two layers, both decoded exactly and deterministically (the same bytes decode
to the same floats, run after run):

* **the base** (the paper's codec): every channel is segmented into states
  ``B G R Y`` (:mod:`kinetology.codec.knots`, with parameters pinned in the
  codec); a channel with ``n`` segments has ``n + 1`` knots, and each segment
  decodes to the jerk-minimising quartic fixed by its knot values and the
  derivative conditions its state changes imply
  (:mod:`kinetology.codec.quartic`). The encoder fits the knot values by least
  squares and rounds them to multiples of ``quantum`` degrees; per segment it
  stores state, duration and displacement, LZMA-compressed.
* **the residual layer** (optional, for high fidelity): the difference
  between the motion and the decoded base, on a grid of ``residual_step``,
  quantised with hysteresis and entropy coded by an adaptive binary rANS coder
  with one lane per channel (:mod:`kinetology.codec.residual`,
  :mod:`kinetology.codec.entropy`).

Rotation channels (``rx``, ``ry``, ``rz``) are unwrapped (period 360°) before
coding, so they decode unwrapped: equal to the original modulo 360°, and the
reported errors compare them modulo 360°.

:func:`compress` with ``max_error`` picks its own settings
(:mod:`kinetology.codec.rate`); the bytes layout is in
:mod:`kinetology.codec.stream`.
"""

from __future__ import annotations

import numpy as np

from ..motion import Motion, check_motion
from .encoder import (CODEC_DEFAULTS, Compressed, absolute_errors, compress_with, decompress,
                      encode_segments, mean_errors)
from .knots import PINNED
from .quartic import basis, fit_knots, reconstruct
from .rate import compress_to

__all__ = ["compress", "decompress", "Compressed", "mean_errors", "absolute_errors",
           "encode_segments", "reconstruct", "basis", "fit_knots", "CODEC_DEFAULTS", "PINNED"]


def compress(motion: Motion, max_error: float | None = None, **params) -> Compressed:
    """Compress a motion: by its segments, plus a residual layer when fidelity asks for it.

    Parameters
    ----------
    motion : Motion
        The motion (any channels; rotation channels are unwrapped first).
    max_error : float, optional
        Rate control: the largest mean absolute error allowed over the
        rotation channels, in degrees (modulo 360°). The codec then chooses
        every setting itself (see :mod:`kinetology.codec.rate`) and
        ``params`` must be empty.
    **params
        Without ``max_error``: settings as in :data:`CODEC_DEFAULTS`:
        ``smoothing`` (s), ``velocity_deadband`` (deg/s),
        ``acceleration_deadband`` (deg/s²) and ``quantum`` (degrees) for the
        base; ``residual_step`` (degrees, 0 for none) and ``hysteresis``
        (a fraction of the step, at least 0.5) for the residual layer.

    Returns
    -------
    Compressed
        The bytes, with the report: ``mean_error`` (rotation channels,
        degrees), ``mean_error_all`` (every channel), ``settings`` and
        ``max_error``.

    Raises
    ------
    TypeError
        For an unknown setting, or settings given with ``max_error``.
    ValueError
        For a setting out of range, ``max_error`` not positive, or a
        ``max_error`` no setting meets (checked on the decoded values: the
        returned stream's ``mean_error`` is never above it).

    Examples
    --------
    >>> from kinetology.synthetic import synthetic_motion
    >>> m = synthetic_motion(4, (0, 1), seed=3)
    >>> data = compress(m, max_error=0.2)
    >>> data.mean_error <= 0.2
    True
    >>> back = decompress(data)
    >>> round(mean_errors(m, back)[0], 9) == round(data.mean_error, 9)
    True
    >>> len(compress(m)) < len(data)      # the defaults: the base alone, coarser
    True
    """
    check_motion(motion)
    if max_error is not None and params:
        raise TypeError(f"max_error chooses the settings itself; drop "
                        f"{', '.join(sorted(params))}")
    # values near the float range's end overflow in the smoothing and the knot fit; those
    # candidates are refused by the checks on what decodes, so numpy's warnings say nothing
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        if max_error is not None:
            return compress_to(motion, max_error)
        return compress_with(motion, params)
