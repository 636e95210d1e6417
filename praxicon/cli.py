"""``psgs praxicon build|draw|generate|verify|recognise|parse``: the praxicon's command line.

Reached from ``psgs`` through the entry-point group ``psgs.commands``
(``praxicon = "praxicon.cli:register"``), and without an install as
``python -m praxicon``. Bad input is one line on stderr, never a traceback.
"""

from __future__ import annotations

import sys
from pathlib import Path

from psgs._foundation.engines import usable_cores
from psgs._foundation.shell import NO, file_name, key_values, positive_int
from psgs.errors import ValidationError

__all__ = ["register", "main"]


def _bad(message: str):
    raise ValidationError(message)


def run_build(args) -> int:
    from psgs.induce.registry import text_params

    from kinetology.motion import check_number
    from kinetology.segmentation import DEFAULTS

    from .builder import build, executor_for
    from .datasets import DatasetError, read_datasets
    from .learn import Settings

    # an unknown inducer or parameter: one line, now; none is None where that is the default
    params = text_params(args.inducer, key_values(args.param, "--param"))
    segmentation = key_values(args.segment, "--segment")
    unknown = sorted(set(segmentation) - set(DEFAULTS))
    if unknown:
        _bad(f"--segment {unknown[0]}: unknown (known: {', '.join(DEFAULTS)})")
    # the values as kinetology checks them: else every action of the build fails on them
    for key, value in segmentation.items():
        try:
            check_number(value, key)
        except ValueError as exc:
            _bad(f"--segment {exc}")
    try:
        actions = read_datasets(args.datasets, args.group_by)
    except DatasetError as exc:
        _bad(str(exc))
    if not actions:  # an empty folder of status 0 would be what a script chains on
        _bad(f"{', '.join(args.datasets)}: no action to learn in "
             f"{'it' if len(args.datasets) == 1 else 'them'}")
    settings = Settings.make(args.inducer, params, segmentation, args.min_performances)
    # no more processes than actions: a pool forks all of them at once, and a count past a
    # C int was a traceback from the semaphore
    workers = None if args.workers is None else min(args.workers, len(actions))
    try:
        executor, close = executor_for(workers, args.scheduler)
    except (ValueError, OSError) as exc:
        _bad(f"--scheduler {args.scheduler}: {exc}")
    try:
        result = build(actions, args.output, settings=settings, executor=executor,
                       progress=not args.no_progress, datasets=args.datasets)
    except BaseException:  # Ctrl-C or an error: the workers end now, not after their action
        close(stop=True)
        raise
    close()
    counts = result.praxicon.counts
    print(f"praxicon: {counts['actions']} actions, {counts['learnt']} learnt, "
          f"{counts['failed']} failed ({len(result.skipped)} already done) -> "
          f"{args.output}/index.json")
    if counts["actions"] and not counts["learnt"]:
        # the folder is written (the failures are its record), but there is nothing to use:
        # a script chaining build and recognise learns it here, not from the next command
        print(f"praxicon: no action learnt: every one of the {counts['actions']} failed "
              f"(each reason is a line above and in {args.output}/index.json)", file=sys.stderr)
        return NO
    return 0


def _draw_progress(done: int, total: int, name: str) -> None:
    # one line rewritten in place on stderr: stdout stays the list of pictures written
    print(f"\rdrawing {done + 1}/{total}: {name:<70}", end="", file=sys.stderr, flush=True)


def run_draw(args) -> int:
    from .pictures import draw_praxicon

    drawn: list[int] = []  # whether the progress line was started

    def progress(done: int, total: int, name: str) -> None:
        drawn.append(done)
        _draw_progress(done, total, name)

    try:
        written = draw_praxicon(args.praxicon, args.output, fmt=args.format,
                                progress=progress, workers=args.workers)
    except ValueError as exc:
        if drawn:  # the error on a line of its own, not at the end of the progress line
            print(file=sys.stderr)
        _bad(str(exc))
    pictures = "picture" if len(written) == 1 else "pictures"
    print(f"\rdrew {len(written)} {pictures} into {args.output}" + " " * 70, file=sys.stderr)
    for path in written:
        print(path)
    return 0


def _check_outputs(args) -> None:
    """Every output's name, before anything is generated: a wrong one is one line now, not an
    error after the BVH file (or the plot) is already on disk."""
    from kinetology.viewer import check_output

    from .outputs import check_folder
    from .pictures import check_picture

    if Path(args.output).suffix.lower() != ".bvh":
        _bad(f"{args.output}: the motion is written as BVH; give -o a .bvh file")
    check_folder(args.output, "the motion")
    if args.plot is not None:
        check_picture(args.plot)
    if args.view is not None:
        check_output(args.view)
        check_folder(args.view, "the player")


