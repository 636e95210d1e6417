"""Lark export: loads, accepts exactly the component's context-free language, names reversible."""

from __future__ import annotations

import dataclasses
import itertools
import re
from pathlib import Path

import lark
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import psgs
import psgs.strategies as pst
from psgs import PCGS, Grammar, Nonterminal, Query, Rule, Terminal, ValidationError
from psgs.enumeration import language
from psgs.lark_export import (EMPTY_TERMINAL, LARK_OPTIONS, START_RULE, from_lark_name,
                              lark_name, to_lark)

S, A, B, C = (Nonterminal(n) for n in "SABC")
a, b = Terminal("a"), Terminal("b")


def parser_for(text: str) -> lark.Lark:
    return lark.Lark(text, **LARK_OPTIONS)


def parses(parser: lark.Lark, word) -> bool:
    try:
        parser.parse(" ".join(t.name for t in word))
    except lark.exceptions.LarkError:
        return False
    return True


def leaves(tree: lark.Tree) -> tuple[Terminal, ...]:
    return tuple(from_lark_name(token.type) for token in tree.scan_values(
        lambda v: isinstance(v, lark.Token)))


def all_words(alphabet, max_length):
    for n in range(max_length + 1):
        for letters in itertools.product(alphabet, repeat=n):
            yield tuple(letters)


def assert_same_language(grammar: Grammar, max_length: int):
    """Lark's parser and our enumeration agree on every word up to max_length."""
    parser = parser_for(to_lark(grammar)[grammar.name])
    ours = language(grammar, max_length)
    assert ours.complete
    expected = set(ours)
    alphabet = sorted(grammar.terminals)
    for word in all_words(alphabet, max_length):
        assert parses(parser, word) == (word in expected), (word, expected)


# ---------------------------------------------------------------- names
def test_lark_names_have_lark_shapes_and_known_values():
    assert lark_name(Nonterminal("N13")) == "n__n13"
    assert lark_name(Nonterminal("s_1")) == "n_s__1"
    assert lark_name(Terminal("a")) == "T_A"
    assert lark_name(Terminal("Up")) == "T__UP"
    assert lark_name(Terminal("é")) == "T__233_"


identifiers = st.from_regex(r"[A-Za-z_][A-Za-z0-9_]{0,10}", fullmatch=True)
# (no control or format character: a terminal refuses them)
terminal_texts = st.text(st.characters(blacklist_categories=("Cs", "Cc", "Cf", "Zs", "Zl", "Zp")),
                         min_size=1, max_size=8).filter(lambda t: not any(c.isspace() for c in t))


@settings(max_examples=150, deadline=None)
@given(identifiers)
def test_nonterminal_names_round_trip_and_are_lark_rule_names(name):
    mangled = lark_name(Nonterminal(name))
    assert re.fullmatch(r"[a-z][_a-z0-9]*", mangled)
    assert from_lark_name(mangled) == Nonterminal(name)


@settings(max_examples=300, deadline=None)
@given(terminal_texts)
def test_terminal_names_round_trip_and_are_lark_terminal_names(text):
    mangled = lark_name(Terminal(text))
    assert re.fullmatch(r"[A-Z][_A-Z0-9]*", mangled)
    assert from_lark_name(mangled) == Terminal(text)


@settings(max_examples=100, deadline=None)
@given(identifiers, identifiers)
def test_mangling_is_injective_on_nonterminals(x, y):
    assert (lark_name(Nonterminal(x)) == lark_name(Nonterminal(y))) == (x == y)


@settings(max_examples=200, deadline=None)
@given(terminal_texts, terminal_texts)
def test_mangling_is_injective_on_terminals(x, y):
    assert (lark_name(Terminal(x)) == lark_name(Terminal(y))) == (x == y)


@pytest.mark.parametrize("name", ["start", EMPTY_TERMINAL, "__ANON_0", "n_X", "n__", "n_-",
                                  "T_a", "T__", "T__0_", "T__065_", "T__99999999_", "T_",
                                  "x", ""])
def test_names_no_export_writes_are_rejected(name):
    with pytest.raises(ValidationError) as refused:
        from_lark_name(name)
    # said once ('T__' was "... writes ('T__' is not a name psgs.to_lark writes)")
    assert str(refused.value).count("is not a name psgs.to_lark writes") == 1


# ---------------------------------------------------------------- grammars
def test_export_text_documents_how_to_load_and_what_it_cannot_say():
    system = psgs.load(Path(__file__).resolve().parents[2] / "grammars" / "counting.psgs")
    texts = to_lark(system)
    assert list(texts) == ["G1", "G2"]
    for text in texts.values():
        assert 'start="start", parser="earley", lexer="basic"' in text
        assert "Synchronisation" in text and "not expressible in Lark" in text
        assert "necessary condition" in text and "mode parallel" in text
        assert '%ignore " "' in text
    single = dataclasses.replace(system, mode="single")
    for text in to_lark(single).values():
        assert "necessary condition" in text and "parallel" not in text


def test_a_single_grammar_exports_as_one_entry():
    g = Grammar("G", S, (Rule("p", S, (a, S)), Rule("q", S, (b,))))
    texts = to_lark(g)
    assert list(texts) == ["G"]
    assert_same_language(g, 6)


def test_other_values_are_refused():
    with pytest.raises(ValidationError):
        to_lark("S -> a")


