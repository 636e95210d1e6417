"""What making the ``psgs`` parser imports: the subcommands' working modules load when they
run, so that ``--help`` and ``--version`` start fast (every ``psgs`` process pays for the
parser).

Each check runs in a fresh interpreter: in this one, other tests have imported everything.
"""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

#: Modules the parser was made with once and no longer needs: the grammar reader and its
#: parser generator (read when a FILE is), the skeleton player (when ``kinetology view``
#: runs), the praxicon's store (when a praxicon folder is read); numpy and the modules whose
#: defaults the help texts print (they read them from numpy-free modules of defaults), and
#: kinetology's motion, which its package no longer imports at once.
DEFERRED = ("lark", "psgs.format", "psgs._format_reader", "kinetology.viewer",
            "kinetology._viewer_checks", "kinetology.readers", "praxicon.store", "numpy",
            "kinetology.motion", "kinetology.segmentation", "kinetology.codec",
            "praxicon.description", "praxicon.parsing", "psgs.draw")


def _fresh(code: str) -> dict:
    """What ``code`` prints as JSON on its last line, run in a new interpreter."""
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60, check=True)
    return json.loads(done.stdout.splitlines()[-1])


def test_the_parser_is_made_without_the_deferred_modules():
    found = _fresh(
        "import json, sys\n"
        "from psgs.cli import build_parser\n"
        "build_parser()\n"
        f"loaded = [m for m in {DEFERRED!r} if m in sys.modules]\n"
        "import kinetology.codec.quartic as q\n"
        "print(json.dumps({'loaded': loaded, 'tables': q._tables.cache_info().currsize}))\n")
    assert found["loaded"] == []
    # the codec's quartic tables (tens of milliseconds of exact solves) are made on first use
    assert found["tables"] == 0


@pytest.mark.parametrize("argv, reads", [(["derive", "paper_example", "--seed", "1"], True),
                                         (["show", "--help"], False)])
def test_a_subcommand_imports_its_modules_when_it_runs(argv, reads):
    # derive reads a grammar (the reader loads); a --help reads none (it does not)
    found = _fresh(
        "import contextlib, io, json, sys\n"
        "from psgs.cli import main\n"
        "with contextlib.redirect_stdout(io.StringIO()):\n"
        "    try:\n"
        f"        main({argv!r})\n"
        "    except SystemExit:\n"
        "        pass\n"
        "print(json.dumps('psgs.format' in sys.modules))\n")
    assert found is reads


def test_version_is_printed_when_asked():
    from psgs._foundation.shell import version

    for command in ("psgs", "kinetology"):
        done = subprocess.run([sys.executable, "-m", command, "--version"], capture_output=True,
                              text=True, timeout=60)
        assert (done.returncode, done.stdout, done.stderr) == (0, f"{command} {version()}\n",
                                                               "")


def test_the_quartic_tables_are_each_patterns_basis():
    from kinetology.codec.quartic import _border_flags, _tables, basis

    table_u, table_w = _tables()
    assert table_u.shape == table_w.shape == (16, 5)
    assert not table_u.flags.writeable and not table_w.flags.writeable
    for k in range(16):
        u, w = basis(*(bool(k >> b & 1) for b in (3, 2, 1, 0)))
        assert np.array_equal(table_u[k], u) and np.array_equal(table_w[k], w)
    # the index a segment's borders give picks its row: a lone B segment (first and last)
    # enters with velocity 0 (the cycle's Y -> B) and leaves with acceleration 0 (B -> G)
    assert _border_flags(np.array([0])).tolist() == [8 + 1]


@pytest.mark.parametrize("k", range(16))
def test_the_exact_quartics_agree_with_a_float_solve(k):
    """Oracle: the least-jerk quartic under the pattern's conditions, solved by LAPACK in
    floats (the codec solves it in exact rationals, so that every CPU decodes alike)."""
    from kinetology.codec.quartic import _gram, _row, _tables

    flags = [bool(k >> b & 1) for b in (3, 2, 1, 0)]  # lv, la, rv, ra
    rows = [_row(0, 0), _row(1, 0)]
    for flag, at, derivative in ((flags[0], 0, 1), (flags[2], 1, 1), (flags[1], 0, 2),
                                 (flags[3], 1, 2)):
        if flag and len(rows) < 5:
            rows.append(_row(at, derivative))
    constraints = np.array(rows)
    m = len(rows)
    kkt = np.zeros((5 + m, 5 + m))
    kkt[:5, :5] = 2 * (_gram(3) + 1e-6 * _gram(2))
    kkt[:5, 5:], kkt[5:, :5] = constraints.T, constraints
    rhs = np.zeros((5 + m, 2))
    rhs[5, 0] = rhs[6, 1] = 1.0
    expected = np.linalg.solve(kkt, rhs)[:5].T
    table_u, table_w = _tables()
    np.testing.assert_allclose(np.stack([table_u[k], table_w[k]]), expected, atol=1e-9)


def test_kinetology_loads_its_names_on_first_use_and_keeps_them():
    # the package imports neither motion nor numpy; the module performances, imported first,
    # does not take the function's name; a Motion from motion.py shows its player
    found = _fresh(
        "import json, sys, types\n"
        "import kinetology\n"
        "at_once = [m for m in ('numpy', 'kinetology.motion') if m in sys.modules]\n"
        "from kinetology.performances import cut\n"
        "from kinetology.motion import Motion\n"
        "from kinetology import performances\n"
        "import kinetology.performances as named\n"
        "print(json.dumps({'at_once': at_once, 'function': [\n"
        "    isinstance(f, types.FunctionType) and f.__name__ == 'performances'\n"
        "    for f in (kinetology.performances, performances, named)],\n"
        "    'shown': Motion._repr_html_.__name__, 'Motion': kinetology.Motion is Motion}))\n")
    assert found == {"at_once": [], "function": [True, True, True], "shown": "_motion_html",
                     "Motion": True}
