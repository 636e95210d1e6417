"""Which members of a group of sections in step move together, so that their repeats are one.

The test of a group of sections in step (:mod:`~psgs.induce.pal.in_step`) weighs its
strings as if they were independent, and two strings that move together are not. Where one
string's symbol determines the other's (:func:`determines`: a renamed copy of it, a joint that
follows another), a repeat of the one is a repeat of the other, and the second repeat is no
evidence: a random string of 60 symbols over 4 letters beside a renamed copy of it was claimed
about 1 time in 5, a chance repeat of the one "confirmed" by the same repeat of the other.

Dependence is read away from the lead's copies (:func:`moves_with`): inside them both strings
repeat by the very event the group is weighed for, so their symbols pair off alike in both
copies whether they depend on each other or not, and a string recorded only around the
copies would look determined by any other. Where the strings meet outside the copies, the
pairing must hold there and be unlikely for an independent string (the chance that every
stretch of one of the lead's symbols meets the same symbol of the other, at most ``level``).

A member that moves with the lead, or that is a renamed copy of a member counted before it
(:func:`renamed_key`, and moving with it as above), stays a member (it moves with the group)
but adds nothing to the group's weight, nor to the number of strings the group was chosen
from: the group's evidence is that of the one string of both, as the pairs' joint string
(:class:`~psgs.induce.pal.paired_sections._JointString`) weighs it.
"""

from __future__ import annotations

import hashlib
import math

import numpy as np

from .motifs import Timed

__all__: list[str] = []  # private: in_step.py is the caller


def _stretches(a: Timed, b: Timed) -> tuple[np.ndarray, np.ndarray, np.ndarray] | None:
    """The stretches in which neither string changes, over the time both cover: each one's
    symbol of ``a``, of ``b`` and its middle (None when they share no time)."""
    lo, hi = max(a.starts[0], b.starts[0]), min(a.ends[-1], b.ends[-1])
    if not hi > lo:
        return None
    if np.array_equal(a.ends, b.ends) and np.array_equal(a.starts, b.starts):
        return a.codes, b.codes, (a.starts + a.ends) / 2  # (the same segments: each one)
    cuts = []
    for string in (a, b):
        for times in (string.starts, string.ends):
            cuts.append(times[(times > lo) & (times < hi)])
    cuts = np.unique(np.concatenate([[lo, hi], *cuts]))
    middles = (cuts[:-1] + cuts[1:]) / 2
    # (segments of one string are contiguous: the one ending first after a middle holds it)
    x = a.codes[np.minimum(np.searchsorted(a.ends, middles, side="right"), len(a.codes) - 1)]
    y = b.codes[np.minimum(np.searchsorted(b.ends, middles, side="right"), len(b.codes) - 1)]
    return x, y, middles


def _is_function(x: np.ndarray, y: np.ndarray) -> bool:
    """Whether every stretch with one symbol ``x`` has one symbol ``y`` beside it."""
    beside = np.zeros(int(x.max()) + 1, dtype=y.dtype)
    beside[x] = y
    return bool(np.array_equal(beside[x], y))


def determines(a: Timed, b: Timed) -> bool:
    """Whether ``a``'s symbol determines ``b``'s at every time both strings cover: each
    symbol of ``a`` is met there beside one symbol of ``b`` only (False when they share
    no time).

    Read on the stretches in which neither changes: a symbol of ``b`` that changes
    inside a segment of ``a`` puts one symbol of ``a`` beside two of ``b``.

    Examples
    --------
    >>> def timed(codes):
    ...     return Timed.from_codes(np.array(codes), np.ones(len(codes)), 0.0)
    >>> a = timed([0, 1, 2, 0, 1, 2, 3])
    >>> determines(a, timed([5, 4, 6, 5, 4, 6, 7])), determines(a, timed([1, 1, 0, 1, 1, 0, 0]))
    (True, True)
    >>> determines(timed([1, 0, 1, 0, 1, 0, 0]), a)  # a finer string: not the other way
    False
    >>> determines(a, Timed.from_codes(np.array([0, 1]), np.array([1.0, 2.0]), 7.0))
    False
    """
    read = _stretches(a, b)
    return read is not None and _is_function(read[0], read[1])


