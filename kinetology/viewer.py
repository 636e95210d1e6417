"""See a motion: the skeleton from forward kinematics, played in time, joints coloured by kineteme.

:func:`view` turns one or more motions into a :class:`Player`: per motion a panel holding the
joint positions (:func:`kinetology.forward_kinematics`) of a subsample of the frames, the state
(``B G R Y``, :mod:`kinetology.segmentation`) each joint is in at each of those frames, and which
joints are actuators. A player writes itself as

* a self-contained HTML page (``.html``): the data and the script inline, no network, so it
  opens from a file on a machine without internet; a time slider, play/pause, drag to turn the
  bodies; several motions side by side on one clock;
* an animated GIF (``.gif``, matplotlib's animation with Pillow) or an MP4 (``.mp4``, with
  ffmpeg), for documents and papers.

In a notebook a :class:`~kinetology.Motion` shows this player (``Motion._repr_html_``).

**A joint's colour** is the state of its moving rotation channel with the widest range (a
joint has up to three; the widest is the one that shapes the pose most); grey when none of its
channels moves (``min_range``, as the segmentation decides). **Actuators**, when given, are
drawn with a ring.

**Data volume.** Frames are subsampled, every ``k``-th kept with ``k`` the smallest step that
gives at most ``max_rate`` frames per second (30) and at most ``max_frames`` frames per motion
(500); positions are stored to 1/1000 of the motion's largest extent, as differences from the
frame before. A page holds at most ``max_frames x joints x 3`` small integers per motion (180 KB
for a CMU walk with its 38 joints at the cap, 490 frames).
"""

from __future__ import annotations

import math
import os
import shutil
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import Iterable, Mapping, Sequence

import numpy as np

# below: a panel's geometry (_viewer_camera), what it shows of its motion besides the
# positions (_viewer_contents), and the HTML of a player (_viewer_page)
from . import _viewer_camera as camera
from ._viewer_camera import PITCH as _PITCH, YAW as _YAW
from ._viewer_checks import pace_problem, panels_problem, tick_problem, view_problem
from ._viewer_contents import (actuator_flags, actuator_problem, frame_step, joint_states,
                               titled)
from ._viewer_page import fragment, packed_positions, page
from .kinematics import positions_problem
from .motion import Motion, MotionFormatError, check_number
from .motion import counted as _count

__all__ = ["SUFFIXES", "ViewError", "Panel", "Player", "view", "motion_html", "check_output"]

#: Output suffixes a player writes.
SUFFIXES = (".html", ".gif", ".mp4")


class ViewError(MotionFormatError):
    """Motion the viewer cannot show, or an output it cannot write; one line, naming what.

    A :class:`~kinetology.MotionFormatError` (so a ``ValueError``): the command line reports
    it as it reports a bad motion file, in one line with exit status 2.

    Parameters
    ----------
    message : str
        What is wrong.
    source : str
        The motion, file or output concerned (``str(error)`` is ``source: message``).
    line, column : int, optional
        Unused: the viewer's errors have no place in a file.

    Examples
    --------
    >>> import numpy as np
    >>> view(Motion(np.zeros((0, 1)), ("knee.rx",), 30, source="empty.bvh"))
    Traceback (most recent call last):
    ...
    kinetology.viewer.ViewError: empty.bvh: the motion has no frames; nothing to show
    """


