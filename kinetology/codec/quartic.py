"""The per-segment quartic of the codec: decoding knots to a curve, and fitting knots to one.

Segment ``i`` of a channel runs from knot ``i`` to knot ``i + 1``; on it the
angle is a polynomial of degree 4 in ``s`` (0 to 1 across the segment) with

* the knot values at both ends (2 equations);
* at each border with a neighbour segment, the conditions its state change
  implies: the sign of the velocity changes -> ``θ' = 0`` there; the sign of
  the acceleration changes -> ``θ'' = 0`` there (the paper's "two equations
  for the particular sequence of kinetemes"; a border where both signs change
  gives both, and when that over-determines the quartic the acceleration
  conditions are dropped);
* the last free coefficient(s) chosen to minimise the jerk ``∫ θ'''² ds``
  (with a 1e-6 weight on ``∫ θ''² ds`` so the answer is unique when fewer
  conditions apply).

At the two ends of a recording there is no neighbour: the first segment is
treated as entered from its predecessor in the cycle ``B G R Y B`` and the
last as left towards its successor (``Y -> B`` changes the sign of the
velocity, so a first segment in state ``B`` starts with ``θ' = 0``).

The decoded curve is linear in the knot values, so the best knot values for a
signal are a least-squares problem with a tridiagonal matrix
(:func:`fit_knots`).
"""

from __future__ import annotations

from fractions import Fraction
from functools import lru_cache
from itertools import product

import numpy as np

from psgs.errors import ValidationError

from ..motion import is_whole, real_array, shown

#: The longest curve :func:`reconstruct` makes unless told otherwise (``max_frames=``): 2^26
#: frames, 512 MiB of floats, six days at 120 frames a second. Knots a frame of 10^12 asked
#: for that many values and ran out of memory instead of saying why.
MAX_FRAMES = 1 << 26

__all__ = ["basis", "reconstruct", "fit_knots"]


def _gram(derivative: int) -> np.ndarray:
    """``G[i, j] = ∫_0^1 (d^k s^i)(d^k s^j) ds`` for monomials s^0..s^4."""
    gram = np.zeros((5, 5))
    for i, j in product(range(5), repeat=2):
        if i >= derivative and j >= derivative:
            ci = np.prod(np.arange(i - derivative + 1, i + 1))
            cj = np.prod(np.arange(j - derivative + 1, j + 1))
            power = i + j - 2 * derivative
            gram[i, j] = ci * cj / (power + 1)
    return gram


def _row(at: float, derivative: int) -> np.ndarray:
    row = np.zeros(5)
    for i in range(derivative, 5):
        row[i] = np.prod(np.arange(i - derivative + 1, i + 1)) * at ** (i - derivative)
    return row


def _solve_exactly(matrix: np.ndarray, rhs: np.ndarray) -> np.ndarray:
    """``matrix^-1 rhs`` in exact rationals (the floats' own values), each result rounded once.

    LAPACK's answer depends in its last bits on the CPU's kernels; these coefficients shape
    every decoded value, so they are computed the same way everywhere. The system is small
    (at most 10 x 10) and nonsingular (the two knot values fix the constant and linear
    parts the jerk does not, and the border conditions are independent). ``rhs`` may hold
    several right-hand sides as columns, solved in one elimination: the row operations depend
    on ``matrix`` alone, so each column's answer is the one it has solved on its own.
    """
    rhs = np.asarray(rhs)
    columns = rhs.reshape(len(rhs), -1)
    n, k = len(columns), columns.shape[1]
    a = [[Fraction(float(x)) for x in row] + [Fraction(float(b)) for b in right]
         for row, right in zip(matrix, columns)]
    for col in range(n):
        pivot = next(r for r in range(col, n) if a[r][col] != 0)
        a[col], a[pivot] = a[pivot], a[col]
        for r in range(n):
            if r != col and a[r][col] != 0:
                factor = a[r][col] / a[col][col]
                a[r] = [x - factor * y for x, y in zip(a[r], a[col])]
    solved = np.array([[float(a[r][n + j] / a[r][r]) for j in range(k)] for r in range(n)])
    return solved.reshape(rhs.shape)


