"""PAL on parallel streams that are not motion: the voices of real music, repeats as the truth.

Run from the repository root (music21, in the bench extra, brings the corpus):

    python benchmarks/streams.py [--limit N] [--no-write] [--confirm | --confirm2]

The data: the pieces of music21's corpus by the composers in ``COMPOSERS`` with
three to five voices (parts). The four-part Bach chorales are left out on
purpose (they are kept to check the result). One voice is one string, one
note a symbol (its pitch with octave, the top note of a chord; a rest is
``r``), times in beats. A piece **with repetition** has repeat barlines: its
repeats are expanded (music21's ``expandRepeats``), so each repeated section
is played twice in all voices; the truth is the score's own barlines (the
measures whose number comes twice in the expanded score, runs of two
measures or more). A piece **without repetition** has no repeat barline and
no repeat expression (da capo, segno); it is a negative, though a composer
may still write a passage out twice.

Each piece is run alone (its voices only) and with 16 spurious strings beside
its voices (voices of other pieces, their notes shuffled, cut to the piece's
time): the paper's shape of a few patterned strings among many. Methods, in
the same run on the same strings:

- PAL with its defaults, and PAL with ``min_copies=2`` (a section played twice): on the
  pitch strings, with ``section_durations="equal"`` (a section's copies must repeat each
  note's duration too), and on symbols that carry their durations (``C4_1.5``, the other
  encoding: the same pitches in another rhythm are other symbols);
- the longest exact repeat of each string (two copies apart), strings grouped
  by time span: two strings are in step when their copies pair off in time
  (each pair sharing half the time they cover together), every string of a
  group of two or more is named;
- scikit-sequitur's longest rule of each string (its two first copies apart),
  grouped the same way.

A voice counts as **found** when it is named with two reported copies whose
middles lie in the two passes of one true section.

A piece without repeat signs may still repeat a passage written out (a
recapitulation, a line sung twice). An oracle independent of PAL
(:func:`written_repeat`, brute force over the pairs of voices and time shifts)
looks for a section of ``WRITTEN_BARS`` (2) of the piece's measures or more that
two voices play twice at the same two times, note for note (pitches,
durations, rests), each sounding in half of it at least. A piece without
repeat signs where it finds none is a **verified negative**; the claims there
are counted beside the claims on every piece without repeat signs, and again
with a bound of ``WRITTEN_BARS_LONG`` (4) measures, to show how the count moves
with the bound. The oracle also runs on the pieces with repeat signs (it must
find their repeats). Printed and written to docs/data/streams.csv: per method
and shape, pieces where exactly the voices are named, the recall of the true
voices, and the pieces without repetition (by the barlines; verified) where
something is named.
"""

from __future__ import annotations

import argparse
import datetime
import time
from dataclasses import dataclass

import numpy as np

from _common import BENCHMARKS_PAGE, DATA, DOCS, replace_section, require, write_csv

require("psgs")
from psgs import Actiongram  # noqa: E402
from psgs.induce import PAL  # noqa: E402
from psgs.induce.pal.choice import coincide  # noqa: E402 (the same time-span rule for peers)

#: who is read from music21's corpus (Bach is not: its chorales are reserved)
COMPOSERS = ("haydn", "mozart", "beethoven", "corelli", "monteverdi", "handel", "schubert",
             "josquin", "verdi", "weber", "cpebach", "ciconia", "luca", "palestrina")
#: Palestrina's 1,318 pieces are read one in this many (in path order): a sample of motets
#: and masses beside the others, not a corpus of its own
PALESTRINA_STEP = 20
SPURIOUS = 16
#: the confirmation run (``--confirm``), on pieces no earlier run read: the trecento pieces
#: (a composer not in COMPOSERS) and Palestrina's one in 20 from the 11th piece on (the
#: main run reads the 1st, 21st, ...)
CONFIRM_COMPOSERS = ("trecento", "palestrina")
CONFIRM_PALESTRINA_OFFSET = 10
#: the second confirmation run (``--confirm2``), on pieces neither run above read: every
#: piece of the corpus's composers no run read (Bach and the corpus's demos and exercises
#: aside), and Palestrina's one in 20 from the 6th piece and from the 16th (the runs above
#: read the 1st, 11th, 21st, 31st, ...)
CONFIRM2_COMPOSERS = ("beach", "chopin", "johnson_j_r", "joplin", "liliuokalani", "lusitano",
                      "schoenberg", "schumann_clara", "schumann_robert", "webern", "palestrina")
