"""An action without a cyclic grammar, generated as its performances' mean course.

When PAL finds no synchronised repetition in an action (a one-off gesture: Bandai's
``guide`` points the way once), the action has no grammar system to derive copies from.
What it does have are its performances, each the action performed once. The honest model
of such an action is that performance's typical course, played once:

1. every channel of every performance is read as the cyclic generator reads the body
   around its actuators (:func:`praxicon.body_motion.body_of`: wrapped joints unwrapped,
   the root's rotation with its heading turned away, every take on one side of ±180°);
2. the takes are brought to one time base, the median of their lengths, by **dynamic time
   warping** (:func:`warped_mean`): every take is warped onto the most typical one, the
   events so lined up are placed at the takes' mean time, and the takes averaged there. A
   plain time normalisation would average a gesture made early in one take with the rest
   pose of another: the mean of misaligned gestures is a smeared, smaller, slower gesture
   (on Bandai's guide, 4 takes: the transitions' speed 0.53 of the takes' against 0.63
   warped; docs/praxicon.md);
3. the root's course (its heading and its velocity in the heading's frame, frame by frame)
   is averaged along the same alignment, and the root travels and turns as the takes do
   (the generator's own :func:`praxicon.body_motion.animate` machinery for the carrier
   joint above the root);
4. ``repeat`` copies are the gesture played that many times, each copy eased in from
   where the previous one ended (a copy of a gesture that ends where it began joins
   without a jump; one that does not is not bent back to its start).

With a style, only that style's performances are averaged (one performance of the style:
that performance, on its own clock).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

__all__ = ["warping_path", "warped_mean", "performed_motion"]


def warping_path(reference, take, band: float = 0.3) -> tuple[np.ndarray, np.ndarray]:
    """The dynamic time warping path between two multichannel series: index pairs ``(i, j)``.

    ``reference`` is ``(n, d)``, ``take`` ``(m, d)``; the cost of a pair is the squared
    Euclidean distance of the two frames. The path runs from ``(0, 0)`` to
    ``(n - 1, m - 1)`` in steps of one frame in either series or both, and stays within
    ``band`` (a share of the whole, on both series' times from 0 to 1) of the diagonal:
    a gesture made a little earlier or later is matched, a take is not folded onto one frame.

    >>> import numpy as np
    >>> a = np.array([0, 0, 1, 2, 1, 0, 0, 0], float)[:, None]
    >>> b = np.array([0, 0, 0, 0, 1, 2, 1, 0], float)[:, None]   # the same bump, 2 frames on
    >>> i, j = warping_path(a, b, band=0.5)
    >>> [int(j[i == 3][0])]   # the reference's peak is matched with the take's
    [5]
    """
    a = np.asarray(reference, float)
    b = np.asarray(take, float)
    n, m = a.shape[0], b.shape[0]
    cost = np.maximum((a * a).sum(axis=1)[:, None] + (b * b).sum(axis=1)[None, :]
                      - 2.0 * a @ b.T, 0.0)
    ti = np.linspace(0.0, 1.0, n)
    tj = np.linspace(0.0, 1.0, m)
    # the band is widened by one frame of either series, so that a path always exists
    width = band + 1.0 / max(min(n, m) - 1, 1)
    total = np.full((n, m), np.inf)
    for i in range(n):
        inside = np.flatnonzero(np.abs(tj - ti[i]) <= width)
        lo, hi = int(inside[0]), int(inside[-1]) + 1
        c = cost[i, lo:hi]
        if i == 0:
            entry = np.full(hi - lo, np.inf)
            entry[0] = 0.0 if lo == 0 else np.inf
        else:
            up = total[i - 1, lo:hi]
            diagonal = total[i - 1, lo - 1:hi - 1] if lo > 0 else \
                np.concatenate(([np.inf], total[i - 1, :hi - 1]))
            entry = np.minimum(up, diagonal)
        # total[j] = c[j] + min(entry[j], total[j - 1]): unrolled, the least over k <= j of
        # entry[k] plus the costs from k to j, which a running minimum of prefix sums gives
        running = np.cumsum(c)
        before = np.concatenate(([0.0], running[:-1]))
        total[i, lo:hi] = running + np.minimum.accumulate(entry - before)
    i, j = n - 1, m - 1
    path = [(i, j)]
    while i > 0 or j > 0:
        options = []
        if i > 0 and j > 0:
            options.append((total[i - 1, j - 1], i - 1, j - 1))
        if i > 0:
            options.append((total[i - 1, j], i - 1, j))
        if j > 0:
            options.append((total[i, j - 1], i, j - 1))
        _, i, j = min(options, key=lambda o: o[0])
        path.append((i, j))
    pairs = np.array(path[::-1])
    return pairs[:, 0], pairs[:, 1]


def _resampled(x: np.ndarray, frames: int) -> np.ndarray:
    return _at(x, np.linspace(0.0, x.shape[0] - 1, frames))


def _at(x: np.ndarray, where: np.ndarray) -> np.ndarray:
    """``x`` (frames along axis 0) at fractional frames ``where``, linearly interpolated."""
    x = np.asarray(x, float)
    flat = x.reshape(x.shape[0], -1)
    out = np.stack([np.interp(where, np.arange(x.shape[0]), flat[:, k])
                    for k in range(flat.shape[1])], axis=1)
    return out.reshape((len(where),) + x.shape[1:])


def _warp(path, frames: int, length: int) -> np.ndarray:
    """The take's frame (fractional) at each of the reference's ``frames``, from a path.

    Each reference frame takes the mean of the take's frames the path pairs with it; a
    path holds a take still over several reference frames, or skips through it, in runs
    of whole frames, so the warp is then averaged over a few frames (5 % of the
    reference), which keeps it monotone and makes those stairs slopes. Its ends stay at
    the takes' ends.
    """
    i, j = path
    w = np.bincount(i, weights=j, minlength=frames) / np.bincount(i, minlength=frames)
    width = max(3, int(round(0.05 * frames)) | 1)
    padded = np.pad(w, width // 2, mode="edge")
    w = np.convolve(padded, np.ones(width) / width, mode="valid")
    w[0], w[-1] = 0.0, length - 1.0
    return np.clip(w, 0.0, length - 1.0)


def warped_mean(takes, frames: int, band: float = 0.3):
    """The takes' average on ``frames`` frames, each warped onto the most typical; and the warps.

    ``takes`` are ``(frames_i, d)`` arrays. The most typical take is the one nearest (by
    :func:`warping_path`'s cost) to the mean of the takes linearly resampled to one
    length; every take is warped onto it (:func:`warping_path`), so that a rise is
    averaged with the others' rises, not with their rest before it. The events it lines up
    are then placed at the takes' mean time (each take's time as a share of its length,
    averaged), on ``frames`` frames, and the takes' values there averaged. Returns
    ``(mean, where)``: ``where[i]`` is take ``i``'s (fractional) frame at each generated
    frame, to carry other signals of the takes along the same alignment.

    Two takes of one bump made at different times average to a bump nearly as high, at
    their mean time, where the plain mean of the resampled takes is two half-height bumps:

    >>> import numpy as np
    >>> t = np.arange(60)
    >>> bump = lambda at: np.exp(-0.5 * ((t - at) / 4.0) ** 2)[:, None]
    >>> mean, _ = warped_mean([bump(20), bump(40)], 60)
    >>> round(float(mean.max()), 1), int(np.argmax(mean))
    (1.0, 30)
    >>> round(float(np.mean([bump(20), bump(40)], axis=0).max()), 1)
    0.5
    """
    takes = [np.asarray(x, float) for x in takes]
    linear = np.mean([_resampled(x, frames) for x in takes], axis=0)

    def cost(path, a, b):
        return float(((a[path[0]] - b[path[1]]) ** 2).sum())

    typical = int(np.argmin([cost(warping_path(linear, x, band), linear, x) for x in takes]))
    reference = takes[typical]
    n = reference.shape[0]
    warps = [_warp(warping_path(reference, x, band), n, x.shape[0]) for x in takes]
    # the reference's frames at the takes' mean time: a monotone map, made strictly so
    shares = np.mean([w / max(x.shape[0] - 1, 1) for w, x in zip(warps, takes)], axis=0)
    shares = shares + 1e-9 * np.arange(n)
    at = np.interp(np.linspace(0.0, shares[-1], frames), shares, np.arange(n, dtype=float))
    where = [np.interp(at, np.arange(n), w) for w in warps]
    mean = np.mean([_at(x, w) for x, w in zip(takes, where)], axis=0)
    return mean, where


def _eased(copy: np.ndarray, start: np.ndarray, frames: int) -> np.ndarray:
    """``copy`` begun at ``start`` instead of its own first frame, easing into its own course
    over ``frames`` frames (a smoothstep, so the join has no kink in the angle)."""
    s = np.clip(np.arange(copy.shape[0]) / max(frames, 1), 0.0, 1.0)
    weight = 1.0 - s * s * (3.0 - 2.0 * s)
    return copy + weight[:, None] * (start - copy[0])[None, :]


def _curves_of(body, takes, channels) -> list[dict]:
    """Per take, channel -> angles ready to average: the body's when it has them (root
    heading-free), else each channel unwrapped and every take on the first's side of ±180°."""
    from kinetology.segmentation import unwrap

    from .body_motion import _is_angle, nearest_turn

    if body.curves:
        return [dict(t) for t in body.curves]
    out: list[dict] = []
    for m in takes:
        take = {c: unwrap(m.column(c)) if _is_angle(c) else np.asarray(m.column(c), float)
                for c in channels}
        if out:
            take = {c: nearest_turn(v, float(np.mean(out[0][c]))) if _is_angle(c) else v
                    for c, v in take.items()}
        out.append(take)
    return out


