"""Which engine segments: numpy's array passes or numba's compiled loops (the same output).

``engine="auto"`` (the default of every function that segments) takes the compiled engine
when numba can be imported (``pip install 'psgs[fast]'``) and numpy's otherwise; ``"numpy"``
and ``"numba"`` ask for one. The choice is an argument, never a setting held anywhere.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Callable

import numpy as np

from . import _kinetemes

__all__: list[str] = []  # private: kinetology.segmentation is the interface

ENGINES = ("auto", "numpy", "numba")


@dataclass(frozen=True)
class Engine:
    """The functions an engine supplies (each as :mod:`kinetology._kinetemes` defines it)."""

    name: str
    largest_step: Callable
    smooth_channels: Callable
    row_ranges: Callable
    segment_columns: Callable


def _ranges(rows):
    return np.ptp(rows, axis=1)


NUMPY = Engine("numpy", _kinetemes.largest_step, _kinetemes.smooth_channels, _ranges,
               _kinetemes.segment_columns)


@lru_cache(maxsize=1)
def _compiled() -> Engine | str:
    """The numba engine, or why it cannot be had (numba's import error); looked up once."""
    try:
        import numba  # noqa: F401  (only to know whether it imports)
    except ImportError as error:
        return str(error)
    from . import _kinetemes_jit as jit
    return Engine("numba", jit.largest_step, jit.smooth_channels, jit.row_ranges,
                  jit.segment_columns)


def select(engine: str = "auto") -> Engine:
    """The engine named ``engine`` (one of :data:`ENGINES`).

    Raises ``ValueError`` for another name and ``ImportError`` when ``"numba"`` is asked for
    and numba does not import.
    """
    if not isinstance(engine, str) or engine not in ENGINES:
        raise ValueError(f"engine must be one of {', '.join(map(repr, ENGINES))}, "
                         f"not {engine!r}")
    if engine == "numpy":
        return NUMPY
    compiled = _compiled()
    if isinstance(compiled, Engine):
        return compiled
    if engine == "numba":
        raise ImportError(f"engine='numba' needs numba, which does not import here "
                          f"({compiled}); install it with `pip install 'psgs[fast]'`, or use "
                          f"engine='numpy'")
    return NUMPY
