"""The PSGS derivation engine: the semantics of docs/semantics.md (D1-D4), steps, derivations, random derivations."""

from __future__ import annotations

import dataclasses

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from psgs import IDLE, PSGS, Grammar, Nonterminal, Rule, Terminal, ValidationError
from psgs.derivation import (Derivation, applicable_steps, apply_tuple, initial_configuration,
                             random_derivation)
from psgs.enumeration import language
from psgs.notation import format_form
from psgs.steps import Step, random_step

S, A, B = Nonterminal("S"), Nonterminal("A"), Nonterminal("B")
S1, S2 = Nonterminal("S1"), Nonterminal("S2")
a, b, c = Terminal("a"), Terminal("b"), Terminal("c")


def w(text: str):
    return tuple(Terminal(ch) for ch in text)


def one_component(rules, mode="parallel", sync=None, unsynchronised="free"):
    g = Grammar("G", S, rules)
    sync = sync if sync is not None else []
    return PSGS((g,), sync=sync, mode=mode, unsynchronised=unsynchronised)


AA_RULES = [Rule("r1", S, (A, A)), Rule("r2", A, (a, A)), Rule("r3", A, (b,))]


# ---------------------------------------------------------------- D1 rewriting mode
def test_parallel_mode_rewrites_every_occurrence_at_once():
    system = one_component(AA_RULES, mode="parallel")
    config = ((A, A),)
    steps = applicable_steps(system, config)
    assert [s.after for s in steps] == [((a, A, a, A),), ((b, b),)]
    assert all(s.positions == ((0, 1),) for s in steps)


def test_single_mode_rewrites_one_occurrence_per_step():
    system = one_component(AA_RULES, mode="single")
    steps = applicable_steps(system, ((A, A),))
    assert [s.after for s in steps] == [((a, A, A),), ((A, a, A),), ((b, A),), ((A, b),)]
    assert [s.positions for s in steps] == [((0,),), ((1,),), ((0,),), ((1,),)]


def test_modes_give_different_languages_on_S_to_AA():
    """S → AA, A → aA | b: parallel gives {aⁿb aⁿb}, single gives {aⁿb aᵐb}."""
    parallel = language(one_component(AA_RULES, mode="parallel"), 6, method="search")
    single = language(one_component(AA_RULES, mode="single"), 6, method="search")
    as_text = lambda lang: {"".join(map(str, t[0])) for t in lang}  # noqa: E731
    assert as_text(parallel) == {"bb", "abab", "aabaab"}
    assert as_text(single) == {"a" * i + "b" + "a" * j + "b"
                               for i in range(5) for j in range(5) if i + j <= 4}
    assert parallel.complete and single.complete


# ---------------------------------------------------------------- D2 unsynchronised rules
def two_components(unsynchronised="free", mode="parallel"):
    g1 = Grammar("G1", S1, [Rule("p1", S1, (a, S1)), Rule("p2", S1, (a,))])
    g2 = Grammar("G2", S2, [Rule("q1", S2, (b, S2)), Rule("q2", S2, (b,)), Rule("q3", S2, (c,))])
    return PSGS((g1, g2), sync=[("p1", "q1"), ("p2", "q2")], mode=mode,
                unsynchronised=unsynchronised)


def test_free_applies_a_rule_in_no_tuple_on_its_own():
    system = two_components("free")
    steps = applicable_steps(system, initial_configuration(system))
    q3 = system.components[1].rule("q3")
    assert [s.tuple for s in steps] == [*system.sync, (IDLE, q3)]
    assert steps[-1].after == ((S1,), (c,)) and steps[-1].positions == ((), (0,))


def test_strict_applies_only_tuples_of_M():
    system = two_components("strict")
    steps = applicable_steps(system, initial_configuration(system))
    assert [s.tuple for s in steps] == list(system.sync)
    with pytest.raises(ValidationError, match="unsynchronised strict"):
        apply_tuple(system, initial_configuration(system), ("#", "q3"))


def test_free_and_strict_languages_differ_as_expected():
    free = language(two_components("free"), 6)
    strict = language(two_components("strict"), 6)
    assert set(strict) == {(w("a" * n), w("b" * n)) for n in (1, 2, 3)}
    # under free, q3 ends G2 alone; G1 then goes on with the tuples, whose G2 entry is
    # skipped because G2 is terminal (D3)
    assert (w("aa"), w("bc")) in free and (w("a"), w("c")) in free
    assert set(strict) < set(free)


# ---------------------------------------------------------------- D3 applicability
def test_idle_components_are_unchanged():
    system = dataclasses.replace(two_components(), sync=(("p1", "#"), ("p2", "q2")))
    step = apply_tuple(system, initial_configuration(system), ("p1", "#"))
    assert step.after == ((a, S1), (S2,)) and step.positions == ((0,), ())


