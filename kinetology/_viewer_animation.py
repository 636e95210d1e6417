"""A :class:`~kinetology.viewer.Player` as an animated GIF (Pillow) or MP4 (ffmpeg).

The same picture as the HTML page: the orthographic view of :meth:`Panel.pose`, bones grey,
joints coloured by state, actuators ringed; one frame per slider step.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ._viewer_checks import GIF_LONGEST, GIF_SHORTEST, MP4_SLOWEST, slowest_rate
from .plotting import STATE_COLOURS, STILL_COLOUR as _STILL

__all__ = ["animate", "GIF_LONGEST", "GIF_SHORTEST", "MP4_SLOWEST"]

def _pace(player, suffix: str) -> float:
    """The frames per second the file plays at: the player's, or for a single frame (whose
    duration shows nothing) the slowest rate the format holds; the caller has refused more
    frames slower than that (:func:`~kinetology._viewer_checks.pace_problem`)."""
    return max(player.frame_rate, slowest_rate(suffix))


def animate(player, path: Path, suffix: str, *, dpi: int = 72) -> None:
    """Write ``player`` (a :class:`~kinetology.viewer.Player`) to ``path`` as ``.gif`` or
    ``.mp4``, one frame per slider step; the caller has checked that the writer is there."""
    from matplotlib import animation
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.collections import LineCollection
    from matplotlib.figure import Figure

    rate = _pace(player, suffix)
    n = len(player.panels)
    fig = Figure(figsize=(2.6 * n, 3.4), dpi=dpi)
    FigureCanvasAgg(fig)
    artists = []
    for i, panel in enumerate(player.panels):
        ax = fig.add_subplot(1, n, i + 1)
        every = np.stack([panel.pose(f) for f in range(panel.frames)])
        floors = [panel.floor(f) for f in range(panel.frames)]
        lo, hi = every[:, panel.body].min(axis=(0, 1)), every[:, panel.body].max(axis=(0, 1))
        pad = 0.05 * float((hi - lo).max())
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal")
        ax.set_axis_off()
        ax.set_title(panel.label, fontsize=8)
        grid = LineCollection([], colors="#e4e4e4", linewidths=0.8)
        ax.add_collection(grid)
        pairs = [(j, p) for j, p in enumerate(panel.parents) if panel.bones[j]]
        bones = LineCollection([], colors="#444444", linewidths=2, capstyle="round")
        ax.add_collection(bones)
        dots = [j for j, name in enumerate(panel.joints)
                if panel.body[j] and not name.endswith(".end")]
        joints = ax.scatter(np.zeros(len(dots)), np.zeros(len(dots)), s=14, zorder=3)
        ringed = [j for j, a in enumerate(panel.actuators) if a]
        rings = ax.scatter(np.zeros(len(ringed)), np.zeros(len(ringed)), s=70,
                           facecolors="none", edgecolors="black", linewidths=1.2, zorder=4)
        label = ax.text(0.02, 0.98, "", transform=ax.transAxes, fontsize=7, va="top")
        artists.append((panel, every, floors, grid, pairs, bones, dots, joints, ringed, rings,
                        label))

    def update(tick: int):
        for i, (panel, every, floors, grid, pairs, bones, dots, joints, ringed, rings,
                label) in enumerate(artists):
            f = player.frame_of(i, tick)
            xy = every[f]
            grid.set_segments(floors[f])
            bones.set_segments([(xy[p], xy[j]) for j, p in pairs])
            joints.set_offsets(xy[dots])
            joints.set_facecolors([STATE_COLOURS.get(panel.states[j][f], _STILL)
                                   for j in dots])
            if ringed:
                rings.set_offsets(xy[ringed])
            label.set_text(f"{tick / player.frame_rate:.2f} s")
        return []

    if suffix == ".gif":
        _gif(fig, update, player, path, rate)
        return
    movie = animation.FuncAnimation(fig, update, frames=player.ticks, interval=1000 / rate,
                                    blit=False)
    movie.save(str(path), writer=animation.FFMpegWriter(fps=rate), dpi=dpi)


def _gif(fig, update, player, path: Path, rate: float) -> None:
    """The frames drawn by matplotlib, written by Pillow with one palette for all of them:
    a picture of a few flat colours, so a small file (matplotlib's own PillowWriter stores
    every frame in full colour, several times larger) with no dithering noise."""
    from PIL import Image

    # the picture's own colours, each also blended with the white background (the edges
    # that antialiasing draws), as the palette every frame is mapped to
    inks = ["#000000", "#444444", "#e4e4e4", _STILL, *STATE_COLOURS.values()]
    rgb = [tuple(int(c[i:i + 2], 16) for i in (1, 3, 5)) for c in inks]
    shades = [(255, 255, 255)] + [tuple(round(255 + (v - 255) * k) for v in colour)
                                  for colour in rgb for k in (1.0, 0.66, 0.33)]
    palette = Image.new("P", (1, 1))
    palette.putpalette([v for colour in shades for v in colour])
    step = max(1, math.ceil(rate * GIF_SHORTEST - 1e-9))  # every step-th tick: the same clock
    frames = []
    for tick in range(0, player.ticks, step):
        update(tick)
        fig.canvas.draw()
        image = Image.fromarray(np.asarray(fig.canvas.buffer_rgba())[..., :3])
        frames.append(image.quantize(palette=palette, dither=Image.Dither.NONE))
    # a GIF stores whole hundredths: each frame ends at its time rounded, so the delays add up
    # to the motion's length (a fixed rounded delay ran 30 fps at 33.3, 120 fps drawn every
    # third step at 50 instead of 40)
    ends = np.rint(np.arange(len(frames) + 1) * (100.0 * step / rate))
    frames[0].save(path, format="GIF", save_all=True, append_images=frames[1:], loop=0,
                   duration=[10 * int(d) for d in np.diff(ends)], optimize=True)
