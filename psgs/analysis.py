"""Grammar analysis: the facts about rules and systems that every search needs.

Plain functions over :mod:`psgs.model` values (and over plain graphs), each
near-linear in the size of the grammar, so that analysing a grammar of
thousands of rules costs no more than reading it:

* :func:`min_yields` -- each nonterminal's least terminal yield (Knuth's
  generalisation of Dijkstra's algorithm, not a Bellman-Ford fixpoint);
* :func:`reachable` and :func:`strongly_connected` -- graph walks on an
  explicit stack (no recursion limit);
* :func:`usable_rules` -- the rules a PSGS can apply (all of them under
  ``free``, those in some tuple under ``strict``);
* :func:`moves` -- what a PSGS step may apply: the tuples of M, then (under
  ``free``) every unsynchronised rule alone as ``(#, …, p, …, #)``.
"""

from __future__ import annotations

import heapq
import math
from collections.abc import Callable, Hashable, Iterable, Mapping, Sequence

from .errors import ValidationError
from .model import IDLE, PSGS, Nonterminal, Query, Rule, SyncTuple, Terminal

__all__ = ["min_yields", "least_sums", "reachable", "strongly_connected", "usable_rules",
           "moves"]

INFINITE = math.inf


def _successors_of(graph) -> Callable[[Hashable], Iterable[Hashable]]:
    if callable(graph):
        return graph
    if isinstance(graph, Mapping):
        return lambda node: graph.get(node, ())
    return graph.__getitem__


def reachable(graph, sources: Iterable[Hashable], *, strict: bool = False) -> set:
    """The nodes reachable from ``sources`` in ``graph``.

    ``graph`` maps a node to its successors: a mapping, a sequence indexed by
    node, or a function. With ``strict=False`` the sources count as reached
    (zero steps); with ``strict=True`` only nodes reached by at least one
    edge do, so a source is in the answer exactly when it lies on a cycle or
    another source reaches it.

    Examples
    --------
    >>> sorted(reachable({1: [2], 2: [3], 3: [], 4: [1]}, [1]))
    [1, 2, 3]
    >>> sorted(reachable({1: [2], 2: [1], 3: [1]}, [3], strict=True))
    [1, 2]
    """
    successors = _successors_of(graph)
    seen: set = set()
    todo: list = []
    for s in sources:
        if strict:
            todo.extend(successors(s))
        elif s not in seen:
            seen.add(s)
            todo.append(s)
    if strict:
        todo = [t for t in todo if not (t in seen or seen.add(t))]
    while todo:
        for y in successors(todo.pop()):
            if y not in seen:
                seen.add(y)
                todo.append(y)
    return seen


def strongly_connected(nodes: Sequence[Hashable], graph) -> list[list]:
    """The strongly connected components of ``graph``, each successor component first.

    Tarjan's algorithm on an explicit stack. The list is in reverse
    topological order: every edge leads into the same component or into one
    listed earlier, so a bottom-up pass over it sees each component after
    everything it depends on.

    Examples
    --------
    >>> strongly_connected([1, 2, 3], {1: [2], 2: [1, 3], 3: []})
    [[3], [1, 2]]
    """
    successors = _successors_of(graph)
    index: dict = {}
    low: dict = {}
    on_stack: set = set()
    stack: list = []
    out: list[list] = []
    for root in nodes:
        if root in index:
            continue
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        work = [(root, iter(successors(root)))]
        while work:
            v, it = work[-1]
            for w in it:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on_stack.add(w)
                    work.append((w, iter(successors(w))))
                    break
                if w in on_stack and index[w] < low[v]:
                    low[v] = index[w]
            else:
                work.pop()
                if work:
                    parent = work[-1][0]
                    if low[v] < low[parent]:
                        low[parent] = low[v]
                if low[v] == index[v]:
                    component = []
                    while True:
                        w = stack.pop()
                        on_stack.discard(w)
                        component.append(w)
                        if w == v:
                            break
                    out.append(sorted(component, key=index.__getitem__))
    return out


