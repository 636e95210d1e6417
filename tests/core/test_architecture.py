"""The import graph of psgs, kinetology (and praxicon, when present) keeps its layers.

The graph is built from the source with ``ast``: every ``import`` and ``from … import``
anywhere in a module (inside functions and ``if TYPE_CHECKING:`` blocks too: an import that
only names a type still ties the modules together), relative imports resolved, ``from pkg
import sub`` counted as an import of the submodule ``pkg.sub``. Nothing is imported to build it.
docs/architecture.md draws the layers these tests keep.
"""

from __future__ import annotations

import ast
import importlib
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
PACKAGES = ("psgs", "kinetology", "praxicon")  # praxicon: a package another branch may add

# The formal core, bottom-up: a module may import its own tier and the tiers below, never above.
# At the bottom, the foundation every package of the distribution shares (errors, the
# command-line shell, lazy names, the engine selector).
FOUNDATION = ("psgs.errors", "psgs._foundation", "psgs._foundation.shell",
              "psgs._foundation.lazy", "psgs._foundation.engines", "psgs._foundation.files",
              "psgs._foundation.pictures",
              "psgs._foundation.text")
CORE_TIERS = (
    (*FOUNDATION, "psgs.budget", "psgs.names"),
    ("psgs.model",),
    ("psgs.analysis", "psgs.notation"),
    ("psgs.steps",),
    ("psgs.derivation",),
    ("psgs.membership", "psgs.membership.*"),
    ("psgs.search", "psgs.enumeration"),
)
# Beside the core: readers, writers and exporters of the model, needing nothing above it.
BESIDE = ("psgs.format", "psgs._format_reader", "psgs.writing", "psgs.lark_export",
          "psgs.graph")
# (psgs.load and psgs.dump read and write actiongrams too, so format and writing may import it)
BESIDE_MAY_IMPORT = (*FOUNDATION, "psgs.names", "psgs.model", "psgs.writing",
                     "psgs.actiongram", "psgs._format_reader")
#: What kinetology may import from psgs: the actiongram (what it makes) and the foundation
#: every package of the distribution shares (errors, command-line shell, lazy names, engines),
#: each module named.
KINETOLOGY_MAY_IMPORT = ("psgs.actiongram", "psgs.actiongram.*", *FOUNDATION)
#: No module of the three packages is longer (related code stays together in a subpackage).
MAX_LINES = 600

def module_files() -> dict[str, Path]:
    out = {}
    for package in PACKAGES:
        root = REPO / package
        if not root.is_dir():
            continue
        for path in sorted(root.rglob("*.py")):
            parts = list(path.relative_to(REPO).with_suffix("").parts)
            if parts[-1] == "__init__":
                parts.pop()
            out[".".join(parts)] = path
    return out


