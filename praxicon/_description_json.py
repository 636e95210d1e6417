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

The checks of what a description holds are made on its values (:func:`check_action`,
:func:`check_spread`), which the dataclasses' constructors run: descriptions made in Python
are checked as a file's are, and a file's once. :func:`action_fields` and
:func:`spread_fields` only read the JSON values into them (lists of numbers as tuples of
floats). What a description's names must name beside a praxicon (the window descriptions of
the takes' actions, the families of the actions, features a motion can have:
:func:`check_feature_names`) is checked by :func:`check_named_alike`.

The checks raise :class:`FieldError`, which :mod:`praxicon.description` (which this module
must not import: it reads through this one) turns into its ``DescriptionError``.

>>> check_spread(("a",), (1.0,), (), (0.0,), 1.0, 1.0, 0.0, (), math.inf)
Traceback (most recent call last):
...
praxicon._description_json.FieldError: spread: 'noise' must be numbers above 0: value 1 is 0.0
"""

from __future__ import annotations

import json
import math
from collections import Counter

from .feature_groups import feature_groups
from .jsonvalues import bad_item, shown, written_by

__all__ = ["WINDOWS", "FieldError", "json_object", "check_format", "check_action",
           "check_spread", "action_fields", "spread_fields", "check_window",
           "check_named_alike", "check_feature_names"]

#: Shortest and longest window (seconds) window descriptions may be learnt from and parse
#: cuts a recording into: under 0.1 s a window is a few frames at the usual capture rates
#: (3 at 30 fps), with no movement in it to tell; over a minute it holds many actions, and
#: parsing it gives one span. The build learns 2-second windows.
WINDOWS = (0.1, 60.0)


class FieldError(ValueError):
    """A description's field that is missing or out of its range (one line naming it)."""


_error = FieldError


def json_object(text: str) -> dict:
    """The JSON object ``text`` holds (a :class:`FieldError` for text that is not one).

    Examples
    --------
    >>> json_object('{"a": ')
    Traceback (most recent call last):
    ...
    praxicon._description_json.FieldError: not JSON (line 1, column 7: Expecting value)
    """
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise _error(f"not JSON (line {exc.lineno}, column {exc.colno}: {exc.msg})") from None
    except RecursionError:  # '[' * 100000: the decoder recurses per nesting level
        raise _error("not JSON that can be read: nested too deeply") from None
    except ValueError as exc:  # an integer of thousands of digits (Python's int limit)
        raise _error(f"not JSON that can be read: {str(exc).split(':')[0]}") from None
    if not isinstance(data, dict):
        raise _error("not a praxicon description (a JSON object expected)")
    return data


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


def _is_number(value) -> bool:
    """An int or a float (a float's subclass too: numpy's float64), not a bool: what JSON
    writes as a number."""
    return not isinstance(value, bool) and isinstance(value, (int, float))


def _number(data: dict, key: str, where: str) -> float:
    """The JSON number at ``key`` as a float (its range is :func:`_positive`'s and
    :func:`check_window`'s)."""
    value = _need(data, key, where)
    if not _is_number(value):
        raise _error(f"{where}{key!r} must be a number, not {shown(value)}")
    try:
        return float(value)
    except OverflowError:  # an integer of 400 digits
        raise _error(f"{where}{key!r} must be a finite number, not an integer of "
                     f"{len(str(value))} digits") from None


def _positive(value, key: str, where: str, *, infinite: bool = False) -> None:
    """A :class:`FieldError` unless ``value`` is a number above 0 (and finite, unless
    ``infinite``)."""
    if not _is_number(value):
        raise _error(f"{where}{key!r} must be a number, not {shown(value)}")
    value = _float(value)  # an int past the float range is infinite
    if math.isnan(value) or (math.isinf(value) and not (infinite and value > 0)):
        raise _error(f"{where}{key!r} must be a finite number, not {value!r}")
    if not value > 0:
        raise _error(f"{where}{key!r} must be above 0, not {value!r}")


def _texts(data: dict, key: str, where: str) -> tuple[str, ...]:
    """The JSON list of text at ``key``, checked as :func:`_names` checks a tuple."""
    value = _need(data, key, where)
    if not isinstance(value, list):
        raise _error(f"{where}{key!r} must be a list of text, not {shown(value)}")
    return _names(tuple(value), key, where, "a list")


