"""The ``psgs`` command line.

Each group of subcommands lives in its own module with a ``register(subparsers)``
function; errors derived from :class:`psgs.PSGSError` (and file errors) become
one line on stderr and a non-zero exit status, never a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys

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
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
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
    return parser


def main(argv: list[str] | None = None, commands=None) -> int:
    from ..errors import PSGSError

    parser = build_parser(commands)
    args, unrecognized = parser.parse_known_args(argv)
    error_status = getattr(args, "error_status", None)
    error_status = 2 if error_status is None else error_status
    if unrecognized:  # what parse_args does, but with the subcommand's error status
        parser.print_usage(sys.stderr)
        print(f"psgs: error: unrecognized arguments: {' '.join(unrecognized)}", file=sys.stderr)
        return error_status
    try:
        status = args.run(args)
    except PSGSError as exc:
        print(f"psgs: error: {exc}", file=sys.stderr)
        return error_status
    except BrokenPipeError:
        # the reader (e.g. `| head`) went away: stop quietly, as Unix tools do
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 141
    except OSError as exc:
        where = f"{exc.filename}: " if getattr(exc, "filename", None) else ""
        print(f"psgs: error: {where}{exc.strerror or exc}", file=sys.stderr)
        return error_status
    except KeyboardInterrupt:
        print("psgs: interrupted", file=sys.stderr)
        return 130
    return int(status or 0)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
