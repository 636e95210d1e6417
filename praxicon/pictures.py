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

import os
from pathlib import Path

import numpy as np

from kinetology.plotting import STATE_COLOURS
from psgs._foundation.pictures import picture_suffix

from ._values import check_count, is_count, shown as _shown
from .outputs import check_folder, check_writable_folder
from .records import ActionRecord, Praxicon
from .store import actuator_matrix, load

__all__ = ["draw_actuator_matrix", "draw_morphemes", "draw_shared_patterns",
           "draw_generated", "draw_praxicon", "check_picture", "check_folder"]



def _pyplot():
    try:
        import matplotlib
    except ImportError:  # pragma: no cover - the praxicon extra is not installed
        raise ValueError("pictures need matplotlib (pip install 'psgs[praxicon]')") from None
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def check_picture(path) -> str:
    """The suffix of ``path`` when matplotlib can write a picture there, else a ValueError (one
    line; :class:`~psgs.errors.ValidationError` for the suffix): checked before anything is
    drawn or written.

    Its folder must exist and be writable (the answers a picture goes with are not printed
    first, to end in an error for the picture alone), and ``path`` must not be a folder.

    Examples
    --------
    >>> check_picture("walk.PNG")
    '.png'
    >>> check_picture("walk.bvh")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: walk.bvh: matplotlib cannot write '.bvh' pictures; give one of .png, .svg, .pdf, ...
    >>> check_picture("/nonexistent/dir/walk.png")
    Traceback (most recent call last):
    ...
    ValueError: /nonexistent/dir/walk.png: no folder /nonexistent/dir to write the picture into
    """
    if not isinstance(path, (str, os.PathLike)):  # Path(5) is a TypeError
        raise ValueError(f"a picture is written to a file's path, not {type(path).__name__}")
    suffix = picture_suffix(path, needs="pip install 'psgs[praxicon]'")
    check_folder(path, "the picture")
    return suffix


def _save(fig, path) -> Path:
    plt = _pyplot()
    if not isinstance(path, (str, os.PathLike)):  # Path(5) is a TypeError
        plt.close(fig)
        raise ValueError(f"a picture is written to a file's path, not {type(path).__name__}")
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    # no date in the metadata: the same praxicon gives the same picture bytes
    import matplotlib

    metadata = {"Date": None} if path.suffix.lower() == ".svg" else {}
    with matplotlib.rc_context({"svg.hashsalt": "praxicon", "svg.fonttype": "none"}):
        fig.savefig(path, dpi=110, metadata=metadata or None)
    plt.close(fig)
    return path


def _praxicon(praxicon) -> Praxicon:
    # the pictures read the records only: descriptions of another version do not stop them
    return praxicon if isinstance(praxicon, Praxicon) else load(praxicon, descriptions=False)


def _named(folder) -> str:
    """What an error calls the praxicon drawn: its folder, or for a loaded one no repr of
    every count and setting."""
    return "the praxicon" if isinstance(folder, Praxicon) else str(folder)


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
        raise ValueError(f"{_named(folder)}: no learnt action to draw")
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


_LETTER_IN = 0.09  # inches a run needs for its letter at fontsize 6; narrower runs are colour only