def _names(value, key: str, where: str, kind: str = "a tuple") -> tuple[str, ...]:
    """``value`` when it is a tuple of text, one or more, none twice."""
    if not isinstance(value, tuple):
        raise _error(f"{where}{key!r} must be {kind} of text, not {shown(value)}")
    if not set(map(type, value)) <= {str}:  # at C speed: a load reads thousands of names
        _items(key, value, lambda v: isinstance(v, str), f"{kind} of text", where)
    if not value:
        raise _error(f"{where}{key!r} is empty")
    if len(set(value)) != len(value):
        counts = Counter(value)  # not value.count per value (quadratic)
        twice = next(v for v in value if counts[v] > 1)
        raise _error(f"{where}{key!r} names {twice!r} twice")
    return value


def _json_numbers(value, key: str, where: str) -> tuple[float, ...]:
    """A JSON list of numbers as a tuple of floats (an integer past the float range is
    infinite: refused as not finite by :func:`_numbers`)."""
    if not isinstance(value, list):
        raise _error(f"{where}{key!r} must be a list of numbers, not {shown(value)}")
    if not set(map(type, value)) <= _NUMBERS:
        _items(key, value, _is_number, "a list of numbers", where)
    try:
        return tuple(map(float, value))
    except OverflowError:  # an integer of 400 digits
        return tuple(map(_float, value))


#: The types of a JSON number as read (a float's subclass is a number too: the slow path).
_NUMBERS = {int, float}


def _plain(value: tuple, least: float | None, strict: bool) -> bool:
    """Whether ``value`` is numbers that are plainly finite and in range, read at C speed
    (the checks of a load go through thousands of them): ints and floats whose sum is finite
    and whose least is at least ``least`` (above it when ``strict``). False is no error:
    :func:`_numbers` then looks at each."""
    try:
        if not set(map(type, value)) <= _NUMBERS or not math.isfinite(math.fsum(value)):
            return False
    except (OverflowError, ValueError):  # an int past the float range, or inf and -inf
        return False  # together (fsum refuses them): said by _numbers
    return least is None or not value or (min(value) > least if strict else
                                          min(value) >= least)


def _numbers(value, key: str, where: str, count: int, *, least: float | None = None,
             strict: bool = False) -> None:
    """A :class:`FieldError` unless ``value`` is a tuple of ``count`` finite numbers (at least
    ``least``, above it when ``strict``)."""
    if not isinstance(value, tuple):
        raise _error(f"{where}{key!r} must be a tuple of numbers, not {shown(value)}")
    if len(value) == count and _plain(value, least, strict):
        return
    _items(key, value, _is_number, "a tuple of numbers", where)
    if len(value) != count:
        raise _error(f"{where}{key!r} has {len(value)} values for {count} features")
    _items(key, value, lambda v: math.isfinite(_float(v)), "finite numbers", where)
    if least is not None:
        _items(key, value, (lambda v: v > least) if strict else (lambda v: v >= least),
               f"numbers {'above' if strict else 'from'} {least:g}", where)


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


def _limits(limits, features: tuple[str, ...], where: str) -> None:
    """A :class:`FieldError` unless ``limits`` are ``(group, number)`` pairs, each number above
    0 and each group a feature group of ``features``, none named twice."""
    pair = "a tuple of (group, number) pairs"
    if not isinstance(limits, tuple):
        raise _error(f"{where}'limits' must be {pair}, not {shown(limits)}")
    _items("limits", limits, lambda p: isinstance(p, tuple) and len(p) == 2
           and isinstance(p[0], str), pair, where)
    # above 0: the group test divides a group's distance by its limit (the calibration never
    # writes one under the group's size, one standard deviation per feature)
    _numbers(tuple(v for _, v in limits), "limits", where, len(limits), least=0.0,
             strict=True)
    names = [g for g, _ in limits]
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
    if not _is_number(window):
        raise _error(f"{where}'window' must be a number, not {shown(window)}")
    if window != 0.0 and not WINDOWS[0] <= window <= WINDOWS[1]:
        raise _error(f"{where}'window' must be 0 (whole takes) or {WINDOWS[0]:g} to "
                     f"{WINDOWS[1]:g} seconds, not {shown(window)}")
    return window


def _version(version, current: int, where: str) -> None:
    if version != current or not isinstance(version, int) or isinstance(version, bool):
        raise _error(f"{where}'version' must be {current} (the descriptions this psgs reads "
                     f"and writes), not {shown(version)}")


