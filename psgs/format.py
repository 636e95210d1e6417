"""Reading the psgs text format (see ``docs/format.md``), and every file psgs reads.

A file describes one PSGS or one PCGS::

    psgs Sync
    mode parallel
    component G1 start S
      p1: S -> "a" S
      p2: S -> "a"
    component G2 start T
      q1: T -> "b" T
      q2: T -> "b"
    sync
      (p1, q1)
      (p2, q2)

The text is split into lines by a Lark grammar shipped with the package
(``psgs/format.lark``); this module reads the keywords, checks the order of
the lines and builds the model values. Every mistake, of syntax or of
meaning, becomes one :class:`~psgs.errors.FormatError` naming
``source:line:column``. :func:`load` is psgs's one file reader (grammar systems,
examples by name, actiongrams); writing is :mod:`psgs.writing`'s (``dump``).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import resources
from os import PathLike
from pathlib import Path

import lark

from ._foundation.files import decode_utf8, read_text
from .errors import FormatError, ValidationError
from .model import IDLE, PCGS, PSGS, Grammar, Nonterminal, Query, Rule, Terminal
__all__ = ["loads", "load", "example_names", "example_path", "ACTIONGRAM_SUFFIXES"]

_MODES = ("parallel", "single")
_UNSYNCHRONISED = ("free", "strict")
_RETURNING = {"yes": True, "no": False}
_SETTINGS = {"psgs": ("mode", "unsynchronised"), "pcgs": ("returning", "master")}

# how a Lark terminal is named in a message
_TOKEN_WORDS = {
    "ARROW": "'->'", "NAME": "a name", "STRING": 'a quoted terminal like "a"',
    "QUERY": "a query like ?G2", "EPSILON": "'ε'", "_NL": "the end of the line",
    "COMMA": "','", "RPAR": "')'", "LPAR": "'('", "IDLE": "'#'", "COLON": "':'",
    "$END": "the end of the text",
}


@lru_cache(maxsize=1)
def _parser() -> lark.Lark:
    text = resources.files("psgs").joinpath("format.lark").read_text(encoding="utf-8")
    return lark.Lark(text, parser="lalr", maybe_placeholders=False)


# ---------------------------------------------------------------- reading
def loads(text: str | bytes, source: str = "<string>") -> PSGS | PCGS:
    """Read a PSGS or a PCGS from text in the psgs format.

    ``source`` names the text in error messages. Bytes are decoded as UTF-8.
    Parameters
    ----------
    text : str or bytes
        The system in the psgs text format (bytes are decoded as UTF-8).
    source : str, default "<string>"
        The name error messages give.

    Returns
    -------
    PSGS or PCGS
        Whichever the header line (``psgs NAME`` or ``pcgs NAME``) says.

    Raises
    ------
    FormatError
        For malformed text, as ``source:line:col: message``; also for a system that is not
        valid (a tuple of the wrong arity, ...), at the place it is written.

    Examples
    --------
    >>> system = loads('''
    ... psgs Copy
    ... component G1 start S
    ...   p1: S -> "a" S
    ...   p2: S -> "a"
    ... component G2 start T
    ...   q1: T -> "b" T
    ...   q2: T -> "b"
    ... sync
    ...   (p1, q1)
    ...   (p2, q2)
    ... ''')
    >>> system.name, len(system.sync), system.mode
    ('Copy', 2, 'parallel')

    >>> loads("psgs Broken", source="broken.psgs")
    Traceback (most recent call last):
    ...
    psgs.errors.FormatError: broken.psgs:1:...
    """
    if isinstance(text, (bytes, bytearray)):
        text = decode_utf8(bytes(text), source)
    if not isinstance(text, str):
        raise TypeError(f"loads expects text, not {type(text).__name__}")
    if text.startswith("\ufeff"):
        text = text[1:]  # a byte-order mark is not content; columns of line 1 shift by one
    if not text.endswith("\n"):
        text += "\n"
    try:
        tree = _parser().parse(text)
    except lark.exceptions.UnexpectedInput as exc:
        raise _syntax_error(exc, text, source) from None
    except lark.exceptions.LarkError as exc:  # pragma: no cover - defensive
        raise FormatError(f"cannot parse: {exc}", source=source) from None
    return _Builder(source).build(tree)


#: Suffixes of actiongram files (``psgs.load`` reads every other file as a grammar system).
ACTIONGRAM_SUFFIXES = (".actiongram", ".json")


def example_names() -> list[str]:
    """The example grammar systems shipped inside the package, loadable by name.

    Returns
    -------
    list of str
        Names such as ``"paper_example"`` (the files are ``psgs/grammars/NAME.psgs``).

    Examples
    --------
    >>> "paper_example" in example_names()
    True
    """
    folder = resources.files("psgs").joinpath("grammars")
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".psgs"))


def example_path(text: str | PathLike) -> str | PathLike:
    """``text`` itself when such a file exists, else the shipped example it names, else ``text``.

    ``paper_example`` (or ``paper_example.psgs``) names the example inside the package when
    there is no file of that name in the working directory, so a pip user can follow the tour.
    Text holding a path separator is always a path.

    Parameters
    ----------
    text : str or PathLike
        A path, or an example's name.

    Returns
    -------
    str or PathLike
        The path to read.

    Examples
    --------
    >>> example_path("paper_example").endswith("paper_example.psgs")
    True
    >>> example_path("no/such.psgs")
    'no/such.psgs'
    """
    name = str(text)
    if Path(name).exists() or any(sep in name for sep in ("/", "\\")):
        return text
    stem = name[:-5] if name.endswith(".psgs") else name
    if stem in example_names():
        return str(resources.files("psgs").joinpath("grammars", f"{stem}.psgs"))
    return text


def load(path: str | PathLike, *, kind: str | None = None):
    """Read a file: a grammar system (PSGS or PCGS), an example by name, or an actiongram.

    ``kind=None`` decides by the name: ``.actiongram`` and ``.json`` files are actiongrams
    (:class:`psgs.Actiongram`; JSON when the name ends in ``.json``, else the text form),
    every other file a grammar system in the text format, whose header line says PSGS or
    PCGS. A name with no such file, such as ``"paper_example"``, reads the example shipped
    in the package (:func:`example_names`). Errors name the file:
    ``grammars/x.psgs:3:7: missing arrow ...``.

    Parameters
    ----------
    path : str or PathLike
        The file, or an example's name.
    kind : {None, "system", "actiongram"}, default None
        What the file holds, when its name does not say (an actiongram named ``walk.txt``).

    Returns
    -------
    PSGS, PCGS or Actiongram

    Raises
    ------
    FormatError
        For malformed text or bytes that are not UTF-8, naming ``path:line:col``; for an
        actiongram file that holds no string.
    ValidationError
        For another ``kind``.
    FileNotFoundError
        When the file does not exist (and is no example's name).

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("paper_example")
    >>> gamma.name, len(gamma.components), len(gamma.sync)
    ('Gamma', 4, 8)
    >>> psgs.load("grammars/paper_example.psgs") == gamma
    True
    """
    if kind not in (None, "system", "actiongram"):
        raise ValidationError(f"kind must be None, 'system' or 'actiongram', not {kind!r}")
    if kind == "actiongram" or (kind is None
                                and Path(path).suffix.lower() in ACTIONGRAM_SUFFIXES):
        from .actiongram import _read_file

        return _read_file(path)
    path = example_path(path)
    return loads(read_text(path), source=str(path))


def _syntax_error(exc: lark.exceptions.UnexpectedInput, text: str, source: str) -> FormatError:
    line, column = exc.line, exc.column
    if isinstance(exc, lark.exceptions.UnexpectedCharacters):
        char = text[exc.pos_in_stream] if exc.pos_in_stream < len(text) else ""
        if char == '"':
            message = "unterminated string: a terminal needs its closing '\"' on the same line"
        elif char == "(" or char == ")":
            message = f"unexpected {char!r}: a tuple stands on a line of its own, after 'sync'"
        elif not char.isprintable() and char not in "\t":
            message = (f"unexpected character {char!r} (control characters and binary data "
                       f"are not allowed)")
        else:
            message = f"unexpected character {char!r}"
            allowed = sorted(_TOKEN_WORDS.get(name, name) for name in exc.allowed or ())
            if allowed:
                message += f"; expected {_one_of(allowed)}"
        return FormatError(message, source=source, line=line, column=column)
    token = getattr(exc, "token", None)
    expected = set(getattr(exc, "expected", ()) or ())
    found = _describe_token(token)
    if "ARROW" in expected:
        message = f"missing arrow: expected '->' (or '→') after the left-hand side, found {found}"
    elif expected <= {"COMMA", "RPAR"} and expected:
        message = f"unterminated tuple: expected ',' or ')', found {found}"
    elif token is not None and token.type == "ARROW":
        message = "a rule needs a label: write 'label: LHS -> ...'"
    elif token is not None and token.type == "_NL":
        words = sorted(_TOKEN_WORDS.get(name, name) for name in expected)
        message = "unterminated line" + (f": expected {_one_of(words)}" if words else "")
    else:
        words = sorted(_TOKEN_WORDS.get(name, name) for name in expected)
        message = f"unexpected {found}" + (f"; expected {_one_of(words)}" if words else "")
    return FormatError(message, source=source, line=line, column=column)


def _describe_token(token) -> str:
    if token is None:
        return "the end of the text"
    if token.type == "_NL":
        return "the end of the line"
    if token.type == "$END":
        return "the end of the text"
    return repr(str(token))


def _one_of(words: list[str]) -> str:
    return words[0] if len(words) == 1 else "one of " + ", ".join(words)


@dataclass
class _Component:
    name: str
    start: Nonterminal
    at: tuple[int, int]
    rules: list[Rule] = field(default_factory=list)
    rule_at: dict[str, tuple[int, int]] = field(default_factory=dict)
    bodies: dict[tuple, Rule] = field(default_factory=dict)


class _Builder:
    """Reads the parsed lines in order and builds the system, with positions for every error."""

    def __init__(self, source: str) -> None:
        self.source = source
        self.kind: str | None = None
        self.name = ""
        self.header_at = (1, 1)
        self.settings: dict[str, tuple[str, tuple[int, int]]] = {}
        self.components: list[_Component] = []
        # name -> component, so a repeated name is found in O(1), not by a scan of all earlier
        # components (16,000 components took 6 s that way)
        self.component_named: dict[str, _Component] = {}
        self.sync_at: tuple[int, int] | None = None
        self.tuples: list[tuple[list[lark.Token], tuple[int, int]]] = []
        # symbol name -> (kind, position of first use), to report a name used as two kinds
        self.kinds: dict[str, tuple[str, tuple[int, int]]] = {}
        self.terminals: dict[str, Terminal] = {}  # quoted text -> terminal, decoded once

    def error(self, message: str, at: tuple[int, int] | None) -> FormatError:
        line, column = at if at else (None, None)
        return FormatError(message, source=self.source, line=line, column=column)

    # -- lines ------------------------------------------------------------
    def build(self, tree: lark.Tree) -> PSGS | PCGS:
        for line in tree.children:
            if line.data == "words":
                self.words_line(line.children)
            elif line.data == "rule":
                self.rule_line(line)
            else:
                self.tuple_line(line)
        if self.kind is None:
            raise self.error("empty file: expected a first line 'psgs NAME' or 'pcgs NAME'",
                             (1, 1))
        if not self.components:
            raise self.error(f"a {self.kind} needs at least one 'component NAME start SYMBOL' "
                             f"line", self.header_at)
        return self.system()

    def words_line(self, words: list[lark.Token]) -> None:
        first = words[0]
        at = _at(first)
        if self.kind is None:
            if str(first) not in ("psgs", "pcgs") or len(words) != 2:
                raise self.error("expected a first line 'psgs NAME' or 'pcgs NAME'", at)
            self.kind, self.name, self.header_at = str(first), str(words[1]), at
            return
        if str(first) in ("psgs", "pcgs"):
            raise self.error(f"a second header line: this file already describes "
                             f"{self.kind} {self.name}", at)
        if str(first) in ("mode", "unsynchronised", "returning", "master"):
            self.setting_line(words)
        elif str(first) == "component":
            self.component_line(words)
        elif str(first) == "sync" and len(words) == 1:
            self.sync_line(at)
        else:
            raise self.error(f"cannot read line starting {str(first)!r}: expected a setting, "
                             f"'component NAME start SYMBOL', 'sync', a rule 'label: LHS -> ...' "
                             f"or a tuple", at)

    def setting_line(self, words: list[lark.Token]) -> None:
        key = str(words[0])
        at = _at(words[0])
        if key not in _SETTINGS[self.kind]:
            other = "pcgs" if self.kind == "psgs" else "psgs"
            raise self.error(f"'{key}' is a setting of a {other}, not of a {self.kind}", at)
        if self.components:
            raise self.error(f"the setting '{key}' must come before the first component", at)
        if len(words) != 2:
            raise self.error(f"write the setting as '{key} VALUE' (one value)", at)
        if key in self.settings:
            raise self.error(f"'{key}' is set twice (first on line "
                             f"{self.settings[key][1][0]})", at)
        value = str(words[1])
        allowed = {"mode": _MODES, "unsynchronised": _UNSYNCHRONISED,
                   "returning": tuple(_RETURNING)}.get(key)
        if allowed and value not in allowed:
            raise self.error(f"{key} must be {' or '.join(allowed)}, not {value!r}",
                             _at(words[1]))
        self.settings[key] = (value, _at(words[1]))

    def component_line(self, words: list[lark.Token]) -> None:
        at = _at(words[0])
        if self.sync_at is not None:
            raise self.error("components must come before the 'sync' section", at)
        if len(words) != 4 or str(words[2]) != "start":
            raise self.error("write a component as 'component NAME start SYMBOL'", at)
        name = str(words[1])
        other = self.component_named.get(name)
        if other is not None:
            raise self.error(f"a second component named {name} (the first is on line "
                             f"{other.at[0]})", _at(words[1]))
        start = Nonterminal(str(words[3]))
        self.note_kind(start.name, "nonterminal", _at(words[3]))
        component = _Component(name, start, at)
        self.components.append(component)
        self.component_named[name] = component

    def sync_line(self, at: tuple[int, int]) -> None:
        if self.kind == "pcgs":
            raise self.error("a pcgs has no 'sync' section (its components communicate by "
                             "queries)", at)
        if self.sync_at is not None:
            raise self.error(f"a second 'sync' line (the first is on line {self.sync_at[0]})", at)
        if not self.components:
            raise self.error("'sync' must follow the components", at)
        self.sync_at = at

    def rule_line(self, tree: lark.Tree) -> None:
        label_token, lhs_token, _arrow, *symbols = tree.children
        at = _at(label_token)
        if self.kind is None:
            raise self.error("expected a first line 'psgs NAME' or 'pcgs NAME'", at)
        if self.sync_at is not None or not self.components:
            where = "after 'sync'" if self.sync_at is not None else "before any component"
            raise self.error(f"a rule {where}: rules belong under a 'component' line", at)
        component = self.components[-1]
        label = str(label_token)
        if label in component.rule_at:
            raise self.error(f"component {component.name}: a second rule labelled {label} "
                             f"(the first is on line {component.rule_at[label][0]})", at)
        lhs = Nonterminal(str(lhs_token))
        self.note_kind(lhs.name, "nonterminal", _at(lhs_token))
        rhs = self.right_side(symbols)
        rule = Rule(label, lhs, rhs)
        other = component.bodies.setdefault((rule.lhs, rule.rhs), rule)
        if other is not rule:
            raise self.error(f"component {component.name}: rule {label} repeats rule "
                             f"{other.label} ({other})", at)
        component.rules.append(rule)
        component.rule_at[label] = at

    def right_side(self, symbols: list[lark.Token]) -> tuple:
        rhs = []
        for token in symbols:
            at = _at(token)
            if token.type == "EPSILON":
                if len(symbols) > 1:
                    raise self.error("ε stands alone: write it as the whole right side, or leave "
                                     "the right side empty", at)
            elif token.type == "NAME":
                self.note_kind(str(token), "nonterminal", at)
                rhs.append(Nonterminal(str(token)))
            elif token.type == "STRING":
                rhs.append(self.terminal(token))
            else:
                if self.kind == "psgs":
                    raise self.error(f"query symbol {token} in a psgs: only a pcgs has queries",
                                     at)
                rhs.append(Query(str(token)[1:]))
        return tuple(rhs)

    def terminal(self, token: lark.Token) -> Terminal:
        known = self.terminals.get(str(token))
        if known is not None:
            return known
        at = _at(token)
        try:
            text = json.loads(str(token))
        except json.JSONDecodeError as exc:
            raise self.error(f"bad terminal {token}: {exc.msg}", at) from None
        try:
            terminal = Terminal(text)
        except ValidationError as exc:
            raise self.error(str(exc), at) from None
        self.note_kind(text, "terminal", at)
        self.terminals[str(token)] = terminal
        return terminal

    def note_kind(self, name: str, kind: str, at: tuple[int, int]) -> None:
        prior = self.kinds.setdefault(name, (kind, at))
        if prior[0] != kind:
            shown = f'"{name}"' if kind == "terminal" else name
            raise self.error(f"{shown} is used as a {kind} here but as a {prior[0]} on line "
                             f"{prior[1][0]}: a name is either a terminal (quoted) or a "
                             f"nonterminal (bare), not both", at)

    def tuple_line(self, tree: lark.Tree) -> None:
        parenthesis, *entries = tree.children
        at = _at(parenthesis)
        if self.kind is None:
            raise self.error("expected a first line 'psgs NAME' or 'pcgs NAME'", at)
        if self.sync_at is None:
            raise self.error("a tuple outside the 'sync' section: write 'sync' on the line "
                             "before the tuples", at)
        self.tuples.append((entries, at))

    # -- the system -------------------------------------------------------
    def system(self) -> PSGS | PCGS:
        grammars = [self.grammar(c) for c in self.components]
        values = {key: value for key, (value, _) in self.settings.items()}
        try:
            if self.kind == "pcgs":
                names = [g.name for g in grammars]
                master = values.get("master", names[0])
                if master not in names:
                    raise self.error(f"the master {master} is not a component (components: "
                                     f"{', '.join(names)})", self.settings["master"][1])
                self.check_queries(names)
                return PCGS(tuple(grammars), returning=_RETURNING[values.get("returning", "yes")],
                            master=master, name=self.name)
            sync = self.sync_tuples(grammars)
            return PSGS(tuple(grammars), sync=sync, mode=values.get("mode", "parallel"),
                        unsynchronised=values.get("unsynchronised", "free"), name=self.name)
        except ValidationError as exc:
            # anything the checks above did not place is reported at the header
            raise self.error(str(exc), self.header_at) from None

    def grammar(self, component: _Component) -> Grammar:
        if not component.rules:
            raise self.error(f"component {component.name} has no rules", component.at)
        if not any(r.lhs == component.start for r in component.rules):
            raise self.error(f"component {component.name}: start symbol {component.start} has "
                             f"no rule", component.at)
        try:
            return Grammar(component.name, component.start, tuple(component.rules))
        except ValidationError as exc:
            raise self.error(str(exc), component.at) from None

    def check_queries(self, names: list[str]) -> None:
        names = set(names)  # a query is checked in O(1), not against a list of every component
        for component in self.components:
            for rule in component.rules:
                for sym in rule.rhs:
                    if isinstance(sym, Query) and sym.component not in names:
                        raise self.error(f"component {component.name}: rule {rule.label} "
                                         f"queries ?{sym.component}, which names no component",
                                         component.rule_at[rule.label])

    def sync_tuples(self, grammars: list[Grammar]) -> tuple:
        out = []
        seen: dict[tuple, int] = {}
        for entries, at in self.tuples:
            if len(entries) != len(grammars):
                raise self.error(f"this tuple has {_count(len(entries), 'entry', 'entries')} but "
                                 f"the system has {_count(len(grammars), 'component')} "
                                 f"({', '.join(g.name for g in grammars)})", at)
            resolved = []
            for grammar, token in zip(grammars, entries):
                if token.type == "IDLE":
                    resolved.append(IDLE)
                elif str(token) in grammar.rule_by_label:
                    resolved.append(grammar.rule_by_label[str(token)])
                else:
                    raise self.error(f"component {grammar.name} has no rule labelled {token}",
                                     _at(token))
            key = tuple(resolved)
            if all(r is IDLE for r in key):
                raise self.error("this tuple idles in every component", at)
            if key in seen:
                raise self.error(f"this tuple repeats the tuple on line {seen[key]}", at)
            seen[key] = at[0]
            out.append(key)
        return tuple(out)


def _count(n: int, singular: str, plural: str | None = None) -> str:
    return f"{n} {singular if n == 1 else plural or singular + 's'}"


def _at(token: lark.Token) -> tuple[int, int]:
    return (token.line, token.column)


# ---------------------------------------------------------------- writing
