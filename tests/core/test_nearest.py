"""psgs.nearest against a brute-force oracle: enumerate L(Γ) to a length bound, least summed edit distance."""

from __future__ import annotations

import itertools

import pytest
from hypothesis import HealthCheck, assume, given, settings, strategies as st

import psgs.strategies as pst
from psgs.enumeration import language
from psgs.membership import accepts, nearest
from psgs.membership.costs import apply_edits, edit_costs
from psgs.membership.nearest import _all_costs, _edit_distance
from psgs.model import Terminal

ALPHABET = ("a", "b")
INPUT_ALPHABET = ("a", "b", "z")  # z is in no system: it must be deleted or substituted
MAX_LANGUAGE = 7
PROPERTY = settings(max_examples=40, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much])


def word_tuples(components: int):
    word = st.lists(st.sampled_from(INPUT_ALPHABET), max_size=2).map(tuple)
    return st.tuples(*[word] * components)


def oracle(members, words, costs):
    """Least total cost over the enumerated tuples (None when there are none)."""
    best = None
    for u in members:
        d = sum(_edit_distance(w, v, costs) for w, v in zip(words, u))
        if best is None or d < best:
            best = d
    return best


def check_against_oracle(system, words, costs=None):
    table = edit_costs(costs)
    lang = language(system, MAX_LANGUAGE, method="search", max_configurations=5_000)
    assume(lang.complete)
    words = tuple(tuple(Terminal(x) for x in w) for w in words)
    members = list(lang.words)
    result = nearest(system, words, costs=costs, max_states=20_000, max_seconds=20)
    assert result.exact, result
    # a tuple longer than the enumeration bound needs at least this many insertions
    floor = (MAX_LANGUAGE + 1 - sum(map(len, words))) * min(
        [table.insert, *table.insert_symbol.values()])
    expected = oracle(members, words, table)
    if expected is not None and expected <= floor:
        assert result.distance == pytest.approx(expected, rel=1e-12), (words, result)
    elif result.distance is not None:
        assert result.distance >= floor - 1e-9
        assert expected is None or result.distance <= expected + 1e-9
    if result.distance is None:
        assert expected is None
        return result
    member = bool(accepts(system, words, max_states=20_000))
    if min(_all_costs(table)) > 0:
        assert (result.distance == 0) == member
    else:  # free edits can reach a member at no cost
        assert result.distance == 0 or not member
    check_witness(words, result, table)
    return result


def check_witness(words, result, table) -> None:
    """The witness derives the nearest words; the edit scripts turn the input into them, at
    the costs ``table`` (:func:`~psgs.membership.costs.edit_costs`) adding up to the distance."""
    assert result.witness.words == result.words
    assert result.witness.is_terminal
    total = 0
    for w, u, script in zip(words, result.words, result.edits):
        assert apply_edits(w, script) == u
        assert sum(e.cost for e in script) == pytest.approx(_edit_distance(w, u, table))
        total += sum(e.cost for e in script)
    assert total == pytest.approx(result.distance)


@pytest.mark.parametrize("mode", ["parallel", "single"])
@pytest.mark.parametrize("policy", ["free", "strict"])
def test_nearest_equals_the_oracle(mode, policy):
    seen = []

    @PROPERTY
    @given(st.data())
    def check(data):
        system = data.draw(pst.psgs_systems(max_components=2, mode=mode, unsynchronised=policy,
                                            max_rules=4, max_rhs=2, alphabet=ALPHABET))
        words = data.draw(word_tuples(len(system.components)))
        result = check_against_oracle(system, words)
        seen.append(result.distance)

    check()
    assert sum(d is not None for d in seen) >= 8, "too few drawn systems had a tuple"
    assert any(d is not None and d > 0 for d in seen), "no drawn input needed an edit"


@PROPERTY
@given(st.data())
def test_nearest_with_costs_equals_the_oracle(data):
    system = data.draw(pst.psgs_systems(max_components=2, max_rules=4, max_rhs=2,
                                        alphabet=ALPHABET))
    words = data.draw(word_tuples(len(system.components)))
    # costs that are no binary fractions too: their sums in different orders differ in the
    # last place (0.4 + 0.2 > 0.6), which every comparison of costs must allow for
    number = st.sampled_from([0, 0.1, 0.5, 0.7, 1, 2, 3.2])
    costs = {"insert": data.draw(number), "delete": data.draw(number),
             "substitute": data.draw(number), "pairs": {("a", "b"): data.draw(number)}}
    result = check_against_oracle(system, words, costs)
    if result is not None and result.distance is not None:  # within max_errors = the distance
        within = nearest(system, words, costs=costs, max_errors=result.distance,
                         max_states=20_000, max_seconds=20)
        assert within.exact and within.distance == pytest.approx(result.distance, rel=1e-12), within


