"""Motion generated back from an action's grammar system (the paper: a grammar generates it).

For an action of a praxicon, :func:`generate`:

1. derives ``K`` synchronised copies from the action's grammar system (the
   recursive axiom tuple applied ``K - 1`` times, then the rest in order), so
   each component's word is its morpheme repeated ``K`` times;
2. gives each kineteme its learnt duration and angular displacement. The copies of all
   components are kept in step: each channel's durations are scaled to the action's period
   (the median over channels of one copy's duration). A displacement takes the sign its state
   implies (``B``, ``G`` rise; ``R``, ``Y`` fall), and a copy's rises and falls are scaled to
   cancel, so the joint returns where it started each cycle instead of drifting;
3. reconstructs each joint angle from those knots with kinetology's quartic,
   jerk-minimising decoder (:func:`kinetology.codec.reconstruct`), around the
   performances' mean angle;
4. segments each channel again at once, and where the quartic alone does not
   give back its morpheme ``K`` times, corrects it with the frame-domain layer of
   :mod:`praxicon.shaping` (segments lengthened within the period, or
   displacements scaled up past ``min_range``, where that is what it takes);
5. gives every other channel the performances' mean cycle, phase-aligned to the generated
   channel that moves most, moves the root as the performances do (their mean speed in the
   body's own frame and mean turning rate, from the root's world rotation: measured by
   :mod:`praxicon.body_motion`) and writes a BVH file on the source skeleton
   (:func:`kinetology.write_bvh`; an ASF skeleton's ``axis`` pre-rotations, which BVH
   cannot hold, turned into its angles by :func:`kinetology.bvh_writer.without_axes`).

:meth:`Generated.round_trip` segments the generated motion again and says, per
channel (or per actuator), whether its kineteme string is the morpheme repeated
``K`` times; :attr:`Generated.methods` says how each channel was made.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ._values import check_count, is_count
from .channel_curve import SMOOTH_STEPS as _SMOOTH_STEPS
from .channel_curve import Method, channel_curves
from .body_motion import _source_take, animate, body_of, whole_cycle
from .performance_files import learnt_files, missing_style, performances_of, \
    read_performances, style_of, unreadable
from ._record_checks import lookup_problem
from .jsonvalues import as_dict
from .records import ActionRecord, Praxicon, _count
from .store import load, system_problem

__all__ = ["Generated", "Method", "generate", "generate_motion", "derive_copies",
           "has_grammar", "is_smooth_cycle", "style_scales", "MAX_REPEAT"]

#: The most copies one call makes: the time grows with their square (10,000: 30 s; 10**9 hung).
MAX_REPEAT = 1000

_RISING = {"B": 1.0, "G": 1.0, "R": -1.0, "Y": -1.0}


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
    """A generated motion, the channels it drives, and what they were made from.

    Built by :func:`generate` (or from :func:`generate_motion`'s results).

    ``methods`` says per channel how its curve was made (:class:`Method`: the
    quartic alone, or with the correction layer, with segments lengthened or
    displacements scaled up), ``owners`` each channel's joint, ``cycle`` how many
    morphemes make one of the ``repeat`` copies (2 when the morpheme is half a stride,
    :func:`praxicon.body_motion.whole_cycle`): each word is its morpheme
    ``repeat * cycle`` times.

    ``origin`` is ``"grammar"`` (derived from the action's grammar system) or
    ``"performances"`` (an action with no synchronised repetition, hence no grammar: its
    performances' mean course, :mod:`praxicon.acyclic`; then ``channels``, ``words`` and
    ``methods`` are empty, there is no symbolic round trip, and ``performances`` says how
    many takes were averaged).
    """

    motion: object
    action: str
    repeat: int
    actuators: tuple[str, ...]
    channels: tuple[str, ...]
    words: dict
    segmentation: dict
    methods: dict = field(default_factory=dict)
    owners: dict = field(default_factory=dict)
    cycle: int = 1
    origin: str = "grammar"
    performances: int = 0

    def __repr__(self) -> str:  # a summary, not the dataclass dump of the motion's values
        m = self.motion
        made = (f"from the grammar, {self.repeat} cop{'y' if self.repeat == 1 else 'ies'}"
                + (f" of {self.cycle} morphemes" if self.cycle > 1 else "")
                + f", {_count(len(self.channels), 'channel')} of "
                  f"{_count(len(self.actuators), 'actuator')}"
                if self.origin == "grammar" else
                f"from the course of {_count(self.performances, 'performance')}, played "
                + ("once" if self.repeat == 1 else f"{self.repeat} times"))
        size = f"{_count(m.frames, 'frame')} at {m.frame_rate:g} fps" if m is not None else \
            "no motion"
        return f"<Generated {self.action!r}: {size}, {made}>"

    def resegmented(self) -> dict[str, tuple[str, ...]]:
        """Per generated channel, its kineteme string when the motion is segmented again."""
        import kinetology

        again = kinetology.segment(self.motion, channels=list(self.channels), **self.segmentation)
        return {c: (again.string(c) if c in again.names else ()) for c in self.channels}

    def round_trip(self, interior: bool = False, by: str = "channel") -> dict[str, bool]:
        """Does re-segmenting give the morpheme repeated K times, per channel or per actuator?

        Parameters
        ----------
        interior : bool
            Let the first and last kineteme differ: the rest must appear, unbroken, in
            the re-segmented string (a looser check; the correction layer makes the
            exact one hold).
        by : {"channel", "actuator"}
            Per generated channel, or per actuator (joint): True when every one of its
            generated channels comes back.

        Returns
        -------
        dict
            Channel (or joint) name -> bool.

        Raises
        ------
        ValueError
            For another ``by``.

        Examples
        --------
        ``generate(DIR, ACTION).round_trip(by="actuator")`` gives e.g.
        ``{'UpperArm_L': True, 'LowerArm_L': False, ...}``; the unit asked must be one of
        the two:

        >>> Generated(None, "a", 1, (), (), {}, {}).round_trip(by="joint")
        Traceback (most recent call last):
        ValueError: by must be 'channel' or 'actuator', not 'joint'

        """
        if by not in ("channel", "actuator"):
            raise ValueError(f"by must be 'channel' or 'actuator', not {by!r}")
        out = {}
        for channel, got in self.resegmented().items():
            want = _merged(self.words[channel])
            if not interior:
                out[channel] = got == want
            else:
                core = want[1:-1]
                out[channel] = any(got[i:i + len(core)] == core
                                   for i in range(len(got) - len(core) + 1))
        if by == "channel":
            return out
        joints: dict[str, bool] = {}
        for channel, ok in out.items():
            joint = self.owners.get(channel, channel.split(".", 1)[0])
            joints[joint] = joints.get(joint, True) and ok
        return joints


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


def style_scales(record, channels, period: float, style: str, rate: float, performances=None):
    """How a style's performances differ from all of an action's: (tempo, amplitude per channel).

    ``tempo`` is the style's median period over all performances' median (the morphemes'
    durations are at the median tempo), each performance's period read from its
    autocorrelation near ``period`` (:func:`praxicon.body_motion.own_period`) on the
    channel that moves most in the performances; a channel's amplitude is the style's mean
    range (5th to 95th percentile) over all performances' mean. Raises ValueError when no
    performance of the action has that style. ``performances``: the action's motions
    when already read (:func:`praxicon.performance_files.performances_of`), else read here.
    """
    from .body_motion import own_period

    read = performances is None  # here, every file read (performances_of raises otherwise)
    if read:
        performances = performances_of(record)
    every = [m for m in performances if set(channels) <= set(m.channels)]
    # the style's takes are among those just read: picked by their file names, not read again
    own = [m for m in every if style in style_of(m.source)]
    if not own:
        raise missing_style(record, style, {} if read else None)

    def spread(m, c):
        return float(np.subtract(*np.percentile(m.column(c), [95, 5])))

    ranges = {c: [spread(m, c) for m in every] for c in channels}
    amplitude = {c: float(np.mean([spread(m, c) for m in own]) / max(np.mean(r), 1e-9))
                 for c, r in ranges.items()}
    leader = max(channels, key=lambda c: float(np.mean(ranges[c])))
    expected = max(2, int(round(period * rate)))

    def periods(takes):
        found = [own_period(m.column(leader), expected) for m in takes]
        return [p for p in found if p is not None] or [expected]

    return float(np.median(periods(own)) / np.median(periods(every))), amplitude


def _style_error(record, style: str, performances, failed) -> ValueError | None:
    """Why ``style`` picks no performance in particular, else None: none of ``performances``
    (those read; ``failed``: why each of the others could not be, :func:`read_performances`)
    has it (:func:`missing_style`: no such style, or its files cannot be read),
    or every performance generation reads holds it as a word of its file name (``bye`` of
    ``dataset-1_bye_normal_001.bvh`` and its siblings).

    Such a word picks every performance: the style's tempo and amplitudes would be all of
    theirs, the motion the one made without a style, under a style's name. The action's own
    style (an action built per style, whose file names all hold it) is a style all the same.
    """
    if not any(style in style_of(m.source) for m in performances):
        return missing_style(record, style, failed)
    names = [style_of(f) for f in learnt_files(record)]
    if style == record.style or not all(style in n for n in names):
        return None
    # the styles there are, as missing_style names them: the words that tell the names apart
    # (take numbers aside), and the action's own style
    styles = {w for n in names for i, w in enumerate(n)
              if not w.isdigit() and any(len(o) <= i or o[i] != w for o in names)}
    styles = sorted(styles | ({record.style} if record.style else set()))
    held = ("the file name of its one performance holds it" if len(names) == 1 else
            f"the file names of all {len(names)} of its performances hold it")
    return ValueError(f"action {record.name!r}: style {style!r} does not tell its performances "
                      f"apart ({held}; " + (f"styles: {', '.join(styles)})" if styles else
                                            "it has no styles)"))


def has_grammar(record: ActionRecord) -> bool:
    """Whether the action has a grammar system to derive copies from (actuators and a system).

    A learnt action without one is an action in which the inducer found no synchronised
    repetition (``record.verdict``): it is generated from its performances' course
    (:mod:`praxicon.acyclic`), not from a grammar.
    """
    return bool(record.actuators and record.system)


def generate_motion(record: ActionRecord, repeat: int, source_motion=None,
                    style: str | None = None, progress=None, workers: int = 1):
    """The generated :class:`kinetology.Motion` of one action record, its words, its methods.

    Returns ``(motion, words, methods)``: the motion, per generated channel its merged
    kineteme sequence, and per channel the :class:`Method` that made it.

    With ``style``, the motion is that style's: the period scaled by the style's tempo and
    each actuator channel's displacements by its amplitude (:func:`style_scales`), the
    other channels and the root's course from that style's performances only.

    ``source_motion`` gives the skeleton and the channel order (default: the
    record's ``skeleton_source`` file, read). Channels no morpheme drives take the
    performances' mean cycle (:func:`praxicon.body_motion.animate`); the root advances and
    turns steadily at the performances' average speed and turning rate, on the still joint
    above it when the skeleton has one (Bandai's ``joint_Root``), so that the root's own
    channels keep their generated values.

    An action without a grammar system (:func:`has_grammar`: no synchronised repetition)
    is its performances' mean course instead, warped to one time base and played
    ``repeat`` times (:func:`praxicon.acyclic.performed_motion`); its words and methods
    are empty. ``workers`` channels are made at once (threads; the motion is the same).

    Raises ValueError, one line, for a record that was not learnt, a ``style`` that every
    performance's file name holds (it would pick them all), and a performance the action was
    learnt from that cannot be read (naming it and why: the motion made from the others, or
    from the mean pose when none reads, would not be the one the praxicon gives).
    """
    import kinetology
    from psgs import loads

    if not isinstance(record, ActionRecord):
        raise ValueError(f"record must be an ActionRecord, not {type(record).__name__}")
    if not record.learnt:  # a record may hold no reason (a hand-made or older one)
        raise ValueError(f"action {record.name!r} was not learnt"
                         + (f": {record.reason}" if record.reason and record.reason.strip()
                            else " (no reason recorded)"))
    if not is_count(repeat) or repeat > MAX_REPEAT:  # a numpy integer is a count too
        raise ValueError(f"repeat must be a whole number from 1 to {MAX_REPEAT}, not {repeat!r}")
    if progress is not None and not callable(progress):  # else a TypeError after a channel
        raise ValueError(f"progress must be callable, not {progress!r}")
    check_count(workers, "workers")
    if not has_grammar(record):  # a one-off gesture: its performances' course, played
        from .acyclic import performed_motion

        performances, failed = read_performances(record)
        wrong = None if style is None else _style_error(record, style, performances, failed)
        if wrong:
            raise wrong
        if source_motion is None:
            source_motion = _source_take(record)
        if failed:
            raise ValueError(unreadable(record, failed))
        motion, _ = performed_motion(record, repeat, source_motion, style, performances)
        return motion, {}, {}
    try:
        system = loads(record.system, source=record.file)
    except ValueError as exc:  # the record's text: the record is what is damaged, not the copy
        raise ValueError(system_problem(record, f"the record of {record.name!r}")
                         or str(exc)) from None
    usable = {c: m for c, m in record.morphemes().items() if m.durations and m.displacements}
    if not usable:
        raise ValueError(f"action {record.name!r}: no morpheme has durations and "
                         f"displacements (no exact occurrence of any pattern)")
    rate = float(record.frame_rate)
    period = float(np.median([sum(m.durations) for m in usable.values()]))
    tempo, amplitude = 1.0, {}
    # the performances are read once, for the style's scales and for the body around them
    performances, failed = read_performances(record)
    if style is not None:
        wrong = _style_error(record, style, performances, failed)
        if wrong:
            raise wrong
        tempo, amplitude = style_scales(record, sorted(usable), period, style, rate,
                                        performances)
        period *= tempo
    if source_motion is None:
        source_motion = _source_take(record)
    # said after the skeleton's error and the style's own, which keep coming first
    if failed:
        raise ValueError(unreadable(record, failed))
    # an ASF skeleton is kept (the viewer draws it); the BVH file re-expresses its angles
    skeleton = source_motion.skeleton
    channels = source_motion.channels
    looked_up = lookup_problem(record, {g.name for g in system.components}, channels)
    if looked_up:  # else a channel silently posed at 0, or derived from no component
        raise RecordFieldError(f"action {record.name!r}: {looked_up}")
    pose = dict(record.mean_pose)
    body = body_of(record, channels, set(usable), period, style, performances)
    # a morpheme of half a stride repeats before the body does (the legs take turns): each
    # copy asked for is the whole body's cycle, that many morphemes
    cycle = whole_cycle(body, period, rate)
    copies = repeat * cycle
    words = dict(zip((g.name for g in system.components), derive_copies(system, copies)))
    frames = int(round(copies * period * rate)) + 1
    centre = {**pose, **(body.centre or {})}  # the root's rotation: heading-free means
    values = np.tile([pose.get(c, 0.0) for c in channels], (frames, 1))
    params = as_dict(record.segmentation)
    component = dict(record.component_names)
    jobs, sequences = [], {}
    for channel, morpheme in usable.items():
        word = words.get(component[channel])
        kinetemes = morpheme.kinetemes
        if word is None or tuple(word) != kinetemes * copies:
            raise ValueError(f"action {record.name!r}: the system derives "
                             f"{' '.join(word or ())!r} for {channel}, not its morpheme "
                             f"{' '.join(kinetemes)!r} x {copies}")
        durations = np.asarray(morpheme.durations, float)
        durations = np.tile(durations * period / durations.sum(), copies)
        steps = np.tile(_balanced(kinetemes, morpheme.displacements), copies) * \
            amplitude.get(channel, 1.0)
        sequence, durations, steps = _merge_runs(kinetemes * copies, durations, steps)
        knots = np.round(np.concatenate(([0.0], np.cumsum(durations))) * rate).astype(int)
        jobs.append((channel, (knots, sequence, steps, frames, rate, params, channel)))
        sequences[channel] = sequence
    # each channel's correction may take seconds at 120 fps: progress as each is made
    made = channel_curves(jobs, workers, progress)
    derived, methods = {}, {}
    for channel, _ in jobs:  # in the channels' order, however many were made at once
        curve, methods[channel] = made[channel]
        values[:, channels.index(channel)] = curve - curve.mean() + centre.get(channel, 0.0)
        derived[channel] = sequences[channel]
    # a morpheme that only rises (or only falls) drifts: on a root rotation, an Euler flip
    drifting = {c for c, m in usable.items() if len({_RISING[k] for k in m.kinetemes}) == 1}
    animate(values, channels, body, set(derived), rate, period * cycle, drifting)
    motion = kinetology.Motion(values, channels, rate, skeleton, f"generated:{record.name}",
                               {"format": "generated", "cycle": cycle})
    return motion, derived, methods


class RecordFieldError(ValueError):
    """A learnt record whose ``mean_pose`` or ``component_names`` do not name what generation
    looks up (the command line names the record's file before it)."""


def generate(folder: str | Path | Praxicon, action: str, *, repeat: int | None = None,
             output: str | Path | None = None, plot: str | Path | None = None,
             style: str | None = None, progress=None, workers: int = 1) -> Generated:
    """Generate ``repeat`` copies of ``action`` from the praxicon in ``folder``.

    An action with a grammar system is derived from it (the module's steps). A learnt
    action in which no synchronised repetition was found has none: it is generated from its
    performances' course (:mod:`praxicon.acyclic`: every channel their mean after warping
    them to their median length, the root travelling and turning as they do), played once,
    or ``repeat`` times, and ``Generated.origin`` says so.

    Parameters
    ----------
    folder : str, Path or Praxicon
        A praxicon folder (``psgs praxicon build``) or a loaded praxicon.
    action : str
        An action name of its index.
    repeat : int, optional
        How many synchronised copies (default 3, at most :data:`MAX_REPEAT`); of an action
        without a grammar, how many times its gesture is played in a row (default 1).
    output : str or Path, optional
        Write the motion there as BVH.
    plot : str or Path, optional
        Save a picture of the first actuator channel: a performance beside the generated motion.
    style : str, optional
        Generate that style of the action: a word of its performances' file names (Bandai
        Namco's ``dataset-2_walk_elderly_001.bvh`` is style ``elderly``). Its tempo and each
        actuator channel's amplitude are the style's performances' against all of them
        (:func:`style_scales`), the other joints and the root's course are those
        performances' alone. Default: every performance together.
    progress : callable, optional
        Called as ``progress(done, total, channel)`` after each actuator channel is made.
    workers : int, default 1
        Actuator channels made at once, in threads: the correction layer's linear programmes
        run on that many cores (at 120 fps they take most of the time); the motion is the same
        for any number.
    
    Returns
    -------
    Generated

    Raises
    ------
    ValueError
        When the action is unknown, was not learnt, has nothing to generate (no grammar and no
        performance that reads), has no performance of ``style`` or a ``style`` every
        performance has (a word all their file names share, such as the content's), a
        performance it was learnt from cannot be read, or an argument is wrong.

    Examples
    --------
    A praxicon of the wave from two takes of the shared data, then one copy of it:

    >>> import pathlib, tempfile
    >>> from praxicon import read_dataset, build
    >>> data = pathlib.Path("../shared/data/mocap/bandai-namco-1/data").resolve()
    >>> work = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (work / "m.csv").write_text("action,file\\n" + "".join(
    ...     f"bye,{data / f'dataset-1_bye_{style}_001.bvh'}\\n" for style in ("normal", "active")))
    >>> _ = build(read_dataset(work / "m.csv"), work / "px", progress=False)
    >>> generated = generate(work / "px", "m.bye", repeat=1, output=work / "bye.bvh")
    >>> generated.motion.frames > 0, (work / "bye.bvh").exists()
    (True, True)
    >>> generated  # doctest: +ELLIPSIS
    <Generated 'm.bye': ... frames at 30 fps, from the grammar, 1 copy, ... channels of ... actuators>
    >>> active = generate(work / "px", "m.bye", repeat=1, style="active")
    >>> generate(work / "px", "m.bye", style="sad")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ValueError: action 'm.bye' has no performance of style 'sad' (styles: active, normal)
    >>> generate(work / "px", "m.bye", style="bye")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ValueError: action 'm.bye': style 'bye' does not tell its performances apart (the file ...)
    >>> generate(work / "px", "m.Nope")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    praxicon.records.PraxiconError: no action 'm.Nope' in the praxicon (actions: m.bye)
    """
    import kinetology

    if plot is not None:  # a picture matplotlib cannot write: said before any work
        from .pictures import check_picture

        check_picture(plot)
    if output is not None:  # as the picture: a place it cannot be written, before the work
        from .outputs import check_folder

        check_folder(output, "the motion")
    # generation reads the records only: descriptions of another version do not stop it
    record = (folder if isinstance(folder, Praxicon)
              else load(folder, descriptions=False))[action]
    grammar = has_grammar(record)
    if repeat is None:
        repeat = 3 if grammar else 1
    motion, words, methods = generate_motion(record, repeat, style=style, progress=progress,
                                             workers=workers)
    if output is not None:  # on the source skeleton, an ASF one's axes turned into angles
        from kinetology.bvh_writer import without_axes

        kinetology.write_bvh(without_axes(motion), output)
    owners = {c: j.name for j in record.joints for c in j.channels}
    result = Generated(motion, action, repeat, record.actuators, tuple(words), words,
                       as_dict(record.segmentation), methods, owners,
                       int(motion.meta.get("cycle", 1)),
                       "grammar" if grammar else "performances",
                       int(motion.meta.get("performances", 0)))
    if plot is not None:
        from .pictures import draw_generated

        draw_generated(record, result, plot)
    return result
