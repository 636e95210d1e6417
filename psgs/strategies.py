"""Hypothesis strategies for grammar systems, for users who property-test them.

``import psgs`` does not import hypothesis; ``import psgs.strategies`` does
(hypothesis is in the ``test`` extra).

Every strategy draws values that are valid by construction (the model
validates them as they are built) and shrinks towards small readable ones:
sizes are drawn first, the alphabet is ``a``, ``b``, ... and nonterminals are
``S``, ``A``, ``B``, ... (suffixed by the component number inside a system:
``S1``, ``A1``, ``S2``...). Every nonterminal of a drawn grammar is productive:
its first rule uses only terminals and later nonterminals.

>>> from hypothesis import given
>>> import psgs.strategies as pst
>>> @given(pst.psgs_systems(max_components=2))
... def test_has_axioms(system):
...     assert len(system.axioms) == len(system.components)
>>> test_has_axioms()
"""

from __future__ import annotations

from collections.abc import Sequence

from hypothesis import strategies as st

from .model import PCGS, PSGS, Grammar, Nonterminal, Query, Rule, Terminal

__all__ = [
    "terminals", "nonterminals", "symbols", "grammars", "psgs_systems", "pcgs_systems",
    "near_misses",
]

DEFAULT_ALPHABET = ("a", "b", "c")
DEFAULT_NAMES = ("S", "A", "B", "C", "D", "E")


def terminals(alphabet: Sequence[str] = DEFAULT_ALPHABET) -> st.SearchStrategy[Terminal]:
    """One :class:`Terminal` from ``alphabet`` (shrinks towards the first letter)."""
    return st.sampled_from(tuple(alphabet)).map(Terminal)


def nonterminals(names: Sequence[str] = DEFAULT_NAMES) -> st.SearchStrategy[Nonterminal]:
    """One :class:`Nonterminal` from ``names`` (shrinks towards the first name)."""
    return st.sampled_from(tuple(names)).map(Nonterminal)


def symbols(alphabet: Sequence[str] = DEFAULT_ALPHABET,
            names: Sequence[str] = DEFAULT_NAMES) -> st.SearchStrategy:
    """A terminal or a nonterminal (terminals first, so examples shrink to words)."""
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
    """
    count = draw(st.integers(1, max(1, min(max_nonterminals, len(DEFAULT_NAMES)))))
    names = [Nonterminal(n + suffix) for n in DEFAULT_NAMES[:count]]
    alphabet = tuple(alphabet)
    min_rhs = 0 if allow_epsilon else 1

    def body(allowed_nts: list[Nonterminal], allow_queries: bool):
        pool = [st.sampled_from(alphabet).map(Terminal)]
        if allowed_nts:
            pool.append(st.sampled_from(allowed_nts))
        if allow_queries and queries:
            pool.append(st.sampled_from(tuple(queries)).map(Query))
        return st.lists(st.one_of(*pool), min_size=min_rhs, max_size=max_rhs).map(tuple)

    def acceptable(rhs: tuple) -> bool:
        if not allow_unit and len(rhs) == 1 and isinstance(rhs[0], Nonterminal):
            return False
        return True

    bodies: list[tuple[Nonterminal, tuple]] = []
    for index, lhs in enumerate(names):
        # productive by construction: only later nonterminals, the last one none
        rhs = draw(body(names[index + 1:], False).filter(acceptable))
        bodies.append((lhs, rhs))
    extra = draw(st.integers(0, max(0, max_rules - count)))
    for _ in range(extra):
        lhs = draw(st.sampled_from(names))
        rhs = draw(body(names, True).filter(acceptable))
        bodies.append((lhs, rhs))
    rules, seen = [], set()
    for lhs, rhs in bodies:
        if (lhs, rhs) in seen:
            continue
        seen.add((lhs, rhs))
        rules.append(Rule(f"r{len(rules) + 1}{suffix}", lhs, rhs))
    return Grammar(name, names[0], tuple(rules))


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
    """
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
    """
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
