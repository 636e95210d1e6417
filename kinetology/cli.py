"""The ``kinetology`` command: segment, compress, decompress, evaluate, plot.

Every error a user can cause (a bad file, an unknown channel, a bad number) is one of the
project's errors (:class:`psgs.PSGSError`), one line on stderr and exit status 2, never a
traceback; any other exception is a bug and keeps its traceback. The command runs in the
shell every command of the distribution shares (:mod:`psgs._foundation.shell`: the exit
statuses, printed at the end of every ``--help``); it is also ``psgs kinetology ...``
(entry-point group ``psgs.commands``).
"""

from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from psgs._foundation.files import read_bytes
from psgs._foundation.shell import (add_version, file_name, positive_float, run,
                                    with_exit_status_help)
from psgs.errors import ValidationError

# the defaults the help texts print; the modules that work with them (and numpy) are imported
# by the handlers, so that making the parser (every --help and --version) does not load them
from ._defaults import CODEC_DEFAULTS, DEFAULTS, MIN_UNWRAP

_FILE_HELP = "a motion file: .bvh, or .amc (its .asf skeleton is found beside it)"
_FRAME_RATE_HELP = ("frames per second of an AMC file (AMC files do not say; default 120, the "
                    "CMU rate); a BVH file states its own")

_PARAM_HELP = {
    "smoothing": "Gaussian smoothing sigma in seconds",
    "velocity_deadband": "velocity dead band in deg/s",
    "acceleration_deadband": "acceleration dead band in deg/s^2",
    "min_range": "channels moving less than this many degrees are left out",
    "relative_deadband": "dead bands at least this share of a channel's own 95th-percentile "
                         "speed and acceleration",
    "unwrap": f"period in degrees of rotation channels, unwrapped before smoothing (0: off; "
              f"else at least {MIN_UNWRAP:g}: a step between two frames of more than half the "
              f"period is taken for a wrap)",
}


_CODEC_HELP = {
    "quantum": "knot value step in degrees",
    "residual_step": "residual layer grid step in degrees (0: no residual layer)",
    "hysteresis": "residual grid hysteresis, a fraction of the step (>= 0.5)",
}


#: What the segmentation options mean to ``plot`` where it differs from ``segment``: the codec
#: (``--kind reconstruction``) has no min_range, relative dead band or unwrapping, and a view
#: angle is compared whatever its range.
_PLOT_NOTES = {
    "min_range": "--kind states: a channel moving less than this many degrees is still (segment "
                 "leaves it out) and drawn grey, without states; an error with reconstruction "
                 "and view",
    "relative_deadband": _PARAM_HELP["relative_deadband"] + "; not with --kind reconstruction",
    "unwrap": _PARAM_HELP["unwrap"] + "; not with --kind reconstruction",
}


#: ``evaluate --min-range`` counts the segments of the moving channels; the mocap6 descriptions
#: keep their own threshold (:func:`kinetology.evaluation.describe`).
_EVALUATE_NOTES = {
    "min_range": "channels moving less than this many degrees are left out of the segment "
                 "count (--mocap6's descriptions call a channel still below 5 degrees, "
                 "whatever this is)",
}


def _add_params(parser, *, codec: bool = False, notes=None) -> None:
    """The segmentation options (or with ``codec`` the codec's); ``notes``: help texts that
    replace :data:`_PARAM_HELP`'s for this command."""
    if codec:  # the codec pins its own settings: its defaults, not the segmentation's
        for name, default in CODEC_DEFAULTS.items():
            text = _PARAM_HELP.get(name, _CODEC_HELP.get(name))
            parser.add_argument(f"--{name.replace('_', '-')}", dest=name, type=float,
                                default=None, help=f"{text} (default {default:g})")
        parser.add_argument("--max-error", dest="max_error", type=float, default=None,
                            help="rate control: mean angle error bound in degrees; the codec "
                                 "then chooses every setting itself")
        return
    for name, default in DEFAULTS.items():
        parser.add_argument(f"--{name.replace('_', '-')}", dest=name, type=float, default=None,
                            help=f"{(notes or _PARAM_HELP).get(name, _PARAM_HELP[name])} "
                                 f"(default {default:g})")


