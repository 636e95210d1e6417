"""``kinetology evaluate``: the five kinetological principles measured on motion files, and
with ``--mocap6`` reproducibility and selectivity on cmu-mocap6."""

from __future__ import annotations

from pathlib import Path

from psgs._foundation.shell import file_name, positive_float
from psgs.errors import ValidationError

from .._defaults import CODEC_DEFAULTS, DEFAULTS
from .files import given_params, read_motion
from .options import FILE_HELP, FRAME_RATE_HELP, add_params

__all__ = ["register", "run_evaluate"]

#: ``evaluate --min-range`` counts the segments of the moving channels; the mocap6 descriptions
#: keep their own threshold (:func:`kinetology.evaluation.describe`).
_EVALUATE_NOTES = {
    "min_range": "channels moving less than this many degrees are left out of the segment "
                 "count (--mocap6's descriptions call a channel still below 5 degrees, "
                 "whatever this is)",
}


def register(sub) -> None:
    """Add ``evaluate`` under ``sub``."""
    p = sub.add_parser("evaluate", help="measure the five kinetological principles")
    p.add_argument("files", nargs="*", metavar="FILE", type=file_name,
                   help=FILE_HELP + " (any number)")
    p.add_argument("--frame-rate", type=positive_float, metavar="FPS", help=FRAME_RATE_HELP)
    p.add_argument("--mocap6", type=file_name,
                   help="cmu-mocap6 folder: reproducibility and selectivity")
    p.add_argument("--views", type=int, default=36, help="viewpoints on the circle")
    add_params(p, notes=_EVALUATE_NOTES)
    p.set_defaults(run=run_evaluate)


def run_evaluate(args) -> int:
    """Run ``kinetology evaluate``; the exit status."""
    import numpy as np

    from ..evaluation import (MAX_VIEWS, angle_table, codec_point, mocap6_performances,
                              reproducibility, selectivity, view_invariance)
    from ..kinematics import measurable_positions
    from ..motion import MotionFormatError, counted
    from ..segmentation import _check as check_parameters, segments

    if not args.files and not args.mocap6:
        raise MotionFormatError("nothing to evaluate: give motion files and/or --mocap6 DIR",
                                source="kinetology evaluate")
    if not 1 <= args.views <= MAX_VIEWS:  # refused before the report, not after it
        raise ValidationError(f"--views must be a whole number from 1 to {MAX_VIEWS}, not "
                              f"{args.views}")
    params = given_params(args, DEFAULTS)
    check_parameters(params)
    # every file read (and cmu-mocap6 with it) before the first line of the report: a bad
    # file is then one line of error, not the tail of a report
    motions = [read_motion(args, name) for name in args.files]
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

    from ..motion import counted
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
