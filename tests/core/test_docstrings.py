"""Every public function and class of psgs and kinetology has a numpydoc docstring that runs.

Walks ``psgs.__all__`` and ``kinetology.__all__`` (constants such as ``psgs.IDLE`` have no
docstring of their own and are skipped) and reads each docstring's numpydoc sections (a title line
underlined with dashes). Required:

* an ``Examples`` section with at least one ``>>>`` line (``--doctest-modules`` runs it);
* for a function, or a class's constructor, a ``Parameters`` section naming every parameter
  (``self`` aside; ``*args``/``**kwargs`` named with or without their stars); a class may name
  them under ``Attributes`` instead (result types, built by the library rather than by users);
* for a function annotated to return something other than ``None``, a ``Returns`` (or ``Yields``)
  section;
* for a function whose own body has a ``raise`` statement, a ``Raises`` section.

Beyond the two packages' ``__all__``, every function and class that a public module lists in its
own ``__all__`` (and defines) needs at least the ``Examples`` section: every public function
and class has an example that runs (``EXAMPLES_NOT_YET`` lists those still without one).

The API pages in docs/api/ must name every public module, so that a new module appears in the
site (whose strict build checks that its docstrings exist).
"""

from __future__ import annotations

import ast
import dataclasses
import inspect
import re
import textwrap
import warnings
from pathlib import Path

import pytest

import kinetology
import psgs

ROOT = Path(__file__).resolve().parents[2]

# Public names whose docstring still lacks required sections (space-separated). This table only
# shrinks; the test fails on a missing section not listed here and on a listed one now present.
NOT_YET: dict[str, str] = {
    "kinetology.Segmentation": "Parameters Examples",
    "kinetology.compress": "Parameters Returns Examples",
    "kinetology.decompress": "Parameters Returns Raises Examples",
    "kinetology.reconstruct": "Parameters Returns Examples",
    "kinetology.segment": "Parameters Examples",
    "kinetology.segments": "Parameters Returns Examples",
    "kinetology.states": "Parameters Returns Examples",
    "psgs.Acceptance": "Parameters Examples",
    "psgs.Actiongram": "Parameters Examples",
    "psgs.BoundReached": "Examples",
    "psgs.Derivation": "Parameters Examples",
    "psgs.FormatError": "Parameters Examples",
    "psgs.Grammar": "Parameters Examples",
    "psgs.Language": "Parameters Examples",
    "psgs.Nonterminal": "Parameters Examples",
    "psgs.PCGS": "Parameters Examples",
    "psgs.PSGS": "Parameters Examples",
    "psgs.PSGSError": "Examples",
    "psgs.Query": "Parameters Examples",
    "psgs.Rule": "Parameters Examples",
    "psgs.Step": "Parameters Examples",
    "psgs.Terminal": "Parameters Examples",
    "psgs.ValidationError": "Examples",
    "psgs.accepts": "Parameters Returns Raises Examples",
    "psgs.applicable_steps": "Parameters Returns Examples",
    "psgs.apply_step": "Parameters Returns Raises Examples",
    "psgs.as_word": "Parameters Returns Raises Examples",
    "psgs.dump": "Parameters Examples",
    "psgs.dumps": "Parameters Returns Raises Examples",
    "psgs.from_lark_name": "Parameters Returns Raises Examples",
    "psgs.initial_configuration": "Parameters Returns Examples",
    "psgs.language": "Parameters Examples",
    "psgs.load": "Parameters Returns Examples",
    "psgs.load_actiongram": "Parameters Returns Raises Examples",
    "psgs.loads": "Parameters Returns Raises Examples",
    "psgs.random_derivation": "Parameters Returns Raises Examples",
    "psgs.to_lark": "Parameters Returns Raises Examples",
    "psgs.to_networkx": "Parameters Returns Raises Examples",
    "psgs.word": "Parameters Returns Examples",
}