#: Frames a motion needs to be segmented (segment, compress, evaluate, plot): a frame's state
#: is the sign of its velocity and its acceleration, and an acceleration takes three frames.
MIN_FRAMES = 3


def _read(args, path: str, *, enough: bool = True):
    """Read a motion file, with ``--frame-rate`` for AMC (a BVH file states its own rate);
    ``enough``: refuse one of fewer than :data:`MIN_FRAMES` frames."""
    from ._frame_rate_option import frame_rate_options
    from .readers import read
    motion = read(path, **frame_rate_options(args, path))
    if enough:
        _enough_frames(motion, path, args)
    return motion


def _enough_frames(motion, path: str, args, span: str = "") -> None:
    """One line, not an empty actiongram (or a traceback), for a motion too short to segment."""
    from .motion import MotionFormatError
    if motion.frames < MIN_FRAMES:
        command = getattr(args, "kinetology_command", None) or args.command
        raise MotionFormatError(
            f"{span.strip() + ': ' if span else ''}{motion.frames} "
            f"frame{'s' * (motion.frames != 1)}, but {command} needs at least {MIN_FRAMES} (a "
            f"state is the sign of a velocity and an acceleration, and an acceleration takes "
            f"{MIN_FRAMES} frames)", source=path)


def _params(args, names) -> dict:
    return {n: getattr(args, n) for n in names if getattr(args, n, None) is not None}


def _write(text: str, out: str | None) -> None:
    if out in (None, "-"):
        sys.stdout.write(text)
    else:
        Path(out).write_text(text)


def _keep_inputs(output: str | None, inputs) -> None:
    """Refuse an output that is one of the input files: writing it destroyed the take (and
    compress then reported the size of its own output as the original's)."""
    if output in (None, "-") or not Path(output).exists():
        return
    for name in inputs:
        if name and Path(name).exists() and os.path.samefile(output, name):
            raise ValidationError(f"-o {output} is the input {name}, which writing would "
                                  f"destroy; give another output")


def _is_folder(output: str) -> bool:
    """Whether ``-o`` names a folder: ``DIR/`` or an existing directory."""
    return output.endswith(("/", os.sep)) or Path(output).is_dir()


def _segment_checks(args) -> list[str] | None:
    """The channels asked for (None: every angle); the options' refusals, before any work."""
    from ._option_checks import check_segment_options
    channels = None
    if args.channels:
        channels = [c for item in args.channels for c in item.split(",") if c]
        if not channels:  # an empty list segmented nothing: an actiongram of its header alone
            raise ValidationError(f"--channels {' '.join(args.channels)!r} names no channel")
    if not args.labels:  # they choose among the spans of a label file, and there is none
        given = [o for o, v in (("--label", args.label), ("--min-seconds", args.min_seconds))
                 if v is not None]
        if given:
            raise ValidationError(f"{' and '.join(given)} choose{'s' * (len(given) == 1)} "
                                  f"among the spans of --labels LABELS, which is not given")
    check_segment_options(args)  # the values too, before any file is read
    return channels


def _refuse_empty(grams, names, args, channels) -> None:
    """No actiongram without strings: psgs refuses to read one (``empty actiongram``)."""
    from .motion import MotionFormatError
    for name, ag in zip(names, grams):
        if not len(ag):
            limit = args.min_range if args.min_range is not None else DEFAULTS["min_range"]
            which = "none of the --channels given" if channels else "no angle channel"
            raise MotionFormatError(f"no channel left to segment: {which} moves by --min-range "
                                    f"{limit:g} degrees or more; nothing written", source=name)


