"""Pictures of a grammar system: a forest of parse trees and the synchronisation graph.

The paper's Fig. 12 shows, for a learnt action, each component grammar as the
parse tree of a derived word, and which rules of different components are
synchronised. :func:`parse_forest` builds the trees from a derivation (one tree
per component; in ``parallel`` mode one step grows every occurrence of the
rewritten nonterminal), :func:`sync_edges` lists the synchronised rule pairs
(consecutive entries of each tuple of M; PCGS: each query, from the rule that
holds it to the queried component), and :func:`draw` renders both side by side:

* through Graphviz (the ``graphviz`` package, and Debian's ``graphviz`` for the
  ``dot`` program) when ``dot`` is on the PATH;
* with a matplotlib layout otherwise: per component a cell (its parse tree, leaves in
  word order, over its rules), at most :data:`PER_ROW` cells a row, further components
  wrapped onto more rows; synchronisation as tags ``Mk`` on the rules of tuple k of M
  (lines would cross the components between), explained in a legend.

:func:`to_svg` gives the SVG text (what notebooks show, ``_repr_svg_``).
"""

from __future__ import annotations

import shutil
from dataclasses import dataclass
from pathlib import Path

# MAX_NODES, the most parse-tree nodes drawn: its own module, which psgs draw --help reads
from ._draw_limits import MAX_NODES
from ._draw_matplotlib import PER_ROW, _PALETTE, _matplotlib, _rule_text
from .errors import MissingDependency, PSGSError, ValidationError
from .model import PCGS, PSGS, Query

__all__ = ["Forest", "parse_forest", "sync_edges", "draw", "to_svg", "graphviz_available",
           "PER_ROW", "MAX_NODES"]


@dataclass(frozen=True)
class Forest:
    """Parse trees of a derivation: ``labels[i]`` of node ``i``, ``children[i]`` its children.

    ``roots[c]`` is the root node of component ``c``; ``rules[i]`` the label of
    the rule that rewrote node ``i`` (``None`` for a leaf); ``complete`` is
    False when the trees stop before a terminal configuration. ``bound`` names the
    bound that stopped them (the derivation's, e.g. ``"max_steps"``, or ``"max_nodes"``
    when :func:`parse_forest` left steps out), ``None`` when they are terminal or the
    derivation is blocked; ``reason`` says it in words.

    Examples
    --------
    >>> import psgs
    >>> counting = psgs.load("grammars/counting.psgs")
    >>> forest = parse_forest(counting, seed=0)
    >>> forest.components, forest.roots, forest.complete
    (('G1', 'G2'), (0, 1), True)
    """

    components: tuple[str, ...]
    labels: tuple[str, ...]
    children: tuple[tuple[int, ...], ...]
    rules: tuple[str | None, ...]
    roots: tuple[int, ...]
    complete: bool
    bound: str | None = None
    reason: str | None = None

    def leaves(self, component: int) -> tuple[str, ...]:
        """The word under component ``component``'s tree, left to right."""
        out, stack = [], [self.roots[component]]
        while stack:
            node = stack.pop()
            if self.children[node]:
                stack.extend(reversed(self.children[node]))
            else:
                out.append(self.labels[node])
        return tuple(out)


