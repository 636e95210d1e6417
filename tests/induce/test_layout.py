"""How psgs.induce is put together: no import cycle (type-only imports included), phases
that never import a learner, and modules of a readable size."""

from __future__ import annotations

import ast
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
INDUCE = ROOT / "psgs" / "induce"
#: The learners: the inducer classes that run the phases in order.
LEARNERS = {"psgs.induce.pal.entry", "psgs.induce.pal.learner", "psgs.induce.pal.motion.learner"}
#: What may import a learner: the packages that export them, PAL (which hands input to the
#: two), the registry that builds them by name.
MAY_IMPORT_LEARNERS = {"psgs.induce", "psgs.induce.pal", "psgs.induce.pal.motion",
                       "psgs.induce.pal.entry", "psgs.induce.registry"}


def _modules() -> dict[str, Path]:
    out = {}
    for path in sorted(INDUCE.rglob("*.py")):
        parts = list(path.relative_to(ROOT).with_suffix("").parts)
        if parts[-1] == "__init__":
            parts.pop()
        out[".".join(parts)] = path
    return out


def _edges() -> dict[str, set[str]]:
    """Every import of a psgs.induce module, anywhere in a file (type-only ones too)."""
    modules = _modules()
    edges: dict[str, set[str]] = {m: set() for m in modules}
    for name, path in modules.items():
        package = name if path.name == "__init__.py" else name.rpartition(".")[0]
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            targets = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                base = package.split(".")[:len(package.split(".")) - node.level + 1] \
                    if node.level else []
                target = ".".join(base + [node.module] if node.module else base) \
                    if node.level else node.module
                # ``from pkg import sub`` imports the submodule, ``from mod import name`` the module
                targets = [f"{target}.{a.name}" if f"{target}.{a.name}" in modules else target
                           for a in node.names]
            for target in targets:
                while target and target not in modules:
                    target = target.rpartition(".")[0]
                if target and target != name:
                    edges[name].add(target)
    return edges


def _cycle(edges: dict[str, set[str]]) -> list[str] | None:
    state: dict[str, int] = {}

    def visit(node, path):
        state[node] = 1
        for nxt in sorted(edges[node]):
            if state.get(nxt) == 1:
                return path[path.index(nxt):] + [nxt]
            if nxt not in state:
                found = visit(nxt, path + [nxt])
                if found:
                    return found
        state[node] = 2
        return None

    for root in sorted(edges):
        if root not in state:
            found = visit(root, [root])
            if found:
                return found
    return None


def test_the_graph_sees_type_only_and_function_level_imports():
    edges = _edges()
    # a type-only import: the Induction's fields typed with the motion learner's results
    assert "psgs.induce.pal.motion.results" in edges["psgs.induce.results"]
    # a function-level import: the compiled engine, imported only when it runs
    assert "psgs.induce.pal._motifs_jit" in edges["psgs.induce.pal.motifs"]


def test_no_import_cycle_in_psgs_induce():
    cycle = _cycle(_edges())
    assert cycle is None, " -> ".join(cycle)


def test_no_phase_module_imports_a_learner():
    edges = _edges()
    bad = sorted(f"{m} -> {t}" for m, ts in edges.items() if m not in MAY_IMPORT_LEARNERS
                 for t in ts & LEARNERS)
    assert not bad, bad


def test_phases_are_handed_a_frozen_conf():
    for path in (INDUCE / "pal").rglob("*.py"):
        text = path.read_text(encoding="utf-8")
        assert "params: PAL" not in text and "from .learner import PAL" not in text, path


def test_no_module_over_600_lines():
    long = {str(p.relative_to(ROOT)): n for p in INDUCE.rglob("*.py")
            if (n := len(p.read_text(encoding="utf-8").splitlines())) > 600}
    assert not long, long
