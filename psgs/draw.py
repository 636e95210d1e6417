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
* with a matplotlib layout otherwise (leaves in word order, a parent over its
  children; rules of a component in one column, synchronisation as lines).

:func:`to_svg` gives the SVG text (what notebooks show, ``_repr_svg_``).
"""

from __future__ import annotations

import shutil
from dataclasses import dataclass
from pathlib import Path

from .errors import PSGSError, ValidationError
from .model import PCGS, PSGS, Query

__all__ = ["Forest", "parse_forest", "sync_edges", "draw", "to_svg", "graphviz_available"]

_PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2",
            "#17becf", "#bcbd22", "#7f7f7f")


@dataclass(frozen=True)
class Forest:
    """Parse trees of a derivation: ``labels[i]`` of node ``i``, ``children[i]`` its children.

    ``roots[c]`` is the root node of component ``c``; ``rules[i]`` the label of
    the rule that rewrote node ``i`` (``None`` for a leaf); ``complete`` is
    False when the derivation stopped before a terminal configuration.

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
                 max_steps: int = 200) -> Forest:
    """The parse trees of ``derivation`` (default: a random one with ``seed``).

    Parameters
    ----------
    system : PSGS
        A parallel synchronous grammar system (PCGS: ValidationError; use :func:`draw`,
        which shows a PCGS's rules and queries).
    derivation : psgs.Derivation, optional
        Default ``psgs.random_derivation(system, seed, max_steps=max_steps)``.

    Returns
    -------
    Forest

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> f = parse_forest(gamma, seed=1)
    >>> "".join(f.leaves(0)) in {"abcdbcad" * k for k in range(1, 20)}
    True
    """
    from .derivation import random_derivation

    if not isinstance(system, PSGS):
        raise ValidationError("a forest of parse trees is drawn for a PSGS; a PCGS "
                              "communicates forms between components")
    if derivation is None:
        derivation = random_derivation(system, seed, max_steps=max_steps)
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
    for step in derivation.steps:
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
    return Forest(system.component_names, tuple(labels), tuple(tuple(k) for k in children),
                  tuple(rules), roots, derivation.is_terminal)


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


def _rule_text(rule) -> str:
    rhs = " ".join(str(s) for s in rule.rhs) or "ε"
    return f"{rule.label}: {rule.lhs} → {rhs}"


def _graphviz(system, forest: Forest | None):
    import graphviz

    graph = graphviz.Digraph(name=system.name or "system", graph_attr={
        "rankdir": "TB", "fontname": "Helvetica", "splines": "line"},
        node_attr={"fontname": "Helvetica", "fontsize": "10"})
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