def check_action(name, features, mean, spread, takes, window, version, current) -> None:
    """A :class:`FieldError` unless an action description's values are what the scores rely
    on: a name, its features (text, none twice), one finite mean and one spread from 0 per
    feature, ``takes`` a whole number from 1, a window :func:`check_window` takes, and
    ``version`` the ``current`` one (:class:`~praxicon.description.ActionDescription` runs
    it when made).

    Examples
    --------
    >>> check_action("wave", ("a.rx:pose",), (0.5,), (-1.0,), 2, 0.0, 6, 6)
    Traceback (most recent call last):
    ...
    praxicon._description_json.FieldError: action 'wave': 'spread' must be numbers from 0: value 1 is -1.0
    """
    if not isinstance(name, str) or not name:
        raise _error(f"action: 'name' must be text, not {shown(name)}")
    where = f"action {name!r}: "
    _names(features, "features", where)
    _numbers(mean, "mean", where, len(features))
    _numbers(spread, "spread", where, len(features), least=0.0)
    if isinstance(takes, bool) or not isinstance(takes, int) or takes < 1:
        raise _error(f"{where}'takes' must be a whole number from 1, not {shown(takes)}")
    check_window(window, where)
    _version(version, current, where)


def check_spread(features, scale, factors, noise, threshold, temperature, window, limits,
                 tail, version: int = 0, current: int = 0) -> None:
    """A :class:`FieldError` unless a spread's values are what the scores rely on: its
    features (text, none twice), per feature a finite scale and noise above 0, each row of
    ``factors`` a finite number per feature, the threshold above 0 (infinite: descriptions
    that only rank), the temperature finite and above 0, a window :func:`check_window` takes,
    each group limit above 0 and naming a feature group of the features
    (:func:`~praxicon.feature_groups.feature_groups`) once, the tail above 0 (infinite:
    Gaussian likelihoods) and ``version`` the ``current`` one
    (:class:`~praxicon.description.Spread` runs it when made)."""
    where = "spread: "
    _names(features, "features", where)
    n = len(features)
    _numbers(scale, "scale", where, n, least=0.0, strict=True)
    if not isinstance(factors, tuple):
        raise _error(f"{where}'factors' must be a tuple of rows of numbers, not "
                     f"{shown(factors)}")
    for i, row in enumerate(factors):
        _numbers(row, "factors", f"{where}row {i + 1} of ", n)
    _numbers(noise, "noise", where, n, least=0.0, strict=True)
    _positive(threshold, "threshold", where, infinite=True)
    _positive(temperature, "temperature", where)
    check_window(window, where)
    _limits(limits, features, where)
    _positive(tail, "tail", where, infinite=True)
    _version(version, current, where)


def action_fields(data, version: int) -> tuple:
    """``(name, features, mean, spread, takes, window)`` of an action description's JSON
    value (of descriptions version ``version``), read as :func:`check_action` checks them."""
    check_format(data, "praxicon-action-description", version)
    name = _need(data, "name", "action: ")
    if not isinstance(name, str) or not name:
        raise _error(f"action: 'name' must be text, not {shown(name)}")
    where = f"action {name!r}: "
    features = _texts(data, "features", where)
    mean = _json_numbers(_need(data, "mean", where), "mean", where)
    spread = _json_numbers(_need(data, "spread", where), "spread", where)
    return name, features, mean, spread, _need(data, "takes", where), \
        _number(data, "window", where)


def spread_fields(data, version: int) -> tuple:
    """``(features, scale, factors, noise, threshold, temperature, window, limits, tail)`` of
    a spread's JSON value (of descriptions version ``version``), read as :func:`check_spread`
    checks them (a ``tail`` of null, or none, is infinite: Gaussian likelihoods; no
    ``limits``, as descriptions written before the group test have: no group test)."""
    check_format(data, "praxicon-spread", version)
    where = "spread: "
    features = _texts(data, "features", where)
    scale = _json_numbers(_need(data, "scale", where), "scale", where)
    rows = _need(data, "factors", where)
    if not isinstance(rows, list):
        raise _error(f"{where}'factors' must be a list of rows of numbers, not {shown(rows)}")
    factors = tuple(_json_numbers(r, "factors", f"{where}row {i + 1} of ")
                    for i, r in enumerate(rows))
    noise = _json_numbers(_need(data, "noise", where), "noise", where)
    threshold = _number(data, "threshold", where)
    temperature = _number(data, "temperature", where)
    window = _number(data, "window", where)
    limits = data.get("limits", [])
    pair = "a list of [group, number] pairs"
    if not isinstance(limits, list):
        raise _error(f"{where}'limits' must be {pair}, not {shown(limits)}")
    _items("limits", limits, lambda p: isinstance(p, list) and len(p) == 2
           and isinstance(p[0], str) and _is_number(p[1]), pair, where)
    tail = data.get("tail")
    tail = math.inf if tail is None else _number(data, "tail", where)
    if math.isinf(tail) and data.get("tail") is not None:  # Gaussian is written null
        raise _error(f"{where}'tail' must be a finite number, not {tail!r}")
    return (features, scale, factors, noise, threshold, temperature, window,
            tuple((g, _float(v)) for g, v in limits), tail)


