"""Membership: is a word tuple in L(Γ)? Is a word in the language of a PCGS?

:func:`accepts` answers with an :class:`Acceptance`: ``"yes"`` (with a
witness derivation, replayed step by step with the derivation engine),
``"no"`` (with a reason) or ``"unknown"`` (naming the budget that ran out).

PSGS (sound and complete in both modes and both policies): each word is
parsed by a goal-directed chart, then a depth-first search looks for a
synchronised schedule (:mod:`psgs.membership.schedule_search`). PCGS (membership is
undecidable in general): a breadth-first search over configurations, pruned
soundly by the master's word (:mod:`psgs.membership.pcgs_search`). See
``docs/membership.md``.

:func:`nearest` answers how far a word tuple is from the language instead,
with a :class:`Nearest` tuple, its witness and the edits
(:mod:`psgs.membership.nearest`).

The package, bottom-up: ``chart`` (one context-free grammar, one word),
``witness`` (the typed schedule of a yes and its replay as a checked
:class:`~psgs.derivation.Derivation`), ``result`` (the :class:`Acceptance`
value), ``depth_first`` (the walk of the PSGS searches), ``schedule_search``
(PSGS, general), ``block_search`` (PSGS, the block-by-block fast path),
``decide`` (PSGS: the two, in order), ``pcgs_search`` (PCGS), and
:func:`accepts` here.
"""

from __future__ import annotations

import gc
import numbers

from ..budget import Budget, check_count, check_seconds
from ..errors import ValidationError
from ..model import PCGS, PSGS, as_word
from .nearest import Nearest, nearest
from .pcgs_search import accepts_pcgs
from .result import Acceptance
from .decide import accepts_psgs
from .words import coerce_words as _coerce_words

__all__ = ["Acceptance", "accepts", "EAGER_REPLAY_LIMIT", "MAX_SYMBOLS", "Nearest", "nearest"]

#: Words of at most this many symbols in all get their witness replayed at once.
EAGER_REPLAY_LIMIT = 2000
#: The default memory bound of a search, in symbols kept (states × form size, and chart items).
MAX_SYMBOLS = 10_000_000


def _flag(value) -> bool:
    """True for a yes-or-no value: a bool, numpy's bool, 0 or 1 (not "no", which is truthy)."""
    if getattr(value, "shape", None) == () and getattr(value, "dtype", None) == bool:
        return True  # numpy's bool scalar (no numbers.Number)
    return isinstance(value, numbers.Number) and value in (True, False)


def accepts(system: PSGS | PCGS, words, *, max_states: int = 200_000,
            max_seconds: float = 30.0, max_steps: int = 200,
            max_symbols: int = MAX_SYMBOLS, check_witness: bool | None = None) -> Acceptance:
    """Decide whether ``words`` is in the language of ``system``.

    PSGS: ``words`` holds one word per component; a word is a ``str`` of
    one-character terminals or a sequence of terminal names or
    :class:`~psgs.model.Terminal`. A one-component system also takes a
    single word. The answer is ``"yes"``/``"no"`` unless a budget runs out:
    ``max_states`` search states (default 200,000) or ``max_seconds`` of
    wall-clock time (default 30), giving ``"unknown"`` with the budget named.
    The clock starts before the grammar analysis, so ``max_seconds`` covers
    everything the caller waits for. ``max_symbols`` bounds memory: the
    states a search keeps, counted as states × form size in symbols, and
    what the parse charts keep (default :data:`MAX_SYMBOLS`, about 0.7 GB in
    the PSGS search).

    ``bound`` of an ``"unknown"`` answer is the name of the budget that ran
    out (``"max_seconds"``, ``"max_states"``, ``"max_symbols"`` or, PCGS only,
    ``"max_steps"``); ``reason`` says it in words, with the budget's value.

    PCGS: ``words`` is the master's word. ``"yes"`` comes with a witness;
    ``"no"`` only when the search proved it (every configuration from which
    the master could still derive the word was explored); otherwise
    ``"unknown"`` naming ``max_steps`` (derivation length, default 200),
    ``max_states`` or ``max_seconds``.

    ``check_witness`` replays the witness (a yes answer) with the derivation
    engine before returning; ``None`` (default) does so when the words are at
    most :data:`EAGER_REPLAY_LIMIT` symbols long in all, and leaves it to the
    first access of ``.witness`` otherwise.

    Parameters
    ----------
    system : PSGS or PCGS
        The system.
    words : sequence of words, or a word
        One word per component (PSGS) or the master's word (PCGS); a word is a ``str`` of
        one-character terminals or a sequence of terminal names or Terminals.
    max_states : int, default 200_000
        Budget of search states.
    max_seconds : float, default 30.0
        Budget of wall-clock time.
    max_symbols : int, default MAX_SYMBOLS
        Budget of memory: states kept times their size in symbols, and the charts' items.
    max_steps : int, default 200
        PCGS only: the longest derivation searched.
    check_witness : bool or None, default None
        Replay the witness before returning (None: only for short words).

    Returns
    -------
    Acceptance
        ``"yes"`` (with a witness), ``"no"`` or ``"unknown"`` (naming the budget).

    Raises
    ------
    ValidationError
        When ``words`` does not fit the system (a word per component), a word holds something
        that is not a terminal, a budget is not positive, or ``check_witness`` is no bool.

    Examples
    --------
    >>> from psgs.model import Grammar, Rule, PSGS, Nonterminal as N, Terminal as T
    >>> g = Grammar("G", N("S"), (Rule("p", N("S"), (T("a"), N("S"))), Rule("q", N("S"), (T("a"),))))
    >>> h = Grammar("H", N("R"), (Rule("u", N("R"), (T("b"), N("R"))), Rule("v", N("R"), (T("b"),))))
    >>> system = PSGS((g, h), (("p", "u"), ("q", "v")), unsynchronised="strict")
    >>> accepts(system, ["aaa", "bbb"]).answer, accepts(system, ["aaa", "bb"]).answer
    ('yes', 'no')
    """
    for name, value in (("max_states", max_states), ("max_steps", max_steps),
                        ("max_symbols", max_symbols)):
        check_count(value, name)  # the bounds' one check, as nearest's
    check_seconds(max_seconds)
    if check_witness is not None and not _flag(check_witness):  # "no" is truthy
        raise ValidationError(f"check_witness must be True, False or None, not {check_witness!r}")
    budget = Budget(max_seconds, max_symbols, every=32)
    if isinstance(system, PCGS):
        word = as_word(words)  # the count from the word read: an iterator has no len()
        result = accepts_pcgs(system, word, max_steps=max_steps, max_states=max_states,
                              budget=budget)
        total = len(word)
    elif isinstance(system, PSGS):
        tuple_of_words = _coerce_words(system, words)
        # The search keeps a deep stack and a large visited set alive while allocating many
        # short-lived tuples: the cyclic collector's full passes over them made the run grow
        # faster than linearly (measured: k = 2000 Γ repetitions 6.9 s with it, 2.2 s
        # without). Nothing here makes reference cycles, so it is paused and then restored.
        collecting = gc.isenabled()
        gc.disable()
        try:
            result = accepts_psgs(system, tuple_of_words, max_states, budget)
        finally:
            if collecting:
                gc.enable()
        total = sum(len(w) for w in tuple_of_words)
    else:
        raise ValidationError(f"expected a PSGS or a PCGS, not {type(system).__name__}")
    if result.answer == "yes":
        if check_witness or (check_witness is None and total <= EAGER_REPLAY_LIMIT):
            result.witness  # noqa: B018 -- replaying checks every step
    return result