def least_sums(rules: Sequence[tuple[Hashable, Sequence[Hashable], float]]) -> dict:
    """The least value of each head when a rule's value is its constant plus its items' values.

    ``rules`` are ``(head, items, constant)``: the head can be had for
    ``constant`` plus the value of every item (with repetition). Heads never
    derivable are absent from the answer. Knuth's generalisation of
    Dijkstra's algorithm: each head is settled once, in order of value, so
    the cost is O(R log R) in the total size R of the rules, where a
    round-by-round fixpoint is quadratic on a long chain.

    Examples
    --------
    ``S`` costs 1 plus two ``A``; ``A`` costs 2 (or one ``S``, which is dearer):

    >>> least_sums([("S", ["A", "A"], 1), ("A", [], 2), ("A", ["S"], 0)])
    {'A': 2, 'S': 5}
    """
    waiting = []
    partial = []
    uses: dict = {}
    heap: list = []
    for k, (head, items, constant) in enumerate(rules):
        waiting.append(len(items))
        partial.append(constant)
        for x in items:
            uses.setdefault(x, []).append(k)
        if not items and constant < INFINITE:
            heap.append((constant, k, head))
    heapq.heapify(heap)
    value: dict = {}
    while heap:
        v, _, head = heapq.heappop(heap)
        if head in value:
            continue
        value[head] = v
        for k in uses.get(head, ()):
            partial[k] += v
            waiting[k] -= 1
            if waiting[k] == 0 and partial[k] < INFINITE and rules[k][0] not in value:
                heapq.heappush(heap, (partial[k], k, rules[k][0]))
    return value


def min_yields(rules: Iterable[Rule], *, query_yield: float = INFINITE) -> dict:
    """Each nonterminal's minimum terminal yield under ``rules`` (``math.inf`` if unproductive).

    A query symbol yields ``query_yield``: infinite for a grammar taken alone
    (it derives no word on its own), 0 as a sound lower bound inside a PCGS.

    Examples
    --------
    >>> from psgs.model import Nonterminal as N, Rule, Terminal as T
    >>> S, A = N("S"), N("A")
    >>> min_yields([Rule("r", S, (T("a"), A, A)), Rule("q", A, (T("b"),)), Rule("e", A, (S,))])
    {Nonterminal(name='S'): 3, Nonterminal(name='A'): 1}
    """
    rules = tuple(rules)
    best: dict[Nonterminal, float] = {}
    encoded = []
    for r in rules:
        best.setdefault(r.lhs, INFINITE)
        items = []
        constant = 0
        for s in r.rhs:
            if s.__class__ is Terminal:
                constant += 1
            elif s.__class__ is Query:
                constant += query_yield
            else:
                best.setdefault(s, INFINITE)
                items.append(s)
        encoded.append((r.lhs, items, constant))
    best.update(least_sums(encoded))
    return best


def usable_rules(system: PSGS) -> tuple[tuple[Rule, ...], ...]:
    """Per component, the rules a derivation can apply.

    Under ``free`` every rule; under ``strict`` only the rules that appear in
    some tuple of M (a rule in no tuple can never fire).

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> [len(rules) for rules in usable_rules(gamma)]
    [8, 8, 6, 8]
    """
    _require_psgs(system, "usable_rules")
    if system.unsynchronised == "free":
        return tuple(g.rules for g in system.components)
    return tuple(tuple(r for r in g.rules if r in synced)
                 for g, synced in zip(system.components, system.synchronised_rules))


def moves(system: PSGS) -> tuple[SyncTuple, ...]:
    """What one PSGS step may apply, in the order every search tries them.

    The tuples of M in order, then (under ``free``) each unsynchronised rule
    alone as ``(#, …, p, …, #)``, by component and rule order (the free mode of unsynchronised rules).

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> from psgs.notation import show_tuple
    >>> [show_tuple(move) for move in moves(gamma)][:2]
    ['(S1a, S2a, S3a, S4a)', '(S1b, S2b, S3b, S4b)']
    >>> len(moves(gamma)) - len(gamma.sync)      # the unsynchronised rules, each alone
    2
    """
    _require_psgs(system, "moves")
    out = list(system.sync)
    if system.unsynchronised == "free":
        n = len(system.components)
        for i, rules in enumerate(system.unsynchronised_rules):
            for rule in rules:
                out.append(tuple(rule if j == i else IDLE for j in range(n)))
    return tuple(out)


def _require_psgs(system: object, what: str) -> None:
    if not isinstance(system, PSGS):  # a PCGS has no sync tuples: an AttributeError deep in
        raise ValidationError(f"{what} takes a PSGS, not {type(system).__name__}")
