"""Which engine computes: numpy's array passes or numba's compiled loops (the same output).

An algorithm with two engines writes each as a table of the same functions (a frozen
dataclass, say) and calls ``select(engine, numpy=TABLE, numba=loader)``: ``engine="auto"``
takes the compiled table when numba imports (``pip install 'psgs[fast]'``) and numpy's
otherwise; ``"numpy"`` and ``"numba"`` ask for one. The choice is an argument, never a
setting held anywhere. The compiled module decorates its loops with :func:`jit`, so that it
still imports (as plain Python) where numba does not.

Under ``"auto"``, :func:`for_input` keeps an input too small to repay loading the compiled
code (numba reads it from its cache, about a second a process) on numpy; both engines give
the same output, so the choice is only about time. The first compilation (tens of seconds,
once per installed copy) is announced on stderr by one line.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable
from functools import lru_cache
from typing import TypeVar

from ..errors import MissingDependency, ValidationError

__all__ = ["ENGINES", "resolve", "select", "for_input", "jit", "jit_inlined", "numba_missing", "usable_cores"]

#: The engine names every algorithm with two engines accepts.
ENGINES = ("auto", "numpy", "numba")

T = TypeVar("T")
F = TypeVar("F", bound=Callable)


@lru_cache(maxsize=1)
def numba_missing() -> str:
    """Why numba cannot be had (its import error), or ``""`` when it imports; looked up once.

    Returns
    -------
    str
        The import error's text, empty when numba imports.

    Examples
    --------
    >>> isinstance(numba_missing(), str)
    True
    """
    try:
        import numba  # noqa: F401  (only to know whether it imports)
    except ImportError as error:
        return str(error) or "numba is not installed"
    return ""


def resolve(engine: str = "auto") -> str:
    """The engine that runs for ``engine`` (one of :data:`ENGINES`): ``"numpy"`` or ``"numba"``.

    Parameters
    ----------
    engine : {"auto", "numpy", "numba"}
        What the caller asked for.

    Returns
    -------
    str
        ``"numpy"`` or ``"numba"``.

    Raises
    ------
    ValidationError
        For another name.
    MissingDependency
        When ``"numba"`` is asked for and numba does not import.

    Examples
    --------
    >>> resolve("numpy")
    'numpy'
    >>> resolve("auto") in ("numpy", "numba")
    True
    >>> resolve("fortran")
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: engine must be one of 'auto', 'numpy', 'numba', not 'fortran'
    """
    _known(engine)
    if engine == "numpy":
        return "numpy"
    missing = numba_missing()
    if not missing:
        return "numba"
    if engine == "numba":
        raise MissingDependency(f"engine='numba' needs numba, which does not import here "
                                f"({missing}); install it with `pip install 'psgs[fast]'`, or "
                                f"use engine='numpy'")
    return "numpy"


def select(engine: str, *, numpy: T, numba: Callable[[], T]) -> T:
    """The table of functions that runs for ``engine``: ``numpy`` or what ``numba()`` returns.

    Parameters
    ----------
    engine : {"auto", "numpy", "numba"}
        What the caller asked for (see :func:`resolve`).
    numpy : object
        The numpy engine's table.
    numba : callable
        Returns the compiled engine's table; called only when that engine runs, so that the
        compiled module is imported (and compiled) only then.

    Returns
    -------
    object
        The chosen table.

    Examples
    --------
    >>> select("numpy", numpy="array passes", numba=lambda: "compiled loops")
    'array passes'
    """
    if resolve(engine) != "numba":
        return numpy
    _announce_compiling()
    return numba()


def _known(engine: object) -> None:
    if not isinstance(engine, str) or engine not in ENGINES:
        raise ValidationError(f"engine must be one of {', '.join(map(repr, ENGINES))}, "
                              f"not {engine!r}")


def _loaded(module: str) -> bool:
    """Whether a compiled module's loops already run in this process (compiled or read from
    numba's cache by an earlier call): then the compiled engine costs nothing more to use."""
    found = sys.modules.get(module)
    return found is not None and any(getattr(value, "signatures", None)
                                     for value in vars(found).values())


