"""PAL on sections played twice: the long repeat found, weighed and reported per copy."""

from __future__ import annotations

import math
from itertools import combinations

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from psgs import Actiongram, ValidationError
from psgs.induce import PAL
from psgs.induce.pal.choice import coincide
from psgs.induce.pal.in_step import in_step_significance
from psgs.induce.pal.motifs import Timed
from psgs.induce.pal.sections import Section, find_section, repeat_significance


def _draw(rng: np.random.Generator, letters: int, count: int, before: int | None = None
          ) -> list[int]:
    """``count`` symbols from ``letters``, no two neighbours equal (an actiongram merges
    them), the first unlike ``before``."""
    out: list[int] = []
    for _ in range(count):
        last = out[-1] if out else before
        choice = int(rng.integers(0, letters - (last is not None)))
        out.append(choice + (last is not None and choice >= last))
    return out


def _sectioned(seed: int, sectioned: int, spurious: int, length: int, letters: int):
    """Strings of 60 symbols; ``sectioned`` of them play a section of ``length`` twice, at the
    same times in each; ``spurious`` random strings beside them. Returns the actiongram, the
    sectioned names and the two copies' times."""
    rng = np.random.default_rng(seed)
    lead, gap = int(rng.integers(0, 10)), int(rng.integers(1, 8))
    strings, truth = {}, []
    for k in range(sectioned):
        section = _draw(rng, letters, length)
        while len(set(section)) < 4:
            section = _draw(rng, letters, length)
        head = _draw(rng, letters, lead)
        # the head's last symbol must differ from the section's first, or they would merge
        # and the first copy would start earlier than the second (not the same times)
        while head and head[-1] == section[0]:
            head = _draw(rng, letters, lead)
        parts = head + section
        parts += _draw(rng, letters, gap, parts[-1])
        # the gap's last symbol must differ from the section's first, or they would merge
        while parts[-1] == section[0]:
            parts[-1] = (parts[-1] + 1) % letters if parts[-2] != (parts[-1] + 1) % letters \
                else (parts[-1] + 2) % letters
        parts += section
        parts += _draw(rng, letters, 60 - len(parts), parts[-1])
        strings[f"s{k}"] = parts
        truth.append(f"s{k}")
    for k in range(spurious):
        strings[f"r{k}"] = _draw(rng, letters, 60)
    names = "abcdefghijklmnop"
    ag = Actiongram.from_strings({n: [names[c] for c in s] for n, s in strings.items()})
    copies = ((lead, lead + length), (lead + length + gap, lead + 2 * length + gap))
    return ag, truth, copies


def _holds_both_copies(result, name: str, copies) -> bool:
    """Whether ``name`` is reported with both copies of its section: each true copy mostly
    held by a reported one, every reported copy exact (agreement 1). Where a reported copy
    reaches past the section, the symbols around both copies agree by chance and the data
    does repeat that far; a third exact copy the random symbols happen to hold counts too."""
    found = result.occurrences[name]
    return (all(share == 1.0 for share in result.agreements[name])
            and all(any(min(end, b) - max(start, a) >= (b - a) / 2 for start, end in found)
                    for a, b in copies))


def _exactly_right(seed: int, sectioned: int, spurious: int, length: int, letters: int) -> bool:
    ag, truth, copies = _sectioned(seed, sectioned, spurious, length, letters)
    result = PAL(min_copies=2).induce(ag)
    return (set(result.components) == set(truth)
            and all(_holds_both_copies(result, name, copies) for name in truth))


@settings(max_examples=40, deadline=None, derandomize=True)
@given(seed=st.integers(0, 10_000), sectioned=st.integers(2, 6), spurious=st.integers(0, 16),
       length=st.integers(8, 16), letters=st.integers(4, 12))
