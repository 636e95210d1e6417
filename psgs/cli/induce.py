"""``psgs induce``: learn a grammar system from an actiongram file, or the built-in example.

It prints a summary (what was found: per joint, or per component, one line),
the whole grammar system with ``--full``, or JSON with ``--json``.
``psgs synth`` and ``psgs bench`` are in :mod:`psgs.cli.bench`.
"""

from __future__ import annotations

import json
import re
import sys
import time
from pathlib import Path

from .._foundation.shell import INCOMPLETE, file_name, key_values
from ..actiongram import GAPS
from ..errors import ValidationError

# a motion string's status names its joint: "why (joint J)", or "verdict (why, joint J)"
_OF_JOINT = re.compile(r"(?P<head>.*?)(?: \(joint (?P<alone>[^()]+)\)|, joint (?P<inner>[^()]+)\))")


def _dropped(statuses: list[str]) -> str:
    """The dropped strings counted by why, the joints a reason names gathered into one entry
    (one entry per joint made a line of 800 characters for a take of 22 joints).

    >>> _dropped(["far (joint A)", "far (joint B)", "far (joint A)", "odd", "v (far, joint C)"])
    '3 far (joints A, B), 1 odd, 1 v (far) (joint C)'
    """
    joints: dict[str, list[str]] = {}
    for status in statuses:
        found = _OF_JOINT.fullmatch(status)
        if found is None:
            why, joint = status, None
        elif found["alone"] is not None:
            why, joint = found["head"], found["alone"]
        else:
            why, joint = found["head"] + ")", found["inner"]
        joints.setdefault(why, []).append(joint)
    parts = []
    for why, named in sorted(joints.items()):
        each = sorted({j for j in named if j is not None})
        where = f" (joint {each[0]})" if len(each) == 1 else \
            f" (joints {', '.join(each)})" if each else ""
        parts.append(f"{len(named)} {why}{where}")
    return ", ".join(parts)


def register(subparsers) -> None:
    """Add ``induce`` to the ``psgs`` command.

    Parameters
    ----------
    subparsers : argparse._SubParsersAction
        The ``psgs`` parser's subcommands.

    Examples
    --------
    >>> from psgs.cli import build_parser
    >>> build_parser().parse_args(["induce", "--inducer", "sequential"]).inducer
    'sequential'
    """
    induce = subparsers.add_parser(
        "induce", help="learn a grammar system from an actiongram",
        description="Learn a parallel synchronous grammar system from an actiongram file "
                    "(text form 'name: sym sym@D ...', or .json). Without FILE (or with "
                    "--example) it learns from a built-in synthetic actiongram and explains "
                    "what it found.")
    induce.add_argument("file", metavar="FILE", nargs="*", type=file_name,
                        help="an actiongram file; several files are performances of one action "
                             "(learnt from together, never joined)")
    induce.add_argument("--events", metavar="FILE.csv", action="append", type=file_name,
                        help="learn from an events table instead: a CSV file with a header row "
                             "stream,onset,duration,symbol (one row an event, in any order)")
    induce.add_argument("--gaps", choices=GAPS,
                        help="with --events: a gap between two events of a stream becomes a "
                             "rest symbol (rest, the default), the event before lasts until the "
                             "next onset (hold), or is an error")
    induce.add_argument("--rest-symbol", metavar="SYM",
                        help="with --events: the symbol of a gap (default _)")
    induce.add_argument("--keep-repeats", action="store_true",
                        help="with --events: keep equal neighbours (a re-struck note C C) as "
                             "separate segments instead of merging them")
    induce.add_argument("--example", action="store_true",
                        help="use the built-in synthetic example (20 strings, 4 patterned)")
    induce.add_argument("--inducer", default="pal", help="pal (default), sequential, or a "
                                                         "plug-in's name")
    induce.add_argument("--param", action="append", default=[], metavar="K=V",
                        help="an inducer parameter, e.g. --param alpha=1e-6 (repeatable); "
                             "a parameter whose default is none takes none (PAL's "
                             "max_seconds=none: no time bound)")
    induce.add_argument("--json", action="store_true",
                        help="print one JSON object (the system as text under 'system')")
    induce.add_argument("--full", action="store_true",
                        help="also print the whole grammar system and every pattern in full "
                             "(default: a summary, one line per joint or component)")
    induce.add_argument("-o", "--output", metavar="OUT.psgs",
                        help="also write the grammar system to this file")
    induce.set_defaults(run=run_induce)
    locate = subparsers.add_parser(
        "locate", help="find a learned action in new motion",
        description="Learn an action from the performances given with --learn (actiongram "
                    "files), then print the time spans of each FILE where it occurs, with a "
                    "score (chance-corrected agreement with the learned patterns).")
    locate.add_argument("file", metavar="FILE", nargs="+", type=file_name,
                        help="actiongram files to search")
    locate.add_argument("--learn", metavar="PERF", action="append", required=True,
                        type=file_name,
                        help="an actiongram file of one performance to learn from (repeatable)")
    locate.add_argument("--threshold", type=float, default=0.4,
                        help="least score of a place (default 0.4)")
    locate.add_argument("--param", action="append", default=[], metavar="K=V",
                        help="a PAL parameter (repeatable); max_seconds=none: no time "
                             "bound, the default")
    locate.add_argument("--json", action="store_true", help="print one JSON object")
    locate.set_defaults(run=run_locate)


