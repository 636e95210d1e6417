"""The shell every command of the distribution runs in: ``psgs``, ``kinetology`` and plug-ins.

One table of exit statuses (printed at the end of every ``--help``), one help formatter, the
argument types that refuse bad text with one clear line, and :func:`run`, which turns every
error of the project's tree (:class:`psgs.errors.PSGSError`) and every file error into one
line on stderr and an exit status, never a traceback. Any other exception is a bug and
propagates with its traceback.
"""

from __future__ import annotations

import argparse
import math
import os
import sys

from ..errors import PSGSError, ValidationError

__all__ = ["OK", "NO", "ERROR", "INCOMPLETE", "INTERRUPTED", "BROKEN_PIPE", "EXIT_STATUS_HELP",
           "version", "add_version", "TableHelpFormatter", "with_exit_status_help", "natural",
           "positive_int", "positive_float", "share", "file_name", "parse_value", "key_values",
           "run"]

#: Exit statuses of every psgs and kinetology subcommand.
OK, NO, ERROR, INCOMPLETE = 0, 1, 2, 3
INTERRUPTED, BROKEN_PIPE = 130, 141

#: The table at the end of every ``--help`` (docs/cli.md holds the same statuses).
EXIT_STATUS_HELP = """\
exit status (the same for every psgs and kinetology command):
  0    yes / done
  1    no: check: the words are not in the language; derive: the random derivation is
       blocked, or --enumerate found no word up to --max-length; praxicon build: no
       action was learnt (every one failed; the folder records why); praxicon verify:
       a file of the folder is not what its records give
  2    usage or input error: a bad option, a file that cannot be read or is malformed
       (one line on stderr, never a traceback)
  3    a bound was hit or the answer is unknown: a search or derivation stopped at a
       budget (what was found is still printed; the bound is named on stderr)
  130  interrupted (Ctrl-C)
  141  the reader of the output went away (e.g. | head)"""


def version() -> str:
    """The installed distribution's version (``psgs.__version__`` when run from a checkout).

    kinetology and praxicon ship in the psgs distribution, so every command prints this one.

    Returns
    -------
    str
        The version, e.g. ``"0.1.0"``.

    Examples
    --------
    >>> import psgs
    >>> version() == psgs.__version__ or version()  # an installed copy may differ
    True
    """
    from importlib import metadata
    try:
        return metadata.version("psgs")
    except metadata.PackageNotFoundError:
        from . import __version__
        return __version__