def _runs(ax, rows, width_in: float, height: float = 0.8) -> None:
    """Kineteme runs ``(y, kinetemes, durations)`` as one collection of rectangles.

    One collection, not a bar per run: a praxicon's morphemes are ten thousand runs, and an
    artist per run made drawing them most of ``praxicon draw``'s time. A run wide enough
    on the page (``width_in`` inches for the x range) carries its letter.
    """
    from matplotlib.collections import PolyCollection

    span = max((sum(d) for _, _, d in rows), default=1.0) or 1.0
    boxes, colours = [], []
    letters: dict[str, list[tuple[float, float]]] = {}
    for y, kinetemes, durations in rows:
        x = 0.0
        for k, d in zip(kinetemes, durations):
            boxes.append(((x, y - height / 2), (x + d, y - height / 2),
                          (x + d, y + height / 2), (x, y + height / 2)))
            colours.append(STATE_COLOURS.get(k, "#999999"))
            if d / span * width_in >= _LETTER_IN:
                letters.setdefault(k, []).append((x + d / 2, y))
            x += d
    ax.add_collection(PolyCollection(boxes, facecolors=colours, edgecolors="white",
                                     linewidths=0.5))
    # each letter as a marker of one scatter (its glyph laid out once), not a text per run
    for k, at in letters.items():
        xs, ys = zip(*at)
        ax.scatter(xs, ys, marker=f"$\\mathrm{{{k}}}$", s=22, linewidths=0,
                   c="black" if k == "Y" else "white")
    ax.set_ylim(max((y for y, _, _ in rows), default=0) + 0.6, -0.6)  # first row on top


def draw_morphemes(folder, action: str, path) -> Path:
    """An action's morphemes, one row per actuator channel, kinetemes as coloured runs (Fig. 11)."""
    plt = _pyplot()
    record = _praxicon(folder)[action]
    rows = list(record.morphemes().items())
    if not rows:
        raise ValueError(f"action {action!r} has no actuators to draw")
    height = 0.8 + 0.28 * len(rows)
    fig, ax = plt.subplots(figsize=(7, height))
    # margins from the labels' length, not tight_layout (which draws the figure once more)
    left = min(3.0, 0.25 + 0.055 * max(len(c) for c, _ in rows))
    fig.subplots_adjust(left=left / 7, right=1 - 0.15 / 7, top=1 - 0.35 / height,
                        bottom=0.45 / height)
    runs = [(y, m.kinetemes, m.durations or [0.1] * len(m.kinetemes))
            for y, (_, m) in enumerate(rows)]
    _runs(ax, runs, width_in=7 - left - 0.15)
    ax.set_xlim(0, max(sum(d) for _, _, d in runs))
    ax.set_yticks(range(len(rows)), [c for c, _ in rows], fontsize=7)
    ax.set_xlabel("seconds (typical durations)")
    ax.set_title(f"morphemes of {action}", fontsize=9)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    return _save(fig, path)


def draw_shared_patterns(folder, path, *, most: int = 30, **options) -> Path:
    """The ``most`` sub-patterns shared by the most actions, with the actions (Fig. 13)."""
    from .shared import shared_patterns

    check_count(most, "most")  # -1 cut the last; np.int64 is a whole number, as before
    plt = _pyplot()
    patterns = sorted(shared_patterns(_praxicon(folder), **options),
                      key=lambda p: (-len(p.actions), -len(p.kinetemes)))[:most]
    if not patterns:
        raise ValueError(f"{_named(folder)}: no sub-pattern is shared by several actions")
    fig, ax = plt.subplots(figsize=(10, 0.8 + 0.3 * len(patterns)))
    longest = max(len(p.kinetemes) for p in patterns)
    _runs(ax, [(y, p.kinetemes, [0.25] * len(p.kinetemes)) for y, p in enumerate(patterns)],
          width_in=10 * 0.25 * longest / (0.25 * longest + 7))
    for y, pattern in enumerate(patterns):
        names = [a.split(".", 1)[-1] for a in pattern.actions]
        # at most 8 names, then a count: a long list ran off the picture's right edge
        shown = ", ".join(names[:8]) + (f", +{len(names) - 8} more" if len(names) > 8 else "")
        ax.text(0.25 * longest + 0.1, y, f"{len(pattern.actions)}: {shown}",
                va="center", fontsize=6, clip_on=True)
    ax.set_yticks(range(len(patterns)), [p.joint for p in patterns], fontsize=7)
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
        # (an action without a grammar generates every channel from its performances)
        candidates = generated.channels or [c for c in generated.motion.channels
                                            if c.rsplit(".", 1)[-1] in ("rx", "ry", "rz")]
        channel = max(candidates, key=lambda c: float(np.ptp(original.column(c))))
    fig, axes = plt.subplots(1, 2, figsize=(10, 3), sharey=True)
    t = np.arange(original.frames) / original.frame_rate
    axes[0].plot(t, original.column(channel), color="#444444", lw=1)
    axes[0].set_title(f"a performance: {Path(perf.file).name}", fontsize=9)
    g = generated.motion
    axes[1].plot(np.arange(g.frames) / g.frame_rate, g.column(channel), color="#1f5fbf", lw=1)
    made = "the grammar" if generated.origin == "grammar" else \
        "its performances' course"
    axes[1].set_title(f"generated from {made}, {generated.repeat} "
                      f"cop{'y' if generated.repeat == 1 else 'ies'}", fontsize=9)
    for ax in axes:
        ax.set_xlabel("seconds")
    axes[0].set_ylabel(f"{channel} (degrees)")
    fig.suptitle(record.name, fontsize=10)
    fig.tight_layout()
    return _save(fig, path)


