"""Benchmark: psgs.accepts against Lark (Earley and LALR) on the same component words; psgs.nearest.

    python benchmarks/membership.py            # full run; rewrites the membership sections
    python benchmarks/membership.py --quick    # small sizes, prints only
    python benchmarks/membership.py --forms    # only the multiplying grammars (about 5 min)

For each system of ``grammars/`` and each size, the words are a member tuple
of the language. ``accepts`` is timed end to end (parse every component and
find a synchronised schedule; building the schedule found and replaying the
witness are left to first access and not timed). Lark is timed parsing each
component's word with the exported grammar (``psgs.to_lark``,
``lark.Lark(..., parser="earley", lexer="basic")``,
symbols joined by spaces), parser construction excluded; Lark's time is the
same for both modes (it knows nothing of them) and is measured once per word
tuple; Lark's LALR parser is timed the same way where the exported grammar
has no LALR conflict ("n/a" otherwise). The growth exponent is the
least-squares slope of log(time) against log(size) over the sizes of one row
group.

``nearest``: member tuples of the shipped grammars with random edits (a
seeded generator inserts, deletes or substitutes a symbol at a random place
of a random component) at 0.1%, 1% and 5% of the symbols (at least one),
timed end to end (best of 2), once exact (no ``max_errors``) and once with
``max_errors`` set to the number of edits made (the distance is at most
that: undoing each edit costs 1).

``--forms`` (also part of the full run): the distance in parallel mode on
systems with a rule that multiplies its nonterminal (``S → S S``), where
:func:`psgs.nearest` takes the form search
(``psgs.membership.parallel_distance``). A seeded generator
(:func:`multiplying_system`) draws systems of one or two components, each
with ``S → S S``, a terminal rule and up to three more rules over
``S, A, a, b`` (bodies of 0-3 symbols), two components with up to three
tuples (a system whose language is empty is drawn again); the input is a
word tuple of 20-50 symbols in all, over ``a, b``, each word with its own
share of ``a``. The form search has 3 s per input on 300 inputs; the span
search (``psgs.membership.nearest_search``, which ``nearest`` takes when it
is told that no rule multiplies) 3 s per input on the first 60. Counted are
the answers each gives exactly and the budgets that ran out, timed the
exact answers (median, mean, slowest) and the whole run, and compared the
distances where both answered. ``--forms --quick``: 30 inputs, the span
search on 12, docs untouched; ``--seed``, ``--symbols LEAST MOST`` and
``--inputs FORM SPAN`` draw other inputs (``--inputs 300 0``: the form search
alone) and print only.
"""

from __future__ import annotations

import argparse
import dataclasses
import importlib
import math
import os
import platform
import random
import statistics
import time

import lark
from _common import BENCHMARKS_PAGE, REPO, loglog_slope, replace_section, require

require("psgs")
from psgs import to_lark  # noqa: E402
from psgs.format import load  # noqa: E402
from psgs import PSGS, Grammar, Nonterminal, Rule, Terminal  # noqa: E402
from psgs.membership import accepts, nearest  # noqa: E402

# the module, not the function psgs.membership re-exports under its name
NEAREST_MODULE = importlib.import_module("psgs.membership.nearest")

GAMMA_BLOCKS = ("abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad")


def cases(quick: bool):
    """(label, file, size, words) for every benchmarked word tuple."""
    sizes = (10, 30, 100) if quick else (10, 100, 1000)
    for k in sizes:
        yield "Γ (paper_example)", "paper_example.psgs", k, [b * k for b in GAMMA_BLOCKS]
    for n in sizes:
        yield "counting (aⁿ, bⁿ)", "counting.psgs", n, ["a" * n, "b" * n]
    for n in sizes:
        yield "idling (aⁿcⁿ, bⁿ)", "idling.psgs", n, ["a" * n + "c" * n, "b" * n]
    for n in sizes:
        yield "modes (aⁿb aⁿb)", "modes.psgs", n, ["a" * n + "b" + "a" * n + "b"]


def time_accepts(system, words, repeats: int) -> tuple[float, str]:
    best = math.inf
    answer = ""
    for _ in range(repeats):
        start = time.perf_counter()
        result = accepts(system, words, check_witness=False, max_seconds=600.0,
                         max_states=5_000_000)
        best = min(best, time.perf_counter() - start)
        answer = result.answer
    return best, answer


