"""``psgs praxicon recognise|parse``: learnt actions found in new motion files.

The descriptions they read are learnt by ``psgs praxicon build`` (``descriptions.json`` in
the folder, :mod:`praxicon.description_store`). The commands (added to ``psgs praxicon`` by
:func:`register_recognise`):

* ``psgs praxicon recognise PX FILE... [--explain] [--plot PNG]``: one line per file, best
  action, its probability, the runner-up; with ``--explain`` the joints that decided it, with
  ``--plot`` (one file) the picture of them;
* ``psgs praxicon parse PX FILE [--plot PNG] [--max-seconds S]``: the recording's timeline of
  spans; past ``S`` seconds, the timeline up to where it got, the bound named on stderr and
  exit status 3.

Bad input (a folder that is not a praxicon or that ``praxicon.load`` refuses, descriptions of
another version or damaged, a ``--plot`` into a folder that is not there) is one line on
stderr and exit status 2, before any answer. A FILE that cannot be answered for (an empty or
one-frame motion, a path that does not exist, a value too large to compute with, a motion
that shares no joint with any learnt action) is one line on stderr naming it: ``parse``
stops there; ``recognise`` still answers every other FILE (recognised together, a chunk of
files at a time: ``CHUNK_FILES``) and exits with status 2 at the end. A motion whose
skeleton lacks some of its best action's joints (for ``parse``, of the actions its spans
name) is recognised over the joints it has, and those joints are named on stderr (actions
learnt from another skeleton, sharing no joint with it, are ranked last).
"""

from __future__ import annotations

from psgs._foundation.shell import ERROR, INCOMPLETE, file_name, positive_float
from psgs.errors import ValidationError

from ._errors import DescriptionError

__all__ = ["register_recognise"]

#: how the shell every psgs command runs in begins an error line (``python -m praxicon``
#: runs in it too); recognise says a FILE's error itself and goes on to the next FILE
_ERROR = "psgs: error: "


def _read_motion(path: str, doing: str = "recognising"):
    import kinetology
    from psgs.errors import PSGSError

    try:
        motion = kinetology.read(path)
    except FileNotFoundError:
        raise ValidationError(f"{path}: no such file")
    except OSError as exc:  # unreadable: the file and why, as every command says it
        raise ValidationError(f"{path}: {exc.strerror or exc}")
    except PSGSError as exc:  # not motion: one line
        raise ValidationError(str(exc).splitlines()[0])
    from .recognition import _frames

    try:
        _frames(motion, doing)  # the API's refusal, said as the command's one line
    except DescriptionError as exc:
        raise ValidationError(str(exc)) from None
    return motion


def _check_pictures(plot) -> None:
    # before any work: without the praxicon extra, with a suffix matplotlib cannot write or
    # into a folder that is not there, a --plot would fail only after the answers were printed
    if plot:
        from .pictures import check_picture

        try:
            check_picture(plot)
        except ValueError as exc:
            raise ValidationError(str(exc)) from None


def _lacking(file, motion, missing) -> str:
    """The line naming the joints a motion lacks; where its channels are numbered (an AMC file
    read without its ASF names them ``bone.1``, ``bone.2``, ...), it says so: the joints are
    there, under names no action was learnt with."""
    line = f"{file}: recognised without the joints it lacks: {', '.join(missing)}"
    if any(c.rpartition(".")[2].isdigit() for c in motion.channels):
        line += (" (its channels are numbered, not named: an AMC file read without its ASF; "
                 "put the .asf file beside it)")
    return line


def _unread(file, motion, joints) -> str:
    """The line naming the joints a motion has but that were read without some of their
    learnt features: the travel and turning of a root none of whose positions move (a take
    on the spot, its root's travel taken out), or channels other than those learnt."""
    from .features import _root_joints

    if not _root_joints(motion):
        return (f"{file}: recognised without the travel and turning of {', '.join(joints)}: "
                f"no position of the motion moves")
    return (f"{file}: recognised without some of the learnt features of joints it has: "
            f"{', '.join(joints)} (its channels, or the joints its travel is on, are not the "
            f"learnt actions')")


def _said(file, motion, answer) -> None:
    """What the answer was read without, on stderr: the joints the motion lacks, and those
    it has but not as learnt."""
    import sys

    if answer.missing:
        print(_lacking(file, motion, answer.missing), file=sys.stderr)
    if answer.unread:
        print(_unread(file, motion, answer.unread), file=sys.stderr)