CONFIRM2_PALESTRINA_OFFSETS = (5, 15)


@dataclass(frozen=True)
class Piece:
    """One piece: its voices as (onset, duration, symbol) rows, and its repeated sections."""

    name: str
    voices: tuple[tuple[tuple[float, float, str], ...], ...]
    sections: tuple[tuple[tuple[float, float], tuple[float, float]], ...]  # (pass 1, pass 2)
    bar: float = 4.0  # the length of its most common measure, in beats


def voice_rows(part) -> tuple[tuple[float, float, str], ...]:
    """A part as one monophonic line: notes (top of a chord), rests and the gaps as ``r``."""
    rows, end = [], 0.0
    for el in part.flatten().notesAndRests:
        # beats to a millionth: music21's float offsets leave crumbs of 1e-15
        onset, duration = round(float(el.offset), 6), round(float(el.quarterLength), 6)
        if duration <= 0 or onset < end:
            continue  # a grace note, or a second voice of the staff under the first
        if onset > end:
            rows.append((end, round(onset - end, 6), "r"))
        if el.isRest:
            symbol = "r"
        elif el.isChord:
            symbol = max(el.pitches, key=lambda p: p.ps).nameWithOctave
        else:
            symbol = el.pitch.nameWithOctave
        rows.append((onset, duration, symbol))
        end = round(onset + duration, 6)
    return tuple(rows)


def repeated_sections(part) -> tuple[tuple[tuple[float, float], tuple[float, float]], ...]:
    """The runs of two or more measures whose numbers come twice in an expanded part."""
    measures = list(part.getElementsByClass("Measure"))
    first: dict[int, int] = {}
    runs, current = [], None
    for j, m in enumerate(measures):
        i = first.get(m.number)
        if i is None:
            first[m.number] = j
        if i is not None and current is not None and i == current[1] + 1 and j == current[3] + 1:
            current[1], current[3] = i, j
            continue
        if current is not None:
            runs.append(current)
        current = [i, i, j, j] if i is not None else None
    if current is not None:
        runs.append(current)

    def span(a, b):
        return float(measures[a].offset), float(measures[b].offset + measures[b].quarterLength)

    return tuple((span(a, b), span(c, d)) for a, b, c, d in runs if b > a)


def bar_length(part) -> float:
    """The length in beats of a part's most common measure (4.0 when it has none)."""
    lengths = [round(float(m.quarterLength), 6) for m in part.getElementsByClass("Measure")]
    return max(set(lengths), key=lengths.count) if lengths else 4.0


