"""The core subcommands: ``psgs derive``, ``psgs export`` and ``psgs show``.

Output on stdout is only the result (tuples, words, grammars, the summary),
so it can be piped; notes about bounds go to stderr. Exit status: 0 done,
1 no word (a blocked random derivation, an enumeration that found none),
2 an error (one line on stderr), 3 a bound stopped the work before it was
complete (what was found is still printed); see ``psgs._foundation.shell.EXIT_STATUS_HELP``.

FILE is a path or the name of an example shipped in the package
(``psgs show paper_example``). A nonterminal that has no rule (in its component; in a PCGS,
in any component, since forms travel) is a warning on stderr at load: the file is valid,
but a form holding it can never become terminal.
"""

from __future__ import annotations

import dataclasses
import re
import sys
import unicodedata
from pathlib import Path

from ..errors import ValidationError
from ..model import IDLE, PCGS, PSGS
from .._foundation.shell import INCOMPLETE, NO, natural, positive_float, positive_int
from ._types import example_names, grammar_file

_FILE_HELP = "a .psgs file, or the name of an example (paper_example, counting, ...)"


def rule_less_nonterminals(system: PSGS | PCGS) -> list[tuple[str, str]]:
    """``(component, nonterminal)`` for each nonterminal that no rule can rewrite.

    In a PSGS each component rewrites only its own form, so a nonterminal needs a rule in its
    own component; in a PCGS a form can be sent to another component, so a rule in any
    component will do.
    """
    if isinstance(system, PCGS):
        anywhere = {r.lhs for g in system.components for r in g.rules}
        rewritten = [anywhere] * len(system.components)
    else:
        rewritten = [set(g.rules_by_lhs) for g in system.components]
    return [(g.name, n.name) for g, have in zip(system.components, rewritten)
            for n in sorted(g.nonterminals, key=lambda n: n.name) if n not in have]


def load_system(path: str) -> PSGS | PCGS:
    """``psgs.load`` for the commands: a missing file names the shipped examples, and
    nonterminals without rules are a warning on stderr."""
    from ..format import load  # its reader's parser (lark) loads when a file is read

    try:
        system = load(path)
    except FileNotFoundError as exc:
        raise ValidationError(f"{path}: no such file (the shipped examples, usable by name: "
                              f"{', '.join(example_names())})") from exc
    for component, name in rule_less_nonterminals(system):
        print(f"psgs: warning: {path}: nonterminal {name} of component {component} has no "
              f"rule, so a form holding it never becomes terminal", file=sys.stderr)
    return system


def register(subparsers) -> None:
    """Add ``derive``, ``export`` and ``show`` to the ``psgs`` command."""
    derive = subparsers.add_parser(
        "derive", help="derive words of a grammar system: one random derivation or all up to "
                       "a length",
        description="Derive from a grammar system file. --random (the default) prints one "
                    "seeded random derivation in the paper's notation; --enumerate prints every "
                    "word tuple (PSGS) or master word (PCGS) up to --max-length, one per line, "
                    "in order of size. Exit status 1 when no word came out (a blocked derivation, "
                    "nothing up to the length), 3 when a bound stopped the work.")
    derive.add_argument("file", metavar="FILE", type=grammar_file, help=_FILE_HELP)
    how = derive.add_mutually_exclusive_group()
    how.add_argument("--random", action="store_true",
                     help="one random derivation (the default)")
    how.add_argument("--enumerate", action="store_true",
                     help="every word up to --max-length, in order of size")
    derive.add_argument("--seed", type=natural, default=0,
                        help="seed of --random, a whole number from 0 (default 0)")
    derive.add_argument("--max-steps", type=positive_int, default=10_000, metavar="K",
                        help="--random stops after K steps (default 10000)")
    derive.add_argument("--max-symbols", type=positive_int, default=10_000_000, metavar="N",
                        help="memory budget: --random stops before its configurations would "
                             "hold N symbols together, --enumerate before the configurations "
                             "it keeps would (default 10000000)")
    derive.add_argument("--max-length", type=natural, default=None, metavar="L",
                        help="--enumerate: total length bound (needed)")
    derive.add_argument("--max-configurations", type=positive_int, default=200_000, metavar="N",
                        help="--enumerate: search budget (default 200000)")
    derive.add_argument("--max-seconds", type=positive_float, default=60.0, metavar="S",
                        help="time budget in seconds of --random, and of --enumerate with its "
                             "analysis (default 60)")
    derive.add_argument("--mode", choices=("parallel", "single"),
                        help="PSGS: override the file's rewriting mode")
    derive.add_argument("--returning", choices=("yes", "no"),
                        help="PCGS: override the file's returning mode")
    derive.add_argument("--trace", action="store_true",
                        help="also print the derivation of each word (--enumerate) or each "
                             "step (--random)")
    derive.set_defaults(run=run_derive)

    export = subparsers.add_parser(
        "export", help="export each component's grammar (to Lark)",
        description="Write each component's context-free grammar as a Lark grammar: one "
                    "COMPONENT.lark file per component in DIR, or all of them to stdout.")
    export.add_argument("file", metavar="FILE", type=grammar_file, help=_FILE_HELP)
    export.add_argument("--to", choices=("lark",), default="lark", help="target (lark)")
    export.add_argument("-o", "--output", metavar="DIR", default=None,
                        help="directory for the .lark files (created if needed)")
    export.set_defaults(run=run_export)

    show = subparsers.add_parser(
        "show", help="a readable summary of a grammar system",
        description="Print the kind, settings, N, T, components with their rules, and the "
                    "tuples (PSGS) or the communication settings (PCGS).")
    show.add_argument("file", metavar="FILE", type=grammar_file, help=_FILE_HELP)
    show.set_defaults(run=run_show)