#: ``recognise`` reads its FILEs in chunks, recognises each chunk in one batch (features
#: once, one matrix of scores per skeleton), prints its lines and drops its motions before
#: reading the next: the memory of a run is one chunk's (and at most
#: :data:`~praxicon._verdict.KEPT_MODELS` score models), however many FILEs. A chunk ends at
#: this many files, or sooner once its motions' values hold ``CHUNK_BYTES`` (a chunk holds at
#: least one file, however long). What scoring reads of the descriptions alone (the score
#: model, the telling groups: about 17 ms for 28 actions) is made once per skeleton for the
#: whole command (:class:`~praxicon._verdict.ScoreModels`), not once per chunk; a take's answer
#: is the same in any chunk (:func:`~praxicon.scoring.distances`)
CHUNK_FILES = 256
CHUNK_BYTES = 64 * 2**20


def _chunks(files, most_files: int = CHUNK_FILES, most_bytes: int = CHUNK_BYTES):
    """``(file, motion or its ValidationError)`` pairs, in the order given, a chunk at a time
    (at most ``most_files`` files, or fewer holding ``most_bytes``); the next chunk's files
    are read when it is asked for, so that a caller that drops each chunk first holds one
    chunk's motions at a time."""
    chunk, size = [], 0
    for file in files:
        try:
            motion = _read_motion(file)
            size += motion.values.nbytes
        except ValidationError as exc:
            motion = exc
        chunk.append((file, motion))
        del motion  # the chunk alone holds it, so that dropping the chunk frees it
        if len(chunk) >= most_files or size >= most_bytes:
            yield chunk
            chunk, size = [], 0
    if chunk:
        yield chunk


def _answer(file, r, explain: bool) -> None:
    """One FILE's line (and explanation) on stdout, or its error line on stderr."""
    import sys

    from .recognition import Recognition

    if not isinstance(r, Recognition):
        print(f"{_ERROR}{r}", file=sys.stderr)
        return
    (best, p), *rest = r.ranking
    runner = f", runner-up {rest[0][0]} {rest[0][1]:.3f}" if rest else ""
    answer = r.action if r.action else f"none of these (closest {best})"
    print(f"{file}: {answer} {p:.3f}{runner}")
    if explain:
        print(r.explain())


def _recognise_chunk(models, chunk, args):
    """One chunk's FILEs recognised together (``models``: the descriptions'
    :class:`~praxicon._verdict.ScoreModels`, kept from chunk to chunk), each one's lines
    printed in its turn: ``(whether every FILE was answered, the last answer)``."""
    from .recognition import Recognition, _in_file, _recognitions

    readable = [k for k, (_, m) in enumerate(chunk) if not isinstance(m, ValidationError)]
    try:
        answers = _recognitions(models, [chunk[k][1] for k in readable],
                                explain=3 if args.explain or args.plot else 0)
    except DescriptionError as exc:  # of the praxicon, not of a FILE: no more answers
        raise ValidationError(str(_in_file(exc, args.praxicon)))
    found = [m for _, m in chunk]
    for k, r in zip(readable, answers):
        found[k] = r
    for (file, motion), r in zip(chunk, found):
        if isinstance(r, Recognition):
            _said(file, motion, r)
        _answer(file, r, args.explain)
    return all(isinstance(r, Recognition) for r in found), found[-1]


def run_recognise(args, *, most_files: int = CHUNK_FILES,
                  most_bytes: int = CHUNK_BYTES) -> int:
    """``psgs praxicon recognise``, its FILEs read and recognised a chunk at a time (at most
    ``most_files`` files, or fewer holding ``most_bytes``: :func:`_chunks`)."""
    from .recognition import ScoreModels
    from .store import read_descriptions

    if args.plot and len(args.files) != 1:
        raise ValidationError(f"--plot draws one recognition's explanation: give one FILE "
                              f"(got {len(args.files)})")
    _check_pictures(args.plot)
    try:
        descriptions = read_descriptions(args.praxicon)
    except DescriptionError as exc:
        raise ValidationError(str(exc))
    # descriptions the scores cannot compute with are found by the first chunk holding a
    # motion of the features they fail on: of one skeleton, the first chunk, before any answer
    models = ScoreModels(descriptions)  # made as each skeleton's first chunk asks, then kept
    answered, last = True, None
    for chunk in _chunks(args.files, most_files, most_bytes):
        done, last = _recognise_chunk(models, chunk, args)
        answered &= done
        del chunk  # its motions let go before the next chunk is read
    if not answered:
        return ERROR  # every other FILE answered; the status says one was not
    if args.plot:
        from .recognition_pictures import draw_explanation
        draw_explanation(last, args.plot)
        print(args.plot)
    return 0


