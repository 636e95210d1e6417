"""Enumerating languages by size: PSGS tuples, PCGS master words, context-free words.

Every enumeration here is bounded and says so: the result is a
:class:`Language` whose ``complete`` is ``True`` only when the search
exhausted everything up to ``max_length``, and whose ``bound`` otherwise names
the budget that stopped it.

Two methods for a PSGS (see ``docs/derivation.md``):

* ``"search"``: breadth-first search over configurations, with a visited
  set and sound pruning (terminals never disappear; each nonterminal still
  costs at least its minimum terminal yield). Fast in ``parallel`` mode; in
  ``single`` mode the interleavings of independent rewrites explode.
* ``"filter"``: enumerate each component's context-free words by length
  (cheap), combine them into candidate tuples of total length ≤ L, and
  keep those that :func:`psgs.membership.accepts` accepts. Sound and
  complete because every word a component derives under either mode is in
  its context-free language (a parallel step is a sequence of ordinary
  steps).
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterable, Iterator, Sequence
from dataclasses import dataclass

from .analysis import min_yields, usable_rules
from .budget import Budget, check_count, check_seconds
from .errors import BoundReached, ValidationError
from .membership import MAX_SYMBOLS, accepts
from .model import PCGS, PSGS, Grammar, Nonterminal, Query, Rule, Terminal, Word, as_word
from .search import budget_sentence, pcgs_search, psgs_search

__all__ = ["Language", "language", "context_free_words"]

INFINITE = math.inf
#: words built between two readings of the clock (about a millisecond of set inserts)
_WORDS_PER_READING = 4096
#: What a word kept in a set costs besides its symbols, counted in symbols (pointers): the
#: tuple's header and its slot in the set, about 70 bytes. Words are short, so counting their
#: symbols alone let 10 million "symbols" of eight-symbol words take 400 MB
WORD_OVERHEAD = 8


@dataclass(frozen=True)
class Language:
    """The words of a language up to a size bound, in order of size, each once.

    ``words`` holds terminal tuples (one :data:`~psgs.model.Word` per
    component) for a PSGS, master words for a PCGS, words for a
    :class:`~psgs.model.Grammar`. They are sorted by size (total length),
    then by the names of their terminals. ``complete`` is ``True`` when every
    word up to ``max_length`` is listed; otherwise ``bound`` is the name of
    the budget that stopped the search (or left words out), e.g.
    ``"max_configurations"``, ``reason`` says it in words, and ``words``
    holds what was found (for context-free enumeration: every word shorter
    than the length at which it stopped). ``explored`` counts the configurations (search),
    candidate tuples (filter) or words (context-free) that were examined;
    ``kind`` is ``"tuples"`` (PSGS) or ``"words"``. ``item in language``
    accepts words written as strings, e.g. ``("ab", "ba") in lang``.

    Attributes
    ----------
    words : tuple
        The words (or tuples of words), by size and then by terminal names.
    complete : bool
        Whether every word up to ``max_length`` is listed.
    bound : str or None
        The budget that stopped an incomplete enumeration.
    reason : str or None
        The same in words, with the budget's value.
    max_length : int
        The size bound asked for.
    method : str
        ``"search"``, ``"filter"`` or ``"context-free"``.
    explored : int, default 0
        Configurations, candidate tuples or words examined.
    kind : str, default "words"
        ``"tuples"`` (PSGS) or ``"words"``.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> found = psgs.language(gamma, max_length=32)
    >>> found.kind, found.complete, found.bound
    ('tuples', True, None)
    >>> ["".join(map(str, w)) for w in found.words[0]]
    ['abcdbcad', 'bcadabcd', 'cdabcdab', 'abcdbcad']
    """

    words: tuple
    complete: bool
    bound: str | None
    max_length: int
    method: str
    explored: int = 0
    kind: str = "words"
    reason: str | None = None

    def __iter__(self) -> Iterator:
        return iter(self.words)

    def __len__(self) -> int:
        return len(self.words)

    def __contains__(self, item: object) -> bool:
        try:
            key = _coerce(item, self.kind == "tuples")
        except (ValidationError, TypeError):
            return False
        return key in self._word_set

    @property
    def _word_set(self) -> frozenset:
        cached = self.__dict__.get("_cached_set")
        if cached is None:
            cached = frozenset(self.words)
            object.__setattr__(self, "_cached_set", cached)
        return cached


def _coerce(item, of_tuples: bool):
    """Accept a word or a word tuple written with strings, as the rest of the API does."""
    if of_tuples:
        if isinstance(item, (str, bytes)):
            raise TypeError("a PSGS language holds tuples of words")
        return tuple(as_word(w) for w in item)
    return as_word(item)


def _names(w: Word) -> tuple[str, ...]:
    return tuple(t.name for t in w)


def _word_key(w: Word):
    return (len(w), _names(w))


def _tuple_key(ws: tuple[Word, ...]):
    return (sum(len(w) for w in ws), tuple(_names(w) for w in ws))


# ---------------------------------------------------------------- context-free facts
def context_free_words(grammar: Grammar, max_length: int, *, rules: Iterable[Rule] | None = None,
                       start: Nonterminal | None = None, max_words: int = 1_000_000,
                       max_seconds: float | None = 60.0, max_symbols: int | None = MAX_SYMBOLS):
    """The context-free words of ``grammar`` up to ``max_length``, by length.

    Returns ``(words_by_length, bound)``: a list whose entry ``n`` is the
    frozenset of words of length ``n`` derivable from ``start`` (the axiom
    unless given) with ``rules`` (all the grammar's rules unless given), and
    ``None`` or a sentence naming the bound that stopped it: ``max_words`` when the table
    grew past that many words, ``max_symbols`` (default
    :data:`psgs.membership.MAX_SYMBOLS`, ``None`` for no limit) when the words kept and those
    being built would hold more symbols (the memory bound: a word of length n counts as
    n + :data:`WORD_OVERHEAD` symbols, what its tuple and its place in a set take), or
    ``max_seconds`` (default 60, ``None`` for no limit) when time ran out; then the list
    stops before the length at which it was hit, and every shorter length is
    complete. ε-rules, unit cycles and left recursion are
    fine: each length is a fixpoint over finitely many words. Query symbols
    derive nothing here.

    Examples
    --------
    >>> from psgs import Grammar, Nonterminal, Rule, Terminal
    >>> S = Nonterminal("S")
    >>> g = Grammar("G", S, [Rule("r1", S, (Terminal("a"), S, Terminal("b"))), Rule("r2", S, ())])
    >>> by_length, bound = context_free_words(g, 4)
    >>> [sorted("".join(map(str, w)) for w in words) for words in by_length], bound
    ([[''], [], ['ab'], [], ['aabb']], None)
    >>> by_length, bound = context_free_words(g, 40, max_symbols=100)
    >>> len(by_length), bound
    (14, 'stopped at length 14: the words kept and those being built would hold more than 100 symbols (max_symbols); shorter words are complete')
    """
    if not isinstance(grammar, Grammar):
        raise ValidationError(f"expected a Grammar, not {type(grammar).__name__}")
    check_count(max_length, "max_length", minimum=0)
    check_count(max_words, "max_words")
    check_seconds(max_seconds, optional=True)
    if max_symbols is not None:
        check_count(max_symbols, "max_symbols")
    rules = grammar.rules if rules is None else rules
    if isinstance(rules, Rule) or not isinstance(rules, Iterable):
        raise ValidationError(f"rules must be an iterable of Rule values, not {rules!r}")
    rules = tuple(rules)
    for rule in rules:
        if not isinstance(rule, Rule):
            raise ValidationError(f"rules must hold Rule values, not {rule!r}")
    start = grammar.start if start is None else start
    if not isinstance(start, Nonterminal):
        raise ValidationError(f"start must be a Nonterminal, not {start!r}")
    return _words_by_length(grammar, max_length, rules, start, max_words,
                            Budget(max_seconds, max_symbols, every=32))


def _words_by_length(grammar: Grammar, max_length: int, rules, start, max_words: int,
                     clock: Budget):
    """:func:`context_free_words` on a running budget (its time and its memory: the symbols of
    the words kept are held on it); a bound reached keeps the complete lengths."""
    yields = min_yields(rules)
    lhs_order = sorted({r.lhs for r in rules}, key=lambda n: n.name)
    table: dict[Nonterminal, list[set]] = {a: [] for a in lhs_order}
    stored = 0

    def words_of(sym, n: int):
        if isinstance(sym, Terminal):
            return ((sym,),) if n == 1 else ()
        if isinstance(sym, Query):
            return ()
        rows = table.get(sym)
        if rows is None or n >= len(rows):
            return ()
        return rows[n]

    for n in range(max_length + 1):
        for a in lhs_order:
            table[a].append(set())
        changed = True
        while changed:
            changed = False
            for r in rules:
                if yields[r.lhs] > n:
                    continue
                row = table[r.lhs][n]
                before = len(row)
                try:
                    row.update(_sequence_words(r.rhs, n, words_of, yields, clock))
                    if len(row) != before:
                        stored += len(row) - before
                        changed = True
                        clock.hold((len(row) - before) * (n + WORD_OVERHEAD))
                except BoundReached as stop:
                    for a in lhs_order:
                        table[a].pop()
                    return _rows_of(table, start, n), _stopped_at(str(stop), n, clock)
            if stored > max_words:
                for a in lhs_order:
                    table[a].pop()
                bound = (f"stopped at length {n} after {stored} words (max_words={max_words}); "
                         f"shorter words are complete")
                return _rows_of(table, start, n), bound
    return _rows_of(table, start, max_length + 1), None


def _stopped_at(bound: str, n: int, clock: Budget) -> str:
    """The sentence of a context-free enumeration stopped at length ``n`` by ``bound``."""
    if bound == "max_symbols":
        why = (f"the words kept and those being built would hold more than "
               f"{clock.max_symbols} symbols (max_symbols)")
        return f"stopped at length {n}: {why}; shorter words are complete"
    return (f"stopped at length {n} after {clock.seconds:g} seconds (max_seconds); "
            f"shorter words are complete")


def _rows_of(table, start, count: int) -> list[frozenset]:
    rows = table.get(start)
    if rows is None:
        return [frozenset() for _ in range(count)]
    return [frozenset(rows[n]) for n in range(count)]


def _sequence_words(rhs, n: int, words_of, yields, clock: Budget) -> set:
    """Words of length exactly ``n`` derivable from the symbol sequence ``rhs``.

    Built from the end of ``rhs`` backwards, one position at a time (no
    recursion, so a body of thousands of symbols is fine). Raises
    :class:`~psgs.errors.BoundReached` when ``clock``'s time runs out, or when the words kept
    (``clock.held``) and those built here would hold more than its ``max_symbols``.
    """
    k = len(rhs)
    suffix_min = [0] * (k + 1)
    for i in range(k - 1, -1, -1):
        s = rhs[i]
        one = 1 if isinstance(s, Terminal) else (INFINITE if isinstance(s, Query)
                                                 else yields.get(s, INFINITE))
        suffix_min[i] = suffix_min[i + 1] + one
    if suffix_min[0] > n:
        return set()
    # tails[m]: the words of length m derivable from rhs[i + 1:]; tail_symbols what they hold
    tails: dict[int, set] = {0: {()}}
    tail_symbols = 0
    work = 0
    for i in range(k - 1, -1, -1):
        clock.tick()
        here: dict[int, set] = {}
        here_symbols = 0
        low = int(suffix_min[i] - suffix_min[i + 1])
        # rhs[:i] takes at least suffix_min[0] - suffix_min[i] symbols of the n; the whole
        # body (i == 0) is asked for the words of length n alone
        top = n - int(suffix_min[0] - suffix_min[i])
        if i == k - 1:
            # the last symbol's words are taken as they are (the table's rows, kept and
            # counted already), not built again word by word: hashing a word costs its
            # length, and every length's were built again at every n (S -> a S: cubic)
            for m in range(n if i == 0 else low, top + 1):
                words = words_of(rhs[i], m)
                if words:
                    here[m] = words
            tails = here
            continue
        for m in range(n if i == 0 else int(suffix_min[i]), top + 1):
            out: set = set()
            # the lengths the tails have, not every split of m: a tail of one length (the
            # last symbol's) made each m a loop over m splits, and the enumeration cubic
            for rest, after in tails.items():
                n1 = m - rest
                if n1 < low:
                    continue
                work += 1
                for h in words_of(rhs[i], n1):
                    out.update(h + t for t in after)
                    work += len(after)
                    # read every few thousand words built or splits tried: one position's
                    # products can be millions of words (S -> SS | aSb | ε)
                    if work >= _WORDS_PER_READING:
                        work = 0
                        _within(clock, tail_symbols + here_symbols
                                + len(out) * (m + WORD_OVERHEAD))
                if work >= _WORDS_PER_READING:  # splits that built nothing count too
                    work = 0
                    _within(clock, tail_symbols + here_symbols + len(out) * (m + WORD_OVERHEAD))
            if out:
                here[m] = out
                here_symbols += len(out) * (m + WORD_OVERHEAD)
        tails, tail_symbols = here, here_symbols
    return tails.get(n, set())


def _within(clock: Budget, building: int) -> None:
    """BoundReached when the time is up, or when the words kept and the ``building`` symbols
    of those being built pass the memory bound (a word counted as its symbols and
    :data:`WORD_OVERHEAD`)."""
    clock.check()
    if clock.max_symbols is not None and clock.held + building > clock.max_symbols:
        raise BoundReached("max_symbols")


# ---------------------------------------------------------------- entry point
def language(system, max_length: int, *, max_configurations: int = 200_000,
             max_form_length: int = 1_000, max_candidates: int = 100_000,
             max_words: int = 1_000_000, max_seconds: float | None = 60.0,
             max_symbols: int = MAX_SYMBOLS, method: str | None = None,
             **membership_options) -> Language:
    """Enumerate the language of ``system`` up to size ``max_length``, in order of size.

    * :class:`~psgs.model.PSGS`: the terminal tuples whose total length is at
      most ``max_length``. ``method`` is ``"search"`` (breadth-first over
      configurations, bounded by ``max_configurations`` and by
      ``max_form_length``, the longest sentential form it keeps: ε-rules let
      forms grow without adding terminals) or ``"filter"``
      (component words by length, kept when :func:`psgs.membership.accepts`
      accepts the tuple; bounded by ``max_words`` and ``max_candidates``; the
      remaining keyword arguments go to ``accepts``). The default is
      ``"search"`` in ``parallel`` mode and ``"filter"`` in ``single`` mode.
    * :class:`~psgs.model.PCGS`: the master's terminal words of length at
      most ``max_length`` (search only).
    * :class:`~psgs.model.Grammar`: its context-free words up to
      ``max_length`` (the component taken alone; query symbols derive nothing).

    ``max_seconds`` (default 60; ``None``: no limit) bounds the wall-clock
    time of the whole call, grammar analysis included (in the filter each
    ``accepts`` call gets the time left as its own ``max_seconds``).
    ``max_symbols`` bounds memory: the configurations the search keeps,
    counted as configurations × form size in symbols, or the context-free words the filter
    and a grammar's enumeration keep and build, their symbols and :data:`WORD_OVERHEAD` a
    word (default
    :data:`psgs.membership.MAX_SYMBOLS`; each ``accepts`` call of the filter gets what the
    words leave). The other budgets are deterministic.

    Always terminates. When a budget stops it, ``complete`` is ``False``,
    ``bound`` is the budget's name, e.g. ``"max_configurations"``, and
    ``reason`` says it in words (``"stopped after 200000 configurations
    (max_configurations)"``).

    Parameters
    ----------
    system : PSGS, PCGS or Grammar
        The system (or one grammar) to enumerate.
    max_length : int
        The size bound: total length of a tuple (PSGS), length of a word otherwise.
    max_configurations : int, default 200_000
        Search: at most this many configurations explored.
    max_form_length : int, default 1_000
        Search: sentential forms longer than this are not kept.
    max_candidates : int, default 100_000
        Filter: at most this many candidate tuples checked.
    max_words : int, default 1_000_000
        Filter: at most this many component words listed.
    max_seconds : float or None, default 60.0
        Wall-clock budget (None: none).
    max_symbols : int, optional
        Budget of memory: the configurations the search keeps times their size in symbols;
        the words the context-free enumeration keeps and builds, their symbols and
        :data:`WORD_OVERHEAD` a word.
    method : {None, "search", "filter"}
        PSGS only; None chooses by mode (see above).
    **membership_options
        Filter: ``max_states``, ``max_steps`` or ``check_witness``, passed to
        :func:`psgs.accepts`; any other name is a ValidationError.

    Returns
    -------
    Language
        Says whether it is complete and, if not, which bound stopped it.

    Raises
    ------
    ValidationError
        For an unknown method, a method that does not fit the system, or a budget that is not
        a positive whole number.

    Examples
    --------
    >>> from psgs import Grammar, Nonterminal, Rule, Terminal
    >>> S = Nonterminal("S")
    >>> g = Grammar("G", S, [Rule("r1", S, (Terminal("a"), S)), Rule("r2", S, ())])
    >>> [''.join(map(str, w)) for w in language(g, 3)]
    ['', 'a', 'aa', 'aaa']

    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> found = psgs.language(gamma, max_length=32)
    >>> found.complete, len(found)
    (True, 1)
    >>> ("abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad") in found
    True
    """
    check_count(max_length, "max_length", minimum=0)
    for name, value in (("max_configurations", max_configurations),
                        ("max_form_length", max_form_length),
                        ("max_candidates", max_candidates), ("max_words", max_words)):
        check_count(value, name)
    check_seconds(max_seconds, optional=True)
    check_count(max_symbols, "max_symbols")
    # checked here, not by the first accepts call: with no candidate tuple there is none, and
    # a misspelt budget would be ignored in silence
    for name, value in membership_options.items():
        if name not in _MEMBERSHIP_OPTIONS:
            raise ValidationError(f"unknown option {name!r}; language takes "
                                  f"{', '.join(_MEMBERSHIP_OPTIONS)} for accepts")
        if name != "check_witness":
            check_count(value, name)
    clock = Budget(max_seconds, max_symbols, every=32)
    if method not in (None, "search", "filter"):
        raise ValidationError(f"method must be 'search' or 'filter', not {method!r}")
    if isinstance(system, Grammar):
        return _grammar_language(system, max_length, max_words, clock)
    if isinstance(system, PCGS):
        if method == "filter":
            raise ValidationError("method 'filter' needs a PSGS; a PCGS is enumerated by search")
        found = pcgs_search(system, max_length, max_configurations, max_form_length, clock)
        words = sorted(found.found, key=_word_key)
        return Language(tuple(words), found.bound is None, found.bound, max_length, "search",
                        found.explored, reason=found.reason)
    if isinstance(system, PSGS):
        if method is None:
            method = "search" if system.mode == "parallel" else "filter"
        if method == "search":
            found = psgs_search(system, max_length, max_configurations, max_form_length, clock)
            words = sorted(found.found, key=_tuple_key)
            return Language(tuple(words), found.bound is None, found.bound, max_length,
                            "search", found.explored, "tuples", found.reason)
        return _psgs_filter(system, max_length, max_words, max_candidates, membership_options,
                            clock)
    raise ValidationError(f"expected a PSGS, a PCGS or a Grammar, not {type(system).__name__}")


#: What language hands on to :func:`psgs.accepts` (its own budgets cover the rest).
_MEMBERSHIP_OPTIONS = ("max_states", "max_steps", "check_witness")


def _grammar_language(grammar: Grammar, max_length: int, max_words: int,
                      clock: Budget) -> Language:
    rows, reason = _words_by_length(grammar, max_length, grammar.rules, grammar.start,
                                    max_words, clock)
    words = sorted((w for row in rows for w in row), key=_word_key)
    return Language(tuple(words), reason is None, _bound_name(reason), max_length,
                    "context-free", sum(len(r) for r in rows), reason=reason)


def _bound_name(sentence: str | None) -> str | None:
    """The budget a sentence names: the last ``max_…`` in it."""
    if sentence is None:
        return None
    found = re.findall(r"\b(max_[a-z_]+)\b", sentence)
    return found[-1] if found else None


# ---------------------------------------------------------------- PSGS
def _psgs_filter(system: PSGS, max_length: int, max_words: int, max_candidates: int,
                 membership_options: dict, clock: Budget) -> Language:
    usable = usable_rules(system)
    yields = [min_yields(rules) for rules in usable]
    floors = [y.get(g.start, INFINITE) for g, y in zip(system.components, yields)]
    if sum(floors) > max_length:
        return Language((), True, None, max_length, "filter", 0, "tuples")
    per_component: list[list[Word]] = []
    bounds: list[str] = []
    names: list[str] = []
    for g, rules, floor in zip(system.components, usable, floors):
        room = max_length - (sum(floors) - floor)
        rows, bound = _words_by_length(g, int(room), rules, g.start, max_words, clock)
        if bound:
            bounds.append(f"component {g.name}: {bound}")
            names.append(_bound_name(bound))
        per_component.append(sorted((w for row in rows for w in row), key=_word_key))

    candidates = 0
    accepted: list = []
    unknown: list = []
    stopped = None
    for words in _tuples_within(per_component, max_length):
        if candidates >= max_candidates:
            stopped = f"stopped after {candidates} candidate tuples (max_candidates)"
            break
        if clock.expired():
            stopped = (budget_sentence("max_seconds", clock)
                       + f" ({candidates} candidate tuples checked)")
            break
        candidates += 1
        options = membership_options
        if clock.deadline is not None:  # one accepts call may not outlive language's budget
            options = {**membership_options, "max_seconds": clock.left()}
        if clock.max_symbols is not None:  # nor hold more than the component words leave
            options = {**options, "max_symbols": max(1, clock.max_symbols - clock.held)}
        answer = accepts(system, words, **options)
        verdict = getattr(answer, "answer", "yes" if answer else "no")
        if verdict == "yes":
            accepted.append(words)
        elif verdict != "no":
            unknown.append(answer)
    if unknown:
        first = unknown[0]
        bounds.append(f"membership answered unknown for {len(unknown)} candidate tuples"
                      + (f" ({first.reason})" if first.reason else ""))
        names.append(first.bound)
    if stopped:
        bounds.append(stopped)
        names.insert(0, _bound_name(stopped))  # what stopped the loop comes first
    accepted.sort(key=_tuple_key)
    reason = "; ".join(bounds) if bounds else None
    return Language(tuple(accepted), reason is None, names[0] if names else None, max_length,
                    "filter", candidates, "tuples", reason)


def _tuples_within(per_component: Sequence[Sequence[Word]], max_length: int) -> Iterator:
    """Every choice of one word per component with total length ≤ max_length."""
    shortest = [min((len(w) for w in ws), default=None) for ws in per_component]
    if any(s is None for s in shortest):
        return
    rest_min = [0] * (len(per_component) + 1)
    for i in range(len(per_component) - 1, -1, -1):
        rest_min[i] = rest_min[i + 1] + shortest[i]

    def extend(i: int, budget: int, prefix: tuple):
        if i == len(per_component):
            yield prefix
            return
        for w in per_component[i]:  # sorted by length, so stop at the first too long
            if len(w) + rest_min[i + 1] > budget:
                break
            yield from extend(i + 1, budget - len(w), prefix + (w,))

    yield from extend(0, max_length, ())


