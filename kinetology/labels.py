"""Action labels of the shared motion data, as time spans in seconds.

Two label formats are read:

* **CMU mocap6** ``truelabels/T.txt`` (Fox, Hughes, Sudderth, Jordan 2014): one integer
  label per block of 12 AMC frames (1/10 s at 120 fps), whitespace separated; label ``k``
  names the exercise ``MOCAP6_ACTIONS[k - 1]``. A run of equal labels is one :class:`Span`.
* **Bandai Namco** ``*.json`` beside each BVH take: ``{"content": i, "style": j}``, indices
  into ``cfg/content_label.txt`` and ``cfg/style_label.txt`` of the dataset (lines such as
  ``dataset-1_bye``; the ``dataset-N_`` prefix is dropped). A take is one performance of one
  content in one style, so its one span covers the whole take; its length comes from the
  ``Frames:`` and ``Frame Time:`` lines of the BVH file of the same name.

Every error names the file (and the line and column where there is one), as
:class:`~kinetology.motion.MotionFormatError`.
"""

from __future__ import annotations

import json
import re
from dataclasses import dataclass
from numbers import Real
from pathlib import Path

from psgs._foundation.text import split_lines
from psgs.errors import ValidationError

from .bvh import FRAME_TIME_RANGE
from ._file_motion import file_text
from .motion import MotionFormatError, as_path, check_number

__all__ = ["Span", "MOCAP6_ACTIONS", "read_cmu_truelabels", "read_bandai_json", "spans_of"]

#: The twelve cmu-mocap6 exercises, label ``k`` is ``MOCAP6_ACTIONS[k - 1]``.
MOCAP6_ACTIONS = ("JumpJack", "Jog", "Squat", "KneeRaise", "ArmCircle", "Twist", "SideReach",
                  "Box", "UpDown", "ToeTouchOneHand", "SideBend", "ToeTouchTwoHands")

#: AMC frames per mocap6 label (the labels are at 10 Hz, the AMC files at 120 fps).
FRAMES_PER_LABEL = 12


@dataclass(frozen=True, slots=True)
class Span:
    """One labelled stretch of a take: ``label`` from ``start`` to ``stop`` seconds.

    Parameters
    ----------
    label : str
        The action.
    start, stop : float
        Seconds from the take's first frame, ``0 <= start < stop`` (else ``ValueError``).
    style : str, optional
        The performer's style where the labels give one (Bandai Namco), else None.

    Examples
    --------
    >>> Span("Squat", 2.0, 5.5).duration
    3.5
    """

    label: str
    start: float
    stop: float
    style: str | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.label, str) or not isinstance(self.style, (str, type(None))):
            raise ValidationError(f"span label and style must be strings, not {self.label!r}, "
                                  f"{self.style!r}")
        if any(isinstance(t, bool) or not isinstance(t, Real) for t in (self.start, self.stop)):
            raise ValidationError(f"span {self.label!r}: start and stop must be numbers of "
                                  f"seconds, not {self.start!r}, {self.stop!r}")
        if not (0 <= self.start < self.stop):
            raise ValidationError(f"span {self.label!r}: need 0 <= start < stop, got "
                             f"{self.start!r}..{self.stop!r}")

    @property
    def duration(self) -> float:
        """``stop - start`` in seconds."""
        return self.stop - self.start


