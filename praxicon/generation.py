"""Motion generated back from an action's grammar system (the paper's claim, issue 10 item 6).

For an action of a praxicon, :func:`generate`:

1. derives ``K`` synchronised copies from the action's grammar system (the
   recursive axiom tuple applied ``K - 1`` times, then the rest in order), so
   each component's word is its morpheme repeated ``K`` times;
2. gives each kineteme its learnt duration and angular displacement. The
   copies of all components are kept in step: each channel's durations are
   scaled to the action's period (the median over channels of one copy's
   duration). A displacement takes the sign its state implies (``B``, ``G``
   rise; ``R``, ``Y`` fall), and a copy's rises and falls are scaled to cancel,
   so the joint returns where it started each cycle instead of drifting;
3. reconstructs each joint angle from those knots with kinetology's quartic,
   jerk-minimising decoder (:func:`kinetology.codec.reconstruct`), around the
   performances' mean angle;
4. holds every other channel at the performances' mean pose, and writes a BVH
   file on the source skeleton (:func:`kinetology.write_bvh`).

:meth:`Generated.round_trip` segments the generated motion again and says, per
channel, whether its kineteme string is the morpheme repeated ``K`` times.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .store import load_record

__all__ = ["Generated", "generate", "generate_motion", "derive_copies", "is_smooth_cycle"]

_RISING = {"B": 1.0, "G": 1.0, "R": -1.0, "Y": -1.0}
# kineteme changes a smooth angle can make: one sign flips, and a velocity sign flips only
# where the acceleration pushes it that way (a maximum is G -> R, a minimum Y -> B)
_SMOOTH_STEPS = {("B", "G"), ("G", "B"), ("G", "R"), ("R", "Y"), ("Y", "R"), ("Y", "B")}


def is_smooth_cycle(kinetemes) -> bool:
    """True when the morpheme, repeated, only makes kineteme changes a smooth angle can make.

    ``B G R Y`` is one (and ``Y B G R Y``: its repeated ends merge); ``R Y B`` is
    not (``B -> R`` would need the velocity and the acceleration to flip at once).
    Only such morphemes can come back unchanged from segmenting their motion.

    >>> is_smooth_cycle("BGRY"), is_smooth_cycle("YBGRY"), is_smooth_cycle("RYB")
    (True, True, False)
    """
    k = list(kinetemes)
    if len(k) > 1 and k[0] == k[-1]:
        k = k[:-1]
    if len(k) < 2:
        return False
    return all((a, b) in _SMOOTH_STEPS for a, b in zip(k, k[1:] + k[:1]))


def derive_copies(system, copies: int, max_steps: int = 100_000):
    """The terminal words of ``system`` after ``copies`` synchronised repetitions.

    A step whose rules all rewrite a nonterminal into a form holding it again
    (``S -> N S``, the axiom's repeat tuple) is taken while fewer than
    ``copies - 1`` were; otherwise the first applicable step that is not one.
    Raises ValueError when the system blocks or runs past ``max_steps``.
    """
    from psgs.derivation import applicable_steps, initial_configuration, \
        is_terminal_configuration

    def recursive(step) -> bool:
        rules = [r for r in step.tuple if r is not None]
        return bool(rules) and all(r.lhs in r.rhs for r in rules)

    configuration = initial_configuration(system)
    repeated = 0
    for _ in range(max_steps):
        if is_terminal_configuration(system, configuration):
            return tuple(tuple(str(s) for s in form) for form in configuration)
        steps = applicable_steps(system, configuration)
        if not steps:
            raise ValueError("the grammar system blocks before a terminal configuration")
        repeat = [s for s in steps if recursive(s)]
        other = [s for s in steps if not recursive(s)]
        if repeat and (repeated < copies - 1 or not other):
            step, repeated = repeat[0], repeated + 1
        else:
            step = other[0]
        configuration = step.after
    raise ValueError(f"no terminal configuration within {max_steps} steps")


@dataclass(frozen=True, eq=False)
class Generated:
    """A generated motion, the channels it drives, and what they were made from."""

    motion: object
    action: str
    repeat: int
    actuators: tuple[str, ...]
    channels: tuple[str, ...]
    words: dict
    segmentation: dict

    def resegmented(self) -> dict[str, tuple[str, ...]]:
        """Per generated channel, its kineteme string when the motion is segmented again."""
        import kinetology

        again = kinetology.segment(self.motion, channels=list(self.channels), **self.segmentation)
        return {c: (again.string(c) if c in again.names else ()) for c in self.channels}

    def round_trip(self, interior: bool = False) -> dict[str, bool]:
        """Per generated channel: does re-segmenting give the morpheme repeated K times?

        With ``interior``, the first and last kineteme may differ (the segmentation's
        smoothing flattens a turning point at the very start or end of a recording,
        and its dead band may then absorb that first or last segment): the rest must
        appear, unbroken, in the re-segmented string.
        """
        out = {}
        for channel, got in self.resegmented().items():
            want = _merged(self.words[channel])
            if not interior:
                out[channel] = got == want
            else:
                core = want[1:-1]
                out[channel] = any(got[i:i + len(core)] == core
                                   for i in range(len(got) - len(core) + 1))
        return out


def _merged(word) -> tuple[str, ...]:
    out: list[str] = []
    for symbol in word:
        if not out or out[-1] != symbol:
            out.append(symbol)
    return tuple(out)


def _merge_runs(kinetemes, durations, steps):
    """Adjacent equal kinetemes (the ends of two copies of ``G R Y B G``) as one segment."""
    out_k, out_d, out_s = [], [], []
    for k, d, x in zip(kinetemes, durations, steps):
        if out_k and out_k[-1] == k:
            out_d[-1] += d
            out_s[-1] += x
        else:
            out_k.append(k)
            out_d.append(float(d))
            out_s.append(float(x))
    return tuple(out_k), np.array(out_d), np.array(out_s)


def _balanced(kinetemes, displacements) -> np.ndarray:
    signs = np.array([_RISING.get(k, 1.0) for k in kinetemes])
    d = np.abs(np.asarray(displacements, dtype=float)) * signs
    up, down = d[d > 0].sum(), -d[d < 0].sum()
    if up > 0 and down > 0:  # rises and falls of one copy cancel: no drift over K copies
        mean = (up + down) / 2
        d = np.where(d > 0, d * mean / up, d * mean / down)
    return d


def generate_motion(record: dict, repeat: int, source_motion=None):
    """The generated :class:`kinetology.Motion` of one action record, and its words.

    ``source_motion`` gives the skeleton and the channel order (default: the
    record's ``skeleton_source`` file, read).
    """
    import kinetology
    from kinetology.codec import reconstruct
    from kinetology.segmentation import STATES
    from psgs import loads

    if record.get("status") != "ok":
        raise ValueError(f"action {record['name']!r} was not learnt: {record.get('reason')}")
    if not record.get("actuators") or not record.get("system"):
        raise ValueError(f"action {record['name']!r} has no actuators "
                         f"({record.get('verdict') or 'nothing learnt'}): nothing to generate")
    if not isinstance(repeat, int) or repeat < 1:
        raise ValueError(f"repeat must be a whole number >= 1, not {repeat!r}")
    system = loads(record["system"], source=f"{record['name']}.psgs")
    words = dict(zip((g.name for g in system.components), derive_copies(system, repeat)))
    morphemes = {c: m for j in record["actuators"] for c, m in
                 record["joints"][j]["morphemes"].items()}
    usable = {c: m for c, m in morphemes.items() if m["durations"] and m["displacements"]}
    if not usable:
        raise ValueError(f"action {record['name']!r}: no morpheme has durations and "
                         f"displacements (no exact occurrence of any pattern)")
    rate = float(record["frame_rate"])
    period = float(np.median([sum(m["durations"]) for m in usable.values()]))
    frames = int(round(repeat * period * rate)) + 1
    if source_motion is None:
        source_motion = kinetology.read(record["skeleton_source"])
    skeleton = source_motion.skeleton
    if skeleton is not None and any(any(j.axis) for j in skeleton.joints):
        skeleton = None  # an ASF skeleton: BVH cannot hold its axes, write angles on a star
    channels = source_motion.channels
    pose = record["mean_pose"]
    values = np.tile([pose.get(c, 0.0) for c in channels], (frames, 1))
    derived = {}
    for channel, morpheme in usable.items():
        word = words.get(record["component_names"].get(channel, channel))
        kinetemes = tuple(morpheme["kinetemes"])
        if word is None or tuple(word) != kinetemes * repeat:
            raise ValueError(f"action {record['name']!r}: the system derives "
                             f"{' '.join(word or ())!r} for {channel}, not its morpheme "
                             f"{' '.join(kinetemes)!r} x {repeat}")
        durations = np.asarray(morpheme["durations"], float)
        durations = np.tile(durations * period / durations.sum(), repeat)
        steps = np.tile(_balanced(kinetemes, morpheme["displacements"]), repeat)
        sequence, durations, steps = _merge_runs(kinetemes * repeat, durations, steps)
        knots = np.round(np.concatenate(([0.0], np.cumsum(durations))) * rate).astype(int)
        knots = np.maximum.accumulate(np.maximum(knots, np.arange(knots.size)))
        knots[-1] = max(knots[-1], frames - 1)
        knot_values = np.concatenate(([0.0], np.cumsum(steps)))
        codes = np.array([STATES.index(k) for k in sequence], dtype=np.int8)
        curve = reconstruct(knots, codes, knot_values)
        curve = curve[:frames] if curve.size >= frames else \
            np.pad(curve, (0, frames - curve.size), mode="edge")
        values[:, channels.index(channel)] = curve - curve.mean() + pose.get(channel, 0.0)
        derived[channel] = sequence
    motion = kinetology.Motion(values, channels, rate, skeleton,
                               f"generated:{record['name']}", {"format": "generated"})
    return motion, derived


def generate(folder: str | Path, action: str, *, repeat: int = 3, output: str | Path | None = None,
             plot: str | Path | None = None) -> Generated:
    """Generate ``repeat`` copies of ``action`` from the praxicon in ``folder``.

    Parameters
    ----------
    folder : str or Path
        A praxicon folder (``psgs praxicon build``).
    action : str
        An action name of its index.
    repeat : int
        How many synchronised copies.
    output : str or Path, optional
        Write the motion there as BVH.
    plot : str or Path, optional
        Save a picture of the first actuator channel: a performance beside the
        generated motion.

    Returns
    -------
    Generated

    Raises
    ------
    ValueError
        When the action is unknown, was not learnt, or has nothing to generate.

    Examples
    --------
    >>> generate("out/px", "cmu-mocap6.Nope")  # doctest: +SKIP
    Traceback (most recent call last):
    ValueError: no action 'cmu-mocap6.Nope' in out/px (actions: ...)
    """
    import kinetology

    record = load_record(folder, action)
    motion, words = generate_motion(record, repeat)
    if output is not None:
        kinetology.write_bvh(motion, output)
    result = Generated(motion, action, repeat, tuple(record["actuators"]), tuple(words), words,
                       dict(record.get("segmentation") or {}))
    if plot is not None:
        from .pictures import draw_generated

        draw_generated(record, result, plot)
    return result