def time_lark(system, words, algorithm: str = "earley") -> float | None:
    texts = to_lark(system)
    total = 0.0
    for g, w in zip(system.components, words):
        try:
            parser = lark.Lark(texts[g.name], start="start", parser=algorithm, lexer="basic")
        except lark.exceptions.GrammarError:
            return None  # an LALR conflict: Lark cannot build this parser
        sentence = " ".join(w)
        start = time.perf_counter()
        parser.parse(sentence)
        total += time.perf_counter() - start
    return total


def run(quick: bool) -> str:
    rows = []
    groups: dict[tuple[str, str], list[tuple[int, float, float]]] = {}
    lark_cache: dict[tuple[str, int], float] = {}
    lalr_cache: dict[tuple[str, int], float | None] = {}
    for label, file, size, words in cases(quick):
        base = load(REPO / "grammars" / file)
        key = (file, size)
        if key not in lark_cache:
            lark_cache[key] = time_lark(base, words)
            lalr_cache[key] = time_lark(base, words, "lalr")
        for mode in ("parallel", "single"):
            system = dataclasses.replace(base, mode=mode)
            repeats = 3
            ours, answer = time_accepts(system, words, repeats)
            theirs = lark_cache[key]
            lalr = lalr_cache[key]
            symbols = sum(len(w) for w in words)
            rows.append((label, mode, size, symbols, answer, ours, theirs, lalr))
            groups.setdefault((label, mode), []).append((size, ours, theirs))
            print(f"{label:22} {mode:8} n={size:5} symbols={symbols:6} {answer:7} "
                  f"ours={ours:8.3f}s lark={theirs:8.3f}s lalr={_s(lalr)} "
                  f"ratio={ours / theirs:6.3f}", flush=True)
    lines = ["| system | mode | size n (k) | symbols | answer | accepts (s) | Lark Earley (s) "
             "| ours / Earley | Lark LALR (s) | ours / LALR |",
             "|---|---|---:|---:|---|---:|---:|---:|---:|---:|"]
    for label, mode, size, symbols, answer, ours, theirs, lalr in rows:
        ratio = "n/a" if lalr is None else f"{ours / lalr:.2f}"
        lines.append(f"| {label} | {mode} | {size} | {symbols} | {answer} | {ours:.3f} | "
                     f"{theirs:.3f} | {ours / theirs:.3f} | {_s(lalr)} | {ratio} |")
    lines += ["", "Growth exponent (log-log slope of time against n):", "",
              "| system | mode | accepts | Lark Earley |", "|---|---|---:|---:|"]
    for (label, mode), points in groups.items():
        sizes = [n for n, _, _ in points]
        ours_slope = loglog_slope(sizes, [t for _, t, _ in points])
        lark_slope = loglog_slope(sizes, [t for _, _, t in points])
        lines.append(f"| {label} | {mode} | {ours_slope:.2f} | {lark_slope:.2f} |")
    return "\n".join(lines)


def _s(value: float | None) -> str:
    return "n/a" if value is None else f"{value:.3f}"


RATES = (0.001, 0.01, 0.05)


def edited(words: list[str], alphabet: str, rate: float, seed: int) -> tuple[list[str], int]:
    """The words with ``rate`` of their symbols edited at random (at least one edit)."""
    rng = random.Random(seed)
    out = [list(w) for w in words]
    count = max(1, round(rate * sum(map(len, out))))
    for _ in range(count):
        w = out[rng.randrange(len(out))]
        p = rng.randrange(len(w) + 1)
        op = rng.choice(("insert", "delete", "substitute")) if p < len(w) else "insert"
        if op == "insert":
            w.insert(p, rng.choice(alphabet))
        elif op == "delete":
            del w[p]
        else:
            w[p] = rng.choice([x for x in alphabet if x != w[p]])
    return ["".join(w) for w in out], count


def nearest_cases(quick: bool):
    """(label, file, size, member words, alphabet) for the nearest benchmark."""
    sizes = (10, 30) if quick else (10, 30, 100)
    for k in sizes:
        yield "Γ (paper_example)", "paper_example.psgs", k, [b * k for b in GAMMA_BLOCKS], "abcd"
    for n in ((30, 100) if quick else (30, 100, 300, 1000)):
        yield "counting (aⁿ, bⁿ)", "counting.psgs", n, ["a" * n, "b" * n], "ab"


