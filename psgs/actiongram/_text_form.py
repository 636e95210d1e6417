"""The text form of an actiongram, read and written (:meth:`psgs.Actiongram.from_text`,
:meth:`psgs.Actiongram.to_text`).

One line per string, ``name[@T]: sym sym@D sym@D~X ...``; ``%`` directive lines for the
extras and for ``%keep_repeats``; ``#`` comments. The grammar is in the docstring of
:mod:`psgs.actiongram` and in docs/actiongram.md.
"""

from __future__ import annotations

import itertools
import re

from .._foundation.text import character_name, split_lines
from ..errors import FormatError, ValidationError
from ._checks import _bad_name, _format_number, _read_number, _shown
from ._extras import DIRECTIVE as _DIRECTIVE
from ._extras import default_actuator
from ._extras import read_directive as _read_directive
from ._faults import first_fault, first_refused, strings_of

__all__: list[str] = []  # private: Actiongram.from_text and to_text are the interface

#: the directive line that keeps equal neighbours apart (``Actiongram.keep_repeats``)
KEEP_REPEATS = "%keep_repeats"

_COMMENT = re.compile(r"(?:^|\s)#")
_TOKEN = re.compile(r"\S+")


def strip_comment(line: str, source: str, line_no: int) -> str:
    """``line`` without its comment.

    A line whose first non-blank character is ``#`` is a comment; elsewhere a comment starts
    at a ``#`` after white space that is followed by white space or ends the line. A token
    that starts with ``#`` and goes on (``1 #4 5``) is neither a symbol (none starts with
    ``#``) nor a comment, so it is an error at its place rather than a silent cut.
    """
    match = _COMMENT.search(line)
    if match is None:
        return line
    at = match.end() - 1  # the '#'
    if not line[:at].strip():
        return ""
    after = line[at + 1:at + 2]
    if after and not after.isspace():
        token = line[at:].split(None, 1)[0]
        raise FormatError(f"{_shown(token)} starts with '#': a symbol cannot, and a comment "
                          f"needs white space after its '#' ('# note')", source=source,
                          line=line_no, column=at + 1)
    return line[:at]


# every control character but the tab, and the characters str.splitlines breaks lines at
# (lines break at "\n" only, so an error names the line an editor shows)
_CONTROL = re.compile("[\x00-\x08\x0b-\x1f\x7f\x85\u2028\u2029]")


def read_text(cls, text: str, source: str):
    """The actiongram (of class ``cls``) that ``text`` holds; FormatError at its place."""
    if not isinstance(text, str):
        raise ValidationError(f"from_text reads a str, not {type(text).__name__}")
    names, symbol_rows, duration_rows, origins = [], [], [], []
    disp_rows: list[tuple[float, ...] | None] = []
    owner: dict[str, str] = {}
    edges: list[tuple[str, str | None]] = []
    where: dict[str, int] = {}
    # (line, column) of each string, each %parent edge and each %actuator entry, in order
    string_places: list[tuple[int, int]] = []
    edge_places: list[tuple[int, int]] = []
    owner_places: list[tuple[int, int]] = []
    keep_repeats = False
    for line_no, raw in enumerate(split_lines(text), start=1):
        line = strip_comment(raw, source, line_no)
        control = _CONTROL.search(line)
        if control:  # no symbol or name may hold one (a NUL would reach the grammar unseen)
            raise FormatError(f"control character {character_name(control.group())} in the text",
                              source=source, line=line_no, column=control.start() + 1)
        if not line.strip():
            continue
        if line.strip() == KEEP_REPEATS:
            keep_repeats = True
            continue
        if _DIRECTIVE.match(line):
            counts = len(owner), len(edges)
            _read_directive(line, source, line_no, owner, edges)
            place = (line_no, len(line) - len(line.lstrip()) + 1)
            owner_places.extend([place] * (len(owner) - counts[0]))
            edge_places.extend([place] * (len(edges) - counts[1]))
            continue
        head, colon, body = line.partition(":")
        if not colon:
            col = len(raw) - len(raw.lstrip()) + 1
            raise FormatError("expected 'name: symbols' (no ':' on this line)",
                              source=source, line=line_no, column=col)
        name_col = len(head) - len(head.lstrip()) + 1
        name_text = head.strip()
        name, at, origin_text = name_text.partition("@")
        origin = 0.0
        if at:
            origin = _read_number(origin_text, allow_nonpositive=True)
            if origin is None:
                raise FormatError(f"start time {_shown(origin_text)} is not a number",
                                  source=source, line=line_no,
                                  column=name_col + len(name) + 1)
        problem = _bad_name(name)
        if problem:
            raise FormatError(problem, source=source, line=line_no, column=name_col)
        if name in where:
            raise FormatError(f"actuator {_shown(name)} already given on line {where[name]}",
                              source=source, line=line_no, column=name_col)
        where[name] = line_no
        string_places.append((line_no, name_col))
        syms, durs, disps = [], [], []
        offset = len(head) + 1
        for match in _TOKEN.finditer(body):
            token, col = match.group(), offset + match.start() + 1
            sym, at, dur_text = token.partition("@")
            if ":" in token:
                raise FormatError(f"symbol {_shown(token)} contains ':'", source=source,
                                  line=line_no, column=col)
            if not sym:
                raise FormatError(f"{_shown(token)} has a duration but no symbol",
                                  source=source,
                                  line=line_no, column=col)
            dur = 1.0
            if at and "~" in dur_text:  # sym@D~X: a duration, then a signed displacement
                dur_text, _, disp_text = dur_text.partition("~")
                disp = _read_number(disp_text, allow_nonpositive=True)
                if disp is None:
                    raise FormatError(
                        f"unknown displacement syntax {_shown('~' + disp_text)} (write "
                        f"sym@D~X with X a number)", source=source, line=line_no,
                        column=col + len(sym) + 1 + len(dur_text))
                disps.append(disp)
            if at:
                dur = _read_number(dur_text, allow_nonpositive=True)
                if dur is not None and dur <= 0:
                    raise FormatError(f"duration {_shown(dur_text)} must be positive",
                                      source=source, line=line_no, column=col + len(sym) + 1)
                if dur is None:
                    raise FormatError(
                        f"unknown duration syntax {_shown('@' + dur_text)} (write sym@D "
                        f"with D a positive number)", source=source, line=line_no,
                        column=col + len(sym))
            syms.append(sym)
            durs.append(dur)
            if len(disps) not in (0, len(syms)):
                raise FormatError("give a displacement (sym@D~X) for every symbol of a "
                                  "string or for none", source=source, line=line_no,
                                  column=col)
        names.append(name)
        symbol_rows.append(tuple(syms))
        duration_rows.append(tuple(durs))
        origins.append(origin)
        disp_rows.append(tuple(disps) if disps else None)
    for name, (line_no, column) in zip(owner, owner_places):
        if name not in where:
            raise FormatError(f"%actuator names unknown string {_shown(name)}",
                              source=source, line=line_no, column=column)
    actuators = tuple(owner.get(n, default_actuator(n)) for n in names)

    def build(strings: slice, skeleton: int):
        """The actiongram of the ``strings`` and the first ``skeleton`` parent lines."""
        return cls(tuple(names[strings]), tuple(symbol_rows[strings]),
                   tuple(duration_rows[strings]), tuple(origins[strings]),
                   tuple(disp_rows[strings]), actuators[strings], tuple(edges[:skeleton]),
                   keep_repeats)

    try:
        return build(slice(None), len(edges))
    except FormatError as exc:  # found by the checks of the whole value, which name no line
        strings = strings_of(names, symbol_rows, duration_rows, origins, keep_repeats,
                             disp_rows, actuators)
        raise _placed(exc, strings, lambda k: build(slice(0), k), text, source,
                      string_places, edge_places) from None


