"""Pictures in the style of the paper's figures (matplotlib, the optional ``plot`` extra).

Each function draws into a new figure and returns it; ``save`` writes it.
matplotlib is imported only when a function runs, with a clear message when
it is missing.
"""

from __future__ import annotations

from types import MappingProxyType

import numpy as np

from psgs._foundation.pictures import picture_suffix
from psgs.errors import MissingDependency, ValidationError

from .codec.knots import is_rotation
from .motion import Motion
from .segmentation import DEFAULTS, STATES, segments, states

__all__ = ["STATE_COLOURS", "STILL_COLOUR", "plot_states", "plot_reconstruction", "plot_view_invariance",
           "plot_reproducibility", "plot_selectivity", "plot_rate_distortion", "check_output",
           "save"]

#: Colours of the four states (B blue, G green, R red, Y yellow).
STATE_COLOURS = MappingProxyType({"B": "#1f5fd6", "G": "#2ca02c", "R": "#d62728",
                                  "Y": "#e8b400"})
#: Colour of a channel or joint that does not move (the viewer's state ``"-"``).
STILL_COLOUR = "#9a9a9a"


def _pyplot():
    try:
        import matplotlib
        matplotlib.use("Agg", force=False)
        import matplotlib.pyplot as plt
    except ImportError:  # pragma: no cover - depends on the environment
        raise MissingDependency("plotting needs matplotlib: pip install 'psgs[plot]' "
                          "(or pip install matplotlib)") from None
    return plt


def _state_cmap():
    from matplotlib.colors import ListedColormap
    return ListedColormap([STATE_COLOURS[s] for s in STATES])


def _state_legend(target, **options):
    """A legend of the four state colours (for pictures drawn with ``imshow``)."""
    from matplotlib.patches import Patch
    signs = {"B": "+,+", "G": "+,-", "R": "-,-", "Y": "-,+"}
    handles = [Patch(color=STATE_COLOURS[s], label=f"{s} ({signs[s]})") for s in STATES]
    return target.legend(handles=handles, ncol=4, fontsize=8, title="state (θ', θ'')",
                         title_fontsize=8, **options)


def _window(frames: int, frame_rate: float, start: float, stop: float | None) -> tuple:
    """Frame times and the mask of those in ``[start, stop]``; an empty window is an error."""
    t = np.arange(frames) / frame_rate
    window = (t >= start) & (t <= (stop if stop is not None else np.inf))
    if not window.any():
        raise ValidationError(f"no frames between {start:g} s and "
                         f"{'the end' if stop is None else f'{stop:g} s'} (the motion has "
                         f"{frames} frames, {frames / frame_rate:g} s)")
    return t, window


def plot_states(motion: Motion, channel: str, *, start: float = 0.0, stop: float | None = None,
                **params):
    """Fig. 1 style: one joint angle over time, each segment coloured by its state.

    Parameters
    ----------
    motion : Motion
        The motion.
    channel : str
        The channel to draw.
    start : float, default 0.0
        Start of the time window drawn, seconds.
    stop : float, optional
        End of the time window drawn, seconds (default: the end of the motion).
    **params
        Segmentation parameters (:data:`kinetology.segmentation.DEFAULTS`). A channel whose
        smoothed range is below ``min_range`` is still, as :func:`kinetology.segment` leaves
        it out of the actiongram: it is drawn grey (:data:`STILL_COLOUR`) and the title says
        so.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ImportError
        When matplotlib is not installed.
    ValueError
        When no frame falls between ``start`` and ``stop``.
    KeyError
        When the motion has no channel ``channel``.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import kinetology
    >>> walk = kinetology.synthetic_motion(2, (0,), seed=0)
    >>> fig = plot_states(walk, "j0.rx", stop=2.0)
    >>> fig.axes[0].get_xlabel()
    'time (s)'
    >>> save(fig, Path(tempfile.mkdtemp()) / "figure.png")
    >>> still = plot_states(walk, "j0.rx", min_range=1e6)
    >>> still.axes[0].get_title().startswith("j0.rx: still")
    True
    >>> save(still, Path(tempfile.mkdtemp()) / "still.png")
    """
    plt = _pyplot()
    p = {k: v for k, v in {**DEFAULTS, **params}.items() if k != "min_range"}
    signal = motion.column(channel)
    t, window = _window(motion.frames, motion.frame_rate, start, stop)
    # segments() before states(): of values too large to difference, its error names the take
    still = _is_still(motion, channel, params)
    code = states(signal, motion.frame_rate, **p)
    fig, ax = plt.subplots(figsize=(9, 3))
    if still:
        ax.plot(t[window], signal[window], color=STILL_COLOUR, lw=2.2, label="still")
        title = (f"{channel}: still (moves less than min_range "
                 f"{params.get('min_range', DEFAULTS['min_range']):g} deg), no states")
    else:
        for k, letter in enumerate(STATES):
            mask = code == k
            mask[1:] |= code[:-1] == k  # include the next frame, so segments touch
            masked = np.where(mask & window, signal, np.nan)
            ax.plot(t, masked, color=STATE_COLOURS[letter], lw=2.2, label=letter)
        title = f"{channel}: states B (θ'>0, θ''>0) G (+,-) R (-,-) Y (-,+)"
    ax.set_xlim(t[window][0], t[window][-1])
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"{channel} (deg)")
    ax.legend(ncol=4, loc="upper right", fontsize=8)
    ax.set_title(title)
    fig.tight_layout()
    return fig


