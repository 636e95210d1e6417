"""Hypothesis strategies for grammar systems, for users who property-test them.

``import psgs`` does not import hypothesis; ``import psgs.strategies`` does
(hypothesis is in the ``test`` extra).

Every strategy draws values that are valid by construction (the model
validates them as they are built) and shrinks towards small readable ones:
sizes are drawn first, the alphabet is ``a``, ``b``, ... and nonterminals are
``S``, ``A``, ``B``, ... (suffixed by the component number inside a system:
``S1``, ``A1``, ``S2``...). Every nonterminal of a drawn grammar is productive:
its first rule uses only terminals and later nonterminals.

>>> from hypothesis import given, settings
>>> import psgs.strategies as pst
>>> @settings(max_examples=25)
... @given(pst.psgs_systems(max_components=2))
... def test_has_axioms(system):
...     assert len(system.axioms) == len(system.components)
>>> test_has_axioms()
"""

from __future__ import annotations

import functools
import numbers
from collections.abc import Sequence

from hypothesis import strategies as st
from hypothesis.errors import InvalidArgument

from .model import PCGS, PSGS, Grammar, Nonterminal, Query, Rule, Terminal

__all__ = [
    "terminals", "nonterminals", "symbols", "grammars", "psgs_systems", "pcgs_systems",
    "derivations", "derivable_words", "near_misses", "actiongrams", "MAX_SIZE",
]

DEFAULT_ALPHABET = ("a", "b", "c")
DEFAULT_NAMES = ("S", "A", "B", "C", "D", "E")
#: The largest size a strategy draws up to (components, rules, strings, steps...): a size of
#: None or 10**9 drew until memory ran out.
MAX_SIZE = 1_000_000


def _sizes(**sizes) -> None:
    """Each ``name=(value, least)`` a whole number from ``least`` to :data:`MAX_SIZE`, else
    hypothesis's InvalidArgument naming it (raised when the strategy first draws, as
    hypothesis's own strategies check theirs)."""
    for name, (value, least) in sizes.items():
        if isinstance(value, bool) or not isinstance(value, numbers.Integral) \
                or not least <= value <= MAX_SIZE:
            raise InvalidArgument(f"{name} must be a whole number from {least} to {MAX_SIZE}, "
                                  f"not {value!r}")


def _names(name: str, value) -> tuple[str, ...]:
    """The strings ``tuple()`` reads from ``value`` (a string: its characters; a set, a numpy
    array, dict keys...), at least one."""
    try:
        names = tuple(value)
    except TypeError:
        names = ()
    if not names or not all(isinstance(v, str) for v in names):
        raise InvalidArgument(f"{name} must be a non-empty sequence of strings, not {value!r}")
    return names


def terminals(alphabet: Sequence[str] = DEFAULT_ALPHABET) -> st.SearchStrategy[Terminal]:
    """One :class:`Terminal` from ``alphabet`` (shrinks towards the first letter).

    Parameters
    ----------
    alphabet : sequence of str, default ("a", "b", "c")
        The names to draw from.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of Terminal

    Examples
    --------
    >>> from hypothesis import find
    >>> find(terminals(), lambda t: True)
    Terminal(name='a')
    >>> find(terminals(["x", "y"]), lambda t: t.name != "x")
    Terminal(name='y')
    """
    return st.sampled_from(tuple(alphabet)).map(Terminal)


def nonterminals(names: Sequence[str] = DEFAULT_NAMES) -> st.SearchStrategy[Nonterminal]:
    """One :class:`Nonterminal` from ``names`` (shrinks towards the first name).

    Parameters
    ----------
    names : sequence of str, default ("S", "A", "B", "C", "D", "E")
        The names to draw from.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of Nonterminal

    Examples
    --------
    >>> from hypothesis import find
    >>> find(nonterminals(), lambda n: True)
    Nonterminal(name='S')
    """
    return st.sampled_from(tuple(names)).map(Nonterminal)


