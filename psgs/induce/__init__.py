"""Inducers: learn a grammar system from an actiongram.

Every inducer is configured by keyword arguments and has one method,
``induce(actiongram) -> Induction``. Built in: :class:`PAL` (``"pal"``) and
the sequential baseline :class:`Sequential` (``"sequential"``). Other
packages add inducers through the entry-point group ``psgs.inducers``
(``name = "package.module:Class"``); :func:`get` and :func:`available` see them.
"""

from __future__ import annotations

from importlib.metadata import entry_points

from .base import Induction, Inducer, StringReport
from .pal import PAL
from .sequential import Sequential

__all__ = ["Induction", "Inducer", "StringReport", "PAL", "Sequential", "get", "available"]

_BUILT_IN = {"pal": PAL, "sequential": Sequential}


def _plugins() -> dict[str, object]:
    return {ep.name: ep for ep in entry_points(group="psgs.inducers")}


def available() -> tuple[str, ...]:
    """Names of the inducers that :func:`get` knows, built-in first, then plug-ins sorted."""
    extra = sorted(n for n in _plugins() if n not in _BUILT_IN)
    return (*_BUILT_IN, *extra)


def get(name: str, **params) -> Inducer:
    """A new inducer by name, built with ``params``; ValueError for an unknown name.

    >>> get("pal", min_copies=4).min_copies
    4
    """
    if name in _BUILT_IN:
        return _BUILT_IN[name](**params)
    plugins = _plugins()
    if name in plugins:
        try:
            factory = plugins[name].load()
        except Exception as exc:  # a broken plug-in: say which, in one line
            raise ValueError(f"inducer {name!r} (a plug-in) could not be loaded: "
                             f"{type(exc).__name__}: {exc}") from None
        return factory(**params)
    raise ValueError(f"unknown inducer {name!r}; available: {', '.join(available())}")