def run_parse(args) -> int:
    import math
    import sys

    from psgs.budget import Budget

    # the deadline starts first: --max-seconds covers reading the praxicon and the FILE too
    clock = Budget(args.max_seconds)

    from ._arguments import real_number
    from .parsing import _parsed
    from .recognition import _in_file
    from .store import read_descriptions

    _check_pictures(args.plot)
    try:  # before the folder is read, as every other value of the command
        real_number(args.support, "--support", least=0.0, most=1.0)
        real_number(args.unfit, "--unfit", above=0.0, most=math.inf)
    except DescriptionError as exc:
        raise ValidationError(str(exc))
    try:
        descriptions = read_descriptions(args.praxicon, windows=True)
    except DescriptionError as exc:
        raise ValidationError(str(exc))
    motion = _read_motion(args.file, "parsing")
    # a long recording takes a while (about 0.9 s a minute of a 30 fps take of 25 joints):
    # on a terminal, the window being read on one line of stderr
    shown: list[int] = []  # whether the progress line was started

    def progress(done: int, total: int) -> None:
        shown.append(done)
        _parse_progress(done, total)

    live = not args.no_progress and sys.stderr.isatty()
    try:  # parse's windows are read until the command's own deadline (the first always)
        timeline = _parsed(descriptions, motion, support=args.support, unfit=args.unfit,
                           progress=progress if live else None, max_seconds=args.max_seconds,
                           clock=clock)
    except DescriptionError as exc:
        raise ValidationError(str(_in_file(exc, args.praxicon, windows=True)))
    finally:  # the progress line is wiped before any answer or error is printed
        if shown:
            print(f"\r{' ' * 40}\r", end="", file=sys.stderr, flush=True)
    _said(args.file, motion, timeline)  # as recognise says it: the windows were scored so
    print(timeline.text())
    if args.plot:
        from .recognition_pictures import draw_timeline
        draw_timeline(timeline, motion, args.plot)
        print(args.plot)
    if timeline.bound:  # what was found is printed; the bound and where, on stderr
        print(f"psgs: the parse stopped at its bound {timeline.bound} ({args.max_seconds:g} s):"
              f" parsed to {timeline.end:.2f} s of {timeline.duration:.2f} s; the timeline "
              f"above ends there", file=sys.stderr)
        return INCOMPLETE
    return 0


def _parse_progress(done: int, total: int) -> None:
    import sys

    # one line rewritten in place, a hundred times at most however many windows
    if done == total or done % max(1, total // 100) == 0:
        print(f"\rparsing: window {done}/{total}", end="", file=sys.stderr, flush=True)


def register_recognise(sub) -> None:
    """Add ``recognise`` and ``parse`` to the ``psgs praxicon`` subcommands."""
    from ._defaults import SUPPORT, UNFIT  # not .parsing: --help does not need the parser

    r = sub.add_parser("recognise", help="which learnt action each motion file is",
                       description="One line per file: the best action (or none of these), "
                                   "its probability and the runner-up. A file that cannot be "
                                   "recognised is one error line on stderr instead; the other "
                                   "files are still answered, and the exit status is then 2.")
    r.add_argument("praxicon", metavar="PX", type=file_name, help="a praxicon folder")
    r.add_argument("files", nargs="+", metavar="FILE", type=file_name,
                   help="a .bvh or .amc motion file")
    r.add_argument("--explain", action="store_true",
                   help="also the joints that decided it, tempo, drift, flight and pace")
    r.add_argument("--plot", default=None, metavar="PNG", type=file_name,
                   help="also draw the explanation: per best action its joints' distance "
                        "terms (one FILE)")
    r.set_defaults(run=run_recognise)
    p = sub.add_parser("parse", help="a recording as a timeline of learnt actions",
                       description="One line per span: start, stop (seconds), action (- for "
                                   "none), score.")
    p.add_argument("praxicon", metavar="PX", type=file_name, help="a praxicon folder")
    p.add_argument("file", metavar="FILE", type=file_name, help="a .bvh or .amc motion file")
    p.add_argument("--plot", default=None, metavar="PNG", type=file_name,
                   help="also draw the timeline over the joint angles")
    p.add_argument("--support", type=float, default=SUPPORT, metavar="S",
                   help="the share of a span's windows, 0 to 1, that must pass its action's "
                        "feature-group test for the span to stand, else it is none of these "
                        "(default %(default)g; 0: no span is refused as a whole)")
    p.add_argument("--unfit", type=float, default=UNFIT, metavar="SECONDS",
                   help="a stretch of a span this long in which every window fails the "
                        "action's feature-group test is none of these (default %(default)g; "
                        "inf: never)")
    p.add_argument("--no-progress", action="store_true",
                   help="no progress line on stderr (shown on a terminal only)")
    p.add_argument("--max-seconds", type=positive_float, default=None, metavar="S",
                   help="stop after S seconds: the timeline up to where the windows were "
                        "read is printed, the bound named on stderr, exit status 3 (default: "
                        "no bound; a parse takes about 0.9 s a minute of a 30 fps recording)")
    p.set_defaults(run=run_parse)