def _is_still(motion: Motion, channel: str, params: dict) -> bool:
    """Whether ``segment`` would leave ``channel`` out as still (the same rule: its smoothed,
    unwrapped range below ``min_range``), so the picture shows what the actiongram holds."""
    return bool(segments(motion, [channel], **params).still)


def plot_reconstruction(original: Motion, decoded: Motion, channel: str, *, start: float = 0.0,
                        stop: float | None = None):
    """Fig. 9 style: a joint angle and its reconstruction from segments.

    Parameters
    ----------
    original, decoded : Motion
        The motion and its reconstruction (e.g. ``kinetology.decompress(kinetology.compress(m))``).
    channel : str
        The channel to draw (the title gives its mean absolute error in the window, modulo
        360° for a rotation channel).
    start : float, default 0.0
        Start of the time window drawn, seconds.
    stop : float, optional
        End of the time window drawn, seconds (default: the end of the motion).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ImportError
        When matplotlib is not installed.
    ValueError
        When no frame falls between ``start`` and ``stop``.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import kinetology
    >>> walk = kinetology.synthetic_motion(2, (0,), seed=0)
    >>> decoded = kinetology.decompress(kinetology.compress(walk))
    >>> fig = plot_reconstruction(walk, decoded, "j0.rx", stop=2.0)
    >>> fig.axes[0].get_title().startswith("j0.rx: mean |error|")
    True
    >>> save(fig, Path(tempfile.mkdtemp()) / "figure.png")
    """
    plt = _pyplot()
    t, window = _window(original.frames, original.frame_rate, start, stop)
    a, b = original.column(channel), decoded.column(channel)
    if is_rotation(channel):
        # the decoder returns unwrapped angles (181° for the file's -179°), the same angle: the
        # decoded curve is drawn on the original's turn, so its distance is the error mod 360°
        b = a + ((b - a + 180.0) % 360.0 - 180.0)
    fig, ax = plt.subplots(figsize=(9, 3))
    ax.plot(t[window], a[window], color="black", lw=1.5, label="original")
    ax.plot(t[window], b[window], color="#d62728", lw=1.2, ls="--", label="reconstructed")
    ax.set_xlabel("time (s)")
    ax.set_ylabel(f"{channel} (deg)")
    ax.set_title(f"{channel}: mean |error| {np.abs(a - b)[window].mean():.3f} deg")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def plot_view_invariance(result, title: str = "", frame_rate: float = 120.0, *,
                         start: float = 0.0, stop: float | None = None):
    """Fig. 6 style: viewpoint (rows) x time (columns), coloured by state; 3D on top.

    Parameters
    ----------
    result : ViewInvariance
        What :func:`kinetology.evaluation.view_invariance` returned.
    title : str, default ""
        Put before the agreement in the figure's title.
    frame_rate : float, default 120.0
        Frames per second of the motion measured (for the time axis).
    start : float, default 0.0
        Start of the time window drawn, seconds (the title's agreement is the window's).
    stop : float, optional
        End of the time window drawn, seconds (default: the end of the motion).

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ImportError
        When matplotlib is not installed.
    ValueError
        When no frame falls between ``start`` and ``stop``.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import numpy as np
    >>> from kinetology.evaluation import ViewInvariance
    >>> result = ViewInvariance(np.array([0.0, 180.0]), np.array([0, 1, 2, 3]),
    ...                         np.array([[0, 1, 2, 3], [0, 1, 1, 3]]), np.zeros(4))
    >>> fig = plot_view_invariance(result, "knee", frame_rate=4)
    >>> fig.axes[0].get_title()
    'knee  agreement with 3D: 87.5%'
    >>> save(fig, Path(tempfile.mkdtemp()) / "figure.png")
    >>> plot_view_invariance(result, "knee", frame_rate=4, stop=0.25).axes[0].get_title()
    'knee  agreement with 3D: 100.0%'
    """
    plt = _pyplot()
    t, window = _window(result.states_3d.size, frame_rate, start, stop)
    states_3d, states_2d = result.states_3d[window], result.states_2d[:, window]
    image = np.vstack([states_3d[None, :].repeat(2, axis=0), states_2d])
    agreement = float((states_2d == states_3d[None, :]).mean())
    fig, ax = plt.subplots(figsize=(9, 4.6))
    step = 360.0 / len(result.azimuths)
    # one row per view, centred on its azimuth; the two 3D rows sit above the first view
    top, bottom = result.azimuths[0] - 2.5 * step, result.azimuths[-1] + 0.5 * step
    ax.imshow(image, aspect="auto", interpolation="nearest", cmap=_state_cmap(), vmin=-0.5,
              vmax=3.5, extent=(t[window][0], t[window][-1] + 1 / frame_rate, bottom, top))
    ax.axhline(result.azimuths[0] - 0.5 * step, color="white", lw=2)
    ax.set_xlabel("time (s)")
    ax.set_ylabel("viewpoint azimuth (deg); top band: 3D")
    ax.set_title(f"{title}  agreement with 3D: {100 * agreement:.1f}%")
    _state_legend(fig, loc="lower center")
    fig.tight_layout(rect=(0, 0.08, 1, 1))
    return fig


