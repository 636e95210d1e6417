"""A :class:`~kinetology.viewer.Player` as HTML: the page, and the fragment a notebook shows.

Everything is inline (the data as JSON, the script ``viewer.js``, a legend of the states'
colours), so that a page opens from a file on a machine without network. Positions are
stored as small integers, differences from the frame before.
"""

from __future__ import annotations

import html
import json
from importlib import resources

import numpy as np

from ._viewer_camera import PITCH, YAW
from .plotting import STATE_COLOURS, STILL_COLOUR

__all__ = ["COLOURS", "packed_positions", "fragment", "page"]

#: the states' colours (those of the plots) and a still joint's, ``"-"``
COLOURS = {**STATE_COLOURS, "-": STILL_COLOUR}
_STATE_READING = {"B": "rising, speeding up", "G": "rising, slowing down",
                  "R": "falling, speeding up", "Y": "falling, slowing down", "-": "still"}
_QUANTA = 1000  # positions to 1/1000 of the largest extent: 2 mm on a 2 m body, below a pixel


def packed_positions(positions: np.ndarray, centre: np.ndarray, radius: float,
                     height: float) -> dict:
    """A panel's positions as the page's script reads them: integer steps of ``quantum``
    around ``centre``, each frame a difference from the one before; ``radius`` and ``height``
    (:func:`kinetology._viewer_camera.fit`) in those steps."""
    quantum = max(2 * radius, height) / _QUANTA
    ints = np.rint((positions - centre) / quantum).astype(np.int64)
    deltas = np.diff(ints, axis=0, prepend=np.zeros_like(ints[:1]))
    return {"quantum": quantum, "radius": radius / quantum, "height": height / quantum,
            "pos": deltas.ravel().tolist()}


def page(title: str, body: str) -> str:
    """The whole page around ``body`` (a :func:`fragment`)."""
    return ("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">"
            f"<title>{html.escape(title)}</title></head>\n<body style=\"margin:8px;"
            f"font-family:sans-serif\">\n{body}\n</body></html>\n")


def fragment(player) -> str:
    """The player's element: its panels, the time slider, play/pause, the legend, the data
    and the script that draws them."""
    data = {"rate": player.frame_rate, "ticks": player.ticks, "yaw": YAW, "pitch": PITCH,
            "colours": COLOURS, "panels": [p.to_json() for p in player.panels]}
    # no "<" at all inside the script element: a label cannot end it or open a comment
    text = json.dumps(data, separators=(",", ":")).replace("<", "\\u003c")
    # the element id comes from the content: two players on one notebook page do not
    # collide, and the same motions give the same page
    import hashlib
    ident = "kinetology-view-" + hashlib.sha1(text.encode()).hexdigest()[:12]
    legend = " ".join(
        f'<span title="{_STATE_READING[s]}"><span style="display:inline-block;width:.8em;'
        f'height:.8em;border-radius:50%;background:{c}"></span> {s if s != "-" else "still"}'
        f'</span>' for s, c in COLOURS.items())
    if any(any(p.actuators) for p in player.panels):
        legend += (' <span><span style="display:inline-block;width:.8em;height:.8em;'
                   'border-radius:50%;border:2px solid #000"></span> actuator</span>')
    script = resources.files(__package__).joinpath("viewer.js").read_text("utf-8")
    return (f'<div id="{ident}" class="kinetology-view">\n'
            f'<div class="panels" style="display:flex;gap:8px;flex-wrap:wrap"></div>\n'
            f'<div style="display:flex;gap:8px;align-items:center;margin-top:4px">'
            f'<button class="play" type="button">Play</button>'
            f'<input class="time" type="range" min="0" max="{player.ticks - 1}" value="0" '
            f'step="1" style="flex:1" aria-label="time">'
            f'<span class="clock" style="font-variant-numeric:tabular-nums">0.00 s</span>'
            f'</div>\n<div style="font-size:.85em;margin-top:4px">{legend} '
            f'&middot; drag a body to turn it</div>\n'
            f'<script type="application/json" class="data">{text}</script>\n'
            f'<script>\n(function (script, id) {{\n{script}\n}})(document.currentScript, '
            f'"{ident}");\n</script>\n</div>')
