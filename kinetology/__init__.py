"""kinetology: joint-angle motion in, actiongrams out (an adapter over psgs).

Read motion capture (BVH, ASF/AMC) into a :class:`Motion`, segment each joint
angle into kinetemes (states B, G, R, Y from the signs of velocity and
acceleration), compress and reconstruct motion from its segments, and measure
the paper's five kinetological principles. ``psgs`` is used only for its
:class:`psgs.Actiongram` type.
"""

from __future__ import annotations

from psgs._foundation.lazy import lazy_names

from .motion import AXES, Joint, Motion, MotionFormatError, Skeleton
# imported now: the function shares its module's name, and a later first import of the
# module would otherwise make ``kinetology.performances`` the module
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
    "Span": "labels", "read_cmu_truelabels": "labels", "read_bandai_json": "labels",
    "actuator_map": "joints", "skeleton_parents": "joints",
    "view": "viewer", "Player": "viewer", "ViewError": "viewer",
}

def _motion_html(motion: Motion) -> str | None:
    from .viewer import motion_html
    return motion_html(motion)


# a notebook shows a motion as its skeleton player; attached here, not in motion.py, so that the
# value's module does not depend on the viewer that depends on it
Motion._repr_html_ = _motion_html

__all__ = ["Motion", "MotionFormatError", "Joint", "Skeleton", "AXES", "performances", *_LAZY]


__getattr__, __dir__ = lazy_names(__name__, _LAZY, listed=__all__)