def run_nearest(quick: bool) -> str:
    rows = []
    groups: dict[tuple[str, float, str], list[tuple[int, float]]] = {}
    for label, file, size, words, alphabet in nearest_cases(quick):
        system = load(REPO / "grammars" / file)
        for rate in RATES:
            noisy, count = edited(words, alphabet, rate, seed=size)
            for how, limit in (("exact", None), ("max_errors", count)):
                best = math.inf
                for _ in range(2):
                    start = time.perf_counter()
                    result = nearest(system, noisy, max_errors=limit, max_seconds=300.0,
                                     max_states=5_000_000)
                    best = min(best, time.perf_counter() - start)
                symbols = sum(map(len, noisy))
                shown = "none" if result.distance is None else str(result.distance)
                if not result.exact:
                    shown += f" (not exact: {result.bound})"
                rows.append((label, size, symbols, rate, count, how, shown, best))
                groups.setdefault((label, rate, how), []).append((symbols, best))
                print(f"{label:22} k={size:5} symbols={symbols:6} rate={rate:5} edits={count:4} "
                      f"{how:10} distance={shown:8} {best:8.3f}s", flush=True)
    lines = ["| system | size n (k) | symbols | edit rate | edits made | search | distance "
             "| nearest (s) |", "|---|---:|---:|---:|---:|---|---|---:|"]
    for label, size, symbols, rate, count, how, shown, best in rows:
        lines.append(f"| {label} | {size} | {symbols} | {rate:.1%} | {count} | {how} | {shown} "
                     f"| {best:.3f} |")
    lines += ["", "Growth exponent of `nearest` (log-log slope of time against symbols):", "",
              "| system | edit rate | search | exponent |", "|---|---:|---|---:|"]
    for (label, rate, how), points in groups.items():
        slope = loglog_slope([n for n, _ in points], [t for _, t in points])
        lines.append(f"| {label} | {rate:.1%} | {how} | {slope:.2f} |")
    return "\n".join(lines)


def _measured(command: str, versions: str = "") -> str:
    """How a section's figures were measured: the command, the machine, Python (and
    ``versions``), the date and the load at the end, without the closing punctuation."""
    cpu = platform.processor() or platform.machine()
    return (f"Measured with `{command}` on {cpu}, Python {platform.python_version()}{versions}, "
            f"{time.strftime('%Y-%m-%d', time.gmtime())}, on a machine shared with other jobs "
            f"(load average {os.getloadavg()[0]:.1f} at the end)")


def write_section(table: str, nearest_table: str, command: str) -> None:
    body = (f"## Membership (`psgs.accepts`)\n\n"
            f"{_measured(command, f', lark {lark.__version__}')}. `accepts`: best of 3 runs; "
            f"Lark: one run. `accepts` includes parsing every component and the schedule search "
            f"(not building the schedule found and replaying the witness, both done on first "
            f"access); Lark is the parse of the same "
            f"component words alone, with the exported grammars, parser construction excluded, "
            f"measured once per word tuple (it has no modes).\n\n{table}\n")
    body += ("\n### Distance to the language (`psgs.nearest`)\n\nThe same run: member tuples "
             "with random edits at 0.1%, 1% and 5% of the symbols (seeded), best of 2; "
             "`exact` without a bound, `max_errors` bounded by the number of edits made.\n\n"
             f"{nearest_table}\n")
    replace_section(BENCHMARKS_PAGE, "membership", body)


FORMS_SEED = 2026
FORMS_SYSTEMS = 300  # the form search's inputs
FORMS_BOTH = 60  # the first inputs, on which the span search is timed too
FORMS_SECONDS = 3.0
FORMS_SYMBOLS = (20, 50)  # the least and most symbols of an input