@dataclass(frozen=True, eq=False)
class Panel:
    """One motion as the player shows it: subsampled joint positions, states, actuators.

    Attributes
    ----------
    label : str
        The panel's title (a file name, or the key given to :func:`view`).
    joints : tuple of str
        Joint names in skeleton order (end sites included).
    parents : tuple of int
        Each joint's parent index, -1 for the root.
    positions : numpy.ndarray
        ``(frames, joints, 3)``, the kept frames' joint positions (file units, y up).
    states : tuple of str
        Per joint, one state letter per kept frame (``"-"``: the joint does not move).
    actuators : tuple of bool
        Per joint, whether it is highlighted as an actuator.
    frame_rate : float
        Kept frames per second (the motion's rate divided by the step).
    step : int
        Every ``step``-th frame of the motion was kept.
    follow : bool, default True
        The camera follows the body (the mean of its joints) over the floor: a walk stays in
        the picture, the floor's grid passes under it; False: it looks at the middle of the
        whole path.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Joint, Skeleton
    >>> arm = Skeleton((Joint("shoulder", None, (0, 0, 0), ("shoulder.rz",)),
    ...                 Joint("hand", 0, (10, 0, 0), end_site=True)))
    >>> panel = view(Motion(np.linspace(0, 90, 61)[:, None], ("shoulder.rz",), 60, arm)).panels[0]
    >>> panel.step, panel.frames, panel.joints, panel.parents
    (2, 31, ('shoulder', 'hand'), (-1, 0))
    >>> panel
    <Panel '<motion>': 31 frames of 2 joints at 30 fps (1 frame in 2)>
    >>> np.round(panel.positions[-1, 1], 6)        # the hand, raised by 90 degrees
    array([ 0., 10.,  0.])
    """

    label: str
    joints: tuple[str, ...]
    parents: tuple[int, ...]
    positions: np.ndarray
    states: tuple[str, ...]
    actuators: tuple[bool, ...]
    frame_rate: float
    step: int
    follow: bool = True

    @property
    def frames(self) -> int:
        """Number of kept frames."""
        return self.positions.shape[0]

    def __repr__(self) -> str:  # a summary, not the array of positions
        kept = "every frame" if self.step == 1 else f"1 frame in {self.step}"
        return (f"<Panel {self.label!r}: {_count(self.frames, 'frame')} of "
                f"{_count(len(self.joints), 'joint')} at {self.frame_rate:g} fps ({kept})>")

    @cached_property
    def bones(self) -> tuple[bool, ...]:
        """Per joint, whether the line to its parent is a bone: a link whose length stays
        within 1% of its mean. Not a bone: a root that stays at the origin while the body's
        translation channels carry it away (Bandai Namco's ``joint_Root``); such a link is not
        drawn, and a joint without bones is not part of the body."""
        return camera.bones(self.positions, self.parents)

    @cached_property
    def body(self) -> np.ndarray:
        """Joints that are part of the drawn body (at an end of a bone), a boolean mask."""
        return camera.body(self.bones, self.parents)

    def pose(self, frame: int, yaw: float = _YAW, pitch: float = _PITCH) -> np.ndarray:
        """The joints of kept frame ``frame`` projected on the screen plane, ``(joints, 2)``:
        x to the right, y up, in file units (the page and the GIF draw this projection)."""
        return camera.project(self.positions[frame], self._anchors[frame], yaw, pitch)

    def floor(self, frame: int, yaw: float = _YAW, pitch: float = _PITCH) -> np.ndarray:
        """The floor's grid around the camera's point at kept frame ``frame``, projected as
        :meth:`pose` projects the joints: ``(lines, 2, 2)``. The lines are fixed on the floor,
        so a body that travels passes over them."""
        anchor = self._anchors[frame]
        radius, _ = self._fit
        return camera.project(camera.floor_lines(anchor, radius), anchor, yaw, pitch)

    def _centre(self) -> np.ndarray:
        return camera.centre(self.positions)

    @cached_property
    def _anchors(self) -> np.ndarray:
        """Per kept frame, the floor point the camera looks at: when following, below the mean
        of the joints (not the root joint: Bandai Namco's root stays at the origin while the
        hips carry the body away)."""
        return camera.anchors(self.positions, self.body, self.follow)

    @cached_property
    def _fit(self) -> tuple[float, float]:
        """Horizontal radius around the camera's point (any yaw fits in it) and height."""
        return camera.fit(self.positions, self.body, self._anchors)

    def to_json(self) -> dict:
        """The panel as the page's script reads it (positions as integer differences)."""
        return {"label": self.label, "joints": list(self.joints), "parents": list(self.parents),
                "frames": self.frames, "rate": self.frame_rate,
                **packed_positions(self.positions, self._centre(), *self._fit),
                "states": list(self.states),
                "actuators": [int(a) for a in self.actuators], "follow": self.follow,
                "bones": [int(b) for b in self.bones], "body": [int(b) for b in self.body]}