def moves_with(a: Timed, b: Timed, away: np.ndarray, level: float) -> bool:
    """Whether ``a``'s symbol determines ``b``'s beyond chance away from the times ``away``
    (rows of start and end: the lead's copies): :func:`determines` on the stretches outside
    them, and the chance that an independent ``b`` meets each of ``a``'s symbols with one
    symbol of its own as often as it does, at most ``level`` (log10): over ``a``'s symbols,
    ``b``'s match rate (over its segments outside the copies) to the power of the segments of
    ``b`` the symbol meets past the first.

    Examples
    --------
    >>> def timed(codes, start=0.0):
    ...     return Timed.from_codes(np.array(codes), np.ones(len(codes)), start)
    >>> a = timed([0, 1, 2, 0, 1, 2, 3, 1, 0, 2, 1, 3, 0, 2, 3, 1])
    >>> renamed = timed([5, 4, 6, 5, 4, 6, 7, 4, 5, 6, 4, 7, 5, 6, 7, 4])
    >>> moves_with(a, renamed, np.array([[0.0, 3.0], [3.0, 6.0]]), -2.0)
    True
    >>> # the same pairing met only inside the copies: no evidence
    >>> moves_with(a, timed([5, 4, 6, 5, 4, 6]), np.array([[0.0, 3.0], [3.0, 6.0]]), -2.0)
    False
    """
    read = _stretches(a, b)
    if read is None:
        return False
    x, y, middles = read
    away = np.asarray(away, dtype=float).reshape(-1, 2)
    outside = ~((middles[:, None] > away[:, 0]) & (middles[:, None] < away[:, 1])).any(axis=1)
    # b's segment under each stretch: a stretch that shares a segment of b with an earlier
    # stretch of the same symbol of a is no new meeting (b resting in one symbol outside the
    # copies meets every symbol of a with it, by one event)
    segment = np.minimum(np.searchsorted(b.ends, middles, side="right"), len(b.codes) - 1)
    x, y, segment = x[outside], y[outside], segment[outside]
    if not len(x) or not _is_function(x, y):
        return False
    held = np.unique(segment)
    share = np.bincount(b.codes[held]) / len(held)
    q = float(np.sum(share ** 2))  # b's match rate over its segments outside the copies
    if not 0 < q < 1:
        return False
    # each of a's symbols: the segments of b it meets past the first
    repeats = len(np.unique(np.column_stack((x, segment)), axis=0)) - len(np.unique(x))
    return repeats * math.log10(q) <= level


def renamed_key(string: Timed) -> bytes:
    """A key equal for two strings when one is the other renamed: the same times, and
    its symbols mapped one-to-one (each code replaced by the rank of its first place;
    the key is a 16-byte digest of those and the times, not a copy of the string).

    Examples
    --------
    >>> def timed(codes):
    ...     return Timed.from_codes(np.array(codes), np.ones(len(codes)), 0.0)
    >>> renamed_key(timed([3, 1, 3, 2])) == renamed_key(timed([0, 2, 0, 1]))
    True
    >>> renamed_key(timed([3, 1, 3, 2])) == renamed_key(timed([0, 2, 1, 0]))
    False
    """
    _, first, inverse = np.unique(string.codes, return_index=True, return_inverse=True)
    rank = np.argsort(np.argsort(first))
    digest = hashlib.blake2b(digest_size=16)
    for part in (string.starts, string.ends, rank[inverse.ravel()].astype(np.int64)):
        digest.update(np.ascontiguousarray(part).tobytes())
    return digest.digest()


class Alike:
    """Which members of a group add to its weight, at the chance ``level`` (log10): the
    strings' :func:`renamed_key` found once per string, their dependence (:func:`moves_with`,
    one way or the other, away from the lead's copies) each time it is asked (a pair is asked
    by each of its two strings leading, at its own copies: kept, the answers of a group of N
    strings would be N^2)."""

    def __init__(self, strings: list[Timed], level: float) -> None:
        self.strings = strings
        self.level = level
        self.keys: dict[int, bytes] = {}

    def dependent(self, i: int, j: int, away: np.ndarray) -> bool:
        """Whether string ``i``'s symbol determines ``j``'s, or ``j``'s ``i``'s, beyond
        chance away from the times ``away``."""
        a, b = self.strings[i], self.strings[j]
        return moves_with(a, b, away, self.level) or moves_with(b, a, away, self.level)

    def key(self, i: int) -> bytes:
        """:func:`renamed_key` of string ``i``."""
        if i not in self.keys:
            self.keys[i] = renamed_key(self.strings[i])
        return self.keys[i]

    def counted(self, lead: int, members: list[int], away: np.ndarray) -> list[int]:
        """The ``members`` (in their order) whose weight adds to a group led by ``lead`` at
        the copies ``away``: each that is not :meth:`dependent` with the lead and not a
        renamed copy of a member counted before it that is dependent with it.

        Examples
        --------
        >>> def timed(codes):
        ...     return Timed.from_codes(np.array(codes), np.ones(len(codes)), 0.0)
        >>> base = [0, 1, 2, 0, 1, 3, 2, 1, 0, 3, 1, 2, 3, 0, 2]
        >>> other = [2, 0, 1, 3, 1, 0, 2, 0, 3, 1, 2, 0, 1, 3, 2]
        >>> strings = [timed(base), timed([(c + 1) % 4 for c in base]), timed(other),
        ...            timed([(c + 2) % 4 for c in other])]
        >>> copies = np.array([[0.0, 2.0], [3.0, 5.0]])
        >>> Alike(strings, -2.0).counted(0, [1, 2, 3], copies)  # 1 renames 0; 3 renames 2
        [2]
        """
        out, seen = [], {}
        for j in members:
            if self.dependent(lead, j, away):
                continue
            first = seen.get(self.key(j))
            if first is not None and self.dependent(first, j, away):
                continue
            out.append(j)
            seen.setdefault(self.key(j), j)
        return out
