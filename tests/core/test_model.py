"""The formal model: values are immutable and validated, errors say what is wrong."""

import dataclasses

import pytest

from psgs import IDLE, PCGS, PSGS, Grammar, Nonterminal, Query, Rule, Terminal, ValidationError, as_word

S, A = Nonterminal("S"), Nonterminal("A")
a, b = Terminal("a"), Terminal("b")


def grammar(name="G1", rules=None, start=S):
    rules = rules if rules is not None else [Rule("r1", S, (a, S)), Rule("r2", S, ())]
    return Grammar(name, start, rules)


def two_component_system(**kw):
    g1 = grammar("G1")
    g2 = Grammar("G2", S, [Rule("q1", S, (b, S)), Rule("q2", S, ())])
    return PSGS((g1, g2), sync=[("r1", "q1"), ("r2", "q2")], **kw)


def test_tuples_given_by_label_are_stored_as_rules_and_idle_as_none():
    g1 = grammar("G1")
    g2 = Grammar("G2", S, [Rule("q1", S, (b, S)), Rule("q2", S, ())])
    system = PSGS((g1, g2), sync=[("r1", "#"), (g1.rule("r2"), "q2")])
    assert system.sync[0] == (g1.rule("r1"), IDLE)
    assert system.sync[1] == (g1.rule("r2"), g2.rule("q2"))
    assert system.unsynchronised_rules == ((), (g2.rule("q1"),))


def test_values_are_frozen_and_hashable():
    system = two_component_system()
    with pytest.raises(dataclasses.FrozenInstanceError):
        system.mode = "single"  # type: ignore[misc]
    assert hash(system) == hash(two_component_system())
    assert system == two_component_system()


def test_replace_gives_the_other_reading_and_validates_again():
    system = two_component_system()
    single = dataclasses.replace(system, mode="single")
    assert single.mode == "single" and single.components == system.components
    with pytest.raises(ValidationError, match="mode must be"):
        dataclasses.replace(system, mode="sequential")
    with pytest.raises(ValidationError, match="unsynchronised must be"):
        dataclasses.replace(system, unsynchronised="loose")


@pytest.mark.parametrize("sync, message", [
    ([("r1",)], "tuple 1 has 1 entries but the system has 2 components"),
    ([("r1", "nope")], "component G2 has no rule labelled nope"),
    ([("#", "#")], "idles in every component"),
    ([("r1", "q1"), ("r1", "q1")], "tuple 2 repeats"),
    ([("q1", "r1")], "component G1 has no rule labelled q1"),
])
def test_bad_tuples_are_named(sync, message):
    g1 = grammar("G1")
    g2 = Grammar("G2", S, [Rule("q1", S, (b, S)), Rule("q2", S, ())])
    with pytest.raises(ValidationError, match=message):
        PSGS((g1, g2), sync=sync)


def test_a_rule_object_from_another_component_is_refused():
    g1 = grammar("G1")
    g2 = Grammar("G2", S, [Rule("r1", S, (b, S)), Rule("q2", S, ())])
    with pytest.raises(ValidationError, match="is not a rule of component G1"):
        PSGS((g1, g2), sync=[(g2.rule("r1"), "#")])


def test_a_name_used_as_terminal_and_nonterminal_is_refused():
    with pytest.raises(ValidationError, match="both as a terminal and as a nonterminal"):
        Grammar("G", S, [Rule("r", S, (Terminal("A"), A)), Rule("s", A, ())])
    g1 = Grammar("G1", S, [Rule("r", S, (Terminal("A"),))])
    g2 = Grammar("G2", S, [Rule("r", S, (A,)), Rule("s", A, ())])
    with pytest.raises(ValidationError, match="both as a terminal"):
        PSGS((g1, g2))