def _cmd_segment(args) -> int:
    from .motion import counted
    from .performances import cut, segment_performances
    from .segmentation import segment

    channels = _segment_checks(args)
    if args.labels:
        return _segment_spans(args, channels)
    several = len(args.files) > 1
    out_dir = None
    if several or (args.output and _is_folder(args.output)):
        if not args.output or args.output == "-":
            raise ValidationError("several files make one actiongram each: give -o DIR/")
        if not _is_folder(args.output):  # a file name was made a folder of that name
            raise ValidationError(f"-o {args.output}: several files make one actiongram "
                                  f"each, in a folder: give -o {args.output}/")
        out_dir = Path(args.output)
    if out_dir is None:
        _keep_inputs(args.output, args.files)
    names = [Path(f).stem for f in args.files]
    if out_dir is not None and len(set(names)) != len(names):
        raise ValidationError("two files share a name; their actiongrams would overwrite each other")
    motions, spans = [], []
    for name in args.files:
        motion = _read(args, name)
        span = ""
        if args.start is not None or args.stop is not None:
            motion = cut(motion, args.start, args.stop)
            first, last = motion.meta["cut"]
            span = f" from {first:g} s to {last:g} s"
            _enough_frames(motion, name, args, span)
        motions.append(motion)
        spans.append(span)
    if several:  # performances of one action: the same strings in every actiongram
        grams = segment_performances(motions, channels, **_params(args, DEFAULTS))
    else:
        grams = [segment(motions[0], channels, **_params(args, DEFAULTS))]
    _refuse_empty(grams, args.files, args, channels)
    if out_dir is not None:
        out_dir.mkdir(parents=True, exist_ok=True)
    for name, motion, span, ag in zip(args.files, motions, spans, grams):
        header = (f"# kinetology segment {Path(name).name}{span}: {motion.frames} frames at "
                  f"{motion.frame_rate:g} fps; states B(+,+) G(+,-) R(-,-) Y(-,+) of "
                  f"(velocity, acceleration); durations in seconds\n")
        if out_dir is None:
            _write(header + ag.to_text(), args.output)
        else:
            target = out_dir / f"{Path(name).stem}.actiongram"
            target.write_text(header + ag.to_text())
            print(f"{target}: {counted(len(ag), 'string')}, "
                  f"{counted(ag.total_symbols, 'kineteme')}")
    return 0


def _segment_spans(args, channels) -> int:
    """One actiongram per labelled span of one take: DIR/TAKE-LABEL-K.actiongram."""
    from .labels import spans_of
    from .motion import counted
    from .performances import from_spans, segment_performances

    if len(args.files) != 1 or not args.output or args.output == "-":
        raise ValidationError("--labels cuts one take into performances: give one FILE and -o DIR/")
    if not _is_folder(args.output):  # a file name was made a folder of that name
        raise ValidationError(f"-o {args.output}: --labels writes one actiongram per span, in a "
                              f"folder: give -o {args.output}/")
    if args.start is not None or args.stop is not None:
        raise ValidationError("--labels and --start/--stop do not go together")
    min_seconds = args.min_seconds if args.min_seconds is not None else 0.0
    motion = _read(args, args.files[0])
    spans = spans_of(args.labels, motion.frame_rate)
    parts = from_spans(motion, spans, args.label, min_seconds=min_seconds,
                       source=args.labels)
    _note_unlabelled_end(args, motion, spans)
    short = [p for p in parts if p.frames < MIN_FRAMES]  # no acceleration to segment by
    if short:
        print(f"kinetology: left out {len(short)} span{'s' * (len(short) != 1)} of fewer than "
              f"{MIN_FRAMES} frames in {args.labels}", file=sys.stderr)
        parts = [p for p in parts if p.frames >= MIN_FRAMES]
    if not parts:
        raise ValidationError(f"no span{' labelled ' + repr(args.label) if args.label else ''} of "
                         f"at least {min_seconds:g} s in {args.labels}")
    grams = segment_performances(parts, channels, **_params(args, DEFAULTS))
    _refuse_empty(grams, args.files * len(parts), args, channels)
    out_dir = Path(args.output)
    out_dir.mkdir(parents=True, exist_ok=True)
    count: dict[str, int] = {}
    for part, ag in zip(parts, grams):
        label = part.meta["label"]
        count[label] = count.get(label, 0) + 1
        first, last = part.meta["cut"]
        target = out_dir / f"{Path(args.files[0]).stem}-{label}-{count[label]}.actiongram"
        target.write_text(f"# kinetology segment {Path(args.files[0]).name} from {first:g} s "
                          f"to {last:g} s ({label}): {part.frames} frames at "
                          f"{part.frame_rate:g} fps; durations in seconds\n" + ag.to_text())
        print(f"{target}: {label} {first:g}-{last:g} s, {counted(len(ag), 'string')}")
    return 0


