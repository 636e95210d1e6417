"""Which engine segments: numpy's array passes or numba's compiled loops (the same output).

``engine="auto"`` (the default of every function that segments) takes the compiled engine
when numba can be imported (``pip install 'psgs[fast]'``) and numpy's otherwise; ``"numpy"``
and ``"numba"`` ask for one. The choice is an argument, never a setting held anywhere; how it
is made is :mod:`psgs._foundation.engines`'s, shared with PAL.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Callable

import numpy as np

from psgs._foundation import engines

from . import _kinetemes

__all__: list[str] = []  # private: kinetology.segmentation is the interface


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
def _compiled() -> Engine:
    """The numba engine (imported, and its loops compiled on first call, only when chosen)."""
    from . import _kinetemes_jit as jit
    return Engine("numba", jit.largest_step, jit.smooth_channels, jit.row_ranges,
                  jit.segment_columns)


#: Samples (frames x channels) from which ``"auto"`` segments with numba in a fresh process.
#: Measured on a 2-core machine: numpy segments 17 million samples (a 132-channel take tiled
#: to 128,000 frames) in 0.50 s, numba in 0.53 s once loaded, and reading numba's cache costs
#: 0.7-1.8 s a process; so below some 34 million samples numpy is the faster choice.
CROSSOVER = 2 ** 25


def select(engine: str = "auto", size: int | None = None) -> Engine:
    """The engine named ``engine`` (one of ``"auto"``, ``"numpy"``, ``"numba"``).

    With ``size`` (the samples to segment), ``"auto"`` keeps an input below
    :data:`CROSSOVER` on numpy unless the compiled loops already run in this process.
    Raises :class:`psgs.errors.ValidationError` (a ``ValueError``) for another name and
    :class:`psgs.errors.MissingDependency` (an ``ImportError``) when ``"numba"`` is asked for
    and numba does not import.
    """
    if size is not None:
        engine = engines.for_input(engine, size, CROSSOVER, "kinetology._kinetemes_jit")
    return engines.select(engine, numpy=NUMPY, numba=_compiled)