def load(limit: int | None, run: str = "main") -> tuple[list[Piece], list[Piece]]:
    """The pieces with repetition and those without, from music21's corpus: the main
    run's, or the pieces of a confirmation run (``run`` "confirm" or "confirm2")."""
    from music21 import bar, corpus, repeat

    with_rep, without = [], []
    seen: set[str] = set()
    composers, offsets = {"main": (COMPOSERS, (0,)),
                          "confirm": (CONFIRM_COMPOSERS, (CONFIRM_PALESTRINA_OFFSET,)),
                          "confirm2": (CONFIRM2_COMPOSERS, CONFIRM2_PALESTRINA_OFFSETS)}[run]
    for composer in composers:
        paths = sorted(map(str, corpus.getComposer(composer)))
        if composer == "palestrina":
            paths = [p for offset in offsets for p in paths[offset::PALESTRINA_STEP]]
        for path in paths:
            stem = path.rsplit(".", 1)[0].removesuffix("_old")
            if stem in seen:
                continue  # one piece in two encodings (krn and mxl), or an older copy
            seen.add(stem)
            try:
                score = corpus.parse(path)
            except Exception:  # a file music21 cannot read is left out, as a user would
                continue
            if hasattr(score, "scores"):
                score = score.scores[0]
            if not 3 <= len(score.parts) <= 5:
                continue
            name = path.split("corpus/")[-1]
            marks = list(score.parts[0].recurse().getElementsByClass(bar.Repeat))
            expressions = list(score.recurse().getElementsByClass(repeat.RepeatExpression))
            if not marks and not expressions:
                voices = tuple(voice_rows(p) for p in score.parts)
                if all(len(v) >= 8 for v in voices):
                    without.append(Piece(name, voices, (), bar_length(score.parts[0])))
                continue
            if expressions:
                continue  # da capo and segno: the truth is not the barlines alone
            try:
                expanded = score.expandRepeats()
            except Exception:
                continue
            sections = repeated_sections(expanded.parts[0])
            voices = tuple(voice_rows(p) for p in expanded.parts)
            if sections and all(len(v) >= 8 for v in voices):
                with_rep.append(Piece(name, voices, sections, bar_length(score.parts[0])))
            if limit and len(with_rep) >= limit and len(without) >= limit:
                return with_rep, without
    return with_rep, without


#: a written-out repeat counts when it lasts this many of the piece's measures: the shortest
#: run the barline truth of the pieces with repetition counts (two measures)
WRITTEN_BARS = 2
#: a longer bound, printed beside it to show how the verdict moves with the bound
WRITTEN_BARS_LONG = 4


def shift_runs(rows, shortest: float) -> dict[float, list[tuple[float, float]]]:
    """Per time shift ``d``: the spans of ``shortest`` beats or more where the voice at
    ``t`` equals itself at ``t + d`` (the same notes, durations and rests, event by event).

    The events of a voice tile its time (its gaps are rests), so a run of equal events at a
    fixed distance in the event list has one time shift.
    """
    keys: dict[tuple[str, float], int] = {}
    codes = np.array([keys.setdefault((s, d), len(keys)) for _, d, s in rows])
    onsets = np.array([o for o, _, _ in rows])
    ends = np.array([o + d for o, d, _ in rows])
    out: dict[float, list[tuple[float, float]]] = {}
    for k in range(1, len(rows)):
        equal = np.concatenate(([False], codes[:-k] == codes[k:], [False]))
        edges = np.flatnonzero(np.diff(equal.astype(np.int8)))
        first, last = edges[::2], edges[1::2] - 1
        long = ends[last] - onsets[first] >= shortest
        first, last = first[long], last[long]
        shifts = np.round(onsets[first + k] - onsets[first], 6)
        for a, b, d in zip(onsets[first].tolist(), ends[last].tolist(), shifts.tolist()):
            out.setdefault(d, []).append((a, b))
    return {d: sorted(v) for d, v in out.items()}


class Sounding:
    """How many beats a voice sounds notes (not rests) up to any time: prefix sums."""

    def __init__(self, rows):
        self.bounds = np.array([o for o, _, _ in rows] + [rows[-1][0] + rows[-1][1]])
        self.notes = np.array([s != "r" for _, _, s in rows] + [False])
        self.before = np.concatenate(([0.0], np.cumsum(np.diff(self.bounds) * self.notes[:-1])))

    def until(self, t: float) -> float:
        """Beats sounded from the voice's start to ``t``."""
        i = int(np.clip(np.searchsorted(self.bounds, t, side="right") - 1, 0,
                        len(self.bounds) - 1))
        return float(self.before[i] + max(0.0, t - self.bounds[i]) * self.notes[i])

    def between(self, a: float, b: float) -> float:
        """Beats sounded in ``[a, b)``.

        >>> Sounding([(0.0, 2.0, "C4"), (2.0, 2.0, "r"), (4.0, 1.0, "D4")]).between(1.0, 5.0)
        2.0
        """
        return self.until(b) - self.until(a)


