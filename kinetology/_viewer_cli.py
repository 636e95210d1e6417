"""``kinetology view``: the skeleton player of :mod:`kinetology.viewer` on the command line."""

from __future__ import annotations

from pathlib import Path

from psgs._foundation.shell import file_name, positive_float

__all__ = ["register"]


def _run(args) -> int:
    # the player's modules load when it runs, not when the command's parser is made
    import numpy as np

    from ._frame_rate_option import frame_rate_options
    from ._viewer_checks import view_problem
    from .motion import counted
    from .readers import read
    from .viewer import ViewError, check_output, view

    check_output(Path(args.output))
    # the option values before any file is read, in view's own words (as the other commands)
    if problem := view_problem(args.max_rate, args.max_frames, True, True):
        raise ViewError(problem, source="kinetology.view")
    # --frame-rate with a BVH file is refused, as by the other commands, before any reading
    options = [frame_rate_options(args, name) for name in args.files]
    motions = [read(name, **o) for name, o in zip(args.files, options)]
    actuators = [a for item in args.actuators or () for a in item.split(",") if a]
    player = view(motions, args.output, actuators=actuators or None,
                  kinetemes=not args.no_kinetemes, max_rate=args.max_rate,
                  follow=not args.fixed_camera,
                  max_frames=args.max_frames)
    kept = ", ".join(f"{p.label}: {counted(p.frames, 'frame')} at {p.frame_rate:g} fps"
                     for p in player.panels)
    print(f"{args.output}: {kept}")
    for p in player.panels:  # a skeleton of angles only draws as a dot: said, not hidden
        if np.ptp(p.positions, axis=1).max() < 1e-9:
            print(f"{p.label}: every joint at one point (all offsets 0: a skeleton of angles "
                  f"only, as written for an AMC take without its ASF); the body is a dot")
    return 0


def register(subparsers) -> None:
    """Add ``view`` to a command's subparsers (the ``kinetology`` command).

    Examples
    --------
    >>> import argparse
    >>> parser = argparse.ArgumentParser(prog="kinetology")
    >>> register(parser.add_subparsers())
    >>> parser.parse_args(["view", "walk.bvh", "-o", "walk.html"]).max_rate
    30.0
    """
    p = subparsers.add_parser(
        "view", help="play motion files as a skeleton: an HTML page, a GIF or an MP4",
        description="Draw the body from the skeleton's forward kinematics and play it; several "
                    "files side by side on one clock; joints coloured by their current "
                    "kineteme. The HTML page is self-contained (opens from a file, no network). "
                    "Exit status 0: written; 2: a file that is not motion, a motion without "
                    "frames or skeleton, an output suffix other than .html/.gif/.mp4, or a "
                    "missing writer (matplotlib for .gif, ffmpeg for .mp4), in one line.")
    p.add_argument("files", nargs="+", metavar="FILE", type=file_name,
                   help="motion files: .bvh, or .amc (its .asf skeleton found beside it)")
    p.add_argument("-o", "--output", required=True, metavar="OUT", type=file_name,
                   help="out.html (player page), out.gif (needs matplotlib) or out.mp4 "
                        "(needs matplotlib and ffmpeg)")
    p.add_argument("--actuators", nargs="+", metavar="JOINT",
                   help="joints to highlight (names or comma lists)")
    p.add_argument("--no-kinetemes", action="store_true",
                   help="do not colour joints by state (skips the segmentation)")
    p.add_argument("--fixed-camera", action="store_true",
                   help="look at the middle of the whole path instead of following the body")
    p.add_argument("--max-rate", type=float, default=30.0, metavar="FPS",
                   help="most frames per second kept (default 30)")
    p.add_argument("--max-frames", type=int, default=500, metavar="N",
                   help="most frames kept per file (default 500)")
    p.add_argument("--frame-rate", type=positive_float, default=None, metavar="FPS",
                   help="frames per second of AMC files (default 120, the CMU rate; an error "
                        "with a BVH file, which states its own)")
    p.set_defaults(run=_run)