@lru_cache(maxsize=None)
def basis(left_velocity: bool, left_acceleration: bool, right_velocity: bool,
          right_acceleration: bool) -> tuple[np.ndarray, np.ndarray]:
    """Coefficients ``(U, W)`` of ``θ(s) = y0 U(s) + y1 W(s)`` for one border pattern.

    Parameters
    ----------
    left_velocity, left_acceleration, right_velocity, right_acceleration : bool
        Which derivatives vanish at the left (s=0) and right (s=1) border.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        Coefficients of ``s^0 .. s^4`` (read-only: cached and shared).

    Examples
    --------
    Velocity zero at both ends: the least-jerk quartic from 0 to 1 is the
    cubic ``3 s² - 2 s³``:

    >>> u, w = basis(True, False, True, False)
    >>> [round(float(c), 6) + 0.0 for c in w]
    [0.0, 0.0, 3.0, -2.0, 0.0]
    """
    rows, kinds = [_row(0, 0), _row(1, 0)], []
    wanted = [(left_velocity, 0, 1), (right_velocity, 1, 1), (left_acceleration, 0, 2),
              (right_acceleration, 1, 2)]
    for flag, at, derivative in wanted:
        if flag and len(rows) < 5:
            rows.append(_row(at, derivative))
            kinds.append(derivative)
    constraints = np.array(rows)
    cost = _gram(3) + 1e-6 * _gram(2)
    m = len(rows)
    kkt = np.zeros((5 + m, 5 + m))
    kkt[:5, :5] = 2 * cost
    kkt[:5, 5:] = constraints.T
    kkt[5:, :5] = constraints
    # the knot values y0 = 1, y1 = 0 (U) and y0 = 0, y1 = 1 (W), in one elimination
    rhs = np.zeros((5 + m, 2))
    rhs[5, 0] = rhs[6, 1] = 1.0
    solved = _solve_exactly(kkt, rhs)[:5]
    out = []
    for column in solved.T:
        coefficients = column.copy()
        coefficients.setflags(write=False)  # cached: shared by every caller
        out.append(coefficients)
    return out[0], out[1]


def _border_flags(codes: np.ndarray) -> np.ndarray:
    """Per segment, its flag pattern index 0..15 (bits: lv, la, rv, ra)."""
    falling = codes >> 1
    braking = (codes == 1) | (codes == 2)  # acceleration negative in G and R
    velocity_flip = falling[1:] != falling[:-1]
    acceleration_flip = braking[1:] != braking[:-1]
    n = codes.size
    lv = np.zeros(n, bool)
    la = np.zeros(n, bool)
    rv = np.zeros(n, bool)
    ra = np.zeros(n, bool)
    lv[1:], la[1:] = velocity_flip, acceleration_flip
    rv[:-1], ra[:-1] = velocity_flip, acceleration_flip
    if n:
        # the recording's ends: as if the cycle B -> G -> R -> Y -> B went on, so the
        # first segment enters as its predecessor leaves, the last leaves towards its
        # successor (B->G and R->Y flip the acceleration, G->R and Y->B the velocity)
        first, last = int(codes[0]), int(codes[-1])
        lv[0], la[0] = first in (0, 2), first in (1, 3)
        rv[-1], ra[-1] = last in (1, 3), last in (0, 2)
    return lv * 8 + la * 4 + rv * 2 + ra


@lru_cache(maxsize=1)
def _tables() -> tuple[np.ndarray, np.ndarray]:
    """``(U, W)``: :func:`basis` of every flag pattern 0..15 of :func:`_border_flags`, one row
    each. Made on first use, not at import: the exact solves take tens of milliseconds, which
    every command importing the codec (``--help`` too) paid before."""
    patterns = [basis(*(bool(k >> b & 1) for b in (3, 2, 1, 0))) for k in range(16)]
    tables = np.array([u for u, _ in patterns]), np.array([w for _, w in patterns])
    for table in tables:
        table.setflags(write=False)  # cached: shared by every caller
    return tables