class _VersionAction(argparse.Action):
    """``--version``: the version is looked up when the option is given, not when the parser
    is made (the lookup reads the installed distribution's metadata, which every other
    command and every ``--help`` paid for)."""

    def __init__(self, option_strings, dest=argparse.SUPPRESS, default=argparse.SUPPRESS,
                 help=None):
        super().__init__(option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(self, parser, namespace, values, option_string=None):
        # as argparse's version action does: the line on stdout, then exit status 0
        sys.stdout.write(f"{parser.prog} {version()}\n")
        parser.exit()


def add_version(parser: argparse.ArgumentParser) -> None:
    """Give ``parser`` a ``--version`` option printing ``PROG VERSION`` (:func:`version`).

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser.

    Examples
    --------
    >>> import contextlib, io
    >>> parser = argparse.ArgumentParser(prog="demo")
    >>> add_version(parser)
    >>> out = io.StringIO()
    >>> with contextlib.redirect_stdout(out):
    ...     try:
    ...         parser.parse_args(["--version"])
    ...     except SystemExit as exc:
    ...         status = exc.code
    >>> status, out.getvalue() == f"demo {version()}\\n"
    (0, True)
    """
    parser.add_argument("--version", action=_VersionAction, help="print the version and exit")


class TableHelpFormatter(argparse.HelpFormatter):
    """Wraps descriptions as argparse does, but keeps text with line breaks (the exit-status
    table) as written.

    Examples
    --------
    >>> parser = argparse.ArgumentParser(prog="x", epilog="a\\n  b",
    ...                                  formatter_class=TableHelpFormatter)
    >>> parser.format_help().endswith("a\\n  b\\n")
    True
    """

    def _fill_text(self, text, width, indent):
        if "\n" in text:
            return "".join(indent + line for line in text.splitlines(keepends=True))
        return super()._fill_text(text, width, indent)


def with_exit_status_help(parser: argparse.ArgumentParser,
                          table: str = EXIT_STATUS_HELP) -> None:
    """Put ``table`` at the end of the help of ``parser`` and of every subcommand under it.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser, with its subcommands added.
    table : str, default EXIT_STATUS_HELP
        The text to end every help with.

    Examples
    --------
    >>> parser = argparse.ArgumentParser(prog="x")
    >>> with_exit_status_help(parser)
    >>> parser.format_help().rstrip().endswith("(e.g. | head)")
    True
    """
    parser.epilog = table
    parser.formatter_class = TableHelpFormatter
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in dict.fromkeys(action.choices.values()):
                with_exit_status_help(sub, table)


# -- argument types: each refuses bad text with one line (argparse adds the option's name) --
def _whole(text: str, minimum: int) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < minimum:
        raise argparse.ArgumentTypeError(
            f"{value} is negative" if minimum == 0 else f"must be at least {minimum}")
    return value


def natural(text: str) -> int:
    """A whole number ≥ 0 (lengths, seeds).

    Parameters
    ----------
    text : str
        The option's text.

    Returns
    -------
    int
        The number.

    Examples
    --------
    >>> natural("0")
    0
    >>> natural("-1")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: -1 is negative
    """
    return _whole(text, 0)


def positive_int(text: str) -> int:
    """A whole number ≥ 1 (budgets, counts, workers).

    Parameters
    ----------
    text : str
        The option's text.

    Returns
    -------
    int
        The number.

    Examples
    --------
    >>> positive_int("3")
    3
    >>> positive_int("x")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: 'x' is not a whole number
    """
    return _whole(text, 1)


def _number(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return value


def positive_float(text: str) -> float:
    """A finite number > 0 (seconds, frame rates).

    Parameters
    ----------
    text : str
        The option's text.

    Returns
    -------
    float
        The number.

    Raises
    ------
    argparse.ArgumentTypeError
        For text that is not a positive finite number.

    Examples
    --------
    >>> positive_float("2.5")
    2.5
    >>> positive_float("nan")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: 'nan' is not a finite number
    """
    value = _number(text)
    if not value > 0:
        raise argparse.ArgumentTypeError("must be positive")
    return value


def non_negative_float(text: str) -> float:
    """A finite number >= 0 (a distance, a count of errors).

    Parameters
    ----------
    text : str
        The option's text.

    Returns
    -------
    float
        The number.

    Raises
    ------
    argparse.ArgumentTypeError
        For text that is not a finite number of 0 or more.

    Examples
    --------
    >>> non_negative_float("0")
    0.0
    >>> non_negative_float("-1")
    Traceback (most recent call last):
    ...
    argparse.ArgumentTypeError: -1 is negative
    """
    value = _number(text)
    if value < 0:
        raise argparse.ArgumentTypeError(f"{text} is negative")
    return value


def share(text: str) -> float:
    """A number from 0 to 1 (noise levels, fractions).

    Parameters
    ----------
    text : str
        The option's text.

    Returns
    -------
    float
        The number.

    Raises
    ------
    argparse.ArgumentTypeError
        For text that is not a number from 0 to 1.

    Examples
    --------
    >>> share("0.25")
    0.25
    """
    value = _number(text)
    if not 0 <= value <= 1:
        raise argparse.ArgumentTypeError(f"{text} is not between 0 and 1")
    return value


def file_name(text: str) -> str:
    """A file's name (to read or to write), as given; the type of every such argument.

    An empty name is refused by :func:`run`, in one line naming the argument, before the
    command runs: ``Path("")`` is the current folder, so ``''`` read as ``.`` (``.: Is a
    directory``), and ``''`` where no option means "not given" was taken for none at all.
    (Refused here, argparse would print its usage before the line.)

    Parameters
    ----------
    text : str
        The argument's text.

    Returns
    -------
    str
        ``text`` unchanged.

    Examples
    --------
    >>> file_name("walk.bvh")
    'walk.bvh'
    """
    return text


file_name.names_a_file = True  # what run() looks for; other types may carry it too


def _empty_file_name(parser: argparse.ArgumentParser, args) -> str | None:
    """The refusal of the first file argument given as ``''`` (types with ``names_a_file``),
    among the arguments of ``parser`` and of the subcommands chosen in ``args``."""
    actions = list(parser._actions)
    while actions:
        action = actions.pop(0)
        if isinstance(action, argparse._SubParsersAction):
            chosen = action.choices.get(getattr(args, action.dest, None) or "")
            actions.extend(chosen._actions if chosen is not None else ())
        elif getattr(action.type, "names_a_file", False):
            value = getattr(args, action.dest, None)
            if value == "" or (isinstance(value, list) and "" in value):
                name = "/".join(action.option_strings) or action.metavar or action.dest
                return f"argument {name}: the file name is empty ('')"
    return None


def parse_value(text: str) -> bool | int | float | str:
    """The value of a ``KEY=VALUE`` option: a bool, an int, a float, or the text itself.

    Parameters
    ----------
    text : str
        The part after ``=``.

    Returns
    -------
    bool, int, float or str
        ``true``/``false`` (any case) as a bool, then whatever int or float reads.

    Examples
    --------
    >>> parse_value("True"), parse_value("3"), parse_value("0.5"), parse_value("numpy")
    (True, 3, 0.5, 'numpy')
    """
    lowered = text.lower()
    if lowered in ("true", "false"):
        return lowered == "true"
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def key_values(items: list[str], option: str = "--param") -> dict:
    """``KEY=VALUE`` options (repeatable) as a dict, each value read by :func:`parse_value`.

    Parameters
    ----------
    items : list of str
        The option's texts.
    option : str, default "--param"
        The option's name, for the message.

    Returns
    -------
    dict
        Key -> value.

    Raises
    ------
    ValidationError
        For an item without ``=`` or without a key, or a key given twice.

    Examples
    --------
    >>> key_values(["seed=3", "engine = numpy"])
    {'seed': 3, 'engine': 'numpy'}
    >>> key_values(["seed"])
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: --param 'seed': write KEY=VALUE
    >>> key_values(["seed=3", "seed = 5"])
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: --param seed is given twice (seed=3, then seed=5): give each key once
    """
    out: dict = {}
    given: dict[str, str] = {}  # key -> its item as written, for the message
    for item in items:
        key, eq, value = item.partition("=")
        key = key.strip()
        if not eq or not key:
            raise ValidationError(f"{option} {item!r}: write KEY=VALUE")
        if key in given:
            # the later one silently won before: a typo in a long command line went unseen
            raise ValidationError(f"{option} {key} is given twice ({given[key]}, then "
                                  f"{key}={value.strip()}): give each key once")
        given[key] = f"{key}={value.strip()}"
        out[key] = parse_value(value.strip())
    return out


def run(parser: argparse.ArgumentParser, argv: list[str] | None = None) -> int:
    """Parse ``argv`` and run the chosen subcommand (its ``run`` default); the exit status.

    Errors of the project's tree (:class:`~psgs.errors.PSGSError`) and file errors become
    one line on stderr, ``PROG: error: message``, and status 2; a search out of memory is
    status 3; Ctrl-C 130; a closed pipe 141 (quietly). Anything else is a bug and keeps its
    traceback. A file argument (:func:`file_name`) given as ``''`` is such a line too, before
    the subcommand runs.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        The command's parser; every subcommand sets ``run`` (a function of the parsed
        arguments returning the exit status, ``None`` for 0).
    argv : list of str, optional
        The arguments (default: ``sys.argv[1:]``). A usage error exits 2 (argparse).

    Returns
    -------
    int
        The exit status (:data:`EXIT_STATUS_HELP`).

    Examples
    --------
    >>> from psgs.errors import ValidationError
    >>> parser = argparse.ArgumentParser(prog="demo")
    >>> def fail(args):
    ...     raise ValidationError("no such thing")
    >>> parser.set_defaults(run=fail)
    >>> import contextlib, io
    >>> err = io.StringIO()
    >>> with contextlib.redirect_stderr(err):
    ...     status = run(parser, [])
    >>> status, err.getvalue()
    (2, 'demo: error: no such thing\\n')
    """
    prog = parser.prog
    args = parser.parse_args(argv)  # a usage error exits 2, as every input error does
    try:
        if problem := _empty_file_name(parser, args):
            raise ValidationError(problem)
        status = args.run(args)
    except PSGSError as exc:
        print(f"{prog}: error: {exc}", file=sys.stderr)
        return ERROR
    except BrokenPipeError:
        # the reader (e.g. `| head`) went away: stop quietly, as Unix tools do
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return BROKEN_PIPE
    except OSError as exc:
        where = f"{exc.filename}: " if getattr(exc, "filename", None) else ""
        print(f"{prog}: error: {where}{exc.strerror or exc}", file=sys.stderr)
        return ERROR
    except RecursionError:  # the last line of defence: a limit of Python, not a traceback
        print(f"{prog}: error: the input nests too deeply (Python's recursion limit)",
              file=sys.stderr)
        return ERROR
    except MemoryError:
        print(f"{prog}: out of memory: the work needs more memory than there is; lower a "
              f"budget", file=sys.stderr)
        return INCOMPLETE
    except KeyboardInterrupt:
        print(f"{prog}: interrupted", file=sys.stderr)
        return INTERRUPTED
    return int(status or 0)
