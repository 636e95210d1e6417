"""Writing: a grammar system as psgs text (the inverse of :func:`psgs.format.loads`), and
every file psgs writes (:func:`dump`, the inverse of :func:`psgs.format.load`).

:func:`dumps` writes the canonical form (``loads(dumps(s)) == s`` for every system); the reader
and its error messages are in :mod:`psgs.format`.
"""

from __future__ import annotations

from os import PathLike
from pathlib import Path

from .errors import ValidationError
from .model import IDLE, PCGS, PSGS, Query, Terminal

__all__ = ["dumps", "dump"]


def dumps(system: PSGS | PCGS) -> str:
    """The canonical text of a PSGS or a PCGS; ``loads(dumps(s)) == s``.

    Every setting is written out, rules keep their order, terminals are
    quoted (JSON escapes), ε is written ``ε``.

    Parameters
    ----------
    system : PSGS or PCGS
        The system to write.

    Returns
    -------
    str
        Text that :func:`loads` reads back to an equal system.

    Raises
    ------
    ValidationError
        When ``system`` is neither a PSGS nor a PCGS.

    Examples
    --------
    >>> from psgs import Grammar, Nonterminal, PSGS, Rule, Terminal
    >>> g = Grammar("G", Nonterminal("S"), (Rule("p", Nonterminal("S"), (Terminal("a"),)),))
    >>> print(dumps(PSGS((g,), sync=[("p",)], name="Tiny")), end="")
    psgs Tiny
    mode parallel
    unsynchronised free
    <BLANKLINE>
    component G start S
      p: S -> "a"
    <BLANKLINE>
    sync
      (p)
    """
    if isinstance(system, PSGS):
        lines = [f"psgs {system.name}", f"mode {system.mode}",
                 f"unsynchronised {system.unsynchronised}"]
    elif isinstance(system, PCGS):
        lines = [f"pcgs {system.name}", f"returning {'yes' if system.returning else 'no'}",
                 f"master {system.master}"]
    else:
        raise ValidationError(f"dumps writes a PSGS or a PCGS, not {type(system).__name__}")
    for grammar in system.components:
        lines.append("")
        lines.append(f"component {grammar.name} start {grammar.start}")
        for rule in grammar.rules:
            body = " ".join(_symbol_text(s) for s in rule.rhs) if rule.rhs else "ε"
            lines.append(f"  {rule.label}: {rule.lhs} -> {body}")
    if isinstance(system, PSGS) and system.sync:
        lines.append("")
        lines.append("sync")
        for sync_tuple in system.sync:
            lines.append("  (" + ", ".join("#" if r is IDLE else r.label for r in sync_tuple)
                         + ")")
    return "\n".join(lines) + "\n"


def dump(value, path: str | PathLike) -> None:
    """Write a grammar system or an actiongram to a file (UTF-8), as ``psgs.load`` reads it.

    A system is written in the text format (``dumps(system)``); an actiongram as JSON when
    the name ends in ``.json``, else in its text form.

    Parameters
    ----------
    value : PSGS, PCGS or Actiongram
        What to write.
    path : str or PathLike
        The file (overwritten).

    Raises
    ------
    ValidationError
        For a value that is neither, or a path that is no str or PathLike.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> import psgs
    >>> gamma = psgs.load("paper_example")
    >>> folder = Path(tempfile.mkdtemp())
    >>> dump(gamma, folder / "copy.psgs")
    >>> psgs.load(folder / "copy.psgs") == gamma
    True
    >>> walk = psgs.Actiongram.from_strings({"knee": "BGRY"})
    >>> dump(walk, folder / "walk.json")
    >>> psgs.load(folder / "walk.json") == walk
    True
    """
    if not isinstance(path, (str, PathLike)):  # pathlib's TypeError would name no argument
        raise ValidationError(f"dump writes to a path (a str or PathLike), not {path!r}")
    if isinstance(value, (PSGS, PCGS)):
        text = dumps(value)
    else:
        from .actiongram import Actiongram

        if not isinstance(value, Actiongram):
            raise ValidationError(f"dump writes a PSGS, a PCGS or an Actiongram, not "
                                  f"{type(value).__name__}")
        text = value.to_json() if Path(path).suffix.lower() == ".json" else value.to_text()
    Path(path).write_text(text, encoding="utf-8")


def _symbol_text(symbol) -> str:
    if isinstance(symbol, Terminal):
        return _quote(symbol.name)
    if isinstance(symbol, Query):
        return f"?{symbol.component}"
    return symbol.name


def _quote(text: str) -> str:
    """A JSON string literal; characters that are not printable are escaped."""
    out = ['"']
    for ch in text:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ch.isprintable():
            out.append(ch)
        else:
            code = ord(ch)
            if code > 0xFFFF:  # JSON spells it as a surrogate pair
                code -= 0x10000
                out.append(f"\\u{0xD800 + (code >> 10):04x}\\u{0xDC00 + (code & 0x3FF):04x}")
            else:
                out.append(f"\\u{code:04x}")
    out.append('"')
    return "".join(out)