@dataclass(frozen=True, eq=False)
class Player:
    """Motions ready to be played side by side: ``to_html()``, ``save(path)``, notebook repr.

    Attributes
    ----------
    panels : tuple of Panel
        One per motion, in the order given.
    frame_rate : float
        The clock of the page and of the animation: the fastest panel's kept rate.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Joint, Skeleton
    >>> arm = Skeleton((Joint("shoulder", None, (0, 0, 0), ("shoulder.rz",)),
    ...                 Joint("hand", 0, (10, 0, 0), end_site=True)))
    >>> slow = Motion(np.linspace(0, 90, 10)[:, None], ("shoulder.rz",), 10, arm)
    >>> fast = Motion(np.linspace(0, 90, 30)[:, None], ("shoulder.rz",), 30, arm)
    >>> player = view({"slow": slow, "fast": fast})
    >>> player.frame_rate, player.ticks, player.frame_of(0, 29), player.frame_of(1, 29)
    (30.0, 30, 9, 29)
    >>> player
    <Player of 2 motions at 30 fps, 30 steps: slow (10 frames, 2 joints), fast (30 frames, 2 joints)>
    >>> 'class="kinetology-view"' in player._repr_html_()    # what a notebook shows
    True
    """

    panels: tuple[Panel, ...]
    frame_rate: float

    def __post_init__(self) -> None:  # no panel failed in max(), a string rate in its repr
        if isinstance(self.panels, Iterable) and not isinstance(self.panels, str):
            object.__setattr__(self, "panels", tuple(self.panels))  # a list, as before
        if problem := panels_problem(self.panels, Panel):
            raise ViewError(problem, source="kinetology.Player")
        check_number(self.frame_rate, "frame_rate", positive=True)

    def __repr__(self) -> str:  # a summary, not every panel's positions
        shown = ", ".join(f"{p.label} ({_count(p.frames, 'frame')}, "
                          f"{_count(len(p.joints), 'joint')})" for p in self.panels)
        return (f"<Player of {_count(len(self.panels), 'motion')} at {self.frame_rate:g} fps, "
                f"{_count(self.ticks, 'step')}: {shown}>")

    @property
    def ticks(self) -> int:
        """Steps of the time slider (and frames of a GIF/MP4): the longest motion's length."""
        return max(1, max(math.ceil(p.frames * self.frame_rate / p.frame_rate - 1e-9)
                          for p in self.panels))

    def frame_of(self, panel: int, tick: int) -> int:
        """The kept frame that panel ``panel`` shows at slider step ``tick`` (the last frame
        once its motion has ended)."""
        p = self.panels[panel]
        if problem := tick_problem(tick):  # 3.0 is a whole number, as before
            raise ViewError(problem, source="kinetology.Player")
        return min(int(math.floor(tick * p.frame_rate / self.frame_rate + 1e-9)), p.frames - 1)

    def to_html(self, *, title: str | None = None) -> str:
        """The whole page: inline data and script, nothing fetched, opens from a file."""
        return page(title or " | ".join(p.label for p in self.panels), fragment(self))

    def _repr_html_(self) -> str:
        return fragment(self)

    def save(self, path: str | Path, *, dpi: int = 72) -> Path:
        """Write the player to ``path``: ``.html`` (the page), ``.gif`` or ``.mp4``.

        Raises
        ------
        ViewError
            For another suffix, and for ``.gif``/``.mp4`` when matplotlib (``.gif``: with
            Pillow) or ffmpeg (``.mp4``) is missing, naming what to install.
        """
        path = Path(path)
        suffix = check_output(path)
        if suffix == ".html":
            path.write_text(self.to_html(), encoding="utf-8")
        else:
            try:
                import matplotlib  # noqa: F401  (Pillow, which writes the GIF, comes with it)
            except ImportError:
                raise ViewError(f"writing {suffix} needs matplotlib: pip install 'psgs[plot]'",
                                source=str(path)) from None
            problem = pace_problem(self.frame_rate, self.ticks, suffix)  # before any drawing
            if problem:
                raise ViewError(problem, source=str(path))
            from ._viewer_animation import animate
            animate(self, path, suffix, dpi=dpi)
        return path