def parse_forest(system: PSGS, derivation=None, *, seed: int = 0,
                 max_steps: int = 200, max_nodes: int | None = None) -> Forest:
    """The parse trees of ``derivation`` (default: a random one with ``seed``).

    Parameters
    ----------
    system : PSGS
        A parallel synchronous grammar system (PCGS: ValidationError; use :func:`draw`,
        which shows a PCGS's rules and queries).
    derivation : psgs.Derivation, optional
        Default ``psgs.random_derivation(system, seed, max_steps=max_steps)``.
    max_nodes : int, optional
        At most this many nodes in the trees: the steps of the derivation up to the last
        one that keeps within it (the forest's ``bound`` is then ``"max_nodes"``). None:
        every step.

    Returns
    -------
    Forest

    Raises
    ------
    ValidationError
        For a PCGS, a derivation of another system, or a ``max_nodes`` that is not a
        whole number ≥ 1.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> f = parse_forest(gamma, seed=1)
    >>> "".join(f.leaves(0)) in {"abcdbcad" * k for k in range(1, 20)}
    True
    >>> cut = parse_forest(gamma, seed=1, max_nodes=20)
    >>> len(cut.labels) <= 20, cut.complete, cut.bound
    (True, False, 'max_nodes')
    """
    from .budget import check_count
    from .derivation import Derivation, random_derivation

    if max_nodes is not None:
        check_count(max_nodes, "max_nodes")
    if not isinstance(system, PSGS):
        raise ValidationError("a forest of parse trees is drawn for a PSGS; a PCGS "
                              "communicates forms between components")
    if derivation is None:
        derivation = random_derivation(system, seed, max_steps=max_steps)
    elif not isinstance(derivation, Derivation):
        raise ValidationError(f"derivation must be a Derivation, not {type(derivation).__name__}")
    elif derivation.system != system:
        # another system's steps would be drawn under this one's axioms, without an error
        raise ValidationError("derivation is a derivation of another system")
    labels: list[str] = []
    children: list[list[int]] = []
    rules: list[str | None] = []

    def node(label: str) -> int:
        labels.append(label)
        children.append([])
        rules.append(None)
        return len(labels) - 1

    roots = tuple(node(str(axiom)) for axiom in system.axioms)
    fronts = [[root] for root in roots]  # node of each symbol of each component's form
    bound, reason = derivation.bound, derivation.reason
    for done, step in enumerate(derivation.steps):
        # a step adds a node per symbol of each right side it writes (one for ε); parallel
        # rewriting doubles a form a step, so 17 steps of S -> S S made 262,000 nodes and a
        # picture of 130 MB after three minutes
        grown = sum(len(positions) * max(1, len(rule.rhs))
                    for rule, positions in zip(step.tuple, step.positions)
                    if rule is not None and positions)
        if max_nodes is not None and len(labels) + grown > max_nodes:
            bound = "max_nodes"
            reason = (f"drew the first {done} of {len(derivation.steps)} steps: the next "
                      f"would take the parse trees past {max_nodes} nodes (max_nodes)")
            break
        for c, (rule, positions) in enumerate(zip(step.tuple, step.positions)):
            if rule is None or not positions:
                continue
            front = fronts[c]
            replaced: list[int] = []
            for index, old in enumerate(front):
                if index in positions:
                    rules[old] = rule.label
                    kids = [node(str(s)) for s in rule.rhs] or [node("ε")]
                    children[old] = kids
                    replaced.extend(k for k, s in zip(kids, rule.rhs or (None,)) if s is not None)
                else:
                    replaced.append(old)
            fronts[c] = replaced
    complete = bound != "max_nodes" and derivation.is_terminal
    return Forest(system.component_names, tuple(labels), tuple(tuple(k) for k in children),
                  tuple(rules), roots, complete, None if complete else bound,
                  None if complete else reason)


def sync_edges(system: PSGS | PCGS) -> tuple[tuple[tuple[str, str], tuple[str, str], int], ...]:
    """Edges ``((component, rule), (component, rule), tuple index)`` of the synchronisation graph.

    PSGS: consecutive non-idle entries of each tuple of M. PCGS: from each rule
    holding a query ``?G`` to ``(G, "")`` (the queried component), index -1.

    Examples
    --------
    >>> import psgs
    >>> counting = psgs.load("grammars/counting.psgs")
    >>> sync_edges(counting)
    ((('G1', 'p1'), ('G2', 'q1'), 0), (('G1', 'p2'), ('G2', 'q2'), 1))
    """
    if not isinstance(system, (PSGS, PCGS)):
        raise ValidationError(f"sync_edges takes a PSGS or a PCGS, not {type(system).__name__}")
    names = system.component_names
    edges = []
    if isinstance(system, PSGS):
        for t, entries in enumerate(system.sync):
            used = [(names[c], r.label) for c, r in enumerate(entries) if r is not None]
            edges.extend((a, b, t) for a, b in zip(used, used[1:]))
    else:
        for c, grammar in enumerate(system.components):
            for rule in grammar.rules:
                for sym in rule.rhs:
                    if isinstance(sym, Query):
                        edges.append(((names[c], rule.label), (str(sym.component), ""), -1))
    return tuple(edges)


def graphviz_available() -> bool:
    """True when the ``graphviz`` package imports and the ``dot`` program is on the PATH.

    Examples
    --------
    >>> isinstance(graphviz_available(), bool)
    True
    """
    try:
        import graphviz  # noqa: F401
    except ImportError:
        return False
    return shutil.which("dot") is not None