def _inducer(name: str, items: list[str]):
    """The inducer ``name`` built with the ``--param`` items ``items``.

    A value ``none`` (any case) of a parameter whose default is None is that default (PAL's
    ``max_seconds=none``: no bound): the parameter's own message says it takes a number or
    None, and the text ``None`` was refused with it. For any other parameter ``none`` stays
    a word, which the parameter refuses in its own words.

    Parameters
    ----------
    name : str
        The inducer's name (``--inducer``).
    items : list of str
        The ``KEY=VALUE`` texts.

    Returns
    -------
    Inducer

    Raises
    ------
    ValidationError
        For a bad item, an unknown inducer or parameter, or a bad value.

    Examples
    --------
    >>> _inducer("pal", ["max_seconds=None"]).max_seconds is None
    True
    >>> _inducer("sequential", ["max_rules=none"])
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: parameter max_rules must be an integer, not 'none'
    """
    from ..induce import get
    from ..induce.registry import text_params

    return get(name, **text_params(name, key_values(items)))


MOTION_SUFFIXES = (".bvh", ".amc", ".asf", ".c3d", ".fbx", ".trc")


def _load_performances(files: list[str]):
    """Actiongram files; a motion-capture file gets a one-line hint (psgs never reads motion)."""
    from ..format import load

    for name in files:
        if Path(name).suffix.lower() in MOTION_SUFFIXES:
            stem = Path(name).with_suffix(".actiongram").name
            raise ValidationError(f"{name} is motion capture, not an actiongram: run "
                                  f"'kinetology segment {name} -o {stem}' first, then "
                                  f"'psgs induce {stem}'")
    return [load(name, kind="actiongram") for name in files]


def _load_events(args):
    """The actiongram of ``--events FILE.csv`` with its gap and repeat options."""
    from ..actiongram import read_events_csv

    if args.file or args.example:
        raise ValidationError("give --events, FILE or --example, not two of them")
    if len(args.events) > 1:  # (appended: the last alone would be read, the rest dropped)
        raise ValidationError(f"give --events once (one table holds every stream), not "
                              f"{len(args.events)} times")
    # an option not given is left out, so the reader's own defaults apply (None: not given)
    given = {key: value for key, value in (("gaps", args.gaps),
                                           ("rest_symbol", args.rest_symbol))
             if value is not None}
    return read_events_csv(args.events[0], keep_repeats=args.keep_repeats, **given)


# -- psgs induce -------------------------------------------------------------------------
EXAMPLE_SEED = 1
EXAMPLE_NOISE = 0.1

def _bound_hit(inducer, result) -> str | None:
    """The line naming the budget that stopped the induction, or None.

    The Induction names its bound (``bound``, and in words ``reason``). A bound that stops
    the learning of each string apart (the sequential baseline's ``max_rules``) leaves the
    strings it stopped among the components, their reports saying why they are not plain
    components: those are named, with the bound's value; a bound of the whole induction
    (PAL's ``max_seconds``) is named in the inducer's own words.

    >>> from psgs import Actiongram
    >>> from psgs.induce import Induction, get
    >>> inducer = get("sequential", max_rules=1)
    >>> result = inducer.induce(Actiongram.from_strings({"x": "abcabcabc", "y": "pq"}))
    >>> _bound_hit(inducer, result)
    'sequential stopped at its bound max_rules=1 on 1 string (x): its pattern is what the rules made by then give'
    >>> _bound_hit(get("pal"), Induction(None, (), {}, {}, inducer="pal", bound="max_seconds",
    ...                                  reason="stopped after 1 seconds (max_seconds)"))
    'pal stopped after 1 seconds (max_seconds): no component was found by then'
    """
    bound = getattr(result, "bound", None)  # (a plug-in's result may not have one)
    if bound is None:
        return None
    names = [report.name for report in result.reports
             if report.name in result.components and report.status != "component"]
    if not names:
        found = ("its components are those found by then" if result.components
                 else "no component was found by then")
        return f"{result.inducer} {result.reason or 'stopped at ' + bound}: {found}"
    value = getattr(inducer, bound, None)  # (the inducer holds its parameters)
    shown = ", ".join(names[:5]) + (f", ... ({len(names)} in all)" if len(names) > 5 else "")
    one = len(names) == 1
    return (f"{result.inducer} stopped at its bound {bound}"
            f"{'' if value is None else f'={value}'} on {len(names)} string{'' if one else 's'} "
            f"({shown}): {'its pattern is' if one else 'their patterns are'} what the rules "
            f"made by then give")


