"""PAL's compiled motif search (engine="numba") against numpy's: the same motifs to the bit.

Every motif (codes, copy starts, significance as a float, dtypes) and every Induction must
be identical between the engines; the strings drawn here are those where the search has
edge cases: tiny strings, one-symbol alphabets, exact tilings (the rotation), noisy repeats
(the bridged columns, the level-by-level copy choice), long alphabets (the digrams sorted
instead of counted). numba is in the test extra, so these run (the compile is done by the
warm-up in tests/conftest.py).
"""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import Actiongram
from psgs.induce import PAL
from psgs._foundation import engines
from psgs.induce.pal import _motifs_jit
from psgs.induce.pal.content import find_candidates
from psgs.induce.pal.learner import encode
from psgs.induce.pal.motifs import (Timed, _symbol_statistics, find_motif, find_motifs, grow,
                                    locate_copies)
from psgs.induce.pal.synchronisation import synchronised, synchronised_pairs
from psgs.induce.synthetic import generate

numba = pytest.importorskip("numba", reason="the compiled engine needs numba (test extra)")

NUMPY, NUMBA = PAL(engine="numpy"), PAL(engine="numba")


def same_motif(a, b) -> bool:
    if a is None or b is None:
        return a is None and b is None
    return (a.motif.dtype == b.motif.dtype and a.starts.dtype == b.starts.dtype
            and np.array_equal(a.motif, b.motif) and np.array_equal(a.starts, b.starts)
            and math.copysign(1.0, a.significance) == math.copysign(1.0, b.significance)
            and a.significance == b.significance)


def check(strings: list[np.ndarray], params: PAL = NUMPY) -> None:
    compiled = find_motifs(strings, params.clone(engine="numba"))
    for codes, got in zip(strings, compiled):
        assert same_motif(find_motif(codes, params), got), codes.tolist()


def _as_codes(values) -> np.ndarray:
    return np.asarray(values, dtype=np.int64)


tiny = st.lists(st.integers(0, 3), max_size=6).map(_as_codes)
one_symbol = st.integers(0, 60).map(lambda n: np.zeros(n, dtype=np.int64))


@st.composite
def tilings(draw):
    """A motif repeated exactly, the string starting anywhere inside a copy."""
    motif = draw(st.lists(st.integers(0, 5), min_size=1, max_size=9))
    copies = draw(st.integers(1, 12))
    offset = draw(st.integers(0, len(motif) - 1))
    return _as_codes((motif * (copies + 1))[offset:offset + copies * len(motif)])


@st.composite
def noisy_repeats(draw):
    """Copies of a motif between random symbols, some positions replaced."""
    alphabet = draw(st.integers(2, 12))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    motif = rng.integers(0, alphabet, draw(st.integers(2, 12)))
    parts = [rng.integers(0, alphabet, draw(st.integers(0, 6)))]
    for _ in range(draw(st.integers(2, 15))):
        parts += [motif, rng.integers(0, alphabet, int(rng.integers(0, 4)))]
    codes = np.concatenate(parts).astype(np.int64)
    damaged = rng.random(len(codes)) < draw(st.sampled_from([0.0, 0.05, 0.15, 0.3]))
    codes[damaged] = rng.integers(0, alphabet, int(damaged.sum()))
    return codes


