"""Draw docs/img/architecture.svg, the layers of the distribution (run from the repository root).

    python docs/architecture_picture.py

Plain SVG written by hand (no Graphviz binary needed), so that the picture is the same on
every machine; tests/core/test_architecture.py checks that the committed file is what this
script writes, and that every arrow it draws is an import the layer rules allow.
"""

from __future__ import annotations

import html
from pathlib import Path

#: box id -> (x, y, width, height, title, lines); the unit is the pixel, y grows downwards
BOXES = {
    "praxicon": (250, 20, 460, 90, "praxicon",
                 ["every action of a motion database: build, draw, generate,",
                  "recognise and parse new motion",
                  "praxicon/ (a psgs.commands plug-in: psgs praxicon ...)"]),
    "kinetology": (20, 140, 300, 90, "kinetology",
                   ["motion capture in, actiongrams out;",
                    "segmentation, codec, evaluation, plots",
                    "kinetology/ (also: psgs kinetology ...)"]),
    "induce": (340, 140, 280, 90, "psgs.induce",
               ["inducers: PAL, Sequential; the registry",
                "and results (Induction)",
                "psgs/induce/"]),
    "cli": (640, 140, 300, 90, "psgs: the top",
            ["psgs/cli/: the psgs command;",
             "psgs/_display.py: notebook pictures;",
             "psgs.strategies (hypothesis)"]),
    "actiongram": (20, 280, 230, 90, "psgs.actiongram",
                   ["timed symbol strings,", "one per actuator",
                    "psgs/actiongram/"]),
    "core": (340, 280, 600, 90, "the formal core (and beside it)",
             ["model, analysis, notation, steps, derivation, membership/, enumeration",
              "beside: format (load), writing (dump), lark_export, graph,",
              "draw (pictures)"]),
    "foundation": (20, 410, 920, 80, "the foundation",
                   ["psgs.errors (PSGSError: every error of the distribution);  psgs/_foundation/:",
                    "shell (exit statuses, argument types, run, version), lazy (names on first use), "
                    "engines (numpy or numba)"]),
}

#: (from, to) or (from, to, x): "from may import to" (x: where a vertical arrow runs, to pass
#: beside a box); every package may also import what its targets import
ARROWS = [
    ("praxicon", "kinetology"), ("praxicon", "induce"), ("praxicon", "cli"),
    ("kinetology", "actiongram"), ("kinetology", "foundation", 295),
    ("induce", "actiongram"), ("induce", "core"),
    ("cli", "induce"), ("cli", "core"),
    ("core", "actiongram"), ("actiongram", "foundation"), ("core", "foundation"),
]

WIDTH, HEIGHT = 960, 540


def _anchor(box: str, towards: str) -> tuple[float, float]:
    x, y, w, h = BOXES[box][:4]
    tx, ty, tw, th = BOXES[towards][:4]
    if ty == y:  # side by side: from one side's middle to the other's
        return (x, y + h / 2) if tx < x else (x + w, y + h / 2)
    # bottom edge when the target is below, top edge when above; x at the overlap's middle
    left, right = max(x, tx), min(x + w, tx + tw)
    cx = (left + right) / 2 if left < right else x + w / 2
    return (cx, y + h) if ty > y else (cx, y)


def svg() -> str:
    """The picture as SVG text."""
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{HEIGHT}" '
           f'viewBox="0 0 {WIDTH} {HEIGHT}" font-family="sans-serif">',
           '<defs><marker id="arrow" viewBox="0 0 10 10" refX="10" refY="5" markerWidth="7" '
           'markerHeight="7" orient="auto-start-reverse"><path d="M 0 0 L 10 5 L 0 10 z" '
           'fill="#555"/></marker></defs>',
           f'<rect width="{WIDTH}" height="{HEIGHT}" fill="white"/>']
    for box, (x, y, w, h, title, lines) in BOXES.items():
        fill = "#eef3fb" if box != "foundation" else "#f4f4f4"
        out.append(f'<rect x="{x}" y="{y}" width="{w}" height="{h}" rx="6" fill="{fill}" '
                   f'stroke="#345" stroke-width="1.2"/>')
        out.append(f'<text x="{x + 10}" y="{y + 20}" font-size="15" font-weight="bold" '
                   f'fill="#123">{html.escape(title)}</text>')
        for k, line in enumerate(lines):
            out.append(f'<text x="{x + 10}" y="{y + 39 + 16 * k}" font-size="12" '
                       f'fill="#333">{html.escape(line)}</text>')
    for source, target, *at in ARROWS:
        (x1, y1), (x2, y2) = _anchor(source, target), _anchor(target, source)
        if at:
            x1 = x2 = at[0]
        out.append(f'<line x1="{x1:g}" y1="{y1:g}" x2="{x2:g}" y2="{y2:g}" stroke="#555" '
                   f'stroke-width="1.4" marker-end="url(#arrow)"/>')
    for k, line in enumerate(["An arrow: may import (and so may use what that layer uses). "
                              "Nothing imports upwards;",
                              "psgs never imports kinetology or praxicon; kinetology imports "
                              "from psgs only the actiongram and the foundation."]):
        out.append(f'<text x="20" y="{HEIGHT - 30 + 16 * k}" font-size="12" '
                   f'fill="#333">{html.escape(line)}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


if __name__ == "__main__":
    target = Path(__file__).resolve().parent / "img" / "architecture.svg"
    target.write_text(svg(), encoding="utf-8")
    print(target)