def draw_praxicon(folder, out, *, fmt: str = "svg", progress=None,
                  workers: int | None = None) -> list[Path]:
    """Every picture of a praxicon into ``out``; returns the paths written.

    ``out/actuators.FMT``, ``out/shared.FMT``, and per action with actuators
    ``out/morphemes/ACTION.FMT`` and ``out/systems/ACTION.FMT`` (the grammar
    forest and synchronisation graph of :func:`psgs.draw.draw`). ``fmt`` is ``"svg"``
    (the default) or ``"png"``: a system of thirty-odd components is a graph some 20,000
    points wide, which SVG keeps readable at any zoom, and which as PNG is most of the time
    spent (rasterising it costs ``dot`` about six times its layout). ``progress``,
    when given, is called with ``(done, total, picture)`` as the per-action pictures
    are drawn. With Graphviz, up to ``workers`` ``dot`` programs (default: the number
    of cores, at most 4) lay out and rasterise systems while the morphemes are drawn;
    without it, ``workers`` processes draw the systems with matplotlib (the same bytes as
    ``workers=1``, which draws them all in this process).
    matplotlib's layout warnings (a title wider than its figure) are kept inside:
    they say nothing a reader of the pictures can act on.

    Examples
    --------
    A praxicon is built as in :func:`draw_actuator_matrix`'s example; a bad worker count is
    refused before anything is read or drawn:

    >>> draw_praxicon("no-such-praxicon", "img", workers=0)
    Traceback (most recent call last):
    ...
    ValueError: workers must be at least 1, not 0
    """
    import warnings

    if workers is not None and not is_count(workers):  # "2" failed in a comparison
        raise ValueError(f"workers must be at least 1, not {_shown(workers)}")
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", category=UserWarning, module="matplotlib")
        warnings.filterwarnings("ignore", message=".*tight_layout.*")
        warnings.filterwarnings("ignore", message=".*Glyph .* missing.*")
        return _draw_all(folder, Path(out), fmt, progress, workers)


def _system_picture(text: str, source: str, path: Path, engine: str = "matplotlib") -> Path:
    """A system's picture from its record's own text (the .psgs file beside it is a copy); a
    plain function of its arguments, so that a worker process can draw it."""
    from psgs import loads
    from psgs.draw import draw

    return draw(loads(text, source=source), path, max_steps=60, engine=engine)


def _check_systems(folder, praxicon: Praxicon) -> None:
    """ValueError naming the first record whose system does not parse, before any picture:
    ``load`` leaves the systems unparsed, and a damaged one stopped the drawing at its
    picture, naming the ``.psgs`` file (which holds a copy, maybe intact) as the culprit."""
    from .store import system_problem

    for action in praxicon.actions:
        where = (f"the record of {action.name!r}" if isinstance(folder, Praxicon)
                 else Path(folder) / "records" / f"{action.name}.json")
        problem = system_problem(action, where)
        if problem:
            raise ValueError(problem)


