"""What the benchmark scripts share: where things are, section rewriting, CSV, best-of timing.

The scripts measure the *installed* packages (``pip install -e '.[bench]'``
from the repository root, or ``PYTHONPATH=$PWD``); none of them edits
``sys.path``. Python puts this directory first on the path when a script of
it runs, which is how ``from _common import ...`` is found. This module
imports neither psgs nor kinetology: :func:`require` does, with a clear
message when they are missing, and says which copy is being measured.
"""

from __future__ import annotations

import csv
import importlib
import importlib.util
import math
import sys
import time
import tracemalloc
from collections.abc import Callable, Iterable, Sequence
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
DOCS = REPO / "docs"
DATA = DOCS / "data"
IMG = DOCS / "img"
BENCHMARKS_PAGE = DOCS / "benchmarks.md"
MOCAP = REPO.parent / "shared" / "data" / "mocap"


def require(name: str):
    """Import the installed package ``name``; exit with one line saying how when it is missing.

    Prints where the package was imported from, so a figure always says which
    copy of the code it measured.
    """
    try:
        module = importlib.import_module(name)
    except ImportError as exc:
        raise SystemExit(f"{name} is not importable ({exc}): install it with "
                         f"pip install -e '.[bench]' from {REPO}") from None
    where = Path(getattr(module, "__file__", "?")).resolve().parent
    print(f"[measuring {name} from {where}]", flush=True)
    return module


def load_file(path: Path, name: str):
    """Import the Python file ``path`` as module ``name`` (a helper outside any package).

    For the few helpers the benchmarks share with the tests (``tests/fuzz_support.py``): the
    file is loaded by its path, so nothing is added to ``sys.path`` and no other module of
    its directory can shadow an installed one.
    """
    spec = importlib.util.spec_from_file_location(name, path)
    if spec is None or spec.loader is None:
        raise SystemExit(f"{path}: not a Python file")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module  # dataclasses and pickling look the module up by name
    spec.loader.exec_module(module)
    return module


def replace_section(path: Path, name: str, text: str) -> None:
    """Rewrite the text between ``<!-- name:start -->`` and ``<!-- name:end -->`` in ``path``.

    Everything outside the markers is kept byte for byte; a page without the
    markers is an error naming them (nothing is written).
    """
    start, end = f"<!-- {name}:start -->", f"<!-- {name}:end -->"
    page = path.read_text(encoding="utf-8")
    if start not in page or end not in page.split(start, 1)[1]:
        raise SystemExit(f"{path} has no {start} ... {end} markers")
    head, rest = page.split(start, 1)
    _, tail = rest.split(end, 1)
    path.write_text(f"{head}{start}\n{text.strip()}\n{end}{tail}", encoding="utf-8")


def write_csv(path: Path, header: Sequence[str], rows: Iterable[Sequence[object]]) -> None:
    """Write ``header`` then ``rows`` to ``path`` (its directory is made when missing)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        writer.writerows(rows)


def best_of(repeat: int, function: Callable[[], object]) -> tuple[float, object]:
    """The least wall time of ``repeat`` calls of ``function`` (at least one), and its last result.

    The minimum, not the mean: on a shared machine other jobs only ever add time.
    """
    best, result = math.inf, None
    for _ in range(max(1, repeat)):
        began = time.perf_counter()
        result = function()
        best = min(best, time.perf_counter() - began)
    return best, result


def peak_bytes(function: Callable[[], object]) -> tuple[int, int]:
    """Peak bytes allocated while ``function`` runs (``tracemalloc``), and bytes its answer
    still holds."""
    tracemalloc.start()
    try:
        answer = function()  # noqa: F841 - held while the memory it takes is read
        held, peak = tracemalloc.get_traced_memory()
        return peak, held
    finally:
        tracemalloc.stop()


def loglog_slope(xs: Sequence[float], ys: Sequence[float]) -> float:
    """The least-squares slope of log(y) against log(x): the growth exponent of a time curve."""
    lx = [math.log(x) for x in xs]
    ly = [math.log(max(y, 1e-9)) for y in ys]
    mx, my = sum(lx) / len(lx), sum(ly) / len(ly)
    return (sum((a - mx) * (b - my) for a, b in zip(lx, ly))
            / sum((a - mx) ** 2 for a in lx))
