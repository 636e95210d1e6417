"""The ``psgs`` command line.

Each group of subcommands lives in its own module with a ``register(subparsers)``
function; errors derived from :class:`psgs.PSGSError` (and file errors) become
one line on stderr and exit status 2, never a traceback. The shell (exit statuses, their
table at the end of every ``--help``, argument types, the error handling) is the one every
command of the distribution runs in, :mod:`psgs._foundation.shell`; other packages add
subcommands through the entry-point group ``psgs.commands`` (praxicon, kinetology).
"""

from __future__ import annotations

import argparse
import importlib
import sys

from .._foundation.shell import add_version, run, with_exit_status_help

# modules that add subcommands; each defines register(subparsers)
_COMMAND_MODULES = ("core", "check", "induce", "bench", "draw")


def _plugin_commands(given) -> dict:
    """Subcommands of other packages (entry-point group ``psgs.commands``: name = register)."""
    from importlib.metadata import entry_points

    commands = dict(given or {})
    for ep in sorted(entry_points(group="psgs.commands"), key=lambda e: e.name):
        if ep.name not in commands:
            try:
                commands[ep.name] = ep.load()
            except Exception as exc:  # a broken plug-in: say which in one line, go on
                print(f"psgs: warning: command {ep.name!r} could not be loaded: "
                      f"{type(exc).__name__}: {exc}", file=sys.stderr)
    return commands


def build_parser(commands=None) -> argparse.ArgumentParser:
    """The parser; ``commands`` adds name -> register(subparsers) beside the plug-ins'."""
    parser = argparse.ArgumentParser(
        prog="psgs", description="Parallel grammar systems: derive, check, export, induce.")
    add_version(parser)
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
    for register in _plugin_commands(commands).values():
        register(sub)
    with_exit_status_help(parser)
    return parser


def main(argv: list[str] | None = None, commands=None) -> int:
    """Run the ``psgs`` command; returns the exit status (the shell's table).

    ``commands`` adds subcommands (name -> register) beside the ``psgs.commands`` plug-ins.
    """
    return run(build_parser(commands), argv)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