# draws of the full ranges that once failed: exact copies weighed as far from a lead
# lengthened by chance agreement as a chance repeat inside it; a section that repeats
# itself (acadbacadba, facdfacd) left out as a cycle; a member read only at a lead whose
# copies reach past the section; a chance repeat inside a section's copies at a shift of
# its own named beside it; two sections each reaching past the repeat they share, on
# other sides, each off the other's copies
@example(996762, 2, 8, 9, 4)
@example(212642, 2, 12, 9, 4)
@example(249899, 2, 12, 11, 4)
@example(805705, 3, 15, 9, 4)
@example(704210, 3, 9, 8, 4)
@example(293546, 3, 8, 8, 9)
@example(502682, 4, 14, 8, 4)
@example(774038, 6, 9, 8, 4)
@example(473188, 4, 12, 8, 4)
@example(7091, 6, 10, 8, 4)
@example(262313, 2, 12, 8, 4)
@example(952231, 5, 13, 16, 9)
@example(422294, 2, 7, 14, 5)
@example(261232, 2, 13, 8, 4)  # two strings, each section reaching past the shared one
@example(570071, 6, 14, 8, 4)  # the weakest of six members short of the test against all
@example(404318, 6, 9, 8, 4)
@example(151062, 4, 15, 8, 4)  # the members so far all reaching a symbol past the section on
@example(991450, 3, 16, 8, 4)  # one side, an exact member reaching past it on the other
def test_pal_names_exactly_the_sectioned_strings_with_both_copies(seed, sectioned, spurious,
                                                                   length, letters):
    assert _exactly_right(seed, sectioned, spurious, length, letters)


def test_pal_errs_on_sections_no_more_often_than_its_significance():
    # a random string can hold, by chance, a repeat at the section's times as strong as a
    # sectioned string's (then it is one, by the data; the draw's labels say otherwise), so
    # no test names exactly the drawn sections in every draw: at alpha = 0.01 PAL may err
    # in about 1 % of them. Measured over 2,000 draws of these ranges: 5 (0.25 %), each a
    # random string or pair claimed at that level (docs/streams.md)
    rng = np.random.default_rng(2026)
    draws = [(int(rng.integers(0, 1_000_000)), int(rng.integers(2, 7)), int(rng.integers(0, 17)),
              int(rng.integers(8, 17)), int(rng.integers(4, 13))) for _ in range(200)]
    wrong = [draw for draw in draws if not _exactly_right(*draw)]
    assert len(wrong) <= 2, wrong


def test_pal_errs_rarely_on_eight_symbols_over_four_letters():
    # the hardest draws: an 8-symbol section over 4 letters is no evidence in one string
    # (a random string of 60 holds a repeat as long 1 time in 13), only in step; measured
    # over 1,000 to 2,500 such draws PAL erred in 1.6 to 2.4 %, and 1.4 % over 3,000 with
    # the rest read at the core by what they cover (10 % when a member was read at the
    # lead's copies alone and a chance repeat at a shift of its own could be in step; that
    # reading errs in 9 of these 100). At 2.4 % about 1 block of 100 draws in 100 holds 7
    # or more wrong
    rng = np.random.default_rng(2026)
    draws = [(int(rng.integers(0, 1_000_000)), int(rng.integers(2, 7)), int(rng.integers(0, 17)),
              8, 4) for _ in range(100)]
    wrong = [draw for draw in draws if not _exactly_right(*draw)]
    assert len(wrong) <= 6, wrong


def test_a_chance_repeat_at_a_shift_of_its_own_is_not_in_step():
    # three strings play a 16-symbol section at 2 and 20; a fourth repeats 8 symbols at 4
    # and 28, inside the section's copies (each pair shares half their time) but 24 apart,
    # not 18: an 8-symbol repeat over 9 letters is rare, yet it is not played in step
    rng = np.random.default_rng(5)
    strings = {}
    for k in range(3):
        section = _draw(rng, 9, 16)
        head = _draw(rng, 9, 2)
        while head[-1] == section[0]:
            head = _draw(rng, 9, 2)
        gap = _draw(rng, 9, 2, section[-1])
        while gap[-1] == section[0]:
            gap = _draw(rng, 9, 2, section[-1])
        parts = head + section + gap + section
        strings[f"s{k}"] = parts + _draw(rng, 9, 60 - len(parts), parts[-1])
    motif = _draw(rng, 9, 8)
    before = _draw(rng, 9, 4)
    while before[-1] == motif[0]:  # (neighbours that agree would merge)
        before = _draw(rng, 9, 4)
    between = _draw(rng, 9, 16, motif[-1])
    while between[-1] == motif[0]:
        between = _draw(rng, 9, 16, motif[-1])
    strings["chance"] = before + motif + between + motif + _draw(rng, 9, 24, motif[-1])
    strings.update({f"r{k}": _draw(rng, 9, 60) for k in range(8)})
    ag = Actiongram.from_strings({n: ["abcdefghi"[c] for c in s] for n, s in strings.items()})
    result = PAL(min_copies=2).induce(ag)
    assert set(result.components) == {"s0", "s1", "s2"}