def performed_motion(record, repeat: int, source_motion, style: str | None = None,
                     performances=None, alignment: str = "warp"):
    """The motion of an action without a grammar: its performances' warped mean, ``repeat`` times.

    Returns ``(motion, used)``: the :class:`kinetology.Motion` (channels and skeleton of
    ``source_motion``, one copy as long as the median performance) and how many
    performances it was made from. ``alignment`` ``"linear"`` averages the takes linearly
    resampled to that length instead of warped (to compare the two). Raises ValueError
    when no performance (of ``style``) can be read with those channels.
    """
    if alignment not in ("warp", "linear"):
        raise ValueError(f"alignment must be 'warp' or 'linear', not {alignment!r}")
    import kinetology

    from .body_motion import Course, _move, _wrap_as_written, body_of, missing_style, \
        performances_of, style_of
    from .heading import _body_velocity

    read = performances is None  # here, every file read (performances_of raises otherwise)
    if read:
        performances = performances_of(record)
    if style is not None:
        own = [m for m in performances if style in style_of(m.source)]
        if not own:
            raise missing_style(record, style, {} if read else None)
        performances = own
    channels = tuple(source_motion.channels)
    takes = [m for m in performances if set(channels) <= set(m.channels) and m.frames >= 2]
    if not takes:
        raise ValueError(f"action {record.name!r} has no grammar system and none of its "
                         f"performances can be read with the channels of "
                         f"{record.skeleton_source}: nothing to generate")
    rate = float(takes[0].frame_rate)
    body = body_of(record, channels, set(), None, None, takes)
    curves = _curves_of(body, takes, channels)
    frames = int(np.median([m.frames for m in takes]))
    # the alignment reads the angles (degrees): the channels that move most, the gesture,
    # weigh most; translations (centimetres) and the root's zeroed path are left out of it
    angles = [c for c in channels if c.rsplit(".", 1)[-1] in ("rx", "ry", "rz")]
    stacked = [np.stack([take[c] for c in channels], axis=1) for take in curves]
    index = [channels.index(c) for c in angles]
    if alignment == "warp":
        _, where = warped_mean([x[:, index] for x in stacked], frames)
    else:
        where = [np.linspace(0.0, x.shape[0] - 1, frames) for x in stacked]
    one = np.mean([_at(x, w) for x, w in zip(stacked, where)], axis=0)
    skeleton = source_motion.skeleton  # an ASF one too: the BVH writer re-expresses its axes
    ease = max(2, min(frames // 4, int(round(0.5 * rate))))
    parts = [one]
    for _ in range(repeat - 1):
        parts.append(_eased(one, parts[-1][-1], ease)[1:])  # the join frame is shared
    values = np.concatenate(parts, axis=0)
    if body.root is not None:
        course = []
        for m, w in zip(takes, where):
            h, _, forward, sideways = _body_velocity(m, body.root, body.axis)
            course.append(_at(np.stack([h - h[0], forward, sideways], axis=1), w))
        h, forward, sideways = np.mean(course, axis=0).T
        h = h - h[0]
        # copy k turns on from where copy k - 1 ended; its velocities are the first's
        path = Course(np.concatenate([h] + [h[1:] + k * h[-1] for k in range(1, repeat)]),
                      *(np.concatenate([v] + [v[1:]] * (repeat - 1)) for v in (forward, sideways)),
                      seconds=None)
        _move(values, {c: i for i, c in enumerate(channels)}, replace(body, course=path),
              rate, set(), {})
    _wrap_as_written(values, channels, takes)
    motion = kinetology.Motion(values, channels, rate, skeleton, f"generated:{record.name}",
                               {"format": "generated", "origin": "performances",
                                "performances": len(takes), "cycle": 1})
    return motion, len(takes)
