"""The options several kinetology commands share, with their help texts: the motion file, the
AMC frame rate, the segmentation's settings and the codec's.

Only the defaults the help texts print are imported (:mod:`kinetology._defaults`, numpy-free):
making the parser does not load the modules that work with them.
"""

from __future__ import annotations

from .._defaults import CODEC_DEFAULTS, DEFAULTS, MIN_UNWRAP

__all__ = ["FILE_HELP", "FRAME_RATE_HELP", "PARAM_HELP", "add_params"]

FILE_HELP = "a motion file: .bvh, or .amc (its .asf skeleton is found beside it)"
FRAME_RATE_HELP = ("frames per second of an AMC file (AMC files do not say; default 120, the "
                   "CMU rate); a BVH file states its own")

PARAM_HELP = {
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


def add_params(parser, *, codec: bool = False, notes=None) -> None:
    """The segmentation options (or with ``codec`` the codec's); ``notes``: help texts that
    replace :data:`PARAM_HELP`'s for this command."""
    if codec:  # the codec pins its own settings: its defaults, not the segmentation's
        for name, default in CODEC_DEFAULTS.items():
            text = PARAM_HELP.get(name, _CODEC_HELP.get(name))
            parser.add_argument(f"--{name.replace('_', '-')}", dest=name, type=float,
                                default=None, help=f"{text} (default {default:g})")
        parser.add_argument("--max-error", dest="max_error", type=float, default=None,
                            help="rate control: mean angle error bound in degrees; the codec "
                                 "then chooses every setting itself")
        return
    for name, default in DEFAULTS.items():
        parser.add_argument(f"--{name.replace('_', '-')}", dest=name, type=float, default=None,
                            help=f"{(notes or PARAM_HELP).get(name, PARAM_HELP[name])} "
                                 f"(default {default:g})")
