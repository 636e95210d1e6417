"""Actiongrams: parallel, timed symbol strings, one per actuator.

An :class:`Actiongram` holds n named strings. Symbol ``j`` of string ``i``
has a start time ``T_i(j)`` and a duration ``D_i(j) > 0`` with
``T_i(j) + D_i(j) = T_i(j + 1)``; each string starts at its own start time
(0 unless given). Strings may differ in length.

Adjacent equal symbols are one segment: when a string is built with two equal
neighbours they are merged into one symbol whose duration is the sum of
theirs, so ``A_i(j) != A_i(j + 1)`` holds, as the paper requires. An actiongram
built with ``keep_repeats=True`` keeps them apart instead (a re-struck note
``C C D`` stays three segments); the flag is part of the value and of both file
forms (``%keep_repeats`` in the text form).

The plain-text form, one actuator per line::

    # a comment line
    lknee: B G R Y B@3 G@2.5
    rknee@10: Y B G        # this string starts at time 10

``sym@D`` gives a duration (default 1). Symbols are non-space tokens without
``@`` or ``:`` and not starting with ``#``; actuator names likewise, also
without white space. A comment is a line whose first non-blank character is
``#``, or the rest of a line from a ``#`` that follows white space and is
followed by white space (or ends the line); a token such as ``#4`` on a string
line is an error at its place, never a silent cut. Bad input raises
:class:`~psgs.errors.FormatError` naming ``source:line:column``.

Three optional extras, which whoever makes the actiongram supplies (kinetology
gives them from motion capture: its joints are the actuators); all are absent in
older files, which still read:

- a **displacement** per symbol, the signed change of the measured quantity over
  the segment, written ``sym@D~X``: ``B@0.5~12.25``;
- an **actuator map**, string name -> actuator (the group it belongs to); by
  default the part of the name before the first dot (``arm.x`` -> ``arm``), a
  name without a dot its own actuator; other assignments are written
  ``%actuator arm: arm.x arm.y``;
- a **skeleton**, actuator -> parent actuator (none for a root), written
  ``%parent arm: body`` and ``%parent body:`` for a root.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

from .._foundation.files import read_text
from ..errors import FormatError, NotFound, ValidationError
from ._checks import _names_of, _refused, _shown, _tuple_of
from ._events import GAPS
from ._extras import default_actuator, normalise_extras
from ._faults import STRING_CHECKS, refuse, strings_of

__all__ = ["Actiongram", "GAPS", "default_actuator", "read_events_csv"]


@dataclass(frozen=True)
class Actiongram:
    """Named, timed symbol strings, one per actuator (immutable).

    Build one with :meth:`from_strings`, :meth:`from_events`, :meth:`from_text`, :meth:`from_json`
    or ``psgs.load(path, kind="actiongram")``. The constructor takes the normalised fields
    (``names``, ``symbols``, ``durations`` as tuples of tuples, ``origins`` the
    start time of each string) and validates and normalises them.

    Parameters
    ----------
    names : tuple of str
        The actuators' names, distinct.
    symbols : tuple of tuple of str
        Each actuator's symbol string (no symbol twice in a row).
    segment_durations : tuple of tuple of float
        Each symbol's duration, positive. Every duration, start time and displacement may be
        any real number (an int, a float, a Fraction, numpy's integer and floating scalars),
        kept as the float of its value.
    origins : tuple of float, default () (every string starts at 0)
        The start time of each string.
    segment_displacements : tuple, default ()
        Per string, each symbol's displacement (``sym@D~X`` in the text form), or None for a
        string without them; () when no string has them.
    string_actuators : tuple of str, default () (each string its own actuator)
        The actuator (group) each string belongs to.
    skeleton_edges : tuple of (str, str or None), default ()
        Actuator to parent actuator (None for a root), where a skeleton is known.
    keep_repeats : bool, default False
        Keep equal neighbours as separate segments instead of merging them.

    Raises
    ------
    FormatError
        For an empty or repeated name, a symbol that is not text, a duration that is not
        positive and finite, or strings and durations of different lengths. Its source is
        ``"Actiongram"``: no file is at fault (the readers name theirs, with the place).
    ValidationError
        For a field that is no sequence (``names`` or ``string_actuators`` a bare ``str``),
        or has not one entry per string.

    Examples
    --------
    >>> ag = Actiongram.from_strings({"knee": "abba", "hip": ["x", "y"]})
    >>> ag.string("knee"), ag.durations["knee"]
    (('a', 'b', 'a'), (1.0, 2.0, 1.0))
    >>> ag.starts["knee"]
    (0.0, 1.0, 3.0)
    """

    names: tuple[str, ...]
    symbols: tuple[tuple[str, ...], ...]
    segment_durations: tuple[tuple[float, ...], ...]
    origins: tuple[float, ...] = ()
    #: per string, one signed displacement per symbol, or None (unknown); () = all unknown
    segment_displacements: tuple[tuple[float, ...] | None, ...] = ()
    #: per string, the actuator (group) it belongs to; () = :func:`default_actuator` of each
    string_actuators: tuple[str, ...] = ()
    #: ``(actuator, parent or None)`` pairs, in the maker's order; () = no skeleton known
    skeleton_edges: tuple[tuple[str, str | None], ...] = ()
    #: True: equal neighbours stay separate segments (a re-struck note), False: they merge
    keep_repeats: bool = False

    def __post_init__(self) -> None:
        names = _names_of(self.names, "names")
        symbols = _tuple_of(self.symbols, "symbols", rows=True)
        durations = _tuple_of(self.segment_durations, "segment_durations", rows=True)
        origins = _tuple_of(self.origins, "origins") if self.origins else (0.0,) * len(names)
        if not (len(names) == len(symbols) == len(durations) == len(origins)):
            raise ValidationError("names, symbols, durations and origins must have one entry "
                                  "per string")
        if not isinstance(self.keep_repeats, bool):
            raise _refused(f"keep_repeats must be True or False, not {_shown(self.keep_repeats)}")
        strings = strings_of(names, symbols, durations, origins, self.keep_repeats)
        # the first fault of the strings' checks, found in the order the readers place it by
        refuse(strings, STRING_CHECKS)
        segments = [s.segments for s in strings]
        object.__setattr__(self, "names", names)
        object.__setattr__(self, "symbols", tuple(s for s, _ in segments))
        object.__setattr__(self, "segment_durations", tuple(d for _, d in segments))
        object.__setattr__(self, "origins", tuple(float(o) for o in origins))
        normalise_extras(self, strings)  # after the names are checked; needs unmerged symbols

    # -- construction ------------------------------------------------------
    @classmethod
    def from_strings(cls, strings: Mapping[str, Iterable[str] | str],
                     durations: Mapping[str, Iterable[float]] | None = None,
                     starts: Mapping[str, float] | None = None, *,
                     displacements: Mapping[str, Iterable[float]] | None = None,
                     actuators: Mapping[str, str] | None = None,
                     skeleton: Mapping[str, str | None] | None = None,
                     keep_repeats: bool = False) -> "Actiongram":
        """Build from ``{name: symbols}`` (a ``str`` is read one character per symbol).

        ``durations`` maps a name to one duration per symbol (default 1 each);
        ``starts`` maps a name to the start time of its string (default 0).
        Adjacent equal symbols are merged, their durations added (and their
        displacements), unless ``keep_repeats``. ``displacements`` maps a name to one signed change per
        symbol (a string left out: unknown); ``actuators`` maps a name to its
        actuator (default :func:`default_actuator`); ``skeleton`` maps an
        actuator to its parent (None for a root).

        >>> ag = Actiongram.from_strings({"lhumerus.rx": "BGG", "lhumerus.rz": "Y"},
        ...                              displacements={"lhumerus.rx": [4, -1, -2.5]},
        ...                              skeleton={"lhumerus": "lclavicle", "lclavicle": None})
        >>> ag.displacements("lhumerus.rx"), ag.displacements("lhumerus.rz")
        ((4.0, -3.5), None)
        >>> ag.actuators, ag.channels("lhumerus"), ag.parent("lhumerus")
        (('lhumerus',), ('lhumerus.rx', 'lhumerus.rz'), 'lclavicle')
        """
        durations = durations or {}
        starts = starts or {}
        displacements = displacements or {}
        actuators = actuators or {}
        for what, given in (("strings", strings), ("durations", durations), ("starts", starts),
                            ("displacements", displacements), ("actuators", actuators),
                            ("skeleton", skeleton or {})):
            if not isinstance(given, Mapping):  # a list of strings has no names to give them
                raise ValidationError(f"{what} must map each string's name to its values, "
                                      f"not be a {type(given).__name__}")
        for extra in (*durations, *starts):  # in the order given: the same error every run
            if extra not in strings:
                raise _refused(f"durations or starts given for unknown string "
                                  f"{_shown(extra)}")
        for extra in (*displacements, *actuators):
            if extra not in strings:
                raise _refused(f"displacements or actuators given for unknown string "
                                  f"{_shown(extra)}")
        names, symbol_rows, duration_rows, origins = [], [], [], []
        for name, syms in strings.items():
            syms = _tuple_of(syms, f"strings[{_shown(name)}]")
            durs = _tuple_of(durations[name], f"durations[{_shown(name)}]") \
                if name in durations else (1.0,) * len(syms)
            names.append(name)
            symbol_rows.append(syms)
            duration_rows.append(durs)
            origins.append(starts.get(name, 0.0))
        disp_rows = tuple(_tuple_of(displacements[n], f"displacements[{_shown(n)}]")
                          if n in displacements else None for n in names)
        owner = tuple(actuators[n] if n in actuators else default_actuator(n)
                      if isinstance(n, str) else n for n in names)
        edges = tuple((skeleton or {}).items())
        return cls(tuple(names), tuple(symbol_rows), tuple(duration_rows), tuple(origins),
                   disp_rows, owner, edges, keep_repeats)

    @classmethod
    def from_codes(cls, codes: Mapping[str, Sequence[int]], alphabet: Sequence[str],
                   durations: Mapping[str, Sequence[float]] | None = None, *,
                   displacements: Mapping[str, Sequence[float]] | None = None,
                   actuators: Mapping[str, str] | None = None,
                   skeleton: Mapping[str, str | None] | None = None) -> "Actiongram":
        """Build from integer codes into ``alphabet`` and arrays, fast: equal to
        ``from_strings({n: [alphabet[k] for k in codes[n]]}, durations, ...)``.

        The checks run on whole arrays (what a segmentation of long takes needs); input that
        fails one, or has equal neighbours to merge, takes :meth:`from_strings`, so the errors
        and results are its own. Every string starts at 0.

        Parameters
        ----------
        codes : mapping of str to array_like of int
            Each string's symbols as indices into ``alphabet``.
        alphabet : sequence of str
            The symbols.
        durations, displacements, actuators, skeleton : mapping, optional
            As for :meth:`from_strings` (arrays welcome).

        Returns
        -------
        Actiongram

        Raises
        ------
        ValidationError
            For codes that are not 1-D integers within the alphabet, or an argument of the
            wrong kind (a mapping expected).
        FormatError
            As :meth:`from_strings` (and for a symbol of the alphabet that cannot be one).

        Examples
        --------
        >>> ag = Actiongram.from_codes({"knee.rx": [0, 1, 0]}, "BG", {"knee.rx": [0.5, 1, 2]})
        >>> ag == Actiongram.from_strings({"knee.rx": "BGB"}, {"knee.rx": [0.5, 1, 2]})
        True
        """
        from ._fast import build

        return build(cls, codes, alphabet, durations, displacements, actuators, skeleton)

    @classmethod
    def from_events(cls, rows, *, gaps: str = "rest", rest_symbol: str = "_",
                    keep_repeats: bool = False,
                    columns: Mapping[str, str] | None = None) -> "Actiongram":
        """Build from an events table: rows of ``(stream, onset, duration, symbol)``.

        Rows may come in any order; each stream's events are put in onset order and its string
        starts at its first onset. Events that meet (within a relative 1e-9, so ``0.1 + 0.2``
        meets ``0.3``) keep their durations. Every instant of a string holds one symbol, so a
        gap between two events of a stream becomes, by ``gaps``:

        - ``"rest"`` (default): a segment of ``rest_symbol`` lasting the gap (silence is a
          symbol of its own; every onset and every end keeps its time);
        - ``"hold"``: the event before lasts until the next onset (onsets keep their times);
        - ``"error"``: a :class:`~psgs.errors.ValidationError`.

        Parameters
        ----------
        rows : iterable of sequence or mapping, or pandas.DataFrame
            ``(stream, onset, duration, symbol)`` tuples, mappings with those keys, or a
            DataFrame with those columns. A stream or symbol is text (a valid name or symbol
            of the text form) or an integer, written in decimal; onsets are 0 or more,
            durations positive, both finite.
        gaps : {"rest", "hold", "error"}, default "rest"
            What a gap between two events of a stream becomes (above).
        rest_symbol : str, default "_"
            The symbol of a gap under ``gaps="rest"``.
        keep_repeats : bool, default False
            Keep equal neighbours (a re-struck note ``C C``) as separate segments; by default
            they merge into one.
        columns : mapping of str to str, optional
            Your key or column name for each of ``stream``, ``onset``, ``duration``,
            ``symbol`` (``{"stream": "voice", "symbol": "pitch"}``); a key that is none of
            these, or two fields given one column, is a ValidationError.

        Returns
        -------
        Actiongram
            One string per stream, in the order of each stream's first row.

        Raises
        ------
        ValidationError
            For no rows, a missing key or column, or a bad row, naming the row (its index, the
            DataFrame's index label): a negative or non-finite onset, a duration that is not
            positive and finite, a symbol the text form cannot hold, two events of one stream
            that overlap, a gap under ``gaps="error"``.

        Examples
        --------
        >>> rows = [("alto", 0, 2, "E4"), ("bass", 1, 1, "C3"), ("bass", 3, 1, "C3"),
        ...         ("alto", 2, 1, "E4"), ("bass", 2, 1, "G2")]
        >>> ag = Actiongram.from_events(rows)
        >>> ag.strings, ag.starts["bass"]
        ({'alto': ('E4',), 'bass': ('C3', 'G2', 'C3')}, (1.0, 2.0, 3.0))
        >>> Actiongram.from_events(rows, keep_repeats=True).string("alto")
        ('E4', 'E4')
        >>> Actiongram.from_events([("s", 0, 1, "a"), ("s", 2, 1, "b")]).durations
        {'s': (1.0, 1.0, 1.0)}
        >>> Actiongram.from_events([("s", 0, 1, "a"), ("s", 2, 1, "b")], gaps="hold").durations
        {'s': (2.0, 1.0)}
        >>> Actiongram.from_events([("s", 0, 2, "a"), ("s", 1, 1, "b")])
        Traceback (most recent call last):
        ...
        psgs.errors.ValidationError: row 1: overlaps row 0 in stream 's' (row 0 lasts from 0 to 2, this one starts at 1)
        """
        from ._events import from_events

        return from_events(cls, rows, gaps=gaps, rest_symbol=rest_symbol,
                           keep_repeats=keep_repeats, columns=columns)

    def to_events(self, rest_symbol: str | None = None) -> tuple[tuple[str, float, float, str],
                                                                  ...]:
        """The events table: one ``(stream, onset, duration, symbol)`` per segment.

        ``Actiongram.from_events(ag.to_events(), keep_repeats=ag.keep_repeats)`` is ``ag``.
        Segments of ``rest_symbol`` are left out when it is given: the table without its
        gaps, which :meth:`from_events` turns back into rests.

        >>> ag = Actiongram.from_events([("s", 0, 1, "a"), ("s", 2, 0.5, "b")])
        >>> ag.to_events(rest_symbol="_")
        (('s', 0.0, 1.0, 'a'), ('s', 2.0, 0.5, 'b'))
        """
        from ._events import to_events

        return to_events(self, rest_symbol)

    @classmethod
    def from_text(cls, text: str, source: str = "<string>") -> "Actiongram":
        """Read the plain-text form (see the module docstring)."""
        from ._text_form import read_text

        return read_text(cls, text, source)

    @classmethod
    def from_json(cls, text: str, source: str = "<string>") -> "Actiongram":
        """Read the JSON form written by :meth:`to_json`.

        Raises
        ------
        FormatError
            Text that is not JSON, or JSON this format cannot hold, at its line and column.
        """
        from ._json_form import read_json

        return read_json(cls, text, source)

    # -- output ------------------------------------------------------------
    def to_text(self) -> str:
        """The plain-text form; :meth:`from_text` reads it back to an equal value."""
        from ._text_form import write_text

        return write_text(self)

    def to_json(self) -> str:
        """A JSON document; :meth:`from_json` reads it back to an equal value."""
        from ._json_form import write_json

        return write_json(self)

    # -- accessors ---------------------------------------------------------
    def __len__(self) -> int:
        """The number of strings (actuators)."""
        return len(self.names)

    @property
    def strings(self) -> dict[str, tuple[str, ...]]:
        """``{name: symbols}`` in actiongram order."""
        return dict(zip(self.names, self.symbols))

    @property
    def durations(self) -> dict[str, tuple[float, ...]]:
        """``{name: durations}``, one per symbol."""
        return dict(zip(self.names, self.segment_durations))

    @property
    def starts(self) -> dict[str, tuple[float, ...]]:
        """``{name: start times}``: T_i(j), with T_i(j) + D_i(j) = T_i(j + 1)."""
        out = {}
        for name, durs, origin in zip(self.names, self.segment_durations, self.origins):
            times, t = [], origin
            for d in durs:
                times.append(t)
                t += d
            out[name] = tuple(times)
        return out

    @property
    def total_symbols(self) -> int:
        """The number of symbols over all strings."""
        return sum(len(s) for s in self.symbols)

    def index(self, name: str) -> int:
        """The position of the string named ``name``."""
        try:
            return self.names.index(name)
        except ValueError:
            raise NotFound(f"no string named {_shown(name)}") from None

    def string(self, name: str) -> tuple[str, ...]:
        """The symbols of string ``name``."""
        return self.symbols[self.index(name)]

    def subset(self, names: Iterable[str]) -> "Actiongram":
        """The actiongram of the named strings only, in the order given (skeleton kept whole).

        ``names`` is a sequence of names: a bare ``str`` is a ValidationError, not the names
        of its characters.

        >>> ag = Actiongram.from_strings({"a": "x", "b": "y", "ab": "z"})
        >>> ag.subset(["ab", "a"]).names
        ('ab', 'a')
        >>> ag.subset("ab")
        Traceback (most recent call last):
        ...
        psgs.errors.ValidationError: names must be a sequence of string names, not a str ('ab'); one name is given as ['ab']
        """
        picks = [self.index(n) for n in _names_of(names, "names")]
        return Actiongram(tuple(self.names[i] for i in picks),
                          tuple(self.symbols[i] for i in picks),
                          tuple(self.segment_durations[i] for i in picks),
                          tuple(self.origins[i] for i in picks),
                          tuple(self.segment_displacements[i] for i in picks) or (),
                          tuple(self.string_actuators[i] for i in picks) or (),
                          self.skeleton_edges, self.keep_repeats)

    def displacements(self, name: str) -> tuple[float, ...] | None:
        """The signed displacement of each symbol of string ``name``, or None when unknown."""
        return self.segment_displacements[self.index(name)]

    def actuator(self, name: str) -> str:
        """The actuator (group) string ``name`` belongs to."""
        return self.string_actuators[self.index(name)]

    @property
    def actuator_map(self) -> dict[str, str]:
        """``{string name: actuator}`` in actiongram order."""
        return dict(zip(self.names, self.string_actuators))

    @property
    def actuators(self) -> tuple[str, ...]:
        """The distinct actuators, in the order of their first string."""
        return tuple(dict.fromkeys(self.string_actuators))

    def channels(self, actuator: str) -> tuple[str, ...]:
        """The strings of ``actuator``, in actiongram order (empty if it has none)."""
        return tuple(n for n, a in zip(self.names, self.string_actuators) if a == actuator)

    @property
    def skeleton(self) -> dict[str, str | None]:
        """``{actuator: parent or None}``; empty when the skeleton is unknown."""
        return dict(self.skeleton_edges)

    def parent(self, actuator: str) -> str | None:
        """The parent of ``actuator`` in the skeleton (None for a root or an unknown actuator)."""
        return next((p for c, p in self.skeleton_edges if c == actuator), None)

    def neighbours(self, actuator: str) -> tuple[str, ...]:
        """The skeleton neighbours of ``actuator`` (its parent, then its children), one hop."""
        edges = self.skeleton_edges
        parent = [p for c, p in edges if c == actuator and p is not None]
        return tuple(parent + [c for c, p in edges if p == actuator])

    def __repr__(self) -> str:
        return f"<Actiongram {len(self)} strings, {self.total_symbols} symbols>"


def read_events_csv(path: str | Path, *, gaps: str = "rest", rest_symbol: str = "_",
                    keep_repeats: bool = False) -> Actiongram:
    """Read a CSV events file as :meth:`Actiongram.from_events` reads rows (what
    ``psgs induce --events`` does).

    Parameters
    ----------
    path : str or Path
        A UTF-8 CSV file whose header row names the columns ``stream``, ``onset``,
        ``duration`` and ``symbol`` (in any order; other columns are ignored), then one row
        per event, in any order. Blank rows are skipped.
    gaps, rest_symbol, keep_repeats
        As for :meth:`Actiongram.from_events`.

    Returns
    -------
    Actiongram

    Raises
    ------
    FormatError
        Naming the file, the line and the column of the cell at fault (a row's end for what
        it lacks): a missing column, a number that is not one, a row of too few cells, no
        rows, or any bad row that :meth:`Actiongram.from_events` refuses.
    ValidationError
        For a bad ``gaps`` or ``rest_symbol``.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> path = Path(tempfile.mkdtemp()) / "song.csv"
    >>> _ = path.write_text("stream,onset,duration,symbol\\nbass,0,1,C2\\nbass,2,1,G2\\n")
    >>> read_events_csv(path).strings
    {'bass': ('C2', '_', 'G2')}
    """
    from ._events import read_csv

    return read_csv(Actiongram, path, gaps=gaps, rest_symbol=rest_symbol,
                    keep_repeats=keep_repeats)


def _read_file(path: str | Path) -> Actiongram:
    """Read an actiongram file (``psgs.load``'s reader of them): JSON when the name ends in
    ``.json``, else the text form.

    A file that is not UTF-8 text, or that holds no string at all, is a
    :class:`~psgs.errors.FormatError` (an empty actiongram is almost always
    the wrong file; build one in Python with ``Actiongram.from_strings({})``).

    >>> import tempfile
    >>> from pathlib import Path
    >>> path = Path(tempfile.mkdtemp()) / "walk.actiongram"
    >>> _ = path.write_text("lknee: B G R@2.5 Y\\nrknee: Y B\\n")
    >>> ag = _read_file(path)
    >>> ag.names, ag.durations["lknee"]
    (('lknee', 'rknee'), (1.0, 1.0, 2.5, 1.0))
    """
    path = Path(path)
    # a leading byte-order mark is not part of the first name
    text = read_text(path, signature=True)
    if path.suffix.lower() == ".json":
        actiongram = Actiongram.from_json(text, source=str(path))
    else:
        actiongram = Actiongram.from_text(text, source=str(path))
    if not len(actiongram):
        raise FormatError("empty actiongram: no 'name: symbols' line" if path.suffix.lower()
                          != ".json" else "empty actiongram: the 'strings' list is empty",
                          source=str(path), line=1, column=1)
    return actiongram