def test_terminal_components_skip_their_entry_of_a_tuple():
    system = two_components()
    config = ((a, S1), (b,))
    steps = applicable_steps(system, config)
    assert [s.after for s in steps] == [((a, a, S1), (b,)), ((a, a), (b,))]
    assert all(s.positions[1] == () for s in steps)
    assert steps[0].tuple == system.sync[0]  # the tuple of M is recorded as applied


def test_a_tuple_whose_left_side_is_missing_does_not_apply():
    system = two_components()
    config = ((a, S1), (b, Nonterminal("X")))
    assert applicable_steps(system, config) == ()
    with pytest.raises(ValidationError, match="S2 does not occur in component G2"):
        apply_tuple(system, config, ("p1", "q1"))


def test_a_tuple_that_changes_nothing_does_not_apply():
    system = one_component([Rule("r1", S, (S,)), Rule("r2", S, (a,))], sync=[("r1",)])
    steps = applicable_steps(system, ((S,),))
    assert [s.after for s in steps] == [((a,),)]
    with pytest.raises(ValidationError, match="changes nothing"):
        apply_tuple(system, ((S,),), ("r1",))
    # and all-terminal configurations have no steps at all
    assert applicable_steps(two_components(), ((a,), (b,))) == ()


# ---------------------------------------------------------------- D4 ε, unit cycles
def test_epsilon_and_unit_cycles_terminate_and_are_complete_when_finite():
    rules = [Rule("r1", S, (A,)), Rule("r2", A, (S,)), Rule("r3", A, (a, A)), Rule("r4", A, ())]
    for mode in ("parallel", "single"):
        lang = language(one_component(rules, mode=mode), 3, method="search")
        assert lang.complete and lang.bound is None
        assert [t[0] for t in lang] == [w(""), w("a"), w("aa"), w("aaa")]


def test_an_infinite_configuration_space_stops_at_its_bound_and_says_so():
    # S → SS | ε: nullable forms grow without end while no terminal appears
    rules = [Rule("r1", S, (S, S)), Rule("r2", S, ())]
    lang = language(one_component(rules, mode="single"), 2, method="search",
                    max_configurations=50)
    assert not lang.complete
    assert lang.bound == "max_configurations"
    assert lang.reason == "stopped after 50 configurations (max_configurations)"
    assert lang.words == ((w(""),),)


# ---------------------------------------------------------------- apply_tuple
def test_apply_tuple_checks_positions():
    system = one_component(AA_RULES, mode="single", sync=[("r2",)])
    step = apply_tuple(system, ((A, A),), ("r2",), positions=[1])
    assert step.after == ((A, a, A),)
    assert apply_tuple(system, ((A, A),), ("r2",)).positions == ((0,),)  # leftmost by default
    with pytest.raises(ValidationError, match="not one occurrence of A"):
        apply_tuple(system, ((A, A),), ("r2",), positions=[(0, 1)])
    parallel = dataclasses.replace(system, mode="parallel")
    with pytest.raises(ValidationError, match="every occurrence"):
        apply_tuple(parallel, ((A, A),), ("r2",), positions=[0])


def test_apply_tuple_rejects_bad_input_with_a_reason():
    system = two_components()
    config = initial_configuration(system)
    with pytest.raises(ValidationError, match="has 1 entries but the system has 2"):
        apply_tuple(system, config, ("p1",))
    with pytest.raises(ValidationError, match="no rule labelled zz"):
        apply_tuple(system, config, ("zz", "#"))
    with pytest.raises(ValidationError, match=r"tuple \(p1, q2\) is not in M"):
        apply_tuple(system, config, ("p1", "q2"))
    with pytest.raises(ValidationError, match="configuration of this system has 2 forms"):
        apply_tuple(system, ((S1,),), ("p1", "q1"))


# ---------------------------------------------------------------- derivations
def test_derivation_checks_that_steps_join_and_prints_the_paper_notation():
    system = two_components()
    first = apply_tuple(system, initial_configuration(system), ("p1", "q1"))
    second = apply_tuple(system, first.after, ("p2", "q2"))
    d = Derivation(system, (first, second))
    assert str(d) == "(S1, S2) ⇒ (aS1, bS2) ⇒ (aa, bb)"
    assert d.result == (w("aa"), w("bb")) and d.is_terminal and d.words == d.result
    assert len(d) == 2 and d.configurations[0] == initial_configuration(system)
    with pytest.raises(ValidationError, match="does not join"):
        Derivation(system, (second, first))