def plot_reproducibility(table: dict, channels, title: str = "Reproducibility"):
    """Actions (rows) x channels (columns): share of performances with the modal description.

    Parameters
    ----------
    table : dict
        What :func:`kinetology.evaluation.reproducibility` returned.
    channels : sequence of str
        The columns, in order (each in every action's row).
    title : str, default "Reproducibility"
        The figure's title.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ImportError
        When matplotlib is not installed.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> table = {"Jog": {"lknee": (1.0, "BGRY", 4), "rknee": (0.75, "BGRY", 4)},
    ...          "Squat": {"lknee": (0.5, "BGBGRY", 2), "rknee": (1.0, "BGRY", 2)}}
    >>> fig = plot_reproducibility(table, ["lknee", "rknee"])
    >>> [label.get_text() for label in fig.axes[0].get_yticklabels()]
    ['Jog (4)', 'Squat (2)']
    >>> save(fig, Path(tempfile.mkdtemp()) / "figure.png")
    """
    plt = _pyplot()
    actions = list(table)
    grid = np.array([[table[a][c][0] for c in channels] for a in actions])
    fig, ax = plt.subplots(figsize=(max(6, 0.35 * len(channels)), 0.5 * len(actions) + 2))
    im = ax.imshow(grid, vmin=0, vmax=1, cmap="viridis", aspect="auto")
    ax.set_xticks(range(len(channels)), channels, rotation=90, fontsize=7)
    ax.set_yticks(range(len(actions)), [f"{a} ({table[a][channels[0]][2]})" for a in actions],
                  fontsize=8)
    fig.colorbar(im, ax=ax, label="share with the most common description")
    ax.set_title(title)
    fig.tight_layout()
    return fig


