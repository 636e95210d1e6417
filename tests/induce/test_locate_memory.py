"""Extreme actiongram shapes for locate: memory that follows the input, not its product with
the alphabet.

A long take of many channels is sampled on a grid of at most 4,096 points per string; the
cycle scores of ``method="joints"`` then compare every channel with itself at every lag.
Batched over channels, those comparisons once held (state, channel, point) arrays whole:
500 channels of ten minutes over 16 states peaked at 352 MiB, over 64 states (before the
alphabet fix) at 1.2 GiB. They are now taken in slices of channels, and the call's peak is
the grid's sampling, the same for any alphabet.
"""

from __future__ import annotations

import tracemalloc

import numpy as np
import pytest

from psgs import Actiongram
from psgs.induce import Induction, locate


def _long_take(strings: int, alphabet: int, seconds: float = 600.0) -> Actiongram:
    """``strings`` channels (three a joint) cycling through four states, now and then
    another of ``alphabet``, every segment 0.2-0.3 s."""
    rng = np.random.default_rng(0)
    letters = [f"s{i}" for i in range(alphabet)]
    count = int(seconds / 0.25)
    names, symbols, durations, displacements = [], [], [], []
    for i in range(strings):
        cycle = np.array([(k + i) % 4 for k in range(count)])
        other = rng.integers(4, alphabet, count) if alphabet > 4 else cycle
        codes = np.where(rng.random(count) < 0.8, cycle, other)
        codes = codes[np.concatenate([[True], codes[1:] != codes[:-1]])]
        names.append(f"j{i // 3}.r{'xyz'[i % 3]}")
        symbols.append(tuple(letters[c] for c in codes))
        durations.append(tuple(rng.uniform(0.2, 0.3, len(codes)).tolist()))
        displacements.append(tuple(rng.normal(0, 20, len(codes)).tolist()))
    return Actiongram(tuple(names), tuple(symbols), tuple(durations),
                      segment_displacements=tuple(displacements),
                      string_actuators=tuple(n.split(".")[0] for n in names))


# over 16 states batches of channels are what the bound tells apart: unbatched, the ten
# minutes peaked at 382 MiB (184 batched), and half as long would pass unbatched too. Over 64
# states each channel is its own batch, slower by the row: five minutes (peaks of 111 MiB;
# 805 MiB with the channels in one batch, as before the alphabet fix) tell the two apart as
# ten did (183 and 1,226 MiB) in half the time
@pytest.mark.parametrize("alphabet, seconds", [(16, 600.0), (64, 300.0)])
def test_locate_over_500_long_strings_peaks_below_256_mib(alphabet, seconds):
    take = _long_take(500, alphabet, seconds)
    channels = take.names[:3]
    learned = Induction(None, channels, {c: ("s0", "s1", "s2", "s3") for c in channels},
                        {c: tuple((k, k + 1.0) for k in range(6)) for c in channels},
                        inducer="pal", performances=2, actuators=("j0",),
                        actuator_channels={"j0": channels})
    tracemalloc.start()
    try:
        locate(learned, take, method="joints")
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 256 * 2 ** 20, f"peak {peak / 2 ** 20:.0f} MiB"
