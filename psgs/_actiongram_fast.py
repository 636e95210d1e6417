"""Building an actiongram from integer codes and arrays (:meth:`psgs.Actiongram.from_codes`).

A segmentation of real motion makes hundreds of thousands of symbols; building them through
:meth:`~psgs.Actiongram.from_strings` checks every symbol, duration and displacement one
Python object at a time. Here the checks are array operations (codes in range, no equal
neighbours, durations positive and finite, start times that advance, finite displacements);
the few names, actuators and skeleton edges take the public checks. Input that passes is
built directly into the same tuples the public constructor makes; input that does not (or
that needs merging) goes through :meth:`~psgs.Actiongram.from_strings`, so every error, and
every merged result, is exactly the public constructor's.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ._actiongram_checks import _bad_name, _bad_symbol, _shown
from ._actiongram_extras import default_actuator, normalise_actuators, normalise_skeleton
from .errors import FormatError

__all__: list[str] = []  # private: Actiongram.from_codes is the interface


def _plain_rows(rows: Mapping, kind: str) -> dict[str, np.ndarray] | None:
    """Each row as a 1-D float64 array of finite values, or None when one is not that (an
    array of another kind, a list holding anything but Python ints and floats)."""
    out = {}
    for name, row in rows.items():
        if not isinstance(row, np.ndarray):  # a list: Python numbers only (no bool)
            row = tuple(row)
            if not set(map(type, row)) <= {int, float}:
                return None
        try:
            array = np.asarray(row)
        except Exception:  # noqa: BLE001 - any oddity: the public path says what is wrong
            return None
        if array.ndim != 1 or array.dtype.kind not in kind or (array.size and not
                                                                np.isfinite(array).all()):
            return None
        out[name] = array.astype(float, copy=False)
    return out


def _lists(rows: Mapping | None) -> Mapping | None:
    if not rows:
        return rows
    return {n: r.tolist() if isinstance(r, np.ndarray) else r for n, r in rows.items()}


def build(cls, codes: Mapping, alphabet: Sequence[str], durations: Mapping | None,
          displacements: Mapping | None, actuators: Mapping | None, skeleton: Mapping | None):
    """An :class:`~psgs.Actiongram` equal to ``from_strings`` of the decoded codes."""
    alphabet = tuple(alphabet)
    for sym in alphabet:
        problem = _bad_symbol(sym)
        if problem:
            raise FormatError(f"alphabet: {problem}")
    rows = {}
    for name, row in codes.items():
        row = np.asarray(row)
        if row.ndim != 1 or (row.size and row.dtype.kind not in "iu"):
            raise ValueError(f"codes of {_shown(name)} must be a 1-D array of integers")
        if row.size and (row.min() < 0 or row.max() >= len(alphabet)):
            raise ValueError(f"codes of {_shown(name)} must index the alphabet "
                             f"(0 to {len(alphabet) - 1})")
        rows[name] = row.astype(np.intp, copy=False)
    lookup = np.array(alphabet + ("",), dtype=object)  # "" keeps it 1-D of str
    distinct = len(set(alphabet)) == len(alphabet)  # else equal codes are not equal symbols

    def public():  # arrays as lists: the errors show numbers as Python writes them
        strings = {n: tuple(lookup[r]) for n, r in rows.items()}
        return cls.from_strings(strings, _lists(durations), displacements=_lists(displacements),
                                actuators=actuators, skeleton=skeleton)

    durations = {} if durations is None else durations
    displacements = {} if displacements is None else displacements
    spans = _plain_rows(durations, "iuf")
    moves = _plain_rows(displacements, "iuf")
    if not distinct or spans is None or moves is None or not set(spans) <= set(rows) \
            or not set(moves) <= set(rows) or not set(actuators or {}) <= set(rows):
        return public()
    names = tuple(rows)
    seen = set()
    for name in names:
        if _bad_name(name) or name in seen:
            return public()
        seen.add(name)
    symbol_rows, duration_rows, move_rows = [], [], []
    for name in names:
        row = rows[name]
        span = spans.get(name)
        if span is None:
            span = np.ones(row.size)
        move = moves.get(name)
        if span.size != row.size or (move is not None and move.size != row.size) or \
                (row.size > 1 and not (row[1:] != row[:-1]).all()) or \
                (row.size and not span.min() > 0):
            return public()  # an error, or equal neighbours to merge: the public rules
        ends = np.cumsum(span)  # the start times, added one by one as the checks add them
        if row.size and (not np.isfinite(ends[-1]) or not (ends[1:] != ends[:-1]).all()
                         or ends[0] == 0.0):
            return public()
        symbol_rows.append(tuple(lookup[row]))
        duration_rows.append(tuple(span.tolist()))
        move_rows.append(tuple(move.tolist()) if move is not None and row.size else None)
    value = object.__new__(cls)
    setattr_ = object.__setattr__
    setattr_(value, "names", names)
    setattr_(value, "symbols", tuple(symbol_rows))
    setattr_(value, "segment_durations", tuple(duration_rows))
    setattr_(value, "origins", (0.0,) * len(names))
    setattr_(value, "segment_displacements", tuple(move_rows))
    owner = actuators or {}
    setattr_(value, "string_actuators",
             tuple(owner[n] if n in owner else default_actuator(n) for n in names))
    setattr_(value, "skeleton_edges", tuple((skeleton or {}).items()))
    normalise_actuators(value, names)
    normalise_skeleton(value)
    return value
