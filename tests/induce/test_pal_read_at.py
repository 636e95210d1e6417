"""Reading a string at a lead's copies: the pruned search against weighing every candidate."""

from __future__ import annotations

import numpy as np
import pytest

from psgs import Actiongram
from psgs.induce import PAL
from psgs.induce.pal import in_step, shift_runs
from psgs.induce.pal.in_step import in_step_significance, read_at
from psgs.induce.pal.pairing import lead_segments, spans_pair
from psgs.induce.pal.motifs import Timed
from psgs.induce.pal.sections import Section, _cycles


def _every_candidate(string: Timed, lead: np.ndarray, follow, need=None):
    """The oracle: every maximal run between the two copies' segments at every shift, each
    of its windows and its part under the lead's copies that pairs with both copies
    weighed, the first of the lightest kept in the grid's order on strings this short (one
    block of shifts): every run's windows, by shift and run, before the runs' parts under
    the lead's copies (None when it is heavier than ``need``)."""
    codes, starts, ends = string.codes, string.starts, string.ends
    n = len(codes)
    segments = lead_segments(string, lead)
    if segments is None:
        return None
    first, second = segments
    in_first, in_second = set(first.tolist()), set(second.tolist())  # (looked up per symbol)
    reach = len(first) + len(second)
    best = None
    for shift in range(max(1, int(second[0] - first[-1])), int(second[-1] - first[0]) + 1):
        lo, hi = max(0, int(first[0]) - reach), min(n - shift, int(first[-1]) + reach + 1)
        if hi - lo < 2:
            continue
        equal = np.concatenate(([False], codes[lo:hi] == codes[lo + shift:hi + shift], [False]))
        edges = np.flatnonzero(np.diff(equal.astype(np.int8)))
        for begin, end in zip((edges[::2] + lo).tolist(), (edges[1::2] + lo).tolist()):
            if end - begin < 2:
                continue
            if (begin == lo and lo > 0) or (end == hi and hi < n - shift):
                continue
            length = min(end - begin, shift)
            windows = [(s, length, True) for s in range(begin, end - length + 1)]
            # the run's part under the lead's copies: each position's segment under the
            # first copy and its partner's under the second, at most a shift long
            under = [p for p in range(begin, end) if p in in_first and p + shift in in_second]
            if under:
                cut = (under[0], min(under[-1] + 1, under[0] + shift) - under[0])
                if cut != (begin, end - begin) and cut[1] >= 2:
                    windows.append((*cut, False))
            for s, length, maximal in windows:
                where = np.array([[starts[s], ends[s + length - 1]],
                                  [starts[s + shift], ends[s + length - 1 + shift]]])
                if not all(spans_pair(w, c) for w, c in zip(where.tolist(), lead.tolist())):
                    continue
                if _cycles(codes, (s, s + shift), length):
                    continue
                motif = codes[s:s + length].copy()
                section = Section(motif, np.array([s, s + shift], dtype=np.int64), 0.0)
                weight = in_step_significance(string, section, where, lead, follow, maximal)
                if weight < np.inf and (best is None or (weight, not maximal) < best[2]):
                    best = (weight, section, (weight, not maximal))
    best = None if best is None else best[:2]
    return None if need is not None and best is not None and best[0] > need else best


def _same(a, b) -> bool:
    if a is None or b is None:
        return a is b
    return (a[0] == b[0] and a[1].motif.tolist() == b[1].motif.tolist()
            and a[1].starts.tolist() == b[1].starts.tolist())