def read_cmu_truelabels(path: str | Path, frame_rate: float = 120.0) -> tuple[Span, ...]:
    """Read a cmu-mocap6 ``truelabels`` file into spans (seconds).

    Parameters
    ----------
    path : str or Path
        A ``truelabels/T.txt`` file: integer labels 1..12, one per 12 AMC frames.
    frame_rate : float
        Frame rate of the AMC file the labels belong to (120 for CMU); a label covers
        ``12 / frame_rate`` seconds.

    Returns
    -------
    tuple of Span
        One span per run of equal labels, in time order, named by :data:`MOCAP6_ACTIONS`.

    Raises
    ------
    MotionFormatError
        A token that is not a label 1..12 (file, line and column named).
    FileNotFoundError
        No such file.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> p = pathlib.Path(tempfile.mkdtemp()) / "t.txt"
    >>> _ = p.write_text("1 1 1 5 5\\n")
    >>> [(s.label, s.start, s.stop) for s in read_cmu_truelabels(p)]
    [('JumpJack', 0.0, 0.3), ('ArmCircle', 0.3, 0.5)]
    """
    path = as_path(path)
    check_number(frame_rate, "frame rate", positive=True)  # "120" or True: no rate
    step = FRAMES_PER_LABEL / frame_rate
    labels: list[int] = []
    for number, line in enumerate(split_lines(file_text(path)), 1):
        for match in re.finditer(r"\S+", line):
            token = match.group()
            # ASCII digits only, and few: int() refuses other Unicode digits ("²") and
            # strings of thousands of digits with a plain ValueError
            if not (token.isascii() and token.isdigit() and len(token) <= 6) or \
                    not 1 <= int(token) <= len(MOCAP6_ACTIONS):
                raise MotionFormatError(f"expected an action label 1..{len(MOCAP6_ACTIONS)}, "
                                        f"found {token[:20]!r}", source=str(path), line=number,
                                        column=match.start() + 1)
            labels.append(int(token))
    spans = []
    start = 0
    for i in range(1, len(labels) + 1):
        if i == len(labels) or labels[i] != labels[start]:
            spans.append(Span(MOCAP6_ACTIONS[labels[start] - 1], round(start * step, 9),
                              round(i * step, 9)))
            start = i
    return tuple(spans)


def _label_names(cfg: Path, index: object, kind: str, source: Path) -> str:
    if isinstance(index, bool) or not isinstance(index, int):
        raise MotionFormatError(f"{kind!r} must be an integer index, not {index!r}",
                                source=str(source))
    if not cfg.is_file():
        raise MotionFormatError(f"no label list {cfg} for the {kind} index", source=str(source))
    names = [re.sub(r"^dataset-\d+_", "", ln.strip()) for ln in split_lines(file_text(cfg))
             if ln.strip()]
    if not 0 <= index < len(names):
        raise MotionFormatError(f"{kind} index {index} is outside {cfg.name} "
                                f"(0..{len(names) - 1})", source=str(source))
    return names[index]


def _bvh_duration(bvh: Path) -> float:
    """The length in seconds the ``Frames:`` and ``Frame Time:`` lines of ``bvh`` give."""
    # file_text refuses a device (/dev/zero has no line end to stop at) and reads a
    # file no further than its size; only the header is decoded, not the frames after it
    frames = frame_time = None
    for line in split_lines(file_text(bvh, until=b"Frame Time:")):
        stripped = line.strip()
        if stripped.startswith("Frames:"):
            frames = stripped.split(":", 1)[1]
        elif stripped.startswith("Frame Time:"):
            frame_time = stripped.split(":", 1)[1]
            break
    try:
        duration = int(frames) * float(frame_time)
    except (TypeError, ValueError, OverflowError):
        raise MotionFormatError("no 'Frames:' and 'Frame Time:' header lines",
                                source=str(bvh)) from None
    if not 0 < duration < float("inf"):  # a label span needs a take of some length
        raise MotionFormatError(f"'Frames: {frames.strip()}' and 'Frame Time: "
                                f"{frame_time.strip()}' give no length to label",
                                source=str(bvh))
    shortest, longest = FRAME_TIME_RANGE
    if not shortest <= float(frame_time) <= longest:  # the take itself would not read
        raise MotionFormatError(f"'Frame Time: {frame_time.strip()}' is outside "
                                f"{shortest:g} .. {longest:g} s", source=str(bvh))
    return duration


