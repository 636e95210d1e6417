"""What the real-motion learner finds beside the grammar system: per joint, per pattern.

An :class:`~psgs.induce.Induction` of several performances holds one
:class:`ActuatorReport` per joint and a :class:`Morpheme` per component
channel; both are values, like the Induction. The learner's working records
(:class:`JointEvidence`, :class:`MotionResult`), which its phases fill in
turn, live here too, so that every phase reads them from one module.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ....errors import ValidationError

__all__ = ["ActuatorReport", "Morpheme"]


@dataclass(frozen=True)
class Morpheme:
    """A component channel's motion pattern as a generator needs it.

    Parameters
    ----------
    kinetemes : tuple of str
        The pattern's symbols, in order.
    durations : tuple of float
        The typical duration of each, seconds (PAL: its segment's in the medoid copy,
        the whole pattern brought to the median copy's length).
    displacements : tuple of float or None
        The typical signed angular change of each, in the channel's unit (PAL: its
        segment's own in the medoid copy), None when the actiongrams carry none.

    Examples
    --------
    >>> Morpheme(("B", "G"), (0.2, 0.3), (10.0, 2.5)).kinetemes
    ('B', 'G')
    """

    kinetemes: tuple[str, ...]
    durations: tuple[float, ...]
    displacements: tuple[float, ...] | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "kinetemes", tuple(self.kinetemes))
        object.__setattr__(self, "durations", tuple(float(d) for d in self.durations))
        if self.displacements is not None:
            object.__setattr__(self, "displacements",
                               tuple(float(d) for d in self.displacements))
        if len(self.durations) != len(self.kinetemes) or (
                self.displacements is not None
                and len(self.displacements) != len(self.kinetemes)):
            raise ValidationError("a morpheme needs one duration (and displacement) per kineteme")


@dataclass(frozen=True)
class ActuatorReport:
    """What an inducer found for one actuator (joint), whether or not it takes part.

    Parameters
    ----------
    name : str
        The actuator.
    status : str
        ``"component"``, ``"component (skeleton neighbour)"``, or the stage
        that dropped it (``"not significant"``, ``"below the share of the
        leader"``, ...).
    share : float, optional
        Its repeated motion relative to the leader's (1 for the leader).
    significance : float, optional
        log10 of the chance of agreement this strong between copies (more
        negative is stronger), corrected for the channels tested.
    repeated : float, optional
        Its repeated motion: angular path length times chance-corrected
        agreement, summed over its channels.
    path : float, optional
        Its angular path length per performance.

    Examples
    --------
    >>> ActuatorReport("lfemur", "component", share=1.0).share
    1.0
    """

    name: str
    status: str
    share: float = 0.0
    significance: float = 0.0
    repeated: float = 0.0
    path: float = 0.0


@dataclass
class JointEvidence:
    """What the learner measured for one joint (a working record)."""

    name: str
    channels: tuple[int, ...]
    path: float = 0.0          # mean angular path length per performance
    repeated: float = 0.0      # repeated motion (path x corrected agreement), summed
    log10_p: float = 0.0       # significance of its best channel, corrected
    share: float = 0.0         # repeated / the leader's
    status: str = "not significant"


@dataclass
class MotionResult:
    """The real-motion learner's findings (channel indices; codes over ``symbols``)."""

    verdict: str
    joints: list[JointEvidence]
    leader: str | None
    symbols: list[str]
    period: float | None = None
    channels: dict[str, tuple[int, ...]] = field(default_factory=dict)
    patterns: dict[int, tuple[int, ...]] = field(default_factory=dict)
    occurrences: dict[int, list[tuple[float, float]]] = field(default_factory=dict)
    occurrence_performance: dict[int, list[int]] = field(default_factory=dict)
    durations: dict[int, tuple[float, ...]] = field(default_factory=dict)
    displacements: dict[int, tuple[float, ...] | None] = field(default_factory=dict)