def _matplotlib(system, forest: Forest | None):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(system.components)
    tall = max(len(g.rules) for g in system.components)
    fig, axes = plt.subplots(1, 2 if forest is not None else 1, squeeze=False,
                             figsize=(6 + 3 * n, 1.5 + 0.45 * tall + (2 if forest else 0)))
    if forest is not None:
        ax = axes[0][0]
        ax.set_title("parse trees of a derived word")
        x_of: dict[int, float] = {}
        depth: dict[int, int] = {}
        cursor = 0.0
        for c, root in enumerate(forest.roots):
            def place(node: int, d: int) -> float:
                nonlocal cursor
                depth[node] = d
                kids = forest.children[node]
                if not kids:
                    x_of[node] = cursor
                    cursor += 1.0
                else:
                    xs = [place(k, d + 1) for k in kids]
                    x_of[node] = sum(xs) / len(xs)
                return x_of[node]
            place(root, 0)
            cursor += 1.5
            colour = _PALETTE[c % len(_PALETTE)]
            stack = [root]
            while stack:
                node = stack.pop()
                for k in forest.children[node]:
                    ax.plot([x_of[node], x_of[k]], [-depth[node], -depth[k]], color=colour,
                            lw=0.8)
                    stack.append(k)
                ax.text(x_of[node], -depth[node], forest.labels[node], ha="center",
                        va="center", fontsize=7,
                        bbox=dict(boxstyle="round", fc="white", ec=colour, lw=0.5))
        ax.axis("off")
    ax = axes[0][-1]
    ax.set_title("synchronisation graph")
    where = {}
    for c, grammar in enumerate(system.components):
        ax.text(c, 1, grammar.name, ha="center", fontweight="bold",
                color=_PALETTE[c % len(_PALETTE)])
        for r, rule in enumerate(grammar.rules):
            where[grammar.name, rule.label] = (c, -r)
            ax.text(c, -r, _rule_text(rule), ha="center", va="center", fontsize=7,
                    bbox=dict(boxstyle="square", fc="white", ec="grey", lw=0.5))
    for a, b, t in sync_edges(system):
        end = where.get(b) or where[(b[0], system.components[system.index(b[0])].rules[0].label)]
        (xa, ya), (xb, yb) = where[a], end
        ax.plot([xa, xb], [ya, yb], color=_PALETTE[t % len(_PALETTE)], lw=1,
                ls="-" if t >= 0 else "--", alpha=0.7, zorder=0)
    ax.set_xlim(-0.7, n - 0.3)
    ax.set_ylim(-tall, 1.5)
    ax.axis("off")
    fig.tight_layout()
    return fig


def _render(system, forest: Forest | None, fmt: str, engine: str) -> bytes:
    """The picture's bytes: Graphviz when asked (or ``auto`` and available), else matplotlib.

    Under ``auto``, a Graphviz failure (``dot`` gives up on some large layouts)
    falls back to matplotlib instead of failing.
    """
    import io

    if engine == "graphviz" or (engine == "auto" and graphviz_available()):
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
    with matplotlib.rc_context({"svg.hashsalt": "psgs"}):  # the same ids in every run
        fig.savefig(buffer, format=fmt, dpi=120,
                    metadata={"Date": None} if fmt == "svg" else None)
    plt.close(fig)
    return buffer.getvalue()


def _forest_or_none(system, seed: int, max_steps: int) -> Forest | None:
    return parse_forest(system, seed=seed, max_steps=max_steps) if isinstance(system, PSGS) \
        else None


def to_svg(system: PSGS | PCGS, *, seed: int = 0, max_steps: int = 200,
           engine: str = "auto") -> str:
    """The picture of :func:`draw` as SVG text.

    Examples
    --------
    >>> import psgs
    >>> counting = psgs.load("grammars/counting.psgs")
    >>> svg = to_svg(counting, engine="matplotlib")
    >>> svg.startswith("<?xml"), "<svg" in svg
    (True, True)
    """
    forest = _forest_or_none(system, seed, max_steps)
    return _render(system, forest, "svg", engine).decode("utf-8")


def draw(system: PSGS | PCGS, path: str | Path, *, seed: int = 0, max_steps: int = 200,
         engine: str = "auto") -> Path:
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

    Returns
    -------
    Path

    Raises
    ------
    ValidationError
        For a suffix other than ``.svg``/``.png`` or an unknown engine.

    Examples
    --------
    >>> import psgs, tempfile, pathlib
    >>> out = draw(psgs.load("grammars/paper_example.psgs"),
    ...            pathlib.Path(tempfile.mkdtemp()) / "gamma.svg", engine="matplotlib")
    >>> out.read_text()[:5]
    '<?xml'
    """
    path = Path(path)
    fmt = path.suffix.lower().lstrip(".")
    if fmt not in ("svg", "png"):
        raise ValidationError(f"{path}: draw writes .svg or .png, not {path.suffix or 'no suffix'!r}")
    if engine not in ("auto", "graphviz", "matplotlib"):
        raise ValidationError(f"engine must be auto, graphviz or matplotlib, not {engine!r}")
    forest = _forest_or_none(system, seed, max_steps)
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
        return to_svg(system, max_steps=60)
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