def run_induce(args) -> int:
    """``psgs induce``: learn from FILE... (one performance each)
    or the built-in example, and print or write the result.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``psgs induce`` arguments.

    Returns
    -------
    int
        0, or 3 when the inducer stopped at one of its budgets (the sequential baseline's
        ``max_rules`` on some string, PAL's ``max_seconds``), named on stderr.

    Raises
    ------
    ValidationError
        For a bad ``--param``, an unknown inducer or parameter, or FILE with ``--example``.
    FormatError
        For an actiongram file that cannot be read (naming file, line and column).

    Examples
    --------
    >>> from psgs.cli import main
    >>> main(["induce", "--example", "--json"])  # doctest: +ELLIPSIS
    {
      "inducer": "pal",
    ...
    0
    """
    from ..induce.synthetic import generate
    from ..writing import dumps

    inducer = _inducer(args.inducer, args.param)
    out_path = args.output
    if out_path == "":  # else taken for no -o at all: nothing written, without a word
        raise ValidationError("-o needs a file name")
    if out_path and (Path(out_path).is_dir() or not Path(out_path).resolve().parent.is_dir()):
        # said now, not after the induction ran
        raise ValidationError(f"{out_path}: not a file in an existing directory")
    truth = None
    if args.file and args.example:
        raise ValidationError("give FILE or --example, not both")
    performances = None
    if args.events is not None:
        actiongram = _load_events(args)
    elif args.gaps is not None or args.rest_symbol is not None or args.keep_repeats:
        raise ValidationError("--gaps, --rest-symbol and --keep-repeats go with --events")
    elif args.file:
        performances = _load_performances(args.file)
        actiongram = performances[0]
    else:
        truth = generate(seed=EXAMPLE_SEED, noise=EXAMPLE_NOISE)
        actiongram = truth.actiongram
    began = time.perf_counter()
    result = inducer.induce(performances if performances and len(performances) > 1
                            else actiongram)
    seconds = time.perf_counter() - began
    bound_line = _bound_hit(inducer, result)
    status = 0 if bound_line is None else INCOMPLETE
    system_text = dumps(result.system) if result.system is not None else None
    if args.output:
        if system_text is None:
            print("psgs: no component found, nothing written to " + args.output, file=sys.stderr)
        else:
            Path(args.output).write_text(system_text, encoding="utf-8")
    if args.json:
        data = result.to_dict()
        data["system"] = system_text
        data["seconds"] = round(seconds, 6)
        print(json.dumps(data, indent=2))
        _say_bound(bound_line)
        return status
    out = []
    if truth is not None:
        out.append(f"Example: a synthetic actiongram (seed {EXAMPLE_SEED}, "
                   f"{EXAMPLE_NOISE:.0%} noise) of {len(actiongram)} strings x 100 symbols "
                   f"over 20 letters.")
        out.append(f"Hidden in it: {len(truth.components)} strings ({', '.join(truth.components)})"
                   f" each repeat an 8-symbol template 10 times, in step; the other "
                   f"{len(actiongram) - len(truth.components)} strings are random. Can "
                   f"{args.inducer} find them?")
        out.append("(Try: psgs synth --noise 0.2 --seed 3 -o ag.txt && psgs induce ag.txt)")
        out.append("")
    read = performances if performances else [actiongram]
    # every performance counts, not the first one's alone: the strings any of them has, and
    # the symbols of all of them
    strings = len(dict.fromkeys(n for p in read for n in p.names))
    takes = f" ({len(read)} performances)" if len(read) > 1 else ""
    out.append(f"{result.inducer}: {len(result.components)} component(s) of "
               f"{strings} strings, {sum(p.total_symbols for p in read)} symbols{takes}, "
               f"in {seconds * 1000:.0f} ms")
    out.extend(_found_lines(result, truth, full=args.full))
    dropped = []
    for report in result.reports:
        if report.status == "component":
            continue
        if report.name in result.components:  # kept, with a caveat (e.g. a search bound hit)
            out.append(f"  note: {report.name}: {report.status}")
        else:
            dropped.append(report.status)
    if dropped:
        out.append("  dropped: " + _dropped(dropped))
    if truth is not None:
        from ..induce.synthetic import success
        out.append("  verdict: " + ("found exactly the hidden patterns" if success(result, truth)
                                   else "did not recover the hidden patterns exactly"))
        if args.inducer == "pal":
            from ..induce import Sequential
            baseline = Sequential().induce(actiongram)
            out.append(f"  for comparison, the sequential baseline (no synchronisation) keeps "
                       f"{len(baseline.components)} of {len(actiongram)} strings: every random "
                       f"string that repeats a digram")
    out.append("")
    if system_text is None:
        out.append("No grammar system: " + (result.verdict or "no string repeats in step with "
                                             "another") + ".")
    else:
        out.append(_system_summary(result.system)
                   + (":" if args.full else " (--full prints it, -o OUT.psgs writes it)."))
        if args.full:
            out.append(system_text.rstrip("\n"))
    print("\n".join(out))
    _say_bound(bound_line)
    return status


