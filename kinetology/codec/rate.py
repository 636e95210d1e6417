"""Rate control: the settings that meet a mean-error bound, at the smallest size found.

Two families of settings are tried, each tuned to just meet the bound:

* **base only**: a ladder of segmentation settings, coarse to fine
  (:data:`BASE_LADDER`, the points of the measured rate-distortion front);
  the coarsest rung that meets the bound is found by bisection over the
  ladder (every rung taken is checked, so the bound holds even where the
  error is not monotone along the ladder);
* **base + residual**: a cheap base (:data:`RESIDUAL_BASES`) and the residual
  layer with the largest step that meets the bound (bisection on the step;
  the smallest step tried, ``max_error / hysteresis``, meets it by
  construction: no decoded value is further than ``hysteresis * step`` from
  the original).

Both are encoded and the smaller is returned. The error is the one
:class:`~kinetology.codec.Compressed` reports (``mean_error``: rotation
channels, modulo 360°), measured on the decoded values themselves.
"""

from __future__ import annotations

import numpy as np

from psgs.errors import ValidationError

from ..motion import Motion
from . import residual
from .encoder import (CODEC_DEFAULTS, Compressed, KnotsTooLarge, _base_values, _errors,
                      compress_with, encode_segments)
from .knots import unwrap

__all__ = ["BASE_LADDER", "RESIDUAL_BASES", "compress_to", "check_max_error"]

#: (smoothing in s, knot quantum in degrees), coarse to fine.
BASE_LADDER = ((0.08, 1.0), (0.06, 1.0), (0.05, 1.0), (0.04, 1.0), (0.03, 1.0), (0.025, 1.0),
               (0.025, 0.5), (0.02, 0.5), (0.015, 0.5))
#: Bases under the residual layer: (smoothing in s, knot quantum in degrees).
RESIDUAL_BASES = ((0.15, 2.0),)
HYSTERESIS = CODEC_DEFAULTS["hysteresis"]
_BISECTIONS = 12


def _settings(smoothing: float, quantum: float, step: float = 0.0) -> dict:
    return {**CODEC_DEFAULTS, "smoothing": smoothing, "quantum": quantum,
            "residual_step": step}


def _base(motion: Motion, settings: dict):
    channels, quantum = encode_segments(motion, **settings)
    decoded = _base_values(motion.frames, [(*ch, quantum) for ch in channels])
    return (channels, quantum), decoded


def _base_only(motion: Motion, max_error: float, original: np.ndarray):
    """The coarsest ladder rung meeting the bound, or None."""
    cache: dict[int, tuple] = {}

    def rung(i: int):
        if i not in cache:
            settings = _settings(*BASE_LADDER[i])
            base, decoded = _base(motion, settings)
            error = _errors(original, decoded, motion.channels)[0]
            cache[i] = (error <= max_error, settings, base)
        return cache[i]

    last = len(BASE_LADDER) - 1
    if not rung(last)[0]:
        return None
    lo, hi = -1, last  # invariant: hi meets the bound
    while hi - lo > 1:
        mid = (lo + hi) // 2
        if rung(mid)[0]:
            hi = mid
        else:
            lo = mid
    _, settings, base = rung(hi)
    return settings, base


def _with_residual(motion: Motion, max_error: float, original: np.ndarray, smoothing: float,
                   quantum: float):
    """The base ``(smoothing, quantum)`` plus the largest residual step meeting the bound."""
    settings = _settings(smoothing, quantum)
    base, decoded = _base(motion, settings)
    unwrapped = unwrap(motion.values, motion.channels)
    target = unwrapped - decoded

    def meets(step: float) -> bool:
        levels = residual.quantise(target, step, HYSTERESIS)
        return _errors(original, decoded + levels * step, motion.channels)[0] <= max_error

    # meets the bound by construction (no error above it; the margin covers rounding)
    lo = max_error / HYSTERESIS * (1 - 1e-9)
    hi = 16 * lo
    if meets(hi):
        lo = hi
    else:
        for _ in range(_BISECTIONS):  # geometric bisection: lo meets the bound, hi does not
            mid = float(np.sqrt(lo * hi))
            if meets(mid):
                lo = mid
            else:
                hi = mid
    return {**settings, "residual_step": lo}, base


def check_max_error(max_error) -> float:
    """``max_error`` as a float, or a :class:`ValidationError`: a bound is a positive number
    of degrees (the command line checks it before reading the take).

    Examples
    --------
    >>> check_max_error(0.5)
    0.5
    >>> check_max_error(0)
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: max_error must be a positive number of degrees, not 0
    """
    if not (isinstance(max_error, (int, float, np.floating, np.integer))
            and not isinstance(max_error, bool)  # True is no bound of 1 degree
            and np.isfinite(max_error) and max_error > 0):
        raise ValidationError(f"max_error must be a positive number of degrees, not {max_error!r}")
    return float(max_error)


def compress_to(motion: Motion, max_error: float) -> Compressed:
    """Compress ``motion`` with a mean rotation-channel error of at most ``max_error`` degrees.

    The bound is checked on every candidate's decoded values; when none meets it (values
    too large to code that finely) a ``ValueError`` says so.

    Examples
    --------
    >>> import kinetology
    >>> walk = kinetology.synthetic_motion(3, seed=0)
    >>> data = compress_to(walk, 0.3)
    >>> data.max_error, data.mean_error <= 0.3
    (0.3, True)
    """
    max_error = check_max_error(max_error)
    original = np.array(motion.values)
    candidates = []
    too_large = None  # a channel whose knots no quantum tried fits in 62 bits
    try:
        found = _base_only(motion, max_error, original)
    except KnotsTooLarge as exc:  # at the ladder's finest quantum: a coarser base may code it
        found, too_large = None, exc.channel
    if found is not None:
        candidates.append(compress_with(motion, found[0], base=found[1], max_error=max_error))
    for smoothing, quantum in RESIDUAL_BASES:
        try:
            settings, base = _with_residual(motion, max_error, original, smoothing, quantum)
        except KnotsTooLarge as exc:  # the residual family's coarser base is too small too
            too_large = exc.channel
            continue
        except ValueError:  # residuals beyond 62 bits at every step that meets the bound
            continue
        candidates.append(compress_with(motion, settings, base=base, max_error=max_error))
    # the promise is checked on what was encoded, not taken for granted: values near the
    # float range's end (1e308) defeat the construction's arithmetic
    meeting = [c for c in candidates if c.mean_error <= max_error]
    if not meeting:
        refusal = f"{motion.source}: no setting meets max_error={max_error}"
        if too_large is not None and not candidates:
            # the quantum is rate control's choice, not the caller's: the refusal is of the
            # bound they gave, and names the channel no quantum tried could code
            raise ValidationError(f"{refusal}: no quantum fine enough to meet it can code the "
                                  f"take (channel {too_large!r} would need knot values of more "
                                  f"than 62 bits)")
        # with no candidate there is no closest error to name (it read "nan degrees")
        closest = (f"the closest reached {min(c.mean_error for c in candidates)!r} degrees"
                   if candidates else "no residual step that fine fits in 62 bits")
        raise ValidationError(f"{refusal} ({closest}); its values may be too large to code "
                              f"that finely")
    return min(meeting, key=len)  # ties: the first (base only), the simpler stream
