"""The ``kinetology`` command: segment, compress, decompress, evaluate, plot.

Every error a user can cause (a bad file, an unknown channel, a bad number) is one of the
project's errors (:class:`psgs.PSGSError`), one line on stderr and exit status 2, never a
traceback; any other exception is a bug and keeps its traceback. The command runs in the
shell every command of the distribution shares (:mod:`psgs._foundation.shell`: the exit
statuses, printed at the end of every ``--help``); it is also ``psgs kinetology ...``
(entry-point group ``psgs.commands``).
"""

from __future__ import annotations

import argparse
import sys

from psgs._foundation.shell import add_version, run, with_exit_status_help

# each group of subcommands adds its parsers and holds its handlers; they import numpy and the
# modules that do the work when a handler runs, so making the parser (every --help and
# --version) does not load them
from ._commands import codec, evaluate, plot, segment
# the least a take needs to be segmented, under the name it has always had here
from ._commands.files import MIN_FRAMES  # noqa: F401


def _add_commands(sub) -> None:
    """Add segment, compress, decompress, evaluate and plot under ``sub``."""
    segment.register(sub)
    codec.register(sub)
    evaluate.register(sub)
    plot.register(sub)
    from ._viewer_cli import register as register_view  # kinetology view: the skeleton player
    register_view(sub)


_DESCRIPTION = ("Motion capture (BVH, ASF/AMC) in, actiongrams out; compression by segments; "
                "the paper's kinetological principles measured.")


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of the ``kinetology`` command (one subparser per subcommand)."""
    parser = argparse.ArgumentParser(prog="kinetology", description=_DESCRIPTION)
    add_version(parser)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True,
                                help="the subcommand (COMMAND --help for its options)")
    _add_commands(sub)
    with_exit_status_help(parser)
    return parser


def register(subparsers) -> None:
    """Add ``kinetology`` (segment, compress, ...) to psgs's subcommands (``psgs.commands``)."""
    parser = subparsers.add_parser("kinetology", help="motion capture in, actiongrams out",
                                   description=_DESCRIPTION)
    sub = parser.add_subparsers(dest="kinetology_command", metavar="COMMAND", required=True,
                                help="the subcommand (COMMAND --help for its options)")
    _add_commands(sub)


def main(argv: list[str] | None = None) -> int:
    """Run the ``kinetology`` command; returns the exit status (the shell's table)."""
    return run(build_parser(), argv)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