def _check_skeleton(praxicon, args) -> None:
    """A player draws bones: an action whose skeleton source is an AMC file without its ASF
    (read as angles, with no skeleton) is refused before any work; the player failed only
    after the motion was generated, and no BVH file was written."""
    from kinetology.asf import find_asf

    if args.view is None or args.action not in praxicon.names:
        return  # no player, or generate's own line for an unknown action
    record = praxicon[args.action]
    source = Path(record.skeleton_source or "")
    if source.suffix.lower() == ".amc" and source.is_file() and find_asf(source) is None:
        _bad(f"{args.view}: no skeleton to draw: {args.action!r} is on the skeleton of "
             f"{record.skeleton_source}, an AMC file without its ASF (generate it without "
             f"--view)")


def _check_system(praxicon, args) -> None:
    """The action's record is named, with the command that learns it again, when its system
    does not parse (``load`` leaves the systems unparsed; the ``.psgs`` file beside it is a
    copy, which the error named before)."""
    from .store import system_problem

    if args.action in praxicon.names:
        problem = system_problem(praxicon[args.action],
                                 Path(args.praxicon) / "records" / f"{args.action}.json")
        if problem:
            _bad(problem)


def _shaping_progress(done: int, total: int, channel: str) -> None:
    # one line rewritten in place on stderr (a channel at 120 fps can take seconds)
    print(f"\rgenerated channel {done}/{total}: {channel:<40}", end="", file=sys.stderr,
          flush=True)


def run_generate(args) -> int:
    from kinetology.bvh_writer import format_bvh, without_axes

    from .generation import RecordFieldError, generate
    from .pictures import draw_generated
    from .store import load

    try:
        _check_outputs(args)
        praxicon = load(args.praxicon, descriptions=False)  # generation reads the records
        _check_skeleton(praxicon, args)
        _check_system(praxicon, args)
        live = not args.no_progress and sys.stderr.isatty()
        try:
            result = generate(praxicon, args.action, repeat=args.repeat, style=args.style,
                              progress=_shaping_progress if live else None,
                              # the cores, at most 4, as draw's default
                              workers=args.workers or min(4, usable_cores()))
        finally:  # the progress line ends before any answer or error is printed
            if live:
                print(file=sys.stderr)
        # everything that can fail is made in memory first: the files are written together
        player, shown = (_beside_a_performance(praxicon, result) if args.view is not None
                         else (None, ()))
        text = format_bvh(without_axes(result.motion))
        if args.plot is not None:
            draw_generated(praxicon[args.action], result, args.plot)
        Path(args.output).write_text(text, encoding="utf-8")
        if player is not None:
            _save_player(player, shown, args.view)
    except RecordFieldError as exc:  # the file to look at: the record's
        _bad(f"{Path(args.praxicon) / 'records' / (args.action + '.json')}: {exc}")
    except ValueError as exc:
        _bad(str(exc))
    if result.origin == "performances":
        _report_performed(args, result)
    else:
        _report_derived(args, result)
    if result.motion.skeleton is None:  # nothing to put the bones on: said, not hidden
        print(f"{args.output}: on a star skeleton (every joint on the root at offset 0, angles "
              f"only): {praxicon[args.action].skeleton_source} has no skeleton (an AMC file "
              f"without its ASF)")
    if player is not None:
        print(f"{args.view}: {' beside '.join(label for label, _ in shown)}")
    return 0


def _report_derived(args, result) -> None:
    """What was derived from the grammar, and the round trip."""
    print(f"{args.output}: {result.motion.frames} frames at {result.motion.frame_rate:g} fps, "
          f"{len(result.channels)} generated channels of {len(result.actuators)} actuators, "
          f"{result.repeat} copies" + (f" of {result.cycle} morphemes each" if result.cycle > 1
                                     else "") + (f", style {args.style}" if args.style else ""))
    # the round trip, what the acceptance asks: the motion segmented again gives the morpheme
    exact = result.round_trip()
    kinds = [result.methods[c].kind for c in result.channels if exact[c]]
    copies = result.repeat * result.cycle
    print(f"segmented again: {sum(exact.values())} of {len(exact)} channels give back their "
          f"morpheme x {copies} ({kinds.count('quartic')} by the quartic alone, "
          f"{kinds.count('corrected')} corrected)")
    for channel in result.channels:
        if not exact[channel]:
            print(f"  {channel}: {result.methods[channel].kind}")


