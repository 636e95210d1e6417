"""Export component grammars as Lark grammars (see ``docs/export.md``).

``to_lark(system)`` gives, per component, a Lark grammar whose language is
exactly that component's context-free language taken alone. Synchronisation
(the tuples of M) and parallel-mode rewriting cannot be said in Lark, so for
a PSGS a word of the export is a *necessary* condition of membership, not the
whole answer.

Words are given to Lark as their terminals' texts joined by single spaces,
so multi-character terminals stay unambiguous::

    parser = lark.Lark(text, start="start", parser="earley", lexer="basic")
    parser.parse("a b c")

Names are mangled injectively and reversibly (:func:`from_lark_name`):

* a nonterminal ``N13`` becomes the rule ``n__n13``: prefix ``n_``, then
  lowercase letters and digits as they are, an uppercase letter ``X`` as
  ``_x`` and ``_`` as ``__``;
* a terminal ``a`` becomes the named terminal ``T_A``: prefix ``T_``, then a
  lowercase letter as its uppercase, an uppercase letter ``X`` as ``_X``,
  a digit as itself, ``_`` as ``__`` and any other character as ``_<code>_``
  (its decimal code point);

A PCGS component taken alone derives nothing from a query symbol (it only
gets a value by communication), so rules holding a query are left out, as
are rules that take part in no terminal derivation; the language is
unchanged.
"""

from __future__ import annotations

from collections.abc import Iterable
from types import MappingProxyType

from .errors import ValidationError
from .model import PCGS, PSGS, Grammar, Nonterminal, Rule, Terminal

__all__ = ["to_lark", "grammar_to_lark", "from_lark_name", "lark_name", "START_RULE",
           "EMPTY_TERMINAL", "LARK_OPTIONS"]

#: The rule every export starts from.
START_RULE = "start"
#: The declared (never produced) terminal a component with an empty language derives.
EMPTY_TERMINAL = "EMPTY_LANGUAGE"
#: The options the exports are written for (read-only: pass them as ``lark.Lark(text, **LARK_OPTIONS)``).
LARK_OPTIONS = MappingProxyType({"start": START_RULE, "parser": "earley", "lexer": "basic"})

_NT_PREFIX = "n_"
_T_PREFIX = "T_"


# ---------------------------------------------------------------- names
def lark_name(symbol: Nonterminal | Terminal) -> str:
    """The Lark name of a symbol: a rule name for a nonterminal, a terminal name otherwise.

    Examples
    --------
    >>> from psgs import Nonterminal, Terminal
    >>> lark_name(Nonterminal("N13")), lark_name(Terminal("a"))
    ('n__n13', 'T_A')
    >>> from_lark_name(lark_name(Nonterminal("N13")))
    Nonterminal(name='N13')
    """
    if isinstance(symbol, Nonterminal):
        return _NT_PREFIX + _encode_nonterminal(symbol.name)
    if isinstance(symbol, Terminal):
        return _T_PREFIX + _encode_terminal(symbol.name)
    raise ValidationError(f"{symbol!r} is not a symbol")


def _encode_nonterminal(name: str) -> str:
    out = []
    for ch in name:
        if ch == "_":
            out.append("__")
        elif "A" <= ch <= "Z":
            out.append("_" + ch.lower())
        else:  # identifiers hold only ASCII letters, digits and _
            out.append(ch)
    return "".join(out)


def _decode_nonterminal(code: str, whole: str) -> str:
    out = []
    chars = iter(code)
    for ch in chars:
        if ch == "_":
            nxt = next(chars, "")
            if nxt == "_":
                out.append("_")
            elif "a" <= nxt <= "z":
                out.append(nxt.upper())
            else:
                raise _not_ours(whole)
        elif "a" <= ch <= "z" or "0" <= ch <= "9":
            out.append(ch)
        else:
            raise _not_ours(whole)
    return "".join(out)


def _encode_terminal(text: str) -> str:
    out = []
    for ch in text:
        if "a" <= ch <= "z":
            out.append(ch.upper())
        elif "A" <= ch <= "Z":
            out.append("_" + ch)
        elif "0" <= ch <= "9":
            out.append(ch)
        elif ch == "_":
            out.append("__")
        else:
            out.append(f"_{ord(ch)}_")
    return "".join(out)


def _decode_terminal(code: str, whole: str) -> str:
    out = []
    i = 0
    while i < len(code):
        ch = code[i]
        if "A" <= ch <= "Z":
            out.append(ch.lower())
            i += 1
        elif "0" <= ch <= "9":
            out.append(ch)
            i += 1
        elif ch == "_" and i + 1 < len(code):
            nxt = code[i + 1]
            if nxt == "_":
                out.append("_")
                i += 2
            elif "A" <= nxt <= "Z":
                out.append(nxt)
                i += 2
            elif "0" <= nxt <= "9":
                end = code.find("_", i + 1)
                if end < 0:
                    raise _not_ours(whole)
                point = int(code[i + 1:end])
                if point > 0x10FFFF or code[i + 1] == "0" and end > i + 2:
                    raise _not_ours(whole)
                out.append(chr(point))
                i = end + 1
            else:
                raise _not_ours(whole)
        else:
            raise _not_ours(whole)
    return "".join(out)


