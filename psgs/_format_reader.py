"""The psgs text format's lines, parsed by Lark and read into a PSGS or a PCGS.

The text is split into lines by a Lark grammar shipped with the package
(``psgs/format.lark``); :class:`_Builder` reads the keywords, checks the order of the
lines and builds the model values. Every mistake, of syntax or of meaning, becomes one
:class:`~psgs.errors.FormatError` naming ``source:line:column``. :func:`read_system` is
what :func:`psgs.loads` runs on a text it has decoded.
"""

from __future__ import annotations

import json
import unicodedata
from array import array
from dataclasses import dataclass, field
from functools import lru_cache
from importlib import resources

import lark

from ._foundation.text import character_name, first_unseen
from .errors import FormatError, ValidationError
from .model import IDLE, PCGS, PSGS, Grammar, Nonterminal, Query, Rule, Terminal

__all__ = ["read_system"]

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



def read_system(text: str, source: str) -> PSGS | PCGS:
    """The system ``text`` describes (a text ending with a line break, no byte-order mark).

    Examples
    --------
    >>> read_system('psgs S\\ncomponent G start S\\n  p: S -> "a"\\n', "s.psgs").name
    'S'
    """
    builder = _Builder(source)
    for offset, chunk in _chunks(text, _CHUNK):
        if len(chunk) > _CHUNK and not builder.read_long_line(chunk, offset):
            continue  # one line longer than a chunk, read token by token: done
        builder.read(_parse(chunk, offset, source), offset)
    return builder.finish()


#: Characters of text parsed at once. Lark holds a token object (~350 bytes) for every
#: symbol of what it parses, so the text is parsed a chunk of whole lines at a time (a
#: statement ends at its line) and the tokens of one chunk are let go before the next: a
#: file's peak memory is what it describes plus a chunk's tokens, not ~100 bytes per byte
#: of the file. A single line longer than this is read token by token from the lexer.
_CHUNK = 1 << 16


def _chunks(text: str, size: int):
    """``(lines before, chunk)`` for runs of whole lines of ``text`` (which ends with a line
    break), each at most ``size`` characters unless it is one line longer than that."""
    start, line = 0, 0
    while start < len(text):
        end = text.rfind("\n", start, start + size) + 1
        if end <= start:  # no line break within size characters: one long line
            end = text.index("\n", start) + 1
        chunk = text[start:end]
        yield line, chunk
        line += chunk.count("\n")
        start = end


def _parse(chunk: str, offset: int, source: str) -> lark.Tree:
    try:
        return _parser().parse(chunk)
    except lark.exceptions.UnexpectedInput as exc:
        raise _syntax_error(exc, chunk, source, offset) from None
    except lark.exceptions.LarkError as exc:  # pragma: no cover - defensive
        raise FormatError(f"cannot parse: {exc}", source=source) from None


def _syntax_error(exc: lark.exceptions.UnexpectedInput, text: str, source: str,
                  offset: int = 0) -> FormatError:
    line, column = exc.line, exc.column
    if isinstance(line, int) and line > 0:
        line += offset  # ``text`` is a chunk of the file that starts after ``offset`` lines
    if isinstance(exc, lark.exceptions.UnexpectedCharacters):
        char = text[exc.pos_in_stream] if exc.pos_in_stream < len(text) else ""
        if char == '"':
            message = "unterminated string: a terminal needs its closing '\"' on the same line"
        elif char == "(" or char == ")":
            message = (f"unexpected {_character(char)}: a tuple stands on a line of its own, "
                       f"after 'sync'")
        elif not char.isprintable() and char not in "\t":
            message = (f"unexpected character {_character(char)} (control characters and "
                       f"binary data are not allowed)")
        else:
            message = f"unexpected character {_character(char)}"
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


def _raw_offset(quoted: str, index: int) -> int:
    r"""Where the character ``index`` of the text a quoted terminal stands for begins in the
    quoted text as written (a JSON string literal, quote included).

    >>> _raw_offset('"ab"', 1), _raw_offset('"\\u00e9b"', 1), _raw_offset('"\\ud83d\\ude00x"', 1)
    (2, 7, 13)
    """
    k, char = 1, 0
    while char < index:
        if quoted[k] != "\\":
            k += 1
        elif quoted[k + 1] != "u":
            k += 2
        else:
            high = int(quoted[k + 2:k + 6], 16)
            k += 6
            # a surrogate pair written as two escapes is one character of the text
            if 0xD800 <= high < 0xDC00 and quoted[k:k + 2] == "\\u" and \
                    0xDC00 <= int(quoted[k + 2:k + 6], 16) < 0xE000:
                k += 6
        char += 1
    return k