def _windows(lo: float, hi: float, d: float, shortest: float, times):
    """The windows tried inside a span ``[lo, hi)`` the two voices share at shift ``d``:
    the whole span (cut to ``d``), and from every note's onset or to every note's end in it
    the longest window and the window of ``shortest`` beats (copies apart: at most ``d``)."""
    yield lo, min(hi, lo + d)
    inside = times[(times > lo) & (times < hi)].tolist()
    for t in inside:
        if t + shortest <= hi:
            yield t, min(hi, t + d)
            yield t, t + shortest
        if t - shortest >= lo:
            yield max(lo, t - d), t
            yield t - shortest, t


def written_repeat(voices, shortest: float):
    """The oracle of repetition, independent of PAL: the longest section of ``shortest``
    beats or more that two voices play twice at the same two times, or None.

    Brute force over the pairs of voices and the time shifts ``d``: a section from ``t``
    to ``t + L`` counts when both voices, from ``t`` on for ``L`` beats, equal themselves
    ``d`` beats later (notes, durations and rests), the copies do not overlap (``L <= d``)
    and each voice sounds notes in half of the section at least (two voices resting at
    two times are no repetition). Inside each span the two voices share at one shift, the
    windows tried start or end at the span's edges and at every note's onset and end.
    Returns ``(L, d, t, (voice, voice))``.
    """
    runs = [shift_runs(v, shortest) for v in voices]
    sounding = [Sounding(v) for v in voices]
    best = None
    for x in range(len(voices)):
        for y in range(x + 1, len(voices)):
            times = np.unique(np.concatenate([sounding[x].bounds, sounding[y].bounds]))
            for d in sorted(set(runs[x]) & set(runs[y])):
                if d < shortest:
                    continue
                ra, rb = runs[x][d], runs[y][d]
                i = j = 0
                while i < len(ra) and j < len(rb):  # the two voices' spans intersected
                    lo, hi = max(ra[i][0], rb[j][0]), min(ra[i][1], rb[j][1])
                    if min(hi - lo, d) >= shortest and (best is None
                                                        or min(hi - lo, d) > best[0]):
                        for a, b in _windows(lo, hi, d, shortest, times):
                            if b - a >= shortest and (best is None or b - a > best[0]) and all(
                                    2 * sounding[v].between(a, b) >= b - a for v in (x, y)):
                                best = (b - a, d, a, (x, y))
                    if ra[i][1] < rb[j][1]:
                        i += 1
                    else:
                        j += 1
    return best

def lies_on_repeat(rows, copies) -> bool:
    """Whether a voice's two reported copies lie on a written-out repeat of the voice: half
    of the first copy's time at least is covered by runs of events (notes, durations, rests)
    that the voice plays again as many beats later as the second copy starts after it."""
    if len(copies) < 2:
        return False
    (a1, b1), (a2, _) = copies[0], copies[1]
    shift = round(a2 - a1, 6)
    covered = 0.0
    for lo, hi in shift_runs(rows, 0.0).get(shift, []):
        covered += max(0.0, min(hi, b1) - max(lo, a1))
    return 2 * covered >= b1 - a1


def false_claim(named: dict, piece: Piece) -> bool:
    """A claim on a piece without repeat signs that is not a written-out repeat: some named
    string is a spurious one, or some named voice's copies do not lie on a repeat of it."""
    if not named:
        return False
    for name, copies in named.items():
        if not name.startswith("v") or not lies_on_repeat(piece.voices[int(name[1:])],
                                                            copies):
            return True
    return False


