"""The :class:`Motion` value every reader returns, and the error bad files raise.

A motion is a frames x channels array of joint angles in degrees (root
translations, where a file has them, in the file's length unit), one name per
channel written ``joint.axis`` with ``axis`` one of ``tx ty tz rx ry rz``, a
frame rate, and optionally the :class:`Skeleton` that forward kinematics
needs. The array is read-only: a motion never changes after it is built.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

__all__ = ["MotionFormatError", "Joint", "Skeleton", "Motion", "AXES", "build_motion"]

#: Channel axes, in the order a joint's channels are listed.
AXES = ("tx", "ty", "tz", "rx", "ry", "rz")
_MESSAGE_LIMIT = 200  # characters of an error message, so that it stays one readable line


class MotionFormatError(ValueError):
    """A motion file (or encoded motion) that could not be read.

    ``str(error)`` is one line, ``file:line:col: message`` (line and column
    left out when they do not apply); the parts are kept as attributes.
    """

    def __init__(self, message: str, *, source: str = "<data>", line: int | None = None,
                 column: int | None = None) -> None:
        if len(message) > _MESSAGE_LIMIT:  # garbage input (a binary file) quoted in full
            message = message[:_MESSAGE_LIMIT - 4] + " ..."
        self.message = message
        self.source = str(source)
        self.line = line
        self.column = column
        super().__init__(str(self))

    def __str__(self) -> str:
        where = self.source
        if self.line is not None:
            where += f":{self.line}"
            if self.column is not None:
                where += f":{self.column}"
        return f"{where}: {self.message}"


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
    """

    name: str
    parent: int | None
    offset: tuple[float, float, float]
    channels: tuple[str, ...] = ()
    rotation_order: str = "ZYX"
    axis: tuple[float, float, float] = (0.0, 0.0, 0.0)
    end_site: bool = False


@dataclass(frozen=True, slots=True)
class Skeleton:
    """Joints in depth-first order (a parent always comes before its children)."""

    joints: tuple[Joint, ...]
    length_unit: str = "file units"

    def __post_init__(self) -> None:
        for index, joint in enumerate(self.joints):
            if joint.parent is not None and not 0 <= joint.parent < index:
                raise ValueError(f"joint {joint.name!r} has parent {joint.parent}, which does "
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
        raise KeyError(f"no joint named {name!r} (joints: {', '.join(self.names)})")


@dataclass(frozen=True, eq=False)
class Motion:
    """Joint-angle motion: ``values[frame, channel]`` in degrees, read-only.

    >>> m = Motion(np.zeros((3, 2)), ("knee.rx", "hip.rx"), 120.0)
    >>> m.frames, m.duration, m.column("hip.rx").shape
    (3, 0.025, (3,))
    """

    values: np.ndarray
    channels: tuple[str, ...]
    frame_rate: float
    skeleton: Skeleton | None = None
    source: str = "<motion>"
    meta: dict = field(default_factory=dict)  # read-only after construction (format, truth)

    def __post_init__(self) -> None:
        values = np.array(self.values, dtype=float, copy=True)
        if values.ndim != 2:
            raise ValueError(f"motion values must be frames x channels, got shape {values.shape}")
        channels = tuple(self.channels)
        if values.shape[1] != len(channels):
            raise ValueError(f"{len(channels)} channel names for {values.shape[1]} columns")
        if len(set(channels)) != len(channels):
            raise ValueError("channel names must be distinct")
        if not np.isfinite(values).all():
            frame, column = np.argwhere(~np.isfinite(values))[0]
            raise ValueError(f"value at frame {frame}, channel {channels[column]!r} is not finite")
        rate = float(self.frame_rate)
        if not np.isfinite(rate) or rate <= 0:
            raise ValueError(f"frame rate must be positive, not {self.frame_rate!r}")
        values.setflags(write=False)
        object.__setattr__(self, "values", values)
        object.__setattr__(self, "channels", channels)
        object.__setattr__(self, "frame_rate", rate)
        object.__setattr__(self, "meta", MappingProxyType(dict(self.meta)))

    @property
    def frames(self) -> int:
        """Number of frames (rows of ``values``)."""
        return self.values.shape[0]

    @property
    def duration(self) -> float:
        """Seconds covered by the frames (``frames / frame_rate``)."""
        return self.frames / self.frame_rate

    def index(self, channel: str) -> int:
        """Column of ``channel`` (``KeyError`` naming it when there is none)."""
        try:
            return self.channels.index(channel)
        except ValueError:
            raise KeyError(f"no channel {channel!r} in {self.source}") from None

    def column(self, channel: str) -> np.ndarray:
        """The read-only column of one channel."""
        return self.values[:, self.index(channel)]

    def select(self, channels) -> "Motion":
        """A motion with only ``channels`` (in that order) and no skeleton."""
        columns = [self.index(c) for c in channels]
        return Motion(self.values[:, columns], tuple(channels), self.frame_rate, None,
                      self.source, self.meta)

    def rotation_channels(self) -> tuple[str, ...]:
        """Channels that are angles (axis ``rx``, ``ry`` or ``rz``)."""
        return tuple(c for c in self.channels if c.rsplit(".", 1)[-1] in ("rx", "ry", "rz"))

    def __repr__(self) -> str:
        return (f"Motion({self.source!r}, {self.frames} frames x {len(self.channels)} channels "
                f"at {self.frame_rate:g} fps)")


def build_motion(values, channels, frame_rate, skeleton=None, source="<motion>",
                 meta=None) -> Motion:
    """A :class:`Motion` for a reader: what :class:`Motion` refuses becomes a :class:`MotionFormatError`.

    Readers check their input as they go; this is the last line of that defence, so that a
    file the checks missed still gives the documented error naming the file, never the plain
    ``ValueError`` of the constructor.
    """
    try:
        return Motion(values, channels, frame_rate, skeleton, source, meta or {})
    except ValueError as exc:
        raise MotionFormatError(str(exc), source=source) from None