def _note_unlabelled_end(args, motion, spans) -> None:
    """Say that the labels end well before the take does (more than the labels' rounding,
    :func:`~kinetology.performances.overshoot`): the rest of the take is in no span, so no
    actiongram holds it. A note, not an error: the spans there are cut as labelled, and a label
    file may mark only the start of a take (a label is an action, and there is none for "no
    action"); but labels of a shorter take would otherwise cut this one without a word. (Labels
    reaching past the end are refused: they cannot be cut.)"""
    from .performances import overshoot

    if not spans:  # none at all: the error that no span is left says so
        return
    reach = max(span.stop for span in spans)
    if reach < motion.duration - overshoot(motion):
        print(f"kinetology: note: the labels in {args.labels} end at {reach:g} s, "
              f"{motion.duration - reach:.3g} s before the end of {args.files[0]} "
              f"({motion.duration:g} s): the rest is in no span and not segmented (labels "
              f"of a shorter take?)", file=sys.stderr)


def _cmd_compress(args) -> int:
    from ._option_checks import check_codec_options
    from .codec import compress

    out = args.output or str(Path(args.file).with_suffix(".kin"))
    _keep_inputs(out, [args.file])
    params = _params(args, CODEC_DEFAULTS)
    if args.max_error is not None and params:
        raise ValidationError(f"--max-error chooses the settings itself; drop "
                         f"{', '.join('--' + n.replace('_', '-') for n in sorted(params))}")
    check_codec_options(params, args.max_error)  # before the take is read, as evaluate's
    motion = _read(args, args.file)
    data = compress(motion, max_error=args.max_error, **params)  # refusals: ValidationError
    Path(out).write_bytes(data)
    size = Path(args.file).stat().st_size
    print(f"{out}: {len(data)} bytes, {100 * len(data) / size:.3f}% of {args.file}; mean "
          f"angle error {data.mean_error:.4f} deg (all channels {data.mean_error_all:.4f})")
    return 0


def _note_other_rate(args, original, motion) -> None:
    """Say that ``--against`` is at another frame rate than the compressed motion: its frames
    are compared one to one all the same (the same count), which is the take's own frames when
    only the rate was read differently (an AMC file states none), but a user comparing against
    a take at another rate would otherwise read the error as that of this one, in silence."""
    from .motion import counted
    if original.frame_rate == motion.frame_rate:
        return
    hint = (f"; an AMC file states no rate: --frame-rate {motion.frame_rate:g} reads it at the "
            f"compressed one" if Path(args.against).suffix.lower() == ".amc" else "")
    print(f"kinetology: note: {args.against} is at {original.frame_rate:g} fps, {args.file} at "
          f"{motion.frame_rate:g} fps: their {counted(motion.frames, 'frame')} "
          f"{'is' if motion.frames == 1 else 'are'} compared one to one{hint}", file=sys.stderr)


def _cmd_decompress(args) -> int:
    import numpy as np

    from .codec import decompress
    from .motion import MotionFormatError

    _keep_inputs(args.output, [args.file, args.against])
    # read_bytes: a device (/dev/zero) is refused, not read until memory runs out
    motion = decompress(read_bytes(args.file), source=args.file)
    if args.against:  # compared before the CSV is written: a mismatch is an error, not a tail
        original = _read(args, args.against, enough=False)  # compared, not segmented
        if original.values.shape != motion.values.shape:
            raise MotionFormatError(f"{args.against} has shape {original.values.shape} at "
                                    f"{original.frame_rate:g} fps, the decoded motion "
                                    f"{motion.values.shape} at {motion.frame_rate:g} fps",
                                    source=args.file)
        if original.channels != motion.channels:
            original = original.select(motion.channels)  # NotFound naming a missing channel
        _note_other_rate(args, original, motion)
    lines = ["time," + ",".join(motion.channels)]
    t = np.arange(motion.frames) / motion.frame_rate
    for time, row in zip(t, motion.values):
        lines.append(f"{time:.6g}," + ",".join(f"{v:.4f}" for v in row))
    _write("\n".join(lines) + "\n", args.output)
    if args.against:
        from .codec import mean_errors
        angles, every = mean_errors(original, motion)
        print(f"mean absolute error {every:.4f} over all channels, {angles:.4f} deg over "
              f"angles (rotation channels compared modulo 360)", file=sys.stderr)
    return 0


