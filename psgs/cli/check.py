"""``psgs check FILE WORD…``: is this word tuple in the system's language?

Exit status: 0 yes, 1 no (the reason is printed), 2 an error (a bad file or
bad words: one line on stderr), 3 unknown (the budget that ran out is
printed); the table of every command is ``psgs._foundation.shell.EXIT_STATUS_HELP``.
With ``--nearest``: 0 distance 0, 1 a distance above 0 (or none within
``--max-errors``, or an empty language), 3 a budget ran out first.
"""

from __future__ import annotations

import dataclasses
import sys

from ..errors import ValidationError
from ..model import PCGS, PSGS, Terminal
from .._foundation.shell import INCOMPLETE, NO, OK, non_negative_float, positive_float, positive_int
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
    check.add_argument("--max-symbols", type=positive_int, default=10_000_000, metavar="N",
                       help="memory budget: the symbols the search's states hold together "
                            "(default 10000000)")
    check.add_argument("--max-steps", type=positive_int, default=200, metavar="K",
                       help="PCGS: longest derivation searched (default 200)")
    check.add_argument("--nearest", action="store_true",
                       help="print the distance to the language, a nearest word tuple and the "
                            "edits under the input (exit 0 at distance 0, 1 above, 3 when a "
                            "budget ran out)")
    check.add_argument("--max-errors", type=non_negative_float, default=None, metavar="D",
                       help="with --nearest: look no further than distance D")
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
    if args.nearest:
        return _run_nearest(system, words, args)
    if args.max_errors is not None:
        raise ValidationError("--max-errors applies with --nearest only")
    result = accepts(system, words, max_states=args.max_states, max_seconds=args.max_seconds,
                     max_steps=args.max_steps, max_symbols=args.max_symbols)
    if result.answer == "yes":
        print("yes")
        if args.trace:
            print(result.witness)
        return YES
    if result.answer == "no":
        print(f"no: {result.reason}")
        return NO
    print(f"unknown: {result.reason} (budget: {result.bound})")
    _name_bound(result.bound, result.reason)
    return UNKNOWN


def _name_bound(bound, reason) -> None:
    """The bound a search stopped at, on stderr (as every command's exit status 3 says)."""
    print(f"psgs: the search stopped at its bound {bound}: {reason}", file=sys.stderr)


def _run_nearest(system, words, args) -> int:
    from ..membership import nearest

    result = nearest(system, words, max_errors=args.max_errors, max_states=args.max_states,
                     max_seconds=args.max_seconds, max_steps=args.max_steps,
                     max_symbols=args.max_symbols)
    print(result)
    if result.words is not None:
        if isinstance(system, PCGS):
            rows = [("master", words, result.words, result.edits)]
        else:
            rows = zip(system.component_names, words, result.words, result.edits)
        for name, given, found, edits in rows:
            print(f"{name}:")
            for line in aligned(given, found, edits):
                print(f"  {line}")
    if not result.exact and result.bound is not None:  # a definite answer names no bound
        _name_bound(result.bound, result.reason)
    if result.distance is None:
        return NO if result.exact else UNKNOWN
    if not result.exact:
        return UNKNOWN
    return YES if result.distance == 0 else NO


def aligned(given, found, edits) -> list[str]:
    """Three lines: the input, the edit marks, the nearest word, one column per aligned symbol.

    ``=`` keeps, ``~`` substitutes, ``-`` deletes (nothing below), ``+`` inserts.

    Examples
    --------
    >>> from psgs.membership.costs import Edit
    >>> from psgs.model import Terminal as T, as_word
    >>> for line in aligned(as_word("abxd"), as_word("abcd"), [Edit("substitute", 2, T("x"), T("c"), 1)]):
    ...     print(line)
    input   a b x d
    edit    = = ~ =
    nearest a b c d
    """
    top, mid, bottom = ["input  "], ["edit   "], ["nearest"]
    by_position: dict[int, list] = {}
    for e in edits:
        by_position.setdefault(e.position, []).append(e)

    def column(a: str, mark: str, b: str) -> None:
        width = max(len(a), len(b), 1)
        top.append(a.ljust(width))
        mid.append(mark.ljust(width))
        bottom.append(b.ljust(width))

    for p in range(len(given) + 1):
        handled = False
        for e in by_position.get(p, ()):
            if e.op == "insert":
                column("", "+", e.new.name)
            elif e.op == "delete":
                column(given[p].name, "-", "")
                handled = True
            else:
                column(given[p].name, "~", e.new.name)
                handled = True
        if p < len(given) and not handled:
            column(given[p].name, "=", given[p].name)
    del found  # the bottom row is rebuilt from the edits; the caller checked they agree
    return [" ".join(row).rstrip() for row in (top, mid, bottom)]