def _graphviz(system, forest: Forest | None):
    import graphviz

    # nodes no taller than their text, half dot's rank gap, a point a pixel (dpi 72): a
    # 30-component system's PNG on under a third of the pixels, which is what it costs to rasterise
    graph = graphviz.Digraph(name=system.name or "system", graph_attr={
        "rankdir": "TB", "fontname": "Helvetica", "splines": "line", "ranksep": "0.25",
        "nodesep": "0.12", "dpi": "72"},
        node_attr={"fontname": "Helvetica", "fontsize": "10", "height": "0.28",
                   "margin": "0.06,0.03"})
    if forest is not None:
        with graph.subgraph(name="cluster_forest") as trees:
            trees.attr(label="parse trees of a derived word", style="dashed")
            for c, root in enumerate(forest.roots):
                with trees.subgraph(name=f"cluster_tree_{c}") as tree:
                    tree.attr(label=forest.components[c], style="solid",
                              color=_PALETTE[c % len(_PALETTE)])
                    stack = [root]
                    while stack:
                        n = stack.pop()
                        leaf = not forest.children[n]
                        tree.node(f"t{n}", forest.labels[n], shape="plaintext" if leaf else
                                  "ellipse", fontcolor="black" if leaf else
                                  _PALETTE[c % len(_PALETTE)])
                        for k in forest.children[n]:
                            tree.edge(f"t{n}", f"t{k}", arrowhead="none")
                        stack.extend(forest.children[n])
    with graph.subgraph(name="cluster_sync") as sync:
        sync.attr(label="synchronisation graph", style="dashed")
        for c, grammar in enumerate(system.components):
            with sync.subgraph(name=f"cluster_rules_{c}") as box:
                box.attr(label=grammar.name, style="solid", color=_PALETTE[c % len(_PALETTE)])
                for rule in grammar.rules:
                    box.node(f"r{c}_{rule.label}", _rule_text(rule), shape="box")
                for a, b in zip(grammar.rules, grammar.rules[1:]):  # one column per component
                    box.edge(f"r{c}_{a.label}", f"r{c}_{b.label}", style="invis")
        index = {name: c for c, name in enumerate(system.component_names)}
        for (ca, ra), (cb, rb), t in sync_edges(system):
            a = f"r{index[ca]}_{ra}"
            if rb:
                sync.edge(a, f"r{index[cb]}_{rb}", dir="none", constraint="false",
                          color=_PALETTE[t % len(_PALETTE)], tooltip=f"tuple {t + 1} of M")
            else:
                first = system.components[index[cb]].rules[0].label
                sync.edge(a, f"r{index[cb]}_{first}", style="dashed", label=f"?{cb}",
                          constraint="false")
    return graph


def _render(system, forest: Forest | None, fmt: str, engine: str) -> bytes:
    """The picture's bytes: Graphviz when asked (or ``auto`` and available), else matplotlib.

    Under ``auto``, a Graphviz failure (``dot`` gives up on some large layouts)
    falls back to matplotlib instead of failing.
    """
    import io

    if engine == "graphviz" or (engine == "auto" and graphviz_available()):
        if not graphviz_available():  # asked for by name: say what it needs
            raise MissingDependency("engine='graphviz' needs the graphviz package (pip install "
                                    "'psgs[praxicon]') and Graphviz's dot program on the PATH "
                                    "(apt-get install graphviz, brew install graphviz)")
        import graphviz

        try:
            return _graphviz(system, forest).pipe(format=fmt, quiet=True)
        except (graphviz.CalledProcessError, graphviz.ExecutableNotFound) as exc:
            if engine == "graphviz":
                raise ValidationError(f"graphviz could not draw this system: "
                                      f"{str(exc).splitlines()[0]}") from None
    try:
        import matplotlib
        import matplotlib.pyplot as plt
    except ImportError:  # a plain install: one line naming what to install, not a traceback
        raise PSGSError("drawing needs matplotlib (pip install 'psgs[plot]') or Graphviz (the "
                        "dot program and pip install graphviz)") from None

    fig = _matplotlib(system, forest)
    buffer = io.BytesIO()
    # the same ids in every run; text as SVG text, not glyph outlines: a system of thirty-odd
    # components has some two thousand labels, and outlining them was most of its drawing time
    with matplotlib.rc_context({"svg.hashsalt": "psgs", "svg.fonttype": "none"}):
        fig.savefig(buffer, format=fmt, dpi=120,
                    metadata={"Date": None} if fmt == "svg" else None)
    plt.close(fig)
    return buffer.getvalue()


def _trees_of(system: PSGS, forest: Forest) -> bool:
    """Whether ``forest`` could be parse trees of ``system``: its components and axioms, and
    every rewritten node a rule of its component, the rule's left side above its right."""
    if forest.components != system.component_names or \
            tuple(forest.labels[r] for r in forest.roots) != tuple(map(str, system.axioms)):
        return False
    for grammar, root in zip(system.components, forest.roots):
        stack = [root]
        while stack:
            node = stack.pop()
            label = forest.rules[node]
            if label is None:
                continue
            rule = grammar.rule_by_label.get(label)
            below = tuple(forest.labels[k] for k in forest.children[node])
            if rule is None or forest.labels[node] != str(rule.lhs) or \
                    below != (tuple(map(str, rule.rhs)) or ("ε",)):
                return False
            stack.extend(forest.children[node])
    return True