def _report_performed(args, result) -> None:
    """What was made for an action without a grammar, and why there is no round trip."""
    each = (result.motion.frames - 1) // result.repeat + 1
    times = "once" if result.repeat == 1 else f"{result.repeat} times, one after the other"
    print(f"{args.output}: {result.motion.frames} frames at {result.motion.frame_rate:g} fps, "
          f"the action played {times} ({each} frames"
          # each copy's last frame is the next one's first: 3 x 358 frames make 1072
          + ("" if result.repeat == 1 else " each, a frame shared where one meets the next")
          + ")"
          + (f", style {args.style}" if args.style else ""))
    if result.performances == 1:
        how = "its one performance's channels, on its own clock"
    else:
        how = "every channel the performances' mean after warping them to their median length"
    print(f"generated from the course of {result.performances} performance"
          f"{'' if result.performances == 1 else 's'}, not from a grammar: no synchronised "
          f"repetition was found in the action, so it has no grammar system ({how}; the root "
          f"travels and turns as in the takes)")
    print("segmented again: no symbolic round trip (there is no morpheme to give back)")


def _beside_a_performance(praxicon, result):
    """The player of the generated motion beside the first performance it was learnt from
    (one clock, actuators ringed), and its panels as (label, full name) pairs. A panel is
    labelled with the file's name: a whole path would be wider than the panel under it."""
    import kinetology

    from .datasets import Performance
    from .learn import _load_performance

    shown = {}
    for p in praxicon[result.action].performances:
        if p.used is not False:
            motion, problem = _load_performance(Performance(p.file, p.start, p.stop, p.label))
            if not problem:
                shown[f"performance ({Path(p.file).name})"] = (motion, p.file)
                break
    shown["generated"] = (result.motion, result.motion.source)
    player = kinetology.view({label: m for label, (m, _) in shown.items()},
                             actuators=list(result.actuators))
    return player, tuple((label, name) for label, (_, name) in shown.items())


def _save_player(player, shown, output) -> None:
    """The page's title names the performance's whole path (the browser's tab and tooltip);
    a GIF or MP4 has no title."""
    if Path(output).suffix.lower() == ".html":
        title = " beside ".join(name for _, name in shown)
        Path(output).write_text(player.to_html(title=title), encoding="utf-8")
    else:
        player.save(output)


def run_verify(args) -> int:
    from .integrity import repair, verify

    try:
        found = repair(args.praxicon) if args.repair else verify(args.praxicon)
    except ValueError as exc:  # a folder load refuses: its line, status 2
        _bad(str(exc))
    for problem in found.problems:
        print(problem)
    done = "repaired; " if args.repair else ""
    if found.intact:
        print(f"{found.folder}: {done}whole: {found.checked} files as its records give",
              file=sys.stderr)
        return 0
    hint = (f" ({found.repairable} of them --repair writes again from the records)"
            if found.repairable and not args.repair else "")
    print(f"{found.folder}: {done}{len(found.problems)} problem(s){hint}", file=sys.stderr)
    return NO


