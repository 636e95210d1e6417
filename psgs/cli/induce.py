"""``psgs induce``: learn a grammar system from an actiongram file, or the built-in example.

It prints the components, their patterns and the system (or JSON with
``--json``). ``psgs synth`` and ``psgs bench`` are in :mod:`psgs.cli.bench`.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

from ..errors import ValidationError


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
    induce.add_argument("file", metavar="FILE", nargs="?", help="an actiongram file")
    induce.add_argument("--example", action="store_true",
                        help="use the built-in synthetic example (20 strings, 4 patterned)")
    induce.add_argument("--inducer", default="pal", help="pal (default), sequential, or a "
                                                         "plug-in's name")
    induce.add_argument("--param", action="append", default=[], metavar="K=V",
                        help="an inducer parameter, e.g. --param alpha=1e-6 (repeatable)")
    induce.add_argument("--json", action="store_true",
                        help="print one JSON object (the system as text under 'system')")
    induce.add_argument("-o", "--output", metavar="OUT.psgs",
                        help="also write the grammar system to this file")
    induce.set_defaults(run=run_induce)


# -- argument types -------------------------------------------------------------------
def _parse_value(text: str):
    lowered = text.lower()
    if lowered in ("true", "false"):
        return lowered == "true"
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def _params(items: list[str]) -> dict:
    out = {}
    for item in items:
        key, eq, value = item.partition("=")
        if not eq or not key:
            raise ValidationError(f"--param {item!r}: write KEY=VALUE")
        out[key.strip()] = _parse_value(value.strip())
    return out


def _make_inducer(name: str, params: dict):
    """The inducer ``name`` built with ``params`` (``get`` says what is wrong in one line)."""
    from ..induce import get

    return get(name, **params)


# -- psgs induce -------------------------------------------------------------------------
EXAMPLE_SEED = 1
EXAMPLE_NOISE = 0.1


def run_induce(args) -> int:
    """``psgs induce``: learn from FILE (or the built-in example) and print or write the result.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed ``psgs induce`` arguments.

    Returns
    -------
    int
        0.

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
    from ..actiongram import load_actiongram
    from ..format import dumps
    from ..induce.synthetic import generate

    inducer = _make_inducer(args.inducer, _params(args.param))
    truth = None
    if args.file and args.example:
        raise ValidationError("give FILE or --example, not both")
    if args.file:
        actiongram = load_actiongram(args.file)
    else:
        truth = generate(seed=EXAMPLE_SEED, noise=EXAMPLE_NOISE)
        actiongram = truth.actiongram
    began = time.perf_counter()
    result = inducer.induce(actiongram)
    seconds = time.perf_counter() - began
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
        return 0
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
    out.append(f"{result.inducer}: {len(result.components)} component(s) of "
               f"{len(actiongram)} strings, {actiongram.total_symbols} symbols, "
               f"in {seconds * 1000:.0f} ms")
    for name in result.components:
        pattern = " ".join(result.patterns[name])
        where = result.occurrences[name]
        times = ", ".join(f"{a:g}-{b:g}" for a, b in where[:3]) + (", ..." if len(where) > 3
                                                                      else "")
        line = f"  {name}: {pattern}   ({len(where)} copies at t = {times})"
        if truth is not None:
            ok = truth.patterns.get(name) == tuple(result.patterns[name])
            line += "   [the hidden template]" if ok else "   [NOT the hidden template]"
        out.append(line)
    dropped: dict[str, int] = {}
    for report in result.reports:
        if report.status == "component":
            continue
        if report.name in result.components:  # kept, with a caveat (e.g. a search bound hit)
            out.append(f"  note: {report.name}: {report.status}")
        else:
            dropped[report.status] = dropped.get(report.status, 0) + 1
    if dropped:
        out.append("  dropped: " + ", ".join(f"{n} {why}" for why, n in sorted(dropped.items())))
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
        out.append("No grammar system: no string repeats in step with another.")
    else:
        out.append("Grammar system (each component repeats its pattern, all the same number of "
                   "times):")
        out.append(system_text.rstrip("\n"))
    print("\n".join(out))
    return 0