def multiplying_system(rng: random.Random) -> PSGS:
    """A parallel-mode system whose components each hold ``S → S S`` (drawn from ``rng``)."""
    a, b = Terminal("a"), Terminal("b")
    grammars = []
    for i in range(rng.choice((1, 2))):
        s, x = Nonterminal(f"S{i}"), Nonterminal(f"A{i}")
        rules = {(s, (s, s)), (s, (rng.choice((a, b)),))}
        for _ in range(rng.randint(0, 3)):
            lhs = rng.choice((s, x))
            rules.add((lhs, tuple(rng.choice((s, x, a, b)) for _ in range(rng.randint(0, 3)))))
        grammars.append(Grammar(f"G{i}", s, [Rule(f"r{i}_{k}", lhs, body)
                                             for k, (lhs, body) in enumerate(sorted(
                                                 rules, key=str))]))
    sync = []
    if len(grammars) == 2:
        labels = [[r.label for r in g.rules] for g in grammars]
        for _ in range(rng.randint(0, 3)):
            pair = (rng.choice([*labels[0], None]), rng.choice([*labels[1], None]))
            if pair != (None, None) and pair not in sync:
                sync.append(pair)
    policy = rng.choice(("free", "strict")) if sync else "free"
    return PSGS(tuple(grammars), tuple(sync), mode="parallel", unsynchronised=policy)


def multiplying_input(rng: random.Random, components: int,
                      symbols: tuple[int, int] = FORMS_SYMBOLS) -> list[str]:
    """A word tuple of 20-50 (``symbols``) symbols in all over ``a, b``; each word its own
    share of ``a``."""
    total = rng.randint(*symbols)
    cuts = sorted(rng.randint(0, total) for _ in range(components - 1))
    lengths = [q - p for p, q in zip([0, *cuts], [*cuts, total])]
    words = []
    for n in lengths:
        share = rng.random()
        words.append("".join("a" if rng.random() < share else "b" for _ in range(n)))
    return words


def forms_cases(count: int, seed: int = FORMS_SEED, symbols: tuple[int, int] = FORMS_SYMBOLS):
    """``count`` (system, words) pairs, the same for the same seed and ``symbols``.

    A system whose language is empty (tuples that never let a strict system finish) is
    drawn again: both searches answer it at once, and it would measure nothing.
    """
    rng = random.Random(seed)
    made = 0
    while made < count:
        system = multiplying_system(rng)
        empty = nearest(system, [""] * len(system.components), max_states=100_000,
                        max_seconds=60.0)
        if empty.exact and empty.distance is None:
            continue
        made += 1
        yield system, multiplying_input(rng, len(system.components), symbols)


def distance_by(search: str, system, words, seconds: float):
    """``nearest`` by the form search, or by the span search; (result, seconds)."""
    kept = NEAREST_MODULE.multiplies
    if search == "span":  # nearest takes the span search when no rule multiplies
        NEAREST_MODULE.multiplies = lambda compiled: False
    try:
        start = time.perf_counter()
        result = nearest(system, words, max_seconds=seconds, max_states=10_000_000)
        return result, time.perf_counter() - start
    finally:
        NEAREST_MODULE.multiplies = kept


