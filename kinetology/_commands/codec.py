"""``kinetology compress`` and ``decompress``: a motion file coded by segments, and the code
read back as CSV (compared, with ``--against``, with the original)."""

from __future__ import annotations

import sys
from pathlib import Path

from psgs._foundation.files import read_bytes
from psgs._foundation.shell import file_name, positive_float
from psgs.errors import ValidationError

from .._defaults import CODEC_DEFAULTS
from .files import given_params, keep_inputs, read_motion, write_output
from .options import FILE_HELP, FRAME_RATE_HELP, add_params

__all__ = ["register", "run_compress", "run_decompress"]


def register(sub) -> None:
    """Add ``compress`` and ``decompress`` under ``sub``."""
    p = sub.add_parser("compress", help="compress a motion file by segments")
    p.add_argument("file", type=file_name, help=FILE_HELP)
    p.add_argument("--frame-rate", type=positive_float, metavar="FPS", help=FRAME_RATE_HELP)
    p.add_argument("-o", "--output", type=file_name,
                   help="output file (default: FILE with suffix .kin)")
    add_params(p, codec=True)
    p.set_defaults(run=run_compress)

    p = sub.add_parser("decompress", help="reconstruct a compressed motion as CSV")
    p.add_argument("file", type=file_name, help="a .kin file written by kinetology compress")
    p.add_argument("-o", "--output", type=file_name, help="CSV output (default: stdout)")
    p.add_argument("--against", type=file_name,
                   help="original motion file: print the mean absolute error, frame by frame "
                        "(its frames and channels must be the decoded motion's; at another "
                        "frame rate it is compared all the same, with a note on stderr)")
    p.add_argument("--frame-rate", type=positive_float, metavar="FPS",
                   help="--against: " + FRAME_RATE_HELP)
    p.set_defaults(run=run_decompress)


def run_compress(args) -> int:
    """Run ``kinetology compress``; the exit status."""
    from .._option_checks import check_codec_options
    from ..codec import compress

    out = args.output or str(Path(args.file).with_suffix(".kin"))
    keep_inputs(out, [args.file])
    params = given_params(args, CODEC_DEFAULTS)
    if args.max_error is not None and params:
        raise ValidationError(f"--max-error chooses the settings itself; drop "
                         f"{', '.join('--' + n.replace('_', '-') for n in sorted(params))}")
    check_codec_options(params, args.max_error)  # before the take is read, as evaluate's
    motion = read_motion(args, args.file)
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
    from ..motion import counted
    if original.frame_rate == motion.frame_rate:
        return
    hint = (f"; an AMC file states no rate: --frame-rate {motion.frame_rate:g} reads it at the "
            f"compressed one" if Path(args.against).suffix.lower() == ".amc" else "")
    print(f"kinetology: note: {args.against} is at {original.frame_rate:g} fps, {args.file} at "
          f"{motion.frame_rate:g} fps: their {counted(motion.frames, 'frame')} "
          f"{'is' if motion.frames == 1 else 'are'} compared one to one{hint}", file=sys.stderr)


def run_decompress(args) -> int:
    """Run ``kinetology decompress``; the exit status."""
    import numpy as np

    from ..codec import decompress
    from ..motion import MotionFormatError

    keep_inputs(args.output, [args.file, args.against])
    # read_bytes: a device (/dev/zero) is refused, not read until memory runs out
    motion = decompress(read_bytes(args.file), source=args.file)
    if args.against:  # compared before the CSV is written: a mismatch is an error, not a tail
        original = read_motion(args, args.against, enough=False)  # compared, not segmented
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
    write_output("\n".join(lines) + "\n", args.output)
    if args.against:
        from ..codec import mean_errors
        angles, every = mean_errors(original, motion)
        print(f"mean absolute error {every:.4f} over all channels, {angles:.4f} deg over "
              f"angles (rotation channels compared modulo 360)", file=sys.stderr)
    return 0
