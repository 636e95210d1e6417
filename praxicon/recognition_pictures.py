"""Pictures of recognition (matplotlib; the ``praxicon`` extra).

* :func:`draw_timeline`: a parsed recording's spans as coloured bands over its most moving
  joint angles;
* :func:`draw_explanation`: a recognition's per-joint distance terms for its best actions
  (small: the joint matched; large: it did not, coloured by why).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from psgs.errors import ValidationError

__all__ = ["draw_timeline", "draw_explanation"]

_ROLE_COLOURS = {"matched": "#2ca02c", "still but should move": "#1f5fbf",
                 "moves but should be still": "#d62728", "differs": "#f2a30f"}


def _short(action: str) -> str:
    """An action's name without its dataset (``dataset.content[.style]``): the content and the
    style both, for actions of one content in several styles differ by the style alone and
    actions of one style by the content alone.

    Examples
    --------
    >>> _short("bandai-namco-2-subset.walk-turn-left.masculine"), _short("m.wave")
    ('walk-turn-left.masculine', 'wave')
    """
    return action.split(".", 1)[-1]


def _pyplot():
    from .pictures import _pyplot as pyplot

    return pyplot()


def draw_timeline(timeline, motion, path, *, channels: int = 6) -> Path:
    """Draw ``timeline`` over the ``channels`` joint angles of ``motion`` that move most.

    Each span is a band in its action's colour (grey hatching: none of these), labelled with
    the action's name without its dataset (content and style); where a timeline stopped at
    its bound, a dashed line says the rest was not parsed. Returns the path written.

    Raises
    ------
    ValidationError
        When ``motion`` is no motion, or not the one parsed (another duration: its spans
        would be drawn over other time).
    """
    from kinetology import Motion
    from kinetology.segmentation import unwrap

    if not isinstance(motion, Motion):
        raise ValidationError(f"a motion must be a kinetology.Motion, not "
                              f"{type(motion).__name__}")
    if not abs(motion.duration - timeline.duration) <= 1e-6 * max(1.0, timeline.duration):
        raise ValidationError(f"{motion.source} lasts {motion.duration:.2f} s; the timeline "
                              f"{timeline.duration:.2f} s: draw a timeline over the motion "
                              f"parsed")
    plt = _pyplot()
    rotations = [c for c, name in enumerate(motion.channels)
                 if name.rsplit(".", 1)[-1] in ("rx", "ry", "rz")]
    values = unwrap(np.asarray(motion.values[:, rotations], dtype=float))
    order = np.argsort(-np.ptp(values, axis=0))[:channels] if values.size else []
    t = np.arange(motion.frames) / motion.frame_rate
    names = sorted({s.action for s in timeline.spans if s.action})
    cmap = plt.get_cmap("tab10")
    colours = {n: cmap(i % 10) for i, n in enumerate(names)}
    fig, ax = plt.subplots(figsize=(10, 3.6))
    for span in timeline.spans:
        if span.action is None:
            ax.axvspan(span.start, span.stop, color="0.85", hatch="//", alpha=0.5, lw=0)
        else:
            ax.axvspan(span.start, span.stop, color=colours[span.action], alpha=0.25, lw=0)
            ax.text((span.start + span.stop) / 2, 1.01, _short(span.action),
                    transform=ax.get_xaxis_transform(), ha="center", va="bottom", fontsize=8)
    if timeline.bound:  # parse stopped at its bound: the rest is not parsed, not no action
        ax.axvline(timeline.end, color="0.3", lw=1, ls="--")
        ax.text(timeline.end, 0.98, f" not parsed past here ({timeline.bound})",
                transform=ax.get_xaxis_transform(), ha="left", va="top", fontsize=8,
                color="0.3")  # inside the axes: the spans' names are above them
    for k in order:
        ax.plot(t, values[:, k] - np.median(values[:, k]), lw=0.8,
                label=motion.channels[rotations[k]])
    ax.set_xlabel("seconds")
    ax.set_ylabel("angle - median (degrees)")
    ax.set_xlim(0, motion.duration)
    ax.legend(fontsize=7, loc="lower right", ncol=3)
    fig.tight_layout()
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def draw_explanation(recognition, path, *, joints: int = 12) -> Path:
    """Draw the per-joint distance terms of a recognition's best actions (one panel each).

    Returns the path written.
    """
    from matplotlib.ticker import MaxNLocator

    plt = _pyplot()
    shown = recognition.reasons
    if not shown:
        raise ValidationError("the recognition keeps no reasons (recognise with explain >= 1)")
    probability = dict(recognition.ranking)
    fig, axes = plt.subplots(1, len(shown), figsize=(3.6 * len(shown), 3.8), squeeze=False)
    for ax, (name, reasons) in zip(axes[0], shown):
        top = sorted(reasons, key=lambda r: -r.penalty)[:joints][::-1]
        ax.barh([r.joint for r in top], [r.penalty for r in top],
                color=[_ROLE_COLOURS[r.role] for r in top])
        ax.set_title(f"{_short(name)} (p={probability[name]:.2f})", fontsize=9)
        ax.set_xlabel("distance term")
        ax.tick_params(labelsize=7)
        # a joint far from an action has a term of 10^5 or more: four ticks, and a power of
        # ten apart from their labels, or six-figure labels run into one another
        ax.xaxis.set_major_locator(MaxNLocator(4))
        ax.ticklabel_format(axis="x", style="sci", scilimits=(-3, 4))
    handles = [plt.Rectangle((0, 0), 1, 1, color=c) for c in _ROLE_COLOURS.values()]
    fig.legend(handles, list(_ROLE_COLOURS), loc="lower center", ncol=4, fontsize=7)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    path = Path(path)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path
