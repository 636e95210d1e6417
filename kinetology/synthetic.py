"""Synthetic multi-joint motion: some joints repeat a movement, the others move without pattern.

For tests and built-in examples where the truth is known. Everything random
comes from ``numpy.random.default_rng(seed)``: one seed, one motion.
"""

from __future__ import annotations

from collections.abc import Iterable
from numbers import Integral

import numpy as np

from psgs.errors import ValidationError

from .motion import Motion, check_number
from .segmentation import smooth

__all__ = ["synthetic_motion", "MAX_SAMPLES"]

#: The most samples (frames x joints) a synthetic motion may have: 512 MiB of values, a
#: hundred times the largest benchmark's walk (100,000 frames x 62 channels).
MAX_SAMPLES = 1 << 26


def synthetic_motion(joints: int = 6, patterned=(0, 1, 2), *, repetitions: int = 8,
                     period: float = 1.0, jitter: float = 0.15, amplitude: float = 30.0,
                     noise: float = 0.2, frame_rate: float = 120.0, seed: int = 0) -> Motion:
    """A :class:`Motion` of ``joints`` channels named ``j0.rx``, ``j1.rx`` ...

    The joints in ``patterned`` each repeat their own movement (a random
    smooth curve of three harmonics) ``repetitions`` times, all in step with
    one another; each repetition lasts ``period`` seconds times a random
    factor in ``1 ± jitter`` (real repetitions are not evenly spaced). The
    other joints follow smoothed random walks of the same amplitude. Gaussian
    sensor noise of ``noise`` degrees is added everywhere.
    ``motion.meta["patterned"]`` names the patterned channels and
    ``motion.meta["repetition_starts"]`` the start of each repetition (seconds).

    Parameters
    ----------
    joints : int, default 6
        Number of channels (one rotation channel per joint).
    patterned : iterable of int, default (0, 1, 2)
        Indices of the joints that repeat a movement; the others do not.
    repetitions : int, default 8
        How many times the patterned joints repeat their movement.
    period : float, default 1.0
        Mean length of one repetition, seconds.
    jitter : float, default 0.15
        Each repetition's length is ``period`` times a factor drawn in ``1 ± jitter``.
    amplitude : float, default 30.0
        Peak-to-peak range of every joint, degrees.
    noise : float, default 0.2
        Standard deviation of the Gaussian sensor noise, degrees.
    frame_rate : float, default 120.0
        Frames per second.
    seed : int, default 0
        Seed of ``numpy.random.default_rng``: the same seed gives the same motion.

    Returns
    -------
    Motion
        ``repetitions * period * frame_rate`` frames (about) of ``joints`` channels, no skeleton.

    Raises
    ------
    ValueError
        (a :class:`psgs.errors.ValidationError`) When ``joints``, ``repetitions`` or ``seed``
        is not an integer (bools are not), ``period`` or ``frame_rate`` is not a positive
        number, ``amplitude`` or ``noise`` a non-negative one, ``jitter`` is outside
        ``[0, 1)``, a patterned index is not a joint, or the motion would have more than
        :data:`MAX_SAMPLES` samples.

    Examples
    --------
    >>> m = synthetic_motion(4, (0, 2), seed=1)
    >>> m.channels, m.meta["patterned"]
    (('j0.rx', 'j1.rx', 'j2.rx', 'j3.rx'), ('j0.rx', 'j2.rx'))
    >>> m.frames == synthetic_motion(4, (0, 2), seed=1).frames and len(m.meta["repetition_starts"])
    8
    """
    for name, value in (("joints", joints), ("repetitions", repetitions), ("seed", seed)):
        # int(1.7), int("3") and True would each pass for a count; seed None for a seed that is
        # none (a new motion every call)
        if isinstance(value, bool) or not isinstance(value, Integral):
            raise ValidationError(f"{name} must be an integer, not {value!r}")
    for name, value in (("period", period), ("frame_rate", frame_rate)):
        check_number(value, name, positive=True)
    for name, value in (("amplitude", amplitude), ("noise", noise), ("jitter", jitter)):
        check_number(value, name)
    if joints < 1 or repetitions < 1 or seed < 0:
        raise ValidationError("joints and repetitions must be positive, seed not negative")
    if not 0 <= jitter < 1:
        raise ValidationError(f"jitter must be in [0, 1), not {jitter}")
    # checked before anything is drawn: repetitions=10**9 or period=1e9 asked for terabytes
    if max(repetitions, repetitions * period * (1 + jitter) * frame_rate * joints) > MAX_SAMPLES:
        raise ValidationError(f"joints x repetitions x period x frame_rate asks for more than "
                              f"{MAX_SAMPLES} samples")
    if isinstance(patterned, str) or not isinstance(patterned, Iterable):  # "01" was (0, 1)
        raise ValidationError(f"patterned must be joint indices, not {patterned!r}")
    patterned = tuple(patterned)
    if any(isinstance(j, bool) or not isinstance(j, Integral) or not 0 <= j < joints
           for j in patterned):
        raise ValidationError(f"patterned joints must be integers in 0..{joints - 1}, "
                              f"not {patterned!r}")
    patterned = tuple(sorted(set(int(j) for j in patterned)))
    rng = np.random.default_rng(seed)
    lengths = period * (1 + jitter * rng.uniform(-1, 1, repetitions))
    total = float(lengths.sum())
    frames = max(2, int(round(total * frame_rate)))
    t = np.arange(frames) / frame_rate
    edges = np.concatenate(([0.0], np.cumsum(lengths)))
    rep = np.clip(np.searchsorted(edges, t, side="right") - 1, 0, repetitions - 1)
    phase = (t - edges[rep]) / lengths[rep]  # 0..1 within each repetition
    values = np.empty((frames, joints))
    for j in range(joints):
        if j in patterned:
            weights = rng.uniform(0.3, 1.0, 3) * np.array([1.0, 0.5, 0.25])
            shifts = rng.uniform(0, 2 * np.pi, 3)
            curve = sum(w * np.sin(2 * np.pi * (h + 1) * phase + s)
                        for h, (w, s) in enumerate(zip(weights, shifts)))
        else:
            steps = rng.normal(size=frames)
            curve = smooth(np.cumsum(steps)[:, None], frame_rate, 0.15 * period)[:, 0]
            curve -= curve.mean()
        span = np.ptp(curve) or 1.0
        values[:, j] = amplitude * curve / span + rng.uniform(-20, 20)
    values += rng.normal(scale=noise, size=values.shape)
    names = tuple(f"j{j}.rx" for j in range(joints))
    return Motion(values, names, frame_rate, None, f"<synthetic seed={seed}>",
                  {"patterned": tuple(names[j] for j in patterned),
                   "repetition_starts": tuple(float(e) for e in edges[:-1])})