def actiongram(piece: Piece, pool: list[tuple[tuple[float, float, str], ...]],
               spurious: int, rng: np.random.Generator) -> tuple[Actiongram, list[str]]:
    """The piece's voices (``v0``...) and ``spurious`` shuffled voices of other pieces."""
    strings, durations, starts = {}, {}, {}
    for k, rows in enumerate(piece.voices):
        strings[f"v{k}"] = [s for _, _, s in rows]
        durations[f"v{k}"] = [d for _, d, _ in rows]
        starts[f"v{k}"] = rows[0][0]
    end = max(o + d for rows in piece.voices for o, d, _ in rows[-1:])
    for k in range(spurious):
        rows = pool[int(rng.integers(len(pool)))]
        order = rng.permutation(len(rows))
        syms, durs, t = [], [], 0.0
        for i in order.tolist():
            if t >= end:
                break
            syms.append(rows[i][2])
            durs.append(rows[i][1])
            t += rows[i][1]
        strings[f"x{k}"], durations[f"x{k}"] = syms, durs
    return Actiongram.from_strings(strings, durations, starts), list(strings)[:len(piece.voices)]


def longest_repeat(symbols: tuple[str, ...]) -> tuple[int, list[int]] | None:
    """Peer (a): the longest window found twice without overlap, its length and two starts."""
    def twice(length):
        seen: dict[tuple[str, ...], int] = {}
        for p in range(len(symbols) - length + 1):
            key = symbols[p:p + length]
            q = seen.setdefault(key, p)
            if p - q >= length:
                return [q, p]
        return None

    low, high, best = 1, len(symbols) // 2, None
    while low <= high:
        middle = (low + high) // 2
        hit = twice(middle)
        if hit:
            low, best = middle + 1, (middle, hit)
        else:
            high = middle - 1
    return best if best and best[0] >= 2 else None


def longest_rule(symbols: tuple[str, ...]) -> tuple[int, list[int]] | None:
    """Peer (b): scikit-sequitur's longest rule, its length and its two first starts apart."""
    from sksequitur import parse

    expansions = parse(list(symbols)).expansions()
    best: tuple[str, ...] = ()
    for rule, expansion in expansions.items():
        if int(rule) != 0 and len(expansion) > len(best):  # rule 0 is the whole string
            best = tuple(expansion)
    if len(best) < 2:
        return None
    starts = []
    for p in range(len(symbols) - len(best) + 1):
        if symbols[p:p + len(best)] == best and (not starts or p - starts[-1] >= len(best)):
            starts.append(p)
            if len(starts) == 2:
                return len(best), starts
    return None


def peer(ag: Actiongram, repeat_of) -> dict[str, tuple[tuple[float, float], ...]]:
    """A peer's repeats per string, grouped by time span: named string -> its copies."""
    found = {}
    for name in ag.names:
        symbols = ag.string(name)
        hit = repeat_of(symbols)
        if hit is None:
            continue
        length, where = hit
        starts = ag.starts[name]
        durs = ag.durations[name]
        found[name] = np.array([(starts[a], starts[a + length - 1] + durs[a + length - 1])
                                for a in where])
    names = list(found)
    named = set()
    for k, a in enumerate(names):
        for b in names[k + 1:]:
            if coincide(found[a], found[b], 2):
                named |= {a, b}
    return {n: tuple(map(tuple, found[n].tolist())) for n in names if n in named}


def score(named: dict, voices: list[str], piece: Piece) -> tuple[bool, int]:
    """Whether exactly the voices are named, and how many voices are found (both passes)."""
    hits = 0
    for v in voices:
        middles = [(a + b) / 2 for a, b in named.get(v, ())]
        if any(any(p1[0] <= m < p1[1] for m in middles) and any(p2[0] <= m < p2[1]
                                                                 for m in middles)
               for p1, p2 in piece.sections):
            hits += 1
    return set(named) == set(voices), hits


def with_durations(ag: Actiongram) -> Actiongram:
    """The other encoding: each symbol carries its duration (``C4_1.5``), so that the same
    pitches in another rhythm are other symbols."""
    return Actiongram.from_strings(
        {n: [f"{s}_{d:g}" for s, d in zip(ag.string(n), ag.durations[n])] for n in ag.names},
        ag.durations, dict(zip(ag.names, ag.origins)))