def read_bandai_json(path: str | Path, duration: float | None = None) -> tuple[Span, ...]:
    """Read a Bandai Namco label file into one span over the whole take.

    Parameters
    ----------
    path : str or Path
        ``dataset-N_CONTENT_STYLE_ID.json`` holding ``{"content": i, "style": j}``; the
        names are looked up in ``../cfg/content_label.txt`` and ``../cfg/style_label.txt``.
    duration : float, optional
        Length of the take in seconds; by default read from the header of the BVH file of
        the same name beside it.

    Returns
    -------
    tuple of Span
        ``(Span(content, 0.0, duration, style),)``.

    Raises
    ------
    MotionFormatError
        Not JSON, a missing or bad index, or no label lists (the file is named).

    Examples
    --------
    >>> from pathlib import Path
    >>> data = Path("../shared/data/mocap/bandai-namco-1/data")
    >>> if data.is_dir():
    ...     span, = read_bandai_json(data / "dataset-1_bye_normal_001.json")
    ...     print(span.label, span.style, round(span.stop, 2))
    ... else:
    ...     print("bye normal 3.7")
    bye normal 3.7
    """
    path = as_path(path)
    text = file_text(path)  # outside the try: its own errors are located already
    try:
        record = json.loads(text)
    except json.JSONDecodeError as exc:
        raise MotionFormatError(f"not JSON: {exc.msg}", source=str(path), line=exc.lineno,
                                column=exc.colno) from None
    except RecursionError:  # json's parser recurses once per nested array or object
        raise MotionFormatError("nests too deeply to be a label file", source=str(path)) \
            from None
    except ValueError as exc:  # a 5,000-digit number
        raise MotionFormatError(f"not a label file ({type(exc).__name__}: "
                                f"{str(exc)[:80]})", source=str(path)) from None
    if not isinstance(record, dict) or "content" not in record:
        raise MotionFormatError("expected an object with 'content' and 'style'",
                                source=str(path))
    cfg = path.resolve().parent.parent / "cfg"
    content = _label_names(cfg / "content_label.txt", record["content"], "content", path)
    style = (_label_names(cfg / "style_label.txt", record["style"], "style", path)
             if "style" in record else None)
    if duration is not None:  # float("3") would take a string for seconds
        check_number(duration, "duration", positive=True)
    if duration is None:
        bvh = path.with_suffix(".bvh")
        if not bvh.is_file():
            raise MotionFormatError(f"no take {bvh.name} beside the labels to give the "
                                    f"duration (pass duration=)", source=str(path))
        duration = _bvh_duration(bvh)
    return (Span(content, 0.0, float(duration), style),)


def spans_of(path: str | Path, frame_rate: float = 120.0) -> tuple[Span, ...]:
    """The spans of a label file of either format, chosen by suffix (``.txt`` / ``.json``).

    Parameters
    ----------
    path : str or Path
        A CMU mocap6 ``truelabels`` ``.txt`` or a Bandai Namco ``.json`` file.
    frame_rate : float
        For ``.txt``: the AMC frame rate (see :func:`read_cmu_truelabels`).

    Returns
    -------
    tuple of Span

    Raises
    ------
    MotionFormatError
        Another suffix, or a malformed file.

    Examples
    --------
    >>> spans_of("labels.csv")
    Traceback (most recent call last):
    ...
    kinetology.motion.MotionFormatError: labels.csv: unknown label format '.csv'; expected .txt (CMU mocap6 truelabels) or .json (Bandai Namco)
    """
    path = as_path(path)
    if path.suffix.lower() == ".json":
        return read_bandai_json(path)
    if path.suffix.lower() == ".txt":
        return read_cmu_truelabels(path, frame_rate)
    raise MotionFormatError(f"unknown label format {path.suffix or '(no suffix)'!r}; expected "
                            f".txt (CMU mocap6 truelabels) or .json (Bandai Namco)",
                            source=str(path))