def for_input(engine: str, size: int, crossover: int, compiled: str) -> str:
    """The engine to ask :func:`select` for, given an input of ``size`` (the caller's measure).

    Under ``"auto"``, ``"numpy"`` when ``size`` is below ``crossover`` (the size from which
    the compiled engine wins, measured in a fresh process, its cache read included) and the
    compiled module ``compiled`` has not run in this process yet; ``engine`` otherwise.

    Parameters
    ----------
    engine : {"auto", "numpy", "numba"}
        What the caller asked for; ``"numpy"`` and ``"numba"`` are kept as they are.
    size : int
        The input's size, in the unit of ``crossover``.
    crossover : int
        Below it a fresh process is faster with numpy.
    compiled : str
        The compiled module's name (its loops loaded means the cost is already paid).

    Returns
    -------
    str

    Examples
    --------
    >>> for_input("auto", 100, 10_000, "no.such.module")
    'numpy'
    >>> for_input("numba", 100, 10_000, "no.such.module")
    'numba'
    >>> for_input("auto", 20_000, 10_000, "no.such.module")
    'auto'
    """
    _known(engine)
    if engine != "auto" or size >= crossover or _loaded(compiled):
        return engine
    return "numpy"


@lru_cache(maxsize=1)
def _announce_compiling() -> None:
    """Listen for numba's compilations (not its cache reads) and say so once, on stderr.

    numba compiles a loop on its first call and reads it from its cache afterwards; only a
    compilation fires its ``numba:compile`` event, so a cached run says nothing.
    """
    from numba.core import event

    event.register("numba:compile", _announcer(sys.stderr))


def _announcer(stream):
    """A numba event listener that writes one line to ``stream`` at the first event it hears."""
    from numba.core import event

    class Announce(event.Listener):
        told = False

        def on_start(self, event) -> None:
            if not self.told:
                self.told = True
                print("psgs: numba is compiling the fast engine (once per installation, up to "
                      "half a minute; later runs read it from numba's cache)", file=stream,
                      flush=True)

        def on_end(self, event) -> None:
            pass

    return Announce()


def jit(function: F) -> F:
    """``function`` compiled by numba on first use, once per installed copy (``cache=True``).

    No ``fastmath``: the compiled loops must give the numpy engine's floats. ``nogil``: the
    callers run channels or strings in threads. Where numba does not import, ``function``
    itself, so that the compiled module still imports (the doctests collect everywhere).

    Parameters
    ----------
    function : callable
        A loop numba can compile (nopython mode).

    Returns
    -------
    callable
        The compiled function, or ``function`` unchanged without numba.

    Examples
    --------
    A compiled module's loop (numba caches compiled code beside a source file, so a loop
    typed at the prompt is not the place to show it)::

        @jit
        def total(values):
            s = 0.0
            for v in values:
                s += v
            return s
    """
    return _compiled(function)


def jit_inlined(function: F) -> F:
    """:func:`jit` for a function with one compiled caller, which numba compiles into that
    caller's body (``inline="always"``) instead of on its own.

    A function compiled on its own is optimised by LLVM once for itself and again inside each
    compiled caller (its code is linked into theirs), so a large function called only by
    another pays its optimisation twice (PAL's motif search of one string: 1.5-2 s of a cold
    start); small helpers measured no faster inlined (numba's inlining costs about what it
    saves). Without numba, ``function`` itself.
    """
    return _compiled(function, inline="always")


def _compiled(function, **options):
    if numba_missing():
        return function
    import numba

    return numba.njit(cache=True, nogil=True, **options)(function)


def usable_cores() -> int:
    """How many CPUs this process may run on: its affinity where the system has one (a
    container or ``taskset`` limits it below the machine's count), else the machine's.

    Every default number of threads or processes starts from this, so that none asks for
    more cores than the process has.

    Examples
    --------
    >>> usable_cores() >= 1
    True
    """
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return os.cpu_count() or 1