def symbols(alphabet: Sequence[str] = DEFAULT_ALPHABET,
            names: Sequence[str] = DEFAULT_NAMES) -> st.SearchStrategy:
    """A terminal or a nonterminal (terminals first, so examples shrink to words).

    Parameters
    ----------
    alphabet : sequence of str, default ("a", "b", "c")
        Names of the terminals.
    names : sequence of str, default ("S", "A", "B", "C", "D", "E")
        Names of the nonterminals.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of Terminal or Nonterminal

    Examples
    --------
    >>> from hypothesis import find
    >>> find(symbols(), lambda s: True)
    Terminal(name='a')
    >>> find(symbols(), lambda s: isinstance(s, Nonterminal))
    Nonterminal(name='S')
    """
    return st.one_of(terminals(alphabet), nonterminals(names))


@st.composite
def grammars(draw, *, name: str = "G", max_nonterminals: int = 3, max_rules: int = 5,
             max_rhs: int = 3, alphabet: Sequence[str] = ("a", "b"),
             allow_epsilon: bool = True, allow_unit: bool = True, suffix: str = "",
             queries: Sequence[str] = ()) -> Grammar:
    """A component grammar named ``name`` with axiom ``S`` + ``suffix``.

    ``max_nonterminals`` names are drawn from ``S, A, B, ...``; each gets one
    productive rule (terminals and later nonterminals only) and the grammar up
    to ``max_rules`` rules in all, bodies of at most ``max_rhs`` symbols.
    ``allow_epsilon`` / ``allow_unit`` allow ε-rules and rules ``A → B``.
    ``queries`` names components whose query symbols (``?name``) may appear in
    the extra rules (PCGS components); the productive rules never hold one.

    Parameters
    ----------
    name : str, default "G"
        The grammar's name.
    max_nonterminals : int, default 3
        At most this many nonterminals (at most 6: ``S, A, ..., E``).
    max_rules : int, default 5
        At most this many rules (at least one per nonterminal).
    max_rhs : int, default 3
        At most this many symbols on a right side.
    alphabet : sequence of str, default ("a", "b")
        Names of the terminals.
    allow_epsilon : bool, default True
        Whether a right side may be empty.
    allow_unit : bool, default True
        Whether a right side may be a single nonterminal.
    suffix : str, default ""
        Appended to every nonterminal name and rule label (``S1``, ``r11``).
    queries : sequence of str, default ()
        Names of components that the extra rules may query.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of Grammar

    Examples
    --------
    >>> from hypothesis import find
    >>> g = find(grammars(allow_epsilon=False), lambda g: len(g.rules) >= 2)
    >>> print(g.name, g.start.name, len(g.rules))
    G S 2
    >>> all(rule.rhs for rule in g.rules)
    True
    """
    _sizes(max_nonterminals=(max_nonterminals, 0), max_rules=(max_rules, 0),  # 0: clamped
           max_rhs=(max_rhs, 0))
    alphabet = _names("alphabet", alphabet)
    count = draw(st.integers(1, max(1, min(max_nonterminals, len(DEFAULT_NAMES)))))
    names = [Nonterminal(n + suffix) for n in DEFAULT_NAMES[:count]]
    min_rhs = 0 if allow_epsilon else 1

    queries, allow_unit = tuple(queries), bool(allow_unit)
    bodies: list[tuple[Nonterminal, tuple]] = []
    for index, lhs in enumerate(names):
        # productive by construction: only later nonterminals, the last one none
        rhs = draw(_bodies(alphabet, tuple(names[index + 1:]), (), min_rhs, max_rhs, allow_unit))
        bodies.append((lhs, rhs))
    extra = draw(st.integers(0, max(0, max_rules - count)))
    for _ in range(extra):
        lhs = draw(st.sampled_from(names))
        rhs = draw(_bodies(alphabet, tuple(names), queries, min_rhs, max_rhs, allow_unit))
        bodies.append((lhs, rhs))
    rules, seen = [], set()
    for lhs, rhs in bodies:
        if (lhs, rhs) in seen:
            continue
        seen.add((lhs, rhs))
        rules.append(Rule(f"r{len(rules) + 1}{suffix}", lhs, rhs))
    return Grammar(name, names[0], tuple(rules))