def _imports(name: str, path: Path, known: set[str]) -> set[tuple[str, str]]:
    """(module imported, name taken from it or '') for every import statement in the file."""
    is_package = path.name == "__init__.py"
    package = name if is_package else name.rpartition(".")[0]
    found = set()
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    for node in ast.walk(tree):  # every import: in functions and ``if TYPE_CHECKING:`` too
        if isinstance(node, ast.Import):
            found.update((alias.name, "") for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                if node.level > 1:
                    base = base[:-(node.level - 1)]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module
            for alias in node.names:
                sub = f"{target}.{alias.name}"
                found.add((sub, "") if sub in known else (target, alias.name))
    return found


def _owner(target: str, known: set[str]) -> str | None:
    """The known module ``target`` names (the longest known prefix), or None if foreign."""
    while target:
        if target in known:
            return target
        target = target.rpartition(".")[0]
    return None


def import_graph() -> tuple[dict[str, set[str]], dict[str, set[tuple[str, str]]]]:
    files = module_files()
    known = set(files)
    edges: dict[str, set[str]] = {m: set() for m in files}
    names: dict[str, set[tuple[str, str]]] = {m: set() for m in files}
    for module, path in files.items():
        for target, taken in _imports(module, path, known):
            owner = _owner(target, known)
            if owner is not None and owner != module:
                edges[module].add(owner)
                names[module].add((owner, taken))
    return edges, names


def tier_of(module: str) -> int | None:
    for k, tier in enumerate(CORE_TIERS):
        for pattern in tier:
            if module == pattern or (pattern.endswith(".*") and
                                     module.startswith(pattern[:-1])):
                return k
    return None


EDGES, NAMES = import_graph()


def _cycle(edges: dict[str, set[str]]) -> list[str] | None:
    colour: dict[str, int] = {}
    for root in sorted(edges):
        if root in colour:
            continue
        colour[root] = 1
        stack = [(root, iter(sorted(edges[root])))]
        path = [root]
        while stack:
            node, it = stack[-1]
            for nxt in it:
                if colour.get(nxt) == 1:
                    return path[path.index(nxt):] + [nxt]
                if nxt not in colour:
                    colour[nxt] = 1
                    stack.append((nxt, iter(sorted(edges.get(nxt, ())))))
                    path.append(nxt)
                    break
            else:
                colour[node] = 2
                stack.pop()
                path.pop()
    return None


def test_the_graph_is_read_from_every_module_with_function_level_imports():
    assert {"psgs.derivation", "psgs.membership", "psgs.enumeration",
            "kinetology.segmentation"} <= set(EDGES)
    # a function-level import is an edge: kinetology's one use of psgs sits inside a method
    assert "psgs.actiongram" in EDGES["kinetology.segmentation"]
    # relative imports are resolved, `from . import x` names the submodule
    assert "psgs.membership.chart" in EDGES["psgs.membership.schedule_search"]


def _cycles(edges: dict[str, set[str]]) -> list[set[str]]:
    """The strongly connected components of more than one module."""
    from psgs.analysis import strongly_connected

    found = strongly_connected(sorted(edges), {m: sorted(ts) for m, ts in edges.items()})
    return [set(component) for component in found if len(component) > 1]


def test_the_cycle_finder_finds_cycles():
    assert _cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [{"a", "b", "c"}]
    assert _cycles({"a": {"b"}, "b": set()}) == []
    assert _cycle({"a": {"b"}, "b": {"a"}}) == ["a", "b", "a"]


def test_no_import_cycle():
    # PAL's phases read the frozen parameter table they are handed, never the learner's class
    assert _cycle(EDGES) is None, " -> ".join(_cycle(EDGES))
    assert _cycles(EDGES) == []


def test_the_notebook_pictures_make_no_cycle_through_the_model():
    # model.py knows no drawing: psgs._display attaches the pictures from above
    assert not {m for m in EDGES["psgs.model"] if m.startswith(("psgs.draw", "psgs.derivation"))}


def test_the_core_layers_point_down_only():
    upward = []
    for module, targets in EDGES.items():
        mine = tier_of(module)
        if mine is None:
            continue
        for target in targets:
            theirs = tier_of(target)
            if theirs is None or theirs > mine:
                upward.append(f"{module} -> {target}")
    assert not upward, "imports pointing up (or out of the core): " + ", ".join(sorted(upward))


def test_format_lark_export_and_graph_stand_beside_the_core():
    for module in BESIDE:
        assert EDGES[module] <= set(BESIDE_MAY_IMPORT), (module, EDGES[module])
    for module, targets in EDGES.items():
        if tier_of(module) is not None:
            assert not targets & set(BESIDE), (module, targets & set(BESIDE))


def test_psgs_never_imports_kinetology_or_praxicon():
    bad = [f"{m} -> {t}" for m, ts in EDGES.items() if m.split(".")[0] == "psgs"
           for t in ts if t.split(".")[0] in ("kinetology", "praxicon")]
    assert not bad, bad


def _matches(module: str, patterns) -> bool:
    return any(module == p or (p.endswith(".*") and module.startswith(p[:-1])) for p in patterns)


def test_kinetology_imports_from_psgs_only_the_actiongram_and_the_foundation():
    uses = {(m, owner, taken) for m, pairs in NAMES.items() if m.split(".")[0] == "kinetology"
            for owner, taken in pairs if owner.split(".")[0] in ("psgs", "praxicon")}
    # ``from psgs import Actiongram`` names the actiongram through the package
    bad = [u for u in uses if not _matches(u[1], KINETOLOGY_MAY_IMPORT)
           and (u[1], u[2]) not in {("psgs", "Actiongram"), ("psgs", "actiongram")}]
    assert not bad, bad
    assert {owner for _, owner, _ in uses} & {"psgs.actiongram", "psgs"}, \
        "kinetology makes actiongrams, so it imports the type somewhere"


def test_the_foundation_stands_on_the_errors_alone():
    """The foundation is below everything: it imports the error tree and its own modules."""
    for module in (m for m in EDGES if _matches(m, FOUNDATION)):
        above = {t for t in EDGES[module] if t.split(".")[0] in PACKAGES}
        assert above <= set(FOUNDATION), (module, above - set(FOUNDATION))
    assert set(EDGES) >= set(FOUNDATION), "every named foundation module exists"


@pytest.mark.parametrize("module", sorted(EDGES))
def test_no_module_is_over_the_line_cap(module):
    path = module_files()[module]
    lines = len(path.read_text(encoding="utf-8").splitlines())
    assert lines <= MAX_LINES, f"{path.relative_to(REPO)} has {lines} lines"


def test_the_lazy_table_agrees_with_the_submodules():
    import psgs
    for name, module_name in psgs._LAZY.items():
        module = importlib.import_module(f"psgs.{module_name}")
        assert name in module.__all__, (name, module_name)
        assert getattr(psgs, name) is getattr(module, name)
    for name in psgs.__all__:
        assert hasattr(psgs, name), name
    for module_name in psgs._PUBLIC:
        module = importlib.import_module(f"psgs.{module_name}")
        missing = [name for name in module.__all__ if not hasattr(module, name)]
        assert not missing, (module_name, missing)
    # one name per function: no public alias of another public name
    values = [id(getattr(psgs, name)) for name in psgs.__all__ if name != "IDLE"]
    assert len(values) == len(set(values))


def test_help_of_psgs_needs_no_hypothesis():
    script = ("import sys; sys.modules['hypothesis'] = None\n"
              "import pydoc, psgs\n"
              "text = pydoc.render_doc(psgs, renderer=pydoc.plaintext)\n"
              "assert 'accepts' in text and 'loads' in text, text[:400]\n"
              "print('ok')\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                          cwd=REPO, timeout=60)
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr[-2000:]


# -- the picture in docs/architecture.md -------------------------------------------------------
def _picture():
    spec = importlib.util.spec_from_file_location("architecture_picture",
                                                  REPO / "docs" / "architecture_picture.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _box(module: str) -> str | None:
    """The box of the picture that holds ``module`` (None: the package roots)."""
    top = module.split(".")[0]
    if top in ("kinetology", "praxicon"):
        return top
    if module == "psgs":
        return None  # the lazy table names everything; what it imports itself is the top's
    if module.startswith("psgs.induce"):
        return "induce"
    if module.startswith(("psgs.cli", "psgs._display", "psgs.strategies", "psgs.__main__")):
        return "cli"
    if module.startswith("psgs.actiongram"):
        return "actiongram"
    if _matches(module, FOUNDATION):
        return "foundation"
    return "core"


def test_the_picture_is_up_to_date_and_draws_what_the_imports_do():
    picture = _picture()
    committed = (REPO / "docs" / "img" / "architecture.svg").read_text(encoding="utf-8")
    assert committed == picture.svg(), "run: python docs/architecture_picture.py"
    arrows: dict[str, set[str]] = {}
    for source, target, *_ in picture.ARROWS:
        arrows.setdefault(source, set()).add(target)

    def reachable(box: str) -> set[str]:
        seen, todo = set(), [box]
        while todo:
            for nxt in arrows.get(todo.pop(), ()):
                if nxt not in seen:
                    seen.add(nxt)
                    todo.append(nxt)
        return seen

    undrawn = sorted(f"{m} -> {t}" for m, ts in EDGES.items() for t in ts
                     if _box(m) and _box(t) and _box(m) != _box(t)
                     and _box(t) not in reachable(_box(m)))
    assert not undrawn, f"imports the picture does not allow: {undrawn}"
    # and each arrow is used by some import (a picture of rules, not of wishes)
    used = {(_box(m), _box(t)) for m, ts in EDGES.items() for t in ts}
    unused = [a[:2] for a in picture.ARROWS if tuple(a[:2]) not in used]
    assert not unused, f"arrows no import takes: {unused}"
