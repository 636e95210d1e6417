"""The matplotlib picture of :func:`psgs.draw.draw`, and what its Graphviz picture shares.

Per component a cell (its parse tree, leaves in word order, over its rules), at most
:data:`PER_ROW` cells a row; synchronisation as tags ``Mk`` on the rules of tuple k of M.
A module of its own so that :mod:`psgs.draw` (the forest, the edges, the renderers' choice,
the notebook views) stays within a module's length.
"""

from __future__ import annotations

from .model import PSGS, Query

# the forests drawn here are psgs.draw.Forest values, named in no annotation: an import of
# psgs.draw (which imports this module) would close a cycle

_PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2",
            "#17becf", "#bcbd22", "#7f7f7f")


def _rule_text(rule) -> str:
    rhs = " ".join(str(s) for s in rule.rhs) or "ε"
    return f"{rule.label}: {rule.lhs} → {rhs}"


PER_ROW = 8  # components side by side in a matplotlib picture; more wrap onto further rows


def _tuples_of(system) -> dict[tuple[str, str], list[int]]:
    """(component, rule) -> the tuples of M (0-based) that hold the rule (PSGS only)."""
    member: dict[tuple[str, str], list[int]] = {}
    if isinstance(system, PSGS):
        names = system.component_names
        for t, entries in enumerate(system.sync):
            for c, rule in enumerate(entries):
                if rule is not None:
                    member.setdefault((names[c], rule.label), []).append(t)
    return member


def _place_tree(forest, root: int):
    """x (leaf order) and depth of every node under ``root``; returns (x, depth, width)."""
    x_of: dict[int, float] = {}
    depth: dict[int, int] = {root: 0}
    cursor = 0.0
    stack: list[tuple[int, bool]] = [(root, False)]
    while stack:  # iterative post-order: a long derivation is a deep tree
        node, done = stack.pop()
        kids = forest.children[node]
        if done:
            x_of[node] = sum(x_of[k] for k in kids) / len(kids)
        elif not kids:
            x_of[node] = cursor
            cursor += 1.0
        else:
            stack.append((node, True))
            for k in reversed(kids):
                depth[k] = depth[node] + 1
                stack.append((k, False))
    return x_of, depth, max(cursor, 1.0)


# characters of a rule that fit its cell: 6-point monospace (0.6 of the size a character) on
# the cell's 1.96 inches right of the tags
_RULE_CHARS = int(1.96 * 72 / (0.6 * 6))


def _fitted(text: str, most: int = _RULE_CHARS) -> str:
    """``text``, cut to ``most`` characters with an ellipsis when longer: a cut rule says so.

    Examples
    --------
    >>> _fitted("p: S → a S", 40), _fitted("r1: N_Hips_rx_1 → N_Hips_rx_2 N_Hips_rx_3", 20)
    ('p: S → a S', 'r1: N_Hips_rx_1 → N…')
    """
    return text if len(text) <= most else text[:most - 1] + "…"


def _cell(ax, box, xlim, ylim):
    """The transform from a cell's own coordinates (``xlim`` by ``ylim``) onto ``box`` (left,
    bottom, width, height in inches) of ``ax``, whose data coordinates are inches."""
    from matplotlib.transforms import Affine2D

    left, bottom, width, height = box
    sx, sy = width / (xlim[1] - xlim[0]), height / (ylim[1] - ylim[0])
    return Affine2D().scale(sx, sy).translate(left - xlim[0] * sx,
                                              bottom - ylim[0] * sy) + ax.transData


def _inches_box(ax, box):
    """``box`` (left, bottom, width, height in inches) as a clip box of ``ax``."""
    from matplotlib.transforms import Bbox, TransformedBbox

    return TransformedBbox(Bbox.from_bounds(*box), ax.transData)


