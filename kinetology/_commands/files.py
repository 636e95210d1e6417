"""What the kinetology commands' handlers share: a take read for a command (and refused when
too short to segment), the settings given on the command line, the output written, and an
output refused that is one of the inputs.

Each helper imports the modules that read motions when it runs, not when the parser is made.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from psgs.errors import ValidationError

__all__ = ["MIN_FRAMES", "read_motion", "enough_frames", "given_params", "write_output",
           "keep_inputs", "is_folder"]

#: Frames a motion needs to be segmented (segment, compress, evaluate, plot): a frame's state
#: is the sign of its velocity and its acceleration, and an acceleration takes three frames.
MIN_FRAMES = 3


def read_motion(args, path: str, *, enough: bool = True):
    """Read a motion file, with ``--frame-rate`` for AMC (a BVH file states its own rate);
    ``enough``: refuse one of fewer than :data:`MIN_FRAMES` frames."""
    from .._frame_rate_option import frame_rate_options
    from ..readers import read
    motion = read(path, **frame_rate_options(args, path))
    if enough:
        enough_frames(motion, path, args)
    return motion


def enough_frames(motion, path: str, args, span: str = "") -> None:
    """One line, not an empty actiongram (or a traceback), for a motion too short to segment."""
    from ..motion import MotionFormatError
    if motion.frames < MIN_FRAMES:
        command = getattr(args, "kinetology_command", None) or args.command
        raise MotionFormatError(
            f"{span.strip() + ': ' if span else ''}{motion.frames} "
            f"frame{'s' * (motion.frames != 1)}, but {command} needs at least {MIN_FRAMES} (a "
            f"state is the sign of a velocity and an acceleration, and an acceleration takes "
            f"{MIN_FRAMES} frames)", source=path)


def given_params(args, names) -> dict:
    """The settings among ``names`` given on the command line (those left out: the defaults)."""
    return {n: getattr(args, n) for n in names if getattr(args, n, None) is not None}


def write_output(text: str, out: str | None) -> None:
    """``text`` to the file ``out``, or to stdout for None or ``-``."""
    if out in (None, "-"):
        sys.stdout.write(text)
    else:
        Path(out).write_text(text)


def keep_inputs(output: str | None, inputs) -> None:
    """Refuse an output that is one of the input files: writing it destroyed the take (and
    compress then reported the size of its own output as the original's)."""
    if output in (None, "-") or not Path(output).exists():
        return
    for name in inputs:
        if name and Path(name).exists() and os.path.samefile(output, name):
            raise ValidationError(f"-o {output} is the input {name}, which writing would "
                                  f"destroy; give another output")


def is_folder(output: str) -> bool:
    """Whether ``-o`` names a folder: ``DIR/`` or an existing directory."""
    return output.endswith(("/", os.sep)) or Path(output).is_dir()