METHODS = {
    "PAL defaults": lambda ag: dict(PAL().induce(ag).occurrences),
    "PAL min_copies=2": lambda ag: dict(PAL(min_copies=2).induce(ag).occurrences),
    "PAL min_copies=2, equal durations": lambda ag: dict(
        PAL(min_copies=2, section_durations="equal").induce(ag).occurrences),
    "PAL min_copies=2, pairs": lambda ag: dict(
        PAL(min_copies=2, section_search="pairs").induce(ag).occurrences),
    "PAL min_copies=2, equal durations, pairs": lambda ag: dict(
        PAL(min_copies=2, section_durations="equal", section_search="pairs").induce(ag)
        .occurrences),
    "PAL min_copies=2 on pitch_duration symbols": lambda ag: dict(
        PAL(min_copies=2).induce(with_durations(ag)).occurrences),
    "longest exact repeat": lambda ag: peer(ag, longest_repeat),
    "scikit-sequitur longest rule": lambda ag: peer(ag, longest_rule),
}


def table(rows: list[dict]) -> str:
    """The results as a markdown table, one line per method and shape."""
    lines = ["| strings | method | exactly the voices named | recall of the true voices | "
             "claims on pieces without repeat signs | claims on verified negatives "
             f"(no written-out repeat of {WRITTEN_BARS} bars) | the same, bound "
             f"{WRITTEN_BARS_LONG} bars | false claims (verified negatives, or off a "
             "written-out repeat) | seconds |", "|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        shape = "the voices alone" if r["spurious"] == 0 else f"+ {r['spurious']} spurious"
        lines.append(f"| {shape} | {r['method']} | {r['exactly_the_voices']} / "
                     f"{r['pieces_with_repeats']} | {r['recall']:.3f} | {r['claims_without']} / "
                     f"{r['pieces_without']} | {r['claims_verified']} / {r['verified']} "
                     f"({100 * r['claims_verified'] / max(r['verified'], 1):.1f} %) | "
                     f"{r['claims_verified_long']} / {r['verified_long']} "
                     f"({100 * r['claims_verified_long'] / max(r['verified_long'], 1):.1f} %) | "
                     f"{r['false_claims']} / {r['pieces_without']} "
                     f"({100 * r['false_claims'] / max(r['pieces_without'], 1):.1f} %) | "
                     f"{r['seconds']} |")
    return "\n".join(lines)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limit", type=int, default=None,
                        help="stop reading the corpus once this many of each kind are in")
    parser.add_argument("--no-write", action="store_true")
    parser.add_argument("--confirm", action="store_true",
                        help="the confirmation run: pieces no earlier run read (printed only)")
    parser.add_argument("--confirm2", action="store_true",
                        help="the second confirmation run: pieces neither run read (printed "
                             "only)")
    args = parser.parse_args(argv)
    if args.confirm or args.confirm2:
        args.no_write = True
    began = time.time()
    with_rep, without = load(args.limit, "confirm2" if args.confirm2 else
                             "confirm" if args.confirm else "main")
    print("pieces:", ", ".join(p.name for p in with_rep + without), flush=True)
    print(f"{len(with_rep)} pieces with repeats, {len(without)} without "
          f"(read in {time.time() - began:.0f} s)", flush=True)
    pool_of = {p.name: p.voices for p in with_rep + without}
    t = time.time()
    written = {p.name: written_repeat(p.voices, WRITTEN_BARS * p.bar) for p in with_rep + without}
    verified = {p.name for p in without if written[p.name] is None}
    verified_long = {p.name for p in without
                     if written_repeat(p.voices, WRITTEN_BARS_LONG * p.bar) is None}
    print(f"written-out repeats (two voices, the same two times, {WRITTEN_BARS} bars or more): "
          f"in {sum(written[p.name] is not None for p in with_rep)} of {len(with_rep)} pieces "
          f"with repeat signs, {len(without) - len(verified)} of {len(without)} without; "
          f"verified negatives {len(verified)} ({len(verified_long)} with a bound of "
          f"{WRITTEN_BARS_LONG} bars; {time.time() - t:.0f} s)", flush=True)
    rows = []
    for spurious in (0, SPURIOUS):
        # exact, found, voices, claims, seconds, claims on verified (2 bars, 4 bars),
        # false claims (on verified negatives, or off a written-out repeat)
        tally = {m: [0, 0, 0, 0, 0.0, 0, 0, 0] for m in METHODS}
        for k, piece in enumerate(with_rep + without):
            pool = [v for name, vs in pool_of.items() if name != piece.name for v in vs]
            rng = np.random.default_rng(k)
            ag, voices = actiongram(piece, pool, spurious, rng)
            for method, run in METHODS.items():
                t = time.perf_counter()
                named = run(ag)
                tally[method][4] += time.perf_counter() - t
                if piece.sections:
                    exact, hits = score(named, voices, piece)
                    tally[method][0] += exact
                    tally[method][1] += hits
                    tally[method][2] += len(voices)
                else:
                    tally[method][3] += bool(named)
                    tally[method][5] += bool(named) and piece.name in verified
                    tally[method][6] += bool(named) and piece.name in verified_long
                    wrong = bool(named) and (piece.name in verified or false_claim(named, piece))
                    tally[method][7] += wrong
                    if wrong and piece.name not in verified and method.startswith("PAL"):
                        print(f"   {method} claims off a written-out repeat in {piece.name}: "
                              + ", ".join(f"{v} {[(round(a, 1), round(b, 1)) for a, b in c]}"
                                          for v, c in named.items()), flush=True)
                    if named and piece.name in verified and method.startswith("PAL"):
                        print(f"   {method} claims verified negative {piece.name}: "
                              + ", ".join(f"{v} {[(round(a, 1), round(b, 1)) for a, b in c]}"
                                          for v, c in named.items()), flush=True)
        for method, (exact, hits, total, claims, seconds, sure, sure_long,
                     wrong) in tally.items():
            rows.append({"spurious": spurious, "method": method,
                         "pieces_with_repeats": len(with_rep),
                         "exactly_the_voices": exact,
                         "recall": round(hits / max(total, 1), 3),
                         "pieces_without": len(without), "claims_without": claims,
                         "verified": len(verified), "claims_verified": sure,
                         "verified_long": len(verified_long), "claims_verified_long": sure_long,
                         "false_claims": wrong, "seconds": round(seconds, 1)})
            print(f"{spurious:2d} spurious  {method:30s} exactly the voices {exact:3d}/"
                  f"{len(with_rep)}  recall {hits / max(total, 1):.3f}  claims on pieces "
                  f"without {claims:2d}/{len(without)}, verified {sure:2d}/{len(verified)} "
                  f"({sure_long}/{len(verified_long)} at {WRITTEN_BARS_LONG} bars), false "
                  f"claims {wrong}/{len(without)}  "
                  f"({seconds:.1f} s)", flush=True)
    if not args.no_write:
        header = list(rows[0])
        write_csv(DATA / "streams.csv", header, [[r[h] for h in header] for r in rows])
        text = table(rows)
        replace_section(BENCHMARKS_PAGE, "streams", "## PAL on parallel streams of music\n\n"
                        f"Measured with `python benchmarks/streams.py` ({datetime.date.today()}); "
                        "data in `docs/data/streams.csv`, what it means in "
                        "[Any parallel streams](streams.md#benchmark-on-real-music).\n\n" + text)
        for page in (DOCS / "pal.md", DOCS / "streams.md"):
            if page.exists() and "<!-- streams:start -->" in page.read_text(encoding="utf-8"):
                replace_section(page, "streams", text)
    print(f"total {time.time() - began:.0f} s")


if __name__ == "__main__":
    main()
