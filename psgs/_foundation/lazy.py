"""A package's public names imported on first use (module-level ``__getattr__``).

A package lists ``name -> submodule`` and gets the two module hooks back, so that
``import package`` stays cheap (matplotlib, dask or numba load only when a name that needs
them is first used).
"""

from __future__ import annotations

import importlib
import sys
from collections.abc import Callable, Iterable, Mapping

__all__ = ["lazy_names"]


def lazy_names(package: str, names: Mapping[str, str], *, submodules: Iterable[str] = (),
               listed: Iterable[str] = ()) -> tuple[Callable[[str], object],
                                                    Callable[[], list[str]]]:
    """The ``__getattr__`` and ``__dir__`` of a package whose names load on first use.

    Parameters
    ----------
    package : str
        The package's ``__name__``.
    names : mapping of str to str
        Public name -> the submodule (relative to ``package``) that defines it. The value is
        kept in the package once looked up, so the hook runs once per name.
    submodules : iterable of str, optional
        Submodules reachable as attributes (imported on first use).
    listed : iterable of str, optional
        What ``dir(package)`` shows (the package's ``__all__``, say); only listed names, so
        that ``help(package)`` imports no submodule.

    Returns
    -------
    (callable, callable)
        The ``__getattr__`` and ``__dir__`` to assign in the package.

    Examples
    --------
    >>> getattr_, dir_ = lazy_names("json", {"JSONDecodeError": "decoder"}, listed=["dumps"])
    >>> getattr_("JSONDecodeError").__name__, dir_()
    ('JSONDecodeError', ['dumps'])
    >>> getattr_("nothing")
    Traceback (most recent call last):
    ...
    AttributeError: module 'json' has no attribute 'nothing'
    """
    table = dict(names)
    modules = frozenset(submodules)
    shown = sorted(set(listed))

    def __getattr__(name: str):
        if name in table:
            value = getattr(importlib.import_module(f".{table[name]}", package), name)
            setattr(sys.modules[package], name, value)
            return value
        if name in modules:
            return importlib.import_module(f".{name}", package)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        return list(shown)

    return __getattr__, __dir__
