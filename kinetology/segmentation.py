"""Segmenting joint angles into kinetemes: states from the signs of velocity and acceleration.

Each frame of a joint angle ``θ(t)`` gets one of four states, from the sign
of the velocity ``θ'`` and of the acceleration ``θ''``:

=====  ======  ======  ====================================================
state  ``θ'``  ``θ''`` reading
=====  ======  ======  ====================================================
``B``   ``+``   ``+``  rising, speeding up
``G``   ``+``   ``-``  rising, slowing down (ends at a maximum)
``R``   ``-``   ``-``  falling, speeding up
``Y``   ``-``   ``+``  falling, slowing down (ends at a minimum)
=====  ======  ======  ====================================================

so one swing of an oscillation reads ``B G R Y`` (cyclically). Contiguous
frames in one state form a segment.

Noise is handled twice. The signal is first smoothed (a Gaussian of
``smoothing`` seconds). Then a *dead band*: a run of frames with one sign of
``θ'`` counts only if somewhere in it ``|θ'|`` exceeds ``velocity_deadband``
(likewise ``|θ''|`` and ``acceleration_deadband``); a run that never does is
sensor noise around zero and takes the sign of the run before it. So segment
borders lie exactly at zero crossings of the smoothed derivatives (which the
reconstruction in :mod:`kinetology.codec` relies on), and wiggles smaller than
the dead band never split a segment.

Rotation channels are **unwrapped** first (``unwrap``, a period of 360°): a joint whose Euler
angle crosses ±180° jumps by ~360° in the file, which would read as a huge range and spurious
kinetemes; after unwrapping it moves continuously. Translations (``tx ty tz``) never are.

Channels whose smoothed range is below ``min_range`` degrees are *still* and
are left out of the actiongram.

Each segment also has a **displacement**: the signed change of the smoothed, unwrapped angle
over it (degrees; the channel's unit for translations), and each channel an **actuator** (the
joint it moves, :mod:`kinetology.joints`), with the joints' parents.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from numbers import Real
from types import MappingProxyType
from typing import Mapping

import numpy as np

from psgs.errors import ValidationError

# DEFAULTS, the default parameters: defined with numpy-free values that the commands' help
# texts read without this module
from ._defaults import DEFAULTS
from ._engines import select
from ._kinetemes import round_half_even, smooth_channels
from .joints import actuator_map, skeleton_parents
from .motion import (Motion, channel_names, check_motion, check_number, check_rate,
                     check_unwrap, real_array, rebuilt)

__all__ = ["STATES", "DEFAULTS", "smooth", "unwrap", "derivatives", "significant_sign",
           "channel_deadbands", "states", "Segmentation", "segments", "segment"]

_TRANSLATIONS = ("tx", "ty", "tz")

#: State letters, indexed by code: code = 2 * (θ' < 0) + ((θ' >= 0) == (θ'' < 0)).
STATES = ("B", "G", "R", "Y")


def _is_rotation(channel: str) -> bool:
    return channel.rsplit(".", 1)[-1] not in _TRANSLATIONS


def unwrap(values: np.ndarray, period: float = DEFAULTS["unwrap"]) -> np.ndarray:
    """Remove jumps of more than half a ``period`` between frames (along axis 0).

    Parameters
    ----------
    values : array_like
        Angles, frames along axis 0 (degrees for the default period).
    period : float
        The period (360 for degrees); ``period <= 0`` returns a copy unchanged.

    Returns
    -------
    numpy.ndarray
        The angles with every jump of more than ``period / 2`` removed.

    Raises
    ------
    ValueError
        (ValidationError) Values that are not real numbers or have no time axis; a NaN period.

    Examples
    --------
    >>> unwrap(np.array([170.0, 179.0, -178.0, -170.0]))
    array([170., 179., 182., 190.])
    """
    values = real_array(values, "values")
    if values.ndim == 0:
        raise ValidationError("values must have a time axis (axis 0), not be one number")
    if isinstance(period, bool) or not isinstance(period, Real) or np.isnan(period):
        raise ValidationError(f"period must be a number, not {period!r}")  # NaN: all NaN
    if period <= 0 or values.shape[0] < 2:
        return values.copy()
    return np.unwrap(values, period=period, axis=0)


_unwrap = unwrap  # for functions whose parameter of that name shadows it


def smooth(values: np.ndarray, frame_rate: float, sigma: float) -> np.ndarray:
    """Gaussian smoothing along time (axis 0), ``sigma`` in seconds.

    The edges are padded by odd reflection (``2 x[0] - x[k]``), which keeps the
    slope at the ends instead of inventing a turning point there. The kernel reaches three
    sigma each side; up to 8 frames each side it is summed directly, longer kernels (120 fps:
    18 frames) as blocks of a banded matrix product (the same sums, rounded in the last bits
    only; see :mod:`kinetology._kinetemes`).

    ``sigma <= 0`` returns a copy unchanged.

    Parameters
    ----------
    values : array_like
        Frames along axis 0 (any further axes are channels).
    frame_rate : float
        Frames per second.
    sigma : float
        The Gaussian's standard deviation, seconds.

    Returns
    -------
    numpy.ndarray
        The smoothed values, the shape of ``values``.

    Examples
    --------
    >>> import numpy as np
    >>> spike = np.array([0.0, 0.0, 10.0, 0.0, 0.0])
    >>> smoothed = smooth(spike, 1.0, 1.0)
    >>> bool(smoothed.max() < 10.0), round(float(smoothed.sum()), 6) <= 10.0
    (True, True)
    >>> smooth(spike, 1.0, 0.0).tolist() == spike.tolist()
    True
    """
    values = np.asarray(values, dtype=float)
    if sigma * frame_rate <= 0 or values.shape[0] < 2:
        return values.copy()
    columns = values.reshape(values.shape[0], -1)
    return np.ascontiguousarray(smooth_channels(columns, frame_rate, sigma).T).reshape(values.shape)


def derivatives(values: np.ndarray, frame_rate: float) -> tuple[np.ndarray, np.ndarray]:
    """Velocity and acceleration (per second) by central differences along axis 0.

    Examples
    --------
    >>> import numpy as np
    >>> velocity, acceleration = derivatives(np.array([0.0, 1.0, 4.0, 9.0, 16.0]), 1.0)
    >>> velocity[1:-1], float(acceleration[2])
    (array([2., 4., 6.]), 2.0)
    """
    if values.shape[0] < 3:
        zero = np.zeros_like(values, dtype=float)
        return zero, zero.copy()
    velocity = np.gradient(values, axis=0) * frame_rate
    acceleration = np.gradient(velocity, axis=0) * frame_rate
    return velocity, acceleration


def significant_sign(signal: np.ndarray, deadband: float) -> np.ndarray:
    """Sign (+1/-1) per sample of a 1-D signal, runs that stay inside the dead band absorbed.

    A run of one raw sign counts when its largest ``|signal|`` exceeds
    ``deadband``; other runs take the sign of the previous counting run (the
    first counting run's sign at the start). A signal with no counting run is
    +1 throughout.

    Examples
    --------
    >>> import numpy as np
    >>> significant_sign(np.array([5.0, 0.5, -0.5, 0.5, -5.0]), 1.0)
    array([ 1,  1,  1,  1, -1]...)
    """
    signal = np.asarray(signal, dtype=float)
    if signal.size == 0:
        return np.zeros(0, dtype=np.int8)
    raw = signal >= 0
    starts = np.concatenate(([0], np.flatnonzero(raw[1:] != raw[:-1]) + 1))
    lengths = np.diff(np.append(starts, signal.size))
    peak = np.maximum.reduceat(np.abs(signal), starts)
    counting = peak > deadband
    if not counting.any():
        return np.ones(signal.size, dtype=np.int8)
    run_sign = np.where(raw[starts], 1, -1)
    # forward-fill the sign of the last counting run over the runs that do not count
    last = np.where(counting, np.arange(starts.size), -1)
    last = np.maximum.accumulate(last)
    last[last < 0] = np.flatnonzero(counting)[0]
    return np.repeat(run_sign[last], lengths).astype(np.int8)


_PERCENTILE_SAMPLES = 8192


def channel_deadbands(signals: np.ndarray, absolute: float, relative: float) -> np.ndarray:
    """Per column: ``max(absolute, relative * the 95th percentile of |signal|)``.

    A dead band relative to how fast the channel itself moves holds for slow and brisk
    tempos alike (slowing a motion by ``k`` divides its velocities by ``k`` and its
    accelerations by ``k²``, a fixed dead band does not follow); the absolute floor keeps a
    nearly still channel from turning its noise into kinetemes.

    Parameters
    ----------
    signals : numpy.ndarray
        ``frames x channels`` velocities (or accelerations).
    absolute : float
        The floor of every band.
    relative : float
        Share of the channel's 95th-percentile ``|signal|``; 0 gives the floor everywhere.

    Returns
    -------
    numpy.ndarray
        One band per channel.

    Examples
    --------
    >>> channel_deadbands(np.array([[0.0, 1.0], [100.0, 2.0]]), 2.0, 0.1).tolist()
    [9.5, 2.0]
    """
    if relative <= 0 or signals.shape[0] == 0:
        return np.full(signals.shape[1], float(absolute))
    # the percentile of every k-th frame (at most ~8,000 a channel): the same to a fraction of
    # a percent on real motion, and a tenth of the cost on long takes
    step = max(1, signals.shape[0] // _PERCENTILE_SAMPLES)
    scale = np.percentile(np.abs(signals[::step]), 95, axis=0)
    return np.maximum(absolute, relative * scale)


def states(values: np.ndarray, frame_rate: float, *, smoothing: float = DEFAULTS["smoothing"],
           velocity_deadband: float = DEFAULTS["velocity_deadband"],
           acceleration_deadband: float = DEFAULTS["acceleration_deadband"],
           relative_deadband: float = DEFAULTS["relative_deadband"],
           unwrap: float = DEFAULTS["unwrap"], engine: str = "auto") -> np.ndarray:
    """State code (index into :data:`STATES`) of every frame, ``frames x channels``.

    ``values`` is ``frames x channels`` (or 1-D, one channel) of angles in
    degrees, unwrapped with period ``unwrap`` (0: not) before smoothing. A
    channel's dead bands are ``max(velocity_deadband, relative_deadband * v95)``
    and likewise for the acceleration, ``v95`` the 95th percentile of the
    channel's own ``|θ'|`` (``|θ''|``).

    Parameters
    ----------
    values : numpy.ndarray
        Frames x channels (or one channel, 1-D), degrees.
    frame_rate : float
        Frames per second.
    smoothing : float, default DEFAULTS["smoothing"]
        Gaussian sigma, seconds.
    velocity_deadband : float, default DEFAULTS["velocity_deadband"]
        Degrees per second.
    acceleration_deadband : float, default DEFAULTS["acceleration_deadband"]
        Degrees per second squared.
    relative_deadband : float, default DEFAULTS["relative_deadband"]
        A channel's dead bands are at least this share of its own 95th-percentile speed and
        acceleration.
    unwrap : float, default DEFAULTS["unwrap"]
        Period of the angles, degrees, undone before smoothing; 0: none, else >= MIN_UNWRAP.
    engine : {"auto", "numpy", "numba"}, default "auto"
        The implementation, as for :func:`segments` (the same codes with each).

    Returns
    -------
    numpy.ndarray of int8
        The state code of every frame, the shape of ``values``.

    Raises
    ------
    ValueError
        (ValidationError) Values that are not finite real numbers, a frame rate that is not a
        positive number, a parameter that is not a non-negative one.

    Examples
    --------
    >>> import numpy as np
    >>> t = np.arange(120) / 120
    >>> codes = states(30 * np.sin(2 * np.pi * t), 120.0)
    >>> "".join(STATES[c] for c in codes[[5, 35, 65, 95]])
    'GRYB'
    """
    check_number(frame_rate, "frame_rate", positive=True)
    _check(dict(smoothing=smoothing, velocity_deadband=velocity_deadband, unwrap=unwrap,
                acceleration_deadband=acceleration_deadband, relative_deadband=relative_deadband))
    values = real_array(values, "values")
    if not np.isfinite(values).all():  # a NaN would be read as a still frame, without a word
        raise ValidationError("values must be finite numbers")
    one_channel = values.ndim == 1
    if one_channel:
        values = values[:, None]
    check_rate(values, frame_rate)  # as segments() does: unwrapping 1e308 overflowed first
    values = _unwrap(values, unwrap)
    out = np.empty(values.shape, dtype=np.int8)
    use = select(engine, values.size)
    if values.shape[0]:
        smoothed = use.smooth_channels(values, frame_rate, smoothing)  # what is differenced
        check_rate(smoothed, frame_rate)
        borders, codes, _ = use.segment_columns(smoothed, frame_rate, velocity_deadband,
                                                acceleration_deadband, relative_deadband)
        for c, (ends, code) in enumerate(zip(borders, codes)):
            out[:, c] = np.repeat(code, np.diff(ends))
    return out[:, 0] if one_channel else out


@dataclass(frozen=True, eq=False)
class Segmentation:
    """The segments of every channel of a motion.

    For channel ``c``: ``borders[c]`` holds the first frame of each segment
    followed by the frame count, ``codes[c]`` the state code of each segment.
    ``still`` names the channels left out because they do not move.
    ``displacements[c]`` holds each segment's signed change of the smoothed,
    unwrapped angle; ``actuators`` maps every kept channel to its joint and
    ``skeleton`` every such joint to its parent joint (None for a root; empty
    when the file gives no hierarchy, see :mod:`kinetology.joints`).

    Attributes
    ----------
    channels : tuple of str
        The segmented (moving) channels.
    frame_rate : float
        Frames per second.
    frames : int
        Number of frames.
    borders : tuple of numpy.ndarray
        Per channel, the first frame of each segment, then the frame count.
    codes : tuple of numpy.ndarray
        Per channel, the state code of each segment.
    still : tuple of str, default ()
        Channels left out because they do not move.
    displacements : tuple of numpy.ndarray, default ()
        Per channel, each segment's signed change of the smoothed angle.
    actuators : mapping of str to str, optional
        Each kept channel's joint.
    skeleton : mapping of str to str or None, optional
        Each such joint's parent joint, None for a root.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Motion
    >>> t = np.arange(240) / 120
    >>> values = np.column_stack([30 * np.sin(2 * np.pi * t), 0 * t])   # a moving knee, a still hip
    >>> wave = Motion(values, ("knee.rx", "hip.rx"), 120)
    >>> found = segments(wave)
    >>> found.segment_count, int(found.borders[0][0]), int(found.borders[0][-1])
    (8, 0, 240)
    >>> found.to_actiongram().names
    ('knee.rx',)
    """

    channels: tuple[str, ...]
    frame_rate: float
    frames: int
    borders: tuple[np.ndarray, ...]
    codes: tuple[np.ndarray, ...]
    still: tuple[str, ...] = ()
    displacements: tuple[np.ndarray, ...] = ()
    actuators: Mapping[str, str] = field(default_factory=dict)
    skeleton: Mapping[str, str | None] = field(default_factory=dict)

    def __post_init__(self) -> None:
        for name in ("actuators", "skeleton"):  # read-only: the mappings given are copied
            object.__setattr__(self, name, MappingProxyType(dict(getattr(self, name))))

    __reduce__ = rebuilt  # pickle and copy.deepcopy cannot take a mappingproxy

    def symbols(self, c: int) -> tuple[str, ...]:
        """State letters of channel ``c``'s segments, in time order."""
        return tuple(STATES[k] for k in self.codes[c])

    def durations(self, c: int) -> np.ndarray:
        """Segment durations of channel ``c`` in seconds."""
        return np.diff(self.borders[c]) / self.frame_rate

    def joint_channels(self) -> dict[str, tuple[str, ...]]:
        """Joint -> its kept channels, joints in the order of their first channel."""
        out: dict[str, list[str]] = {}
        for name in self.channels:
            out.setdefault(self.actuators.get(name, name.split(".", 1)[0]), []).append(name)
        return {k: tuple(v) for k, v in out.items()}

    @property
    def segment_count(self) -> int:
        """Segments over all channels."""
        return sum(len(k) for k in self.codes)

    def to_actiongram(self):
        """The segments as a :class:`psgs.Actiongram` (times in seconds)."""
        from psgs.actiongram import Actiongram

        # rounded to the microsecond so the text form stays readable; above 10 kHz to finer
        # steps, at least 1/100 of a frame (at 2 MHz microseconds rounded frames to 0)
        digits = 6 + max(0, int(np.ceil(np.log10(self.frame_rate))) - 4)
        # every channel rounded at once (split where each channel's rows end)
        spans = [np.diff(b) for b in self.borders]
        durations = dict(zip(self.channels, _rounded(spans, digits, self.frame_rate)))
        # displacements to 1/1000 degree: finer than any sensor, and short in the text form
        moves = dict(zip(self.channels, _rounded(self.displacements, 3))) \
            if self.displacements else None
        return Actiongram.from_codes(dict(zip(self.channels, self.codes)), STATES, durations,
                                     displacements=moves, actuators=dict(self.actuators) or None,
                                     skeleton=dict(self.skeleton) or None)


def _rounded(rows, digits: int, divisor: float = 1.0) -> list[np.ndarray]:
    """``[round(float(x) / divisor, digits) ...]`` of every row, as arrays."""
    if not len(rows):
        return []
    ends = np.cumsum([len(r) for r in rows]).tolist()
    flat = round_half_even(np.concatenate(rows) / divisor, digits)
    return [flat[a:b] for a, b in zip([0] + ends[:-1], ends)]


def _check(params: dict) -> dict:
    unknown = set(params) - set(DEFAULTS)
    if unknown:
        raise TypeError(f"unknown segmentation parameter(s): {', '.join(sorted(unknown))} "
                        f"(known: {', '.join(DEFAULTS)})")
    merged = {**DEFAULTS, **params}
    for name, value in merged.items():  # unwrap: a period, 0 or at least MIN_UNWRAP degrees
        (check_unwrap if name == "unwrap" else check_number)(value, name)
    return merged


def segments(motion: Motion, channels=None, *, engine: str = "auto", **params) -> Segmentation:
    """Segment ``channels`` of ``motion`` (default: every angle channel, not ``t*``).

    Parameters (defaults in :data:`DEFAULTS`): ``smoothing`` (Gaussian sigma in seconds;
    larger merges quick wiggles), ``velocity_deadband`` (deg/s) and ``acceleration_deadband``
    (deg/s²) (larger: fewer, longer segments), ``min_range`` (deg; channels whose smoothed range
    is smaller are still and left out; 0 keeps every channel), ``unwrap`` (period in degrees of
    the rotation channels, unwrapped before smoothing; 0 turns it off, else at least 1).

    Parameters
    ----------
    motion : Motion
        The motion.
    channels : sequence of str, optional
        The channels to segment (default: every angle channel, not the ``t*`` translations).
    engine : {"auto", "numpy", "numba"}, default "auto"
        Which implementation computes the segments; the output is the same to the bit.
        ``"numba"`` runs one compiled loop per channel (channels of a large take in threads,
        one per core; 1.6 to 5 times as fast as ``"numpy"``'s array passes, docs/kinetology.md
        "Speed"; needs ``pip install 'psgs[fast]'``), ``"numpy"`` needs nothing more, ``"auto"``
        takes numba when it imports.
    **params
        ``smoothing``, ``velocity_deadband``, ``acceleration_deadband``, ``min_range``
        (defaults in :data:`DEFAULTS`).

    Returns
    -------
    Segmentation
        The moving channels' segments; ``still`` names the others.

    Raises
    ------
    KeyError
        Naming a channel the motion does not have.
    TypeError
        For an unknown parameter.
    ValueError
        For a parameter that is negative or not finite, or an unknown ``engine``.
    ImportError
        For ``engine="numba"`` when numba does not import.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Motion
    >>> t = np.arange(240) / 120
    >>> values = np.column_stack([30 * np.sin(2 * np.pi * t), 0 * t])   # a moving knee, a still hip
    >>> wave = Motion(values, ("knee.rx", "hip.rx"), 120)
    >>> found = segments(wave)
    >>> found.channels, found.still
    (('knee.rx',), ('hip.rx',))
    >>> found.symbols(0)[:4], float(found.durations(0).sum())
    (('G', 'R', 'Y', 'B'), 2.0)
    >>> segments(wave, engine="numpy").borders[0].tolist() == found.borders[0].tolist()
    True
    >>> segments(wave, engine="fortran")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: engine must be one of 'auto', 'numpy', 'numba', not 'fortran'
    """
    check_motion(motion)
    if channels is not None:  # one string would be split into one-letter names
        channels = channel_names(channels)
    use = select(engine, motion.values.size)
    p = _check(params)
    names, smoothed = _smoothed(motion, channels, p, use)
    check_rate(smoothed, motion.frame_rate, motion.source)
    moving = (use.row_ranges(smoothed) >= p["min_range"]) if motion.frames else \
        np.zeros(len(names), bool)
    return _segmentation(motion, names, smoothed, moving, p, use)


def _smoothed(motion: Motion, channels, p: dict, use) -> tuple[list[str], np.ndarray]:
    """The channels to segment and their unwrapped, smoothed values, channels x frames."""
    if channels is None:  # the rotations, found in one pass (short takes: this is per take)
        rotation = [_is_rotation(c) for c in motion.channels]
        columns = [i for i, r in enumerate(rotation) if r]
        channels = [motion.channels[i] for i in columns]
        rotation = np.ones(len(channels), dtype=bool)
    else:
        channels = list(channels)
        columns = [motion.index(name) for name in channels]  # KeyError naming a missing one
        rotation = np.array([_is_rotation(c) for c in channels], dtype=bool)
    if columns == list(range(motion.values.shape[1])):
        values = motion.values  # every channel in order: no copy
    else:
        # take, not [:, columns]: frames-major, as the compiled engine reads it fastest
        values = motion.values.take(columns, axis=1) if channels else \
            np.zeros((motion.frames, 0))
    check_rate(values, motion.frame_rate, motion.source)  # unwrapping 1e308 overflowed first
    if p["unwrap"] > 0 and rotation.any() and motion.frames > 1:
        # only the columns that jump by more than half a turn somewhere need it
        jumps = rotation & (use.largest_step(values) > p["unwrap"] / 2)
        if jumps.any():
            values = values.copy()
            values[:, jumps] = unwrap(values[:, jumps], p["unwrap"])
    return channels, use.smooth_channels(values, motion.frame_rate, p["smoothing"])


def _segmentation(motion: Motion, channels: list[str], smoothed: np.ndarray,
                  moving: np.ndarray, p: dict, use) -> Segmentation:
    """The segments of the ``moving`` rows of ``smoothed`` (channels x frames)."""
    kept_smooth = smoothed if moving.all() else smoothed[moving]
    borders, codes, moves = use.segment_columns(kept_smooth, motion.frame_rate,
                                                p["velocity_deadband"], p["acceleration_deadband"],
                                                p["relative_deadband"])
    kept = tuple(name for name, m in zip(channels, moving) if m)
    still = tuple(name for name, m in zip(channels, moving) if not m)
    owners = actuator_map(motion, kept)
    return Segmentation(kept, motion.frame_rate, motion.frames, tuple(borders), tuple(codes),
                        still, tuple(moves), owners,
                        skeleton_parents(motion, dict.fromkeys(owners.values())))


def segment(motion: Motion, channels=None, *, engine: str = "auto", **params):
    """Segment a motion into a :class:`psgs.Actiongram` (one string per moving channel).

    Symbols are the states ``B G R Y`` (see the module docstring), durations
    in seconds. ``channels`` and ``params`` as in :func:`segments`.

    Parameters
    ----------
    motion : Motion
        The motion.
    channels : sequence of str, optional
        The channels to segment (default: every angle channel).
    engine : {"auto", "numpy", "numba"}, default "auto"
        The implementation, see :func:`segments` (the same actiongram with each).
    **params
        Segmentation parameters (:data:`DEFAULTS`), see :func:`segments`.

    Returns
    -------
    psgs.Actiongram
        One string per moving channel; symbols ``B G R Y``, durations in seconds.

    Raises
    ------
    KeyError
        Naming a channel the motion does not have.
    TypeError
        For an unknown parameter.
    ValueError
        For a parameter that is negative or not finite, or an unknown ``engine``.
    ImportError
        For ``engine="numba"`` when numba does not import.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Motion
    >>> t = np.arange(240) / 120
    >>> wave = Motion(30 * np.sin(2 * np.pi * t)[:, None], ("knee.rx",), 120)
    >>> segment(wave).string("knee.rx")
    ('G', 'R', 'Y', 'B', 'G', 'R', 'Y', 'B')
    """
    return segments(motion, channels, engine=engine, **params).to_actiongram()
