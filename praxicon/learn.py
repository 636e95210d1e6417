"""Learning one action: its performances through kinetology and an inducer, to one record.

:func:`learn_action` is the unit of work the build hands to an executor: a
plain, picklable function of an :class:`~praxicon.datasets.Action` and a
:class:`Settings`, returning a JSON-ready record (never raising for bad input:
a failure is a record with ``"status": "failed"`` and its reason).

What a record holds (the schema is in ``docs/praxicon.md``): the performances
used and the problems met, the joints that take part (``actuators``), per
joint its channels and per channel the morpheme (kinetemes with typical
durations in seconds and angular displacements in degrees, medians over every
exact occurrence of the pattern in every performance), the grammar system as
text, the mean pose of every channel (what generation holds still joints at),
and the inducer and its parameters.
"""

from __future__ import annotations

import functools
import hashlib
import json
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .datasets import Action, Performance

__all__ = ["Settings", "learn_action", "input_key", "FORMAT_VERSION"]

#: Bumped when what a record holds changes: an old record is then learnt again on resume.
FORMAT_VERSION = 1
_LABEL_SLACK = 0.1  # seconds a label span may overrun its motion (cmu labels are 1/10 s)


@dataclass(frozen=True)
class Settings:
    """How every action is learnt: the inducer by name and its parameters, segmentation.

    ``min_performances`` (2): an action with fewer usable performances fails
    with that reason (one performance cannot show what repeats across them).
    """

    inducer: str = "pal"
    params: tuple[tuple[str, object], ...] = ()
    segmentation: tuple[tuple[str, object], ...] = ()
    min_performances: int = 2

    @classmethod
    def make(cls, inducer: str = "pal", params: dict | None = None,
             segmentation: dict | None = None, min_performances: int = 2) -> "Settings":
        return cls(inducer, tuple(sorted((params or {}).items())),
                   tuple(sorted((segmentation or {}).items())), min_performances)

    def to_dict(self) -> dict:
        return {"inducer": self.inducer, "params": dict(self.params),
                "segmentation": dict(self.segmentation),
                "min_performances": self.min_performances}


# -- inputs ------------------------------------------------------------------------------------
@functools.lru_cache(maxsize=64)
def _file_digest(path: str) -> str:
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()
    except OSError as exc:
        return f"unreadable: {exc.strerror or exc}"


