"""``psgs draw FILE -o out.svg|png``: a grammar system's parse-tree forest and synchronisation graph.

Exit status 0 when the trees drawn are those of a terminal derivation, or of one that is
blocked (the picture shows it whole; a note on stderr says so); 3 when a bound stopped them:
the derivation's (``--max-steps``, ``--max-seconds``, the longest form, the symbols kept) or
the picture's (``--max-nodes``). The picture is written either way.
"""

from __future__ import annotations

from .._foundation.shell import INCOMPLETE, file_name, natural, positive_float, positive_int


def run_draw(args) -> int:
    import sys

    from ..derivation import random_derivation
    from ..draw import draw, graphviz_available, parse_forest
    from ..model import PSGS
    from .core import load_system

    system = load_system(args.file)  # a nonterminal without a rule warned of, as show does
    engine = args.engine
    # the derivation whose trees are drawn, made once: the lines below say whether it ended
    derivation = random_derivation(system, args.seed, max_steps=args.max_steps,
                                   max_seconds=args.max_seconds) \
        if isinstance(system, PSGS) else None
    # the trees drawn, built once: what stopped them is said below (--max-nodes may cut the
    # trees of a derivation that ended, too)
    forest = parse_forest(system, derivation, max_nodes=args.max_nodes) \
        if derivation is not None else None
    path = draw(system, args.output, engine=engine, forest=forest)
    used = "graphviz" if engine == "graphviz" or (engine == "auto" and graphviz_available()) \
        else "matplotlib"
    print(f"{path} ({used})")
    if forest is None:
        return 0
    if forest.bound is None and derivation.is_terminal:
        return 0
    if forest.bound is not None:
        what = "the picture" if forest.bound == "max_nodes" else \
            f"the derivation drawn (seed {args.seed})"
        print(f"psgs: {what} stopped at its bound {forest.bound}: {forest.reason}; its "
              f"parse trees are unfinished", file=sys.stderr)
        return INCOMPLETE
    # not derivation.status: it asks whether a step applies, and the derivation says it
    # already (no bound, not terminal: no step applied)
    print(f"psgs: note: the derivation drawn (seed {args.seed}) is blocked; its parse trees "
          f"are unfinished", file=sys.stderr)
    return 0


def register(subparsers) -> None:
    """Add ``draw`` to the ``psgs`` command."""
    from .._draw_limits import MAX_NODES  # not psgs.draw: --help does not need the drawing

    draw = subparsers.add_parser(
        "draw", help="draw a grammar system: parse trees of a derived word, synchronisation",
        description="Draw the component grammars as a forest of parse trees of a derived word "
                    "(a random derivation, --seed) beside the synchronisation graph; through "
                    "Graphviz when 'dot' is installed, matplotlib otherwise. Exit status 3 "
                    "when a bound stopped the trees (named on stderr; the picture is written).")
    from ._types import grammar_file  # a shipped example by name, as show and derive take it
    draw.add_argument("file", metavar="FILE", type=grammar_file,
                      help="a .psgs file, or the name of an example (paper_example, ...)")
    draw.add_argument("-o", "--output", required=True, metavar="OUT", type=file_name,
                      help="the picture, .svg or .png")
    draw.add_argument("--seed", type=natural, default=0, help="seed of the derivation drawn")
    draw.add_argument("--max-steps", type=positive_int, default=200, metavar="K",
                      help="longest derivation drawn (default 200)")
    draw.add_argument("--max-seconds", type=positive_float, default=60.0, metavar="S",
                      help="time budget of the derivation drawn, in seconds (default 60)")
    draw.add_argument("--max-nodes", type=positive_int, default=MAX_NODES, metavar="N",
                      help=f"most nodes of the parse trees drawn: the steps that keep within "
                           f"them (default {MAX_NODES}; a picture's time grows with them)")
    draw.add_argument("--engine", choices=("auto", "graphviz", "matplotlib"), default="auto",
                      help="auto: Graphviz where dot is installed, else matplotlib")
    draw.set_defaults(run=run_draw)