#: Per axis of a feature's channel the kinds :func:`praxicon.features.motion_features` makes
#: for a window of a recording (``shape=False``, which parse reads) and for a whole take: a
#: rotation channel's (``JOINT.rx:pose``; its quarter means only over a whole take), the root's
#: travel and turning (``JOINT.turny:drift``; a turn's excursion only over a whole take).
_WINDOW_KINDS = {**{f"r{a}": {"pose", "posec", "spread", "energy"} for a in "xyz"},
                 **{f"{m}{a}": {"drift", "energy"} for m in ("travel", "turn") for a in "xyz"}}
_TAKE_KINDS = {axis: kinds | ({f"shape{i}" for i in range(4)} if axis[0] == "r" else
                              {"excursion"} if axis.startswith("turn") else set())
               for axis, kinds in _WINDOW_KINDS.items()}
#: The take-wide features, named alone.
_TAKE_WIDE = ("flight", "pace", "tempo")


def feature_problem(feature: str, window: bool = False) -> str | None:
    """Why no motion (no window of a recording, with ``window``) has a feature named
    ``feature``; ``None`` when one can.

    Recognition compares a motion with an action over the features both have, and reads a
    feature the motion lacks as a joint of another skeleton: a feature no motion can have is
    never compared, and renamed alike in a spread and its actions it went unnoticed.

    Examples
    --------
    >>> feature_problem("Hips.turny:excursion"), feature_problem("tempo")
    (None, None)
    >>> print(feature_problem("Hips.rx:bogus"))
    no motion has it (a feature is JOINT.rx|ry|rz:pose|posec|spread|energy|shape0-3, JOINT.travelx-z|turnx-z:drift|energy, JOINT.turnx-z:excursion, flight, pace or tempo)
    >>> feature_problem("Hips.turny:excursion", window=True)[:28]
    'no window of a recording has'
    """
    if feature in _TAKE_WIDE:
        return None
    channel, colon, kind = feature.rpartition(":")
    joint, dot, axis = channel.rpartition(".")
    if colon and dot and joint and kind in (_WINDOW_KINDS if window else _TAKE_KINDS).get(
            axis, ()):
        return None
    if window and kind in _TAKE_KINDS.get(axis, ()) and joint:
        return ("no window of a recording has it (a window has no quarter means, shape0-3, "
                "nor turn excursions: they read the course of a whole take)")
    return ("no motion has it (a feature is JOINT.rx|ry|rz:pose|posec|spread|energy|shape0-3, "
            "JOINT.travelx-z|turnx-z:drift|energy, JOINT.turnx-z:excursion, flight, pace or "
            "tempo)")


def check_feature_names(described, part: str) -> None:
    """A :class:`FieldError` unless every feature of ``described`` (a
    :class:`~praxicon.description.Descriptions`, ``part`` of a praxicon's descriptions: its
    takes, their families or its windows) is one a motion can have (:func:`feature_problem`),
    naming the first action that names one that is not (else the spread)."""
    window = bool(described.spread.window)
    # the spread's features are every action's (Descriptions checks it): each name once
    bad = next(((f, p) for f in described.spread.features
                if (p := feature_problem(f, window)) is not None), None)
    if bad is None:
        return
    feature, problem = bad
    owner = next((f"action {a.name!r}" for a in described.actions if feature in a.features),
                 "spread")
    raise _error(f"{part}: {owner}: 'features' names {feature!r}: {problem}")


def check_named_alike(takes, windows) -> None:
    """A :class:`FieldError` unless the whole-take descriptions ``takes`` and the window
    descriptions ``windows`` (:class:`~praxicon.description.Descriptions`, each checked alone)
    describe the same actions, each names only features a motion has
    (:func:`check_feature_names`), and the takes' families are those of their actions.

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
    for described, part in ((takes, "takes"), (takes.families, "takes: families"),
                            (windows, "windows")):
        if described is not None:
            check_feature_names(described, part)
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
