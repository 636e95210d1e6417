"""A griffe extension for the API reference: a public object without a docstring is a warning.

mkdocstrings shows an undocumented function as a bare signature and says nothing; with this
extension loaded (``mkdocs.yml``) every public module, function, class, method and property of a
package that has no docstring is logged as a warning, and ``mkdocs build --strict`` fails on it.
"Public" is griffe's reading: listed in the module's ``__all__`` where there is one, otherwise a
name without a leading underscore that is defined (not imported) in the module; methods and
properties of a public class are public unless their name starts with an underscore. Names
imported from elsewhere are checked where they are defined, not where they are re-exported.
It fences the ``>>>`` examples that stand outside an ``Examples`` section (a module's docstring
usually) as ``pycon`` code: the numpy parser reads them as prose, and Markdown then runs their
lines together into one paragraph. It also turns the Sphinx roles the docstrings use (``:func:`name```, ``:class:`~a.b.C```) into
inline code, which is how they read in ``help()`` too; mkdocstrings would print them verbatim.

The command-line modules (``psgs.cli``, ``kinetology.cli``) are not API: a command's documentation
is its ``--help``, so they are not checked here.
"""

from __future__ import annotations

import re
from typing import Any

import griffe

_ROLE = re.compile(r":(?:func|class|meth|attr|data|mod|exc|obj|const):`(~?)([^`]+)`")

_NOT_API = {"cli"}  # submodules whose documentation lives elsewhere (see above)
_checked: set[str] = set()  # each package once per build, however many pages render it


class PublicDocstrings(griffe.Extension):
    """Warn, once per object, about public API without a docstring."""

    def on_package(self, *, pkg: griffe.Module, **kwargs: Any) -> None:
        if pkg.path in _checked:
            return
        _checked.add(pkg.path)
        _plain_roles(pkg)
        for path in sorted(_undocumented(pkg)):
            griffe.logger.warning(f"{path}: public, but has no docstring")


def _undocumented(module: griffe.Module):
    if module.name in _NOT_API:
        return
    if not module.docstring:
        yield module.path
    for name, member in module.members.items():
        if member.is_alias:
            continue
        if member.is_module:
            if not name.startswith("_") and name not in _NOT_API:
                yield from _undocumented(member)
            continue
        if name.startswith("_") or not member.is_public or not (member.is_function
                                                                or member.is_class):
            continue  # (module hooks such as __getattr__ and __dir__ are not API)
        if not member.docstring:
            yield member.path
        if member.is_class:
            yield from _undocumented_methods(member)


def _undocumented_methods(cls: griffe.Class):
    for name, member in cls.members.items():
        if name.startswith("_") or member.is_alias or not member.is_function:
            continue
        if not member.docstring:
            yield member.path


def fence_doctests(text: str) -> str:
    """``>>>`` blocks outside a numpy ``Examples`` section as fenced ``pycon`` code.

    A block runs from its first ``>>>`` line to the next blank line, at the same indent.

    >>> lines = ["Use it:", ">>> 1 + 1", "2", "", "Examples", "--------", ">>> 3", "3"]
    >>> fenced = fence_doctests(chr(10).join(lines)).split(chr(10))
    >>> fenced[:6]
    ['Use it:', '', '```pycon', '>>> 1 + 1', '2', '```']
    >>> fenced[-4:]  # the Examples section is the numpy parser's own: left as it is
    ['Examples', '--------', '>>> 3', '3']
    """
    lines = text.split("\n")
    out: list[str] = []
    in_examples = False
    i = 0
    while i < len(lines):
        line = lines[i]
        underline = lines[i + 1].strip() if i + 1 < len(lines) else ""
        if line.strip() and underline and set(underline) == {"-"}:
            in_examples = line.strip() == "Examples"  # the numpy parser's own code section
        if not in_examples and line.lstrip().startswith(">>>"):
            indent = line[:len(line) - len(line.lstrip())]
            if out and out[-1].strip():
                out.append("")
            out.append(indent + "```pycon")
            while i < len(lines) and lines[i].strip() and lines[i].startswith(indent):
                out.append(lines[i])
                i += 1
            out.append(indent + "```")
            continue
        out.append(line)
        i += 1
    return "\n".join(out)


def _plain_roles(obj) -> None:
    if obj.docstring:
        obj.docstring.value = fence_doctests(_ROLE.sub(
            lambda m: f"`{m.group(2).rsplit('.', 1)[-1] if m.group(1) else m.group(2)}`",
            obj.docstring.value))
    for member in obj.members.values():
        if not member.is_alias:
            _plain_roles(member)


class TableSignatures(griffe.Extension):
    """Give an inducer whose ``__init__`` is made from its parameter table that signature.

    ``psgs.induce.Inducer`` makes the constructor of a subclass that declares ``Conf = ...``
    (a frozen table) when the class is created, so the source holds no ``__init__`` for griffe
    to read: the class would be shown without parameters, and its Parameters section would be
    reported as naming parameters the signature lacks. The signature is read from the class
    itself (imported: it is the one ``help()`` shows) and written as the class's ``__init__``;
    so is a docstring the class completes when it is made (PAL's Parameters section).
    """

    def on_class_members(self, *, cls: griffe.Class, **kwargs: Any) -> None:
        if "__init__" in cls.members or "Conf" not in cls.members:
            return
        try:
            import importlib
            import inspect

            runtime = getattr(importlib.import_module(cls.module.path), cls.name)
            signature = inspect.signature(runtime)
        except (ImportError, AttributeError, TypeError, ValueError):
            return
        parameters = [griffe.Parameter("self", kind=griffe.ParameterKind.positional_only)]
        for p in signature.parameters.values():
            parameters.append(griffe.Parameter(
                p.name, kind=griffe.ParameterKind.keyword_only,
                annotation=None if p.annotation is p.empty else str(p.annotation),
                default=None if p.default is p.empty else repr(p.default)))
        init = griffe.Function("__init__", lineno=cls.lineno, endlineno=cls.lineno,
                               parameters=griffe.Parameters(*parameters), parent=cls)
        cls.set_member("__init__", init)
        # a docstring completed when the class is made (PAL lists its learners' parameters)
        written = inspect.cleandoc(runtime.__doc__ or "")
        if cls.docstring is not None and written and written != cls.docstring.value:
            cls.docstring.value = written