def _cmd_evaluate(args) -> int:
    import numpy as np

    from .evaluation import (MAX_VIEWS, angle_table, codec_point, mocap6_performances,
                             reproducibility, selectivity, view_invariance)
    from .kinematics import measurable_positions
    from .motion import MotionFormatError, counted
    from .segmentation import _check as check_parameters, segments

    if not args.files and not args.mocap6:
        raise MotionFormatError("nothing to evaluate: give motion files and/or --mocap6 DIR",
                                source="kinetology evaluate")
    if not 1 <= args.views <= MAX_VIEWS:  # refused before the report, not after it
        raise ValidationError(f"--views must be a whole number from 1 to {MAX_VIEWS}, not "
                              f"{args.views}")
    params = _params(args, DEFAULTS)
    check_parameters(params)
    # every file read (and cmu-mocap6 with it) before the first line of the report: a bad
    # file is then one line of error, not the tail of a report
    motions = [_read(args, name) for name in args.files]
    for motion in motions:  # a skeleton too large to measure angles on (1e307s), likewise
        if angle_table(motion.skeleton):
            measurable_positions(motion)
    mocap6 = mocap6_performances(args.mocap6) if args.mocap6 else None
    # segmented and compressed before the first line too, and cmu-mocap6 described: values
    # too large to difference or to code in 62 bits (1e307s) refuse a take, in one line naming
    # it, not after the report of the files before it (view-invariance's angles are bounded)
    measured = [(segments(motion, **params),
                 # the codec's own settings only: it always unwraps, and keeps every channel
                 codec_point(motion, Path(name).stat().st_size,
                             **{k: v for k, v in params.items() if k in CODEC_DEFAULTS}))
                for name, motion in zip(args.files, motions)]
    if mocap6 is not None:
        takes, perfs = mocap6
        first = next(iter(takes.values()))
        channels = [c for c in first.channels if c.rsplit(".", 1)[-1] not in ("tx", "ty", "tz")]
        # a description's own still threshold (5 degrees), not --min-range: the option, given
        # at its default of 2, changed the tables from those it gives when left out
        described = {k: v for k, v in params.items() if k != "min_range"}
        repro = reproducibility(takes, perfs, channels, **described)
        sel = selectivity(takes, perfs, channels, **described)
    for name, motion, (seg, point) in zip(args.files, motions, measured):
        print(f"{name}: {counted(motion.frames, 'frame')}, "
              f"{counted(len(motion.channels), 'channel')} at {motion.frame_rate:g} fps")
        durations = [seg.durations(c) for c in range(len(seg.channels))]
        mean_duration = float(np.mean(np.concatenate(durations))) if durations else 0.0
        print(f"  segments: {seg.segment_count} in {counted(len(seg.channels), 'moving channel')} "
              f"({len(seg.still)} still), mean duration {mean_duration:.3f} s")
        print(f"  compactness: {point['bytes']} bytes = {point['percent']:.3f}% of the file "
              f"(paper: 3.698%)")
        print(f"  reconstructivity: mean |error| {point['mae']:.3f} over all channels, "
              f"{point['mae_angles']:.3f} deg over angles (paper: 0.823 deg)")
        table = angle_table(motion.skeleton)
        if table:
            scores = []
            for angle, triple in table.items():
                vi = view_invariance(motion, triple, views=args.views, **params)
                scores.append(f"{angle} {100 * vi.agreement:.1f}%")
            print(f"  view-invariance (2D state = 3D state, {counted(args.views, 'view')}): "
                  + ", ".join(scores))
        else:
            print("  view-invariance: needs a skeleton with CMU or Bandai Namco joint names")
    if mocap6 is not None:
        _print_mocap6(args.mocap6, perfs, repro, sel)
    return 0