# ---------------------------------------------------------------- derive
def _system_for(args) -> PSGS | PCGS:
    system = load_system(args.file)
    if args.mode is not None:
        if not isinstance(system, PSGS):
            raise ValidationError("--mode applies to a PSGS; this file is a pcgs "
                                  "(use --returning)")
        system = dataclasses.replace(system, mode=args.mode)
    if args.returning is not None:
        if not isinstance(system, PCGS):
            raise ValidationError("--returning applies to a PCGS; this file is a psgs "
                                  "(use --mode)")
        system = dataclasses.replace(system, returning=args.returning == "yes")
    return system


def run_derive(args) -> int:
    system = _system_for(args)
    if args.enumerate:
        return _enumerate(system, args)
    if args.max_length is not None:
        raise ValidationError("--max-length goes with --enumerate")
    return _random(system, args)


def _show_words(system: PSGS | PCGS, words) -> str:
    from ..notation import format_configuration, format_form
    if isinstance(system, PCGS):
        return format_form(words, system)
    return format_configuration(words, system)


def _enumerate(system: PSGS | PCGS, args) -> int:
    from ..budget import Budget
    from ..enumeration import language
    if args.max_length is None:
        raise ValidationError("--enumerate needs --max-length L")
    # --max-seconds covers the witnesses of --trace too: each was a search of its own 30 s
    clock = Budget(args.max_seconds)
    found = language(system, args.max_length, max_configurations=args.max_configurations,
                     max_seconds=args.max_seconds, max_symbols=args.max_symbols)
    out = sys.stdout
    missing = []  # the witnesses a bound kept from being found
    for words in found:
        print(_show_words(system, words), file=out)
        if args.trace:
            line, bound = _witness(system, words, args, clock)
            print("  " + line, file=out)
            if bound is not None:
                missing.append(bound)
    if missing:
        print(f"psgs: no derivation was found for {len(missing)} of the words above within "
              f"the bounds ({', '.join(dict.fromkeys(missing))}); they are in the language all "
              f"the same", file=sys.stderr)
    if not found.complete:
        # not "the words up to length L": a budget can stop it before any tuple is checked
        said = ("the words above are those it found" if len(found)
                else "it found no word")
        print(f"psgs: the enumeration is incomplete: {found.reason}; {said} before it stopped, "
              f"not every word up to length {args.max_length}", file=sys.stderr)
        return INCOMPLETE
    if not len(found):  # say so: an empty stdout with status 0 looked like success
        print(f"psgs: no word up to length {args.max_length}", file=sys.stderr)
        return NO
    return INCOMPLETE if missing else 0


def _witness(system: PSGS | PCGS, words, args, clock) -> tuple[str, str | None]:
    """The derivation of ``words`` as a line, and the bound that kept it from being found
    (None when it was found), searched within the time --max-seconds leaves."""
    from ..membership import accepts
    if clock.expired():  # no search past the bound: each would still get its millisecond
        return "(no derivation searched: stopped at max_seconds)", "max_seconds"
    try:
        answer = accepts(system, words, max_seconds=clock.left(), max_symbols=args.max_symbols)
    except ModuleNotFoundError as exc:  # a membership back end not installed in this build
        return f"(no derivation: {exc})", None
    if answer.answer == "yes" and answer.witness is not None:
        return str(answer.witness), None
    return (f"(no derivation found: {answer.reason or answer.answer})",
            answer.bound if answer.answer == "unknown" else None)


def _random(system: PSGS | PCGS, args) -> int:
    from ..derivation import random_derivation
    from ..notation import format_configuration
    derivation = random_derivation(system, args.seed, max_steps=args.max_steps,
                                   max_symbols=args.max_symbols, max_seconds=args.max_seconds)
    if args.trace:
        print(format_configuration(derivation.configurations[0], system))
        for step in derivation.steps:
            print(f"  ⇒ {format_configuration(step.after, system)}    by {step}")
    else:
        print(derivation)
    if derivation.is_terminal:
        return 0
    if derivation.bound:
        print(f"psgs: the derivation did not finish: {derivation.reason or derivation.bound}",
              file=sys.stderr)
        return INCOMPLETE
    print("psgs: the derivation is blocked: no step applies to its last configuration",
          file=sys.stderr)
    return NO


