"""The depth-first walk behind the PSGS searches of ``accepts`` and ``nearest``.

Both searches walk the same kind of tree: a node's successors come from a lazy
iterator, the walk keeps a stack of those iterators and the path of entries
that led to the current node, reads the budget's clock once per generated
successor, and backs up when an iterator is exhausted. What a search does with
one successor (skip it as visited or too costly, descend into it, record a
goal, stop) is its own :data:`Expand` function; the loop is here once.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

__all__ = ["Finish", "depth_first"]


class Finish:
    """What an expand function returns to end the walk with ``value``.

    Examples
    --------
    >>> Finish("found").value
    'found'
    """

    __slots__ = ("value",)

    def __init__(self, value: Any) -> None:
        self.value = value


_END = object()

#: ``expand(item, path)``: ``None`` skips the item, ``(entry, children)`` appends ``entry``
#: to the path and descends into ``children`` (an iterable of items), a :class:`Finish` ends
#: the walk. ``path`` is the list of entries from the root to the item's parent (read only).
Expand = Callable[[Any, list], Any]


def depth_first(children: Iterable, expand: Expand, tick: Callable[[], None]) -> Any:
    """Walk depth first from the root's ``children``; the :class:`Finish` value, else ``None``.

    ``tick`` is called once per item generated (a budget's clock), so a
    search whose successors are all visited or cut still reads the clock.
    The walk runs on an explicit stack: a path of a hundred thousand steps
    does not hit Python's recursion limit.

    Examples
    --------
    >>> def expand(item, path):      # the binary words of length 3, stop at "101"
    ...     word = "".join(path) + item
    ...     if word == "101":
    ...         return Finish(word)
    ...     return (item, "01") if len(word) < 3 else None
    >>> depth_first("01", expand, lambda: None)
    '101'
    >>> depth_first("01", lambda item, path: None, lambda: None) is None
    True
    """
    stack = [iter(children)]
    path: list = []
    while stack:
        item = next(stack[-1], _END)
        tick()
        if item is _END:
            stack.pop()
            if path:
                path.pop()
            continue
        outcome = expand(item, path)
        if outcome is None:
            continue
        if isinstance(outcome, Finish):
            return outcome.value
        entry, grandchildren = outcome
        path.append(entry)
        stack.append(iter(grandchildren))
    return None