@pytest.mark.parametrize("length", [8, 10])
def test_a_short_section_over_four_letters_is_found_in_step(length):
    # one string's repeat of 8 or 10 symbols over 4 letters is no evidence (a random string
    # of 60 holds one as long about once in 13 or 130 times); three strings repeating at the
    # same times are: weighed each alone, every one of these was "not significant"
    for seed in range(10):
        ag, truth, _ = _sectioned(seed, 3, 0, length, 4)
        result = PAL(min_copies=2).induce(ag)
        assert set(result.components) == set(truth), (seed, [r.status for r in result.reports])


def test_random_strings_over_four_letters_claim_nothing():
    rng = np.random.default_rng(2)
    for _ in range(20):
        ag = Actiongram.from_strings({f"r{k}": ["abcd"[c] for c in _draw(rng, 4, 60)]
                                      for k in range(18)})
        assert PAL(min_copies=2).induce(ag).components == ()


def test_a_long_section_twice_outweighs_a_short_figure_played_often():
    assert repeat_significance(800, 40, 2, 40, 0.1) < repeat_significance(800, 4, 5, 16, 0.1)
    # exact copies are stronger than the same copies half damaged
    assert repeat_significance(100, 8, 4, 24, 0.1) < repeat_significance(100, 8, 4, 12, 0.1)
    assert repeat_significance(10, 8, 2, 8, 0.1) == pytest.approx(
        math.log10(3) - 8, rel=1e-9)


