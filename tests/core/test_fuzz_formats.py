"""Fuzzing the psgs readers: mutated grammar files, actiongrams (text and JSON) and events tables either read
(and survive a round trip) or raise FormatError/ValidationError, each within a time limit.

Derandomised by the ``ci`` profile (tests/conftest.py); the long run is benchmarks/fuzz.py.
"""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from fuzz_support import READERS, apply, mutations_strategy, outcome, seed_bytes


@pytest.mark.parametrize("name", ["grammar", "actiongram-text", "actiongram-json", "events-csv"])
@settings(max_examples=75)
@given(seed=st.integers(0, 2), mutations=mutations_strategy())
def test_mutated_files_read_or_give_a_documented_error(name, seed, mutations, tmp_path_factory):
    reader = READERS[name]
    data = apply(seed_bytes(reader, seed), mutations)
    assert outcome(reader, data, tmp_path_factory.getbasetemp()) in ("ok", "error")


@pytest.mark.parametrize("name", ["grammar", "actiongram-text", "actiongram-json", "events-csv"])
def test_the_unmutated_seeds_read(name):
    reader = READERS[name]
    for k in range(len(reader.seeds)):
        assert outcome(reader, seed_bytes(reader, k)) == "ok"
