"""Learning one action: its performances through kinetology and an inducer, to one record.

:func:`learn_action` is the unit of work the build hands to an executor: a
plain, picklable function of an :class:`~praxicon.datasets.Action` and a
:class:`Settings`, returning an :class:`~praxicon.records.ActionRecord` (never raising
for bad input: a failure is a record with ``status == "failed"`` and its reason).

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
from collections import Counter
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from psgs._foundation.files import read_bytes
from psgs.errors import FormatError, ValidationError

from .datasets import Action, Performance
from .jsonvalues import freeze
from .records import (FORMAT_VERSION, ActionRecord, ChannelMorpheme, JointRecord,
                      PerformanceRecord, Settings)

__all__ = ["Settings", "learn_action", "input_key"]

_LABEL_SLACK = 0.1  # seconds a label span may overrun its motion (cmu labels are 1/10 s)


# -- inputs ------------------------------------------------------------------------------------
def _file_digest(path: str) -> str:
    try:
        stat = Path(path).stat()
    except OSError as exc:
        return f"unreadable: {exc.strerror or exc}"
    except ValueError as exc:  # a NUL byte in the path
        return f"unreadable: {exc}"
    # cached by size and modification time too: a file changed in place is hashed again
    return _digest(path, stat.st_size, stat.st_mtime_ns)


@functools.lru_cache(maxsize=64)
def _digest(path: str, size: int, mtime_ns: int) -> str:
    # read_bytes: a device named as a take is refused, not read without end
    try:
        return hashlib.sha256(read_bytes(path)).hexdigest()
    except OSError as exc:
        return f"unreadable: {exc.strerror or exc}"
    except FormatError as exc:
        return f"unreadable: {exc.message}"


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


def _read(path: str):
    # cached by size and modification time too, as the digest: keyed by the path alone, a
    # take changed in place was learnt again (its digest changed) from the motion read before
    try:
        stat = Path(path).stat()
    except (OSError, ValueError):  # kinetology.read says what is wrong with it
        return _read_file(path, None, None)
    return _read_file(path, stat.st_size, stat.st_mtime_ns)


@functools.lru_cache(maxsize=8)  # one file holds several labelled performances (cmu-mocap6)
def _read_file(path: str, size: int | None, mtime_ns: int | None):
    import kinetology

    return kinetology.read(path)


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
    import kinetology

    try:
        motion = _read(perf.file)
    except FileNotFoundError:
        return None, f"{perf.file}: unreadable file (no such file)"
    except (OSError, ValueError) as exc:
        return None, f"{perf.file}: unreadable file ({_one_line(exc)})"
    if perf.stop is not None and perf.stop > motion.duration + _LABEL_SLACK:
        return None, (f"{perf.label or perf.file}: label span {perf.start or 0:g}-{perf.stop:g} s ends "
                      f"after the motion ({motion.duration:g} s): the label file does not match "
                      f"its motion")
    stop = perf.stop
    if stop is not None and stop > motion.duration:
        stop = None  # a label's last 1/10 s may reach past the last frame: to the end
    try:
        motion = kinetology.cut(motion, perf.start, stop)
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
    actuators: dict = field(default_factory=dict)      # channel -> joint (kinetology.joints)


def _segment_all(motions, segmentation: dict) -> list[_Segmented]:
    """Segment every performance on the same channels: those that move in any of them.

    Inducers want performances with the same actuators; a joint still in one take
    and moving in another keeps its (short) string in both.
    """
    from kinetology.segmentation import segments

    first = [segments(m, **segmentation) for m in motions]
    moving = set().union(*(s.channels for s in first))
    channels = [c for c in motions[0].channels if c in moving]
    out = []
    for motion, seg in zip(motions, first):
        if tuple(seg.channels) != tuple(channels):
            seg = segments(motion, channels=channels, **{**segmentation, "min_range": 0.0})
        item = _Segmented(seg.to_actiongram())
        for c, name in enumerate(seg.channels):
            item.symbols[name] = seg.symbols(c)
            item.durations[name] = seg.durations(c)
            item.displacements[name] = np.asarray(seg.displacements[c])
        item.actuators = dict(seg.actuators)
        out.append(item)
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


def _actuator_of(channel: str, segmented: _Segmented) -> str:
    return segmented.actuators.get(channel) or channel.split(".", 1)[0]


def _induce(inducer, segmented: list[_Segmented]):
    """(induction, performances learnt from, note)."""
    from psgs.errors import ValidationError

    actiongrams = [s.actiongram for s in segmented]
    try:
        return inducer.induce(tuple(actiongrams)), list(range(len(segmented))), None
    except (TypeError, ValidationError) as exc:
        # an inducer that takes one actiongram only (the content learner, a plug-in): learn
        # from the longest performance, say so in the record, and still read morphemes from
        # all
        lengths = [sum(map(sum, ag.segment_durations)) for ag in actiongrams]
        longest = int(np.argmax(lengths))
        why = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        note = (f"learnt from performance {longest + 1} of {len(segmented)} (the longest): "
                f"the inducer refused several ({why})")
        return inducer.induce(actiongrams[longest]), [longest], note


def _round(values) -> tuple[float, ...]:
    return tuple(round(float(v), 6) for v in values)


def learn_action(action: Action, settings: Settings) -> tuple[ActionRecord, float]:
    """Learn one action; returns ``(record, seconds)`` (see the module docstring).

    Never raises for bad input: unreadable files, labels that do not match their motion and
    performances whose channels differ from the others' are listed in ``record.problems``
    (each costs its performance only); with fewer than ``settings.min_performances`` usable
    performances, or when the inducer fails, ``record.status`` is ``"failed"`` and
    ``record.reason`` says why. An ``action`` that is no :class:`Action` or ``settings`` that
    are no :class:`Settings` are a ValidationError.
    """
    if not (isinstance(action, Action) and isinstance(settings, Settings)):
        raise ValidationError(f"learn_action learns an Action with Settings, not "
                              f"{type(action).__name__} and {type(settings).__name__}")
    began = time.perf_counter()
    motions, used, problems = _load_all(action)
    base = ActionRecord(
        action.name, action.dataset, action.content, action.style, status="failed",
        problems=tuple(action.problems) + tuple(problems),
        performances=tuple(PerformanceRecord(p.file, p.start, p.stop, p.label, i in used)
                           for i, p in enumerate(action.performances)))
    if len(motions) < settings.min_performances:
        reason = (f"{len(motions)} usable performance(s); an action needs at least "
                  f"{settings.min_performances} to show what repeats across them")
        return replace(base, reason=reason), time.perf_counter() - began
    try:
        record = _learnt(base, action, motions, used, settings)
    except Exception as exc:  # a failure of one action is recorded; the build goes on
        record = replace(base, reason=_one_line(exc))
    return record, time.perf_counter() - began


def _load_all(action: Action) -> tuple[list, list[int], list[str]]:
    """(motions, indices of the performances they are, problems): every performance that
    can be read, on the channels most of them share (one line per performance left out)."""
    loaded, problems = [], []
    for i, perf in enumerate(action.performances):
        try:
            motion, problem = _load_performance(perf)
        except Exception as exc:  # whatever one performance does, it costs that one only
            motion, problem = None, f"{perf.file}: unreadable ({_one_line(exc)})"
        if problem:
            problems.append(problem)
        else:
            loaded.append((i, motion))
    counts = Counter(tuple(m.channels) for _, m in loaded)
    if len(counts) > 1:  # inducers need one channel set: the most common one (first on a tie)
        common = max(counts, key=counts.__getitem__)
        for i, motion in loaded:
            if tuple(motion.channels) != common:
                problems.append(f"{action.performances[i].file}: its {len(motion.channels)} "
                                f"channels are not the {len(common)} of the other "
                                f"performances (left out)")
        loaded = [(i, m) for i, m in loaded if tuple(m.channels) == common]
    return [m for _, m in loaded], [i for i, _ in loaded], problems


def _learnt(base: ActionRecord, action: Action, motions, used: list[int],
            settings: Settings) -> ActionRecord:
    from psgs import dumps
    from psgs.induce import get

    segmentation = dict(settings.segmentation)
    segmented = _segment_all(motions, segmentation)
    inducer = get(settings.inducer, **dict(settings.params))
    induction, learnt, note = _induce(inducer, segmented)
    if getattr(induction, "bound", None) is not None:
        # what an inducer found before its bound is not what it learns: kept, the action
        # would read as learnt whole (its record says ok, its params do not hold the bound)
        raise ValueError(f"the inducer stopped at its bound {induction.bound} "
                         f"({induction.reason}): nothing kept; raise the bound to learn it")
    channels = _component_channels(induction)
    joints: dict[str, list] = {}
    for channel in channels:
        pattern = tuple(induction.patterns.get(channel, ()))
        joints.setdefault(_actuator_of(channel, segmented[0]), []).append(
            (channel, _morpheme(induction, channel, pattern, segmented)))
    actuators = tuple(induction.actuators) or tuple(joints)
    return replace(
        base, status="ok", learnt_from=tuple(used[i] for i in learnt), note=note,
        actuators=actuators,
        joints=tuple(JointRecord(j, tuple(joints[j])) for j in actuators if j in joints),
        verdict=induction.verdict or ("" if actuators else "no synchronised repetition"),
        inducer=induction.inducer or settings.inducer, params=freeze(dict(induction.params)),
        system=dumps(induction.system) if induction.system is not None else None,
        # channel -> component name in the system (names made identifiers: Hips.rx -> Hips_rx)
        component_names=tuple(sorted((c, induction.component_names.get(c, c))
                                     for c in channels)),
        frame_rate=motions[0].frame_rate,
        skeleton_source=action.performances[used[0]].file,
        # every joint of the motion in skeleton order
        all_joints=tuple(dict.fromkeys(c.rsplit(".", 1)[0] for c in motions[0].channels)),
        mean_pose=tuple(sorted(
            (c, round(float(v), 6)) for c, v in
            zip(motions[0].channels, np.mean(np.vstack([m.values for m in motions]), axis=0)))),
        segmentation=freeze(segmentation))


def _component_channels(induction) -> list[str]:
    if induction.actuator_channels:  # per joint, the channels that carry the pattern
        return [c for j in induction.actuators for c in induction.actuator_channels[j]]
    return list(induction.components)


def _morpheme(induction, channel: str, pattern: tuple[str, ...], segmented) -> ChannelMorpheme:
    given = induction.morphemes.get(channel)
    if given is not None:  # the inducer's own morpheme, displacements filled in
        pattern = tuple(given.kinetemes)
    durations, displacements, count = _typical(pattern, channel, segmented)
    if given is not None:
        durations = given.durations or durations
        displacements = given.displacements or displacements
    return ChannelMorpheme(pattern,
                           _round(durations) if durations is not None else None,
                           _round(displacements) if displacements is not None else None,
                           count)