@settings(max_examples=40, deadline=None, derandomize=True)
@given(st.lists(st.integers(0, 3), min_size=4, max_size=40), st.integers(2, 3))
def test_find_section_is_the_longest_exact_repeat(codes, copies):
    codes = np.asarray(codes, dtype=np.int64)
    found = find_section(codes, copies, 64, 0.3)

    def apart(window):  # the oracle: every start, copies taken left to right
        length, kept = len(window), []
        for p in range(len(codes) - length + 1):
            if tuple(codes[p:p + length]) == window and (not kept or p - kept[-1] >= length):
                kept.append(p)
        return kept

    windows = {tuple(codes[p:p + L]) for L in range(2, len(codes) + 1)
               for p in range(len(codes) - L + 1)}
    best = max((len(w) for w in windows if len(apart(w)) >= copies), default=0)
    if best == 0:
        assert found is None
        return
    window = max((w for w in windows if len(w) == best and len(apart(w)) >= copies),
                 key=lambda w: (len(apart(w)), -apart(w)[0]))
    kept = apart(window)
    stretch = tuple(codes[kept[0]:kept[-1] + best])
    if any(window[p:] == window[:-p] and stretch[p:] == stretch[:-p]
           for p in range(1, best // 2 + 1)):
        assert found is None  # one block played over and over is left to the digram search
        return
    assert len(found.motif) == best
    assert found.starts.tolist() == apart(tuple(found.motif.tolist()))


def test_a_chance_repeat_inside_long_copies_is_not_in_step():
    long = np.array([[0.0, 16.0], [20.0, 36.0]])
    assert coincide(long, long + 0.5, 2)
    assert not coincide(long, np.array([[3.0, 9.0], [23.0, 29.0]]), 2)
    assert not coincide(long, long[:1], 2)


def test_statuses_agree_with_synchronised_with():
    ag, _, _ = _sectioned(3, 3, 12, 10, 8)
    for params in ({}, {"min_copies": 2}):
        for report in PAL(**params).induce(ag).reports:
            if report.status == "not synchronised":
                assert report.synchronised_with == ()
            if report.status in ("no repetition", "not significant"):
                assert report.synchronised_with == ()


def test_no_copy_is_reported_below_copy_agreement():
    from psgs.induce.synthetic import generate

    case = generate(seed=5, noise=0.3)
    for level in (0.5, 0.7):
        result = PAL(copy_agreement=level).induce(case.actiongram)
        for name in result.components:
            shares = result.agreements[name]
            assert len(shares) == len(result.occurrences[name])
            assert min(shares) >= level
    with pytest.raises(ValidationError, match="copy_agreement"):
        PAL(copy_agreement=1.5)


def test_sections_are_pairwise_in_step_in_a_group():
    ag, truth, _ = _sectioned(11, 4, 4, 12, 8)
    result = PAL(min_copies=2).induce(ag)
    for a, b in combinations(truth, 2):
        assert coincide(np.asarray(result.occurrences[a]), np.asarray(result.occurrences[b]), 2)


def test_an_induction_holds_one_agreement_per_occurrence():
    import pickle

    from psgs.induce import Induction

    made = Induction(None, ("k",), {"k": ("a", "b")}, {"k": ((0.0, 2.0), (2.0, 4.0))},
                     agreements={"k": (1.0, 0.5)})
    assert pickle.loads(pickle.dumps(made)).agreements == {"k": (1.0, 0.5)}
    assert made.to_dict()["agreements"] == {"k": [1.0, 0.5]}
    assert "agreements" not in Induction(None, (), {}, {}).to_dict()
    with pytest.raises(ValidationError, match="agreements"):
        Induction(None, ("k",), {"k": ("a", "b")}, {"k": ((0.0, 2.0),)},
                  agreements={"k": (1.0, 0.5)})


def _in_two_rhythms(second_rhythm: bool):
    """Three strings playing a section at the same two times; with ``second_rhythm`` the
    second copy holds the same symbols in another rhythm (each 1 a 2 and each 2 a 1)."""
    rng = np.random.default_rng(7)
    strings, durations = {}, {}
    rhythm = [float(d) for d in rng.choice([1.0, 2.0], 12)]
    again = [3.0 - d for d in rhythm] if second_rhythm else rhythm
    for k in range(3):
        section = _draw(rng, 8, 12)
        head, gap, tail = _draw(rng, 8, 4, None), _draw(rng, 8, 3, section[-1]), _draw(rng, 8, 6)
        while gap[-1] == section[0] or head[-1] == section[0] or tail[0] == section[-1]:
            gap, head, tail = _draw(rng, 8, 3, section[-1]), _draw(rng, 8, 4), _draw(rng, 8, 6)
        strings[f"s{k}"] = ["abcdefgh"[c] for c in head + section + gap + section + tail]
        durations[f"s{k}"] = [1.0] * 4 + rhythm + [1.0] * 3 + again + [1.0] * 6
    return Actiongram.from_strings(strings, durations)


def test_equal_durations_tell_a_repeat_from_the_same_symbols_in_another_rhythm():
    same, other = _in_two_rhythms(False), _in_two_rhythms(True)
    # the symbols alone cannot tell them apart
    assert PAL(min_copies=2).induce(other).components == ("s0", "s1", "s2")
    strict = PAL(min_copies=2, section_durations="equal")
    assert strict.induce(same).components == ("s0", "s1", "s2")
    assert strict.induce(same).occurrences == PAL(min_copies=2).induce(same).occurrences
    assert strict.induce(other).components == ()
    assert strict.induce(same).report("s0").motif == PAL(min_copies=2).induce(same).report(
        "s0").motif


def test_a_section_that_repeats_itself_is_found_when_its_copies_lie_apart():
    # a c a d b repeats at a shift of five inside the section; its two copies lie apart,
    # other symbols between them: a section, not one block played over and over
    section = [0, 2, 0, 3, 1, 0, 2, 0, 3, 1, 0]
    codes = np.array([1, 3, 2, 3] + section + [2, 1, 3, 2, 3, 1] + section + [3, 2, 1, 2])
    found = find_section(codes, 2, 64, 0.3)
    assert found.motif.tolist() == section and found.starts.tolist() == [4, 21]
    block = np.array([0, 1, 2] * 8)  # one block over and over: left to the digram search
    assert find_section(block, 2, 64, 0.3) is None


def test_copies_off_the_lead_alike_are_nearer_than_copies_off_it_unalike():
    # chance agreement around a section moves the edges of all its copies alike: a repeat
    # off the lead's copies by the same time in each keeps the lead's shift, and is
    # weighed as more unlikely by chance than one off by as much in all, but unalike
    section = [1, 2, 3, 4, 5, 6]
    codes = np.array([7, 8, 9, 0, 8, 9, 7, 0, 9, 8] + section + [0, 7, 8, 9, 0, 9, 7, 8, 0]
                     + section + [9, 8, 7, 0, 8, 9, 0, 7, 8])
    string = Timed.from_codes(codes, np.ones(len(codes)), 0.0)
    found = Section(codes[10:16], np.array([10, 25]), -1.0)
    copies = np.array([[10.0, 16.0], [25.0, 31.0]])
    alike = in_step_significance(string, found, copies, copies + 1.0, None)
    unalike = in_step_significance(string, found, copies,
                                   copies + np.array([[2.0, 2.0], [0.0, 0.0]]), None)
    assert alike < unalike  # (the time outside the shared parts is 4 in both)