def from_lark_name(name: str) -> Nonterminal | Terminal:
    """The symbol a Lark rule or terminal name of an export stands for.

    The inverse of :func:`lark_name`.

    Raises :class:`~psgs.errors.ValidationError` for a name no export uses
    (``start``, ``EMPTY_LANGUAGE``, Lark's anonymous names).

    Parameters
    ----------
    name : str
        A rule or terminal name of an exported grammar.

    Returns
    -------
    Nonterminal or Terminal

    Raises
    ------
    ValidationError
        For a name no export uses (``start``, ``EMPTY_LANGUAGE``, Lark's anonymous names).

    Examples
    --------
    >>> from_lark_name("n__n13")
    Nonterminal(name='N13')
    >>> from_lark_name("T_A")
    Terminal(name='a')
    """
    if not isinstance(name, str):
        raise ValidationError(f"a Lark name is text, not {name!r}")
    if not name.startswith((_NT_PREFIX, _T_PREFIX)):
        raise _not_ours(name)  # no prefix: nothing more to say than that
    try:
        if name.startswith(_NT_PREFIX):
            symbol = Nonterminal(_decode_nonterminal(name[len(_NT_PREFIX):], name))
        else:
            symbol = Terminal(_decode_terminal(name[len(_T_PREFIX):], name))
    except ValidationError as exc:
        if str(exc) == str(_not_ours(name)):  # the decoder's own refusal: said once
            raise _not_ours(name) from None
        raise ValidationError(f"{name!r} is not a name psgs.to_lark writes ({exc})") from None
    if lark_name(symbol) != name:  # e.g. a code point spelled with a leading zero
        raise _not_ours(name)
    return symbol


def _not_ours(name: str) -> ValidationError:
    return ValidationError(f"{name!r} is not a name psgs.to_lark writes")


# ---------------------------------------------------------------- grammars
def to_lark(system: PSGS | PCGS | Grammar) -> dict[str, str]:
    """Each component's grammar as Lark grammar text, by component name.

    A single :class:`~psgs.model.Grammar` gives a one-entry dict. Load a
    text with ``lark.Lark(text, start="start", parser="earley",
    lexer="basic")`` and parse words as terminals joined by single spaces.
    The language of each text is exactly the component's context-free
    language taken alone (a PCGS query derives nothing there);
    synchronisation is not expressible in Lark.

    Parameters
    ----------
    system : PSGS, PCGS or Grammar
        The system (or one grammar) to export.

    Returns
    -------
    dict of str to str
        Lark grammar text by component name.

    Raises
    ------
    ValidationError
        When ``system`` is not a PSGS, PCGS or Grammar.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> import lark
    >>> texts = to_lark(gamma)
    >>> sorted(texts)
    ['G1', 'G2', 'G3', 'G4']
    >>> parser = lark.Lark(texts["G1"], start="start", parser="earley", lexer="basic")
    >>> parser.parse("a b c d b c a d").data
    Token('RULE', 'start')
    """
    if isinstance(system, Grammar):
        return {system.name: grammar_to_lark(system)}
    if isinstance(system, (PSGS, PCGS)):
        return {g.name: grammar_to_lark(g, system) for g in system.components}
    raise ValidationError(f"to_lark exports a PSGS, a PCGS or a Grammar, not "
                          f"{type(system).__name__}")


def grammar_to_lark(grammar: Grammar, system: PSGS | PCGS | None = None) -> str:
    """One component's Lark grammar text (see :func:`to_lark`).

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> text = grammar_to_lark(gamma.components[0])
    >>> text == psgs.to_lark(gamma.components[0])["G1"]
    True
    """
    if not isinstance(grammar, Grammar):
        raise ValidationError(f"grammar_to_lark exports a Grammar, not {type(grammar).__name__}")
    useful = _useful_rules(grammar)
    lines = _header(grammar, system)
    if not useful:
        lines += [f"// The start symbol {grammar.start} derives no terminal word: the language",
                  "// is empty, and no input parses.",
                  f"{START_RULE}: {EMPTY_TERMINAL}",
                  f"%declare {EMPTY_TERMINAL}"]
        return "\n".join(lines) + "\n"
    dropped = len(grammar.rules) - len(useful)
    if dropped:
        lines.append(f"// {dropped} rule(s) that take part in no terminal derivation from "
                     f"{grammar.start} are left out (the language is the same).")
    lines.append(f"{START_RULE}: {lark_name(grammar.start)}")
    lines.append("")
    by_lhs: dict[Nonterminal, list[Rule]] = {}
    for rule in useful:
        by_lhs.setdefault(rule.lhs, []).append(rule)
    for lhs, rules in by_lhs.items():
        alternatives = [_expansion(rule) for rule in rules]
        lines.append(f"// {', '.join(f'{r.label}: {r}' for r in rules)}")
        lines.append(f"{lark_name(lhs)}: " + "\n    | ".join(alternatives))
    lines.append("")
    for symbol in _terminals_in(useful):
        lines.append(f"{lark_name(symbol)}: {_literal(symbol.name)}")
    lines.append("")
    lines.append('%ignore " "')
    return "\n".join(lines) + "\n"