def _print_mocap6(folder, perfs, repro, sel) -> None:
    """The reproducibility and selectivity lines of ``evaluate --mocap6``."""
    import numpy as np

    from .motion import counted
    print(f"reproducibility ({folder}, {counted(len(perfs), 'performance')}): mean over channels")
    for action, row in repro.items():
        mean = np.mean([v[0] for v in row.values()])
        print(f"  {action}: {100 * mean:.1f}% "
              f"({counted(next(iter(row.values()))[2], 'performance')})")
    if not repro:  # an action's performances are compared with each other: one is no comparison
        print("  no action has two performances or more")
    actions = sorted({perf.action for perf in perfs})
    if len(actions) < 2:
        # selectivity tells actions apart: one action has no pair to compare (their mean is
        # a mean of nothing, nan), and a lone performance has no nearest other to be right on
        here = (f"{counted(len(perfs), 'performance')} here, "
                f"{'of' if len(perfs) == 1 else 'all of'} {actions[0]}") if perfs else \
            "no performance here: no run of one label lasts 2 s"
        print(f"selectivity: n/a, needs performances of two actions or more ({here})")
        return
    print(f"selectivity: nearest performance of the same action "
          f"{100 * sel['nearest_neighbour_accuracy']:.1f}% (chance "
          f"{100 * sel['chance']:.1f}%); channels described differently, mean over "
          f"action pairs {100 * np.mean(list(sel['pairwise'].values())):.1f}%")


def _cmd_plot(args) -> int:
    from . import plotting
    from ._option_checks import check_codec_options
    from .motion import MotionFormatError
    from .segmentation import _check as check_parameters

    plotting.check_output(args.output)  # matplotlib refuses a suffix only once the work is done
    params = _params(args, DEFAULTS)
    if args.kind == "view" and "min_range" in params:  # it was dropped without a word
        raise ValidationError("--kind view: --min-range does not apply (the angle's states "
                              "are compared in every view whatever its range); drop it")
    foreign = sorted(set(params) - set(CODEC_DEFAULTS))  # compress raised a TypeError for them
    if args.kind == "reconstruction" and foreign:
        raise ValidationError(f"--kind reconstruction: the codec has no setting "
                              f"{', '.join('--' + n.replace('_', '-') for n in foreign)}")
    if args.kind == "reconstruction":  # the values before the take is read, as evaluate's
        check_codec_options(params)
    else:
        check_parameters(params)
    motion = _read(args, args.file)
    if args.kind == "states":
        fig = plotting.plot_states(motion, args.channel, start=args.start, stop=args.stop,
                                   **params)
    elif args.kind == "reconstruction":
        from .codec import compress, decompress
        decoded = decompress(compress(motion, **params))
        fig = plotting.plot_reconstruction(motion, decoded, args.channel, start=args.start,
                                           stop=args.stop)
    else:
        from .evaluation import angle_table, view_invariance
        table = angle_table(motion.skeleton)
        if args.channel not in table:
            raise MotionFormatError(f"--kind view needs a skeleton with CMU or Bandai Namco "
                                    f"joint names and --channel one of "
                                    f"{', '.join(table) or 'lknee, rknee, ...'}",
                                    source=args.file)
        result = view_invariance(motion, table[args.channel], **params)
        fig = plotting.plot_view_invariance(result, f"{args.channel}, {Path(args.file).name}",
                                            motion.frame_rate, start=args.start, stop=args.stop)
    plotting.save(fig, args.output)
    print(args.output)
    return 0


