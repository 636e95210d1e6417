"""``kinetology plot``: a joint angle coloured by state, its reconstruction by the codec, or
the view-invariance picture of an angle, as an image file."""

from __future__ import annotations

from pathlib import Path

from psgs._foundation.shell import file_name, positive_float
from psgs.errors import ValidationError

from .._defaults import CODEC_DEFAULTS, DEFAULTS
from .files import given_params, read_motion
from .options import FILE_HELP, FRAME_RATE_HELP, PARAM_HELP, add_params

__all__ = ["register", "run_plot"]

#: What the segmentation options mean to ``plot`` where it differs from ``segment``: the codec
#: (``--kind reconstruction``) has no min_range, relative dead band or unwrapping, and a view
#: angle is compared whatever its range.
_PLOT_NOTES = {
    "min_range": "--kind states: a channel moving less than this many degrees is still (segment "
                 "leaves it out) and drawn grey, without states; an error with reconstruction "
                 "and view",
    "relative_deadband": PARAM_HELP["relative_deadband"] + "; not with --kind reconstruction",
    "unwrap": PARAM_HELP["unwrap"] + "; not with --kind reconstruction",
}


def register(sub) -> None:
    """Add ``plot`` under ``sub``."""
    p = sub.add_parser("plot", help="draw a joint angle by state, its reconstruction, or "
                                    "the view-invariance picture")
    p.add_argument("file", type=file_name, help=FILE_HELP)
    p.add_argument("--frame-rate", type=positive_float, metavar="FPS", help=FRAME_RATE_HELP)
    p.add_argument("--channel", required=True,
                   help="channel (states, reconstruction) or angle name such as lknee (view)")
    p.add_argument("--kind", choices=("states", "reconstruction", "view"), default="states",
                   help="states: the angle coloured by state (default); reconstruction: the "
                        "angle and its decoded copy; view: 2D against 3D states around a circle")
    p.add_argument("--start", type=float, default=0.0, help="seconds")
    p.add_argument("--stop", type=float, default=None, help="seconds")
    p.add_argument("-o", "--output", required=True, type=file_name,
                   help="image file (.png, .svg, .pdf)")
    add_params(p, notes=_PLOT_NOTES)
    p.set_defaults(run=run_plot)


def run_plot(args) -> int:
    """Run ``kinetology plot``; the exit status."""
    from .. import plotting
    from .._option_checks import check_codec_options
    from ..motion import MotionFormatError
    from ..segmentation import _check as check_parameters

    plotting.check_output(args.output)  # matplotlib refuses a suffix only once the work is done
    params = given_params(args, DEFAULTS)
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
    motion = read_motion(args, args.file)
    if args.kind == "states":
        fig = plotting.plot_states(motion, args.channel, start=args.start, stop=args.stop,
                                   **params)
    elif args.kind == "reconstruction":
        from ..codec import compress, decompress
        decoded = decompress(compress(motion, **params))
        fig = plotting.plot_reconstruction(motion, decoded, args.channel, start=args.start,
                                           stop=args.stop)
    else:
        from ..evaluation import angle_table, view_invariance
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
