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

from collections.abc import Iterable, Mapping, Sequence

import numpy as np

from ..errors import ValidationError
from ._checks import _bad_name, _bad_symbol, _refused, _shown, _tuple_of
from ._extras import default_actuator, normalise_actuators, normalise_skeleton

__all__: list[str] = []  # private: Actiongram.from_codes is the interface


def _plain_rows(rows: Mapping, kind: str) -> dict[str, np.ndarray] | None:
    """Each row as a 1-D float64 array, or None when one is not that (an array of another
    kind, a list holding anything but Python ints and floats). Finiteness is checked later,
    on all rows at once."""
    out = {}
    for name, row in rows.items():
        if not isinstance(row, np.ndarray):  # a list: Python numbers only (no bool)
            row = tuple(row) if isinstance(row, Iterable) else None
            if row is None or not set(map(type, row)) <= {int, float}:
                return None
        try:
            array = np.asarray(row)
        except Exception:  # noqa: BLE001 - any oddity: the public path says what is wrong
            return None
        if array.ndim != 1 or (array.size and array.dtype.kind not in kind):
            return None
        out[name] = array.astype(float, copy=False)
    return out


def _pieces(values: list, ends: np.ndarray) -> list[tuple]:
    """``values`` cut into tuples ending at ``ends``."""
    out, start = [], 0
    for end in ends.tolist():
        out.append(tuple(values[start:end]))
        start = end
    return out


def _lists(rows: Mapping | None) -> Mapping | None:
    if not rows:
        return rows
    return {n: r.tolist() if isinstance(r, np.ndarray) else r for n, r in rows.items()}


def build(cls, codes: Mapping, alphabet: Sequence[str], durations: Mapping | None,
          displacements: Mapping | None, actuators: Mapping | None, skeleton: Mapping | None):
    """An :class:`~psgs.Actiongram` equal to ``from_strings`` of the decoded codes."""
    for what, given in (("codes", codes), ("durations", durations),
                        ("displacements", displacements), ("actuators", actuators),
                        ("skeleton", skeleton)):
        if not isinstance(given, Mapping) and (what == "codes" or given is not None):
            raise ValidationError(f"{what} must map each string's name to its values, "
                                  f"not be a {type(given).__name__}")
    alphabet = _tuple_of(alphabet, "alphabet")
    for sym in alphabet:
        problem = _bad_symbol(sym)
        if problem:
            raise _refused(f"alphabet: {problem}")
    rows = {}
    for name, row in codes.items():
        row = np.asarray(row)
        if row.ndim != 1 or (row.size and row.dtype.kind not in "iu"):
            raise ValidationError(f"codes of {_shown(name)} must be a 1-D array of integers")
        if row.size and (row.min() < 0 or row.max() >= len(alphabet)):
            raise ValidationError(f"codes of {_shown(name)} must index the alphabet "
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
    if len(set(names)) != len(names) or any(_bad_name(n) for n in names):
        return public()
    sizes = [rows[n].size for n in names]
    if any(spans[n].size != rows[n].size for n in spans) or \
            any(moves[n].size != rows[n].size for n in moves):
        return public()
    ends = np.cumsum(sizes, dtype=np.intp)
    starts = ends - np.asarray(sizes, dtype=np.intp)
    flat = np.concatenate([rows[n] for n in names]) if names else np.zeros(0, np.intp)
    span = np.concatenate([spans[n] if n in spans else np.ones(rows[n].size) for n in names]) \
        if names else np.zeros(0)
    same = flat[1:] == flat[:-1]
    same[ends[:-1][(ends[:-1] > 0) & (ends[:-1] < flat.size)] - 1] = False  # across strings
    if same.any() or (span.size and not (span.min() > 0 and np.isfinite(span).all())):
        return public()  # an error, or equal neighbours to merge: the public rules
    # every start time advances (T + D != T): a duration above 2^-50 of its string's total
    # cannot vanish; strings with a smaller one (or a total near overflow) take the checks
    occupied = np.flatnonzero(np.asarray(sizes) > 0)
    if occupied.size:
        totals = np.add.reduceat(span, starts[occupied])
        if not (totals < 1e300).all() or not (span > np.repeat(totals, np.asarray(sizes)[
                occupied]) * 2.0 ** -50).all():
            return public()
    move_rows: list = [None] * len(names)
    if moves:
        present = [i for i, n in enumerate(names) if n in moves and sizes[i]]
        values = np.concatenate([moves[names[i]] for i in present]) if present else np.zeros(0)
        if not np.isfinite(values).all():
            return public()
        for i, piece in zip(present, _pieces(values.tolist(),
                                             np.cumsum([sizes[i] for i in present]))):
            move_rows[i] = piece
    value = object.__new__(cls)
    setattr_ = object.__setattr__
    setattr_(value, "names", names)
    setattr_(value, "symbols", tuple(_pieces(lookup[flat].tolist(), ends)))
    setattr_(value, "segment_durations", tuple(_pieces(span.tolist(), ends)))
    setattr_(value, "origins", (0.0,) * len(names))
    setattr_(value, "segment_displacements", tuple(move_rows))
    owner = actuators or {}
    setattr_(value, "string_actuators",
             tuple(owner[n] if n in owner else default_actuator(n) for n in names))
    setattr_(value, "skeleton_edges", tuple((skeleton or {}).items()))
    setattr_(value, "keep_repeats", False)  # equal neighbours took the public path above
    normalise_actuators(value, names)
    normalise_skeleton(value)
    return value
