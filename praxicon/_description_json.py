"""Descriptions read from their JSON values, every field checked before anything uses it.

:meth:`~praxicon.description.Descriptions.from_dict` (and the action's and the spread's) read
through :func:`action_fields` and :func:`spread_fields`, so that a damaged
``descriptions.json`` is one :class:`~praxicon.description.DescriptionError` naming the field,
not a reshape error deep in the scores or a NaN probability printed as an answer. What is
checked is what the scores rely on: one value per feature in every per-feature list, a
shared direction per row of ``factors`` over every feature, every number finite (the
threshold may be infinite: descriptions learnt without calibration answer every motion),
scales, noise, temperature and group limits above zero, spreads not below it, window lengths
within :data:`WINDOWS`, and each group limit naming a feature group of the spread's features
(:func:`~praxicon.feature_groups.feature_groups`) once: the group test reads only the groups
it finds a limit for, so a limit of a group renamed turned that group's test off without a
word.

The checks raise :class:`FieldError`, which :mod:`praxicon.description` (which this module
must not import: it reads through this one) turns into its ``DescriptionError``.

>>> spread_fields({"format": "praxicon-spread", "version": 4, "features": ["a"],
...                "scale": [1.0], "factors": [], "noise": [0.0], "threshold": 1.0,
...                "temperature": 1.0, "window": 0.0}, 4)
Traceback (most recent call last):
...
praxicon._description_json.FieldError: spread: 'noise' must be numbers above 0: value 1 is 0.0
"""

from __future__ import annotations

import math
from collections import Counter

from .feature_groups import feature_groups
from .jsonvalues import bad_item, shown, written_by

__all__ = ["WINDOWS", "FieldError", "check_format", "action_fields", "spread_fields",
           "check_window", "check_named_alike"]

#: Shortest and longest window (seconds) window descriptions may be learnt from and parse
#: cuts a recording into: under 0.1 s a window is a few frames at the usual capture rates
#: (3 at 30 fps), with no movement in it to tell; over a minute it holds many actions, and
#: parsing it gives one span. The build learns 2-second windows.
WINDOWS = (0.1, 60.0)


class FieldError(ValueError):
    """A description's field that is missing or out of its range (one line naming it)."""


_error = FieldError


def check_format(data, kind: str, version: int) -> None:
    """A :class:`FieldError` unless ``data`` is a JSON object of format ``kind`` and
    descriptions version ``version``."""
    if not isinstance(data, dict):
        raise _error(f"not a {kind} (a JSON object expected, not {type(data).__name__})")
    if data.get("format") != kind:
        raise _error(f"not a {kind} (format {shown(data.get('format'))})")
    said = data.get("version")
    age = written_by(said, version)
    if age:  # a later version's descriptions are not to be learnt again over
        raise _error(f"{kind} of version {shown(said)}; this psgs reads version {version}: "
                     + ("a later psgs wrote it; upgrade psgs to read it" if age == "later" else
                        "learn the descriptions again (psgs praxicon build ... -o PX resumes "
                        "the build and describes its actions)"))


def _need(data: dict, key: str, where: str):
    if key not in data:
        raise _error(f"{where}no {key!r}")
    return data[key]


def _number(data: dict, key: str, where: str, *, above: float | None = None,
            infinite: bool = False) -> float:
    value = _need(data, key, where)
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise _error(f"{where}{key!r} must be a number, not {shown(value)}")
    try:
        value = float(value)
    except OverflowError:  # an integer of 400 digits
        raise _error(f"{where}{key!r} must be a finite number, not an integer of "
                     f"{len(str(value))} digits") from None
    if math.isnan(value) or (math.isinf(value) and not (infinite and value > 0)):
        raise _error(f"{where}{key!r} must be a finite number, not {value!r}")
    if above is not None and not value > above:
        raise _error(f"{where}{key!r} must be above {above:g}, not {value!r}")
    return value


