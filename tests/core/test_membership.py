"""psgs.accepts on PSGS: the paper's Γ, both modes and policies, ε- and unit rules, budgets."""

from __future__ import annotations

import dataclasses
import functools
from pathlib import Path

import pytest

from psgs import PSGS, Grammar, Nonterminal as N, Rule, Terminal as T, ValidationError, as_word
from psgs.enumeration import language
from psgs.membership import Acceptance, accepts

REPO = Path(__file__).resolve().parents[2]
BLOCKS = ("abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad")


def _body(text: str):
    return tuple(T(tok) if tok.islower() and len(tok) == 1 else N(tok) for tok in text.split())


def _grammar(name: str, start: str, prefix: str, texts: list[str]) -> Grammar:
    rules = []
    for k, text in enumerate(texts, start=1):
        lhs, rhs = text.split("->")
        rules.append(Rule(f"{prefix}{k}", N(lhs.strip()), _body(rhs)))
    return Grammar(name, N(start), tuple(rules))


@functools.lru_cache(maxsize=None)
def gamma(mode: str = "parallel", unsynchronised: str = "free") -> PSGS:
    """The paper's Γ (section 3), typed in; grammars/paper_example.psgs when it loads.

    Read once per mode and policy: a PSGS is frozen, and the property tests asked for it in
    every example (a read of the file each, 7 ms)."""
    path = REPO / "grammars" / "paper_example.psgs"
    if path.exists():
        try:
            from psgs.format import load
            return dataclasses.replace(load(path), mode=mode, unsynchronised=unsynchronised)
        except ImportError:
            pass
    g1 = _grammar("G1", "S1", "p", ["S1 -> N13 S1", "S1 -> N13", "N5 -> b c", "N9 -> a N5",
                                    "N10 -> N9 d", "N11 -> N10 N5", "N12 -> N11 a",
                                    "N13 -> N12 d"])
    g2 = _grammar("G2", "S2", "q", ["S2 -> N18 S2", "S2 -> N18", "N1 -> b c", "N14 -> N1 a",
                                    "N15 -> N14 d", "N16 -> N15 a", "N17 -> N16 N1",
                                    "N18 -> N17 d"])
    g3 = _grammar("G3", "S3", "r", ["S3 -> N7 S3", "S3 -> N7", "N2 -> c d", "N3 -> N2 a",
                                    "N4 -> N3 b", "N7 -> N4 N4"])
    g4 = _grammar("G4", "S4", "s", ["S4 -> N23 S4", "S4 -> N23", "N6 -> b c", "N19 -> a N6",
                                    "N20 -> N19 d", "N21 -> N20 N6", "N22 -> N21 a",
                                    "N23 -> N22 d"])
    sync = [("p1", "q1", "r1", "s1"), ("p2", "q2", "r2", "s2"), ("p3", "q3", "r5", "s3"),
            ("p4", "q4", "#", "s4"), ("p5", "q5", "#", "s5"), ("p6", "q6", "#", "s6"),
            ("p7", "q7", "#", "s7"), ("p8", "q8", "r6", "s8")]
    return PSGS((g1, g2, g3, g4), sync, mode=mode, unsynchronised=unsynchronised, name="Gamma")


def gamma_words(*ks: int):
    ks = ks if len(ks) == 4 else ks * 4
    return [block * k for block, k in zip(BLOCKS, ks)]


@pytest.mark.parametrize("mode", ["parallel", "single"])
@pytest.mark.parametrize("k", [1, 2, 3])
def test_gamma_accepts_its_language_with_a_checked_witness(mode, k):
    words = gamma_words(k)
    result = accepts(gamma(mode), words)
    assert result and result.answer == "yes"
    witness = result.witness
    assert witness.words == tuple(as_word(w) for w in words)
    assert str(witness).startswith("(S1, S2, S3, S4) ⇒ ")
    assert str(witness).endswith(f"({', '.join(words)})")


@pytest.mark.parametrize("mode", ["parallel", "single"])
def test_gamma_rejects_mismatched_repetitions_with_the_schedule_reason(mode):
    result = accepts(gamma(mode), gamma_words(2, 2, 2, 1))
    assert not result and result.answer == "no"
    assert result.reason.startswith("every component parses but no schedule of the tuples fits")
    assert result.witness is None


@pytest.mark.parametrize("mode", ["parallel", "single"])
def test_gamma_names_the_component_whose_word_does_not_parse(mode):
    words = gamma_words(1)
    words[2] = "cdabcdba"
    result = accepts(gamma(mode), words)
    assert result.answer == "no"
    assert result.reason == "component G3's word is not in its context-free language"
    words[2] = "cdabcdaz"
    assert "z at position 8 is not one of its terminals" in accepts(gamma(mode), words).reason


def test_strict_policy_forbids_gammas_unsynchronised_rules():
    # N2 → cd and N3 → N2 a are in no tuple: under strict, G3 can never become terminal
    assert accepts(gamma("parallel", "free"), gamma_words(1))
    result = accepts(gamma("parallel", "strict"), gamma_words(1))
    assert result.answer == "no"


