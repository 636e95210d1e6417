"""Fuzzing the motion readers: mutated BVH, ASF and AMC files either read (finite values, and
forward kinematics finite or a MotionFormatError) or raise MotionFormatError, each within a
time limit; the same for codec streams (whole, and their decompressed base part repacked),
label files, write_bvh (what it writes of a read file reads back, or a plain ValueError) and
the codec's encoder (what compress writes at a rate-controlled error decodes within it).

Derandomised by the ``ci`` profile (tests/conftest.py); the long run is benchmarks/fuzz.py.
"""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fuzz_support import READERS, apply, mutations_strategy, outcome, seed_bytes


@pytest.mark.parametrize("name", ["bvh", "asf", "amc", "codec-write"])
@settings(max_examples=75)
@given(seed=st.integers(0, 2), mutations=mutations_strategy())
def test_mutated_files_read_or_give_a_documented_error(name, seed, mutations, tmp_path_factory):
    reader = READERS[name]
    data = apply(seed_bytes(reader, seed), mutations)
    assert outcome(reader, data, tmp_path_factory.getbasetemp()) in ("ok", "error")


@pytest.mark.parametrize("name", ["bvh", "asf", "amc", "codec-write"])
def test_the_unmutated_seeds_read(name):
    assert outcome(READERS[name], seed_bytes(READERS[name], 0)) == "ok"


KINETOLOGY_MORE = ["codec", "codec-body", "bvh-write", "truelabels", "bandai-label"]


@pytest.mark.parametrize("name", KINETOLOGY_MORE)
@settings(max_examples=60)
@given(seed=st.integers(0, 1), mutations=mutations_strategy())
def test_streams_labels_and_written_files_too(name, seed, mutations, tmp_path_factory):
    reader = READERS[name]
    data = apply(seed_bytes(reader, seed), mutations)
    assert outcome(reader, data, tmp_path_factory.getbasetemp()) in ("ok", "error")


@pytest.mark.parametrize("name", KINETOLOGY_MORE)
def test_their_unmutated_seeds_read(name):
    for seed in range(len(READERS[name].seeds)):
        assert outcome(READERS[name], seed_bytes(READERS[name], seed)) == "ok"


@pytest.mark.parametrize("mutations", [
    [("insert", 10356, 1, 34788), ("delete", 13704, 1, 53680)],  # "[" x 2000: RecursionError
    [("byte", 44097, 1, 3107), ("byte", 47065, 2, 8413), ("insert", 34716, 200, 63559),
     ("number", 964, 20, 58491)],                                 # 5,000 digits: ValueError
])
def test_what_the_long_run_found_in_bandai_labels(mutations):
    reader = READERS["bandai-label"]
    assert outcome(reader, apply(seed_bytes(reader, 0), mutations)) == "error"
