"""The weights of sections in step, many rows at once, against one row at a time.

A group of N strings in step weighs every string at every lead's copies (N^2 weights); they
are computed a batch of rows at a time (``in_step_weight.in_step_weights``) and must be, to
the bit, ``in_step_significance`` of each row (the oracle here).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs.induce.pal import in_step_weight
from psgs.induce.pal.in_step_weight import in_step_significance, in_step_weights
from psgs.induce.pal.motifs import Timed
from psgs.induce.pal.sections import Section


def _row(rng: np.random.Generator, many_copies: bool):
    """A random string, a section of it, its copies' times and lead copies near them (or
    anywhere), and a follow rate: one row of in_step_weights."""
    n = int(rng.integers(4, 80))
    durations = rng.choice([1.0, 0.5, 2.0, 1.25], n) if rng.random() < 0.5 else np.ones(n)
    codes = rng.integers(0, 5, n)
    string = Timed.from_codes(codes, durations, float(rng.integers(0, 3)))
    length = int(rng.integers(1, max(2, n // 3)))
    count = int(rng.integers(1, 13 if many_copies else 6))
    starts = np.sort(rng.choice(n - length + 1, min(count, n - length + 1), replace=False))
    section = Section(codes[starts[0]:starts[0] + length].copy(), starts, 0.0)
    copies = string.copy_times(section)
    if rng.random() < 0.5:  # near the copies: in step, or off by a little in some
        lead = copies + rng.choice([0.0, 0.5, 1.0, -1.0, 0.25], copies.shape)
        if rng.random() < 0.3:
            lead = lead[:max(1, len(lead) - 1)]
    else:
        at = np.sort(rng.uniform(0, float(string.ends[-1]), int(rng.integers(1, 6))))
        lead = np.column_stack((at, at + rng.uniform(0.5, 3 * length, len(at))))
    follow = None if rng.random() < 0.5 else float(rng.uniform(0.05, 1.0))
    return string, section, copies, lead, follow


@pytest.mark.parametrize("cells, bits", [(in_step_weight._BATCH_CELLS, 62), (300, 62),
                                         (in_step_weight._BATCH_CELLS, 0)])
@settings(max_examples=75, deadline=None, derandomize=True)
@given(seed=st.integers(0, 2**32 - 1), rows=st.integers(1, 12), many=st.booleans())
def test_the_weights_of_many_rows_are_each_row_s_own(cells, bits, seed, rows, many):
    # (300 cells: batches of a few rows, rows longer than a batch weighed alone and a part
    # of the sets at a time; 0 bits: the sets' keys sorted as pairs, not as one integer)
    kept = in_step_weight._BATCH_CELLS, in_step_weight._KEY_BITS
    in_step_weight._BATCH_CELLS, in_step_weight._KEY_BITS = cells, bits
    try:
        rng = np.random.default_rng(seed)
        drawn = [_row(rng, many) for _ in range(rows)]
        assert in_step_weights(drawn) == [in_step_significance(*row) for row in drawn]
    finally:
        in_step_weight._BATCH_CELLS, in_step_weight._KEY_BITS = kept


def test_the_drawn_rows_reach_every_case_of_the_weight():
    # the draws above hold weights in step, off the shift (inf), copies ranked copy by copy
    # (more than 4,096 sets) and copies that pair with no lead copy
    rng = np.random.default_rng(0)
    seen = {"finite": 0, "inf": 0, "split": 0, "unpaired": 0}
    for _ in range(400):
        string, section, copies, lead, follow = _row(rng, True)
        weight = in_step_significance(string, section, copies, lead, follow)
        seen["finite" if weight < math.inf else "inf"] += 1
        begins = string.starts[:len(string.codes) - len(section.motif) + 1]
        ends = string.ends[len(section.motif) - 1:]
        sizes = []
        for a, b in copies.tolist():
            near = [(lo, hi) for lo, hi in lead.tolist() if _pair((a, b), (lo, hi))]
            if not near:
                seen["unpaired"] += 1
                continue
            lo, hi = min(near, key=lambda c: max(b, c[1]) - min(a, c[0])
                         - (min(b, c[1]) - max(a, c[0])))
            sizes.append(sum(_pair(w, (lo, hi)) for w in zip(begins.tolist(), ends.tolist())))
        seen["split"] += len(sizes) > 1 and math.prod(sizes) > 1 << 12
    assert min(seen.values()) >= 5, seen


def _pair(copy, lead) -> bool:
    (a, b), (c, d) = copy, lead
    shared, union = min(b, d) - max(a, c), max(b, d) - min(a, c)
    return shared > 0 and 2 * shared >= union
