"""Pictures of a praxicon (matplotlib; the ``praxicon`` extra).

* :func:`draw_actuator_matrix`: actions x joints, filled where the joint takes
  part (the paper's Fig. 10);
* :func:`draw_morphemes`: per actuator channel of an action, its morpheme as
  coloured kineteme runs, each as wide as its typical duration (Fig. 11);
* :func:`draw_shared_patterns`: the sub-patterns several actions share, per
  joint, with the actions (Fig. 13);
* :func:`draw_generated`: one joint angle, a performance beside the motion
  generated from the grammar;
* :func:`draw_praxicon`: all of them (and each action's grammar forest and
  synchronisation graph, :func:`psgs.draw.draw`) into one folder.

Kineteme colours follow their letters: ``B`` blue, ``G`` green, ``R`` red,
``Y`` yellow.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from kinetology.plotting import STATE_COLOURS

from .records import ActionRecord, Praxicon
from .store import actuator_matrix, load

__all__ = ["draw_actuator_matrix", "draw_morphemes", "draw_shared_patterns",
           "draw_generated", "draw_praxicon"]



def _pyplot():
    try:
        import matplotlib
    except ImportError:  # pragma: no cover - the praxicon extra is not installed
        raise ValueError("pictures need matplotlib (pip install 'psgs[praxicon]')") from None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(fig, path) -> Path:
    plt = _pyplot()
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    # no date in the metadata: the same praxicon gives the same picture bytes
    import matplotlib

    metadata = {"Date": None} if path.suffix.lower() == ".svg" else {}
    with matplotlib.rc_context({"svg.hashsalt": "praxicon"}):
        fig.savefig(path, dpi=110, metadata=metadata or None)
    plt.close(fig)
    return path


def _praxicon(praxicon) -> Praxicon:
    return praxicon if isinstance(praxicon, Praxicon) else load(praxicon)


def draw_actuator_matrix(folder, path) -> Path:
    """Actions x joints, a filled cell where the joint is an actuator (Fig. 10).

    ``folder`` is a praxicon folder or a loaded :class:`~praxicon.records.Praxicon` (so
    for every drawing function here).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> from praxicon import read_dataset, build
    >>> data = pathlib.Path("../shared/data/mocap/bandai-namco-1/data").resolve()
    >>> work = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (work / "m.csv").write_text("action,file\\n" + "".join(
    ...     f"bye,{data / f'dataset-1_bye_{style}_001.bvh'}\\n" for style in ("normal", "active")))
    >>> _ = build(read_dataset(work / "m.csv"), work / "px", progress=False)
    >>> draw_actuator_matrix(work / "px", work / "px" / "img" / "actuators.png").stat().st_size > 0
    True
    """
    plt = _pyplot()
    names, joints, rows = actuator_matrix(_praxicon(folder))
    if not names:
        raise ValueError(f"{folder}: no learnt action to draw")
    matrix = np.array(rows, dtype=float)
    fig, ax = plt.subplots(figsize=(2 + 0.22 * len(joints), 1.2 + 0.2 * len(names)))
    ax.imshow(matrix, cmap="Greys", vmin=0, vmax=1.4, aspect="auto", interpolation="nearest")
    ax.set_xticks(range(len(joints)), joints, rotation=90, fontsize=7)
    ax.set_yticks(range(len(names)), names, fontsize=7)
    ax.set_xticks(np.arange(-0.5, len(joints)), minor=True)
    ax.set_yticks(np.arange(-0.5, len(names)), minor=True)
    ax.grid(which="minor", color="#dddddd", lw=0.5)
    ax.tick_params(which="minor", length=0)
    ax.set_title("actuator sets: the joints that take part in each action", fontsize=9)
    fig.tight_layout()
    return _save(fig, path)


def _runs(ax, y: float, kinetemes, durations, height: float = 0.8) -> None:
    x = 0.0
    for k, d in zip(kinetemes, durations):
        ax.barh(y, d, left=x, height=height, color=STATE_COLOURS.get(k, "#999999"),
                edgecolor="white", lw=0.5)
        if d > 0.04:
            ax.text(x + d / 2, y, k, ha="center", va="center", fontsize=6,
                    color="black" if k == "Y" else "white")
        x += d


def draw_morphemes(folder, action: str, path) -> Path:
    """An action's morphemes, one row per actuator channel, kinetemes as coloured runs (Fig. 11)."""
    plt = _pyplot()
    record = _praxicon(folder)[action]
    rows = list(record.morphemes().items())
    if not rows:
        raise ValueError(f"action {action!r} has no actuators to draw")
    fig, ax = plt.subplots(figsize=(7, 0.8 + 0.28 * len(rows)))
    for y, (channel, morpheme) in enumerate(rows):
        durations = morpheme.durations or [0.1] * len(morpheme.kinetemes)
        _runs(ax, y, morpheme.kinetemes, durations)
    ax.set_yticks(range(len(rows)), [c for c, _ in rows], fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("seconds (typical durations)")
    ax.set_title(f"morphemes of {action}", fontsize=9)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    fig.tight_layout()
    return _save(fig, path)


def draw_shared_patterns(folder, path, *, most: int = 30, **options) -> Path:
    """The ``most`` sub-patterns shared by the most actions, with the actions (Fig. 13)."""
    from .shared import shared_patterns

    plt = _pyplot()
    patterns = sorted(shared_patterns(_praxicon(folder), **options),
                      key=lambda p: (-len(p.actions), -len(p.kinetemes)))[:most]
    if not patterns:
        raise ValueError(f"{folder}: no sub-pattern is shared by several actions")
    fig, ax = plt.subplots(figsize=(10, 0.8 + 0.3 * len(patterns)))
    longest = max(len(p.kinetemes) for p in patterns)
    for y, pattern in enumerate(patterns):
        _runs(ax, y, pattern.kinetemes, [0.25] * len(pattern.kinetemes))
        names = [a.split(".", 1)[-1] for a in pattern.actions]
        # at most 8 names, then a count: a long list ran off the picture's right edge
        shown = ", ".join(names[:8]) + (f", +{len(names) - 8} more" if len(names) > 8 else "")
        ax.text(0.25 * longest + 0.1, y, f"{len(pattern.actions)}: {shown}",
                va="center", fontsize=6, clip_on=True)
    ax.set_yticks(range(len(patterns)), [p.joint for p in patterns], fontsize=7)
    ax.invert_yaxis()
    ax.set_xlim(0, 0.25 * longest + 7)
    ax.set_xticks([])
    ax.set_title("kineteme sub-patterns shared across actions (joint; how many actions: which)",
                 fontsize=9)
    fig.tight_layout()
    return _save(fig, path)


def draw_generated(record: ActionRecord, generated, path, channel: str | None = None) -> Path:
    """One actuator channel beside a performance (default: the one that moves the most in it)."""
    from .datasets import Performance
    from .learn import _load_performance

    plt = _pyplot()
    used = [p for p in record.performances if p.used]
    perf = Performance(used[0].file, used[0].start, used[0].stop, used[0].label)
    original, problem = _load_performance(perf)
    if problem:
        raise ValueError(problem)
    if channel is None:  # the generated channel that moves the most in the performance
        channel = max(generated.channels, key=lambda c: float(np.ptp(original.column(c))))
    fig, axes = plt.subplots(1, 2, figsize=(10, 3), sharey=True)
    t = np.arange(original.frames) / original.frame_rate
    axes[0].plot(t, original.column(channel), color="#444444", lw=1)
    axes[0].set_title(f"a performance: {Path(perf.file).name}", fontsize=9)
    g = generated.motion
    axes[1].plot(np.arange(g.frames) / g.frame_rate, g.column(channel), color="#1f5fbf", lw=1)
    axes[1].set_title(f"generated from the grammar, {generated.repeat} copies", fontsize=9)
    for ax in axes:
        ax.set_xlabel("seconds")
    axes[0].set_ylabel(f"{channel} (degrees)")
    fig.suptitle(record.name, fontsize=10)
    fig.tight_layout()
    return _save(fig, path)


def draw_praxicon(folder, out, *, fmt: str = "png", progress=None) -> list[Path]:
    """Every picture of a praxicon into ``out``; returns the paths written.

    ``out/actuators.FMT``, ``out/shared.FMT``, and per action with actuators
    ``out/morphemes/ACTION.FMT`` and ``out/systems/ACTION.FMT`` (the grammar
    forest and synchronisation graph of :func:`psgs.draw.draw`). ``progress``,
    when given, is called with ``(done, total, action name)`` before each action.
    matplotlib's layout warnings (a title wider than its figure) are kept inside:
    they say nothing a reader of the pictures can act on.
    """
    import warnings

    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", category=UserWarning, module="matplotlib")
        warnings.filterwarnings("ignore", message=".*tight_layout.*")
        warnings.filterwarnings("ignore", message=".*Glyph .* missing.*")
        return _draw_all(folder, Path(out), fmt, progress)


def _draw_all(folder, out: Path, fmt: str, progress) -> list[Path]:
    from psgs import loads
    from psgs.draw import draw

    praxicon = _praxicon(folder)  # read once: a damaged folder is one error before any picture
    written = [draw_actuator_matrix(praxicon, out / f"actuators.{fmt}")]
    try:
        written.append(draw_shared_patterns(praxicon, out / f"shared.{fmt}"))
    except ValueError:
        pass  # nothing shared: no picture (the praxicon may hold one action)
    drawn = [a for a in praxicon.actions if a.learnt and a.actuators and a.system]
    for done, action in enumerate(drawn):
        if progress is not None:
            progress(done, len(drawn), action.name)
        name = action.name
        written.append(draw_morphemes(praxicon, name, out / "morphemes" / f"{name}.{fmt}"))
        (out / "systems").mkdir(parents=True, exist_ok=True)
        # the system from the record's own text (the .psgs file beside it is a copy)
        written.append(draw(loads(action.system, source=action.file),
                            out / "systems" / f"{name}.{fmt}", max_steps=60))
    return written
