"""A correction layer that makes a generated curve segment to exactly the kinetemes it was built from.

The quartic base (:func:`kinetology.codec.reconstruct`) is smooth: its velocity
and acceleration change sign only where a smooth curve can, and a kineteme whose
displacement is a fraction of a degree stays inside the segmentation's dead bands.
Real motion at 30 fps has such kinetemes (``R Y R B``: a fall that turns into a rise
in one frame), because the segmentation reads *frames*: its velocity and
acceleration are central differences of the Gaussian-smoothed angle, and a run of
one sign counts only when it leaves the dead band somewhere (otherwise it takes the
sign of the run before it, :func:`kinetology.segmentation.significant_sign`).

:func:`shape` works in that frame domain. Smoothing and differencing are linear, so
the smoothed velocity ``v = Mv x`` and acceleration ``a = Ma x`` of a raw curve
``x`` are matrices applied to it (built by running kinetology's own
:func:`~kinetology.segmentation.smooth` and
:func:`~kinetology.segmentation.derivatives` on the identity). For every frame the
wanted state gives the wanted *effective* sign of ``v`` and ``a``; per run of one
effective sign ``[s, e)`` with a chosen peak frame ``p`` these linear conditions make
the segmentation read exactly that run:

* frames ``s .. p`` and ``e - 1`` have the run's sign (by a margin ``eps`` that the
  BVH file's six decimals cannot undo), so the raw run that starts at ``s`` is the
  one that reaches the peak, and the next run starts at ``e``, not before;
* at ``p`` the magnitude exceeds the dead band (by 2 %);
* frames between may take the other sign, but only under 98 % of the dead band
  (so they never count);
* and the smoothed range is at least 1.1 times ``min_range`` (else the channel
  is "still").

The raw curve closest to the base (L1, plus L1 of the correction's steps) under
these conditions is a linear programme (:func:`scipy.optimize.linprog`, HiGHS dual
simplex, its iterations capped; whether the conditions can hold at all is asked first, alone,
until some round's did). The relative dead band (a share of the channel's
own 95th-percentile speed) depends on the answer, so the band is assumed, checked
on the answer and the programme solved again with the answer's band when it moved
(up to ten rounds, fewer where the bands come back to a round's: the rounds would go round
that cycle). The peaks are placed three ways and the nearest answer kept. The caller checks
every answer by segmenting it again.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Shaped", "derivative_matrices", "frame_signs", "shape", "lengthened"]

# effective signs of velocity and acceleration per state (B G R Y)
_VELOCITY = {"B": 1, "G": 1, "R": -1, "Y": -1}
_ACCELERATION = {"B": 1, "G": -1, "R": -1, "Y": 1}
_PEAK_MARGIN = 1.02   # a peak exceeds the dead band by 2 %
_QUIET_MARGIN = 0.98  # a frame of the other sign stays under 98 % of the band
_ROUNDS = 10          # attempts at the relative dead band (most settle in one or two)
_ITERATIONS = 40      # simplex iterations per frame a programme may take
_REACH = 1.1          # the smoothed range asked, in units of the segmentation's min_range


@dataclass(frozen=True)
class Shaped:
    """A raw curve from :func:`shape` and how it was obtained.

    Attributes
    ----------
    curve : numpy.ndarray
        The raw angle, one value per frame.
    status : str
        ``"solved"`` or why not (``"infeasible"``, ``"band"``: the relative dead band
        did not settle between the peaks and the quiet frames, ``"budget"``: the
        solver's iteration limit).
    change : float
        Largest ``|curve - base|``, degrees.
    """

    curve: np.ndarray
    status: str
    change: float


def derivative_matrices(frames: int, frame_rate: float, smoothing: float):
    """Sparse matrices giving the smoothed velocity and acceleration of a raw curve.

    Parameters
    ----------
    frames : int
        Length of the curve.
    frame_rate : float
        Frames per second.
    smoothing : float
        Gaussian sigma in seconds, as the segmentation uses it.

    Returns
    -------
    (scipy.sparse.csr_matrix, scipy.sparse.csr_matrix)
        ``Mv``, ``Ma``: ``Mv @ x`` equals
        ``derivatives(smooth(x, frame_rate, smoothing), frame_rate)[0]`` (within
        rounding), ``Ma @ x`` the acceleration.

    Examples
    --------
    >>> import numpy as np
    >>> from kinetology.segmentation import derivatives, smooth
    >>> mv, ma = derivative_matrices(50, 30.0, 0.05)
    >>> x = np.sin(np.arange(50) / 5)
    >>> v, a = derivatives(smooth(x, 30.0, 0.05), 30.0)
    >>> bool(np.allclose(mv @ x, v) and np.allclose(ma @ x, a))
    True
    """
    from scipy import sparse

    from kinetology.segmentation import derivatives, smooth

    identity = np.eye(frames)
    velocity, acceleration = derivatives(smooth(identity, frame_rate, smoothing), frame_rate)
    scale = max(1.0, float(np.abs(acceleration).max()))
    out = []
    for m in (velocity, acceleration):
        m = np.where(np.abs(m) > 1e-13 * scale, m, 0.0)  # the Gaussian's far tails
        out.append(sparse.csr_matrix(m))
    return out[0], out[1]


def frame_signs(knots, symbols) -> tuple[np.ndarray, np.ndarray]:
    """Per frame, the effective velocity and acceleration sign its segment's state implies.

    Examples
    --------
    >>> v, a = frame_signs([0, 2, 3, 5], "BGR")
    >>> v.tolist(), a.tolist()
    ([1, 1, 1, -1, -1, -1], [1, 1, -1, -1, -1, -1])
    """
    knots = np.asarray(knots, dtype=int)
    lengths = np.diff(knots)
    lengths[-1] += 1  # the last frame belongs to the last segment
    v = np.repeat([_VELOCITY[k] for k in symbols], lengths)
    a = np.repeat([_ACCELERATION[k] for k in symbols], lengths)
    return v.astype(int), a.astype(int)


def _runs(signs: np.ndarray):
    starts = np.concatenate(([0], np.flatnonzero(signs[1:] != signs[:-1]) + 1))
    return zip(starts, np.append(starts[1:], signs.size))


# a velocity run entered by one of these changes must peak on its first frame: the change
# forces the frame after it back to the old sign (``G -> Y``: the acceleration turns positive
# at once, so the velocity of the next frame exceeds that of the frame before the change)
_FIRST_FRAME_PEAK = {("G", "Y"), ("Y", "G")}


def _peaks(signs, base_signal, entered, rule):
    """The frame of each run of one sign where it is made to leave the dead band."""
    out = []
    for (s, e), first in zip(_runs(signs), entered):
        sigma = signs[s]
        if first:
            out.append(s)
        elif rule == "base":  # where the base already peaks
            out.append(s + int(np.argmax(sigma * base_signal[s:e])))
        elif rule == "early":
            out.append(s + min(2, (e - s) // 3))
        else:
            out.append((s + e - 1) // 2)
    return out


def _conditions(signs, peaks, peak, quiet, eps):
    """Per frame lower bounds on ``sign * signal`` (the LP's rows), one run at a time."""
    lower = np.empty(signs.size)
    for (s, e), p in zip(_runs(signs), peaks):
        lower[s:e] = -_QUIET_MARGIN * quiet
        lower[s:p + 1] = eps
        lower[e - 1] = eps
        lower[p] = _PEAK_MARGIN * peak
    return lower


def _band(signal, floor, relative):
    from kinetology.segmentation import channel_deadbands

    return float(channel_deadbands(np.asarray(signal)[:, None], floor, relative)[0])


def _entered(signs, knots, symbols):
    """Per run of ``signs``, whether the change that starts it is one of _FIRST_FRAME_PEAK."""
    change = {int(k): (symbols[i - 1], symbols[i]) for i, k in enumerate(knots[1:-1], 1)}
    return [change.get(int(s)) in _FIRST_FRAME_PEAK for s, _ in _runs(signs)]


# where runs are made to peak, tried in turn: velocity rule, acceleration rule
_STRATEGIES = (("base", "base"), ("base", "early"), ("middle", "early"))


def shape(base, knots, symbols, frame_rate: float, segmentation: dict, *,
          max_change: float = 30.0) -> Shaped:
    """The raw curve nearest ``base`` (L1) whose segmentation is exactly ``symbols`` on ``knots``.

    Parameters
    ----------
    base : array_like
        The base curve, one value per frame (degrees).
    knots : array_like of int
        First frame of every segment, then the last frame.
    symbols : sequence of str
        The state (``B G R Y``) of each segment; neighbours differ.
    frame_rate : float
        Frames per second.
    segmentation : dict
        The segmentation's parameters (:data:`kinetology.segmentation.DEFAULTS` for
        what is missing).
    max_change : float
        The correction stays within this many degrees of the base at every frame.

    Returns
    -------
    Shaped
        The curve (the base itself when no answer was found) and the solver's status.

    Examples
    --------
    A fall that becomes a rise while still accelerating downwards, in one frame
    (``R -> B``), which no smooth curve makes:

    >>> import numpy as np
    >>> from kinetology.codec import reconstruct
    >>> from kinetology.segmentation import STATES, states
    >>> knots, symbols = [0, 20, 40, 60, 80, 100], "RYRBR"
    >>> base = reconstruct(knots, [STATES.index(k) for k in symbols],
    ...                    [0.0, -2.0, -3.0, -5.0, -2.0, -4.0])
    >>> shaped = shape(base, knots, symbols, 30.0, {})
    >>> codes = states(shaped.curve, 30.0)
    >>> runs = [STATES[c] for i, c in enumerate(codes) if i == 0 or c != codes[i - 1]]
    >>> shaped.status, "".join(runs), shaped.change < 5
    ('solved', 'RYRBR', True)
    """
    try:
        from scipy import sparse
        from scipy.optimize import linprog
    except ImportError:  # a plain install: one line naming the extra, not a traceback
        from psgs.errors import MissingDependency
        raise MissingDependency("generation's correction layer needs scipy: pip install "
                                "'psgs[praxicon]'") from None

    from kinetology.segmentation import DEFAULTS

    p = {**DEFAULTS, **(segmentation or {})}
    base = np.asarray(base, dtype=float)
    knots = np.asarray(knots, dtype=int)
    n = base.size
    mv, ma = derivative_matrices(n, frame_rate, p["smoothing"])
    v_signs, a_signs = frame_signs(knots, symbols)
    v_first = _entered(v_signs, knots, symbols)
    a_first = [False] * len(list(_runs(a_signs)))
    # margins the six decimals of a BVH file (5e-7 degrees a frame) cannot undo
    eps_v = max(1e-3, 4 * 5e-7 * float(abs(mv).sum(axis=1).max()))
    eps_a = max(1e-2, 4 * 5e-7 * float(abs(ma).sum(axis=1).max()))
    floors = {"v": p["velocity_deadband"], "a": p["acceleration_deadband"]}
    relative = p["relative_deadband"]
    # variables: x, t >= |x - base|, u >= |(x - base)[i+1] - (x - base)[i]|;
    # minimise sum t + sum u: the correction small and made of few steps, not spikes
    eye = sparse.identity(n, format="csr")
    step = sparse.diags([-np.ones(n - 1), np.ones(n - 1)], [0, 1], shape=(n - 1, n))
    zero_t = sparse.csr_matrix((n - 1, n))
    zero_u = sparse.csr_matrix((n, n - 1))
    cost = np.concatenate((np.zeros(n), np.ones(n), np.ones(n - 1)))
    a_abs = sparse.vstack([sparse.hstack([eye, -eye, zero_u]),
                           sparse.hstack([-eye, -eye, zero_u]),
                           sparse.hstack([step, zero_t, -sparse.identity(n - 1)]),
                           sparse.hstack([-step, zero_t, -sparse.identity(n - 1)])])
    b_abs = np.concatenate((base, -base, step @ base, -(step @ base)))
    dv, da = sparse.diags(v_signs.astype(float)), sparse.diags(a_signs.astype(float))
    # the channel must still move (a smoothed range under min_range is "still", no kinetemes):
    # the smoothed curve rises by 1.1 min_range from where the base's is lowest to highest
    from kinetology.segmentation import smooth

    smoothed = smooth(np.eye(n), frame_rate, p["smoothing"])
    low, high = int(np.argmin(smoothed @ base)), int(np.argmax(smoothed @ base))
    if high < low:
        low, high = high, low  # the order in time does not matter, only the two frames
    reach = smoothed[high] - smoothed[low]
    if (smoothed @ base)[high] < (smoothed @ base)[low]:
        reach = -reach
    signs = sparse.vstack([-(dv @ mv), -(da @ ma), sparse.csr_matrix(-reach[None, :])],
                          format="csc")
    rows = sparse.vstack([a_abs, sparse.hstack([signs, sparse.csr_matrix((2 * n + 1,
                                                                              2 * n - 1))])],
                         format="csc")
    bounds = [(b - max_change, b + max_change) for b in base] + [(0, None)] * (2 * n - 1)
    status, best = "infeasible", None
    held = False  # whether some round's conditions could hold so far

    def feasible(lower):
        # whether the conditions can hold, asked alone (no objective): refuted several times
        # faster than the whole programme, which on conditions that cannot hold also runs
        # into numerical trouble (seconds where this takes hundredths)
        return linprog(np.zeros(n), A_ub=signs, b_ub=-lower, bounds=bounds[:n],
                       method="highs-ds", options={"maxiter": _ITERATIONS * n})

    for v_rule, a_rule in _STRATEGIES:  # every placement of the peaks; the nearest answer wins
        peaks_v = _peaks(v_signs, mv @ base, v_first, v_rule)
        peaks_a = _peaks(a_signs, ma @ base, a_first, a_rule)
        # the dead band the answer will have is not known before it is found: it is assumed
        # (the base's), peaks are asked above it and frames of the other sign under it, and
        # the answer is kept when its own band is still between the two (else: again, with
        # the answer's band)
        bands = {name: _band(m @ base, floors[name], relative) for name, m in (("v", mv), ("a", ma))}
        asked = set()  # the conditions of this placement's rounds so far
        for _ in range(_ROUNDS):
            lower_v = _conditions(v_signs, peaks_v, bands["v"], bands["v"], eps_v)
            lower_a = _conditions(a_signs, peaks_a, bands["a"], bands["a"], eps_a)
            lower = np.concatenate((lower_v, lower_a, [_REACH * p["min_range"]]))
            if lower.tobytes() in asked:
                # the bands came back to a round's: the same programmes give the same
                # answers, so the rounds left would go round that cycle, none settling
                # (status "band", as after the last round), a linear programme or two a round
                break
            asked.add(lower.tobytes())
            # first whether the conditions can hold, then the nearest such curve, its simplex
            # iterations capped (not its time: the answer must not depend on the machine's
            # load); at the cap the feasible curve of the first step is kept. Once a round's
            # conditions held, the nearest curve is asked at once and the first step only
            # where it has no answer: an answer meets the conditions (they are its rows), so
            # there the first step says yes and only costs time (a fifth of the programmes'),
            # and the later rounds of a curve whose conditions held once hold too, as a rule
            first = None if held else feasible(lower)
            if first is None or first.status == 0:
                answer = linprog(cost, A_ub=rows, b_ub=np.concatenate((b_abs, -lower)),
                                 bounds=bounds, method="highs-ds",
                                 options={"maxiter": _ITERATIONS * n})
                if answer.status != 0 and first is None:
                    first = feasible(lower)
            if first is not None and first.status != 0:
                status = "infeasible" if first.status == 2 else "budget"
                break
            held = True
            x = answer.x[:n] if answer.status == 0 else first.x
            got = {name: _band(m @ x, floors[name], relative) for name, m in (("v", mv), ("a", ma))}
            if all(_QUIET_MARGIN * bands[k] < got[k] < _PEAK_MARGIN * bands[k] for k in got):
                distance = float(np.abs(x - base).sum() + np.abs(np.diff(x - base)).sum())
                if best is None or distance < best[0]:
                    best = (distance, x)
                break
            bands, status = got, "band"
    if best is not None:
        return Shaped(best[1], "solved", float(np.abs(best[1] - base).max()))
    return Shaped(base.copy(), status, 0.0)


def lengthened(lengths, minimum: int, which=None, keep: int = 3) -> np.ndarray | None:
    """Segment lengths (frames) with none of ``which`` under ``minimum``, the total kept.

    The frames a short segment gains are taken from the longest of the others, none
    of which is cut under ``keep`` frames (nor under ``minimum`` when ``which`` is
    every segment), so the channel stays in step with the others. None when the
    total cannot hold that.

    Parameters
    ----------
    lengths : array_like of int
        The segments' lengths in frames.
    minimum : int
        The least length of a segment in ``which``.
    which : array_like of bool, optional
        The segments to lengthen (default: all).
    keep : int
        The least length of a segment that gives frames away.

    Returns
    -------
    numpy.ndarray or None

    Examples
    --------
    >>> lengthened([1, 2, 10, 3], 3).tolist()
    [3, 3, 7, 3]
    >>> lengthened([1, 2], 3) is None
    True
    >>> lengthened([6, 13, 6, 13], 10, which=[True, False, True, False]).tolist()
    [10, 9, 10, 9]
    """
    out = np.asarray(lengths, dtype=int).copy()
    every = which is None or bool(np.all(which))
    which = np.ones(out.size, bool) if which is None else np.asarray(which, bool)
    floor = np.full(out.size, minimum) if every else np.where(which, minimum,
                                                              np.minimum(out, keep))
    target = np.where(which, np.maximum(out, minimum), out)
    need = int((target - out).sum())
    out = target
    while need > 0:  # one frame at a time from the longest donor (the first of equals)
        room = out - floor
        if not every:
            room[which] = -1  # the segments lengthened give nothing away
        donor = int(np.argmax(room))
        if room[donor] <= 0:
            return None
        out[donor] -= 1
        need -= 1
    return out