@pytest.mark.parametrize("mode", ["parallel", "single"])
def test_strict_rules_in_no_tuple_are_refused_by_the_chart_not_by_a_budget(mode):
    # S → b and S → ε are in no tuple, so under strict only S → S S applies: the language is
    # empty. Before, the schedule search piled up ε-occurrences and answered "unknown".
    g = _grammar("G", "S", "r", ["S -> b", "S -> ", "S -> S S"])
    doubling = next(r for r in g.rules if len(r.rhs) == 2)
    system = PSGS((g,), ((doubling,),), mode=mode, unsynchronised="strict")
    assert language(system, 4, method="search").words == ()
    for word in ["", "b", "bb"]:
        result = accepts(system, [word], max_seconds=5)
        assert result.answer == "no", (word, result)
        assert "strict" in result.reason
    free = dataclasses.replace(system, unsynchronised="free")
    assert accepts(free, ["bb"]).answer == "yes"


@pytest.mark.parametrize("mode", ["parallel", "single"])
def test_gamma_at_a_thousand_repetitions(mode):
    result = accepts(gamma(mode), gamma_words(1000), check_witness=False)
    assert result.answer == "yes"
    assert accepts(gamma(mode), gamma_words(1000, 1000, 999, 1000)).answer == "no"


def indian_parallel(mode: str) -> PSGS:
    g = _grammar("G", "S", "r", ["S -> A A", "A -> a A", "A -> b"])
    return PSGS((g,), (), mode=mode)


def test_parallel_mode_rewrites_every_occurrence():
    # S → AA, A → aA | b: parallel gives aⁿb aⁿb, single any aⁱb aʲb
    assert accepts(indian_parallel("parallel"), "aabaab")
    assert not accepts(indian_parallel("parallel"), "aabab")
    assert accepts(indian_parallel("single"), "aabab")
    assert accepts(indian_parallel("parallel"), "aabab").reason.startswith(
        "every component parses but no schedule of the tuples fits")


def piling_epsilon_system() -> PSGS:
    """G1 must pile up n erasable B's while G2 reads cⁿ, and erase them only afterwards."""
    g1 = _grammar("G1", "S", "p", ["S -> S B", "S -> a", "B -> "])
    g2 = _grammar("G2", "T", "q", ["T -> c T", "T -> U", "U -> d U", "U -> d"])
    sync = [("p1", "q1"), ("p2", "q2"), ("p3", "q3"), ("p3", "q4")]
    return PSGS((g1, g2), sync, mode="single", unsynchronised="strict")


def test_epsilon_occurrences_that_pile_up_are_searched_beyond_the_first_cap():
    system = piling_epsilon_system()
    result = accepts(system, ["a", "c" * 9 + "d"])
    assert result.answer == "yes"
    assert result.witness.words == (as_word("a"), as_word("c" * 9 + "d"))
    # a small state budget names itself
    small = accepts(system, ["a", "c" * 9 + "d"], max_states=5)
    assert small.answer == "unknown" and small.bound == "max_states"
    assert not small


def test_unit_and_epsilon_rules_agree_with_enumeration():
    g = _grammar("G", "S", "r", ["S -> A", "A -> S", "A -> a S b", "S -> ", "A -> B B", "B -> "])
    for mode in ("parallel", "single"):
        system = PSGS((g,), (), mode=mode)
        lang = language(system, 6, method="search")
        assert lang.complete
        members = {tuple(t.name for t in ws[0]) for ws in lang.words}
        for n in range(7):
            for bits in range(2 ** n):
                word = tuple("ab"[(bits >> k) & 1] for k in range(n))
                assert bool(accepts(system, [word])) == (word in members), (mode, word)


def test_budget_of_seconds_is_named():
    result = accepts(gamma("single"), gamma_words(300), max_seconds=1e-6)
    assert result.answer == "unknown"
    assert result.bound == "max_seconds"
    assert "time" in result.reason


def test_words_in_every_accepted_shape():
    system = gamma("parallel")
    as_names = [list(w) for w in gamma_words(1)]
    as_terminals = [as_word(w) for w in gamma_words(1)]
    assert accepts(system, as_names) and accepts(system, as_terminals)
    single = PSGS((_grammar("G", "S", "r", ["S -> a S", "S -> a"]),), ())
    assert accepts(single, "aaa") and accepts(single, ["aaa"]) and accepts(single, as_word("aa"))


def test_bad_calls_raise_one_clear_error():
    with pytest.raises(ValidationError, match="4 components but 3 words"):
        accepts(gamma(), gamma_words(1)[:3])
    with pytest.raises(ValidationError, match="one word per component"):
        accepts(gamma(), "abcd")
    with pytest.raises(ValidationError, match="max_states"):
        accepts(gamma(), gamma_words(1), max_states=0)
    with pytest.raises(ValidationError, match="PSGS or a PCGS"):
        accepts("not a system", ["a"])