# ---------------------------------------------------------------- export
def run_export(args) -> int:
    from ..lark_export import to_lark
    system = load_system(args.file)
    grammars = to_lark(system)
    if args.output is None:
        for k, (name, text) in enumerate(grammars.items()):
            if k:
                print()
            print(f"// ===== {name}.lark =====")
            print(text, end="")
        return 0
    if not args.output.strip():  # '' was the current directory, without a word
        raise ValidationError("-o needs a folder name (-o . for the current one)")
    directory = Path(args.output)
    if directory.exists() and not directory.is_dir():
        raise ValidationError(f"{directory}: a file, not a folder for the .lark files")
    directory.mkdir(parents=True, exist_ok=True)
    for name, text in grammars.items():
        path = directory / f"{name}.lark"
        path.write_text(text, encoding="utf-8")
        print(path)
    return 0


# ---------------------------------------------------------------- show
def run_show(args) -> int:
    system = load_system(args.file)
    print(summary(system), end="")
    return 0


def _natural_key(name: str):
    # the split's odd parts are its runs of decimal digits; isdigit() also holds for "²" or
    # "①", which int() refuses (a terminal named so made `psgs show` a ValueError)
    return [_by_value(part) if k % 2 else part
            for k, part in enumerate(re.split(r"(\d+)", name))]


def _by_value(digits: str) -> tuple[int, str]:
    """A run of decimal digits (of any script) keyed as its value orders it: fewer digits,
    leading zeros left out, is less; as many, the digits in order.

    Not int(): it refuses a run of more than 4,300 digits (Python's bound on a conversion
    whose time grows with the square of the digits), so a terminal named by 5,000 digits
    made `psgs show` a ValueError.
    """
    if not digits.isascii():
        digits = "".join(str(unicodedata.decimal(c)) for c in digits)
    digits = digits.lstrip("0")
    return len(digits), digits


def summary(system: PSGS | PCGS) -> str:
    """A readable description of a system, as ``psgs show`` prints it."""
    kind = "PSGS" if isinstance(system, PSGS) else "PCGS"
    n = len(system.components)
    lines = [f"{system.name}: a {kind} with {n} component{'s' if n != 1 else ''}"]
    if isinstance(system, PSGS):
        lines.append(f"  mode: {system.mode}" + (
            " (a rule rewrites every occurrence of its left side at once)"
            if system.mode == "parallel" else " (a rule rewrites one occurrence)"))
        lines.append(f"  unsynchronised: {system.unsynchronised}" + (
            " (a rule in no tuple applies on its own)" if system.unsynchronised == "free"
            else " (only the tuples of M apply)"))
    else:
        lines.append(f"  returning: {'yes' if system.returning else 'no'}" + (
            " (a queried component restarts from its axiom)" if system.returning
            else " (a queried component keeps its form)"))
        lines.append(f"  master: {system.master}")
        lines.append(f"  centralised: {'yes' if system.centralised else 'no'}" + (
            " (only the master queries)" if system.centralised else ""))
    nonterminals = sorted((s.name for s in system.nonterminals), key=_natural_key)
    terminals = sorted((s.name for s in system.terminals), key=_natural_key)
    lines.append(f"  N ({len(nonterminals)}): {' '.join(nonterminals)}")
    lines.append(f"  T ({len(terminals)}): {' '.join(terminals) if terminals else '(none)'}")
    label_width = max(len(r.label) for g in system.components for r in g.rules)
    for g in system.components:
        lines.append("")
        lines.append(f"component {g.name}: start {g.start}, {len(g.rules)} "
                     f"rule{'s' if len(g.rules) != 1 else ''}")
        for r in g.rules:
            lines.append(f"  {(r.label + ':').ljust(label_width + 1)} {r}")
    if isinstance(system, PSGS):
        lines.append("")
        lines.append(f"M: {len(system.sync)} tuple{'s' if len(system.sync) != 1 else ''}")
        for t in system.sync:
            lines.append("  (" + ", ".join("#" if r is IDLE else r.label for r in t) + ")")
        loose = [f"{g.name}: {', '.join(r.label for r in rules)}"
                 for g, rules in zip(system.components, system.unsynchronised_rules) if rules]
        if loose:
            how = ("applied on their own" if system.unsynchronised == "free"
                   else "never applied (strict)")
            lines.append(f"rules in no tuple ({how}): " + "; ".join(loose))
    return "\n".join(lines) + "\n"
