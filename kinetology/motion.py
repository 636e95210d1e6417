"""The :class:`Motion` value every reader returns, and the error bad files raise.

A motion is a frames x channels array of joint angles in degrees (root
translations, where a file has them, in the file's length unit), one name per
channel written ``joint.axis`` with ``axis`` one of ``tx ty tz rx ry rz``, a
frame rate, and optionally the :class:`Skeleton` that forward kinematics
needs. The array is read-only: a motion never changes after it is built.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, fields
from numbers import Integral, Real
from pathlib import Path
from types import MappingProxyType

import numpy as np

from psgs.errors import FormatError, NotFound, ValidationError

# MIN_UNWRAP, the shortest unwrap period: defined with numpy-free values that the commands'
# help texts read without this module
from ._defaults import MIN_UNWRAP
from ._values_frozen import frozen_meta, read_only, thawed

__all__ = ["MotionFormatError", "Joint", "Skeleton", "Motion", "AXES", "FRAME_RATE_RANGE",
           "check_number", "MIN_UNWRAP", "check_unwrap", "real_array", "as_path", "shown",
           "counted", "channel_names", "check_motion", "rebuilt"]

#: Channel axes, in the order a joint's channels are listed.
AXES = ("tx", "ty", "tz", "rx", "ry", "rz")
#: The frame rates (frames per second, bounds included) a motion file may have: a BVH file's
#: ``Frame Time`` from 0.0001 s to 10 s, an AMC file's ``frame_rate=``. Beyond high-speed
#: capture (10,000 fps) velocities grow with the rate and accelerations with its square until
#: they overflow (``Frame Time: 1e-300``); below 0.1 fps no capture or key-framing goes.
FRAME_RATE_RANGE = (0.1, 10_000.0)
_MESSAGE_LIMIT = 200  # characters of an error message, so that it stays one readable line


class MotionFormatError(FormatError):
    """A motion file (or encoded motion) that could not be read.

    ``str(error)`` is one line, ``file:line:col: message`` (line and column
    left out when they do not apply); the parts are kept as attributes.
    A :class:`psgs.FormatError`, so one ``except psgs.PSGSError`` catches every
    error of the distribution, and a ``ValueError``, so code that catches bad
    values catches it too.

    Parameters
    ----------
    message : str
        What is wrong, in words (cut to 200 characters: garbage input stays one line).
    source : str, default "<data>"
        The file (or a description of the data).
    line, column : int, optional
        Where in the file, counting from 1.

    Examples
    --------
    >>> error = MotionFormatError("expected 6 numbers, found 5", source="walk.amc", line=12,
    ...                           column=1)
    >>> str(error)
    'walk.amc:12:1: expected 6 numbers, found 5'
    >>> error.line, isinstance(error, ValueError)
    (12, True)
    """

    def __init__(self, message: str, *, source: str = "<data>", line: int | None = None,
                 column: int | None = None) -> None:
        if len(message) > _MESSAGE_LIMIT:  # garbage input (a binary file) quoted in full
            message = message[:_MESSAGE_LIMIT - 4] + " ..."
        super().__init__(message, source=str(source), line=line, column=column)


@dataclass(frozen=True, slots=True)
class Joint:
    """One joint of a skeleton, in the BVH convention.

    The joint sits at ``offset`` from its parent, expressed in the parent's
    frame; its local rotation is ``pre @ R(channels) @ pre.T`` where ``R`` is
    the product of the elementary rotations in ``rotation_order`` (``"ZYX"``
    means ``Rz @ Ry @ Rx``: x is applied to a vector first) and ``pre`` is the
    fixed rotation given by ``axis`` (degrees, also in ``rotation_order``;
    zero for BVH, the ASF ``axis`` for ASF bones). ``channels`` names the
    motion columns that move it (``joint.tx`` .. ``joint.rz``); an end site
    has none.

    Parameters
    ----------
    name : str
        The joint's name.
    parent : int or None
        Index of the parent joint in the skeleton; None for the root.
    offset : tuple of float
        Position relative to the parent, in the parent's frame (file units).
    channels : tuple of str, default ()
        The motion channels that move this joint.
    rotation_order : str, default "ZYX"
        Order of the elementary rotations in the product.
    axis : tuple of float, default (0, 0, 0)
        The fixed pre-rotation (degrees; ASF ``axis``).
    end_site : bool, default False
        Whether this is a BVH ``End Site`` (or an ASF bone's end).

    Examples
    --------
    >>> knee = Joint("knee", 0, (0.0, -10.0, 0.0), ("knee.rx",))
    >>> knee.rotation_order, knee.end_site
    ('ZYX', False)
    """

    name: str
    parent: int | None
    offset: tuple[float, float, float]
    channels: tuple[str, ...] = ()
    rotation_order: str = "ZYX"
    axis: tuple[float, float, float] = (0.0, 0.0, 0.0)
    end_site: bool = False

    def __post_init__(self) -> None:
        # a list or an array given would stay changeable inside the frozen joint
        for name in ("offset", "channels", "axis"):
            given = getattr(self, name)
            if not isinstance(given, (tuple, str)) and isinstance(given, Iterable):
                object.__setattr__(self, name, tuple(given))


@dataclass(frozen=True, slots=True)
class Skeleton:
    """Joints in depth-first order (a parent always comes before its children).

    Parameters
    ----------
    joints : tuple of Joint
        Depth-first: every joint's parent index is smaller than its own.
    length_unit : str, default "file units"
        What the offsets are measured in (said in plots and docs).

    Raises
    ------
    ValueError
        When a joint's parent does not come before it.

    Examples
    --------
    >>> leg = Skeleton((Joint("hip", None, (0, 0, 0)), Joint("knee", 0, (0, -10, 0))))
    >>> leg.names, leg.index("knee")
    (('hip', 'knee'), 1)
    >>> Skeleton((Joint("knee", 1, (0, -10, 0)), Joint("hip", None, (0, 0, 0))))
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: joint 'knee' has parent 1, which does not come before it
    """

    joints: tuple[Joint, ...]
    length_unit: str = "file units"

    def __post_init__(self) -> None:
        if not isinstance(self.joints, tuple) and isinstance(self.joints, Iterable):
            object.__setattr__(self, "joints", tuple(self.joints))  # a list would stay changeable
        for index, joint in enumerate(self.joints):
            if joint.parent is not None and not 0 <= joint.parent < index:
                raise ValidationError(f"joint {joint.name!r} has parent {joint.parent}, which does "
                                 f"not come before it")

    @property
    def names(self) -> tuple[str, ...]:
        """Joint names in skeleton order."""
        return tuple(j.name for j in self.joints)

    def index(self, name: str) -> int:
        """Position of the joint called ``name`` (``KeyError`` listing the joints if none)."""
        for i, joint in enumerate(self.joints):
            if joint.name == name:
                return i
        raise NotFound(f"no joint named {name!r} (joints: {', '.join(self.names)})")


class _Owned:
    """A new float array handed to :class:`Motion` to keep, not copy: only for an array that
    nothing else holds (a reader's, just filled), since the motion then makes it read-only in
    place. Anything else (a view of another array, another type) is copied as any value is.
    Private: a caller that kept the array (or a view of it) could change the motion through it
    (the array owning its memory can be made writeable again), so only the readers, which hold
    their array nowhere else, hand one over. It pickles as its array, checked again when read
    back (a copied array is no longer one nothing else holds).

    Parameters
    ----------
    array : numpy.ndarray
        Frames x channels.

    Examples
    --------
    >>> values = np.zeros((2, 1))
    >>> m = Motion(_Owned(values), ("knee.rx",), 120.0)
    >>> np.shares_memory(m.values, values), values.flags.writeable
    (True, False)
    >>> np.shares_memory(Motion(values, ("knee.rx",), 120.0).values, values)
    False
    """

    __slots__ = ("array",)

    def __init__(self, array) -> None:
        owned = (type(array) is np.ndarray and array.dtype == np.float64
                 and array.base is None and array.flags.c_contiguous)
        self.array = array if owned else real_array(array)

    def __reduce__(self) -> tuple:
        return _Owned, (self.array,)


def rebuilt(value) -> tuple:
    """The ``__reduce__`` of a frozen dataclass keeping read-only mappings (an ASF skeleton's
    ``dofs``, a segmentation's ``actuators``), which :mod:`pickle` and :func:`copy.deepcopy`
    cannot take: its class and its constructor's arguments, each mappingproxy field as a
    ``dict`` (a mappingproxy inside one is not thawed: a motion's ``meta``, which may hold
    some, has its own). The constructor checks them and makes them read-only again.

    Examples
    --------
    >>> import pickle
    >>> from kinetology.asf import AsfSkeleton
    >>> bones = AsfSkeleton({"root": ("tx",)}, Skeleton((Joint("root", None, (0, 0, 0)),)), 1.0)
    >>> rebuilt(bones)[1][0], pickle.loads(pickle.dumps(bones)) == bones
    ({'root': ('tx',)}, True)
    """
    return type(value), tuple(dict(v) if isinstance(v, MappingProxyType) else v
                              for v in (getattr(value, f.name) for f in fields(value) if f.init))


@dataclass(frozen=True, eq=False)
class Motion:
    """Joint-angle motion: ``values[frame, channel]`` in degrees, read-only.

    Frozen: ``values`` is read-only (a copy of what is given; a reader's own array, uncopied),
    and neither it nor its ``base`` lets numpy make it writeable again (``setflags`` refuses);
    ``meta`` is a read-only mapping whose values are frozen too (lists become tuples, dicts
    read-only mappings, arrays read-only copies). A motion pickles and copies to an equal one,
    as frozen.

    Parameters
    ----------
    values : array_like
        Frames x channels, finite numbers (degrees for rotations, file units for
        translations).
    channels : tuple of str
        Distinct channel names, ``joint.axis`` with axis one of :data:`AXES`.
    frame_rate : float
        Frames per second, positive.
    skeleton : Skeleton, optional
        The joints the channels move (for forward kinematics); None when unknown.
    source : str, default "<motion>"
        Where the motion came from (named in errors and in ``repr``).
    meta : dict, optional
        Anything else: the file format, the truth of a synthetic motion, ... Kept frozen at
        every depth: a mapping in it becomes a read-only mapping, a list a tuple, a set a
        frozenset, an array a read-only copy; other values are kept as given.

    Raises
    ------
    ValueError
        (a :class:`psgs.errors.ValidationError`) When ``values`` is not a two-dimensional array
        of real numbers (complex, bool, strings and objects are refused), its columns and
        ``channels`` disagree, names repeat or are not strings, a value is not finite, the
        frame rate is not a positive number, ``skeleton``, ``source`` or ``meta`` is not of
        its type, or ``meta`` holds itself.

    Examples
    --------
    >>> m = Motion(np.zeros((3, 2)), ("knee.rx", "hip.rx"), 120.0)
    >>> m.frames, m.duration, m.column("hip.rx").shape
    (3, 0.025, (3,))
    >>> m
    Motion('<motion>', 3 frames x 2 channels at 120 fps)
    >>> Motion(np.zeros((3, 2)), ("knee.rx",), 120.0)
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: 1 channel names for 2 columns
    >>> cut = Motion(np.zeros((3, 1)), ("knee.rx",), 120.0, meta={"cut": [0.5, 2.0]})
    >>> cut.meta["cut"]
    (0.5, 2.0)
    >>> cut.values.setflags(write=True)
    Traceback (most recent call last):
    ...
    ValueError: cannot set WRITEABLE flag to True of this array
    """

    values: np.ndarray
    channels: tuple[str, ...]
    frame_rate: float
    skeleton: Skeleton | None = None
    source: str = "<motion>"
    meta: dict = field(default_factory=dict)  # read-only after construction (format, truth)

    def __post_init__(self) -> None:
        given = self.values
        # an array a reader has just made is kept (made read-only) rather than copied: the copy
        # took the values' size again, four times the text of a file of one-digit numbers;
        # whatever else is given is copied, so that no holder of it can change the motion
        values = given.array if isinstance(given, _Owned) else real_array(given)
        if values.ndim != 2:
            raise ValidationError(f"motion values must be frames x channels, got shape {values.shape}")
        channels = channel_names(self.channels)
        if not all(isinstance(name, str) for name in channels):
            bad = next(name for name in channels if not isinstance(name, str))
            raise ValidationError(f"channel names must be strings, not {bad!r}")
        if values.shape[1] != len(channels):
            raise ValidationError(f"{len(channels)} channel names for {values.shape[1]} columns")
        if len(set(channels)) != len(channels):
            raise ValidationError("channel names must be distinct")
        if not np.isfinite(values).all():
            frame, column = np.argwhere(~np.isfinite(values))[0]
            raise ValidationError(f"value at frame {frame}, channel {channels[column]!r} is not finite")
        # a string or a bool is no rate: float("30") and float(True) would take either
        if isinstance(self.frame_rate, bool) or not isinstance(self.frame_rate, Real):
            raise ValidationError(f"frame rate must be a number, not {self.frame_rate!r}")
        rate = float(self.frame_rate)
        if not np.isfinite(rate) or rate <= 0:
            raise ValidationError(f"frame rate must be positive, not {self.frame_rate!r}")
        if self.skeleton is not None and not isinstance(self.skeleton, Skeleton):
            raise ValidationError(f"skeleton must be a Skeleton or None, not "
                                  f"{type(self.skeleton).__name__}")
        if not isinstance(self.source, (str, os.PathLike)):
            raise ValidationError(f"source must be a string, not {type(self.source).__name__}")
        meta = {} if self.meta is None else self.meta
        if not isinstance(meta, Mapping):
            raise ValidationError(f"meta must be a mapping, not {type(meta).__name__}")
        frozen = frozen_meta(meta)
        # the array owning the memory could be made writeable again by anyone reaching it
        # through values.base: the motion hands out an array whose base is a holder of it
        # instead, which numpy cannot make writeable (still the reader's memory, uncopied)
        object.__setattr__(self, "values", read_only(values))
        object.__setattr__(self, "channels", channels)
        object.__setattr__(self, "frame_rate", rate)
        object.__setattr__(self, "source", os.fspath(self.source))
        object.__setattr__(self, "meta", frozen)

    @property
    def frames(self) -> int:
        """Number of frames (rows of ``values``)."""
        return self.values.shape[0]

    @property
    def duration(self) -> float:
        """Seconds covered by the frames (``frames / frame_rate``)."""
        return self.frames / self.frame_rate

    def index(self, channel: str) -> int:
        """Column of ``channel``; ``KeyError`` naming it, the closest names and every channel
        of the motion when there is none (a misspelt name is found by reading the message)."""
        columns = self.__dict__.get("_columns")
        if columns is None:  # looked up once: tuple.index per channel made select quadratic
            columns = {name: k for k, name in enumerate(self.channels)}
            object.__setattr__(self, "_columns", columns)
        try:
            return columns[channel]
        except (KeyError, TypeError):  # TypeError: an unhashable name is no channel either
            import difflib
            close = difflib.get_close_matches(str(channel), self.channels, n=3)
            hint = f" (did you mean {', '.join(close)}?)" if close else ""
            raise NotFound(f"no channel {channel!r} in {self.source}{hint}; its "
                           f"{counted(len(self.channels), 'channel')}: "
                           f"{', '.join(self.channels)}") from None

    def column(self, channel: str) -> np.ndarray:
        """The read-only column of one channel."""
        return self.values[:, self.index(channel)]

    def select(self, channels) -> "Motion":
        """A motion with only ``channels`` (in that order) and no skeleton."""
        channels = channel_names(channels)
        columns = [self.index(c) for c in channels]
        # indexing by a list of columns makes a new array, which nothing else holds
        return Motion(_Owned(self.values[:, columns]), tuple(channels), self.frame_rate, None,
                      self.source, self.meta)

    def rotation_channels(self) -> tuple[str, ...]:
        """Channels that are angles (axis ``rx``, ``ry`` or ``rz``)."""
        return tuple(c for c in self.channels if c.rsplit(".", 1)[-1] in ("rx", "ry", "rz"))

    def __reduce__(self) -> tuple:
        # pickle and copy.deepcopy cannot take the read-only meta (mappingproxies, at any
        # depth): the motion is rebuilt by its constructor from its fields, meta thawed to
        # dicts, which checks them and freezes them again; its cached columns are left out
        return Motion, (self.values, self.channels, self.frame_rate, self.skeleton, self.source,
                        thawed(self.meta))

    def __repr__(self) -> str:
        return (f"Motion({self.source!r}, {counted(self.frames, 'frame')} x "
                f"{counted(len(self.channels), 'channel')} at {self.frame_rate:g} fps)")


def check_number(value, name: str, *, positive: bool = False) -> float:
    """``value`` as a float, or a :class:`ValidationError` naming ``name``: it must be a real
    number (a string or a bool is not: ``float("2")`` and ``True`` would pass for one), finite,
    and not negative (positive when ``positive``).

    Examples
    --------
    >>> check_number(2, "smoothing")
    2.0
    >>> check_number("2", "smoothing")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: smoothing must be a number, not '2'
    """
    if isinstance(value, bool) or not isinstance(value, Real):
        raise ValidationError(f"{name} must be a number, not {value!r}")
    number = float(value)
    if not np.isfinite(number) or number < 0 or (positive and number == 0):
        raise ValidationError(f"{name} must be a {'positive' if positive else 'non-negative'} "
                              f"number, not {value!r}")
    return number


def check_unwrap(value, name: str = "unwrap") -> float:
    """``value`` as an unwrap period: :func:`check_number`'s checks, then 0 (off) or at
    least :data:`MIN_UNWRAP` degrees.

    Examples
    --------
    >>> check_unwrap(360), check_unwrap(0)
    (360.0, 0.0)
    >>> check_unwrap(1e-300)
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: unwrap must be 0 (off) or a period of at least 1 degree, not 1e-300: a step of more than half the period between two frames is taken for a wrap and folded back
    """
    number = check_number(value, name)
    if 0 < number < MIN_UNWRAP:
        raise ValidationError(f"{name} must be 0 (off) or a period of at least {MIN_UNWRAP:g} "
                              f"degree, not {value!r}: a step of more than half the period "
                              f"between two frames is taken for a wrap and folded back")
    return number


def check_rate(values: np.ndarray, frame_rate: float, source: str | None = None) -> None:
    """A :class:`ValidationError` when differencing ``values`` (frames first, finite) at
    ``frame_rate`` would overflow: an acceleration is up to the values' size times the rate
    squared, and past the floats' range segmentation read inf and NaN as one still segment.
    ``source``: the take the values are of, named first in the message (the values are the
    take's, so the command line's error says which of its files).

    Examples
    --------
    >>> check_rate(np.array([[0.0], [90.0]]), 3e6)
    >>> check_rate(np.array([[0.0], [90.0]]), 1e300)
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: frame rate 1e+300 fps is too high to difference values up to 90: their velocities and accelerations overflow
    """
    size = float(max(values.max(), -values.min())) if values.size else 0.0  # no |values| copy
    # central differences: a velocity is at most 2 size rate (at the ends), an acceleration
    # twice that rate; all zero, nothing overflows
    if size and not 4.0 * size * frame_rate * frame_rate < sys.float_info.max / 2:
        raise ValidationError(f"{source + ': ' if source else ''}frame rate {frame_rate:g} fps "
                              f"is too high to difference values up to {size:g}: their "
                              f"velocities and accelerations overflow")


def check_motion(motion) -> None:
    """A :class:`ValidationError` unless ``motion`` is a :class:`Motion` (a path, an array or
    None reached the work and failed there with another error).

    Examples
    --------
    >>> check_motion("walk.bvh")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: motion must be a Motion, not str
    """
    if not isinstance(motion, Motion):
        raise ValidationError(f"motion must be a Motion, not {type(motion).__name__}")


def channel_names(channels) -> tuple:
    """``channels`` as a tuple, or a :class:`ValidationError` when it is no sequence of names:
    one string would be split into one-letter names (``"a.rx"``: ``a``, ``.``, ``r``, ``x``).

    Examples
    --------
    >>> channel_names(["a.rx", "b.rx"])
    ('a.rx', 'b.rx')
    >>> channel_names("a.rx")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: channels must be a sequence of names, not 'a.rx'
    """
    if isinstance(channels, str) or not isinstance(channels, Iterable):
        raise ValidationError(f"channels must be a sequence of names, not {shown(channels)}")
    return tuple(channels)


def shown(value, limit: int = 60) -> str:
    """``repr(value)``, cut to ``limit`` characters: a value in an error message keeps it one
    line, however long the value.

    Examples
    --------
    >>> shown("abc"), shown(list(range(100)), 20)
    ("'abc'", '[0, 1, 2, 3, 4, 5...')
    """
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 3] + "..."


def counted(n: int, noun: str) -> str:
    """``n`` and ``noun``, plural unless ``n`` is 1: a count in a message reads "1 string",
    not "1 strings".

    Examples
    --------
    >>> counted(1, "string"), counted(0, "moving channel"), counted(3, "frame")
    ('1 string', '0 moving channels', '3 frames')
    """
    return f"{n} {noun}{'' if n == 1 else 's'}"


def is_whole(value) -> bool:
    """True for a whole number: an int or numpy integer, or a float holding one (``3.0``, which
    ``int()`` read before the checks); not a bool, a string, NaN or infinity.

    Examples
    --------
    >>> is_whole(3), is_whole(np.int64(3)), is_whole(3.0), is_whole(3.5), is_whole(True)
    (True, True, True, False, False)
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, Real):
        return False
    return isinstance(value, Integral) or float(value).is_integer()


def as_path(path, name: str = "path") -> Path:
    """``path`` as a :class:`~pathlib.Path`; a :class:`ValidationError` naming ``name`` when it
    is no path (None, a number), not the ``TypeError`` of ``Path(None)``, or is ``""``, which
    ``Path`` reads as ``"."`` (then "unknown motion format", the folder taken for a take).

    Examples
    --------
    >>> as_path("walk.bvh").name
    'walk.bvh'
    >>> as_path(None)
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: path must be a file's path (str or os.PathLike), not NoneType
    >>> as_path("")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: path must be a file's path, not the empty name ''
    """
    if not isinstance(path, (str, os.PathLike)):
        raise ValidationError(f"{name} must be a file's path (str or os.PathLike), not "
                              f"{type(path).__name__}")
    if path == "":  # Path("") is ".", the current folder: read as a take of no suffix
        raise ValidationError(f"{name} must be a file's path, not the empty name ''")
    return Path(path)


def real_array(values, name: str = "motion values") -> np.ndarray:
    """``values`` as a new float array; a :class:`ValidationError` for anything but real numbers.

    ``np.array(values, dtype=float)`` alone would read the strings ``"1.5"`` as numbers, drop
    the imaginary part of complex values with only a warning, and answer a ragged list or an
    object array with numpy's own errors that do not say which argument was wrong.

    Examples
    --------
    >>> real_array([[1, 2]]).dtype
    dtype('float64')
    >>> real_array(np.ones(2) + 1j, "values")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: values must be real numbers, not complex128 (ndarray)
    """
    try:
        given = np.asarray(values)
    except (TypeError, ValueError) as exc:  # a ragged list of rows
        raise ValidationError(f"{name} must be an array of numbers: {exc}") from None
    if given.dtype.kind not in "iuf":
        raise ValidationError(f"{name} must be real numbers, not {given.dtype} "
                              f"({type(values).__name__})")
    return np.array(given, dtype=float, copy=True)
