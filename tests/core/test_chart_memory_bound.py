"""The per-component chart counts what it keeps against ``max_symbols``.

``S → S S | a | ε`` makes the chart CYK's (every span of ``a^n`` is asked, each with about ``n``
splits), and its memo and resolution stack were not counted: ``psgs check`` on 10,000 a's grew
to 4.5 GB until ``max_seconds`` ran out with 0 states searched. Peak memory is read as the
child process's own high-water mark (``VmHWM`` of its memory map: ``ru_maxrss`` keeps the
forking process's peak across ``exec``, a test worker's hundreds of MB), so other tests'
allocations do not count.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

from psgs import Grammar, Nonterminal as N, Rule, Terminal as T
from psgs.budget import Budget
from psgs.errors import BoundReached
from psgs.membership.chart import ITEM_SYMBOLS, Chart, CompiledGrammar

REPO = Path(__file__).resolve().parents[2]
S, a = N("S"), T("a")
GROW = ("psgs grow\nmode single\n\ncomponent G start S\n"
        "  p: S -> S S\n  q: S -> \"a\"\n  r: S -> ε\n")
LONG = 10_000  # the old code passed 1 GB in 6 s on it, with 0 states searched

# runs in a child process; prints what it answered and its own peak resident memory in MB
CHILD = """
import json, sys, time
sys.path.insert(0, {repo!r})
import psgs
from psgs.cli import main
start = time.process_time()  # the child's CPU: a loaded machine does not stretch it
if {cli!r}:
    import contextlib, io
    out = io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(io.StringIO()):
        status = main(["check", {grammar!r}, "a" * {n}, "--max-seconds", "60"])
    answer = [status, out.getvalue()]
else:
    result = psgs.accepts(psgs.load({grammar!r}), "a" * {n}, max_symbols={symbols},
                          max_seconds=60)
    answer = [result.answer, result.bound, result.reason]
seconds = time.process_time() - start
peak = next(int(line.split()[1]) for line in open("/proc/self/status")
            if line.startswith("VmHWM:"))
print(json.dumps([answer, seconds, peak / 1024]))
"""


def run_child(tmp_path: Path, *, cli: bool, symbols: int = 0):
    grammar = tmp_path / "grow.psgs"
    grammar.write_text(GROW, encoding="utf-8")
    code = CHILD.format(repo=str(REPO), cli=cli, grammar=str(grammar), n=LONG, symbols=symbols)
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=120, check=True)
    return json.loads(done.stdout)


def test_a_long_word_stops_at_max_symbols_with_a_small_peak(tmp_path):
    (answer, bound, reason), seconds, peak_mb = run_child(tmp_path, cli=False,
                                                          symbols=1_000_000)
    assert answer == "unknown" and bound == "max_symbols", reason
    assert "max_symbols=1000000" in reason and "0 states" in reason
    assert seconds < 5  # CPU; measured 0.23 s; before, it ran on until the clock ran out
    assert peak_mb < 250, peak_mb  # measured 51 MB; before, 1,038 MB at the 6 s mark


def test_psgs_check_on_the_reviewed_input_stays_under_the_documented_bound(tmp_path):
    """The review's command at the default max_symbols: about 0.4 GB, named, in seconds."""
    (status, out), seconds, peak_mb = run_child(tmp_path, cli=True)
    assert status == 3 and "(budget: max_symbols)" in out, out
    assert seconds < 7  # CPU; measured 2.1 s; before, it ran on until --max-seconds
    assert peak_mb < 700, peak_mb  # docs/membership.md: about 0.7 GB; measured 382 MB


def test_the_chart_counts_its_memo_and_splits_and_gives_back_its_stack():
    grammar = Grammar("G", S, [Rule("p", S, (S, S)), Rule("q", S, (a,)), Rule("r", S, ())])
    cg = CompiledGrammar(grammar, {a: 0})
    budget = Budget(seconds=10, max_symbols=None)
    chart = Chart(cg, [0] * 40, budget)
    assert chart.derives(cg.index[S], 0, 40)
    assert chart.held == budget.held == ITEM_SYMBOLS * len(chart.memo) > 0  # no stack left
    assert len(chart.splits(0, 0, 40)) == 41  # S → S S on the whole word: 41 ways
    assert len(chart.splits(0, 1, 40)) == 40
    cached = sum(1 + 3 * len(found) for found in chart._split_cache.values())
    assert chart.held == budget.held == ITEM_SYMBOLS * len(chart.memo) + cached


def test_the_stack_counts_while_it_lives():
    """A budget too small for the stack of one question stops it, naming the memory bound."""
    grammar = Grammar("G", S, [Rule("p", S, (S, S)), Rule("q", S, (a,))])
    cg = CompiledGrammar(grammar, {a: 0})
    chart = Chart(cg, [0] * 2_000, Budget(seconds=10, max_symbols=30_000))
    with pytest.raises(BoundReached, match="max_symbols"):
        chart.derives(cg.index[S], 0, 2_000)
    assert len(chart.memo) < 10_000 // ITEM_SYMBOLS  # the stack, not the memo, ran it out