# Functions and classes of public modules' __all__ still without an example (only shrinks).
EXAMPLES_NOT_YET: set[str] = {
    "kinetology.codec.compress",
    "kinetology.codec.decompress",
    "kinetology.codec.encode_segments",
    "kinetology.codec.reconstruct",
    "kinetology.segmentation.Segmentation",
    "kinetology.segmentation.derivatives",
    "kinetology.segmentation.segment",
    "kinetology.segmentation.segments",
    "kinetology.segmentation.significant_sign",
    "kinetology.segmentation.smooth",
    "kinetology.segmentation.states",
    "psgs.actiongram.Actiongram",
    "psgs.actiongram.load_actiongram",
    "psgs.derivation.Derivation",
    "psgs.derivation.Step",
    "psgs.derivation.applicable_steps",
    "psgs.derivation.apply_step",
    "psgs.derivation.apply_tuple",
    "psgs.derivation.communication_step",
    "psgs.derivation.format_configuration",
    "psgs.derivation.format_form",
    "psgs.derivation.initial_configuration",
    "psgs.derivation.is_terminal_configuration",
    "psgs.derivation.language",
    "psgs.derivation.random_derivation",
    "psgs.enumeration.Language",
    "psgs.enumeration.context_free_words",
    "psgs.enumeration.language",
    "psgs.enumeration.min_yields",
    "psgs.format.dump",
    "psgs.format.dumps",
    "psgs.format.load",
    "psgs.format.loads",
    "psgs.graph.nonterminal_node",
    "psgs.graph.rule_node",
    "psgs.graph.to_networkx",
    "psgs.induce.pal.PAL",
    "psgs.lark_export.from_lark_name",
    "psgs.lark_export.grammar_to_lark",
    "psgs.lark_export.lark_name",
    "psgs.lark_export.to_lark",
    "psgs.membership.Acceptance",
    "psgs.membership.accepts",
    "psgs.model.Grammar",
    "psgs.model.Nonterminal",
    "psgs.model.PCGS",
    "psgs.model.PSGS",
    "psgs.model.Query",
    "psgs.model.Rule",
    "psgs.model.Terminal",
    "psgs.model.as_word",
    "psgs.model.is_identifier",
    "psgs.model.resolve_tuple_entries",
    "psgs.model.word",
}


def _public_objects():
    for package in (psgs, kinetology):
        for name in package.__all__:
            obj = getattr(package, name)
            if inspect.isclass(obj) or inspect.isfunction(obj):
                yield f"{package.__name__}.{name}", obj


def sections(doc: str) -> dict[str, str]:
    """The numpydoc sections of ``doc``: title -> body ('' for the summary before the first)."""
    lines = inspect.cleandoc(doc or "").splitlines()
    found, title, body = {}, "", []
    i = 0
    while i < len(lines):
        if (i + 1 < len(lines) and lines[i].strip() and re.fullmatch(r"-{3,}", lines[i + 1].strip())
                and not lines[i].startswith(" ")):
            found[title] = "\n".join(body)
            title, body = lines[i].strip(), []
            i += 2
            continue
        body.append(lines[i])
        i += 1
    found[title] = "\n".join(body)
    return found


def _parameters(obj) -> list[str]:
    target = obj
    if inspect.isclass(obj):
        target = obj.__init__
        if not inspect.isfunction(target):  # a built-in constructor (object, Exception, ...)
            return []
    try:
        signature = inspect.signature(target)
    except (TypeError, ValueError):
        return []
    names = [p.name for p in signature.parameters.values()]
    return [n for n in names if n not in ("self", "cls")]


def _documented_names(body: str) -> set[str]:
    names = set()
    for line in body.splitlines():
        if line and not line.startswith(" "):
            for part in line.split(":")[0].split(","):
                names.add(part.strip().lstrip("*"))
    return names


def _raises_itself(obj) -> bool:
    if not inspect.isfunction(obj):
        return False
    try:
        tree = ast.parse(textwrap.dedent(inspect.getsource(obj)))
    except (OSError, TypeError, SyntaxError):
        return False
    function = tree.body[0]
    nested = {id(n) for d in ast.walk(function) if d is not function
              and isinstance(d, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda))
              for n in ast.walk(d)}
    return any(isinstance(n, ast.Raise) and id(n) not in nested for n in ast.walk(function))