@PROPERTY
@given(st.sampled_from(["parallel", "single"]), st.data())
def test_gamma_one_edit_is_distance_one(mode, data):
    import dataclasses

    from test_membership import gamma

    system = dataclasses.replace(gamma(), mode=mode)
    blocks = ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad"]
    c = data.draw(st.integers(0, 3))
    p = data.draw(st.integers(0, 7))
    op = data.draw(st.sampled_from(["insert", "delete", "substitute"]))
    word = list(blocks[c])
    if op == "insert":
        word.insert(p, data.draw(st.sampled_from("abcdz")))
    elif op == "delete":
        del word[p]
    else:
        word[p] = data.draw(st.sampled_from([x for x in "abcdz" if x != word[p]]))
    words = list(blocks)
    words[c] = "".join(word)
    result = nearest(system, words)
    expected = 0 if words == blocks else 1  # an insertion next to an equal symbol may be undone
    assert result.exact and result.distance == expected
    assert result.witness.words == result.words
    assert apply_edits(tuple(Terminal(x) for x in words[c]), result.edits[c]) == result.words[c]


def test_synchronisation_can_cost_more_than_the_components():
    """(aⁿ, bⁿ): each word alone is in its component's language, the pair needs n equal."""
    from psgs.format import load
    from pathlib import Path

    counting = load(Path(__file__).parents[2] / "grammars" / "counting.psgs")
    result = nearest(counting, ["aaaa", "bb"])
    assert result.exact and result.distance == 2
    assert len(result.words[0]) == len(result.words[1])
    assert accepts(counting, result.words)


@pytest.mark.parametrize("dear", [10, 10**3, 10**6])
def test_a_cheap_edit_dwarfed_by_the_needed_ones_does_not_slow_the_rounds(dear):
    """Substitutions at 1, insertions and deletions at ``dear``: (aa, b) needs one of the
    dear edits. The rounds raised the cap one least cost at a time, exploring nothing, so
    10**6 ran into max_seconds instead of answering."""
    from psgs.format import load
    from pathlib import Path

    counting = load(Path(__file__).parents[2] / "grammars" / "counting.psgs")
    costs = {"insert": dear, "delete": dear, "substitute": 1}
    result = nearest(counting, ["aa", "b"], costs=costs, max_seconds=5)
    assert result.exact and result.distance == dear
    assert accepts(counting, result.words)
    members = list(language(counting, 6, method="search").words)
    words = (tuple(map(Terminal, "aa")), (Terminal("b"),))
    assert result.distance == oracle(members, words, edit_costs(costs))


THREE_A_OR_B_RUNS = """psgs X
mode parallel
unsynchronised free

component G0 start S
  s0: S -> A A A
  s1: S -> B B
  a1: A -> "a"
  b0: B -> "a" B
  b1: B -> "b" "b" "b"
"""


@pytest.mark.parametrize("max_errors", [None, 7.6, 7.7, 100])
def test_a_distance_equal_to_the_cap_is_found_though_its_sums_round(max_errors):
    """Deleting b (0.1) and inserting aaa (2.5 each) costs 7.6 exactly, as much as the cap
    the component's distance is computed up to; the chart summed 2.6 + 2.5 + 2.5 against
    7.6 - 5.0, a hair less than 2.6, and read 7.6 as over the cap: a TypeError without
    max_errors, and with max_errors=100 an exact answer that no tuple is within it."""
    from psgs.format import loads

    system = loads(THREE_A_OR_B_RUNS)
    costs = {"insert": 2.5, "delete": 0.1, "substitute": 3.2}
    result = nearest(system, ["b"], costs=costs, max_errors=max_errors, max_seconds=5)
    assert result.exact and result.distance == pytest.approx(7.6)
    assert [t.name for t in result.words[0]] == ["a", "a", "a"]


def test_components_summed_a_hair_over_max_errors_are_within_it():
    """(aa) and () cost 0.4 + 0.2 = 0.6000000000000001 summed per component, 0.6 as the
    search sums the tuple's edits: max_errors=0.6 answered that no tuple is within it."""
    from psgs.format import loads

    system = loads('psgs X\nmode parallel\nunsynchronised free\n\ncomponent G1 start S1\n'
                   '  r11: S1 -> "a" "a"\n\ncomponent G2 start S2\n  r12: S2 ->\n')
    costs = {"insert": 0.2, "delete": 0.1, "substitute": 0.1}
    result = nearest(system, ["", "aa"], costs=costs, max_errors=0.6, max_seconds=5)
    assert result.exact and result.distance == pytest.approx(0.6)


TWO_WAYS_IN_STEP = """psgs X
mode parallel
unsynchronised strict

component G1 start S1
  p: S1 -> A1
  p2: S1 -> "a"
  a1: A1 -> "a"
  b1: A1 -> "b"

component G2 start S2
  q: S2 -> "c" T2
  q2: S2 -> "d"
  t: T2 ->

sync
  (p, q)
  (p2, q2)
  (b1, t)
  (a1, q)
"""


@pytest.mark.parametrize("big, small", [(10**9, 1), (10**12, 1), (1e6, 1e-6), (1e3, 1e-7),
                                        (1e-10, 1e-10), (1e-12, 1e-12)])
