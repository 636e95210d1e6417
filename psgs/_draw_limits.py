"""How much of a derivation's parse trees :mod:`psgs.draw` draws: a plain value, apart from the
drawing code, so that ``psgs draw --help`` (which prints it) is made without importing it."""

from __future__ import annotations

__all__ = ["MAX_NODES"]

#: The most parse-tree nodes ``psgs draw`` and a notebook's picture draw (about 3 s with
#: matplotlib, 5 s with Graphviz): a tree past a few thousand nodes is no longer readable.
MAX_NODES = 5_000
