"""The ``psgs`` command line.

Each group of subcommands lives in its own module with a ``register(subparsers)``
function; errors derived from :class:`psgs.PSGSError` (and file errors) become
one line on stderr and exit status 2, never a traceback. The exit statuses are
one table for ``psgs`` and ``kinetology`` alike (:data:`EXIT_STATUS_HELP`,
docs/cli.md), printed at the end of every ``--help``.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys

# modules that add subcommands; each defines register(subparsers)
_COMMAND_MODULES = ("core", "check", "induce", "bench")

#: Exit statuses of every psgs and kinetology subcommand.
OK, NO, ERROR, INCOMPLETE = 0, 1, 2, 3
INTERRUPTED, BROKEN_PIPE = 130, 141

#: The table at the end of every ``--help`` (kinetology.cli keeps an equal copy; a test
#: checks that they agree, since kinetology does not import the psgs command line).
EXIT_STATUS_HELP = """\
exit status (the same for every psgs and kinetology command):
  0    yes / done
  1    no: check: the words are not in the language; derive: the random derivation is
       blocked, or --enumerate found no word up to --max-length
  2    usage or input error: a bad option, a file that cannot be read or is malformed
       (one line on stderr, never a traceback)
  3    a bound was hit or the answer is unknown: a search or derivation stopped at a
       budget (what was found is still printed; the bound is named on stderr)
  130  interrupted (Ctrl-C)
  141  the reader of the output went away (e.g. | head)"""


def version() -> str:
    """The installed distribution's version (``psgs.__version__`` when run from a checkout)."""
    from importlib import metadata
    try:
        return metadata.version("psgs")
    except metadata.PackageNotFoundError:
        from .. import __version__
        return __version__


class TableHelpFormatter(argparse.HelpFormatter):
    """Wraps descriptions as argparse does, but keeps text with line breaks (the exit-status
    table) as written."""

    def _fill_text(self, text, width, indent):
        if "\n" in text:
            return "".join(indent + line for line in text.splitlines(keepends=True))
        return super()._fill_text(text, width, indent)


def with_exit_status_help(parser: argparse.ArgumentParser, table: str) -> None:
    """Put ``table`` at the end of the help of ``parser`` and of every subcommand under it."""
    parser.epilog = table
    parser.formatter_class = TableHelpFormatter
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in set(action.choices.values()):
                with_exit_status_help(sub, table)


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``psgs`` command (one subparser per subcommand)."""
    parser = argparse.ArgumentParser(
        prog="psgs", description="Parallel grammar systems: derive, check, export, induce.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {version()}",
                        help="print the version and exit")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND",
                                help="the subcommand (COMMAND --help for its options)")
    sub.required = True
    for name in _COMMAND_MODULES:
        try:
            module = importlib.import_module(f".{name}", __name__)
        except ModuleNotFoundError as exc:
            if exc.name != f"{__name__}.{name}":
                raise
            continue
        module.register(sub)
    with_exit_status_help(parser, EXIT_STATUS_HELP)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run the ``psgs`` command; returns the exit status (see :data:`EXIT_STATUS_HELP`)."""
    from ..errors import PSGSError

    parser = build_parser()
    args = parser.parse_args(argv)  # a usage error exits 2, as every input error does
    try:
        status = args.run(args)
    except PSGSError as exc:
        print(f"psgs: error: {exc}", file=sys.stderr)
        return ERROR
    except BrokenPipeError:
        # the reader (e.g. `| head`) went away: stop quietly, as Unix tools do
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return BROKEN_PIPE
    except OSError as exc:
        where = f"{exc.filename}: " if getattr(exc, "filename", None) else ""
        print(f"psgs: error: {where}{exc.strerror or exc}", file=sys.stderr)
        return ERROR
    except RecursionError:  # the last line of defence: a limit of Python, not a traceback
        print("psgs: error: the input nests too deeply (Python's recursion limit)",
              file=sys.stderr)
        return ERROR
    except MemoryError:
        print("psgs: out of memory: the work needs more memory than there is; lower a budget",
              file=sys.stderr)
        return INCOMPLETE
    except KeyboardInterrupt:
        print("psgs: interrupted", file=sys.stderr)
        return INTERRUPTED
    return int(status or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