@st.composite
def long_alphabets(draw):
    """Many distinct symbols (more digram kinds than the counting table takes)."""
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    n = draw(st.integers(4, 400))
    codes = rng.integers(0, draw(st.sampled_from([50, 500, 5000])), n)
    if draw(st.booleans()):  # a repeat among them
        motif = rng.integers(0, 50, 5)
        for start in range(0, n - 5, max(6, n // 6)):
            codes[start:start + 5] = motif
    return codes.astype(np.int64)


@settings(max_examples=250)
@given(st.lists(st.one_of(tiny, one_symbol, tilings(), noisy_repeats(), long_alphabets()),
                min_size=1, max_size=8))
def test_both_engines_find_the_same_motifs(strings):
    check(strings)


@settings(max_examples=75)
@given(st.lists(noisy_repeats(), min_size=1, max_size=4),
       st.builds(dict, min_copies=st.integers(2, 5), conserve=st.sampled_from([0.4, 0.6, 0.9]),
                 match_fraction=st.sampled_from([0.3, 0.5, 0.8]),
                 scan_alpha=st.sampled_from([0.001, 0.05, 1.0]),
                 max_pattern=st.integers(2, 16), seeds=st.integers(1, 5)))
def test_both_engines_agree_under_other_parameters(strings, params):
    check(strings, PAL(**params))


def test_a_chance_level_on_the_boundary_is_left_to_numpy():
    # scan_alpha set to the very chance level of a window threshold: the kernel cannot
    # decide it in its own floats, marks the string uncertain and numpy searches it
    codes = _as_codes([0, 1, 2, 3] * 6 + [1, 3, 0, 2, 2, 0])
    n, size = len(codes), 4
    freq = np.bincount(codes, minlength=size) / n
    rate = float(np.sum(freq ** 2))
    from psgs.induce.pal.statistics import log10_binom_sf
    alpha = (n - 3 + 1) * 10 ** log10_binom_sf(2, 3, rate)  # the first column grown
    params = PAL(scan_alpha=alpha)
    status = _motifs_jit.find_motifs(
        codes, np.array([0, n]), np.array([size]), np.array([rate]), np.array([math.log(rate)]),
        np.array([math.log1p(-rate)]), np.array([math.log10(4)]), 3, 3, 0.6, 0.5, alpha,
        64)[0]
    assert status.tolist() == [_motifs_jit.UNCERTAIN]
    check([codes], params)


@pytest.mark.parametrize("noise", [0.0, 0.1, 0.2, 0.25, 0.3])
@pytest.mark.parametrize("variant", [{}, {"durations": "random"}, {"irregular_gaps": True},
                                     {"unequal_lengths": True},
                                     {"durations": "random", "irregular_gaps": True,
                                      "unequal_lengths": True}])
def test_both_engines_give_the_same_induction(noise, variant):
    for seed in range(4):
        ag = generate(seed=seed, noise=noise, **variant).actiongram
        expected = NUMPY.induce(ag)
        assert NUMBA.induce(ag) == expected
        assert PAL().induce(ag) == expected  # auto: numba here


def test_the_same_candidates_and_partners_on_many_strings():
    case = generate(seed=3, noise=0.15, strings=120, patterned=12, templates=12, copies=12)
    strings, _ = encode(case.actiongram)
    a, b = find_candidates(strings, NUMPY), find_candidates(strings, NUMBA)
    assert a.candidates == b.candidates and a.partners == b.partners
    assert len(a.candidates) >= 12 and sum(map(len, a.partners.values())) > 0


@st.composite
def copy_lists(draw):
    """Copy intervals in time order, touching, overlapping or apart, some out of order."""
    count = draw(st.integers(0, 8))
    starts = np.cumsum(draw(st.lists(st.sampled_from([0.0, 0.5, 1.0, 2.0, 3.0]),
                                     min_size=count, max_size=count)))
    widths = draw(st.lists(st.sampled_from([0.0, 0.5, 1.0, 2.5]), min_size=count,
                           max_size=count))
    spans = np.column_stack((starts, starts + np.asarray(widths))) if count \
        else np.zeros((0, 2))
    if count > 1 and draw(st.booleans()):
        spans = spans[::-1].copy()
    return spans


@settings(max_examples=75)
@given(st.lists(copy_lists(), min_size=2, max_size=6), st.sampled_from([0.3, 0.5, 1.0]),
       st.integers(1, 4))
def test_both_engines_synchronise_the_same_pairs(lists, fraction, copies):
    params = PAL(sync_fraction=fraction, min_copies=max(2, copies))
    expected = [(i, j) for i in range(len(lists)) for j in range(i + 1, len(lists))
                if synchronised(lists[i], lists[j], fraction, params.min_copies)]
    assert synchronised_pairs(lists, params.clone(engine="numba")) == expected
    assert synchronised_pairs(lists, params.clone(engine="numpy")) == expected


def test_an_unknown_engine_is_refused_by_name():
    with pytest.raises(ValueError, match="engine must be one of 'auto', 'numpy', 'numba', "
                                         "not 'fortran'"):
        PAL(engine="fortran")
    with pytest.raises(ValueError, match="engine must be one of"):
        PAL(engine=None)


def test_numba_asked_for_without_numba_is_an_import_error(monkeypatch):
    monkeypatch.setattr(engines, "numba_missing", lambda: "No module named 'numba'")
    ag = generate(seed=1, noise=0.1).actiongram
    with pytest.raises(ImportError, match=r"pip install 'psgs\[fast\]'"):
        PAL(engine="numba").induce(ag)
    # auto falls back to numpy's engine, with the same result
    assert PAL().induce(ag) == NUMPY.induce(ag)


def test_the_engine_is_a_parameter_like_any_other():
    pal = PAL(engine="numpy", min_copies=4)
    assert pal.get_params()["engine"] == "numpy"
    assert pal.clone().engine == "numpy" and pal.clone(engine="numba").engine == "numba"
    assert PAL().engine == "auto"
    # it changes how PAL computes, never what it finds: the Induction does not record it
    assert "engine" not in pal.induce(generate(seed=1).actiongram).params


@settings(max_examples=100)
@given(st.lists(st.one_of(tiny, one_symbol, noisy_repeats(), long_alphabets(),
                          st.lists(st.integers(0, 300), max_size=300).map(_as_codes)),
                min_size=1, max_size=12))
def test_symbol_statistics_are_each_strings_own(strings):
    # the match rates summed row by row of one array are those of each string alone
    bounds = np.concatenate(([0], np.cumsum([len(c) for c in strings]))).astype(np.int64)
    sizes, distinct, rates = _symbol_statistics(np.concatenate(strings), bounds, 3)
    for i, codes in enumerate(strings):
        if len(codes) < 6:
            assert sizes[i] == distinct[i] == rates[i] == 0
            continue
        freq = np.bincount(codes) / len(codes)
        assert sizes[i] == len(freq) and distinct[i] == np.count_nonzero(freq)
        assert rates[i] == float(np.sum(freq ** 2))


@settings(max_examples=200)
@given(noisy_repeats(), st.integers(0, 2**32 - 1), st.booleans())
def test_both_engines_grow_a_motif_the_same(codes, seed, from_a_copy):
    # as pooling.relocate grows a voted pattern from the copies the scan located
    rng = np.random.default_rng(seed)
    length = int(rng.integers(2, min(8, len(codes)) + 1))
    at = int(rng.integers(0, len(codes) - length + 1))
    motif = codes[at:at + length].copy() if from_a_copy \
        else rng.integers(0, int(codes.max()) + 1, length)
    freq = np.bincount(codes) / len(codes)
    rate, distinct = float(np.sum(freq ** 2)), int(np.count_nonzero(freq))
    starts = locate_copies(codes, motif, max(2, length // 2))
    expected = grow(codes, motif, starts, rate, distinct, NUMPY)
    assert same_motif(grow(codes, motif, starts, rate, distinct, NUMBA), expected)


@st.composite
def actiongrams(draw):
    """Strings of 0 to 60 symbols from a pool of one-character (some beyond the BMP, some
    of many) or longer symbols, positive durations, any origins."""
    pool = draw(st.sampled_from([list("abcde"), [chr(0x4E00 + k) for k in range(300)],
                                 ["a", "\U0001F600", "b"], ["ab", "c", "dd", "e"]]))
    count = draw(st.integers(1, 6))
    rng = np.random.default_rng(draw(st.integers(0, 2**32 - 1)))
    same = draw(st.booleans())  # strings of one length take encode's array path
    length = int(rng.integers(0, 60))
    symbols = [tuple(pool[k] for k in rng.integers(0, len(pool),
                                                    length if same else int(rng.integers(0, 60))))
               for _ in range(count)]
    durations = [tuple(float(d) for d in rng.exponential(1.0, len(s)) + 1e-3) for s in symbols]
    origins = [float(o) for o in rng.normal(0, 10, count)]
    return Actiongram(tuple(f"s{i}" for i in range(count)), tuple(symbols), tuple(durations),
                      tuple(origins))


@settings(max_examples=75)
@given(actiongrams())
def test_encode_is_each_strings_own_coding(ag):
    # codes numbered in order of first appearance, times summed string by string
    alphabet: dict[str, int] = {}
    for syms in ag.symbols:
        for sym in syms:
            alphabet.setdefault(sym, len(alphabet))
    strings, symbols = encode(ag)
    assert symbols == list(alphabet)
    for timed, syms, durations, origin in zip(strings, ag.symbols, ag.segment_durations,
                                              ag.origins):
        own = Timed.from_codes(np.asarray([alphabet[s] for s in syms], dtype=np.int64),
                               np.asarray(durations, dtype=np.float64), origin)
        assert timed.codes.dtype == own.codes.dtype and timed.codes.tolist() == own.codes.tolist()
        assert timed.starts.tobytes() == own.starts.tobytes()
        assert timed.ends.tobytes() == own.ends.tobytes()


def test_the_threaded_search_is_the_single_threaded_one(monkeypatch):
    # from _THREADED_SYMBOLS on, two threads search two runs of strings into shared arrays
    from psgs.induce.pal import motifs
    case = generate(seed=5, noise=0.2, strings=200, patterned=16, templates=16, copies=12)
    strings = [s.codes for s in encode(case.actiongram)[0]]
    monkeypatch.setattr(motifs, "_THREADED_SYMBOLS", 1 << 62)
    alone = find_motifs(strings, NUMBA)
    monkeypatch.setattr(motifs, "_THREADED_SYMBOLS", 1000)
    monkeypatch.setattr(motifs, "usable_cores", lambda: 2)  # threads even on one core
    threaded = find_motifs(strings, NUMBA)
    assert all(same_motif(a, b) for a, b in zip(alone, threaded))
    assert all(same_motif(a, find_motif(c, NUMPY)) for a, c in zip(alone, strings))