def _placed(error: FormatError, strings, build_skeleton, text: str, source: str,
            string_places: list[tuple[int, int]],
            edge_places: list[tuple[int, int]]) -> FormatError:
    """``error``, the whole actiongram's, at the place of its fault.

    A string's fault is the first that the constructor's checks find
    (:func:`~psgs.actiongram._faults.first_fault` over ``strings``, as read): at the token of
    the symbol it names (a refused symbol, the first symbol of a segment whose duration
    vanishes beside its start time), else at the string's name. The skeleton's entries are
    read together (a cycle takes several), so the ``%parent`` line at fault ends the shortest
    run of them that ``build_skeleton`` refuses.
    """
    found = first_fault(strings)
    if found is not None and found[1].message == error.message:
        k, fault = found
        line, column = string_places[k]
        field = fault.fields[0]
        if len(field) == 2:  # ("symbols", j), ("durations", j): the j-th token's
            column = _token_column(text, source, line, field[1])
        return FormatError(error.message, source=source, line=line, column=column)
    refused = first_refused(len(edge_places), build_skeleton)
    if refused is None:  # (not met) no string's fault, no %parent line's: the file as a whole
        return FormatError(error.message, source=source)
    k, error = refused
    line, column = edge_places[k - 1]
    return FormatError(error.message, source=source, line=line, column=column)


def _token_column(text: str, source: str, line_no: int, j: int) -> int:
    """The column of the ``j``-th token after the name on line ``line_no`` of ``text``.

    The columns of the symbols are not kept while reading (one number per symbol of a large
    file): the line is split again, here, on the error's way out.
    """
    line = strip_comment(split_lines(text)[line_no - 1], source, line_no)
    head = line.partition(":")[0]
    token = next(itertools.islice(_TOKEN.finditer(line, len(head) + 1), j, None))
    return token.start() + 1


def write_text(actiongram) -> str:
    """The text form of ``actiongram``, which :func:`read_text` reads back to an equal value."""
    ag = actiongram
    lines = [KEEP_REPEATS] if ag.keep_repeats else []
    for name, syms, durs, origin, disps in zip(ag.names, ag.symbols, ag.segment_durations,
                                               ag.origins, ag.segment_displacements):
        head = name if origin == 0 else f"{name}@{_format_number(origin)}"
        if disps is None:
            tokens = [s if d == 1 else f"{s}@{_format_number(d)}" for s, d in zip(syms, durs)]
        else:
            tokens = [f"{s}@{_format_number(d)}~{_format_number(x)}"
                      for s, d, x in zip(syms, durs, disps)]
        lines.append(f"{head}: {' '.join(tokens)}".rstrip())
    groups: dict[str, list[str]] = {}  # only assignments that differ from the default
    for name, actuator in zip(ag.names, ag.string_actuators):
        if actuator != default_actuator(name):
            groups.setdefault(actuator, []).append(name)
    lines.extend(f"%actuator {a}: {' '.join(ns)}" for a, ns in groups.items())
    lines.extend(f"%parent {c}: {p}" if p is not None else f"%parent {c}:"
                 for c, p in ag.skeleton_edges)
    return "\n".join(lines) + "\n"


