"""The paper's example Γ (section 3): its printed derivation replays step by step (parallel mode)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from psgs import PSGS, Grammar, Nonterminal, Rule, Terminal
from psgs.derivation import (Derivation, applicable_steps, apply_tuple, initial_configuration,
                             language)

REPO = Path(__file__).resolve().parents[1]


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