def _say_bound(line: str | None) -> None:
    """The budget the induction stopped at, on stderr (exit status 3 says one was hit)."""
    if line is not None:
        print(f"psgs: {line}", file=sys.stderr)


SHOWN_SYMBOLS = 12  # a pattern's symbols on a summary line; the rest is counted


def _short(pattern, full: bool) -> str:
    """A pattern as text: whole with ``full``, else its first symbols and how many there are."""
    if full or len(pattern) <= SHOWN_SYMBOLS:
        return " ".join(pattern)
    return " ".join(pattern[:SHOWN_SYMBOLS]) + f" ... ({len(pattern)} symbols)"


def _copies(where) -> str:
    times = ", ".join(f"{a:.4g}-{b:.4g}" for a, b in where[:3])
    times += ", ..." if len(where) > 3 else ""
    return f"{len(where)} copies at t = {times}"


def _found_lines(result, truth, *, full: bool) -> list[str]:
    """What was found: one line per joint (its channels, pattern lengths, copies) when the
    inducer names joints, and one line per component outside any joint; ``full`` spells out
    every pattern instead of a summary."""
    lines = []
    in_joint: set[str] = set()
    if not full:
        for joint in result.actuators:
            channels = [c for c in result.actuator_channels.get(joint, ())
                        if c in result.patterns]
            if not channels or channels == [joint]:  # a string is its own joint: a line below
                continue
            in_joint.update(channels)
            lengths = sorted({len(result.patterns[c]) for c in channels})
            size = str(lengths[0]) if len(lengths) == 1 else f"{lengths[0]}-{lengths[-1]}"
            lines.append(f"  {joint}: {len(channels)} channel(s) ({', '.join(channels)}), "
                         f"patterns of {size} symbols, {_copies(result.occurrences[channels[0]])}")
    elif result.actuators:
        lines.append("  joints: " + ", ".join(
            f"{a} ({', '.join(result.actuator_channels.get(a, ()))})" for a in result.actuators))
    for name in result.components:
        if name in in_joint:
            continue
        line = (f"  {name}: {_short(result.patterns[name], full)}   "
                f"({_copies(result.occurrences[name])})")
        if truth is not None:
            ok = truth.patterns.get(name) == tuple(result.patterns[name])
            line += "   [the hidden template]" if ok else "   [NOT the hidden template]"
        lines.append(line)
    return lines


def _system_summary(system) -> str:
    rules = sum(len(g.rules) for g in system.components)
    tuples = len(getattr(system, "sync", ()))
    return (f"Grammar system: {len(system.components)} component(s), {rules} rules, "
            f"{tuples} synchronised tuples; each component repeats its pattern, all the same "
            f"number of times")


def run_locate(args) -> int:
    """``psgs locate``: learn from --learn performances, print where each FILE holds the action."""
    from ..induce import locate

    # through the registry, as psgs induce does: an unknown --param is its one-line
    # ValidationError, where PAL(...) raised the constructor's TypeError (a traceback)
    learned = _inducer("pal", args.param).induce(_load_performances(args.learn))
    if not learned.components:
        raise ValidationError(f"nothing learnt from the --learn performances: "
                              f"{learned.verdict or 'no component'}")
    found = {name: locate(learned, ag, threshold=args.threshold)
             for name, ag in zip(args.file, _load_performances(args.file))}
    if args.json:
        print(json.dumps({"components": list(learned.components),
                          "actuators": list(learned.actuators),
                          "found": {n: [[s.start, s.stop, s.score] for s in spans]
                                    for n, spans in found.items()}}, indent=2))
        return 0
    print(f"learnt from {len(args.learn)} performance(s): joints "
          f"{', '.join(learned.actuators) or ', '.join(learned.components)}")
    for name, spans in found.items():
        if not spans:
            print(f"{name}: not found")
            continue
        print(f"{name}: " + ", ".join(f"{s.start:.2f}-{s.stop:.2f} s (score {s.score:.2f})"
                                      for s in spans))
    return 0
