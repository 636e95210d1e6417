"""How copies pair with a lead's copies in time.

Two spans **pair** when they share half of the time the two cover together
(:func:`spans_pair`); copies played in step with a lead's keep one shift from
it (:func:`keeps_shift`); a string is read at a lead's copies through the
segments under them (:func:`lead_segments`).
"""

from __future__ import annotations

import numpy as np

from .motifs import Timed

__all__: list[str] = []  # private: in_step.py, shift_runs.py and choice.py are the callers


def lead_segments(string: Timed, lead: np.ndarray) -> tuple[np.ndarray, np.ndarray] | None:
    """The indices of ``string``'s segments that overlap each of the lead's two copies
    (``lead``: their ``[[start, end], [start, end]]`` times), or ``None`` when a copy
    overlaps none.

    Examples
    --------
    >>> string = Timed.from_codes(np.array([5, 1, 2, 6]), np.ones(4), 0.0)
    >>> [s.tolist() for s in lead_segments(string, np.array([[0.5, 2.0], [3.0, 4.0]]))]
    [[0, 1], [3]]
    """
    (a1, b1), (a2, b2) = lead.tolist()
    first = np.flatnonzero((string.starts < b1) & (string.ends > a1))
    second = np.flatnonzero((string.starts < b2) & (string.ends > a2))
    if len(first) == 0 or len(second) == 0:
        return None
    return first, second


def spans_pair(copy, lead) -> bool:
    """Whether two time spans share half of the time the two cover together."""
    (a, b), (c, d) = copy, lead
    shared, union = min(b, d) - max(a, c), max(b, d) - min(a, c)
    return shared > 0 and 2 * shared >= union


def keeps_shift(copies: np.ndarray, others: np.ndarray) -> bool:
    """Whether ``copies`` pair off with two or more of ``others`` (each pair sharing half of
    the time the two cover together) and lie off them by one amount: the start's offset
    and the end's, over the pairs, each within half the median of the pairs' shorter copy.

    Copies played in step with others keep their shift between copies; a chance repeat
    inside long copies pairs with them too, but at a shift of its own.

    Examples
    --------
    >>> section = np.array([[9.0, 25.0], [27.0, 43.0]])
    >>> keeps_shift(np.array([[10.0, 25.0], [28.0, 43.0]]), section)
    True
    >>> keeps_shift(np.array([[9.0, 17.0], [34.0, 42.0]]), section)  # shift 25, not 18
    False
    """
    offsets, lengths = [], []
    for a, b in copies.tolist():
        for c, d in others.tolist():
            if spans_pair((a, b), (c, d)):
                offsets.append((a - c, b - d))
                lengths.append(min(b - a, d - c))
                break
    if len(offsets) < 2:
        return False
    spread = np.ptp(np.asarray(offsets), axis=0)
    return bool(np.all(spread <= np.median(lengths) / 2))


def _pairs_with(begins: np.ndarray, ends: np.ndarray, lo: float, hi: float) -> np.ndarray:
    """:func:`spans_pair` of every span ``(begins[k], ends[k])``
    with ``(lo, hi)``."""
    shared = np.minimum(ends, hi) - np.maximum(begins, lo)
    union = np.maximum(ends, hi) - np.minimum(begins, lo)
    return (shared > 0) & (2 * shared >= union)
