"""Encoding a motion to bytes and back (the base layer, the residual layer, the report)."""

from __future__ import annotations

from types import MappingProxyType

import numpy as np

from psgs.errors import ValidationError

from ..motion import Motion, MotionFormatError
from . import entropy, residual, stream
# CODEC_DEFAULTS, the settings without max_error: defined with numpy-free values that the
# commands' help texts read without this module
from .._defaults import CODEC_DEFAULTS
from .knots import channel_knots, is_rotation, unwrap
from .quartic import fit_knots, reconstruct

__all__ = ["CODEC_DEFAULTS", "Compressed", "absolute_errors", "compress_with", "decompress",
           "encode_segments", "mean_errors"]

class KnotsTooLarge(ValidationError):
    """:func:`encode_segments`' refusal of a quantum too small for ``channel``'s knot values
    (more than 62 bits): rate control, which chooses the quantum, names the channel in its own
    refusal rather than its choice."""

    def __init__(self, message: str, channel: str):
        super().__init__(message)
        self.channel = channel


class Compressed(bytes):
    """The bytes of a compressed motion, with what the encoder reached.

    A :class:`bytes` (write it to a file as it is) carrying a report:

    * ``mean_error``: mean absolute error of the decoded rotation channels, in
      degrees, each difference taken modulo 360 (the decoded angles are the
      unwrapped ones); over all channels when there are no rotation channels;
    * ``mean_error_all``: the same over every channel (root translations in
      their own units);
    * ``max_error``: the bound asked for (``None`` without rate control);
    * ``settings``: the settings used (as :data:`CODEC_DEFAULTS`).

    Examples
    --------
    >>> import kinetology
    >>> walk = kinetology.synthetic_motion(3, seed=0)
    >>> data = kinetology.compress(walk)
    >>> isinstance(data, bytes), data.max_error, data.mean_error < 1.0
    (True, None, True)
    """

    def __new__(cls, data: bytes, mean_error: float, mean_error_all: float, settings,
                max_error: float | None = None):
        self = super().__new__(cls, data)
        report = (float(mean_error), float(mean_error_all), MappingProxyType(dict(settings)),
                  None if max_error is None else float(max_error))
        object.__setattr__(self, "_report", report)
        return self

    def __setattr__(self, name, value):
        raise AttributeError("a Compressed value is read-only")

    def __reduce__(self):
        m, a, s, b = self._report
        return (Compressed, (bytes(self), m, a, dict(s), b))

    @property
    def mean_error(self) -> float:
        return self._report[0]

    @property
    def mean_error_all(self) -> float:
        return self._report[1]

    @property
    def settings(self):
        return self._report[2]

    @property
    def max_error(self) -> float | None:
        return self._report[3]


def _absolute(original: np.ndarray, decoded: np.ndarray, channels) -> np.ndarray:
    """|decoded - original| per frame and channel, rotation channels modulo 360°."""
    difference = np.asarray(decoded, dtype=float) - original
    rotation = [c for c, name in enumerate(channels) if is_rotation(name)]
    if rotation:  # an angle 360° off is the same angle
        difference[:, rotation] = (difference[:, rotation] + 180.0) % 360.0 - 180.0
    return np.abs(difference)


def _errors(original: np.ndarray, decoded: np.ndarray, channels) -> tuple[float, float]:
    if original.size == 0:
        return 0.0, 0.0
    error = _absolute(original, decoded, channels)
    rotation = [c for c, name in enumerate(channels) if is_rotation(name)]
    angles = error[:, rotation] if rotation else error
    return float(angles.mean()), float(error.mean())


def absolute_errors(original: Motion, decoded: Motion) -> np.ndarray:
    """Absolute error of a decoded motion per frame and channel, frames x channels.

    Rotation channels (``rx``, ``ry``, ``rz``) are compared modulo 360°, as in
    :func:`mean_errors` (the decoder returns unwrapped angles: 181° for a file's
    -179°); other channels (root translations) are plain differences.

    Parameters
    ----------
    original, decoded : Motion
        Two motions with the same channels and frame count.

    Returns
    -------
    numpy.ndarray
        ``|decoded - original|``, frames x channels.

    Raises
    ------
    ValueError
        When the channels or frame counts differ.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Motion
    >>> a = Motion(np.array([[-179.0, 1.0]]), ("neck.rz", "root.tx"), 120)
    >>> b = Motion(np.array([[181.5, 361.0]]), ("neck.rz", "root.tx"), 120)
    >>> absolute_errors(a, b)
    array([[  0.5, 360. ]])
    """
    _check_pair(original, decoded)
    return _absolute(np.asarray(original.values, dtype=float), decoded.values,
                     original.channels)


