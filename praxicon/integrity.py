"""Is a praxicon folder whole? Every file it holds, against what its records give.

:func:`~praxicon.store.load` reads and checks ``index.json``, every record and
``descriptions.json``; the other files of a folder (the ``.psgs`` systems, ``actuators.csv``,
``shared.json``) are derived from the records and never read back, so damage to them (a file
cut short by a full disk, a hand edit, a copy that lost a file) would go unnoticed until
someone reads them with another tool. :func:`verify` writes the folder again into a temporary
folder from what ``load`` read (:func:`~praxicon.store.dump`, byte for byte as ``build``
writes it) and compares every file; it also reads ``timings.json``, names files that are no
part of the praxicon (a record or system of an action the index does not list, a temporary
file left by an interrupted write) and a folder of learnt actions without the descriptions
recognition reads; and it parses every record's system, which ``load`` leaves unparsed (a
record whose system does not parse is named; its ``.psgs`` file, a copy of the system as it
was learnt, is not compared with it). :func:`repair` writes every file ``dump`` writes again
from what ``load`` read, and writes nothing while a record's system does not parse.

What this cannot see: a record that is well formed but was changed (its values are checked
for type and range when it is read, and a record is what the other files are derived from;
only learning the action again from its takes tells what it should hold).
"""

from __future__ import annotations

import math
import stat
import tempfile
from dataclasses import dataclass
from pathlib import Path

from ._values import shown
from .description_store import FILE
from ._errors import DAMAGED
from ._record_checks import lookup_problem
from .jsonvalues import read_json
from .records import REBUILD, PraxiconError
from .store import TEMPORARY_NAME, dump, load, system_problem

__all__ = ["Verification", "verify", "repair"]

@dataclass(frozen=True)
class Verification:
    """What :func:`verify` found in a praxicon folder.

    Attributes
    ----------
    folder : str
        The folder verified.
    checked : int
        How many files were compared with what the records give (and ``timings.json``).
    problems : tuple of str
        One line per damaged, missing or stray file, naming the file (and for a file that
        differs, the first line that does), sorted by file; empty for a whole folder.
    repairable : int
        How many of the problems :func:`repair` mends: files missing or differing from what
        the records give (not stray files, timings or descriptions ``load`` refuses).
    """

    folder: str
    checked: int
    problems: tuple[str, ...]
    repairable: int = 0  # how many of the problems repair mends (files missing or differing)

    @property
    def intact(self) -> bool:
        """True when no problem was found."""
        return not self.problems


def _expected(praxicon) -> dict[str, bytes]:
    """Every file ``dump`` writes for ``praxicon``, by its path in the folder."""
    with tempfile.TemporaryDirectory(prefix="psgs-verify-") as work:
        dump(praxicon, work)
        root = Path(work)
        return {p.relative_to(root).as_posix(): p.read_bytes()
                for p in sorted(root.rglob("*")) if p.is_file()}


def _first_difference(found: bytes, expected: bytes) -> str:
    """``line N, column C: ...`` where ``found`` and ``expected`` first part (``found`` holds
    at most one byte more than ``expected``: what it holds past that was not read)."""
    if not found:
        return f"empty; the records give {_lines(expected)} lines"
    if expected.startswith(found):  # cut short (a full disk, an interrupted copy)
        if found + b"\n" == expected:
            return "the last line's newline is missing"
        return (f"cut short: ends at line {_lines(found)} of the {_lines(expected)} the "
                f"records give")
    if found.startswith(expected):
        return f"longer than the records give: more after line {_lines(expected)}"
    found_lines, expected_lines = found.split(b"\n"), expected.split(b"\n")
    for number, (a, b) in enumerate(zip(found_lines, expected_lines), start=1):
        if a != b:
            a_text, b_text = (x.decode("utf-8", errors="backslashreplace") for x in (a, b))
            column = next((i for i, (x, y) in enumerate(zip(a_text, b_text)) if x != y),
                          min(len(a_text), len(b_text)))
            start = max(0, column - 20)
            return (f"line {number}, column {column + 1}: {_shown(a_text, start)} where the "
                    f"records give {_shown(b_text, start)}")
    return "differs"  # not reached: files equal line for line would be equal or a prefix


def _lines(data: bytes) -> int:
    """How many lines ``data`` holds (a last line without its newline counts)."""
    return data.count(b"\n") + (not data.endswith(b"\n"))


def _shown(text: str, start: int) -> str:
    """``text`` from ``start``, cut to 60 characters, as a repr (with ... where cut)."""
    shown = text[start:start + 60]
    return repr(("..." if start else "") + shown + ("..." if len(text) > start + 60 else ""))


