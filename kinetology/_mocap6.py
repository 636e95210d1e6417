"""Reading cmu-mocap6: its takes and their labelled performances.

A cmu-mocap6 folder holds ``amc/T.amc`` (the takes, 120 fps) beside ``truelabels/T.txt`` (one
action label per 1/10 s, Fox, Hughes, Sudderth, Jordan 2014). :func:`mocap6_performances` reads
it into the motions and the :class:`Performance` list that
:func:`kinetology.evaluation.reproducibility` and :func:`kinetology.evaluation.selectivity`
measure. Import them from :mod:`kinetology.evaluation`, their public home; this module only
keeps the reader apart from the measures.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from psgs._foundation.text import split_lines

from .labels import MOCAP6_ACTIONS  # the one list of the exercises, as the label files number them
from ._file_motion import file_text
from .motion import MotionFormatError

__all__ = ["MOCAP6_ACTIONS", "Performance", "mocap6_performances"]


@dataclass(frozen=True, eq=False)
class Performance:
    """One labelled stretch of one take: an action done (usually many times over).

    Parameters
    ----------
    take : str
        The take's name (a key of the motions given with it).
    action : str
        The action's label.
    start : int
        First frame.
    stop : int
        One past the last frame.

    Examples
    --------
    >>> p = Performance("86_01", "Jog", 240, 960)
    >>> p.stop - p.start
    720
    """

    take: str
    action: str
    start: int   # first frame
    stop: int    # one past the last frame


def mocap6_performances(folder: str | Path, *, min_seconds: float = 2.0):
    """Read cmu-mocap6: ``{take: Motion}`` and the list of :class:`Performance`.

    ``truelabels/T.txt`` holds one label per 1/10 s (label ``t`` covers AMC
    frames ``12t .. 12t+11``); a performance is a run of one label lasting at
    least ``min_seconds``. Takes without an AMC file are skipped.

    Parameters
    ----------
    folder : str or Path
        The cmu-mocap6 folder (with ``amc/`` and ``truelabels/``).
    min_seconds : float, default 2.0
        Shorter runs of one label are not performances.

    Returns
    -------
    motions : dict of str to Motion
        Each take's motion, by take name.
    performances : list of Performance
        In take order, then time order.

    Raises
    ------
    MotionFormatError
        When an AMC file or a label file is malformed, or the folder holds no
        take (a missing folder included).

    Examples
    --------
    >>> from pathlib import Path
    >>> folder = Path("../shared/data/mocap/cmu-mocap6")
    >>> motions, performances = mocap6_performances(folder) if folder.is_dir() else ({}, [])
    >>> all(p.action in MOCAP6_ACTIONS and p.take in motions for p in performances)
    True
    """
    from .readers import read

    folder = Path(folder)
    motions, found = {}, []
    for label_file in sorted((folder / "truelabels").glob("*.txt")):
        amc = folder / "amc" / f"{label_file.stem}.amc"
        if not amc.is_file():
            continue
        motion = read(amc)
        motions[label_file.stem] = motion
        labels = _labels(label_file)
        per_frame = np.repeat(labels, 12)[: motion.frames]
        starts = np.concatenate(([0], np.flatnonzero(per_frame[1:] != per_frame[:-1]) + 1))
        stops = np.append(starts[1:], per_frame.size)
        for a, b in zip(starts, stops):
            if (b - a) / motion.frame_rate >= min_seconds:
                found.append(Performance(label_file.stem, MOCAP6_ACTIONS[per_frame[a] - 1],
                                         int(a), int(b)))
    if not motions:
        raise MotionFormatError(f"no cmu-mocap6 takes here (expected truelabels/NAME.txt beside "
                                f"amc/NAME.amc in {folder})", source=str(folder))
    return motions, found


def _labels(path: Path) -> np.ndarray:
    """The labels of a ``truelabels`` file: whole numbers 1 .. 6, one per tenth of a second."""
    text = file_text(path)  # a device refused, bytes that are not UTF-8 an error at line:col
    labels = []
    for number, line in enumerate(split_lines(text), 1):
        column = 1
        for word in line.split():
            column = line.index(word, column - 1) + 1
            if not (word.isascii() and word.isdigit()
                    and 1 <= int(word) <= len(MOCAP6_ACTIONS)):
                raise MotionFormatError(f"a label is a number from 1 to {len(MOCAP6_ACTIONS)}, "
                                        f"not {word[:20]!r}", source=str(path), line=number,
                                        column=column)
            labels.append(int(word))
            column += len(word)
    return np.array(labels, dtype=int)