def _character(char: str) -> str:
    """``char`` as a message names it (:func:`character_name`), quoted before its name when
    it can be seen: ``'%' (U+0025 PERCENT SIGN)``, ``U+001B ESCAPE``.

    A quote is quoted by the other quote (``"'" (U+0027 APOSTROPHE)``), and a combining
    mark, which would sit on its quote, is named alone.

    >>> _character("("), _character("\\x1b"), _character("\\u200b")
    ("'(' (U+0028 LEFT PARENTHESIS)", 'U+001B ESCAPE', 'U+200B ZERO WIDTH SPACE')
    >>> print(_character("'"), _character("\\u0301"), sep=", ")
    "'" (U+0027 APOSTROPHE), U+0301 COMBINING ACUTE ACCENT
    """
    name = character_name(char)
    seen = (char.isprintable() and first_unseen(char) is None
            and not unicodedata.category(char).startswith("M"))
    return f"{char!r} ({name})" if seen else name


def _hidden(text: str) -> str:
    """The first character of ``text`` that cannot be shown as it is (a token is shown with
    escapes, which say little: ``\\x85``, ``\\u200b``), named; "" when every one can.

    >>> _hidden('"a\\x85"'), _hidden('"a"')
    (' (it holds U+0085 NEXT LINE)', '')
    """
    char = next((c for c in text if not c.isprintable()), None)
    return "" if char is None else f" (it holds {character_name(char)})"