@functools.lru_cache(maxsize=256)
def _bodies(alphabet: tuple[str, ...], allowed_nts: tuple[Nonterminal, ...],
            queries: tuple[str, ...], min_rhs: int, max_rhs: int, allow_unit: bool):
    """The right sides :func:`grammars` draws, made once per shape: hypothesis reads the
    source of a filter's predicate each time a filter is made (to find a length bound in
    it), which re-read this file for every rule drawn. A strategy draws the same whether
    made now or then."""
    pool = [st.sampled_from(alphabet).map(Terminal)]
    if allowed_nts:
        pool.append(st.sampled_from(allowed_nts))
    if queries:
        pool.append(st.sampled_from(queries).map(Query))

    def acceptable(rhs: tuple) -> bool:
        if not allow_unit and len(rhs) == 1 and isinstance(rhs[0], Nonterminal):
            return False
        return True

    bodies = st.lists(st.one_of(*pool), min_size=min_rhs, max_size=max_rhs).map(tuple)
    return bodies.filter(acceptable)


@st.composite
def _tuples(draw, components: Sequence[Grammar], max_tuples: int):
    count = draw(st.integers(0, max_tuples))
    tuples, seen = [], set()
    for _ in range(count):
        entry = tuple(draw(st.one_of(st.none(), st.sampled_from(g.rules))) for g in components)
        if all(e is None for e in entry) or entry in seen:
            continue
        seen.add(entry)
        tuples.append(entry)
    return tuple(tuples)


@st.composite
def psgs_systems(draw, *, min_components: int = 1, max_components: int = 3,
                 mode: str | None = None, unsynchronised: str | None = None,
                 max_nonterminals: int = 3, max_rules: int = 4, max_rhs: int = 3,
                 max_tuples: int = 4, alphabet: Sequence[str] = ("a", "b"),
                 allow_epsilon: bool = True, allow_unit: bool = True) -> PSGS:
    """A :class:`PSGS` with ``min_components``..``max_components`` components.

    Component ``i`` is named ``G<i>`` with axiom ``S<i>``; up to ``max_tuples``
    synchronisation tuples pair random rules (or ``#``). ``mode`` and
    ``unsynchronised`` are drawn when left ``None``.

    Parameters
    ----------
    min_components : int, default 1
        Fewest components.
    max_components : int, default 3
        Most components.
    mode : {None, "parallel", "single"}
        The derivation mode; drawn when None.
    unsynchronised : {None, "free", "strict"}
        What a rule in no tuple may do; drawn when None.
    max_nonterminals : int, default 3
        Passed to :func:`grammars` for every component, like the next four.
    max_rules : int, default 4
    max_rhs : int, default 3
    alphabet : sequence of str, default ("a", "b")
    allow_epsilon : bool, default True
    allow_unit : bool, default True
        Passed to :func:`grammars` (with the five above).
    max_tuples : int, default 4
        At most this many synchronisation tuples.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of PSGS

    Examples
    --------
    >>> from hypothesis import find
    >>> system = find(psgs_systems(mode="single"), lambda s: len(s.components) == 2)
    >>> [g.name for g in system.components], system.mode
    (['G1', 'G2'], 'single')
    """
    _sizes(min_components=(min_components, 1), max_components=(max_components, min_components),
           max_tuples=(max_tuples, 0))
    n = draw(st.integers(min_components, max_components))
    components = tuple(
        draw(grammars(name=f"G{i}", suffix=str(i), max_nonterminals=max_nonterminals,
                      max_rules=max_rules, max_rhs=max_rhs, alphabet=alphabet,
                      allow_epsilon=allow_epsilon, allow_unit=allow_unit))
        for i in range(1, n + 1))
    sync = draw(_tuples(components, max_tuples))
    chosen_mode = mode or draw(st.sampled_from(("parallel", "single")))
    policy = unsynchronised or draw(st.sampled_from(("free", "strict")))
    return PSGS(components, sync, mode=chosen_mode, unsynchronised=policy)