def _forest_or_none(system, derivation, seed: int, max_steps: int,
                    engine: str, max_nodes: int | None = None,
                    forest: Forest | None = None) -> Forest | None:
    """The parse trees of a PSGS's derivation (given, or drawn with ``seed``), or ``forest``
    when given; None for a PCGS."""
    # draw's checks, to_svg's too: it drew an unknown engine as auto, a non-system raised
    # an AttributeError
    if engine not in ("auto", "graphviz", "matplotlib"):
        raise ValidationError(f"engine must be auto, graphviz or matplotlib, not {engine!r}")
    if not isinstance(system, (PSGS, PCGS)):
        raise ValidationError(f"draw takes a PSGS or a PCGS, not {type(system).__name__}")
    if forest is not None:
        if not isinstance(forest, Forest):
            raise ValidationError(f"forest must be a Forest, not {type(forest).__name__}")
        if derivation is not None or max_nodes is not None:
            # the forest is drawn as it is: a derivation or a bound beside it would be unused
            raise ValidationError("give forest, or the derivation and max_nodes to build it "
                                  "from, not both")
    if isinstance(system, PSGS):
        if forest is None:
            return parse_forest(system, derivation, seed=seed, max_steps=max_steps,
                                max_nodes=max_nodes)
        # another system's trees would be drawn beside this one's rules, without an error
        if not _trees_of(system, forest):
            raise ValidationError("forest holds the parse trees of another system")
        return forest
    if derivation is not None or forest is not None:
        raise ValidationError(f"a PCGS is drawn without parse trees: give no "
                              f"{'derivation' if forest is None else 'forest'}")
    return None


def to_svg(system: PSGS | PCGS, *, seed: int = 0, max_steps: int = 200,
           engine: str = "auto", derivation=None, max_nodes: int | None = None,
           forest: Forest | None = None) -> str:
    """The picture of :func:`draw` as SVG text (its parameters are :func:`draw`'s).

    Examples
    --------
    >>> import psgs
    >>> counting = psgs.load("grammars/counting.psgs")
    >>> svg = to_svg(counting, engine="matplotlib")
    >>> svg.startswith("<?xml"), "<svg" in svg
    (True, True)
    """
    forest = _forest_or_none(system, derivation, seed, max_steps, engine, max_nodes, forest)
    return _render(system, forest, "svg", engine).decode("utf-8")


def draw(system: PSGS | PCGS, path: str | Path, *, seed: int = 0, max_steps: int = 200,
         engine: str = "auto", derivation=None, max_nodes: int | None = None,
         forest: Forest | None = None) -> Path:
    """Draw the forest of parse trees of a derived word and the synchronisation graph.

    Parameters
    ----------
    system : PSGS or PCGS
        A PCGS gets its rules and query edges, no forest.
    path : str or Path
        ``.svg`` or ``.png``.
    seed, max_steps : int
        The random derivation whose word is drawn.
    engine : {"auto", "graphviz", "matplotlib"}
        ``auto``: Graphviz when :func:`graphviz_available`, else matplotlib.
    derivation : psgs.Derivation, optional
        A derivation of ``system`` (a PSGS) to draw instead of the random one of ``seed``
        and ``max_steps``: a caller that also reports on it derives it once.
    max_nodes : int, optional
        The most nodes of the parse trees drawn (see :func:`parse_forest`); None: every
        step. The time of a picture grows with its nodes (Graphviz's faster than linearly:
        8,000 nodes took 17 s), so a caller that draws what it does not know passes one,
        e.g. :data:`MAX_NODES`.
    forest : Forest, optional
        The parse trees to draw, as :func:`parse_forest` built them for ``system`` (then
        no ``derivation`` nor ``max_nodes``; ``seed`` and ``max_steps`` are not used): a
        caller that also reports on them (what stopped them) builds them once. Trees that
        are not ``system``'s (another component, axiom or rule) are refused.

    Returns
    -------
    Path

    Raises
    ------
    ValidationError
        For a suffix other than ``.svg``/``.png``, an unknown engine, a derivation or forest
        of another system (or of a PCGS), or a forest with a derivation or ``max_nodes``.

    Examples
    --------
    >>> import psgs, tempfile, pathlib
    >>> out = draw(psgs.load("grammars/paper_example.psgs"),
    ...            pathlib.Path(tempfile.mkdtemp()) / "gamma.svg", engine="matplotlib")
    >>> out.read_text()[:5]
    '<?xml'
    >>> counting = psgs.load("grammars/counting.psgs")
    >>> trees = parse_forest(counting, seed=2, max_nodes=4)
    >>> trees.bound
    'max_nodes'
    >>> out = draw(counting, out.with_name("cut.svg"), engine="matplotlib", forest=trees)
    >>> out.read_bytes() == to_svg(counting, seed=2, max_nodes=4, engine="matplotlib").encode()
    True
    """
    path = Path(path)
    fmt = path.suffix.lower().lstrip(".")
    if fmt not in ("svg", "png"):
        raise ValidationError(f"{path}: draw writes .svg or .png, not {path.suffix or 'no suffix'!r}")
    forest = _forest_or_none(system, derivation, seed, max_steps, engine, max_nodes, forest)
    path.write_bytes(_render(system, forest, fmt, engine))
    return path


