"""Equal neighbours merged into one segment (one job): a run of equal symbols becomes one
symbol whose duration, and displacement, is the sum of the run's.

An :class:`~psgs.Actiongram` merges its strings so unless it is made with ``keep_repeats``;
its checks time the merged segments, and its text and JSON readers place a fault of a merged
segment at the run's first symbol.
"""

from __future__ import annotations

from collections.abc import Sequence

__all__: list[str] = []  # private helpers


def _merge(symbols: Sequence[str], durations: Sequence[float]) -> tuple[tuple[str, ...],
                                                                       tuple[float, ...]]:
    """Merge runs of equal neighbours into one segment, adding their durations.

    >>> _merge(("a", "a", "b"), (1, 2, 0.5))
    (('a', 'b'), (3.0, 0.5))
    """
    out_symbols: list[str] = []
    out_durations: list[float] = []
    # float() of each: a numpy float32 added to a float would stay a float32, and lose digits
    for sym, dur in zip(symbols, durations):
        if out_symbols and out_symbols[-1] == sym:
            out_durations[-1] += float(dur)
        else:
            out_symbols.append(sym)
            out_durations.append(float(dur))
    return tuple(out_symbols), tuple(out_durations)


def _merge_displacements(symbols: Sequence[str],
                         displacements: Sequence[float]) -> tuple[float, ...]:
    """The displacements of :func:`_merge`'s segments: a merged run's changes add up.

    >>> _merge_displacements(("a", "a", "b"), (1, -3, 2))
    (-2.0, 2.0)
    """
    out: list[float] = []
    previous = None
    for sym, disp in zip(symbols, displacements):
        if out and previous == sym:
            out[-1] += float(disp)
        else:
            out.append(float(disp))
        previous = sym
    return tuple(out)