def input_key(action: Action, settings: Settings) -> str:
    """A digest of everything an action's record depends on (files' bytes, spans, settings)."""
    described = {
        "format": FORMAT_VERSION,
        "action": [action.name, action.dataset, action.content, action.style],
        "performances": [[p.file, _file_digest(p.file), p.start, p.stop, p.label]
                         for p in action.performances],
        "problems": list(action.problems),
        "settings": settings.to_dict(),
    }
    text = json.dumps(described, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()


@functools.lru_cache(maxsize=8)  # one file holds several labelled performances (cmu-mocap6)
def _read(path: str):
    import kinetology

    return kinetology.read(path)


def _cut(motion, start, stop):
    import kinetology

    cut = getattr(kinetology, "cut", None)
    if cut is not None:  # kinetology.cut (issue 9) when it exists
        return cut(motion, start=start, stop=stop)
    rate = motion.frame_rate
    first = 0 if start is None else int(round(start * rate))
    last = motion.frames if stop is None else min(motion.frames, int(round(stop * rate)))
    from kinetology import Motion

    return Motion(motion.values[first:last], motion.channels, rate, motion.skeleton,
                  motion.source, motion.meta)


def _unwrapped(motion):
    """Rotation channels unwrapped (period 360°), so a crossing of ±180° is no jump."""
    from kinetology import Motion

    values = np.array(motion.values)
    for c, name in enumerate(motion.channels):
        if name.rsplit(".", 1)[-1] in ("rx", "ry", "rz") and len(values):
            values[:, c] = np.unwrap(values[:, c], period=360.0)
    return Motion(values, motion.channels, motion.frame_rate, motion.skeleton, motion.source,
                  motion.meta)


def _one_line(exc: BaseException) -> str:
    text = str(exc).splitlines()[0] if str(exc) else ""
    return f"{type(exc).__name__}: {text}" if not isinstance(exc, (OSError, ValueError)) \
        else (text or type(exc).__name__)


def _load_performance(perf: Performance):
    """(motion cut and unwrapped, None) or (None, problem as one line)."""
    try:
        motion = _read(perf.file)
    except FileNotFoundError:
        return None, f"{perf.file}: unreadable file (no such file)"
    except (OSError, ValueError) as exc:
        return None, f"{perf.file}: unreadable file ({_one_line(exc)})"
    if perf.stop is not None and perf.stop > motion.duration + _LABEL_SLACK:
        return None, (f"{perf.label or perf.file}: label span {perf.start:g}-{perf.stop:g} s ends "
                      f"after the motion ({motion.duration:g} s): the label file does not match "
                      f"its motion")
    try:
        motion = _cut(motion, perf.start, perf.stop)
    except ValueError as exc:
        return None, f"{perf.file}: {_one_line(exc)}"
    if motion.frames < 3:
        return None, f"{perf.file}: span {perf.start}-{perf.stop} s holds {motion.frames} frames"
    return _unwrapped(motion), None


# -- morphemes ---------------------------------------------------------------------------------
@dataclass
class _Segmented:
    actiongram: object
    symbols: dict = field(default_factory=dict)       # channel -> tuple of kinetemes
    durations: dict = field(default_factory=dict)     # channel -> seconds per segment
    displacements: dict = field(default_factory=dict)  # channel -> degrees per segment


def _segment(motion, segmentation: dict) -> _Segmented:
    from kinetology.segmentation import segments, smooth, DEFAULTS

    seg = segments(motion, **segmentation)
    sigma = segmentation.get("smoothing", DEFAULTS["smoothing"])
    out = _Segmented(seg.to_actiongram())
    for c, name in enumerate(seg.channels):
        signal = smooth(np.asarray(motion.column(name)), motion.frame_rate, sigma)
        borders = np.minimum(seg.borders[c], motion.frames - 1)
        out.symbols[name] = seg.symbols(c)
        out.durations[name] = seg.durations(c)
        out.displacements[name] = np.diff(signal[borders])
    return out


def _typical(pattern: tuple[str, ...], name: str, performances: list[_Segmented]):
    """Median duration and displacement per pattern position over its exact occurrences."""
    k = len(pattern)
    durations, displacements = [], []
    for perf in performances:
        symbols = perf.symbols.get(name, ())
        for i in range(len(symbols) - k + 1):
            if tuple(symbols[i:i + k]) == pattern:
                durations.append(perf.durations[name][i:i + k])
                displacements.append(perf.displacements[name][i:i + k])
    if not durations:
        return None, None, 0
    return (np.median(durations, axis=0), np.median(displacements, axis=0), len(durations))


def _actuator_of(channel: str, actiongram) -> str:
    mapping = getattr(actiongram, "actuator", None)
    if callable(mapping):  # the actuator map of issue 9, when the actiongram has one
        try:
            return mapping(channel)
        except (KeyError, TypeError):
            pass
    return channel.split(".", 1)[0]


def _induce(inducer, segmented: list[_Segmented]):
    """(induction, performances learnt from, note)."""
    actiongrams = [s.actiongram for s in segmented]
    try:
        return inducer.induce(tuple(actiongrams)), list(range(len(segmented))), None
    except (TypeError, AttributeError):
        # an inducer that takes one actiongram (before issue 9): learn from the longest
        # performance, say so in the record, and still read morphemes from all of them
        lengths = [sum(map(sum, ag.segment_durations)) for ag in actiongrams]
        longest = int(np.argmax(lengths))
        note = (f"inducer {type(inducer).__name__} takes one actiongram: learnt from "
                f"performance {longest + 1} of {len(segmented)} (the longest)")
        return inducer.induce(actiongrams[longest]), [longest], note


def _round(values) -> list[float]:
    return [round(float(v), 6) for v in values]


def learn_action(action: Action, settings: Settings) -> tuple[dict, float]:
    """Learn one action; returns ``(record, seconds)`` (see the module docstring).

    Never raises for bad input: unreadable files and labels that do not match
    their motion are listed in ``record["problems"]``; with fewer than
    ``settings.min_performances`` usable performances, or when the inducer
    fails, ``record["status"]`` is ``"failed"`` and ``record["reason"]`` says why.
    """
    began = time.perf_counter()
    record = {"name": action.name, "dataset": action.dataset, "content": action.content,
              "style": action.style, "status": "failed", "reason": None,
              "problems": list(action.problems),
              "performances": [p.to_dict() for p in action.performances]}
    try:
        _learn_into(record, action, settings)
    except Exception as exc:  # a failure of one action is recorded; the build goes on
        record["status"], record["reason"] = "failed", _one_line(exc)
    return record, time.perf_counter() - began


def _learn_into(record: dict, action: Action, settings: Settings) -> None:
    from psgs import dumps
    from psgs.induce import get

    motions, used = [], []
    for i, perf in enumerate(action.performances):
        motion, problem = _load_performance(perf)
        if problem:
            record["problems"].append(problem)
        else:
            motions.append(motion)
            used.append(i)
    for i, perf in enumerate(record["performances"]):
        perf["used"] = i in used
    if len(motions) < settings.min_performances:
        record["reason"] = (f"{len(motions)} usable performance(s); an action needs at least "
                            f"{settings.min_performances} to show what repeats across them")
        return
    segmentation = dict(settings.segmentation)
    segmented = [_segment(m, segmentation) for m in motions]
    inducer = get(settings.inducer, **dict(settings.params))
    induction, learnt, note = _induce(inducer, segmented)
    record["learnt_from"] = [used[i] for i in learnt]
    record["note"] = note
    first = segmented[0].actiongram
    channels = _component_channels(induction)
    joints: dict[str, dict] = {}
    for channel in channels:
        joint = _actuator_of(channel, first)
        pattern = tuple(induction.patterns.get(channel, ()))
        morpheme = _morpheme(induction, channel, pattern, segmented)
        joints.setdefault(joint, {"channels": [], "morphemes": {}})
        joints[joint]["channels"].append(channel)
        joints[joint]["morphemes"][channel] = morpheme
    actuators = tuple(getattr(induction, "actuators", None) or joints)
    record.update({
        "status": "ok",
        "actuators": list(actuators),
        "joints": {j: joints[j] for j in actuators if j in joints},
        "verdict": getattr(induction, "verdict", None) or
        ("" if actuators else "no synchronised repetition"),
        "inducer": induction.inducer or settings.inducer,
        "params": {k: v for k, v in sorted(dict(induction.params).items())},
        "system": dumps(induction.system) if induction.system is not None else None,
        # channel -> component name in the system (names made identifiers: Hips.rx -> Hips_rx)
        "component_names": {c: induction.component_names.get(c, c) for c in channels},
        "frame_rate": motions[0].frame_rate,
        "skeleton_source": action.performances[used[0]].file,
        # every joint of the motion in skeleton order (JSON objects are written sorted)
        "all_joints": list(dict.fromkeys(c.rsplit(".", 1)[0] for c in motions[0].channels)),
        "mean_pose": {c: round(float(v), 6) for c, v in
                      zip(motions[0].channels, np.mean(np.vstack([m.values for m in motions]),
                                                       axis=0))},
        "segmentation": segmentation,
    })


def _component_channels(induction) -> list[str]:
    per_joint = getattr(induction, "actuator_channels", None)
    if per_joint:  # issue 9: per joint, the channels that carry the pattern
        return [c for j in induction.actuators for c in per_joint[j]]
    return list(induction.components)


def _morpheme(induction, channel: str, pattern: tuple[str, ...], segmented) -> dict:
    learnt = getattr(induction, "morphemes", None) or {}
    given = learnt.get(channel)
    if given is not None:  # the inducer's own morpheme (issue 9), displacements filled in
        pattern = tuple(getattr(given, "kinetemes", pattern))
    durations, displacements, count = _typical(pattern, channel, segmented)
    if given is not None:
        durations = getattr(given, "durations", None) or durations
        displacements = getattr(given, "displacements", None) or displacements
    return {"kinetemes": list(pattern),
            "durations": _round(durations) if durations is not None else None,
            "displacements": _round(displacements) if displacements is not None else None,
            "occurrences": count}