def _design(knots: np.ndarray, codes: np.ndarray):
    """For every frame: its segment, and the weights of its left and right knot.

    A weight is ``sum_k c_k s^k`` over the coefficients ``c`` of its segment's row of the
    tables, in one fixed order of elementwise operations (powers by multiplication, terms
    added from ``k = 0``: ``np.einsum`` and ``**`` may add or round differently on another
    CPU). Each coefficient is repeated over its segment's frames rather than each frame's row
    gathered (two frames x 5 arrays read a column at a time were most of a long curve's
    decoding time)."""
    lengths = np.diff(knots)
    frames = knots[-1] + 1
    counts = np.append(lengths, 1)  # the last frame ends the last segment
    seg = np.repeat(np.append(np.arange(lengths.size), lengths.size - 1), counts)
    offset = np.arange(frames) - knots[seg]
    s = offset / lengths[seg]
    pattern = _border_flags(codes)
    table_u, table_w = _tables()
    per_segment = np.concatenate((table_u[pattern], table_w[pattern]), axis=1)
    # row k (u) and 5 + k (w): the coefficients of s^k, a row of its own to repeat
    rows = np.concatenate((per_segment, per_segment[-1:])).T.copy()
    u, w = np.repeat(rows[0], counts), np.repeat(rows[5], counts)
    power = s  # s^1: what 1.0 * s is, exactly
    for k in range(1, 5):
        if k > 1:
            power = power * s
        for out, row in ((u, rows[k]), (w, rows[5 + k])):
            term = np.repeat(row, counts)
            term *= power
            out += term
    return seg, u, w


def reconstruct(knots: np.ndarray, codes: np.ndarray, values: np.ndarray, *,
                max_frames: int | None = MAX_FRAMES) -> np.ndarray:
    """The decoded curve of one channel from its knots, segment states and knot values.

    Parameters
    ----------
    knots : array_like of int
        Knot frames: 0, the first frame of every later segment, the last frame.
    codes : array_like of int
        State code (0..3 for ``B G R Y``) of each of the ``len(knots) - 1`` segments.
    values : array_like of float
        The angle at every knot.
    max_frames : int or None, optional
        The most frames the curve may have (default :data:`MAX_FRAMES`; None: no bound, the
        caller has bounded the knots).

    Returns
    -------
    numpy.ndarray
        One value per frame (``knots[-1] + 1`` of them).

    Raises
    ------
    ValueError
        (ValidationError) Knots that are not whole frames rising from 0, codes that are not
        one state 0..3 per segment, values that are not one finite number per knot, a last
        knot at or past ``max_frames``.

    Examples
    --------
    A rise (``B``, speeding up) then a slowing rise (``G``) from 0 to 10 degrees:

    >>> curve = reconstruct([0, 5, 10], [0, 1], [0.0, 4.0, 10.0])
    >>> curve.shape, [round(float(curve[f]), 9) for f in (0, 5, 10)]
    ((11,), [0.0, 4.0, 10.0])
    """
    knots, codes, values = _checked(knots, codes, values)
    if max_frames is not None:
        if not is_whole(max_frames) or max_frames < 1:
            raise ValidationError(f"max_frames must be a whole number ≥ 1 or None, not "
                                  f"{shown(max_frames)}")
        if knots[-1] >= max_frames:
            raise ValidationError(f"the last knot at frame {int(knots[-1])} asks for a curve of "
                                  f"{int(knots[-1]) + 1} frames, more than max_frames="
                                  f"{max_frames} (pass a larger max_frames, or None)")
    if knots.size == 1:
        return np.full(1, float(values[0]))
    seg, u, w = _design(knots, codes)
    return values[seg] * u + values[seg + 1] * w