def check_output(path: str | Path) -> str:
    """The suffix of ``path`` when a player can be written there (``.html``, ``.gif``, ``.mp4``
    with ffmpeg on PATH), else :class:`ViewError`: checked before any work is done.

    Examples
    --------
    >>> check_output("walk.HTML")
    '.html'
    >>> check_output("walk.pdf")
    Traceback (most recent call last):
    ...
    kinetology.viewer.ViewError: walk.pdf: cannot write '.pdf'; give one of .html, .gif, .mp4
    """
    if not isinstance(path, (str, os.PathLike)):
        raise ViewError(f"the output must be a file's path, not {type(path).__name__}",
                        source="kinetology.view")
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in SUFFIXES:
        raise ViewError(f"cannot write {suffix or 'a file without a suffix'!r}; give one of "
                        f"{', '.join(SUFFIXES)}", source=str(path))
    if suffix == ".mp4" and shutil.which("ffmpeg") is None:
        raise ViewError("writing .mp4 needs ffmpeg, which is not on PATH (install it, e.g. "
                        "apt-get install ffmpeg), or write a .gif", source=str(path))
    return suffix


def _panel(label: str, motion: Motion, actuators, kinetemes: bool, max_rate: float,
           max_frames: int, follow: bool, params: dict) -> Panel:
    if not isinstance(motion, Motion):
        raise ViewError(f"not a kinetology.Motion but {type(motion).__name__}", source=label)
    if motion.frames == 0:
        raise ViewError("the motion has no frames; nothing to show", source=motion.source)
    if motion.skeleton is None:
        raise ViewError("no skeleton to draw (read an AMC file with its ASF)",
                        source=motion.source)
    from .kinematics import forward_kinematics

    step = frame_step(motion, max_rate, max_frames)
    kept = Motion(motion.values[::step], motion.channels, motion.frame_rate / step,
                  motion.skeleton, motion.source)
    positions = forward_kinematics(kept)
    if problem := positions_problem(positions):
        raise ViewError(problem, source=motion.source)
    positions.setflags(write=False)
    joints = motion.skeleton.joints
    states = joint_states(motion, step, params) if kinetemes else \
        tuple("-" * kept.frames for _ in joints)
    actuators = tuple(actuators or ())  # read once: a generator is checked, then flagged
    if problem := actuator_problem(motion, actuators):
        raise ViewError(problem, source=label)
    return Panel(label, motion.skeleton.names,
                 tuple(-1 if j.parent is None else j.parent for j in joints), positions,
                 states, actuator_flags(motion, actuators), kept.frame_rate, step, follow)


