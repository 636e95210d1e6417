"""Notebook pictures of grammar systems, attached to the model's classes from above it.

A notebook shows a value by calling its ``_repr_svg_``. The model knows nothing of drawing
(the drawing code reads derivations, which read the model), so the method is given to
:class:`~psgs.model.PSGS` and :class:`~psgs.model.PCGS` here, when ``psgs`` is imported;
the drawing module itself is imported only when a notebook first shows a system.
"""

from __future__ import annotations

from .model import PCGS, PSGS

__all__: list[str] = []  # private: what it adds is the notebook's protocol


def _repr_svg_(system) -> str | None:
    """The forest of a derived word and the synchronisation graph (notebooks)."""
    from .draw import system_svg

    return system_svg(system)


PSGS._repr_svg_ = _repr_svg_
PCGS._repr_svg_ = _repr_svg_