def _compare(folder: Path, name: str, expected: bytes) -> tuple[str, bool] | None:
    """The problem with ``folder/name`` against ``expected`` and whether :func:`repair`
    mends it (a file missing or differing; not one that cannot be written over), or None."""
    path = folder / name
    if not path.exists():
        return f"{path}: missing", True
    try:
        if not stat.S_ISREG(path.stat().st_mode):
            return f"{path}: not a file", False
        # no more than one byte past what the records give: a file grown to gigabytes is
        # "longer", not read whole
        with open(path, "rb") as handle:
            found = handle.read(len(expected) + 1)
    except OSError as exc:
        return f"{path}: cannot be read ({exc.strerror or exc})", False
    if found == expected:
        return None
    return (f"{path}: differs from what the records give "
            f"({_first_difference(found, expected)})"), True


def _timings(folder: Path, names: set[str]) -> str | None:
    """The problem with ``timings.json`` (absent is none: it holds wall times only)."""
    path = folder / "timings.json"
    if not path.exists():
        return None
    try:
        value = read_json(path, PraxiconError)
    except PraxiconError as exc:
        return str(exc)
    if not isinstance(value, dict):
        return f"{path}: not an object of seconds per action"
    for name, seconds in sorted(value.items()):
        if name not in names:
            return f"{path}: {name!r} is no action of index.json"
        if isinstance(seconds, bool) or not isinstance(seconds, (int, float)) \
                or (isinstance(seconds, float) and not math.isfinite(seconds)) or seconds < 0:
            return (f"{path}: {name!r}: seconds must be a number 0 or more, not "
                    f"{shown(seconds, 40)}")
    return None


def _strays(folder: Path, expected: dict[str, bytes]) -> list[str]:
    """Files where a praxicon keeps its own that are not of this one: a record or system of
    an action the index does not list, a temporary file of an interrupted write."""
    problems = []
    candidates = [*folder.glob("*.psgs"), *(folder / "records").glob("*.json"),
                  *folder.glob(".*.tmp"), *(folder / "records").glob(".*.tmp")]
    for path in sorted(set(candidates)):
        name = path.relative_to(folder).as_posix()
        if name in expected:
            continue
        if TEMPORARY_NAME.match(path.name):
            problems.append(f"{path}: a temporary file left by an interrupted write")
        elif path.suffix == ".psgs":
            problems.append(f"{path}: the system of no learnt action of index.json")
        else:
            problems.append(f"{path}: the record of no action of index.json")
    return problems


def _loaded(folder):
    """``(praxicon, "")`` as :func:`~praxicon.load` reads ``folder``; when only its
    descriptions are refused (damaged, of another format, learnt from other records),
    ``(praxicon without them, load's line)``, so that every other file is still checked.
    Anything else ``load`` refuses is its :class:`PraxiconError` (read without the
    descriptions, the folder is refused again, by what is wrong with it)."""
    try:
        return load(folder), ""
    except PraxiconError as exc:
        return load(folder, descriptions=False), str(exc)


def _damaged_systems(folder: Path, praxicon, components: dict | None = None) -> dict[str, str]:
    """Per record whose system does not parse, its file's path in the folder -> the line
    naming it (:func:`~praxicon.store.system_problem`); into ``components``, per record whose
    system parses, its components' names (each system is parsed once)."""
    from psgs import loads
    from psgs.errors import PSGSError

    problems = {}
    for record in praxicon.actions:
        name = f"records/{record.name}.json"
        if not record.system:
            continue
        try:
            system = loads(record.system, source=str(folder / name))
        except (PSGSError, ValueError):  # system_problem's line (it parses it again)
            problems[name] = system_problem(record, folder / name) or f"{folder / name}: " \
                "'system' does not parse"
            continue
        if components is not None:
            components[record.name] = {g.name for g in system.components}
    return problems


def _misnamed_channels(folder: Path, praxicon, components: dict) -> list[str]:
    """A line per learnt record whose ``component_names`` give a channel of its morphemes a
    component that is not of its system (``components``, per record whose system parses, its
    components' names): :func:`~praxicon._record_checks.lookup_problem`, of which
    :func:`~praxicon.load` made the rest (the keys the record alone shows wrong), since it
    leaves the systems unparsed. Generation derives each channel's word from its component."""
    problems = []
    for record in praxicon.actions:
        if record.learnt and record.name in components:
            problem = lookup_problem(record, components[record.name])
            if problem:
                problems.append(f"{folder / 'records' / (record.name + '.json')}: {problem}: "
                                f"{DAMAGED}")
    return problems


def _written_from(damaged: dict[str, str]) -> set[str]:
    """The files of the folder written from the damaged records: the records themselves and
    their ``.psgs`` files."""
    return {*damaged, *(f"{Path(n).stem}.psgs" for n in damaged)}