@st.composite
def pcgs_systems(draw, *, min_components: int = 1, max_components: int = 3,
                 returning: bool | None = None, centralised: bool | None = None,
                 max_nonterminals: int = 3, max_rules: int = 4, max_rhs: int = 3,
                 alphabet: Sequence[str] = ("a", "b"), allow_epsilon: bool = True) -> PCGS:
    """A :class:`PCGS`; component ``G1`` is the master.

    When ``centralised`` is true only the master's rules hold query symbols;
    when false (or drawn false) any component may query any other one. A
    component never queries itself.

    Parameters
    ----------
    min_components : int, default 1
        Fewest components.
    max_components : int, default 3
        Most components.
    returning : bool or None, default None
        Returning (a queried component restarts from its axiom) or not; drawn when None.
    centralised : bool or None, default None
        Whether only the master may query; drawn when None.
    max_nonterminals : int, default 3
        Passed to :func:`grammars` for every component, like the next four.
    max_rules : int, default 4
    max_rhs : int, default 3
    alphabet : sequence of str, default ("a", "b")
    allow_epsilon : bool, default True

    Returns
    -------
    hypothesis.strategies.SearchStrategy of PCGS

    Examples
    --------
    >>> from hypothesis import find
    >>> system = find(pcgs_systems(returning=True), lambda s: len(s.components) == 2)
    >>> system.master, system.returning
    ('G1', True)
    """
    _sizes(min_components=(min_components, 1), max_components=(max_components, min_components))
    n = draw(st.integers(min_components, max_components))
    central = draw(st.booleans()) if centralised is None else centralised
    names = [f"G{i}" for i in range(1, n + 1)]
    components = []
    for i, name in enumerate(names, start=1):
        may_query = i == 1 or not central
        targets = tuple(x for x in names if x != name) if may_query else ()
        components.append(draw(grammars(
            name=name, suffix=str(i), max_nonterminals=max_nonterminals, max_rules=max_rules,
            max_rhs=max_rhs, alphabet=alphabet, allow_epsilon=allow_epsilon, queries=targets)))
    ret = draw(st.booleans()) if returning is None else returning
    return PCGS(tuple(components), returning=ret)


@st.composite
def derivations(draw, system, *, max_steps: int = 30, max_form_length: int = 40,
                terminal: bool = False):
    """A derivation of ``system`` (PSGS or PCGS), one drawn choice per step.

    Each step is drawn among :func:`psgs.derivation.applicable_steps`, so the
    derivation shrinks towards the first applicable step at each point and
    towards fewer steps. It stops when terminal, blocked, after ``max_steps``
    steps or when a form exceeds ``max_form_length`` symbols. With
    ``terminal=True`` only terminal derivations are drawn (others are
    rejected, so use it with systems that terminate easily).

    Parameters
    ----------
    system : PSGS or PCGS
        The system to derive in.
    max_steps : int, default 30
        At most this many steps.
    max_form_length : int, default 40
        Stop once a sentential form is longer than this.
    terminal : bool, default False
        Draw only derivations that end in terminal words.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of psgs.Derivation

    Examples
    --------
    >>> import psgs
    >>> from hypothesis import find
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> print(find(derivations(gamma), lambda d: len(d.steps) >= 1))
    (S1, S2, S3, S4) ⇒ (N13S1, N18S2, N7S3, N23S4)
    """
    from hypothesis import assume

    from .derivation import (Derivation, applicable_steps, initial_configuration,
                             is_terminal_configuration)

    _sizes(max_steps=(max_steps, 0))  # max_form_length only stops a derivation: any bound
    configuration = initial_configuration(system)
    steps = []
    length = draw(st.integers(0, max_steps))
    while len(steps) < length and not is_terminal_configuration(system, configuration):
        if max(len(f) for f in configuration) > max_form_length:
            break
        options = applicable_steps(system, configuration)
        if not options:
            break
        step = options[draw(st.integers(0, len(options) - 1))]
        steps.append(step)
        configuration = step.after
    derivation = Derivation(system, tuple(steps))
    if terminal:
        assume(derivation.is_terminal)
    return derivation


def derivable_words(system, *, max_steps: int = 30, max_form_length: int = 40):
    """``(words, derivation)`` pairs: terminal results of :func:`derivations` of ``system``.

    ``words`` is the tuple of words (PSGS) or the master's word (PCGS).

    Parameters
    ----------
    system : PSGS or PCGS
        The system to derive in (it should terminate easily: non-terminal
        derivations are rejected).
    max_steps : int, default 30
        Passed to :func:`derivations`.
    max_form_length : int, default 40
        Passed to :func:`derivations`.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of (tuple, psgs.Derivation)

    Examples
    --------
    >>> import psgs
    >>> from hypothesis import find
    >>> counting = psgs.load("grammars/counting.psgs")           # (aⁿ, bⁿ), n ≥ 1
    >>> words, derivation = find(derivable_words(counting), lambda pair: len(pair[0][0]) >= 2)
    >>> ["".join(t.name for t in w) for w in words]
    ['aa', 'bb']
    >>> bool(psgs.accepts(counting, words)), derivation.is_terminal
    (True, True)
    """
    return derivations(system, max_steps=max_steps, max_form_length=max_form_length,
                       terminal=True).map(lambda d: (d.words, d))


