"""Fuzzing praxicon folders: a seed folder with its index, a record or its descriptions mutated
either loads (and survives a round trip through JSON values) or raises PraxiconError, within a
time limit.

The seed folder (tests/data/fuzz/praxicon) is written by ``fuzz_support.write_praxicon_seed``
at the current format versions; the first test fails when it is stale, which would otherwise
leave every mutated folder refused as "another version" and test nothing past that check.
Derandomised by the ``ci`` profile (tests/conftest.py); the long run is benchmarks/fuzz.py.
"""

from __future__ import annotations

import pytest
from hypothesis import given, settings

from fuzz_support import (READERS, SEEDS, apply, mutations_strategy, outcome, seed_bytes,
                          write_praxicon_seed)

SURFACES = ["praxicon-index", "praxicon-record", "praxicon-descriptions"]


def test_the_seed_folder_is_what_the_seed_writer_writes(tmp_path):
    write_praxicon_seed(tmp_path / "px")
    stored = sorted(p.relative_to(SEEDS / "praxicon") for p in (SEEDS / "praxicon").rglob("*")
                    if p.is_file())
    written = sorted(p.relative_to(tmp_path / "px") for p in (tmp_path / "px").rglob("*")
                     if p.is_file())
    assert stored == written
    for name in written:
        assert (SEEDS / "praxicon" / name).read_bytes() == (tmp_path / "px" / name).read_bytes(), \
            f"{name} is stale: run 'python tests/fuzz_support.py' to write the seed folder anew"


@pytest.mark.parametrize("name", SURFACES)
def test_the_unmutated_seed_folder_loads(name):
    assert outcome(READERS[name], seed_bytes(READERS[name], 0)) == "ok"


@pytest.mark.parametrize("name", SURFACES)
@settings(max_examples=40)
@given(mutations=mutations_strategy())
def test_mutated_folders_load_or_give_a_praxicon_error(name, mutations, tmp_path_factory):
    reader = READERS[name]
    data = apply(seed_bytes(reader, 0), mutations)
    assert outcome(reader, data, tmp_path_factory.getbasetemp()) in ("ok", "error")


@pytest.mark.parametrize("mutations", [
    [("number", 59441, 1, 6038)],  # 400 digits for a float: OverflowError
    [("json", 98, 1, 6)],          # the same for the spread's threshold
    [("json", 144, 1, 3)],         # an action's description replaced by 0: AttributeError
])
def test_what_the_fuzzer_found_in_descriptions(mutations):
    reader = READERS["praxicon-descriptions"]
    assert outcome(reader, apply(seed_bytes(reader, 0), mutations)) == "error"
