"""The default settings of kinetology's segmentation and codec, and the least unwrap period:
plain values, without numpy, so that the commands' help texts (which print them) are made
without importing the modules that work with them.

:mod:`kinetology.segmentation`, :mod:`kinetology.motion`, :mod:`kinetology.codec.knots` and
:mod:`kinetology.codec.encoder` import their values from here under the names they document.
"""

from __future__ import annotations

from types import MappingProxyType

__all__ = ["DEFAULTS", "MIN_UNWRAP", "PINNED", "CODEC_DEFAULTS"]

#: Default parameters (all in seconds and degrees, so they hold from 30 to 120 fps).
DEFAULTS = MappingProxyType({
    "smoothing": 0.05,               # Gaussian sigma, seconds (1.5 frames at 30 fps, 6 at 120)
    "velocity_deadband": 2.0,        # degrees per second, the floor of the velocity dead band
    "acceleration_deadband": 10.0,   # degrees per second squared, likewise
    "relative_deadband": 0.05,       # share of a channel's own 95th-percentile |θ'|, |θ''|
    "min_range": 2.0,                # degrees; channels that move less are still
    "unwrap": 360.0,                 # period of rotation channels in degrees; 0: no unwrapping
})

#: The shortest unwrap period segmentation takes, degrees (0 turns unwrapping off). An angle's
#: period is 360 degrees (180 for an axis without a direction; 2 pi for radians, given to the
#: API); a step between two frames of more than half the period is taken for a wrap and
#: folded back, so a period of 1e-300 folded every movement away and each channel read as
#: still ("no channel left to segment"), and one below a degree folds ordinary movement.
MIN_UNWRAP = 1.0

#: The codec's segmentation parameters (seconds, degrees): fixed here, not read
#: from :data:`DEFAULTS`, so that a change of the segmentation's defaults does not move what
#: the codec writes (see :mod:`kinetology.codec.knots`).
PINNED = MappingProxyType({
    "smoothing": 0.025,              # Gaussian sigma, seconds
    "velocity_deadband": 5.0,        # degrees per second
    "acceleration_deadband": 200.0,  # degrees per second squared
})

#: Settings of :func:`kinetology.codec.compress` without ``max_error``: the pinned
#: segmentation, the knot quantum (degrees), and no residual layer
#: (``residual_step`` 0; ``hysteresis`` applies when there is one).
CODEC_DEFAULTS = MappingProxyType({**PINNED, "quantum": 0.5, "residual_step": 0.0,
                                   "hysteresis": 0.7})