# -- notebook views (``_repr_svg_`` / ``_repr_html_`` of systems, actiongrams, inductions) -------
_HTML_SYMBOLS = 60  # symbols shown per string; the rest is counted


def _escape(text: object) -> str:
    import html

    return html.escape(str(text), quote=True)


def system_svg(system) -> str | None:
    """A system's picture as SVG for a notebook, or None when it cannot be drawn here."""
    try:
        return to_svg(system, max_steps=60, max_nodes=MAX_NODES)
    except Exception:  # no matplotlib, a system too large for dot: the notebook shows text
        return None


def _colour(symbol: str, alphabet: list[str], colours) -> str:
    return colours.get(symbol) or _PALETTE[alphabet.index(symbol) % len(_PALETTE)]


def actiongram_html(actiongram, colours=None) -> str:
    """An actiongram as an HTML table: per string its symbols as coloured runs (width = time).

    ``colours`` (symbol -> CSS colour) fixes the colours of the symbols that have a meaning
    to whoever made the actiongram (kinetology's ``kinetology.plotting.STATE_COLOURS`` for its
    four states); other symbols take the palette in alphabetical order. A notebook shows an
    actiongram with the palette alone: psgs gives symbols no meaning.

    >>> from psgs import Actiongram
    >>> html = actiongram_html(Actiongram.from_strings({"knee": "BGRY"}), {"B": "#1f5fd6"})
    >>> "<table" in html and "background:#1f5fd6" in html
    True
    """
    colours = dict(colours or {})
    alphabet = sorted({s for row in actiongram.symbols for s in row})
    total = max((sum(d) for d in actiongram.segment_durations), default=0.0) or 1.0
    rows = []
    for name, symbols, durations in zip(actiongram.names, actiongram.symbols,
                                        actiongram.segment_durations):
        cells = "".join(
            f'<span title="{_escape(s)} {d:g}" style="display:inline-block;height:1.1em;'
            f'width:{max(0.15, 100 * d / total):.2f}%;background:{_colour(s, alphabet, colours)};'
            f'color:white;font-size:0.7em;overflow:hidden">{_escape(s)}</span>'
            for s, d in list(zip(symbols, durations))[:_HTML_SYMBOLS])
        more = f" … (+{len(symbols) - _HTML_SYMBOLS})" if len(symbols) > _HTML_SYMBOLS else ""
        rows.append(f"<tr><td><code>{_escape(name)}</code></td><td style='width:100%'>"
                    f"{cells}{more}</td><td>{len(symbols)}</td></tr>")
    return ("<table><tr><th>string</th><th>symbols (width: duration)</th><th>n</th></tr>"
            + "".join(rows) + "</table>")


def induction_html(induction) -> str:
    """An induction as HTML: verdict, actuators, each component's pattern, the system's picture."""
    head = (f"<p><b>{_escape(induction.inducer or 'induction')}</b>: "
            f"{len(induction.components)} component(s)")
    actuators = getattr(induction, "actuators", ())
    if actuators:
        head += f", actuators {_escape(', '.join(actuators))}"
    verdict = getattr(induction, "verdict", "")
    if verdict:
        head += f" — {_escape(verdict)}"
    rows = "".join(f"<tr><td><code>{_escape(c)}</code></td><td><code>"
                   f"{_escape(' '.join(induction.patterns.get(c, ())))}</code></td></tr>"
                   for c in induction.components)
    table = f"<table><tr><th>component</th><th>pattern</th></tr>{rows}</table>" if rows else ""
    picture = system_svg(induction.system) if induction.system is not None else None
    return head + "</p>" + table + (picture or "")