def view(motions: Motion | Sequence[Motion] | Mapping[str, Motion],
         output: str | Path | None = None, *,
         actuators: Iterable[str] | Mapping[str, Iterable[str]] | None = None,
         kinetemes: bool = True, max_rate: float = 30.0, max_frames: int = 500,
         follow: bool = True,
         **params) -> Player:
    """A player of one or more motions side by side; written to ``output`` when given.

    Parameters
    ----------
    motions : Motion, sequence of Motion, or mapping of str to Motion
        What to show, one panel each, on one clock. A mapping's keys are the panels' titles
        (``{"real": take, "generated": result.motion}``); otherwise the file names.
    output : str or Path, optional
        ``.html``, ``.gif`` or ``.mp4`` (see :meth:`Player.save`).
    actuators : iterable of str, or mapping of title to iterable of str, optional
        Joints (or channels, standing for their joints) drawn with a ring; a mapping gives each
        panel its own.
    kinetemes : bool, default True
        Colour joints by their current state (False: every joint grey, no segmentation run).
    max_rate : float, default 30
        Most frames per second kept (``inf``: every frame).
    max_frames : int, default 500
        Most frames kept per motion (the step grows for longer motions; ``inf``: no cap).
    follow : bool, default True
        The camera follows the body over the floor (False: it looks at the middle of the
        path, so the whole path is in the picture and the body smaller).
    **params
        Segmentation parameters (:data:`kinetology.segmentation.DEFAULTS`).

    Returns
    -------
    Player

    Raises
    ------
    ViewError
        For no motion, a motion without frames or skeleton, an unknown joint to highlight, an
        output suffix it cannot write or a missing writer (naming what to install).

    Examples
    --------
    A leg of two bones whose knee bends, played at most 10 frames per second:

    >>> import numpy as np
    >>> from kinetology.bvh import parse_bvh
    >>> lines = "\\n".join(f"0 {a:g}" for a in 45 * (1 - np.cos(np.linspace(0, 6.3, 60))))
    >>> leg = parse_bvh('''HIERARCHY
    ... ROOT hip
    ... { OFFSET 0 0 0
    ...   CHANNELS 1 Xrotation
    ...   JOINT knee
    ...   { OFFSET 0 -10 0
    ...     CHANNELS 1 Xrotation
    ...     End Site
    ...     { OFFSET 0 -10 0 } } }
    ... MOTION
    ... Frames: 60
    ... Frame Time: 0.0333333
    ... ''' + lines + "\\n", source="leg.bvh")
    >>> player = view(leg, actuators=["knee"], max_rate=10)
    >>> panel = player.panels[0]
    >>> panel.step, panel.frames, panel.states[1][:8], panel.actuators
    (3, 20, 'BBBBBGGG', (False, True, False))
    >>> page = player.to_html()       # data and script inline: nothing to fetch
    >>> page.startswith("<!DOCTYPE html>"), " src=" in page, "<link" in page
    (True, False, False)
    >>> view(leg, "leg.png")
    Traceback (most recent call last):
    ...
    kinetology.viewer.ViewError: leg.png: cannot write '.png'; give one of .html, .gif, .mp4
    """
    if output is not None:
        check_output(output)  # before any work: a bad suffix fails at once
    if isinstance(motions, Motion):
        motions = [motions]
    if isinstance(motions, str) or not isinstance(motions, Iterable):
        raise ViewError(f"motions must be a Motion, a sequence or a mapping of them, not "
                        f"{type(motions).__name__}", source="kinetology.view")
    named = dict(motions) if isinstance(motions, Mapping) else titled(motions)
    if not named:
        raise ViewError("no motion to show", source="kinetology.view")
    for label, motion in named.items():
        if not isinstance(motion, Motion):
            raise ViewError(f"panel {label!r} is a {type(motion).__name__}, not a Motion",
                            source="kinetology.view")
    if problem := view_problem(max_rate, max_frames, kinetemes, follow):
        raise ViewError(problem, source="kinetology.view")
    kinetemes, follow = bool(kinetemes), bool(follow)  # numpy bools too, as before
    if actuators is not None and (isinstance(actuators, str) or not isinstance(actuators, Iterable)):
        raise ViewError(f"actuators must be a collection of joint names, not {actuators!r}",
                        source="kinetology.view")  # a string was taken letter by letter
    per_panel = actuators if isinstance(actuators, Mapping) else \
        dict.fromkeys(named, None if actuators is None else tuple(actuators))  # read once
    unknown = set(per_panel) - set(named)
    if unknown:
        raise ViewError(f"actuators given for {', '.join(map(repr, sorted(unknown)))}, which "
                        f"is not a panel ({', '.join(map(repr, named))})",
                        source="kinetology.view")
    panels = tuple(_panel(label, m, per_panel.get(label), kinetemes, max_rate, max_frames,
                          follow, params) for label, m in named.items())
    player = Player(panels, max(p.frame_rate for p in panels))
    if output is not None:
        player.save(output)
    return player


def motion_html(motion: Motion) -> str | None:
    """What a notebook shows for a motion: its player (no page around it), or None (the plain
    ``repr``) when the motion has no frames or no skeleton.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology import Joint, Skeleton
    >>> arm = Skeleton((Joint("shoulder", None, (0, 0, 0), ("shoulder.rz",)),
    ...                 Joint("hand", 0, (10, 0, 0), end_site=True)))
    >>> swing = Motion(np.linspace(0, 90, 30)[:, None], ("shoulder.rz",), 30, arm)
    >>> motion_html(swing) == swing._repr_html_(), motion_html(swing.select(swing.channels))
    (True, None)
    """
    if motion.frames == 0 or motion.skeleton is None:
        return None
    return view(motion)._repr_html_()