def test_undefined_start_symbol_and_other_grammar_errors():
    with pytest.raises(ValidationError, match="start symbol S has no rule"):
        Grammar("G", S, [Rule("r", A, (a,))])
    with pytest.raises(ValidationError, match="two rules are labelled r"):
        Grammar("G", S, [Rule("r", S, (a,)), Rule("r", S, (b,))])
    with pytest.raises(ValidationError, match="are the same rule"):
        Grammar("G", S, [Rule("r", S, (a,)), Rule("s", S, (a,))])
    with pytest.raises(ValidationError, match="not a valid name"):
        Nonterminal("1x")
    with pytest.raises(ValidationError, match="without white space"):
        Terminal("a b")
    with pytest.raises(ValidationError, match="left-hand side must be a nonterminal"):
        Rule("r", a, ())  # type: ignore[arg-type]


def test_system_level_errors():
    g = grammar("G1")
    with pytest.raises(ValidationError, match="two components are named G1"):
        PSGS((g, g))
    with pytest.raises(ValidationError, match="at least one component"):
        PSGS(())
    with pytest.raises(ValidationError, match="has no query symbols"):
        PSGS((Grammar("G1", S, [Rule("r", S, (Query("G1"),))]),))


def test_pcgs_master_queries_and_centralised():
    master = Grammar("M", S, [Rule("r", S, (a, Query("H"))), Rule("s", S, (a,))])
    helper = Grammar("H", S, [Rule("t", S, (b, S)), Rule("u", S, (b,))])
    system = PCGS((master, helper), returning=False)
    assert system.master == "M" and system.master_index == 0
    assert system.centralised
    chatty = Grammar("H", S, [Rule("t", S, (b, Query("M"))), Rule("u", S, (b,))])
    assert not PCGS((master, chatty)).centralised
    with pytest.raises(ValidationError, match="names no component"):
        PCGS((Grammar("M", S, [Rule("r", S, (Query("X"),))]),))
    with pytest.raises(ValidationError, match="master 'Z' is not a component"):
        PCGS((master, helper), master="Z")


@pytest.mark.parametrize("master", [0, False, [], ()])
def test_pcgs_master_is_a_name_not_any_falsy_value(master):
    # master=0 (an index?) was taken for the default "" and chose the first component silently,
    # while master=1 was refused
    helper = Grammar("H", S, [Rule("t", S, (b,))])
    first = Grammar("M", S, [Rule("r", S, (a, Query("H")))])
    with pytest.raises(ValidationError, match="is not a component"):
        PCGS((first, helper), master=master)
    assert PCGS((first, helper), master=None).master == PCGS((first, helper)).master == "M"


def test_word_reads_a_str_as_one_character_symbols():
    assert as_word("ab") == (a, b)
    assert as_word(["up", "down"]) == (Terminal("up"), Terminal("down"))
    with pytest.raises(ValidationError):
        as_word([S])  # type: ignore[list-item]


@pytest.mark.parametrize("name", ["\ud800", "a\udcff", "\udfff\ud800"])
def test_a_terminal_is_no_lone_surrogate(name):
    # a "\ud800" escape in a file, or a byte of argv that is not UTF-8, made a terminal that
    # `psgs show`, `derive` and `export` could not print (UnicodeEncodeError, a traceback)
    with pytest.raises(ValidationError, match="terminal"):
        Terminal(name)
    assert Terminal("\U0001f600").name == "\U0001f600"  # a pair of surrogates in JSON, one character


def test_grammar_lookup_tables_are_read_only_and_pickle():
    import pickle

    N, T = Nonterminal, Terminal
    g = Grammar("G", N("S"), (Rule("s", N("S"), (T("a"),)),))
    assert g.rule("s").label == "s" and g.rules_by_lhs[N("S")][0].label == "s"
    with pytest.raises(TypeError):
        g.rule_by_label["t"] = g.rule("s")
    with pytest.raises(TypeError):
        g.rules_by_lhs[N("T")] = ()
    assert "t" not in g.rule_by_label and N("T") not in g.rules_by_lhs
    assert pickle.loads(pickle.dumps(g)) == g