def _texts(data: dict, key: str, where: str) -> tuple[str, ...]:
    value = _need(data, key, where)
    if not isinstance(value, list):
        raise _error(f"{where}{key!r} must be a list of text, not {shown(value)}")
    _items(key, value, lambda v: isinstance(v, str), "a list of text", where)
    if not value:
        raise _error(f"{where}{key!r} is empty")
    if len(set(value)) != len(value):
        counts = Counter(value)  # not value.count per value (quadratic)
        twice = next(v for v in value if counts[v] > 1)
        raise _error(f"{where}{key!r} names {twice!r} twice")
    return tuple(value)


def _numbers(value, key: str, where: str, count: int, *, least: float | None = None,
             strict: bool = False) -> tuple[float, ...]:
    """``count`` finite numbers (at least ``least``, above it when ``strict``)."""
    if not isinstance(value, list):
        raise _error(f"{where}{key!r} must be a list of numbers, not {shown(value)}")
    _items(key, value, lambda v: not isinstance(v, bool) and isinstance(v, (int, float)),
           "a list of numbers", where)
    if len(value) != count:
        raise _error(f"{where}{key!r} has {len(value)} values for {count} features")
    out = tuple(map(_float, value))
    _items(key, out, math.isfinite, "finite numbers", where)
    if least is not None:
        _items(key, out, (lambda v: v > least) if strict else (lambda v: v >= least),
               f"numbers {'above' if strict else 'from'} {least:g}", where)
    return out


def _float(number) -> float:
    try:
        return float(number)
    except OverflowError:  # an integer of 400 digits
        return math.inf


def _items(key: str, items, good, expected: str, where: str) -> None:
    """A :class:`FieldError` naming the first of ``items`` that is not ``good`` and its place
    (:func:`~praxicon.jsonvalues.bad_item`, as the records' readers name it)."""
    problem = bad_item(key, items, good, expected)
    if problem:
        raise _error(f"{where}{problem}")


def _limit_groups(names: list, features: tuple[str, ...], where: str) -> None:
    """A :class:`FieldError` unless each of ``names`` (the groups of a spread's ``limits``)
    is a feature group of ``features`` and none is named twice."""
    groups = feature_groups(features)
    _items("limits", names, groups.__contains__, "of the spread's feature groups", where)
    first: dict[str, int] = {}
    for i, name in enumerate(names, 1):
        if name in first:
            raise _error(f"{where}'limits' names {name!r} twice (values {first[name]} and "
                         f"{i})")
        first[name] = i


def check_window(window: float, where: str = "") -> float:
    """``window`` when it is 0 (whole takes) or a window length within :data:`WINDOWS`.

    Examples
    --------
    >>> check_window(2.0), check_window(0.0)
    (2.0, 0.0)
    >>> check_window(1e300, "spread: ")
    Traceback (most recent call last):
    ...
    praxicon._description_json.FieldError: spread: 'window' must be 0 (whole takes) or 0.1 to 60 seconds, not 1e+300
    """
    if isinstance(window, bool) or not isinstance(window, (int, float)):
        raise _error(f"{where}'window' must be a number, not {shown(window)}")
    if window != 0.0 and not WINDOWS[0] <= window <= WINDOWS[1]:
        raise _error(f"{where}'window' must be 0 (whole takes) or {WINDOWS[0]:g} to "
                     f"{WINDOWS[1]:g} seconds, not {window!r}")
    return window


def action_fields(data, version: int) -> tuple:
    """``(name, features, mean, spread, takes, window)`` of an action description's JSON
    value (of descriptions version ``version``), each checked."""
    check_format(data, "praxicon-action-description", version)
    name = _need(data, "name", "action: ")
    if not isinstance(name, str) or not name:
        raise _error(f"action: 'name' must be text, not {shown(name)}")
    where = f"action {name!r}: "
    features = _texts(data, "features", where)
    mean = _numbers(_need(data, "mean", where), "mean", where, len(features))
    spread = _numbers(_need(data, "spread", where), "spread", where, len(features), least=0.0)
    takes = _need(data, "takes", where)
    if isinstance(takes, bool) or not isinstance(takes, int) or takes < 1:
        raise _error(f"{where}'takes' must be a whole number from 1, not {shown(takes)}")
    window = check_window(_number(data, "window", where), where)
    return name, features, mean, spread, takes, window


