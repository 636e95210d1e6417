"""kinetology: joint-angle motion in, actiongrams out (an adapter over psgs).

Read motion capture (BVH, ASF/AMC) into a :class:`Motion`, segment each joint
angle into kinetemes (states B, G, R, Y from the signs of velocity and
acceleration), compress and reconstruct motion from its segments, and measure
the paper's five kinetological principles. ``psgs`` is used only for its
:class:`psgs.Actiongram` type.
"""

from __future__ import annotations

import sys
from types import ModuleType
from typing import TYPE_CHECKING

from psgs._foundation.lazy import lazy_names

if TYPE_CHECKING:  # for readers and checkers; at run time every name loads on first use
    from .motion import AXES, Joint, Motion, MotionFormatError, Skeleton
    from .performances import performances

# public name -> module that defines it (imported on first use)
_LAZY = {
    "read": "readers", "read_bvh": "bvh", "read_amc": "asf", "read_asf": "asf",
    "forward_kinematics": "kinematics", "joint_angle": "kinematics",
    "segment": "segmentation", "states": "segmentation", "segments": "segmentation",
    "Segmentation": "segmentation", "STATES": "segmentation",
    "compress": "codec", "decompress": "codec", "reconstruct": "codec",
    "synthetic_motion": "synthetic", "unwrap": "segmentation", "write_bvh": "bvh_writer",
    "cut": "performances", "segment_performances": "performances",
    "Motion": "motion", "MotionFormatError": "motion", "Joint": "motion", "Skeleton": "motion",
    "AXES": "motion",
    "Span": "labels", "read_cmu_truelabels": "labels", "read_bandai_json": "labels",
    "actuator_map": "joints", "skeleton_parents": "joints",
    "view": "viewer", "Player": "viewer", "ViewError": "viewer",
}


def _motion_html(motion: Motion) -> str | None:
    from .viewer import motion_html
    return motion_html(motion)


class _Package(ModuleType):
    """This package, with two rules a module-level ``__getattr__`` cannot keep: the import
    system sets each submodule, once loaded, as an attribute of its package, after the
    submodule ran.

    * ``kinetology.performances`` is the function, not its module (which shares its name),
      whoever imports the module first.
    * A :class:`Motion` shows its skeleton player in a notebook: ``_repr_html_`` is attached
      when :mod:`kinetology.motion` loads, here, not in motion.py, so that the value's module
      does not depend on the viewer that depends on it.
    """

    @property
    def performances(self):
        if "performances" not in vars(self):
            from .performances import performances
            vars(self)["performances"] = performances
        return vars(self)["performances"]

    @performances.setter
    def performances(self, value) -> None:
        # the import system sets the submodule once loaded: the name stays the function's
        if value is not sys.modules.get(f"{__name__}.performances"):
            vars(self)["performances"] = value

    def __setattr__(self, name: str, value) -> None:
        super().__setattr__(name, value)
        if name == "motion" and isinstance(value, ModuleType):
            value.Motion._repr_html_ = _motion_html


__all__ = ["Motion", "MotionFormatError", "Joint", "Skeleton", "AXES", "performances", *_LAZY]


__getattr__, __dir__ = lazy_names(__name__, _LAZY, listed=__all__)
sys.modules[__name__].__class__ = _Package