def test_forms_are_spaced_when_a_terminal_name_is_long():
    g = Grammar("G", S, [Rule("r1", S, (Terminal("up"), S)), Rule("r2", S, ())])
    system = PSGS((g,), sync=[("r1",)])
    step = apply_tuple(system, initial_configuration(system), ("r1",))
    assert str(Derivation(system, (step,))) == "(S) ⇒ (up S)"
    assert format_form((), system) == "ε"


def test_random_derivations_are_seeded_and_report_how_they_ended():
    system = two_components()
    assert random_derivation(system, 7) == random_derivation(system, 7)
    runs = [random_derivation(system, seed) for seed in range(20)]
    assert all(r.status == "terminal" and r.bound is None for r in runs)
    assert len({r.result for r in runs}) > 1
    # a system that can only grow hits max_steps, and says so
    grow = one_component([Rule("r1", S, (a, S))], sync=[("r1",)])
    stuck = random_derivation(grow, 0, max_steps=25)
    assert len(stuck) == 25 and stuck.status == "open"
    assert stuck.bound == "max_steps" and stuck.reason == "stopped after 25 steps (max_steps)"
    # a system that blocks: the tuple needs A in G2, which never appears
    g1 = Grammar("G1", S1, [Rule("p1", S1, (a, S1))])
    g2 = Grammar("G2", S2, [Rule("q1", S2, (b,)), Rule("q2", A, (b,))])
    blocked = random_derivation(PSGS((g1, g2), sync=[("p1", "q2")], unsynchronised="strict"), 0)
    assert blocked.status == "blocked" and len(blocked) == 0 and blocked.bound is None


def test_random_derivation_stops_when_forms_explode():
    doubling = one_component([Rule("r1", S, (S, S))], sync=[("r1",)])
    d = random_derivation(doubling, 0, max_form_length=1000)
    assert "max_form_length" in d.bound and max(len(f) for f in d.result) > 1000
    assert len(d) == 10  # 2**10 = 1024 symbols



def test_random_derivation_holds_at_most_max_symbols_and_says_so():
    # a form that grows a symbol a step: the configurations kept hold the square of the steps
    grow = one_component([Rule("r1", S, (a, S))], sync=[("r1",)])
    d = random_derivation(grow, 0, max_symbols=5_000)
    held = [sum(len(f) for f in c) for c in d.configurations]
    assert d.bound == "max_symbols" and d.status == "open" and "5000 symbols" in d.reason
    assert sum(held) <= 5_000 < sum(held) + held[-1] + 1  # one step more would pass it
    assert len(d) == 98  # 1 + 2 + ... + 99 = 4,950 symbols; 100 more would be 5,050
    # with the default bound, 10,000 steps of it would hold 50 million symbols (400 MB)
    default = random_derivation(grow, 0)
    assert default.bound == "max_symbols" and len(default) < 4_500
    with pytest.raises(ValidationError, match="max_symbols"):
        random_derivation(grow, 0, max_symbols=0)


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_a_derivation_stopped_at_max_symbols_starts_the_one_a_larger_bound_allows(data):
    system = data.draw(_systems())
    seed = data.draw(st.integers(0, 2**16))
    small = data.draw(st.integers(1, 60))
    whole = random_derivation(system, seed, max_steps=30, max_form_length=40)
    cut = random_derivation(system, seed, max_steps=30, max_form_length=40, max_symbols=small)
    assert cut.steps == whole.steps[:len(cut.steps)]
    if cut.bound == "max_symbols":  # the step it let go was drawn: the other one took it
        assert len(cut.steps) < len(whole.steps)
    else:
        assert cut == whole


# ---------------------------------------------------------------- properties
def _systems():
    from psgs.strategies import psgs_systems
    return psgs_systems(max_components=2, max_nonterminals=2, max_rules=4, max_rhs=2,
                        max_tuples=3)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_random_derivations_take_only_applicable_steps_and_land_in_the_language(data):
    system = data.draw(_systems())
    seed = data.draw(st.integers(0, 2**16))
    d = random_derivation(system, seed, max_steps=30, max_form_length=40)
    for step, here in zip(d.steps, d.configurations):
        assert step in applicable_steps(system, here)
        replay = apply_tuple(system, here, step.tuple, step.positions)
        assert replay == step
        for k, rule in enumerate(step.tuple):
            if rule is IDLE:
                assert step.after[k] == step.before[k]
    if d.is_terminal:
        size = sum(len(f) for f in d.result)
        lang = language(system, size, method="search", max_configurations=3_000,
                        max_form_length=60)
        if lang.complete:
            assert d.result in lang.words
        else:  # an honest stop: the words found so far, and the bound named
            assert "max_configurations" in lang.bound or "max_form_length" in lang.bound