def test_terminals_stay_visible_in_the_parse_tree():
    g = Grammar("G", S, (Rule("p", S, (a, S, b)), Rule("q", S, ())))
    parser = parser_for(to_lark(g)["G"])
    tree = parser.parse("a a b b")
    assert leaves(tree) == (a, a, b, b)
    assert from_lark_name(tree.children[0].data) == S


def test_multi_character_terminals_stay_apart():
    ab = Terminal("ab")
    g = Grammar("G", S, (Rule("p", S, (a, b)), Rule("q", S, (ab,)), Rule("r", S, (ab, a))))
    parser = parser_for(to_lark(g)["G"])
    assert leaves(parser.parse("a b")) == (a, b)
    assert leaves(parser.parse("ab")) == (ab,)
    assert leaves(parser.parse("ab a")) == (ab, a)
    assert not parses(parser, (a, b, a))


def test_epsilon_rules_unit_cycles_and_left_recursion():
    g = Grammar("G", S, (
        Rule("e", S, ()), Rule("u", S, (A,)), Rule("v", A, (S,)), Rule("w", A, (A, a)),
        Rule("x", A, (b, B)), Rule("y", B, ()), Rule("z", B, (B,))))
    assert_same_language(g, 5)


def test_unreachable_and_unproductive_rules_are_left_out_and_still_load():
    dead, lost = Nonterminal("Dead"), Nonterminal("Lost")
    g = Grammar("G", S, (
        Rule("p", S, (a,)), Rule("q", S, (dead, b)), Rule("r", dead, (dead, a)),
        Rule("s", lost, (b,)), Rule("t", S, (b, S))))
    text = to_lark(g)["G"]
    assert "n__dead" not in text and "n__lost" not in text
    assert "3 rule(s)" in text
    assert_same_language(g, 5)


def test_an_empty_language_exports_a_grammar_that_rejects_everything():
    g = Grammar("G", S, (Rule("p", S, (a, S)),))
    text = to_lark(g)["G"]
    assert EMPTY_TERMINAL in text and "empty" in text
    parser = parser_for(text)
    for word in all_words([a], 3):
        assert not parses(parser, word)


def test_pcgs_components_leave_out_rules_with_queries():
    g1 = Grammar("G1", S, (Rule("p", S, (a, Query("G2"))), Rule("q", S, (a, S)),
                           Rule("r", S, (b,))))
    g2 = Grammar("G2", Nonterminal("T"), (Rule("s", Nonterminal("T"), (b,)),))
    texts = to_lark(PCGS((g1, g2)))
    assert "Communication" in texts["G1"]
    assert "?G2" not in texts["G1"].split("// Names")[1]
    assert_same_language(g1, 5)


@pytest.mark.parametrize("text", ["\\", '"', "*", "/", "'", "a\\\\b", "[", "^$", "😀(", "a\ue000",
                                  "\u0300", "x\\u0041"])
def test_terminals_with_odd_text_export_and_parse(text):
    t = Terminal(text)
    g = Grammar("G", S, (Rule("p", S, (t, a)),))
    tree = parser_for(to_lark(g)["G"]).parse(f"{text} a")
    assert leaves(tree) == (t, a)
    assert [token.value for token in tree.scan_values(lambda v: True)] == [text, "a"]


@settings(max_examples=60, deadline=None)
@given(st.lists(terminal_texts, min_size=1, max_size=4, unique=True), st.data())
def test_any_terminal_texts_export_and_parse(texts, data):
    terminals = [Terminal(t) for t in texts]
    rules = tuple(Rule(f"p{k}", S, (t, S)) for k, t in enumerate(terminals)) + (
        Rule("end", S, ()),)
    g = Grammar("G", S, rules)
    parser = parser_for(to_lark(g)["G"])
    word = tuple(data.draw(st.lists(st.sampled_from(terminals), max_size=5)))
    assert leaves(parser.parse(" ".join(t.name for t in word))) == word


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(pst.grammars(max_nonterminals=3, max_rules=6, max_rhs=3))
def test_generated_grammars_export_exactly_their_language(grammar):
    assert_same_language(grammar, 4)


@settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(pst.psgs_systems(max_components=3))
def test_every_component_of_a_generated_system_loads(system):
    texts = to_lark(system)
    assert list(texts) == [g.name for g in system.components]
    for g in system.components:
        parser = parser_for(texts[g.name])
        for word in language(g, 3):
            assert parses(parser, word)


def test_the_start_rule_is_documented():
    assert START_RULE == "start" and LARK_OPTIONS["start"] == START_RULE
    with pytest.raises(TypeError):  # shared options: no caller may change them for all others
        LARK_OPTIONS["parser"] = "lalr"


# ---------------------------------------------------------------- docs/export.md
def test_the_python_blocks_of_the_export_page_print_what_it_says(monkeypatch, capsys):
    doc = Path(__file__).resolve().parents[2] / "docs" / "export.md"
    text = doc.read_text(encoding="utf-8")
    pairs = re.findall(r"```python\n(.*?)```\s*prints\s*```text\n(.*?)```", text, re.S)
    assert len(pairs) == len(re.findall(r"```python\n", text)) >= 4
    monkeypatch.chdir(doc.parents[1])
    for code, printed in pairs:
        exec(compile(code, str(doc), "exec"), {})
        assert capsys.readouterr().out == printed