def test_acceptance_is_a_value():
    yes = accepts(gamma(), gamma_words(1))
    assert isinstance(yes, Acceptance) and str(yes) == "yes"
    no = accepts(gamma(), gamma_words(1, 1, 1, 2))
    assert str(no).startswith("no: ")
    with pytest.raises(dataclasses.FrozenInstanceError):
        no.answer = "yes"


# ---------------------------------------------------------------- the psgs check command
def run_cli(*argv: str):
    import subprocess
    import sys
    return subprocess.run([sys.executable, "-m", "psgs", "check", *argv], cwd=REPO,
                          capture_output=True, text=True, timeout=120)


PAPER = "grammars/paper_example.psgs"
K2 = ["abcdbcadabcdbcad", "bcadabcdbcadabcd", "cdabcdabcdabcdab", "abcdbcadabcdbcad"]


@pytest.mark.skipif(not (REPO / PAPER).exists(), reason="grammars/paper_example.psgs not written")
def test_cli_check_exit_statuses():
    yes = run_cli(PAPER, *K2)
    assert yes.returncode == 0 and yes.stdout.strip() == "yes"
    no = run_cli(PAPER, *K2[:3], "abcdbcad")
    assert no.returncode == 1
    assert no.stdout.startswith("no: every component parses but no schedule of the tuples fits")
    unknown = run_cli(PAPER, *K2, "--max-states", "2")
    assert unknown.returncode == 3 and "max_states=2" in unknown.stdout
    traced = run_cli("--trace", PAPER, "a b c d b c a d", "bcadabcd", "cdabcdab", "abcdbcad")
    assert traced.returncode == 0
    assert traced.stdout.splitlines()[1].startswith("(S1, S2, S3, S4) ⇒ (N13, N18, N7, N23)")
    assert traced.stdout.rstrip().endswith("(abcdbcad, bcadabcd, cdabcdab, abcdbcad)")


def test_cli_check_usage_errors_exit_2_not_the_unknown_status():
    # one table for every command: 2 usage or input error, 3 unknown
    for argv in [(), ("--max-seconds", "0", PAPER, "a"), ("--max-states", "x", PAPER, "a"),
                 ("--bogus", PAPER, "a")]:
        result = run_cli(*argv)
        assert result.returncode == 2, (argv, result.returncode, result.stderr)
        assert "error" in result.stderr and "Traceback" not in result.stderr


def test_cli_check_errors_are_one_line_and_non_zero(tmp_path):
    bad = tmp_path / "bad.psgs"
    bad.write_text("psgs X\ncomponent\n")
    for argv in ([str(bad), "a"], [str(tmp_path / "missing.psgs"), "a"]):
        result = run_cli(*argv)
        assert result.returncode == 2
        assert len(result.stderr.strip().splitlines()) == 1
        assert result.stderr.startswith("psgs: error: ")
    if (REPO / PAPER).exists():
        wrong = run_cli(PAPER, "abcd")
        assert wrong.returncode == 2 and "give 4 words" in wrong.stderr


def test_cli_reads_words_with_spaces_or_one_character_symbols():
    from psgs.cli.check import read_word
    system = PSGS((_grammar("G", "S", "r", ["S -> a S", "S -> a"]),), ())
    assert read_word("a a a", system) == as_word("aaa")
    assert read_word("aaa", system) == as_word("aaa")
    assert read_word("", system) == ()
    g = Grammar("G", N("S"), (Rule("r", N("S"), (T("up"), T("down"))),))
    assert read_word("up", PSGS((g,), ())) == (T("up"),)
    assert read_word("up down", PSGS((g,), ())) == (T("up"), T("down"))


def test_docs_membership_page_runs():
    from test_strategies import run_markdown_python
    namespace = run_markdown_python("docs/membership.md")
    assert namespace["short"].answer == "no" and namespace["hard"].bound == "max_states"


def test_a_yes_carries_a_typed_schedule_that_replays():
    from psgs.membership.witness import PSGSSchedule, Rewrite, ScheduledMove, replay
    system = gamma()
    result = accepts(system, BLOCKS)
    schedule = result.schedule
    assert isinstance(schedule, PSGSSchedule) and schedule.words == tuple(map(as_word, BLOCKS))
    assert all(isinstance(m, ScheduledMove) and len(m.rewrites) == 4 for m in schedule.moves)
    first = schedule.moves[0]
    assert first.entries in system.sync
    assert all(isinstance(r, Rewrite) and r.split[0] == r.start and r.split[-1] == r.end
               for rw in first.rewrites for r in rw)
    assert replay(system, schedule).words == schedule.words
    # a schedule that does not fit the system is refused by the derivation engine
    broken = PSGSSchedule(schedule.words, schedule.moves[1:])
    with pytest.raises(ValidationError):
        replay(system, broken)
