"""How a :class:`~kinetology.motion.Motion` keeps what it holds from changing: its values in an
array no numpy call makes writeable again, and its ``meta`` read-only all the way down.

Kept apart from :mod:`kinetology.motion` (the value and its checks), which is near the module
line cap.
"""

from __future__ import annotations

from collections.abc import Mapping, MutableSequence, MutableSet
from types import MappingProxyType

import numpy as np

from psgs.errors import ValidationError

__all__ = ["frozen_meta", "read_only", "thawed"]


class _ReadOnlyMemory:
    """The array that owns a motion's memory, kept out of reach of its views.

    numpy makes any array that owns its memory writeable again on ``setflags(write=True)``,
    whatever was set before, and every view's ``.base`` leads back to that owner. An array
    made from this holder's ``__array_interface__`` (data marked read-only) has the holder
    as its base instead: the holder has no buffer to write through, so numpy refuses
    ``setflags(write=True)`` on that array and on every view of it. What stays open is
    reaching into the holder's private ``_owner`` (or writing through the raw pointer with
    ctypes), as ``object.__setattr__`` can still set a field of any frozen dataclass.
    """

    __slots__ = ("_owner",)

    def __init__(self, owner: np.ndarray) -> None:
        owner.setflags(write=False)  # so that its interface marks the data read-only
        self._owner = owner

    @property
    def __array_interface__(self) -> dict:
        # a property, not a field: nothing can set an interface whose data is writeable
        return self._owner.__array_interface__


def read_only(array: np.ndarray) -> np.ndarray:
    """``array``'s memory, uncopied, as an array that cannot be made writeable.

    ``array`` itself becomes read-only; whoever still holds it could make it writeable again
    (numpy allows that to the array owning the memory), so only an array nothing else holds
    is given. Views of the answer, and the answer's ``base``, refuse ``setflags(write=True)``.

    Examples
    --------
    >>> values = read_only(np.zeros((2, 3)))
    >>> values.flags.writeable, values[:, 1].flags.writeable
    (False, False)
    >>> values.base.setflags(write=True)
    Traceback (most recent call last):
    ...
    AttributeError: '_ReadOnlyMemory' object has no attribute 'setflags'
    >>> values.setflags(write=True)
    Traceback (most recent call last):
    ...
    ValueError: cannot set WRITEABLE flag to True of this array
    """
    return np.asarray(_ReadOnlyMemory(array))


def _settled(array: np.ndarray) -> bool:
    """Whether ``array`` is already one :func:`read_only` made (or a view of one): its memory
    cannot change, so it is kept rather than copied again."""
    base = array.base
    while isinstance(base, np.ndarray):
        if base.flags.writeable:
            return False
        base = base.base
    return isinstance(base, _ReadOnlyMemory) and not array.flags.writeable


def frozen_meta(meta: Mapping) -> MappingProxyType:
    """``meta`` as a read-only mapping whose values cannot change either.

    Each value is frozen in turn: a mapping becomes a read-only mapping (a
    ``types.MappingProxyType`` of a new dict), a list (any mutable sequence) or tuple a
    tuple, a set a ``frozenset``, a ``bytearray`` ``bytes``, and a numpy array a read-only
    copy (its objects frozen too, for an array of objects). Anything else is kept as given:
    numbers, strings, ``None`` and other values that do not change, or an object of the
    caller's own, whose mutability is its own.

    Raises
    ------
    ValidationError
        When ``meta`` holds itself (a list inside itself, ...) or is nested too deeply to
        freeze.

    Examples
    --------
    >>> meta = frozen_meta({"cut": [0.5, 2.0], "truth": {"labels": ["walk"]}})
    >>> meta["cut"], meta["truth"]["labels"], type(meta["truth"]).__name__
    ((0.5, 2.0), ('walk',), 'mappingproxy')
    >>> loop = []
    >>> loop.append(loop)
    >>> frozen_meta({"loop": loop})
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: meta['loop'][0] holds itself: a motion's meta must be a tree of values
    """
    try:
        return _frozen(meta, "meta", set())
    except RecursionError:
        raise ValidationError("meta is nested too deeply to freeze") from None


def _frozen(value, where: str, inside: set):
    """``value`` frozen (see :func:`frozen_meta`); ``where`` names it in an error, ``inside``
    holds the ids of the containers it is in (a container inside itself never ends)."""
    if value is None or isinstance(value, (str, bytes, int, float, complex, np.generic)):
        return value  # the common case first: nothing to freeze
    container = isinstance(value, (Mapping, MutableSequence, MutableSet, tuple, frozenset,
                                   np.ndarray))
    if container and id(value) in inside:
        raise ValidationError(f"{where} holds itself: a motion's meta must be a tree of values")
    inside.add(id(value))
    try:
        if isinstance(value, Mapping):
            return MappingProxyType({key: _frozen(item, f"{where}[{key!r}]", inside)
                                     for key, item in value.items()})
        if isinstance(value, bytearray):
            return bytes(value)
        if isinstance(value, tuple) and hasattr(type(value), "_make"):  # a named tuple
            return type(value)._make(_frozen(item, f"{where}.{name}", inside)
                                     for name, item in zip(value._fields, value))
        if type(value) is tuple or isinstance(value, MutableSequence):
            return tuple(_frozen(item, f"{where}[{k}]", inside) for k, item in enumerate(value))
        if isinstance(value, (MutableSet, frozenset)):
            return frozenset(value)  # its items are hashable, which no list or dict is
        if isinstance(value, np.ndarray):
            if _settled(value):
                return value
            copy = np.array(value, copy=True, subok=False)
            if copy.dtype.hasobject:
                for index in np.ndindex(copy.shape):
                    copy[index] = _frozen(copy[index], f"{where}[{index}]", inside)
            return read_only(copy)
        return value
    finally:
        inside.discard(id(value))


def thawed(value):
    """``value`` (a frozen meta, or one of its values) with each read-only mapping a dict:
    :mod:`pickle` and :func:`copy.deepcopy` cannot take a ``mappingproxy``, at any depth.
    What holds none is given back as it is; :func:`frozen_meta` freezes the answer again.

    Examples
    --------
    >>> import pickle
    >>> meta = frozen_meta({"truth": {"labels": [{"walk": (0, 2)}]}})
    >>> plain = thawed(meta)
    >>> plain, frozen_meta(pickle.loads(pickle.dumps(plain))) == meta
    ({'truth': {'labels': ({'walk': (0, 2)},)}}, True)
    """
    if isinstance(value, MappingProxyType):
        return {key: thawed(item) for key, item in value.items()}
    if isinstance(value, tuple):
        items = [thawed(item) for item in value]
        if all(new is old for new, old in zip(items, value)):
            return value
        return type(value)._make(items) if hasattr(type(value), "_make") else tuple(items)
    if isinstance(value, np.ndarray) and value.dtype.hasobject:
        copy = np.empty(value.shape, dtype=object)
        for index in np.ndindex(value.shape):
            copy[index] = thawed(value[index])
        return copy
    return value