def spread_fields(data, version: int) -> tuple:
    """``(features, scale, factors, noise, threshold, temperature, window, limits, tail)`` of
    a spread's JSON value (of descriptions version ``version``), each checked (a ``tail`` of
    null, or none, is infinite: Gaussian likelihoods)."""
    check_format(data, "praxicon-spread", version)
    where = "spread: "
    features = _texts(data, "features", where)
    n = len(features)
    scale = _numbers(_need(data, "scale", where), "scale", where, n, least=0.0, strict=True)
    rows = _need(data, "factors", where)
    if not isinstance(rows, list):
        raise _error(f"{where}'factors' must be a list of rows of numbers, not {shown(rows)}")
    factors = tuple(_numbers(r, "factors", f"{where}row {i + 1} of ", n)
                    for i, r in enumerate(rows))
    noise = _numbers(_need(data, "noise", where), "noise", where, n, least=0.0, strict=True)
    threshold = _number(data, "threshold", where, above=0.0, infinite=True)
    temperature = _number(data, "temperature", where, above=0.0)
    window = check_window(_number(data, "window", where), where)
    # descriptions written before the group test have no limits: no group test
    limits = data.get("limits", [])
    pair = "a list of [group, number] pairs"
    if not isinstance(limits, list):
        raise _error(f"{where}'limits' must be {pair}, not {shown(limits)}")
    _items("limits", limits, lambda p: isinstance(p, list) and len(p) == 2
           and isinstance(p[0], str), pair, where)
    # above 0: the group test divides a group's distance by its limit (the calibration never
    # writes one under the group's size, one standard deviation per feature)
    bounds = _numbers([v for _, v in limits], "limits", where, len(limits), least=0.0,
                      strict=True)
    _limit_groups([g for g, _ in limits], features, where)
    tail = data.get("tail")
    tail = math.inf if tail is None else _number(data, "tail", where, above=0.0)
    return (features, scale, factors, noise, threshold, temperature, window,
            tuple((g, v) for (g, _), v in zip(limits, bounds)), tail)


def check_named_alike(takes, windows) -> None:
    """A :class:`FieldError` unless the whole-take descriptions ``takes`` and the window
    descriptions ``windows`` (:class:`~praxicon.description.Descriptions`, each checked alone)
    describe the same actions, and the takes' families are those of their actions.

    The build learns both from the same takes, and the families' descriptions are the
    families the actions name (``family_of``; an action alone is its own family, under its
    own name) and no other: an action parse cannot answer with, or a family no action is in,
    changes the answers without a word (a family's "none of these" reads the groups that tell
    it apart from every other family described). A family may have the name of one of its own
    members, never of another action (that action's own family would be another with its
    name).

    Examples
    --------
    >>> from types import SimpleNamespace as D
    >>> check_named_alike(D(names=("a", "b"), families=None), D(names=("a",)))
    Traceback (most recent call last):
    ...
    praxicon._description_json.FieldError: takes and windows describe other actions: 'b' is described in takes only
    """
    whole, windowed = set(takes.names), set(windows.names)
    if whole != windowed:  # which part was damaged cannot be told: both are named
        part, only = ("takes", whole - windowed) if whole - windowed else \
            ("windows", windowed - whole)
        raise _error(f"takes and windows describe other actions: {min(only)!r} is described "
                     f"in {part} only")
    if takes.families is None:
        return
    pooled: dict[str, list[str]] = {}  # the families of two or more actions
    for name, family in zip(takes.names, takes.family_of):
        if family:
            pooled.setdefault(family, []).append(name)
    for family, members in pooled.items():
        if family in whole and family not in members:
            raise _error(f"takes: family {family!r} has the name of another action "
                         f"(its members: {', '.join(map(repr, members[:3]))})")
    alone = {name for name, family in zip(takes.names, takes.family_of) if not family}
    stray = [f for f in takes.families.names if f not in pooled and f not in alone]
    if stray:
        raise _error(f"takes: families: describes {stray[0]!r}, the family of no action")
