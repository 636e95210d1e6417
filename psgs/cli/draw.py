"""``psgs draw FILE -o out.svg|png``: a grammar system's parse-tree forest and synchronisation graph."""

from __future__ import annotations

from .._foundation.shell import file_name, natural, positive_int


def run_draw(args) -> int:
    import sys

    from ..derivation import random_derivation
    from ..draw import draw, graphviz_available
    from ..model import PSGS
    from .core import load_system

    system = load_system(args.file)  # a nonterminal without a rule warned of, as show does
    engine = args.engine
    # the derivation whose trees are drawn, made once: the note below says whether it ended
    derivation = random_derivation(system, args.seed, max_steps=args.max_steps) \
        if isinstance(system, PSGS) else None
    path = draw(system, args.output, engine=engine, derivation=derivation)
    used = "graphviz" if engine == "graphviz" or (engine == "auto" and graphviz_available()) \
        else "matplotlib"
    print(f"{path} ({used})")
    # the trees drawn are those of this derivation: unfinished where it did not end
    if derivation is not None and derivation.status != "terminal":
        print(f"psgs: note: the derivation drawn (seed {args.seed}) is {derivation.status}"
              f"{': ' + derivation.reason if derivation.reason else ''}; its parse trees "
              f"are unfinished", file=sys.stderr)
    return 0


def register(subparsers) -> None:
    """Add ``draw`` to the ``psgs`` command."""
    draw = subparsers.add_parser(
        "draw", help="draw a grammar system: parse trees of a derived word, synchronisation",
        description="Draw the component grammars as a forest of parse trees of a derived word "
                    "(a random derivation, --seed) beside the synchronisation graph; through "
                    "Graphviz when 'dot' is installed, matplotlib otherwise.")
    from ._types import grammar_file  # a shipped example by name, as show and derive take it
    draw.add_argument("file", metavar="FILE", type=grammar_file,
                      help="a .psgs file, or the name of an example (paper_example, ...)")
    draw.add_argument("-o", "--output", required=True, metavar="OUT", type=file_name,
                      help="the picture, .svg or .png")
    draw.add_argument("--seed", type=natural, default=0, help="seed of the derivation drawn")
    draw.add_argument("--max-steps", type=positive_int, default=200, metavar="K",
                      help="longest derivation drawn (default 200)")
    draw.add_argument("--engine", choices=("auto", "graphviz", "matplotlib"), default="auto",
                      help="auto: Graphviz where dot is installed, else matplotlib")
    draw.set_defaults(run=run_draw)
