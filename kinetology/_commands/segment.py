"""``kinetology segment``: motion files into actiongrams, one per file (performances of one
action: the same strings in each), or with ``--labels`` one per labelled span of a take."""

from __future__ import annotations

import sys
from pathlib import Path

from psgs._foundation.shell import file_name, positive_float
from psgs.errors import ValidationError

from .._defaults import DEFAULTS
from .files import (MIN_FRAMES, enough_frames, given_params, is_folder, keep_inputs,
                    read_motion, write_output)
from .options import FILE_HELP, FRAME_RATE_HELP, add_params

__all__ = ["register", "run_segment"]


def register(sub) -> None:
    """Add ``segment`` under ``sub`` (the kinetology command's subparsers)."""
    p = sub.add_parser("segment", help="segment motion files into actiongrams (text form), "
                                       "one per file (one performance each)")
    p.add_argument("files", nargs="+", metavar="FILE", type=file_name,
                   help=FILE_HELP + "; several files are performances of one action")
    p.add_argument("--frame-rate", type=positive_float, metavar="FPS", help=FRAME_RATE_HELP)
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
    add_params(p)
    p.set_defaults(run=run_segment)


def _segment_checks(args) -> list[str] | None:
    """The channels asked for (None: every angle); the options' refusals, before any work."""
    from .._option_checks import check_segment_options
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
    from ..motion import MotionFormatError
    for name, ag in zip(names, grams):
        if not len(ag):
            limit = args.min_range if args.min_range is not None else DEFAULTS["min_range"]
            which = "none of the --channels given" if channels else "no angle channel"
            raise MotionFormatError(f"no channel left to segment: {which} moves by --min-range "
                                    f"{limit:g} degrees or more; nothing written", source=name)


def run_segment(args) -> int:
    """Run ``kinetology segment``; the exit status."""
    from ..motion import counted
    from ..performances import cut, segment_performances
    from ..segmentation import segment

    channels = _segment_checks(args)
    if args.labels:
        return _segment_spans(args, channels)
    several = len(args.files) > 1
    out_dir = None
    if several or (args.output and is_folder(args.output)):
        if not args.output or args.output == "-":
            raise ValidationError("several files make one actiongram each: give -o DIR/")
        if not is_folder(args.output):  # a file name was made a folder of that name
            raise ValidationError(f"-o {args.output}: several files make one actiongram "
                                  f"each, in a folder: give -o {args.output}/")
        out_dir = Path(args.output)
    if out_dir is None:
        keep_inputs(args.output, args.files)
    names = [Path(f).stem for f in args.files]
    if out_dir is not None and len(set(names)) != len(names):
        raise ValidationError("two files share a name; their actiongrams would overwrite each other")
    motions, spans = [], []
    for name in args.files:
        motion = read_motion(args, name)
        span = ""
        if args.start is not None or args.stop is not None:
            motion = cut(motion, args.start, args.stop)
            first, last = motion.meta["cut"]
            span = f" from {first:g} s to {last:g} s"
            enough_frames(motion, name, args, span)
        motions.append(motion)
        spans.append(span)
    if several:  # performances of one action: the same strings in every actiongram
        grams = segment_performances(motions, channels, **given_params(args, DEFAULTS))
    else:
        grams = [segment(motions[0], channels, **given_params(args, DEFAULTS))]
    _refuse_empty(grams, args.files, args, channels)
    if out_dir is not None:
        out_dir.mkdir(parents=True, exist_ok=True)
    for name, motion, span, ag in zip(args.files, motions, spans, grams):
        header = (f"# kinetology segment {Path(name).name}{span}: {motion.frames} frames at "
                  f"{motion.frame_rate:g} fps; states B(+,+) G(+,-) R(-,-) Y(-,+) of "
                  f"(velocity, acceleration); durations in seconds\n")
        if out_dir is None:
            write_output(header + ag.to_text(), args.output)
        else:
            target = out_dir / f"{Path(name).stem}.actiongram"
            target.write_text(header + ag.to_text())
            print(f"{target}: {counted(len(ag), 'string')}, "
                  f"{counted(ag.total_symbols, 'kineteme')}")
    return 0


def _segment_spans(args, channels) -> int:
    """One actiongram per labelled span of one take: DIR/TAKE-LABEL-K.actiongram."""
    from ..labels import spans_of
    from ..motion import counted
    from ..performances import from_spans, segment_performances

    if len(args.files) != 1 or not args.output or args.output == "-":
        raise ValidationError("--labels cuts one take into performances: give one FILE and -o DIR/")
    if not is_folder(args.output):  # a file name was made a folder of that name
        raise ValidationError(f"-o {args.output}: --labels writes one actiongram per span, in a "
                              f"folder: give -o {args.output}/")
    if args.start is not None or args.stop is not None:
        raise ValidationError("--labels and --start/--stop do not go together")
    min_seconds = args.min_seconds if args.min_seconds is not None else 0.0
    motion = read_motion(args, args.files[0])
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
    grams = segment_performances(parts, channels, **given_params(args, DEFAULTS))
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
    from ..performances import overshoot

    if not spans:  # none at all: the error that no span is left says so
        return
    reach = max(span.stop for span in spans)
    if reach < motion.duration - overshoot(motion):
        print(f"kinetology: note: the labels in {args.labels} end at {reach:g} s, "
              f"{motion.duration - reach:.3g} s before the end of {args.files[0]} "
              f"({motion.duration:g} s): the rest is in no span and not segmented (labels "
              f"of a shorter take?)", file=sys.stderr)