def test_language_order_is_by_size_then_names_and_each_once():
    system = one_component(AA_RULES, mode="single")
    lang = language(system, 7, method="search")
    keys = [(sum(len(x) for x in t), tuple(tuple(s.name for s in x) for x in t)) for t in lang]
    assert keys == sorted(keys) and len(set(lang.words)) == len(lang)
    assert isinstance(Step, type)


def test_parallel_doubling_of_nullable_symbols_stops_at_max_form_length():
    # S → SS | a | ε in parallel mode: S^(2^k) forms, each still able to vanish
    rules = [Rule("r1", S, (S, S)), Rule("r2", S, (a,)), Rule("r3", S, ())]
    lang = language(one_component(rules, mode="parallel", sync=[("r1",)]), 4)
    assert not lang.complete and "max_form_length" in lang.bound
    assert [t[0] for t in lang] == [w(""), w("a"), w("aa"), w("aaaa")]


# ---------------------------------------------------------------- docs/derivation.md
def test_the_examples_in_docs_derivation_run(capsys, monkeypatch):
    import re
    from pathlib import Path
    root = Path(__file__).resolve().parents[2]
    if not (root / "grammars" / "paper_example.psgs").exists():
        pytest.skip("grammars/paper_example.psgs is not in this tree")
    text = (root / "docs" / "derivation.md").read_text(encoding="utf-8")
    blocks = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    assert len(blocks) >= 6
    monkeypatch.chdir(root)
    namespace: dict = {}
    for block in blocks:
        exec(compile(block, "docs/derivation.md", "exec"), namespace)
    out = capsys.readouterr().out.splitlines()
    # every "# comment" promising output on a print line must match what was printed
    promised = [m.group(1).strip() for block in blocks for line in block.splitlines()
                if line.lstrip().startswith("print(") and (m := re.search(r"\)\s+# (.*)$", line))]
    for expected in promised:
        assert any(expected.split(":")[0] in line for line in out), expected
    assert "(S1, S2, S3, S4)" in out
    assert "(abcdbcad, bcadabcd, cdabcdab, abcdbcad)" in out


# ---------------------------------------------------------------- random steps without listing
def _listing_choice(system, configuration, rng):
    options = applicable_steps(system, configuration)
    return options[rng.randrange(len(options))] if options else None


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_a_random_step_is_the_step_a_listing_would_pick(data):
    """random_derivation draws by counting; the same seed picks what applicable_steps lists."""
    import random

    from psgs.strategies import pcgs_systems
    system = data.draw(st.one_of(_systems(), pcgs_systems(max_components=3, max_nonterminals=2,
                                                         max_rules=4, max_rhs=2)))
    seed = data.draw(st.integers(0, 2**16))
    d = random_derivation(system, seed, max_steps=12, max_form_length=30)
    # a PCGS rule A → A makes the draw reject combinations that change nothing: still uniform
    # over the applicable steps, but the random stream is consumed differently
    exact = isinstance(system, PSGS) or not any(
        r.rhs == (r.lhs,) for g in system.components for r in g.rules)
    for configuration in d.configurations:
        fast, slow = random.Random(seed), random.Random(seed)
        drawn = random_step(system, configuration, fast)
        listed = _listing_choice(system, configuration, slow)
        if exact:
            assert drawn == listed
            assert fast.random() == slow.random()  # the two consumed the stream alike
        else:
            assert (drawn is None) == (listed is None)
            assert drawn is None or drawn in applicable_steps(system, configuration)


def test_random_derivation_does_not_list_single_mode_occurrence_products():
    """Γ in single mode with 30 copies: 30⁴ occurrence choices per tuple, drawn by counting."""
    from test_paper_derivation import gamma_in_python
    system = gamma_in_python("single")
    configuration = initial_configuration(system)
    for _ in range(29):
        configuration = apply_tuple(system, configuration, ("p1", "q1", "r1", "s1")).after
    configuration = apply_tuple(system, configuration, ("p2", "q2", "r2", "s2")).after
    step = apply_tuple(system, configuration, ("p8", "q8", "r6", "s8"))
    import random

    drawn = random_step(system, step.after, random.Random(0))
    assert drawn is not None and drawn.tuple in system.sync
    assert drawn == apply_tuple(system, step.after, drawn.tuple, drawn.positions)


def test_bad_positions_and_long_forms_give_short_clear_errors():
    system = one_component(AA_RULES, mode="single", sync=[("r2",)])
    for bad in ([["x"]], ["1"], [True]):
        with pytest.raises(ValidationError, match="positions are an index"):
            apply_tuple(system, ((A, A),), ("r2",), positions=bad)
    long_form = ((b,) * 500 + (S,),)
    with pytest.raises(ValidationError, match=r"does not occur .*… \(501 characters\)") as info:
        apply_tuple(system, long_form, ("r2",))
    assert len(str(info.value)) < 200