def run_forms(count: int, both_count: int, seed: int = FORMS_SEED,
              symbols: tuple[int, int] = FORMS_SYMBOLS, seconds: float = FORMS_SECONDS) -> str:
    """The form search on ``count`` drawn inputs, the span search on the first ``both_count``.

    Returns the table: per search and set of inputs, how many it answered exactly within
    ``seconds``, which budgets ran out, the median and mean time per exact answer and the
    slowest; and on how many of the shared inputs both answered, and whether they agree.
    """
    times = {"form": [], "form_first": [], "span": []}
    bounds: dict[str, dict[str, int]] = {key: {} for key in times}
    totals = dict.fromkeys(times, 0.0)
    differ = both = 0
    for k, (system, words) in enumerate(forms_cases(count, seed, symbols)):
        searches = ("form", "span") if k < both_count else ("form",)
        got = {}
        for search in searches:
            result, took = distance_by(search, system, words, seconds)
            got[search] = result
            for key in (search, "form_first") if search == "form" and k < both_count else \
                    (search,):
                totals[key] += took
                if result.exact:
                    times[key].append(took)
                else:
                    bounds[key][result.bound] = bounds[key].get(result.bound, 0) + 1
        form, span = got["form"], got.get("span")
        if span is not None and form.exact and span.exact:
            both += 1
            differ += form.distance != span.distance
        shown = "" if span is None else f"span: {_answer(span)}"
        print(f"{k:3} {sum(map(len, words)):3} symbols  form: {_answer(form):26} {shown}",
              flush=True)
    lines = [f"| search | inputs | exact within {seconds:g} s | ran out (budget: count) "
             "| median s per exact answer | mean s per exact answer | slowest exact (s) "
             "| whole run (s) |", "|---|---:|---:|---|---:|---:|---:|---:|"]
    rows = (("form", f"form search (what `nearest` takes), all {count}", count),
            ("form_first", f"form search, the first {both_count}", both_count),
            ("span", f"span search, the first {both_count}", both_count))
    for key, label, inputs in rows:
        if not inputs:
            continue
        found = times[key]
        ran_out = ", ".join(f"{b}: {n}" for b, n in sorted(bounds[key].items())) or "none"
        median = f"{statistics.median(found):.3f}" if found else "n/a"
        mean = f"{statistics.fmean(found):.3f}" if found else "n/a"
        slowest = f"{max(found):.3f}" if found else "n/a"
        lines.append(f"| {label} | {inputs} | {len(found)} | {ran_out} | {median} | {mean} | "
                     f"{slowest} | {totals[key]:.1f} |")
    if both_count:
        lines += ["", f"Of the first {both_count}, both searches answered {both} exactly; their "
                  f"distances differ on {differ}."]
    return "\n".join(lines)


def _answer(result) -> str:
    if result.exact:
        return f"{result.distance} exact ({result.states} states)"
    return f"unknown ({result.bound})"


def write_forms_section(table: str, command: str) -> None:
    body = (f"### Distance on grammars that multiply a nonterminal (parallel mode)\n\n"
            f"{_measured(command)}: {FORMS_SYSTEMS} systems "
            f"drawn by `multiplying_system` (seed {FORMS_SEED}), parallel mode, one or two "
            f"components each with `S → S S`, a terminal rule and up to three more (a system "
            f"whose language is empty is drawn again); inputs of 20-50 symbols over `a, b`; "
            f"{FORMS_SECONDS:g} s per input and search, one run each. The form search is what "
            f"`psgs.nearest` takes on such systems; the span search, what it takes otherwise, "
            f"is timed on the first {FORMS_BOTH} (it runs out of time on most).\n\n{table}\n")
    replace_section(BENCHMARKS_PAGE, "membership-forms", body)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small sizes; do not write docs")
    parser.add_argument("--forms", action="store_true",
                        help="only the distance on grammars that multiply a nonterminal")
    parser.add_argument("--seed", type=int, default=FORMS_SEED,
                        help="--forms: the generator's seed (another: prints only)")
    parser.add_argument("--symbols", type=int, nargs=2, default=FORMS_SYMBOLS,
                        metavar=("LEAST", "MOST"),
                        help="--forms: the inputs' lengths (others than 20 50: prints only)")
    parser.add_argument("--inputs", type=int, nargs=2, default=(FORMS_SYSTEMS, FORMS_BOTH),
                        metavar=("FORM", "SPAN"),
                        help="--forms: inputs for the form search, and of them for the span "
                             "search (others than 300 60: prints only)")
    args = parser.parse_args()
    default = (args.seed == FORMS_SEED and tuple(args.symbols) == FORMS_SYMBOLS
               and tuple(args.inputs) == (FORMS_SYSTEMS, FORMS_BOTH))
    if args.forms:
        inputs = (30, 12) if args.quick and default else tuple(args.inputs)
        forms_table = run_forms(*inputs, args.seed, tuple(args.symbols))
        print()
        print(forms_table)
        if not args.quick and default:
            write_forms_section(forms_table, "python benchmarks/membership.py --forms")
        return
    table = run(args.quick)
    print()
    print(table)
    nearest_table = run_nearest(args.quick)
    print()
    print(nearest_table)
    forms_table = run_forms(*((30, 12) if args.quick else (FORMS_SYSTEMS, FORMS_BOTH)))
    print()
    print(forms_table)
    if not args.quick:
        write_section(table, nearest_table, "python benchmarks/membership.py")
        write_forms_section(forms_table, "python benchmarks/membership.py")


if __name__ == "__main__":
    main()
