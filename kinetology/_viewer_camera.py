"""Where the player's camera looks, and how a body is drawn on the screen: the geometry behind
:class:`kinetology.viewer.Panel`'s ``pose``, ``floor``, ``bones`` and ``body``.

Positions are ``(frames, joints, 3)`` in file units, y up. The camera looks at a point on the
floor (per frame, when it follows the body) from ``yaw`` degrees about the vertical, tilted
``pitch`` degrees downwards, and projects orthographically.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["YAW", "PITCH", "project", "bones", "body", "centre", "anchors", "fit",
           "floor_lines"]

YAW, PITCH = 30.0, 12.0  # degrees: the default view, a little from the side and above


def project(points: np.ndarray, centre: np.ndarray, yaw: float, pitch: float) -> np.ndarray:
    """Orthographic view turned by ``yaw`` about the vertical and tilted ``pitch`` downwards."""
    a, b = math.radians(yaw), math.radians(pitch)
    x, y, z = (points - centre)[..., 0], (points - centre)[..., 1], (points - centre)[..., 2]
    across = x * math.cos(a) - z * math.sin(a)
    depth = x * math.sin(a) + z * math.cos(a)
    return np.stack([across, y * math.cos(b) + depth * math.sin(b)], axis=-1)


def bones(positions: np.ndarray, parents) -> tuple[bool, ...]:
    """Per joint, whether the link to its parent keeps its length within 1% of its mean."""
    out = []
    for j, parent in enumerate(parents):
        if parent < 0:
            out.append(False)
            continue
        length = np.linalg.norm(positions[:, j] - positions[:, parent], axis=-1)
        out.append(bool(np.ptp(length) <= 0.01 * length.mean() + 1e-9))
    return tuple(out)


def body(links: tuple[bool, ...], parents) -> np.ndarray:
    """The joints at an end of a bone (``links``: :func:`bones`), a boolean mask; every joint
    when there is no bone."""
    mask = np.array(links)
    for j, parent in enumerate(parents):
        if links[j]:
            mask[parent] = True
    return mask if mask.any() else np.ones(len(parents), bool)


def centre(positions: np.ndarray) -> np.ndarray:
    """The middle of the whole path on the floor, at the lowest height reached."""
    lo, hi = positions.min(axis=(0, 1)), positions.max(axis=(0, 1))
    return np.array([(lo[0] + hi[0]) / 2, lo[1], (lo[2] + hi[2]) / 2])


def anchors(positions: np.ndarray, mask: np.ndarray, follow: bool) -> np.ndarray:
    """Per frame, the floor point the camera looks at: below the mean of the body's joints
    (``mask``) when following, else :func:`centre`."""
    out = np.tile(centre(positions), (positions.shape[0], 1))
    if follow:
        out[:, [0, 2]] = positions[:, mask][..., [0, 2]].mean(axis=1)
    return out


def fit(positions: np.ndarray, mask: np.ndarray, looked_at: np.ndarray) -> tuple[float, float]:
    """Horizontal radius of the body around the camera's points ``looked_at`` (any yaw fits in
    it) and its height above the floor."""
    points = positions[:, mask]
    flat = points[..., [0, 2]] - looked_at[:, None, [0, 2]]
    radius = float(np.sqrt((flat ** 2).sum(-1)).max())
    height = float(points[..., 1].max() - looked_at[0, 1])
    return max(radius, 1e-9), max(height, 1e-9)


def floor_lines(anchor: np.ndarray, radius: float) -> np.ndarray:
    """The floor's grid within ``radius`` of ``anchor``, ``(lines, 2, 3)``: five lines each of
    constant x and of constant z, at a spacing of half the radius, fixed on the floor."""
    spacing = radius / 2
    lines = []
    for axis in (0, 2):  # lines of constant x, then of constant z
        other = 2 - axis
        first = math.ceil((anchor[axis] - radius) / spacing)
        for k in range(first, first + 5):
            a, b = anchor.copy(), anchor.copy()
            a[axis] = b[axis] = k * spacing
            a[other], b[other] = anchor[other] - radius, anchor[other] + radius
            lines.append((a, b))
    return np.array(lines, float).reshape(-1, 2, 3)