def _matplotlib(system, forest):
    """Components in rows of at most :data:`PER_ROW`; per component its rules (and its parse
    tree) in its own cell, so that no line crosses another component.

    Synchronisation is drawn as tags, not lines: a rule in tuple k of M carries ``Mk``, in
    tuple k's colour, and the legend says what a tag means; a line between two components
    would cross every component between them, idle ones included.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    n = len(system.components)
    columns = min(n, PER_ROW)
    rows = -(-n // columns)
    member = _tuples_of(system)
    tall = max(len(g.rules) for g in system.components)
    placed = [_place_tree(forest, root) for root in forest.roots] if forest is not None else []
    deep = max((max(d.values()) for _, d, _ in placed), default=-1) + 1
    tree_h = 0.0 if forest is None else min(6.0, 0.6 + 0.18 * deep)
    rule_h = 0.5 + 0.28 * tall
    cell_w = 2.6
    fig = plt.figure(figsize=(0.4 + cell_w * columns, 1.4 + rows * (rule_h + tree_h + 0.4)))
    width_in, height = fig.get_figwidth(), fig.get_figheight()
    # one axes in inches for the whole picture, each cell placed by its own transform: an axes
    # per cell (two per component) cost more than the drawing itself in a praxicon system
    ax = fig.add_axes((0, 0, 1, 1))
    ax.set_axis_off()
    ax.set_xlim(0, width_in)
    ax.set_ylim(0, height)
    top = 1 - 0.9 / height
    band = (top - 0.5 / height) / rows
    for c, grammar in enumerate(system.components):
        row, col = divmod(c, columns)
        colour = _PALETTE[c % len(_PALETTE)]
        left = 0.2 + col * cell_w
        width = cell_w - 0.15
        y0 = (top - (row + 1) * band) * height
        share = tree_h / (tree_h + rule_h)
        rules = (left, y0, width, band * (1 - share) * 0.9 * height)
        low = -tall + 0.4  # the cell's rules from y=1 (the name) down to one row per rule
        cell = _cell(ax, rules, (0.0, 1.0), (low, 1.0))
        clip = _inches_box(ax, rules)
        ax.text(0.5, 0.8, grammar.name, ha="center", va="center", fontweight="bold",
                fontsize=8, color=colour, transform=cell)
        for r, rule in enumerate(grammar.rules):
            tags = member.get((grammar.name, rule.label), [])
            # the tag first, then the rule: a long rule is clipped at the cell's edge, never
            # drawn over its tag or the next component
            text = ax.text(0.2, -r, _fitted(_rule_text(rule)), ha="left", va="center",
                           fontsize=6, family="monospace", clip_on=True, transform=cell)
            text.set_clip_box(clip)
            if tags:
                ax.text(0.0, -r, " ".join(f"M{t + 1}" for t in tags[:2])
                        + ("…" if len(tags) > 2 else ""), ha="left", va="center",
                        fontsize=6, color="white", fontweight="bold", transform=cell,
                        bbox=dict(boxstyle="round,pad=0.15", lw=0,
                                  fc=_PALETTE[tags[0] % len(_PALETTE)]))
            for sym in rule.rhs:
                if isinstance(sym, Query):
                    ax.text(0.0, -r, f"?{sym.component}", ha="left", va="center",
                            fontsize=6, color="black", transform=cell,
                            bbox=dict(boxstyle="round,pad=0.15", lw=0.5, fc="white",
                                      ec="black", ls="--"))
        if forest is not None:
            x_of, depth, wide = placed[c]
            tree_box = (left, y0 + band * (1 - share) * height, width,
                        band * share * 0.95 * height)
            tree = _cell(ax, tree_box, (-0.8, wide - 0.2), (-deep + 0.5, 0.6))
            segments = [[(x_of[p], -depth[p]), (x_of[k], -depth[k])]
                        for p in x_of for k in forest.children[p]]
            from matplotlib.collections import LineCollection

            ax.add_collection(LineCollection(segments, colors=colour, linewidths=0.6,
                                             transform=tree))
            small = max(3.0, min(6.0, 60 / wide))
            for node, x in x_of.items():
                leaf = not forest.children[node]
                ax.text(x, -depth[node], forest.labels[node], ha="center", va="center",
                        fontsize=small, color="black" if leaf else colour, transform=tree)
    what = ("each component's parse tree of a derived word (top) and its rules (below); "
            if forest is not None else "each component's rules; ")
    if isinstance(system, PSGS):
        legend = (what + "a tag Mk: the rule belongs to tuple k of M (rules with the same tag "
                  "are applied together, components without it idle)")
    else:
        legend = what + "?G: the rule queries component G (its form is communicated)"
    fig.text(0.5, 1 - 0.3 / height, system.name or "system", ha="center", va="center",
             fontsize=10, fontweight="bold")
    fig.text(0.5, 1 - 0.6 / height, legend, ha="center", va="center", fontsize=7,
             wrap=True)
    return fig