def test_costs_a_least_cost_apart_are_told_apart_at_any_size(big, small):
    """(a, c) becomes (a, d) at big + small or (b, c) at big + 2 small, in step. A tolerance
    of 1e-9 of the cap took the second for the first at 10**9 + 1 and 10**9 + 2 (and an
    absolute 1e-9 below 1 did at costs of 1e-10): the dearer answered, exactly."""
    from psgs.format import loads

    system = loads(TWO_WAYS_IN_STEP)
    costs = {"insert": 10 * big, "delete": 10 * big, "substitute": 10 * big,
             "pairs": {("a", "b"): big + 2 * small, ("c", "d"): big + small}}
    for max_errors in (None, big + small):
        result = nearest(system, ["a", "c"], costs=costs, max_errors=max_errors, max_seconds=5)
        assert result.exact and result.distance == big + small, result
        assert ["".join(t.name for t in w) for w in result.words] == ["a", "d"]


def test_a_round_that_finds_the_cheapest_tuple_ends_the_search():
    """A found tuple bounds the round a little under its cost; what the round cut then lay
    a hair under it (insertions at 0.1), the search read it as possibly cheaper and ran its
    rounds again at the same cap until max_states."""
    from psgs.format import loads

    system = loads('psgs X\nmode parallel\nunsynchronised free\n\ncomponent G1 start S1\n'
                   '  r11: S1 ->\n\ncomponent G2 start S2\n  r12: S2 ->\n'
                   '  r22: S2 -> S2 "a" S2\n')
    costs = {"insert": 0.1, "delete": 1, "substitute": 0.7}
    result = nearest(system, ["", "ab"], costs=costs, max_states=2_000, max_seconds=5)
    assert result.exact and result.distance == pytest.approx(0.8), result
    assert result.states < 100


def test_a_least_cost_far_under_the_distance_does_not_make_a_round_of_each():
    """Substituting a for b at 1e-6 beside edits at 0.1: the states' costs take so many
    values under 0.1 that rounds raised one least cost at a time stopped at max_states."""
    from psgs.format import loads

    system = loads('psgs X\nmode parallel\nunsynchronised free\n\ncomponent G1 start S1\n'
                   '  r11: S1 ->\n  r21: S1 -> "a" S1 S1\n')
    costs = {"insert": 0.1, "delete": 0.1, "substitute": 0.1, "pairs": {("a", "b"): 1e-6}}
    result = nearest(system, ["aa"], costs=costs, max_states=20_000, max_seconds=5)
    assert result.exact and result.distance == pytest.approx(0.1, rel=1e-12), result
    assert result.states < 1_000


def test_rounds_that_never_explore_keep_a_finite_cap_until_the_time_bound():
    """A language empty in a way the analysis does not see: (p, q) finishes H, and then no
    tuple applies, so no round explores a state. Doubled without end, the cap's raise
    overflowed to inf and the charts computed with nan (a ValueError at once)."""
    from psgs.format import loads

    system = loads('''psgs R
mode single
unsynchronised strict
component G start S
  p: S -> S A
  e: S -> ε
component H start S
  q: S -> "a" "a"
  r: A -> "b" S
sync
  (e, r)
  (p, q)
''')
    result = nearest(system, ["", ""], max_seconds=0.5)
    assert result.distance is None and not result.exact and result.bound == "max_seconds"
    assert 0 < result.lower_bound < float("inf")


def test_all_tuples_small_exhaustive():
    """Every input up to length 3 for Γ's one-block prefix shape: distance 0 iff accepted."""
    from test_membership import gamma

    system = gamma()
    blocks = ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad"]
    for k, sub in itertools.product(range(4), ["", "a", "ab"]):
        words = list(blocks)
        words[k] = words[k][:4] + sub
        result = nearest(system, words)
        assert result.exact and (result.distance == 0) == bool(accepts(system, words))


@PROPERTY
@given(st.data())
def test_error_chart_is_the_context_free_distance(data):
    """The chart's cost (the search's estimate) equals the brute-force distance to L(G) alone."""
    from psgs.membership.chart import CompiledGrammar
    from psgs.membership.error_chart import ErrorChart

    grammar = data.draw(pst.grammars(max_rules=5, max_rhs=3, alphabet=ALPHABET))
    word = data.draw(st.lists(st.sampled_from(INPUT_ALPHABET), max_size=4))
    lang = language(grammar, MAX_LANGUAGE, max_configurations=5_000)
    assume(lang.complete)
    table = edit_costs(None)
    ids = {Terminal("a"): 0, Terminal("b"): 1}
    cg = CompiledGrammar(grammar, ids)
    ws = [ids.get(Terminal(x), 2) for x in word]
    chart = ErrorChart(cg, ws, [1, 1], [1] * len(ws), lambda p, t: 0 if ws[p] == t else 1)
    got = chart.cost(cg.index[grammar.start], 0, len(ws), cap=50)
    w = tuple(Terminal(x) for x in word)
    expected = min((_edit_distance(w, u, table) for u in lang.words), default=None)
    floor = MAX_LANGUAGE + 1 - len(word)
    if expected is not None and expected <= floor:
        assert got == expected
    else:
        assert got >= min(floor, expected if expected is not None else floor)
