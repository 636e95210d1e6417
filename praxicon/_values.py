"""Small tests of argument values the checks of praxicon share (no praxicon imports here).

A whole number is any integer, numpy's too (``np.int64(3)`` worked wherever ``3`` did before
the checks), never a bool; a flag is a bool or a numpy bool. ``shown`` (kinetology's) keeps a
message to a line when the value given is a long sequence.
"""

from __future__ import annotations

from collections.abc import Mapping
from numbers import Integral

import numpy as np

from kinetology.motion import shown
from psgs.errors import ValidationError


def is_count(value, least: int = 1) -> bool:
    """True for an integer (a numpy one too, not a bool) of at least ``least``."""
    return isinstance(value, Integral) and not isinstance(value, (bool, np.bool_)) \
        and value >= least


def check_count(value, name: str) -> None:
    """A :class:`ValidationError` unless ``value`` is a whole number of at least 1
    (:func:`is_count`), naming ``name`` and the value shown short."""
    if not is_count(value):
        raise ValidationError(f"{name} must be a whole number of at least 1, not {shown(value)}")


def is_flag(value) -> bool:
    """True for True or False, numpy's too."""
    return isinstance(value, (bool, np.bool_))


def not_all(given, items, kind) -> str:
    """The end of a message refusing ``given`` (read into ``items``, None when it is no
    iterable) for holding something other than ``kind`` values: that value, shown short."""
    if items is None:
        return f"not {shown(given)}"
    return f"not one holding {shown(next(i for i in items if not isinstance(i, kind)))}"


def _pairs_of(value, name: str) -> tuple:
    # a list of pairs worked before the check, a dict too (sorted here, as Settings.make does)
    items = list(value.items()) if isinstance(value, Mapping) else value
    if isinstance(items, (list, tuple)):
        pairs = tuple(tuple(p) if isinstance(p, (list, tuple)) else p for p in items)
        if all(isinstance(p, tuple) and len(p) == 2 and isinstance(p[0], str) for p in pairs):
            return tuple(sorted(pairs, key=lambda p: p[0])) if isinstance(value, Mapping) \
                else pairs
    raise ValidationError(f"settings need {name} as (name, value) pairs (Settings.make takes "
                          f"dicts), not {shown(value)}")


def settings_fields(inducer, params, segmentation, min_performances) -> tuple:
    """A :class:`~praxicon.records.Settings`' params, segmentation and min_performances as it
    keeps them (tuples of pairs, a plain int), or a ValidationError naming the field."""
    if not isinstance(inducer, str):
        raise ValidationError(f"settings need an inducer's name (a string), not {shown(inducer)}")
    if not is_count(min_performances):  # a string or a bool is no count
        raise ValidationError(f"settings need min_performances, a whole number of at least 1, "
                              f"not {shown(min_performances)}")
    return (_pairs_of(params, "params"), _pairs_of(segmentation, "segmentation"),
            int(min_performances))
