"""The paper's example Γ (section 3): its printed derivation replays step by step (parallel mode)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from psgs import PSGS, Grammar, Nonterminal, Rule, Terminal
from psgs.derivation import Derivation, applicable_steps, apply_tuple, initial_configuration
from psgs.enumeration import language

REPO = Path(__file__).resolve().parents[2]


def _symbols(text: str):
    """'N13 S1' -> symbols; lower-case single letters are terminals."""
    out = []
    for token in text.split():
        if token.islower() and len(token) == 1:
            out.append(Terminal(token))
        else:
            out.append(Nonterminal(token))
    return tuple(out)


def _rules(prefix: str, texts: list[str]):
    rules = []
    for k, text in enumerate(texts, start=1):
        lhs, rhs = text.split("->")
        rules.append(Rule(f"{prefix}{k}", Nonterminal(lhs.strip()), _symbols(rhs)))
    return rules


def gamma_in_python(mode: str = "parallel") -> PSGS:
    """Γ typed in from the paper's section 3 (rules in the paper's order, labels p/q/r/s + index)."""
    g1 = Grammar("G1", Nonterminal("S1"), _rules("p", [
        "S1 -> N13 S1", "S1 -> N13", "N5 -> b c", "N9 -> a N5", "N10 -> N9 d",
        "N11 -> N10 N5", "N12 -> N11 a", "N13 -> N12 d"]))
    g2 = Grammar("G2", Nonterminal("S2"), _rules("q", [
        "S2 -> N18 S2", "S2 -> N18", "N1 -> b c", "N14 -> N1 a", "N15 -> N14 d",
        "N16 -> N15 a", "N17 -> N16 N1", "N18 -> N17 d"]))
    g3 = Grammar("G3", Nonterminal("S3"), _rules("r", [
        "S3 -> N7 S3", "S3 -> N7", "N2 -> c d", "N3 -> N2 a", "N4 -> N3 b", "N7 -> N4 N4"]))
    g4 = Grammar("G4", Nonterminal("S4"), _rules("s", [
        "S4 -> N23 S4", "S4 -> N23", "N6 -> b c", "N19 -> a N6", "N20 -> N19 d",
        "N21 -> N20 N6", "N22 -> N21 a", "N23 -> N22 d"]))
    sync = [("p1", "q1", "r1", "s1"), ("p2", "q2", "r2", "s2"), ("p3", "q3", "r5", "s3"),
            ("p4", "q4", "#", "s4"), ("p5", "q5", "#", "s5"), ("p6", "q6", "#", "s6"),
            ("p7", "q7", "#", "s7"), ("p8", "q8", "r6", "s8")]
    return PSGS((g1, g2, g3, g4), sync=sync, mode=mode, name="Gamma")


def gamma(mode: str = "parallel") -> PSGS:
    """Γ from grammars/paper_example.psgs once the text format has landed, else typed in here."""
    path = REPO / "grammars" / "paper_example.psgs"
    try:
        from psgs.format import load
    except ImportError:
        return gamma_in_python(mode)
    if not path.exists():
        return gamma_in_python(mode)
    return dataclasses.replace(load(path), mode=mode)


# The derivation printed in section 3 of the paper, one configuration per line, with the tuple of M
# (by the position of the rules in the paper's P_i lists) or the unsynchronised rule applied.
PAPER_CONFIGURATIONS = [
    "S1, S2, S3, S4",
    "N13, N18, N7, N23",
    "N12 d, N17 d, N4 N4, N22 d",
    "N11 a d, N16 N1 d, N4 N4, N21 a d",
    "N10 N5 a d, N15 a N1 d, N4 N4, N20 N6 a d",
    "N9 d N5 a d, N14 d a N1 d, N4 N4, N19 d N6 a d",
    "a N5 d N5 a d, N1 a d a N1 d, N4 N4, a N6 d N6 a d",
    "a b c d b c a d, b c a d a b c d, N3 b N3 b, a b c d b c a d",
    "a b c d b c a d, b c a d a b c d, N2 a b N2 a b, a b c d b c a d",
    "a b c d b c a d, b c a d a b c d, c d a b c d a b, a b c d b c a d",
]
PAPER_PRINTED = (
    "(S1, S2, S3, S4) ⇒ (N13, N18, N7, N23) ⇒ (N12d, N17d, N4N4, N22d) ⇒ (N11ad, N16N1d, N4N4, "
    "N21ad) ⇒ (N10N5ad, N15aN1d, N4N4, N20N6ad) ⇒ (N9dN5ad, N14daN1d, N4N4, N19dN6ad) ⇒ "
    "(aN5dN5ad, N1adaN1d, N4N4, aN6dN6ad) ⇒ (abcdbcad, bcadabcd, N3bN3b, abcdbcad) ⇒ (abcdbcad, "
    "bcadabcd, N2abN2ab, abcdbcad) ⇒ (abcdbcad, bcadabcd, cdabcdab, abcdbcad)")


def _configuration(line: str):
    return tuple(_symbols(part) for part in line.split(","))


def _paper_rule(system: PSGS, component: int, lhs: str, rhs: str):
    """The rule of a component found by its body, so the test does not depend on labels."""
    body = _symbols(rhs)
    [rule] = [r for r in system.components[component].rules
              if r.lhs == Nonterminal(lhs) and r.rhs == body]
    return rule


def test_the_paper_derivation_replays_step_by_step_in_parallel_mode():
    system = gamma("parallel")
    expected = [_configuration(line) for line in PAPER_CONFIGURATIONS]
    assert initial_configuration(system) == expected[0]
    steps = []
    current = expected[0]
    for target in expected[1:]:
        # exactly one applicable step leads to the paper's next configuration
        leading = [s for s in applicable_steps(system, current) if s.after == target]
        assert len(leading) == 1, f"no unique step from {current} to {target}"
        steps.append(leading[0])
        current = target
    derivation = Derivation(system, tuple(steps))
    assert derivation.is_terminal and derivation.status == "terminal"
    assert derivation.configurations == tuple(expected)
    assert str(derivation) == PAPER_PRINTED


def test_the_paper_derivation_uses_the_tuples_the_text_implies():
    system = gamma("parallel")
    sync = list(system.sync)
    r = lambda i, lhs, rhs: _paper_rule(system, i, lhs, rhs)  # noqa: E731
    tuples = [
        (r(0, "S1", "N13"), r(1, "S2", "N18"), r(2, "S3", "N7"), r(3, "S4", "N23")),
        (r(0, "N13", "N12 d"), r(1, "N18", "N17 d"), r(2, "N7", "N4 N4"), r(3, "N23", "N22 d")),
        (r(0, "N12", "N11 a"), r(1, "N17", "N16 N1"), None, r(3, "N22", "N21 a")),
        (r(0, "N11", "N10 N5"), r(1, "N16", "N15 a"), None, r(3, "N21", "N20 N6")),
        (r(0, "N10", "N9 d"), r(1, "N15", "N14 d"), None, r(3, "N20", "N19 d")),
        (r(0, "N9", "a N5"), r(1, "N14", "N1 a"), None, r(3, "N19", "a N6")),
        (r(0, "N5", "b c"), r(1, "N1", "b c"), r(2, "N4", "N3 b"), r(3, "N6", "b c")),
        (None, None, r(2, "N3", "N2 a"), None),  # unsynchronised, applied alone (free)
        (None, None, r(2, "N2", "c d"), None),   # unsynchronised, applied alone (free)
    ]
    for t in tuples[:7]:
        assert t in sync
    for t in tuples[7:]:
        assert t not in sync
    current = initial_configuration(system)
    for t, line in zip(tuples, PAPER_CONFIGURATIONS[1:]):
        step = apply_tuple(system, current, t)
        assert step.after == _configuration(line)
        current = step.after
    # the step N4N4 ⇒ N3bN3b rewrites both occurrences at once: the paper's parallel reading
    step = apply_tuple(system, _configuration(PAPER_CONFIGURATIONS[6]), tuples[6])
    assert step.positions[2] == (0, 1)


def test_the_paper_derivation_is_not_a_single_mode_derivation():
    """In single mode N4N4 cannot become N3bN3b in one step: why D1 has two readings."""
    system = gamma("single")
    before = _configuration(PAPER_CONFIGURATIONS[6])
    after = _configuration(PAPER_CONFIGURATIONS[7])
    assert all(s.after != after for s in applicable_steps(system, before))
    assert any(s.after[2] == _symbols("N3 b N4") for s in applicable_steps(system, before))


@pytest.mark.parametrize("mode", ["parallel", "single"])
def test_gamma_language_to_64_is_k1_and_k2(mode):
    system = gamma(mode)
    patterns = ["abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad"]
    expected = [tuple(tuple(Terminal(c) for c in p * k) for p in patterns) for k in (1, 2)]
    lang32 = language(system, 32)
    assert lang32.complete and lang32.words == tuple(expected[:1])
    lang64 = language(system, 64)
    assert lang64.complete and lang64.words == tuple(expected)
    assert language(system, 31).words == ()