def _describe_token(token) -> str:
    if token is None:
        return "the end of the text"
    if token.type == "_NL":
        return "the end of the line"
    if token.type == "$END":
        return "the end of the text"
    return repr(str(token)) + _hidden(str(token))


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
        # per tuple: its entries (a rule label, or None for the idle marker), its line, the
        # column of its parenthesis and of each entry -- not lark's tokens, which are let go
        # with their chunk
        self.tuples: list[tuple[tuple, int, array]] = []
        self.labels: dict[str, str] = {}  # one string per label, however many tuples name it
        self.offset = 0  # lines before the chunk being read
        # symbol name -> (kind, position of first use), to report a name used as two kinds
        self.kinds: dict[str, tuple[str, tuple[int, int]]] = {}
        self.terminals: dict[str, Terminal] = {}  # quoted text -> terminal, decoded once

    def error(self, message: str, at: tuple[int, int] | None) -> FormatError:
        line, column = at if at else (None, None)
        return FormatError(message, source=self.source, line=line, column=column)

    def at(self, token: lark.Token) -> tuple[int, int]:
        """Where ``token`` is in the file (its chunk starts after ``self.offset`` lines)."""
        return (token.line + self.offset, token.column)

    # -- lines ------------------------------------------------------------
    def read(self, tree: lark.Tree, offset: int) -> None:
        """Read the lines of one parsed chunk, which starts after ``offset`` lines."""
        self.offset = offset
        for line in tree.children:
            if line.data == "words":
                self.words_line(line.children)
            elif line.data == "rule":
                label, lhs, _arrow, *symbols = line.children
                self.rule_line(label, lhs, symbols)
            else:
                self.tuple_line(line.children[0], line.children[1:])

    def read_long_line(self, line: str, offset: int) -> bool:
        """Read one long line from the lexer's tokens as they come, without a token list;
        True when it is no rule or tuple to read so (then it is parsed as any chunk).

        A line that is not a well-formed rule or tuple is parsed up to the token where it
        goes wrong, which raises the parser's own error at that place.
        """
        self.offset = offset
        tokens = _parser().lex(line)
        try:
            first, second = next(tokens), next(tokens)
            if first.type == "NAME" and second.type == "COLON":
                lhs, arrow = next(tokens), next(tokens)
                if lhs.type != "NAME" or arrow.type != "ARROW":
                    return self.parse_error(line, arrow)
                self.rule_line(first, lhs, _rule_symbols(tokens, self, line))
            elif first.type == "LPAR":
                self.tuple_line(first, _tuple_entries(second, tokens, self, line))
            else:
                return True
        except lark.exceptions.UnexpectedInput as exc:  # a character no token starts with
            # the character and the next: a '\r' cut from its '\n' would read as a line break
            return self.parse_error(line, None, exc.pos_in_stream + 2)
        except (StopIteration, _Unparsed):  # a blank line; or what the parser reads otherwise
            return True
        return False

    def parse_error(self, line: str, token, end: int | None = None) -> bool:
        """Parse ``line`` up to ``token`` (or character ``end``): the parser's own error there.
        True when that part parses (no error to raise: read the whole line as a chunk)."""
        part = line[:token.end_pos if token is not None else end]
        _parse(part if part.endswith("\n") else part + "\n", self.offset, self.source)
        return True

    def finish(self) -> PSGS | PCGS:
        if self.kind is None:
            raise self.error("empty file: expected a first line 'psgs NAME' or 'pcgs NAME'",
                             (1, 1))
        if not self.components:
            raise self.error(f"a {self.kind} needs at least one 'component NAME start SYMBOL' "
                             f"line", self.header_at)
        return self.system()

    def words_line(self, words: list[lark.Token]) -> None:
        first = words[0]
        at = self.at(first)
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
        at = self.at(words[0])
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
                             self.at(words[1]))
        self.settings[key] = (value, self.at(words[1]))

    def component_line(self, words: list[lark.Token]) -> None:
        at = self.at(words[0])
        if self.sync_at is not None:
            raise self.error("components must come before the 'sync' section", at)
        if len(words) != 4 or str(words[2]) != "start":
            raise self.error("write a component as 'component NAME start SYMBOL'", at)
        name = str(words[1])
        other = self.component_named.get(name)
        if other is not None:
            raise self.error(f"a second component named {name} (the first is on line "
                             f"{other.at[0]})", self.at(words[1]))
        start = Nonterminal(str(words[3]))
        self.note_kind(start.name, "nonterminal", self.at(words[3]))
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

    def rule_line(self, label_token: lark.Token, lhs_token: lark.Token, symbols) -> None:
        at = self.at(label_token)
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
        self.note_kind(lhs.name, "nonterminal", self.at(lhs_token))
        rhs = self.right_side(symbols)
        rule = Rule(label, lhs, rhs)
        other = component.bodies.setdefault((rule.lhs, rule.rhs), rule)
        if other is not rule:
            raise self.error(f"component {component.name}: rule {label} repeats rule "
                             f"{other.label} ({other})", at)
        component.rules.append(rule)
        component.rule_at[label] = at

    def right_side(self, symbols) -> tuple:
        rhs = []
        epsilon = None  # where an ε stands, which must stand alone
        for token in symbols:  # a list, or tokens as the lexer makes them
            at = self.at(token)
            if epsilon is not None or (token.type == "EPSILON" and rhs):
                raise self.error("ε stands alone: write it as the whole right side, or leave "
                                 "the right side empty", epsilon or at)
            if token.type == "EPSILON":
                epsilon = at
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
        at = self.at(token)
        try:
            text = json.loads(str(token))
        except json.JSONDecodeError as exc:
            # a raw control character is the one reading outside quotes rejects, told the same
            # way at its own column: echoed, it broke the line (json's message ends "at")
            if exc.msg.startswith("Invalid control character"):
                raise self.error(f"unexpected character {_character(str(token)[exc.pos])} "
                                 f"(control characters and binary data are not allowed)",
                                 (at[0], at[1] + exc.pos)) from None
            shown = "".join(c if c.isprintable() else repr(c)[1:-1] for c in str(token))
            raise self.error(f"bad terminal {shown}{_hidden(str(token))}: {exc.msg}",
                             at) from None
        try:
            terminal = Terminal(text)
        except ValidationError as exc:
            # at the character at fault (written as it is or as an escape), not at the quote
            bad = first_unseen(text)
            where = at if bad is None else (at[0], at[1] + _raw_offset(str(token), bad))
            raise self.error(str(exc), where) from None
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

    def tuple_line(self, parenthesis: lark.Token, entries) -> None:
        at = self.at(parenthesis)
        if self.kind is None:
            raise self.error("expected a first line 'psgs NAME' or 'pcgs NAME'", at)
        if self.sync_at is None:
            raise self.error("a tuple outside the 'sync' section: write 'sync' on the line "
                             "before the tuples", at)
        labels, columns = [], array("q", [at[1]])
        for token in entries:  # a list, or tokens as the lexer makes them
            labels.append(None if token.type == "IDLE"
                          else self.labels.setdefault(str(token), str(token)))
            columns.append(token.column)
        self.tuples.append((tuple(labels), at[0], columns))

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
        for entries, line, columns in self.tuples:
            at = (line, columns[0])
            if len(entries) != len(grammars):
                raise self.error(f"this tuple has {_count(len(entries), 'entry', 'entries')} but "
                                 f"the system has {_count(len(grammars), 'component')} "
                                 f"({', '.join(g.name for g in grammars)})", at)
            resolved = []
            for grammar, label, column in zip(grammars, entries, columns[1:]):
                if label is None:
                    resolved.append(IDLE)
                elif label in grammar.rule_by_label:
                    resolved.append(grammar.rule_by_label[label])
                else:
                    raise self.error(f"component {grammar.name} has no rule labelled {label}",
                                     (line, column))
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


def _rule_symbols(tokens, builder: _Builder, line: str):
    """The right side's tokens of a long rule line, up to its line break; a token a right
    side cannot hold raises the parser's error at it."""
    for token in tokens:
        if token.type == "_NL":
            return
        if token.type not in ("NAME", "STRING", "QUERY", "EPSILON"):
            builder.parse_error(line, token)
            raise _Unparsed
        yield token


def _tuple_entries(first: lark.Token, tokens, builder: _Builder, line: str):
    """The entries of a long tuple line, ``(entry, entry, ...)`` and its line break."""
    token, expected = first, ("NAME", "IDLE")
    while True:
        if token.type not in expected:
            builder.parse_error(line, token)
            raise _Unparsed
        if token.type in ("NAME", "IDLE"):
            yield token
            expected = ("COMMA", "RPAR")
        elif token.type == "COMMA":
            expected = ("NAME", "IDLE")
        elif token.type == "RPAR":
            expected = ("_NL",)
        else:
            return
        token = next(tokens, None)
        if token is None:  # pragma: no cover - every line ends with _NL
            raise _Unparsed


class _Unparsed(Exception):
    """A long line the parser reads without error up to the token the shortcut refused."""


# ---------------------------------------------------------------- writing
