"""Which of the Actiongram constructor's checks refuses a string first, and which field it
names (one job: the checks of a string, in order, each with its place).

:data:`CHECKS` is the one list of a string's checks. The constructor runs it and raises the
first fault's message; the readers of the text and JSON forms, whose call of the constructor
refuses a file as a whole, run the same list over what they read to place that message, at a
value of the JSON document or at a token of the text line. So the order in which a reader
looks for the fault is the order in which the constructor finds it: there is one.

A check reads one string as given (:class:`StringFields`) and says what is wrong with it as a
:class:`Fault`: the message, and the fields at fault named as the JSON form names a string's
keys (``("symbols", 2)``: the third symbol; ``("start",)``), the most precise first. Each list
of :data:`CHECKS` runs over every string before the next list does: the constructor checks
every string's name, symbols, durations and times before any string's displacements, and
those before any string's actuator.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field

from ..errors import FormatError
from ._checks import (_bad_displacement, _bad_duration, _bad_name, _bad_symbol, _finite,
                      _plain_displacements, _plain_durations, _real, _refused, _shown,
                      _times_problem)
from ._segments import _merge, _merge_displacements

__all__: list[str] = []  # private: the constructor and the readers are the interface


@dataclass(frozen=True)
class Fault:
    """What a check finds wrong with a string: the constructor's message, and the fields at
    fault (paths within the string, as the JSON form names them), the most precise first."""

    message: str
    fields: tuple[tuple, ...]


@dataclass(frozen=True, eq=False, slots=True)
class StringFields:
    """One string of an actiongram as given to the constructor, before any check.

    ``displacements`` is a tuple, None (unknown), or what was given when it is no sequence
    (which a check refuses); it and ``actuator`` are read by the checks of their own list
    alone, so the constructor gives them once the strings have passed theirs.
    """

    name: object
    symbols: tuple
    durations: tuple
    start: object = 0.0
    keep_repeats: bool = False
    #: an earlier string has this name
    repeated: bool = False
    displacements: object = None
    actuator: object = None
    #: what is worked out once from the fields (a record of 20,000 strings is made in a
    #: constructor's call: neither functools.cached_property, which takes a lock, nor
    #: dataclasses.replace, which reads the fields anew, at each)
    _memo: dict = field(default_factory=dict, repr=False)

    @property
    def segments(self) -> tuple[tuple, tuple[float, ...]]:
        """The symbols and durations as timed: equal neighbours merged, unless kept apart
        (read once the symbols and durations have passed their checks)."""
        memo = self._memo
        if "segments" not in memo:
            memo["segments"] = (self.symbols, tuple(map(float, self.durations))) \
                if self.keep_repeats else _merge(self.symbols, self.durations)
        return memo["segments"]

    @property
    def displacement_row(self) -> tuple[float, ...] | None:
        """The displacement of each segment; None when unknown, and for a string without
        symbols, which has nothing to displace (as the text form reads it back)."""
        memo = self._memo
        if "displacement_row" not in memo:
            memo["displacement_row"] = None if self.displacements is None or not self.symbols \
                else tuple(map(float, self.displacements)) if self.keep_repeats \
                else _merge_displacements(self.symbols, self.displacements)
        return memo["displacement_row"]

    def given(self, displacements: object) -> "StringFields":
        """This string with its displacements as given (a sequence read into a tuple)."""
        if displacements is not None and not isinstance(displacements, (str, bytes)) \
                and isinstance(displacements, Iterable):
            displacements = tuple(displacements)
        return StringFields(self.name, self.symbols, self.durations, self.start,
                            self.keep_repeats, self.repeated, displacements, self.actuator)


def strings_of(names: Sequence, symbols: Sequence[tuple], durations: Sequence[tuple],
               starts: Sequence, keep_repeats: bool, displacements: Sequence | None = None,
               actuators: Sequence | None = None) -> tuple[StringFields, ...]:
    """One :class:`StringFields` per string of the constructor's rows (of one length each).

    >>> [s.repeated for s in strings_of(["a", "b", "a"], [()] * 3, [()] * 3, [0] * 3, False)]
    [False, False, True]
    """
    seen: set[str] = set()
    out = []
    for k, name in enumerate(names):
        text = isinstance(name, str)  # a name that is not text is refused as a name, first
        string = StringFields(name, symbols[k], durations[k], starts[k], keep_repeats,
                              text and name in seen,
                              actuator=None if actuators is None else actuators[k])
        out.append(string if displacements is None else string.given(displacements[k]))
        if text:
            seen.add(name)
    return tuple(out)


# -- the checks, each of one string ------------------------------------------------------------
def _name(s: StringFields) -> Fault | None:
    problem = _bad_name(s.name)
    return None if problem is None else Fault(problem, (("name",),))


def _repeated(s: StringFields) -> Fault | None:
    return Fault(f"two strings are named {_shown(s.name)}", (("name",),)) if s.repeated else None


def _lengths(s: StringFields) -> Fault | None:
    if len(s.symbols) == len(s.durations):
        return None
    return Fault(f"string {_shown(s.name)} has {len(s.symbols)} symbols but "
                 f"{len(s.durations)} durations", (("durations",),))


def _symbols(s: StringFields) -> Fault | None:
    try:
        distinct = dict.fromkeys(s.symbols)  # each distinct symbol once, where it first stands
    except TypeError:  # an unhashable symbol (a list from JSON): not text
        distinct = s.symbols
    for sym in distinct:
        problem = _bad_symbol(sym)
        if problem is not None:
            return Fault(f"string {_shown(s.name)}: {problem}",
                         (("symbols", s.symbols.index(sym)),))
    return None


def _durations(s: StringFields) -> Fault | None:
    if _plain_durations(s.durations):  # the usual case: one pass, no message to make
        return None
    for j, dur in enumerate(s.durations):
        problem = _bad_duration(dur)
        if problem is not None:
            return Fault(f"string {_shown(s.name)}: {problem}", (("durations", j),))
    return None


def _start(s: StringFields) -> Fault | None:
    if not _real(s.start) or not _finite(s.start):
        return Fault(f"string {_shown(s.name)}: start time must be a finite number, not "
                     f"{_shown(s.start)}", (("start",),))
    return None


def _times_overflow(s: StringFields) -> Fault | None:
    if math.isfinite(float(s.start) + sum(s.segments[1])):
        return None
    return Fault(f"string {_shown(s.name)}: its times overflow (the durations add up to more "
                 f"than a float can hold)", (("durations",), ("start",)))


def _vanishing(s: StringFields) -> Fault | None:
    found = _times_problem(s.name, float(s.start), s.segments[1], s.symbols, s.keep_repeats)
    return None if found is None else Fault(found[1], (("durations", found[0]), ("start",)))


def _displacements_kind(s: StringFields) -> Fault | None:
    if s.displacements is None or isinstance(s.displacements, tuple):
        return None
    return Fault(f"string {_shown(s.name)}: displacements must be a list of numbers or None, "
                 f"not {_shown(s.displacements)}", (("displacements",),))


def _displacements_count(s: StringFields) -> Fault | None:
    if s.displacements is None or len(s.displacements) == len(s.symbols):
        return None
    return Fault(f"string {_shown(s.name)} has {len(s.symbols)} symbols but "
                 f"{len(s.displacements)} displacements", (("displacements",),))


def _displacement_values(s: StringFields) -> Fault | None:
    if _plain_displacements(s.displacements or ()):  # the usual case: no value to look at alone
        return None
    for j, disp in enumerate(s.displacements or ()):
        problem = _bad_displacement(disp)
        if problem is not None:
            return Fault(f"string {_shown(s.name)}: {problem}", (("displacements", j),))
    return None


def _displacements_overflow(s: StringFields) -> Fault | None:
    row = s.displacement_row  # each finite, a merged run's sum may not be
    if s.keep_repeats or row is None or all(map(math.isfinite, row)):
        return None
    return Fault(f"string {_shown(s.name)}: its displacements overflow (equal neighbours "
                 f"merged add up to more than a float can hold)", (("displacements",),))


def _actuator(s: StringFields) -> Fault | None:
    problem = _bad_name(s.actuator)
    if problem is None:
        return None
    # no "actuator" key in a JSON string: its default, made from the name
    return Fault(f"string {_shown(s.name)}: actuator {_shown(s.actuator)}: {problem}",
                 (("actuator",), ("name",)))


Check = Callable[[StringFields], "Fault | None"]
#: a string's name, symbols, durations and times, in the order they are checked
STRING_CHECKS: tuple[Check, ...] = (_name, _repeated, _lengths, _symbols, _durations, _start,
                                    _times_overflow, _vanishing)
#: a string's displacements (after every string's STRING_CHECKS)
DISPLACEMENT_CHECKS: tuple[Check, ...] = (_displacements_kind, _displacements_count,
                                          _displacement_values, _displacements_overflow)
#: a string's actuator (after every string's displacements)
ACTUATOR_CHECKS: tuple[Check, ...] = (_actuator,)
#: every check of a string, in the constructor's order: each list over every string in turn
CHECKS: tuple[tuple[Check, ...], ...] = (STRING_CHECKS, DISPLACEMENT_CHECKS, ACTUATOR_CHECKS)


def first_fault(strings: Sequence[StringFields],
                checks: tuple[tuple[Check, ...], ...] = CHECKS) -> tuple[int, Fault] | None:
    """The first fault the ``checks`` find, with the index of its string; None when none.

    >>> first_fault(strings_of(["a", "b"], [("x", "y"), ("y", "z@")], [(1, 1), (1, -1)],
    ...                        [0, 0], False))
    (1, Fault(message="string 'b': symbol 'z@' must have no white space, control character, '@' or ':' and not start with '#'", fields=(('symbols', 1),)))
    """
    for listed in checks:
        for k, string in enumerate(strings):
            for check in listed:
                fault = check(string)
                if fault is not None:
                    return k, fault
    return None


def refuse(strings: Sequence[StringFields], checks: tuple[Check, ...]) -> None:
    """Raise the first fault of the ``checks`` as the constructor does: a FormatError with
    its message, placed nowhere (the readers place it in their file)."""
    found = first_fault(strings, (checks,))
    if found is not None:
        raise _refused(found[1].message)


def first_refused(count: int, build: Callable[[int], object]) -> tuple[int, FormatError] | None:
    """The least ``k`` (1 to ``count``) for which ``build(k)`` raises, with its error; None
    when ``build(count)`` does not. Once refused, every longer prefix is.

    The skeleton's entries are checked together (a cycle takes several), so the entry at
    fault is the one that ends the shortest run of them refused.

    >>> def build(k):
    ...     if k >= 3:
    ...         raise FormatError(f"{k} entries")
    >>> k, error = first_refused(5, build)
    >>> k, error.message
    (3, '3 entries')
    """
    try:
        build(count)
        return None
    except FormatError as exc:
        refused, error = count, exc
    low = 0  # build(low) is accepted, build(refused) is not
    while refused - low > 1:
        middle = (low + refused) // 2
        try:
            build(middle)
            low = middle
        except FormatError as exc:
            refused, error = middle, exc
    return refused, error