def _checked(knots, codes, values):
    """The three arrays of :func:`reconstruct`, or one ValidationError: knots that are not
    whole frames rising from 0, codes that are not one state (0..3) per segment or knot values
    that are not one finite number per knot gave numpy's errors, a curve of NaN, or a curve
    read from the wrong rows without a word."""
    knots, codes = _checked_segments(knots, codes)
    values = real_array(values, "values")
    if values.shape != knots.shape or not np.isfinite(values).all():
        raise ValidationError(f"values must be one finite number for each of the {knots.size} "
                              f"knots")
    return knots, codes, values


def _checked_segments(knots, codes):
    """Knots and codes as arrays, or the ValidationError of :func:`_checked`."""
    knots, codes = np.asarray(knots), np.asarray(codes)
    if knots.ndim != 1 or not knots.size or knots.dtype.kind not in "iu" or knots[0] != 0 \
            or np.any(np.diff(knots) < 1):
        raise ValidationError("knots must be whole frames rising from 0, not "
                              f"{np.array2string(knots, threshold=8)}")
    if codes.shape != (knots.size - 1,) or (codes.size and (
            codes.dtype.kind not in "iu" or codes.min() < 0 or codes.max() > 3)):
        raise ValidationError(f"codes must be one state 0..3 for each of the {knots.size - 1} "
                              f"segments, not {np.array2string(codes, threshold=8)}")
    return knots, codes


def fit_knots(knots, codes, signal) -> np.ndarray:
    """Knot values minimising the squared error of :func:`reconstruct` against ``signal``.

    A tridiagonal solve (each frame depends on the two knots of its segment).

    Raises
    ------
    ValueError
        (ValidationError) Knots that are not whole frames rising from 0, codes that are not
        one state 0..3 per segment, a signal that is not one finite number per frame
        (``knots[-1] + 1`` of them).

    Examples
    --------
    >>> import numpy as np
    >>> signal = 10 * np.sin(np.linspace(0, np.pi, 21))   # one hump: rise, then fall
    >>> values = fit_knots(np.array([0, 10, 20]), np.array([1, 2]), signal)
    >>> bool(np.abs(reconstruct([0, 10, 20], [1, 2], values) - signal).max() < 0.5)
    True
    """
    knots, codes = _checked_segments(knots, codes)
    signal = real_array(signal, "signal")
    # more samples than frames were read from the first rows without a word, fewer were
    # numpy's broadcast error
    if signal.shape != (int(knots[-1]) + 1,) or not np.isfinite(signal).all():
        raise ValidationError(f"signal must be one finite number for each of the "
                              f"{int(knots[-1]) + 1} frames the knots span")
    n = knots.size
    if n == 1:
        return np.array([signal[0]], dtype=float)
    seg, u, w = _design(knots, codes)
    diag = np.bincount(seg, u * u, n) + np.bincount(seg + 1, w * w, n)
    off = np.bincount(seg, u * w, n - 1)[: n - 1]
    rhs = np.bincount(seg, u * signal, n) + np.bincount(seg + 1, w * signal, n)
    # Thomas algorithm (the matrix is symmetric positive definite: every knot has
    # a frame where it alone sets the value)
    c_prev, d_prev = 0.0, 0.0
    diag_l, off_l, rhs_l = diag.tolist(), off.tolist() + [0.0], rhs.tolist()
    cl, dl = [0.0] * n, [0.0] * n
    for i in range(n):
        lower = off_l[i - 1] if i else 0.0
        denominator = diag_l[i] - lower * c_prev
        c_prev = off_l[i] / denominator
        d_prev = (rhs_l[i] - lower * d_prev) / denominator
        cl[i], dl[i] = c_prev, d_prev
    x = [0.0] * n
    x[-1] = dl[-1]
    for i in range(n - 2, -1, -1):
        x[i] = dl[i] - cl[i] * x[i + 1]
    return np.array(x)