def mean_errors(original: Motion, decoded: Motion) -> tuple[float, float]:
    """Mean absolute error ``(rotation channels, all channels)`` of a decoded motion.

    Rotation channels (``rx``, ``ry``, ``rz``) are compared modulo 360°; with
    none, the first number is over all channels.

    Parameters
    ----------
    original, decoded : Motion
        Two motions with the same channels and frame count.

    Returns
    -------
    tuple of float
        The mean over the rotation channels (degrees) and over every channel.

    Raises
    ------
    ValueError
        When the channels or frame counts differ.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Motion
    >>> a = Motion(np.array([[179.0, 1.0]]), ("neck.rz", "root.tx"), 120)
    >>> b = Motion(np.array([[-180.5, 1.5]]), ("neck.rz", "root.tx"), 120)
    >>> mean_errors(a, b)
    (0.5, 0.5)
    """
    _check_pair(original, decoded)
    return _errors(np.array(original.values), np.array(decoded.values), original.channels)


def _check_pair(original: Motion, decoded: Motion) -> None:
    """What comparing a motion with its decoded copy needs: one channel list, one length."""
    if original.channels != decoded.channels or original.frames != decoded.frames:
        raise ValidationError("the two motions differ in channels or frame count")


def _settings(params: dict) -> dict:
    unknown = set(params) - set(CODEC_DEFAULTS)
    if unknown:
        raise TypeError(f"unknown codec setting(s): {', '.join(sorted(unknown))} "
                        f"(known: {', '.join(CODEC_DEFAULTS)}, max_error)")
    p = {**CODEC_DEFAULTS, **params}
    for name, value in p.items():
        if not (isinstance(value, (int, float, np.floating, np.integer))
                and not isinstance(value, bool)  # True is no quantum of 1 degree
                and np.isfinite(value) and value >= 0):
            raise ValidationError(f"{name} must be a non-negative number, not {value!r}")
    if not p["quantum"] > 0:
        raise ValidationError(f"quantum must be positive, not {p['quantum']!r}")
    if p["residual_step"] and p["hysteresis"] < 0.5:
        raise ValidationError(f"hysteresis must be at least 0.5, not {p['hysteresis']!r}")
    return {k: float(v) for k, v in p.items()}


def encode_segments(motion: Motion, **params):
    """Per channel: knot frames, segment state codes, and quantised knot values (ints).

    Rotation channels are unwrapped first.

    Parameters
    ----------
    motion : Motion
    **params
        Settings of :data:`CODEC_DEFAULTS` (only the segmentation ones and
        ``quantum`` matter here).

    Returns
    -------
    (list of (knots, codes, values), float)
        Per channel the knot frames, the state code of each segment and the
        knot values in quanta; and the quantum in degrees.

    Raises
    ------
    TypeError, ValueError
        For unknown or out-of-range settings (a quantum too small for 62 bits).

    Examples
    --------
    >>> from kinetology.synthetic import synthetic_motion
    >>> channels, quantum = encode_segments(synthetic_motion(2, (0,), seed=1))
    >>> knots, codes, values = channels[0]
    >>> quantum, int(knots[0]), len(values) == len(codes) + 1
    (0.5, 0, True)
    """
    p = _settings(params)
    quantum = p["quantum"]
    values = unwrap(motion.values, motion.channels)
    out = []
    for c, name in enumerate(motion.channels):
        signal = values[:, c]
        if motion.frames <= 1:
            knots, codes = np.zeros(1, int), np.zeros(0, np.int8)
            knot_values = signal[:1].astype(float) if motion.frames else np.zeros(1)
        else:
            knots, codes = channel_knots(signal, motion.frame_rate, p["smoothing"],
                                         p["velocity_deadband"], p["acceleration_deadband"])
            knot_values = fit_knots(knots, codes, signal)
        steps = np.round(knot_values / quantum)
        if not np.all(np.abs(steps) < 2.0 ** 62):
            # beyond this the int64 cast (and the zigzag varints) would silently wrap; the
            # take is named, since its values, not the quantum alone, make the knots too large
            raise KnotsTooLarge(f"{motion.source}: quantum {quantum!r} is too small for "
                                f"channel {name!r}: knot values would need more than 62 bits",
                                name)
        out.append((knots, codes, steps.astype(np.int64)))
    return out, quantum