def verify(folder) -> Verification:
    """Check every file of a praxicon folder against what its records give.

    Parameters
    ----------
    folder : str or Path
        A praxicon folder (made by ``psgs praxicon build``).

    Returns
    -------
    Verification
        ``intact`` when every file is as ``build`` writes it for the folder's records;
        otherwise one line per file that is missing, differs (with its first differing
        line), cannot be read, or is stray, and per record whose system does not parse.

    Raises
    ------
    PraxiconError
        When :func:`~praxicon.load` refuses the folder's index or a record: the same line
        ``load`` gives (descriptions it refuses are one of the problems, and every other file
        is still checked).

    Examples
    --------
    >>> import tempfile
    >>> from praxicon.records import ActionRecord, Praxicon, Settings
    >>> folder = Path(tempfile.mkdtemp()) / "px"
    >>> dump(Praxicon((ActionRecord("m.a", "m", "a", reason="no takes"),),
    ...               Settings.make()), folder)
    >>> verify(folder).intact
    True
    >>> _ = (folder / "actuators.csv").write_text("actions\\n")
    >>> print(*verify(folder).problems)  # doctest: +ELLIPSIS
    /.../px/actuators.csv: differs from what the records give (line 1, column 7: 'actions' where the records give 'action')
    """
    praxicon, refused = _loaded(folder)
    folder = Path(folder)
    expected = _expected(praxicon)
    # a damaged record and its .psgs file are not compared: the record is what is wrong, and
    # "--repair writes it again" would copy the damage over a file that may be intact
    components: dict[str, set[str]] = {}
    damaged = _damaged_systems(folder, praxicon, components)
    skipped = _written_from(damaged)
    compared = [c for c in (_compare(folder, name, data) for name, data in expected.items()
                            if name not in skipped) if c]
    problems = [problem for problem, _ in compared] + list(damaged.values())
    problems += _misnamed_channels(folder, praxicon, components)
    repairable = sum(mendable for _, mendable in compared)
    timing = _timings(folder, set(praxicon.names))
    problems += [timing] if timing else []
    if refused:
        problems.append(refused)
    elif praxicon.descriptions is None and any(a.learnt for a in praxicon.actions):
        problems.append(f"{folder / FILE}: missing: recognise and parse cannot read the "
                        f"folder (learn the descriptions: '{REBUILD}' resumes the build)")
    problems += _strays(folder, expected)
    checked = len(expected) + (folder / "timings.json").exists()
    return Verification(str(folder), checked, tuple(sorted(problems)), repairable)


def repair(folder) -> Verification:
    """Write every file of a praxicon folder again from what :func:`~praxicon.load` reads,
    then verify it.

    The index's names and settings, every record and the descriptions are what the files
    are written from, so a folder whose index or records ``load`` refuses is not repaired
    (the :class:`PraxiconError` says why; ``psgs praxicon build`` learns a damaged record
    again), nor one holding a record whose system does not parse (its ``.psgs`` file would be
    written from that text), and descriptions it refuses (damaged, of an older format) are
    left as they are and reported (``build`` into the folder learns them again);
    the derived files are written anew, and the index, records and descriptions in the
    canonical form ``build`` writes (a key ``load`` does not read, added by hand to a
    record, is dropped). Stray files, a damaged ``timings.json`` and missing descriptions
    are left as they are and still reported.

    Raises
    ------
    PraxiconError
        The line ``load`` gives for a folder it refuses, the line naming a record whose
        system does not parse (nothing is written), or a file that cannot be written (a
        folder in its place).

    Returns
    -------
    Verification
        The folder verified after the repair.

    Examples
    --------
    >>> import tempfile
    >>> from praxicon.records import ActionRecord, Praxicon, Settings
    >>> folder = Path(tempfile.mkdtemp()) / "px"
    >>> dump(Praxicon((ActionRecord("m.a", "m", "a", reason="no takes"),),
    ...               Settings.make()), folder)
    >>> (folder / "shared.json").unlink()
    >>> verify(folder).intact, repair(folder).intact
    (False, True)
    """
    praxicon, _ = _loaded(folder)  # refused descriptions are left as they are
    damaged = sorted(_damaged_systems(Path(folder), praxicon).values())
    if damaged:
        others = f" ({len(damaged) - 1} other record(s) too)" if len(damaged) > 1 else ""
        raise PraxiconError(f"{damaged[0]}; nothing repaired{others}")
    try:
        dump(praxicon, folder)
    except OSError as exc:  # a folder in a file's place, a full disk: the file's line
        raise PraxiconError(f"{exc.filename}: cannot be written ({exc.strerror or exc})") \
            from None
    return verify(folder)