def _draw_all(folder, out: Path, fmt: str, progress, workers: int | None) -> list[Path]:
    from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor

    from psgs._foundation.engines import usable_cores
    from psgs.draw import graphviz_available
    from psgs.errors import ValidationError

    from ._pools import (ignore_interrupts, interrupts_deferred, spawned_ignoring_interrupts,
                         stop_pool)

    # before any picture: a file in its place (else mkdir's bare "File exists"), or a folder
    # that cannot be written, failed at the first picture
    check_writable_folder(out, "a folder for the pictures")
    praxicon = _praxicon(folder)  # read once: a damaged folder is one error before any picture
    if not any(a.learnt for a in praxicon.actions):
        raise ValueError(f"{_named(folder)}: no learnt action to draw")
    _check_systems(folder, praxicon)
    written = [draw_actuator_matrix(praxicon, out / f"actuators.{fmt}")]
    try:
        written.append(draw_shared_patterns(praxicon, out / f"shared.{fmt}"))
    except ValueError:
        pass  # nothing shared: no picture (the praxicon may hold one action)
    drawn = [a for a in praxicon.actions if a.learnt and a.actuators and a.system]
    if drawn:
        (out / "systems").mkdir(parents=True, exist_ok=True)
    total, done = 2 * len(drawn), 0

    def tell(what: str) -> None:
        nonlocal done
        if progress is not None:
            progress(done, total, what)
        done += 1

    def target(action) -> Path:
        return out / "systems" / f"{action.name}.{fmt}"

    def system(action, engine: str) -> Path:
        return _system_picture(action.system, action.file, target(action), engine)

    def by_dot(action) -> Path | None:
        try:
            return system(action, "graphviz")
        except ValidationError:
            return None  # dot gave up on this layout: matplotlib draws it below

    # dot runs as its own program, so threads overlap its layouts with the morphemes'
    # matplotlib (which stays on this thread: pyplot is not thread-safe); without dot,
    # matplotlib draws the systems too, in processes of their own (its labels' layout is the
    # time, one core each)
    dot = graphviz_available() and drawn
    many = workers or min(4, usable_cores())
    pool, pending = None, []
    try:
        # the pool starts its workers and its thread inside the submits: Ctrl-C there is held
        # until they are done, and then, inside this try, stops the pool (raised before it,
        # it left a worker no one stopped, which the interpreter's exit waited for for good,
        # or the exit drew every system submitted)
        with interrupts_deferred():
            if dot:
                pool = ThreadPoolExecutor(max_workers=many)
                pending = [pool.submit(by_dot, a) for a in drawn]
            elif many > 1 and len(drawn) > 1:
                import multiprocessing

                # spawn: a fresh interpreter on every platform, nothing inherited but the
                # arguments; Ctrl-C is this process's to handle (the workers would print
                # their tracebacks)
                pool = ProcessPoolExecutor(max_workers=min(many, len(drawn)),
                                           mp_context=multiprocessing.get_context("spawn"),
                                           initializer=ignore_interrupts)
                with spawned_ignoring_interrupts():
                    pending = [pool.submit(_system_picture, a.system, a.file, target(a))
                               for a in drawn]
        morphemes = []
        for action in drawn:
            tell(f"morphemes of {action.name}")
            morphemes.append(draw_morphemes(praxicon, action.name,
                                            out / "morphemes" / f"{action.name}.{fmt}"))
        for action, picture, future in zip(drawn, morphemes,
                                           pending or [None] * len(drawn)):
            tell(f"system of {action.name}")
            path = future.result() if future is not None else None
            written += [picture, path or system(action, "matplotlib")]
    except BaseException:
        if isinstance(pool, ProcessPoolExecutor):  # workers ignoring Ctrl-C are stopped now
            stop_pool(pool)
        raise
    finally:
        if pool is not None:
            pool.shutdown(cancel_futures=True)
    return written