@st.composite
def near_misses(draw, system, words):
    """``words`` with one symbol changed, inserted or deleted in one component's word.

    These are *candidates* for non-members, not guaranteed non-members: the
    edited tuple may still be in the language (check with
    :func:`psgs.accepts`). Inserted and substituted symbols come from the
    system's terminals. ``words`` is one word per component (PSGS) or one
    word (PCGS).

    Parameters
    ----------
    system : PSGS or PCGS
        The system whose terminals are inserted or substituted.
    words : tuple of words, or a word
        One word per component (PSGS) or the master's word (PCGS); each word a
        string or a sequence of terminals.

    Returns
    -------
    hypothesis.strategies.SearchStrategy
        Of the edited words, in the shape of ``words`` (a word is a tuple of terminals).

    Examples
    --------
    >>> import psgs
    >>> from hypothesis import find
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> words = ("abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad")
    >>> edited = find(near_misses(gamma, words), lambda w: True)
    >>> sum(len(w) for w in edited) - sum(len(w) for w in words) in (-1, 0, 1)
    True
    >>> bool(psgs.accepts(gamma, edited))
    False
    """
    from .model import as_word

    alphabet = sorted(system.terminals) or [Terminal("a")]
    single = isinstance(system, PCGS)
    tuple_of_words = [as_word(words)] if single else [as_word(w) for w in words]
    c = draw(st.integers(0, len(tuple_of_words) - 1))
    w = list(tuple_of_words[c])
    kinds = ["insert"] + (["change", "delete"] if w else [])
    kind = draw(st.sampled_from(kinds))
    if kind == "insert":
        w.insert(draw(st.integers(0, len(w))), draw(st.sampled_from(alphabet)))
    elif kind == "delete":
        del w[draw(st.integers(0, len(w) - 1))]
    else:
        k = draw(st.integers(0, len(w) - 1))
        others = [t for t in alphabet if t != w[k]]
        if not others:
            del w[k]
        else:
            w[k] = draw(st.sampled_from(others))
    tuple_of_words[c] = tuple(w)
    return tuple_of_words[0] if single else tuple(tuple_of_words)


@st.composite
def actiongrams(draw, *, min_strings: int = 1, max_strings: int = 4, max_length: int = 12,
                alphabet: Sequence[str] = ("B", "G", "R", "Y"), durations: bool = True):
    """An :class:`psgs.Actiongram`: named strings with no symbol repeated twice in a row.

    Strings are named ``s1``, ``s2``, ...; lengths are drawn in
    ``1..max_length``; with ``durations`` each symbol gets a duration in 1..5.

    Parameters
    ----------
    min_strings : int, default 1
        Fewest strings.
    max_strings : int, default 4
        Most strings.
    max_length : int, default 12
        At most this many symbols in a string.
    alphabet : sequence of str, default ("B", "G", "R", "Y")
        The symbols (at least two for strings longer than one).
    durations : bool, default True
        Draw a whole-number duration per symbol; otherwise every duration is 1.

    Returns
    -------
    hypothesis.strategies.SearchStrategy of psgs.Actiongram

    Examples
    --------
    >>> from hypothesis import find
    >>> ag = find(actiongrams(min_strings=2), lambda ag: ag.total_symbols >= 3)
    >>> ag.names
    ('s1', 's2')
    >>> all(a != b for string in ag.symbols for a, b in zip(string, string[1:]))
    True
    """
    from .actiongram import Actiongram

    _sizes(min_strings=(min_strings, 0), max_strings=(max_strings, min_strings),
           max_length=(max_length, 1))
    alphabet = _names("alphabet", alphabet)
    count = draw(st.integers(min_strings, max_strings))
    strings, times = {}, {}
    for k in range(1, count + 1):
        length = draw(st.integers(1, max_length))
        symbols = [draw(st.sampled_from(alphabet))]
        for _ in range(length - 1):
            symbols.append(draw(st.sampled_from([a for a in alphabet if a != symbols[-1]])))
        strings[f"s{k}"] = symbols
        if durations:
            times[f"s{k}"] = [draw(st.integers(1, 5)) for _ in symbols]
    return Actiongram.from_strings(strings, durations=times if durations else None)
