"""The checks describe, recognise and parse apply to their arguments before any work.

A wrong type reached numpy or the feature code before (an ``AttributeError`` on a motion that
is None, a ``TypeError`` on a rank given as a string), and some wrong values gave an answer
without a word (a negative hop, a NaN switch cost, a level of 2): each is one
:class:`~praxicon.description.DescriptionError` naming the argument here.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from numbers import Integral, Real
from pathlib import Path

from ._errors import DescriptionError
from ._values import is_flag, shown
from .feature_choice import groups_problem

__all__ = ["DescriptionError", "motion_of", "motions_of", "takes_of", "whole_number",
           "real_number", "flag", "kinds_of", "described"]


def motion_of(source):
    """``source`` itself when it is a :class:`kinetology.Motion`, else the motion read from
    the file it names."""
    import kinetology
    if isinstance(source, kinetology.Motion):
        return source
    if isinstance(source, (str, Path)):
        return kinetology.read(source)
    raise DescriptionError(f"a motion must be a kinetology.Motion or a file's path, not "
                           f"{type(source).__name__}")


def motions_of(motions, name: str = "motions") -> list:
    """Every motion of a sequence (one motion, a string or None is no sequence of them)."""
    import kinetology
    if isinstance(motions, (str, kinetology.Motion)) or not isinstance(motions, Iterable):
        raise DescriptionError(f"{name} must be a sequence of motions, not "
                               f"{type(motions).__name__}")
    return [motion_of(m) for m in motions]


def takes_of(takes) -> dict:
    """``takes`` checked: a mapping of action names (strings) to sequences of motions; a new
    dict of lists (a generator of takes is read once, here)."""
    import kinetology
    if not isinstance(takes, Mapping):
        raise DescriptionError(f"takes must map each action's name to its motions, not "
                               f"{type(takes).__name__}")
    out = {}
    for name, motions in takes.items():
        if not isinstance(name, str):  # a name is written as a JSON key and read back a string
            raise DescriptionError(f"an action's name must be a string, not {name!r}")
        if isinstance(motions, (str, kinetology.Motion)) or not isinstance(motions, Iterable):
            raise DescriptionError(f"the takes of {name!r} must be a sequence of motions, not "
                                   f"{type(motions).__name__}")
        out[name] = list(motions)
        for motion in out[name]:
            if not isinstance(motion, kinetology.Motion):
                raise DescriptionError(f"the takes of {name!r} must be kinetology.Motion "
                                       f"values, not {type(motion).__name__}")
    return out


def whole_number(value, name: str, *, least: int = 0) -> int:
    """``value`` when it is an integer (not a bool) of at least ``least``."""
    if isinstance(value, bool) or not isinstance(value, Integral) or value < least:
        raise DescriptionError(f"{name} must be an integer of at least {least}, not {value!r}")
    return int(value)


def real_number(value, name: str, *, above: float | None = None, least: float | None = None,
                below: float = math.inf, most: float | None = None) -> float:
    """``value`` when it is a number (not a bool or a string) above ``above`` (or at least
    ``least``) and below ``below`` (or at most ``most``); NaN is none of these."""
    fits = not isinstance(value, bool) and isinstance(value, Real) and \
        (value <= most if most is not None else value < below) and \
        (above is None or value > above) and (least is None or value >= least)
    if not fits:
        low = f"above {above:g}" if above is not None else f"at least {least:g}"
        high = f" and at most {most:g}" if most is not None else \
            f" and below {below:g}" if below < math.inf else ""
        finite = "" if high or most is not None else "finite "
        raise DescriptionError(f"{name} must be a {finite}number {low}{high}, not {value!r}")
    return float(value)


def flag(value, name: str) -> bool:
    """``value`` as a bool when it is True or False, numpy's too (a string such as ``"no"`` is
    true)."""
    if not is_flag(value):
        raise DescriptionError(f"{name} must be True or False, not {shown(value)}")
    return bool(value)


def kinds_of(kinds, name: str = "own") -> tuple[str, ...]:
    """Feature kinds: a sequence of strings (one string would be read letter by letter)."""
    given = kinds
    if not isinstance(kinds, str) and isinstance(kinds, Iterable):
        kinds = tuple(kinds)
        if all(isinstance(k, str) for k in kinds):
            return kinds
    raise DescriptionError(f"{name} must be a sequence of feature kinds such as ('drift',), "
                           f"not {given!r}")


def described(takes, rank, level, choose, groups) -> dict:
    """The arguments of :func:`praxicon.description.describe` checked; ``takes`` returned as
    :func:`takes_of` returns them."""
    whole_number(rank, "rank")  # more than the takes allow is cut to what they allow
    real_number(level, "level", above=0.0, below=1.0)
    flag(choose, "choose")
    takes = takes_of(takes)
    problem = None if groups is None else groups_problem(
        {name: len(motions) for name, motions in takes.items()}, groups)
    if problem:
        raise DescriptionError(problem)
    return takes
