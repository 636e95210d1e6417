"""The sequential baseline: Re-Pair per string, no synchronisation."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import psgs
from psgs import Actiongram
from psgs.induce import Sequential
from psgs.induce.synthetic import generate, success


def test_learns_a_clean_repetition():
    result = Sequential().induce(Actiongram.from_strings({"a": "abcd" * 4}))
    assert result.components == ("a",)
    pattern = "".join(result.patterns["a"])
    # its longest rule spells a power of the period
    assert pattern in ("abcd" * 4)[: len(pattern)] and len(pattern) % 4 == 0
    assert result.system.sync == ()


def test_keeps_random_strings_that_repeat_a_digram():
    # the overgeneralisation the paper describes: no synchronisation, so noise is kept
    strings = {"rand": "qwertyqwpzxqwmnb", "once": "abcdefg"}
    result = Sequential().induce(Actiongram.from_strings(strings))
    assert result.components == ("rand",)
    assert result.patterns["rand"] == ("q", "w")
    assert result.report("once").status == "no repetition"


def test_fails_the_paper_protocol_by_keeping_random_strings():
    case = generate(seed=4)
    result = Sequential().induce(case.actiongram)
    assert not success(result, case)
    assert len(result.components) > len(case.components)
    assert set(case.components) <= set(result.components)


@settings(max_examples=60, deadline=None)
@given(st.text(alphabet="abc", min_size=0, max_size=40))
def test_pattern_occurs_where_reported(text):
    ag = Actiongram.from_strings({"x": text})
    result = Sequential(max_rules=1000).induce(ag)
    if "x" not in result.patterns:
        assert result.report("x").status == "no repetition"
        return
    pattern = result.patterns["x"]
    assert result.report("x").status == "component" and result.report("x").copies >= 1
    starts = ag.starts["x"]
    positions = [starts.index(a) for a, _ in result.occurrences["x"]]
    for p in positions:
        assert ag.string("x")[p:p + len(pattern)] == pattern
    # occurrences never overlap
    assert all(b - a >= len(pattern) for a, b in zip(positions, positions[1:]))


@settings(max_examples=60, deadline=None)
@given(st.lists(st.text(alphabet="abc", max_size=12), min_size=2, max_size=4))
def test_performances_learn_like_one_string_cut_by_symbols_that_occur_once(texts):
    # a symbol that occurs once can never be in a rule, which is what a performance boundary is
    takes = [Actiongram.from_strings({"x": t}) for t in texts]
    joined = []
    for k, t in enumerate(texts):
        joined += ([f"cut{k}"] if k else []) + list(t)
    one = Sequential().induce(Actiongram.from_strings({"x": joined}))
    several = Sequential().induce(takes)
    assert several.report("x") == one.report("x")
    assert dict(several.patterns) == dict(one.patterns)
    assert len(several.occurrences.get("x", ())) == len(one.occurrences.get("x", ()))


def test_rule_bound_is_reported():
    result = Sequential(max_rules=1).induce(Actiongram.from_strings({"a": "abcabcabcabc"}))
    assert result.report("a").status == "rule bound reached"
    # and the Induction names it, as every bounded result of the library does
    assert result.bound == "max_rules" and result.to_dict()["reason"] == \
        "stopped making rules at max_rules=1 on 1 string"


@pytest.mark.parametrize("text, rules", [("abab", 1), ("abcabcabcabc", 3), ("abcdabcd", 3)])
def test_a_string_whose_last_rule_is_the_bound_is_not_called_bounded(text, rules):
    # abab makes one rule (a b) and then nothing repeats: max_rules=1 stopped nothing
    actiongram = Actiongram.from_strings({"a": text})
    whole = Sequential().induce(actiongram)
    at_bound = Sequential(max_rules=rules).induce(actiongram)
    assert at_bound.report("a").status == "component" and at_bound.bound is None
    assert at_bound.patterns == whole.patterns and at_bound.reports == whole.reports
    if rules > 1:  # one rule fewer is a real cut
        assert Sequential(max_rules=rules - 1).induce(actiongram).report("a").status == \
            "rule bound reached"


def test_each_component_generates_its_own_repetitions_independently():
    strings = {"x": "abcabcabc", "y": "pqrpqrpqr"}
    result = Sequential().induce(Actiongram.from_strings(strings))
    px, py = result.patterns["x"], result.patterns["y"]
    assert psgs.accepts(result.system, [px * 2, py * 1])


def test_parameters():
    assert Sequential(min_count=3).get_params() == {"min_count": 3, "max_rules": 100_000}
    with pytest.raises(ValueError):
        Sequential(min_count=1)
    with pytest.raises(TypeError):
        Sequential().induce("abc")


def test_the_induction_is_a_read_only_value():
    import pickle

    result = Sequential().induce(Actiongram.from_strings({"a": "abcd" * 4, "b": "xy"}))
    for mapping in (result.patterns, result.occurrences, result.params, result.component_names):
        with pytest.raises(TypeError):
            mapping["a"] = ()
    assert isinstance(result.patterns["a"], tuple)
    assert all(isinstance(span, tuple) for span in result.occurrences["a"])
    assert pickle.loads(pickle.dumps(result)) == result


@pytest.mark.parametrize("params, words", [
    (dict(alpha=float("nan")), "alpha must be a finite number"),
    (dict(conserve=float("nan")), "conserve must be a finite number"),
    (dict(scan_alpha=float("inf")), "scan_alpha must be a finite number"),
])
def test_non_finite_parameters_are_refused(params, words):
    from psgs.induce import get

    with pytest.raises(ValueError, match=words):
        get("pal", **params)


def test_a_broken_plug_in_is_one_clear_error(monkeypatch, capsys):
    import psgs.induce as induce
    import psgs.induce.registry as registry
    from psgs.cli import main

    class BrokenEntryPoint:
        name = "broken"

        def load(self):
            raise ImportError("No module named 'nowhere'")

    monkeypatch.setattr(registry, "entry_points", lambda group: [BrokenEntryPoint()])
    with pytest.raises(ValueError, match="'broken' \\(a plug-in\\) could not be loaded"):
        induce.get("broken")
    assert main(["induce", "--example", "--inducer", "broken"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "No module named 'nowhere'" in err


def _recounted_pair_rules(codes, first_new, min_count, max_rules):
    """Re-Pair as the definition reads: every round counts every digram of the whole sequence
    again (quadratic; what psgs.induce.sequential did before it kept the counts up to date)."""
    import numpy as np

    seq = np.asarray(codes, dtype=np.int64)
    origin = np.arange(len(seq), dtype=np.int64)
    expansion, length_of, code, bounded = {}, {}, first_new, False
    base = np.int64(1 << 31)
    while len(seq) >= 2:
        keys = seq[:-1] * base + seq[1:]
        uniq, first, counts = np.unique(keys, return_index=True, return_counts=True)
        best = uniq[np.lexsort((first, -counts))[0]]
        hits = np.flatnonzero(keys == best)
        left, right = int(best // base), int(best % base)
        if left == right:
            keep, last = [], -2
            for p in hits.tolist():
                if p >= last + 2:
                    keep.append(p)
                    last = p
            hits = np.asarray(keep, dtype=np.int64)
        if len(hits) < min_count:
            break
        if len(expansion) >= max_rules:  # the bound stops a rule that would be made
            bounded = True
            break
        expansion[code] = (left, right)
        length_of[code] = length_of.get(left, 1) + length_of.get(right, 1)
        seq = seq.copy()
        seq[hits] = code
        drop = np.ones(len(seq), dtype=bool)
        drop[hits + 1] = False
        seq, origin = seq[drop], origin[drop]
        code += 1
    return expansion, length_of, dict(zip(origin.tolist(), seq.tolist())), bounded


@settings(max_examples=150, deadline=None)
@given(st.lists(st.integers(0, 3), max_size=120), st.integers(1, 4), st.integers(2, 4),
       st.sampled_from([1, 2, 5, 100_000]))
def test_pair_rules_are_those_of_recounting_every_round(codes, repeat, min_count, max_rules):
    from psgs.induce.sequential import _pair_rules

    codes = codes * repeat  # repeats and runs, where rules are many and ties frequent
    assert _pair_rules(codes, 4, min_count, max_rules) == \
        _recounted_pair_rules(codes, 4, min_count, max_rules)


def test_a_long_random_string_is_learnt_in_seconds_not_hours():
    import random
    import time

    rng = random.Random(0)
    text = [rng.choice("abcdefghijklmnopqrst") for _ in range(100_000)]
    started = time.process_time()
    result = Sequential().induce(Actiongram.from_strings({"x": text}))
    assert time.process_time() - started < 10  # 12 s before, counting every round anew
    assert result.components == ("x",)