def plot_selectivity(motions, performances, channels, *, seconds: float = 3.0, **params):
    """Fig. 8 style: for each action, a few seconds of each channel's states (rows).

    Parameters
    ----------
    motions : dict of str to Motion
        The takes, by name.
    performances : list of Performance
        Labelled stretches of the takes; the first of each action is drawn.
    channels : sequence of str
        The rows of each action's panel.
    seconds : float, default 3.0
        How much of each performance is drawn.
    **params
        Segmentation parameters (:data:`kinetology.segmentation.DEFAULTS`).

    Returns
    -------
    matplotlib.figure.Figure
        One panel per action, sorted by name.

    Raises
    ------
    ImportError
        When matplotlib is not installed.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import kinetology
    >>> from kinetology.evaluation import Performance
    >>> takes = {"a": kinetology.synthetic_motion(3, seed=0)}
    >>> performances = [Performance("a", "swing", 0, 480), Performance("a", "wave", 480, 960)]
    >>> fig = plot_selectivity(takes, performances, ["j0.rx", "j1.rx", "j2.rx"], seconds=2)
    >>> [ax.get_ylabel() for ax in fig.axes[:2]]
    ['swing', 'wave']
    >>> save(fig, Path(tempfile.mkdtemp()) / "figure.png")
    """
    plt = _pyplot()
    p = {k: v for k, v in {**DEFAULTS, **params}.items() if k != "min_range"}
    first = {}
    for perf in performances:
        first.setdefault(perf.action, perf)
    fig, axes = plt.subplots(len(first), 1, figsize=(9, 1.0 + 0.9 * len(first)), sharex=True)
    axes = np.atleast_1d(axes)
    for ax, (action, perf) in zip(axes, sorted(first.items())):
        motion = motions[perf.take]
        n = min(perf.stop - perf.start, int(seconds * motion.frame_rate))
        values = motion.values[:, [motion.index(c) for c in channels]]
        code = states(values, motion.frame_rate, **p)[perf.start:perf.start + n].T
        ax.imshow(code, aspect="auto", interpolation="nearest", cmap=_state_cmap(), vmin=-0.5,
                  vmax=3.5, extent=(0, n / motion.frame_rate, len(channels) - 0.5, -0.5))
        ax.set_yticks(range(len(channels)), channels, fontsize=7)
        ax.set_ylabel(action, rotation=0, ha="right", va="center", fontsize=8)
    axes[-1].set_xlabel("time from the start of the performance (s)")
    _state_legend(fig, loc="lower center")
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    return fig


def plot_rate_distortion(curves: dict, paper=(3.698, 0.823)):
    """Size (% of the original) against mean absolute error, one line per codec.

    Parameters
    ----------
    curves : dict of str to list of (float, float)
        Codec name to its ``(percent, mean absolute error)`` points.
    paper : (float, float), default (3.698, 0.823)
        The paper's point, drawn as a star.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ImportError
        When matplotlib is not installed.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> fig = plot_rate_distortion({"ours": [(2.0, 0.5), (4.0, 0.2)],
    ...                             "peer": [(3.0, 0.5), (6.0, 0.2)]})
    >>> [line.get_label() for line in fig.axes[0].get_lines()]
    ['ours', 'peer', 'paper (3.698%, 0.823°)']
    >>> save(fig, Path(tempfile.mkdtemp()) / "figure.png")
    """
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6, 4))
    markers = iter("osd^v<>")
    for name, points in curves.items():
        points = sorted(points, key=lambda p: p[1])
        ax.plot([p[1] for p in points], [p[0] for p in points], marker=next(markers), label=name)
    ax.plot([paper[1]], [paper[0]], "k*", ms=12, label="paper (3.698%, 0.823°)")
    ax.set_xlabel("mean absolute error (deg, all channels)")
    ax.set_ylabel("size (% of the AMC file)")
    ax.set_yscale("log")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def check_output(path) -> str:
    """The suffix of ``path`` when matplotlib writes pictures of that format, else
    :class:`~psgs.errors.ValidationError` naming the file: checked before any work is done.

    Parameters
    ----------
    path : str or Path
        Where a picture is to be written.

    Returns
    -------
    str
        The suffix, lower case (``".png"``).

    Raises
    ------
    ValidationError
        For a suffix matplotlib does not write (or none).
    MissingDependency
        When matplotlib is not installed.

    Examples
    --------
    >>> check_output("knee.PNG")
    '.png'
    >>> check_output("knee.txt")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: knee.txt: matplotlib cannot write '.txt' pictures; give one of .png, .svg, .pdf, ...
    """
    return picture_suffix(path)


def save(fig, path) -> None:
    """Write a figure (format by suffix) and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure (closed afterwards, so pyplot does not keep it).
    path : str or Path
        Where to write; the suffix chooses the format (``.png``, ``.svg``, ``.pdf``, ...).

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> fig = plot_rate_distortion({"ours": [(2.0, 0.5)]})
    >>> path = Path(tempfile.mkdtemp()) / "front.svg"
    >>> save(fig, path)
    >>> path.read_text().count("<svg") >= 1
    True
    """
    fig.savefig(path, dpi=110)
    import matplotlib.pyplot as plt
    plt.close(fig)