def _add_commands(sub) -> None:
    """Add segment, compress, decompress, evaluate and plot under ``sub``."""
    p = sub.add_parser("segment", help="segment motion files into actiongrams (text form), "
                                       "one per file (one performance each)")
    p.add_argument("files", nargs="+", metavar="FILE", type=file_name,
                   help=_FILE_HELP + "; several files are performances of one action")
    p.add_argument("--frame-rate", type=positive_float, metavar="FPS", help=_FRAME_RATE_HELP)
    p.add_argument("--channels", nargs="+", help="channels to keep (names or comma lists)")
    p.add_argument("--start", type=float, default=None,
                   help="seconds: segment only from here (a performance within a take)")
    p.add_argument("--stop", type=float, default=None, help="seconds: segment only up to here")
    p.add_argument("--labels", type=file_name,
                   help="label file of the take (CMU mocap6 truelabels .txt or Bandai Namco "
                        ".json): one actiongram per labelled span")
    p.add_argument("--label", help="with --labels: only spans with this label")
    p.add_argument("--min-seconds", type=float, default=None,
                   help="with --labels: leave out spans shorter than this (default 0)")
    p.add_argument("-o", "--output", type=file_name,
                   help="output file (default: stdout); with several files a folder, DIR/, "
                        "holding NAME.actiongram per file")
    _add_params(p)
    p.set_defaults(run=_cmd_segment)

    p = sub.add_parser("compress", help="compress a motion file by segments")
    p.add_argument("file", type=file_name, help=_FILE_HELP)
    p.add_argument("--frame-rate", type=positive_float, metavar="FPS", help=_FRAME_RATE_HELP)
    p.add_argument("-o", "--output", type=file_name,
                   help="output file (default: FILE with suffix .kin)")
    _add_params(p, codec=True)
    p.set_defaults(run=_cmd_compress)

    p = sub.add_parser("decompress", help="reconstruct a compressed motion as CSV")
    p.add_argument("file", type=file_name, help="a .kin file written by kinetology compress")
    p.add_argument("-o", "--output", type=file_name, help="CSV output (default: stdout)")
    p.add_argument("--against", type=file_name,
                   help="original motion file: print the mean absolute error, frame by frame "
                        "(its frames and channels must be the decoded motion's; at another "
                        "frame rate it is compared all the same, with a note on stderr)")
    p.add_argument("--frame-rate", type=positive_float, metavar="FPS",
                   help="--against: " + _FRAME_RATE_HELP)
    p.set_defaults(run=_cmd_decompress)

    p = sub.add_parser("evaluate", help="measure the five kinetological principles")
    p.add_argument("files", nargs="*", metavar="FILE", type=file_name,
                   help=_FILE_HELP + " (any number)")
    p.add_argument("--frame-rate", type=positive_float, metavar="FPS", help=_FRAME_RATE_HELP)
    p.add_argument("--mocap6", type=file_name,
                   help="cmu-mocap6 folder: reproducibility and selectivity")
    p.add_argument("--views", type=int, default=36, help="viewpoints on the circle")
    _add_params(p, notes=_EVALUATE_NOTES)
    p.set_defaults(run=_cmd_evaluate)

    p = sub.add_parser("plot", help="draw a joint angle by state, its reconstruction, or "
                                    "the view-invariance picture")
    p.add_argument("file", type=file_name, help=_FILE_HELP)
    p.add_argument("--frame-rate", type=positive_float, metavar="FPS", help=_FRAME_RATE_HELP)
    p.add_argument("--channel", required=True,
                   help="channel (states, reconstruction) or angle name such as lknee (view)")
    p.add_argument("--kind", choices=("states", "reconstruction", "view"), default="states",
                   help="states: the angle coloured by state (default); reconstruction: the "
                        "angle and its decoded copy; view: 2D against 3D states around a circle")
    p.add_argument("--start", type=float, default=0.0, help="seconds")
    p.add_argument("--stop", type=float, default=None, help="seconds")
    p.add_argument("-o", "--output", required=True, type=file_name,
                   help="image file (.png, .svg, .pdf)")
    _add_params(p, notes=_PLOT_NOTES)
    p.set_defaults(run=_cmd_plot)
    from ._viewer_cli import register as register_view  # kinetology view: the skeleton player
    register_view(sub)


_DESCRIPTION = ("Motion capture (BVH, ASF/AMC) in, actiongrams out; compression by segments; "
                "the paper's kinetological principles measured.")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``kinetology`` command (one subparser per subcommand)."""
    parser = argparse.ArgumentParser(prog="kinetology", description=_DESCRIPTION)
    add_version(parser)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True,
                                help="the subcommand (COMMAND --help for its options)")
    _add_commands(sub)
    with_exit_status_help(parser)
    return parser


def register(subparsers) -> None:
    """Add ``kinetology`` (segment, compress, ...) to psgs's subcommands (``psgs.commands``)."""
    parser = subparsers.add_parser("kinetology", help="motion capture in, actiongrams out",
                                   description=_DESCRIPTION)
    sub = parser.add_subparsers(dest="kinetology_command", metavar="COMMAND", required=True,
                                help="the subcommand (COMMAND --help for its options)")
    _add_commands(sub)


def main(argv: list[str] | None = None) -> int:
    """Run the ``kinetology`` command; returns the exit status (the shell's table)."""
    return run(build_parser(), argv)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