def _add_commands(sub) -> None:
    build = sub.add_parser("build", help="learn every action of one or more datasets",
                           description="Learn every action of the datasets into a praxicon "
                                       "folder (docs/praxicon.md).")
    build.add_argument("datasets", nargs="+", metavar="DATASET", type=file_name,
                       help="a Bandai folder, a cmu-mocap6 folder, or a .csv/.toml manifest")
    build.add_argument("-o", "--output", required=True, metavar="DIR", type=file_name,
                       help="the praxicon folder (made when missing; a build there resumes)")
    # the metavar spelt out: argparse's own '{content,content,style}' reads as three choices
    build.add_argument("--group-by", choices=("content", "content,style"), default=None,
                       metavar="content|content,style",
                       help="one action per content, or per content and style (default: "
                            "content,style where most styles have several takes)")
    build.add_argument("--inducer", default="pal", help="the inducer by name (default pal)")
    build.add_argument("--param", action="append", default=[], metavar="K=V",
                       help="an inducer parameter (repeatable); a parameter whose default "
                            "is none takes none (PAL's max_seconds=none: no time bound)")
    build.add_argument("--segment", action="append", default=[], metavar="K=V",
                       help="a kinetology segmentation parameter (repeatable)")
    build.add_argument("--min-performances", type=positive_int, default=2, metavar="N",
                       help="fewest usable performances an action needs (default 2)")
    where = build.add_mutually_exclusive_group()
    where.add_argument("--workers", type=positive_int, default=None, metavar="N",
                       help="learn in N processes")
    where.add_argument("--scheduler", default=None, metavar="ADDRESS",
                       help="learn on a Dask cluster (e.g. tcp://host:8786)")
    build.add_argument("--no-progress", action="store_true", help="no progress bar")
    build.set_defaults(run=run_build)

    draw = sub.add_parser("draw", help="draw a praxicon's pictures",
                          description="Actuator matrix (Fig. 10), morphemes (Fig. 11), shared "
                                      "sub-patterns (Fig. 13).")
    draw.add_argument("praxicon", metavar="DIR", type=file_name, help="a praxicon folder")
    draw.add_argument("-o", "--output", required=True, metavar="IMGDIR", type=file_name,
                      help="folder for the pictures")
    draw.add_argument("--format", choices=("svg", "png"), default="svg",
                      help="picture format (default svg: sharp at any zoom, and a system's "
                           "graph is written without rasterising tens of thousands of pixels)")
    draw.add_argument("--workers", type=positive_int, default=None, metavar="N",
                      help="run up to N Graphviz dot programs at once, or without Graphviz "
                           "N processes drawing with matplotlib (default: the number of cores, "
                           "at most 4)")
    draw.set_defaults(run=run_draw)

    gen = sub.add_parser("generate", help="generate an action's motion as BVH",
                         description="Derive K synchronised copies of an action and write "
                                     "them as a BVH file on the source skeleton; an action "
                                     "with no synchronised repetition is generated from its "
                                     "performances' course instead.")
    gen.add_argument("praxicon", metavar="DIR", type=file_name, help="a praxicon folder")
    gen.add_argument("action", metavar="ACTION", help="an action name of its index")
    gen.add_argument("--repeat", type=positive_int, default=None, metavar="K",
                     help="how many synchronised copies (default 3, at most 1000); an action "
                          "with no synchronised repetition (no grammar) is its performances' "
                          "course, played K times one after the other (default once)")
    gen.add_argument("-o", "--output", required=True, metavar="OUT.bvh", type=file_name,
                     help="the BVH file to write")
    gen.add_argument("--no-progress", action="store_true",
                     help="no progress line (shown only when stderr is a terminal)")
    gen.add_argument("--workers", type=positive_int, default=None, metavar="N",
                     help="make N channels at once (threads: the correction's linear "
                          "programmes on N cores; the motion is the same whatever N); "
                          "default: the number of cores, at most 4")
    gen.add_argument("--style", default=None, metavar="STYLE",
                     help="generate that style of the action: a word of its performances' "
                          "file names that not all of them hold (Bandai's "
                          "dataset-2_walk_elderly_001.bvh is style elderly, not walk); "
                          "default: every performance together")
    gen.add_argument("--plot", default=None, metavar="PNG", type=file_name,
                     help="also plot one joint, original performance beside generated")
    gen.add_argument("--view", default=None, metavar="OUT.html", type=file_name,
                     help="also a player of the generated motion beside a performance "
                          "(.html, .gif or .mp4: kinetology view)")
    gen.set_defaults(run=run_generate)

    check = sub.add_parser("verify", help="check every file of a praxicon against its records",
                           description="Compare every file of a praxicon folder with what its "
                                       "records give (the systems, the actuator matrix, the "
                                       "shared patterns, the index, the descriptions) and name "
                                       "stray files: one line per problem on stdout.")
    check.add_argument("praxicon", metavar="DIR", type=file_name, help="a praxicon folder")
    check.add_argument("--repair", action="store_true",
                       help="write the derived files again from the records first")
    check.set_defaults(run=run_verify)

    from .recognition_cli import register_recognise  # recognise, parse

    register_recognise(sub)


def register(subparsers) -> None:
    """Add ``praxicon`` (build, draw, generate, verify, recognise, parse) to psgs's
    subcommands."""
    parser = subparsers.add_parser("praxicon", help="every action's morphology, at scale",
                                   description="Build, draw, generate, verify, recognise and "
                                               "parse with a praxicon.")
    sub = parser.add_subparsers(dest="praxicon_command", metavar="COMMAND",
                                help="build, draw, generate, verify, recognise or parse "
                                     "(COMMAND --help for its options)")
    sub.required = True
    _add_commands(sub)


def main(argv: list[str] | None = None) -> int:
    """``python -m praxicon``: the ``psgs praxicon`` commands without an install."""
    from psgs.cli import main as psgs_main

    return psgs_main(["praxicon", *(sys.argv[1:] if argv is None else argv)],
                     commands={"praxicon": register})
