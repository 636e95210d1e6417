"""Notebook pictures of grammar systems and actiongrams, attached to their classes from above.

A notebook shows a value by calling its ``_repr_svg_`` or ``_repr_html_``. The model and the
actiongram know nothing of drawing (the drawing code reads derivations, which read the
model), so the methods are given to :class:`~psgs.model.PSGS`, :class:`~psgs.model.PCGS`
and :class:`~psgs.Actiongram` here, when ``psgs`` is imported; the drawing module itself is
imported only when a notebook first shows a value.
"""

from __future__ import annotations

from .actiongram import Actiongram
from .model import PCGS, PSGS

__all__: list[str] = []  # private: what it adds is the notebook's protocol


def _system_svg(system) -> str | None:
    """The forest of a derived word and the synchronisation graph (notebooks)."""
    from .draw import system_svg

    return system_svg(system)


def _actiongram_html(actiongram) -> str:
    """Each string as coloured runs of its symbols, widths by duration (notebooks)."""
    from .draw import actiongram_html

    return actiongram_html(actiongram)


PSGS._repr_svg_ = _system_svg
PCGS._repr_svg_ = _system_svg
Actiongram._repr_html_ = _actiongram_html
