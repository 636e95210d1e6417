"""``psgs check FILE WORD…``: is this word tuple in the system's language?

Exit status: 0 yes, 1 no (the reason is printed), 2 an error (a bad file or
bad words: one line on stderr), 3 unknown (the budget that ran out is
printed); the table of every command is ``psgs._foundation.shell.EXIT_STATUS_HELP``.
"""

from __future__ import annotations

import dataclasses

from ..errors import ValidationError
from ..model import PCGS, PSGS, Terminal
from .._foundation.shell import INCOMPLETE, NO, OK, positive_float, positive_int
from ._types import grammar_file

YES, UNKNOWN = OK, INCOMPLETE


def register(subparsers) -> None:
    """Add ``check`` to the ``psgs`` command."""
    check = subparsers.add_parser(
        "check", help="decide whether words are in the language of a grammar system",
        description="Decide membership. A PSGS takes one WORD per component, a PCGS one word "
                    "for its master. A WORD is symbols separated by spaces inside one argument "
                    "(\"up down up\"), or a plain string of one-character symbols (\"abcd\"); "
                    "'' is the empty word. Exit status: 0 yes, 1 no, 2 error, 3 unknown (a "
                    "budget ran out).")
    check.add_argument("file", metavar="FILE", type=grammar_file,
                       help="a .psgs file, or the name of an example (paper_example, ...)")
    check.add_argument("words", metavar="WORD", nargs="*", help="one word per component")
    check.add_argument("--trace", action="store_true",
                       help="print the witness derivation when the answer is yes")
    check.add_argument("--mode", choices=("parallel", "single"),
                       help="PSGS: override the file's rewriting mode")
    check.add_argument("--max-states", type=positive_int, default=200_000, metavar="N",
                       help="search budget in states (default 200000)")
    check.add_argument("--max-seconds", type=positive_float, default=30.0, metavar="S",
                       help="search budget in seconds (default 30)")
    check.add_argument("--max-steps", type=positive_int, default=200, metavar="K",
                       help="PCGS: longest derivation searched (default 200)")
    check.set_defaults(run=run_check)


def read_word(text: str, system) -> tuple[Terminal, ...]:
    """A command-line word: split at white space, else one symbol per character.

    A space-free argument that is itself a (multi-character) terminal of the
    system is that one symbol.
    """
    if any(ch.isspace() for ch in text):
        return tuple(Terminal(s) for s in text.split())
    if not text:
        return ()
    if len(text) > 1 and Terminal(text) in system.terminals:
        return (Terminal(text),)
    return tuple(Terminal(ch) for ch in text)


def run_check(args) -> int:
    from ..membership import accepts
    from .core import load_system

    system = load_system(args.file)
    if args.mode is not None:
        if not isinstance(system, PSGS):
            raise ValidationError("--mode applies to a PSGS only")
        system = dataclasses.replace(system, mode=args.mode)
    if isinstance(system, PCGS):
        if len(args.words) != 1:
            raise ValidationError(f"a PCGS takes one word (its master's), not {len(args.words)}")
        words = read_word(args.words[0], system)
    else:
        n = len(system.components)
        if len(args.words) != n:
            raise ValidationError(f"{args.file}: the system has {n} components "
                                  f"({', '.join(system.component_names)}), so give {n} words, "
                                  f"not {len(args.words)}")
        words = [read_word(w, system) for w in args.words]
    result = accepts(system, words, max_states=args.max_states, max_seconds=args.max_seconds,
                     max_steps=args.max_steps)
    if result.answer == "yes":
        print("yes")
        if args.trace:
            print(result.witness)
        return YES
    if result.answer == "no":
        print(f"no: {result.reason}")
        return NO
    print(f"unknown: {result.reason} (budget: {result.bound})")
    return UNKNOWN