def missing_sections(obj) -> set[str]:
    """The required sections that ``obj``'s docstring lacks (see the module docstring)."""
    doc = obj.__doc__ if obj.__doc__ != getattr(type(obj), "__doc__", None) else None
    if inspect.isclass(obj) and dataclasses.is_dataclass(obj) and doc and doc.startswith(
            f"{obj.__name__}("):
        doc = None  # the docstring dataclasses writes when there is none
    have = sections(doc or "")
    missing = set()
    if not doc:
        missing.add("docstring")
    if ">>>" not in have.get("Examples", ""):
        missing.add("Examples")
    wanted = _parameters(obj)
    if wanted:
        # a class whose values are results rather than things to build may list its fields
        # as Attributes (numpydoc's section for them)
        listed = have.get("Parameters", "") + "\n" + (
            have.get("Attributes", "") if inspect.isclass(obj) else "")
        named = _documented_names(listed)
        if any(n not in named for n in wanted):
            missing.add("Parameters")
    if inspect.isfunction(obj):
        annotation = inspect.signature(obj).return_annotation
        if annotation not in (inspect.Signature.empty, None, "None") and not (
                "Returns" in have or "Yields" in have):
            missing.add("Returns")
        if _raises_itself(obj) and "Raises" not in have:
            missing.add("Raises")
    return missing


def test_public_api_has_numpydoc_sections_with_examples():
    actual = {(name, section) for name, obj in _public_objects()
              for section in missing_sections(obj)}
    allowed = {(name, section) for name, listed in NOT_YET.items() for section in listed.split()}
    new = sorted(actual - allowed)
    fixed = sorted(allowed - actual)
    assert not new, f"public objects missing numpydoc sections: {new}"
    assert not fixed, f"documented now, remove from NOT_YET: {fixed}"


def test_the_walk_finds_the_public_api():
    names = {name for name, _ in _public_objects()}
    assert {"psgs.load", "psgs.PSGS", "psgs.accepts", "kinetology.read", "kinetology.Motion",
            "kinetology.segment"} <= names


def test_sections_reader():
    doc = """Summary.

    Parameters
    ----------
    x, y : int
        Two numbers.
    **options
        More.

    Examples
    --------
    >>> 1 + 1
    2
    """
    have = sections(doc)
    assert set(have) == {"", "Parameters", "Examples"}
    assert _documented_names(have["Parameters"]) == {"x", "y", "options"}

    def f(x, y, **options) -> int:
        raise ValueError(x)

    f.__doc__ = doc
    assert missing_sections(f) == {"Returns", "Raises"}
    f.__doc__ = "Summary only."
    assert missing_sections(f) == {"Examples", "Parameters", "Returns", "Raises"}


def _modules(package: str):
    for path in sorted((ROOT / package).rglob("*.py")):
        parts = path.relative_to(ROOT).with_suffix("").parts
        if parts[-1] == "__init__":
            parts = parts[:-1]
        if any(p.startswith("_") for p in parts) or "cli" in parts:
            continue
        yield ".".join(parts)


def _module_objects():
    import importlib

    for module_name in (m for package in ("psgs", "kinetology") for m in _modules(package)):
        with warnings.catch_warnings():  # a deprecated alias module warns on import
            warnings.simplefilter("ignore", DeprecationWarning)
            module = importlib.import_module(module_name)
        for name in getattr(module, "__all__", ()):
            obj = getattr(module, name)
            if (inspect.isclass(obj) or inspect.isfunction(obj)) and obj.__module__ == module_name:
                yield f"{module_name}.{name}", obj


def test_every_public_function_and_class_has_an_example():
    actual = {name for name, obj in _module_objects() if "Examples" in missing_sections(obj)}
    new = sorted(actual - EXAMPLES_NOT_YET)
    fixed = sorted(EXAMPLES_NOT_YET - actual)
    assert not new, f"public functions and classes without an Examples section: {new}"
    assert not fixed, f"have an example now, remove from EXAMPLES_NOT_YET: {fixed}"


def test_api_pages_name_every_public_module():
    text = "\n".join(p.read_text(encoding="utf-8") for p in (ROOT / "docs" / "api").glob("*.md"))
    shown = set(re.findall(r"^::: ([\w.]+)", text, flags=re.M))
    packages = [p for p in ("psgs", "kinetology", "praxicon") if (ROOT / p).is_dir()]
    missing = [m for package in packages for m in _modules(package) if m not in shown]
    assert not missing, f"modules not in docs/api/*.md: {missing}"