def _short(seed: int) -> tuple[Timed, np.ndarray]:
    """A short string over two or three letters and two lead copies' times."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(6, 40))
    codes = rng.integers(0, int(rng.integers(2, 4)), n)
    durations = np.ones(n) if seed % 3 else rng.choice([0.5, 1.0, 1.5], n)
    string = Timed.from_codes(codes, durations, 0.0)
    if seed % 2:  # copies on segment edges
        a, length = int(rng.integers(0, n // 2)), int(rng.integers(2, n // 2 + 1))
        b = int(rng.integers(a + 1, n - length + 1)) if a + 1 < n - length + 1 else a + 1
        lead = np.array([[string.starts[min(a, n - 1)], string.ends[min(a + length, n) - 1]],
                         [string.starts[min(b, n - 1)], string.ends[min(b + length, n) - 1]]])
    else:
        lead = np.sort(rng.uniform(0, float(string.ends[-1]), 4)).reshape(2, 2)
    return string, lead


@pytest.mark.parametrize("follow", [None, 0.5, 0.99, 0.0])
def test_read_at_is_the_lightest_of_every_candidate(follow):
    # short strings over two or three letters: many runs at many shifts, and ties; a
    # follow rate near 1 makes the left-end term (the part of the bound that is not the
    # chance agreement) large enough to matter; at 0 every candidate weighs -inf, and the
    # order alone decides
    for seed in range(1200):
        string, lead = _short(seed)
        assert _same(read_at(string, lead, follow), _every_candidate(string, lead, follow)), seed


@pytest.mark.parametrize("follow", [None, 0.99])
def test_every_run_found_from_equal_windows_gives_the_grids_answer(follow, monkeypatch):
    # windows of two symbols find every run the grid does: on the same draws, many ties
    # among them, the runs' candidates must keep the grid's order
    monkeypatch.setattr(in_step, "_GRID_CELLS", 0)
    monkeypatch.setattr(in_step, "_RUN_FLOORS", (2,))
    monkeypatch.setattr(in_step, "grid_runs", None)  # (never reached)
    for seed in range(600):
        string, lead = _short(seed)
        assert _same(read_at(string, lead, follow), _every_candidate(string, lead, follow)), seed


@pytest.mark.parametrize("block", [40, 200])
def test_runs_from_equal_windows_keep_the_grids_order_block_by_block(block, monkeypatch):
    # the grid is filled a block of shifts at a time and its candidates are ordered block
    # by block (which breaks ties between equally light ones): with small blocks, the runs
    # found from windows of two symbols must give the grid's answer on every draw
    monkeypatch.setattr(shift_runs, "_BLOCK_CELLS", block)
    for seed in range(600):
        string, lead = _short(seed)
        for follow in (None, 0.99):
            monkeypatch.setattr(in_step, "_GRID_CELLS", 1 << 40)
            grid = read_at(string, lead, follow)
            monkeypatch.setattr(in_step, "_GRID_CELLS", 0)
            monkeypatch.setattr(in_step, "_RUN_FLOORS", (2,))
            assert _same(read_at(string, lead, follow), grid), (seed, follow)


def _actiongram(seed: int) -> Actiongram:
    """Strings over few letters, some playing a section twice at shared times, some random."""
    rng = np.random.default_rng(seed)
    letters = "abcde"[:int(rng.integers(3, 6))]
    strings = {}
    section_at, gap = int(rng.integers(0, 8)), int(rng.integers(1, 6))
    for k in range(int(rng.integers(2, 7))):
        body = list(rng.choice(list(letters), 50))
        if k < 3:
            length = int(rng.integers(5, 12))
            section = body[section_at:section_at + length]
            body[section_at + length + gap:section_at + 2 * length + gap] = section
        strings[f"s{k}"] = [c for i, c in enumerate(body) if i == 0 or c != body[i - 1]]
    return Actiongram.from_strings(strings)


@pytest.mark.parametrize("seed", range(12))
def test_inductions_are_the_same_as_with_every_candidate_weighed(seed, monkeypatch):
    ag = _actiongram(seed)
    fast = PAL(min_copies=2).induce(ag)
    monkeypatch.setattr(in_step, "read_at", _every_candidate)
    assert PAL(min_copies=2).induce(ag) == fast


def _planted(seed: int) -> tuple[Timed, np.ndarray, float | None]:
    """A string over two to four letters repeating a stretch of 6 to 15 symbols, and lead
    copies at (or half a beat off) the stretch's two times."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(50, 120))
    codes = rng.integers(0, int(rng.integers(2, 5)), n)
    length = int(rng.integers(6, 16))
    a = int(rng.integers(0, n // 3))
    b = int(rng.integers(a + length, n - length))
    codes[b:b + length] = codes[a:a + length]
    durations = np.ones(n) if seed % 3 else rng.choice([0.5, 1.0, 1.5], n)
    string = Timed.from_codes(codes, durations, 0.0)
    lead = np.array([[string.starts[a], string.ends[a + length - 1]],
                     [string.starts[b], string.ends[b + length - 1]]])
    if seed % 2:
        lead = lead + rng.integers(-1, 2, (2, 2)) * 0.5
    return string, lead, [None, 0.5, 0.9][seed % 3]


@pytest.mark.parametrize("floors", [(6,), (10, 4)])
def test_the_long_runs_first_give_the_lightest_of_every_candidate(floors, monkeypatch):
    # long copies are searched for long runs from equal windows before the grid of every
    # shift: forced here on short strings, the answer must still be the oracle's, and the
    # long runs alone must answer in most draws (else the test would only see the grid)
    monkeypatch.setattr(in_step, "_GRID_CELLS", 0)
    monkeypatch.setattr(in_step, "_RUN_FLOORS", floors)
    grids = []
    grid_runs = in_step.grid_runs
    monkeypatch.setattr(in_step, "grid_runs", lambda frame: grids.append(1) or grid_runs(frame))
    for seed in range(150):
        string, lead, follow = _planted(seed)
        assert _same(read_at(string, lead, follow), _every_candidate(string, lead, follow)), seed
    assert len(grids) < 100


def test_colliding_window_hashes_fall_back_to_the_grid(monkeypatch):
    # every window given one hash: the runs built from them fail the symbol-by-symbol check
    # (or are too many pairs), and the grid answers
    monkeypatch.setattr(in_step, "_GRID_CELLS", 0)
    monkeypatch.setattr(shift_runs, "_window_hashes",
                        lambda codes, length: np.zeros(len(codes) - length + 1, np.uint64))
    for seed in range(40):
        string, lead, follow = _planted(seed)
        assert _same(read_at(string, lead, follow), _every_candidate(string, lead, follow)), seed


@pytest.mark.parametrize("need", [-1.5, -3.0])
@pytest.mark.parametrize("cells", [0, in_step._GRID_CELLS])
def test_a_reading_asked_to_be_as_light_as_need_is_the_oracles_or_none(need, cells,
                                                                       monkeypatch):
    # a caller that keeps only readings as light as ``need`` gets the same reading when it
    # is, and None when it is not, though on long copies only runs that could be that
    # light are looked for, and on short ones (the grid of every shift: ``cells`` as
    # committed) no candidate whose bound is heavier is weighed
    monkeypatch.setattr(in_step, "_GRID_CELLS", cells)
    answered = 0
    for seed in range(150):
        string, lead, follow = _planted(seed)
        expected = _every_candidate(string, lead, follow, need)
        assert _same(read_at(string, lead, follow, need), expected), seed
        answered += expected is not None
    assert 20 < answered < 150  # (both answers seen)


def test_cycles_is_its_definition_on_random_and_periodic_windows():
    # the shifts are tried short ones first, then only where the first symbols agree: the
    # verdict must be the definition's, shift by shift, on windows that are cycles and not
    def defined(codes, starts, length):
        first, last = int(starts[0]), int(starts[-1]) + length
        motif, stretch = codes[first:first + length], codes[first:last]
        return any(np.array_equal(motif[p:], motif[:-p])
                   and np.array_equal(stretch[p:], stretch[:-p])
                   for p in range(1, length // 2 + 1))

    rng = np.random.default_rng(3)
    seen = set()
    for _ in range(3000):
        period, n = int(rng.integers(1, 25)), int(rng.integers(4, 160))
        codes = np.resize(rng.integers(0, 4, period), n)
        noisy = rng.random(n) < rng.choice([0.0, 0.01, 0.3])
        codes[noisy] = rng.integers(0, 4, int(noisy.sum()))
        length = int(rng.integers(2, n // 2 + 1))
        a = int(rng.integers(0, n - 2 * length + 1))
        b = int(rng.integers(a + length, n - length + 1))
        verdict = _cycles(codes, (a, b), length)
        assert verdict == defined(codes, (a, b), length)
        seen.add(verdict)
    assert seen == {True, False}


def test_the_runs_checked_a_few_symbols_at_a_time_give_the_same_answer(monkeypatch):
    # the runs found from equal windows are checked symbol by symbol in batches (their
    # symbols together may be many times the pairs): batches of one run, or a few symbols,
    # must find what one batch does, and a run a hash collision made up must still fail
    monkeypatch.setattr(in_step, "_GRID_CELLS", 0)
    monkeypatch.setattr(in_step, "_RUN_FLOORS", (6,))
    for size in (1, 9):
        monkeypatch.setattr(shift_runs, "_CHECK_SYMBOLS", size)
        for seed in range(60):
            string, lead, follow = _planted(seed)
            assert _same(read_at(string, lead, follow), _every_candidate(string, lead, follow))
    # (a window's symbols summed: windows that agree hash alike, and many that do not)
    monkeypatch.setattr(shift_runs, "_window_hashes", lambda codes, length: np.convolve(
        codes.astype(np.int64), np.ones(length, np.int64), "valid").astype(np.uint64))
    for seed in range(60):
        string, lead, follow = _planted(seed)
        assert _same(read_at(string, lead, follow), _every_candidate(string, lead, follow))


def test_a_made_up_run_in_the_last_batch_is_caught(monkeypatch):
    # one pair of windows made equal by a collision, at the largest shift (the last run in
    # order), with one run a batch: the check must reach it and refuse the runs
    from psgs.induce.pal.sections import _window_hashes

    monkeypatch.setattr(shift_runs, "_CHECK_SYMBOLS", 1)
    tried = 0
    for seed in range(60):
        string, lead, _ = _planted(seed)
        frame = in_step._frame_of(string, lead)
        floor, codes = 6, string.codes
        if frame is None or shift_runs.long_runs(frame, floor) is None:
            continue
        p, shift = frame.lo, frame.top
        if p + floor > frame.his(np.array([shift]))[0] or np.array_equal(
                codes[p:p + floor], codes[p + shift:p + shift + floor]):
            continue

        def colliding(window_codes, length, p=p, shift=shift):
            hashes = _window_hashes(window_codes, length).copy()
            hashes[shift] = hashes[0]  # (positions from frame.lo)
            return hashes

        monkeypatch.setattr(shift_runs, "_window_hashes", colliding)
        assert shift_runs.long_runs(frame, floor) is None, seed
        monkeypatch.setattr(shift_runs, "_window_hashes", _window_hashes)
        tried += 1
    assert tried >= 20