def _header(grammar: Grammar, system) -> list[str]:
    whose = f"component {grammar.name}"
    if system is not None:
        kind = "PSGS" if isinstance(system, PSGS) else "PCGS"
        whose += f" of the {kind} {system.name}"
    lines = [
        f"// Lark grammar for {whose}, exported by psgs.to_lark.",
        f"// Load with: lark.Lark(text, start=\"{START_RULE}\", parser=\"earley\", "
        f"lexer=\"basic\")",
        "// and parse a word as its terminals joined by single spaces, e.g. \"a b c\".",
        "// Its language is the component's context-free language taken alone.",
    ]
    if isinstance(system, PSGS):
        if system.mode == "parallel":
            lines += [
                "// Synchronisation (the tuples of M) is not expressible in Lark, and neither",
                "// is rewriting every occurrence at once (mode parallel): a word of this",
                "// grammar is a necessary condition for membership, not the whole answer.",
            ]
        else:
            lines += [
                "// Synchronisation (the tuples of M) is not expressible in Lark: a word of",
                "// this grammar is a necessary condition for membership, not the whole answer.",
            ]
    elif isinstance(system, PCGS):
        lines += [
            "// Communication between components is not expressible in Lark: taken alone a",
            "// component derives nothing from a query ?NAME, so rules with queries are left",
            "// out, and the master's words in the system are not this grammar's language.",
        ]
    lines += [
        "// Names: nonterminal X1 -> rule n__x1; terminal \"a\" -> terminal T_A;",
        "// psgs.lark_export.from_lark_name maps them back.",
        "",
    ]
    return lines


def _expansion(rule: Rule) -> str:
    if not rule.rhs:
        return "  // ε"
    return " ".join(lark_name(s) for s in rule.rhs)


def _terminals_in(rules: Iterable[Rule]) -> list[Terminal]:
    seen: dict[Terminal, None] = {}
    for rule in rules:
        for s in rule.rhs:
            if isinstance(s, Terminal):
                seen.setdefault(s, None)
    return list(seen)


def _literal(text: str) -> str:
    """A Lark pattern matching exactly ``text``.

    Plain text becomes a string literal. Lark's string literals turn ``\\\\``
    into one backslash after unescaping, so text with ``\\``, ``"`` or
    characters that are not printable becomes a regular expression in which
    every character but an ASCII letter or digit is escaped: Lark reads
    ``\\u005c\\uXXXX`` in a pattern as a backslash followed by the character.
    """
    if text.isprintable() and '"' not in text and "\\" not in text:
        return '"' + text + '"'
    parts = []
    for ch in text:
        if ch.isascii() and ch.isalnum():
            parts.append(ch)
        elif ord(ch) > 0xFFFF:
            parts.append(f"\\u005c\\U{ord(ch):08x}")
        else:
            parts.append(f"\\u005c\\u{ord(ch):04x}")
    return "/" + "".join(parts) + "/"


def _useful_rules(grammar: Grammar) -> list[Rule]:
    """The rules that take part in some terminal derivation from the start symbol, in order.

    A query symbol derives nothing in a component taken alone, so a rule
    holding one takes part in no terminal derivation. Linear in the size of
    the grammar (a worklist, as induced grammars have thousands of rules).
    """
    waiting: dict[Nonterminal, list[int]] = {}  # nonterminal -> rules it still blocks
    missing = []
    productive: set[Nonterminal] = set()
    queue: list[Nonterminal] = []
    for index, rule in enumerate(grammar.rules):
        if any(not isinstance(s, (Terminal, Nonterminal)) for s in rule.rhs):
            missing.append(-1)  # a query: never productive
            continue
        needed = {s for s in rule.rhs if isinstance(s, Nonterminal)}
        missing.append(len(needed))
        for symbol in needed:
            waiting.setdefault(symbol, []).append(index)
        if not needed and rule.lhs not in productive:
            productive.add(rule.lhs)
            queue.append(rule.lhs)
    while queue:
        for index in waiting.get(queue.pop(), ()):
            missing[index] -= 1
            lhs = grammar.rules[index].lhs
            if missing[index] == 0 and lhs not in productive:
                productive.add(lhs)
                queue.append(lhs)
    if grammar.start not in productive:
        return []
    candidates: dict[Nonterminal, list[Rule]] = {}
    for index, rule in enumerate(grammar.rules):
        if missing[index] == 0:
            candidates.setdefault(rule.lhs, []).append(rule)
    reachable = {grammar.start}
    frontier = [grammar.start]
    while frontier:
        for rule in candidates.get(frontier.pop(), ()):
            for s in rule.rhs:
                if s not in reachable:
                    reachable.add(s)
                    frontier.append(s)
    return [r for i, r in enumerate(grammar.rules) if missing[i] == 0 and r.lhs in reachable]