def _base_values(frames: int, channels) -> np.ndarray:
    """The decoded base curves from ``(knots, codes, quantised values, quantum)`` per channel."""
    out = np.empty((frames, len(channels)))
    for c, (knots, codes, steps, quantum) in enumerate(channels):
        if frames == 0:
            continue
        if codes.size == 0:
            out[:, c] = steps[0] * quantum
        else:
            # the stream's frames are bounded by what its size (or max_samples) allows
            out[:, c] = reconstruct(knots, codes, steps * quantum, max_frames=None)
    return out


def compress_with(motion: Motion, settings: dict, *, base=None,
                  max_error: float | None = None) -> Compressed:
    """Encode ``motion`` with ``settings`` (see :data:`CODEC_DEFAULTS`), report attached.

    ``base``: an already computed ``(channels, quantum)`` from
    :func:`encode_segments` for these settings (rate control reuses it).

    Examples
    --------
    >>> import kinetology
    >>> walk = kinetology.synthetic_motion(3, seed=0)
    >>> from kinetology.codec import CODEC_DEFAULTS
    >>> compress_with(walk, dict(CODEC_DEFAULTS)) == kinetology.compress(walk)
    True
    """
    p = _settings(settings)
    channels, quantum = base if base is not None else encode_segments(motion, **p)
    decoded = _base_values(motion.frames, [(*ch, quantum) for ch in channels])
    original = unwrap(motion.values, motion.channels)
    layer = b""
    if p["residual_step"] > 0 and motion.frames:
        try:
            levels = residual.quantise(original - decoded, p["residual_step"], p["hysteresis"])
        except ValidationError as exc:  # the step is too fine for this take's values: named
            raise ValidationError(f"{motion.source}: {exc}") from None
        decoded = decoded + levels * p["residual_step"]
        layer = residual.encode(levels)
    layout = stream.Layout(
        motion.frame_rate, motion.frames, quantum, motion.channels,
        tuple(codes for _, codes, _ in channels),
        tuple(np.diff(knots)[: codes.size] for knots, codes, _ in channels),
        tuple(int(steps[0]) for _, _, steps in channels),
        tuple(np.diff(steps)[: codes.size] for _, codes, steps in channels),
        p["residual_step"] if layer else 0.0, layer)
    angles, every = _errors(np.array(motion.values), decoded, motion.channels)
    return Compressed(stream.write(layout), angles, every, p, max_error)


def decompress(data: bytes, source: str = "<compressed motion>", *,
               max_samples: int | None = None) -> Motion:
    """Decode :func:`kinetology.codec.compress` output to a :class:`Motion`.

    Same channels, frames and frame rate as the original; rotation channels
    come back unwrapped (equal to the original modulo 360°).

    Parameters
    ----------
    data : bytes, bytearray or memoryview
        ``KIN2`` bytes (``KIN1`` from earlier versions decode too).
    source : str
        Name used in error messages.
    max_samples : int, optional
        How many samples (frames x channels) the stream may claim. By default
        what its size allows (:mod:`kinetology.codec.stream`, "What a stream
        may claim"): 2^22, or 64 a byte of a longer stream.

    Returns
    -------
    Motion

    Raises
    ------
    MotionFormatError
        When ``data`` is not a compressed motion, is damaged, or claims more
        than its size allows.
    ValueError
        (ValidationError) When ``data`` is not bytes (a ``str``, say).

    Examples
    --------
    >>> from kinetology.synthetic import synthetic_motion
    >>> from kinetology.codec import compress
    >>> m = synthetic_motion(2, (0,), seed=1)
    >>> back = decompress(compress(m))
    >>> back.frames == m.frames and back.channels == m.channels
    True
    """
    layout = stream.read(data, source, max_samples)
    count, frames = len(layout.names), layout.frames
    try:
        channels = []
        for c in range(count):
            knots = np.concatenate(([0], np.cumsum(layout.durations[c])))
            steps = layout.firsts[c] + np.concatenate(([0], np.cumsum(layout.displacements[c])))
            channels.append((knots, layout.codes[c], steps, layout.quantum))
        values = _base_values(frames, channels)
        if layout.residual_step > 0 and frames:
            try:
                levels = residual.decode(layout.residual, frames, count)
            except entropy.EntropyError as exc:
                raise MotionFormatError(str(exc), source=source) from None
            values = values + levels * layout.residual_step
    except MemoryError:
        # a header can claim any frame count; say so instead of a traceback
        raise MotionFormatError(f"{frames} frames x {count} channels do not fit in memory",
                                source=source) from None
    try:
        return Motion(values, layout.names, layout.frame_rate, None, source,
                      {"format": "kinetology-compressed"})
    except ValueError as exc:  # repeated channel names, values that overflow
        raise MotionFormatError(str(exc), source=source) from None
