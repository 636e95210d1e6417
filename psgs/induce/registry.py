"""Inducers by name: the built-ins and the plug-ins of the entry-point group ``psgs.inducers``.

A plug-in is declared in its package's ``pyproject.toml``::

    [project.entry-points."psgs.inducers"]
    mine = "mypackage.learner:MyInducer"

and :func:`get` builds it like a built-in. What can go wrong with a plug-in is
said loudly, naming it: a name that clashes with a built-in (it would be
hidden), two plug-ins of one name, a plug-in that fails to load or to build,
and one that gives something without an ``induce`` method.
"""

from __future__ import annotations

import inspect
from importlib.metadata import entry_points

from ..errors import ValidationError
from .base import Inducer, unknown_parameter
from .pal import PAL, ContentPAL, MotionPAL
from .sequential import Sequential

__all__ = ["get", "available", "GROUP", "text_params"]

#: The entry-point group other packages add inducers to.
GROUP = "psgs.inducers"

_BUILT_IN: dict[str, type[Inducer]] = {"pal": PAL, "sequential": Sequential,
                                        "pal_content": ContentPAL, "pal_motion": MotionPAL}


def _describe(ep) -> str:
    """``'name' (a plug-in, module:attr from distribution)``, with what the entry point tells."""
    value = getattr(ep, "value", None)
    dist = getattr(getattr(ep, "dist", None), "name", None)
    where = ", ".join(part for part in (value, f"from {dist}" if dist else None) if part)
    return f"{ep.name!r} (a plug-in{', ' + where if where else ''})"


def _a(noun: str) -> str:
    """``noun`` with its indefinite article (``an int``, ``a str``)."""
    return f"{'an' if noun[:1].lower() in 'aeiou' else 'a'} {noun}"


def _plugins() -> dict[str, list]:
    """Plug-in name -> its entry points (more than one is an error, reported on use)."""
    found: dict[str, list] = {}
    for ep in entry_points(group=GROUP):
        found.setdefault(ep.name, []).append(ep)
    return found


def available() -> tuple[str, ...]:
    """Names of the inducers :func:`get` can build: the built-ins first, then plug-ins sorted.

    A plug-in named like a built-in is not listed (``get`` refuses that name
    while the clash lasts, saying which plug-in it is).

    Returns
    -------
    tuple of str

    Examples
    --------
    >>> available()[:2]
    ('pal', 'sequential')
    """
    extra = sorted(n for n in _plugins() if n not in _BUILT_IN)
    return (*_BUILT_IN, *extra)


def get(name: str, **params) -> Inducer:
    """A new inducer by name, built with ``params``.

    Parameters
    ----------
    name : str
        ``"pal"``, ``"sequential"``, ``"pal_content"``, ``"pal_motion"`` or a
        plug-in's name (see :func:`available`).
    **params
        The inducer's keyword parameters.

    Returns
    -------
    Inducer
        Or, for a plug-in, any object with an ``induce`` method.

    Raises
    ------
    ValidationError
        For an unknown name; a parameter the inducer does not have, or a value
        it refuses; a plug-in whose name clashes with a built-in's or another
        plug-in's; a plug-in that cannot be loaded or built, or that gives
        something without ``induce``. Every message names the inducer.

    Examples
    --------
    >>> get("pal", min_copies=4).min_copies
    4
    >>> get("pal", colour="red")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: inducer pal has no parameter 'colour' (its parameters: ...)
    """
    if not isinstance(name, str):  # a list is no name, and a dict lookup would say unhashable
        raise ValidationError(f"an inducer is named by a str, not {name!r}; available: "
                              f"{', '.join(available())}")
    plugins = _plugins()
    if name in _BUILT_IN:
        if name in plugins:
            raise ValidationError(
                f"inducer {name!r} is built in, and the plug-in "
                f"{' and '.join(_describe(ep) for ep in plugins[name])} has the same name: "
                f"rename the plug-in (its entry point in group {GROUP!r})")
        factory = _BUILT_IN[name]
        _check_names(name, factory, params)
        return factory(**params)
    if name not in plugins:
        raise ValidationError(f"unknown inducer {name!r}; available: {', '.join(available())}")
    if len(plugins[name]) > 1:
        raise ValidationError(f"inducer {name!r} is given by {len(plugins[name])} plug-ins: "
                              f"{' and '.join(_describe(ep) for ep in plugins[name])}")
    ep = plugins[name][0]
    who = f"inducer {_describe(ep)}"
    try:
        factory = ep.load()
    except Exception as exc:  # a broken plug-in: say which, in one line
        raise ValidationError(f"{who} could not be loaded: {type(exc).__name__}: {exc}") from None
    if not callable(factory):
        raise ValidationError(f"{who} is {_a(type(factory).__name__)}, not a class or function "
                              f"that builds an inducer")
    _check_names(name, factory, params)
    try:
        inducer = factory(**params)
    except ValidationError as exc:
        raise ValidationError(f"{who}: {exc}") from None
    except Exception as exc:  # its own errors, in one line that says whose they are
        raise ValidationError(f"{who} could not be built: {type(exc).__name__}: {exc}") from None
    if not callable(getattr(inducer, "induce", None)):
        raise ValidationError(f"{who} gave {_a(type(inducer).__name__)}, which has no induce "
                              f"method (an inducer subclasses psgs.induce.Inducer or has one)")
    return inducer


def text_params(name: str, params: dict) -> dict:
    """``params`` as given in text (a command line's ``KEY=VALUE``), for inducer ``name``:
    the text ``none`` (any case) of a parameter whose default is None is None.

    A parameter that takes a number or None (PAL's ``max_seconds``, ``max_bytes``) says so
    when refused, and the text ``None`` was refused with that very message; for any other
    parameter ``none`` stays a word, which the parameter refuses in its own words.

    Parameters
    ----------
    name : str
        The inducer's name (see :func:`get`).
    params : dict
        Parameter names to values, the values as given (texts among them).

    Returns
    -------
    dict
        The same parameters, ``none`` read as None where the default is None.

    Raises
    ------
    ValidationError
        As :func:`get` does, for an unknown inducer or parameter or a bad value (the
        values are checked as :func:`get` checks them).

    Examples
    --------
    >>> text_params("pal", {"max_seconds": "None", "alpha": 0.01})
    {'max_seconds': None, 'alpha': 0.01}
    >>> text_params("sequential", {"max_rules": "none"})
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: parameter max_rules must be an integer, not 'none'
    """
    nones = {key for key, value in params.items()
             if isinstance(value, str) and value.lower() == "none"}
    inducer = get(name, **{key: value for key, value in params.items() if key not in nones})
    if not nones:
        return dict(params)
    declared = inspect.signature(type(inducer)).parameters
    read = {key: None if key in nones and key in declared and declared[key].default is None
            else value for key, value in params.items()}
    get(name, **read)  # a none left a word is refused here, in the parameter's words
    return read

def _check_names(name: str, factory, params: dict) -> None:
    """Refuse a parameter the factory does not take, naming the ones it does."""
    if not params:
        return
    if isinstance(factory, type) and issubclass(factory, Inducer):
        known = factory._param_names()
    else:
        try:
            signature = inspect.signature(factory)
        except (TypeError, ValueError):  # no signature to read: let the call decide
            return
        if any(p.kind is p.VAR_KEYWORD for p in signature.parameters.values()):
            return
        known = tuple(p.name for p in signature.parameters.values()
                      if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD))
    for key in params:
        if key not in known:
            raise ValidationError(unknown_parameter(name, key, known))
