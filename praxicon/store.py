"""A praxicon on disk: ``load`` a folder into a :class:`~praxicon.records.Praxicon`, ``dump`` one.

Layout of a praxicon folder ``DIR`` (schema in ``docs/praxicon.md``)::

    DIR/index.json            format, version, settings, datasets, and every action's record
                              without its system text and mean pose, sorted by name
    DIR/actuators.csv         the actuator-set matrix: one row per learnt action, one
                              column per joint, 1 where the joint takes part
    DIR/shared.json           kineteme sub-patterns several actions share, per joint
    DIR/ACTION.psgs           the grammar system learnt for ACTION
    DIR/records/ACTION.json   one full record per action with its input key (what resume reads)
    DIR/timings.json          wall seconds per action (kept out of index.json, whose
                              bytes must not change between runs)
    DIR/descriptions.json     what recognition and parsing read: the learnt actions'
                              descriptions of whole takes and of windows, and the key of
                              the records they were learnt from

Every file is written to a temporary name and renamed into place, so an
interrupted build never leaves a half-written file. Reading a damaged folder
raises one :class:`~praxicon.records.PraxiconError` naming the file and what is wrong.
"""

from __future__ import annotations

import csv
import io
import json
import os
import re
from collections.abc import Iterable
from dataclasses import replace
from pathlib import Path

from ._errors import DAMAGED
from ._record_checks import lookup_problem, name_problem
from ._values import is_flag, not_all, shown
from .records import REBUILD, ActionRecord, Praxicon, PraxiconError, Settings, check_index
from .description import DescriptionError, Descriptions
from .description_store import (FILE, descriptions_key, descriptions_text,
                                read_descriptions_file)
from .jsonvalues import read_json
from .shared import shared_patterns

__all__ = ["load", "dump", "actuator_matrix", "write_atomic", "TEMPORARY_NAME", "dump_json",
           "write_record", "read_records", "write_index", "write_shared", "read_descriptions",
           "system_problem"]

#: What :func:`write_atomic` names a file while it writes it (``.NAME.PID.tmp``): one left in
#: a folder is an interrupted write's.
TEMPORARY_NAME = re.compile(r"^\..+\.\d+\.tmp$")


def write_atomic(path: Path, text: str) -> None:
    """Write ``text`` to ``path`` through a temporary file and a rename.

    An error (a folder in the file's place, a full disk) is an ``OSError`` naming ``path``,
    and the temporary file is removed: it would be a stray file of the folder.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    try:
        tmp.write_text(text, encoding="utf-8", newline="\n")
        os.replace(tmp, path)
    except OSError as exc:
        tmp.unlink(missing_ok=True)
        raise OSError(exc.errno, exc.strerror, str(path)) from None


def dump_json(value) -> str:
    """Canonical JSON: sorted keys, two-space indent, a final newline."""
    return json.dumps(value, indent=2, sort_keys=True, ensure_ascii=False) + "\n"


def write_record(out: Path, record: ActionRecord, key: str) -> None:
    """Store one action's record (with its input key) and its ``.psgs`` file."""
    psgs_path = out / f"{record.name}.psgs"
    if record.system:
        write_atomic(psgs_path, record.system)
    elif psgs_path.exists():
        psgs_path.unlink()
    write_atomic(out / "records" / f"{record.name}.json",
                 dump_json({"key": key, "record": record.to_json()}))


def _stored_record(path: Path, name: str | None = None) -> tuple[str, ActionRecord]:
    """(input key, record) of ``records/NAME.json``, checked against its file name."""
    value = read_json(path, PraxiconError)
    if not isinstance(value, dict) or not isinstance(value.get("key"), str) \
            or "record" not in value:
        raise PraxiconError(f"{path}: not a praxicon record file (key and record expected)")
    record = ActionRecord.from_json(value["record"], str(path))
    if record.name != (name or path.stem):
        raise PraxiconError(f"{path}: holds the record of {record.name!r}, not of "
                            f"{name or path.stem!r}")
    return value["key"], record


def system_problem(record: ActionRecord, where, *, advice: bool = True) -> str | None:
    """Why ``record``'s system text does not parse, as one line naming ``where`` (its record
    file) and, with ``advice``, what learns it again; None for a system that parses (or a
    record without one).

    :func:`load` does not parse the systems (0.7 s for the shared data's 47, seven times what
    recognition spends reading the folder), so a record whose ``system`` was damaged passes
    it; what writes or trusts a system (resume, :func:`praxicon.verify`,
    :func:`praxicon.repair`, the pictures, generation) asks here. The ``.psgs`` file beside
    it is a copy of that text: the record is what is damaged, and only learning the action
    again makes its system.

    Examples
    --------
    >>> from praxicon.records import ActionRecord
    >>> problem = system_problem(ActionRecord("m.a", "m", "a", system="garbage"), "a.json")
    >>> print(problem[:73])
    a.json: 'system' does not parse (line 1, column 1: expected a first line
    >>> problem.endswith("the record is damaged ('psgs praxicon build DATASET... -o FOLDER' "
    ...                  "into the folder learns the action again)")
    True
    """
    if not record.system:
        return None
    from psgs import loads
    from psgs.errors import PSGSError

    try:
        loads(record.system, source=str(where))
    except (PSGSError, ValueError) as exc:
        line, column = getattr(exc, "line", None), getattr(exc, "column", None)
        place = f"line {line}, column {column}: " if line and column else ""
        said = f"{where}: 'system' does not parse ({place}{getattr(exc, 'message', exc)})"
        return said + (f": {DAMAGED}" if advice else "")
    return None


def read_records(out: Path) -> tuple[dict[str, tuple[str, ActionRecord]], dict[str, str]]:
    """What resume can trust in ``out/records``: name -> (input key, record), and per record
    file it cannot trust, its action's name -> why (that action is learnt again). A record
    whose system does not parse is one it cannot trust: resume would write that text over
    the action's ``.psgs`` file."""
    found, damaged = {}, {}
    for path in sorted((out / "records").glob("*.json")):
        try:
            key, record = _stored_record(path)
        except PraxiconError as exc:
            damaged[path.stem] = str(exc)
            continue
        problem = system_problem(record, path, advice=False)  # resume says "learnt again"
        if problem:
            damaged[path.stem] = problem
            continue
        found[record.name] = (key, record)
    return found, damaged


def actuator_matrix(records) -> tuple[list[str], list[str], list[list[int]]]:
    """(action names, joint names, 0/1 rows) of the learnt actions.

    Joints are in order of first appearance over the actions sorted by name, in
    each action's skeleton order (so one dataset's joints stay together).

    Parameters
    ----------
    records : Praxicon or iterable of ActionRecord

    Examples
    --------
    >>> from praxicon.records import ActionRecord
    >>> a = ActionRecord("a", "d", "a", status="ok", actuators=("arm",),
    ...                  all_joints=("hips", "arm", "leg"))
    >>> actuator_matrix([a])
    (['a'], ['hips', 'arm', 'leg'], [[0, 1, 0]])
    """
    given, records = records, records.actions if isinstance(records, Praxicon) else records
    records = tuple(records) if isinstance(records, Iterable) else None
    if records is None or not all(isinstance(r, ActionRecord) for r in records):
        raise PraxiconError(f"actuator_matrix reads a Praxicon or its ActionRecords, "
                            f"{not_all(given, records, ActionRecord)}")
    learnt = [r for r in records if r.learnt]
    # a dict's keys and a set, not a list searched per joint (quadratic)
    joints = list(dict.fromkeys(joint for r in learnt for joint in _pose_joints(r)))
    rows = [[int(j in actuators) for j in joints]
            for actuators in (set(r.actuators) for r in learnt)]
    return [r.name for r in learnt], joints, rows


def _pose_joints(record: ActionRecord) -> list[str]:
    if record.all_joints:
        return list(record.all_joints)
    return list(dict.fromkeys(channel.rsplit(".", 1)[0] for channel, _ in record.mean_pose))


def write_index(out: Path, praxicon: Praxicon, timings: dict[str, float] | None = None) -> dict:
    """Write ``index.json`` and ``actuators.csv`` (with ``timings`` also ``timings.json``).
    Returns the index."""
    index = praxicon.index()
    names, joints, rows = actuator_matrix(praxicon)
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(["action", *joints])
    for name, row in zip(names, rows):
        writer.writerow([name, *row])
    write_atomic(out / "actuators.csv", buffer.getvalue())
    write_atomic(out / "index.json", dump_json(index))
    if timings is not None:
        write_atomic(out / "timings.json", dump_json({k: round(v, 3) for k, v in
                                                     sorted(timings.items())}))
    return index


def write_shared(out: Path, praxicon: Praxicon) -> None:
    """Write ``shared.json``: the patterns that recur across actions."""
    write_atomic(out / "shared.json",
                 dump_json([p.to_dict() for p in shared_patterns(praxicon)]))


def _folder(folder) -> Path:
    """``folder`` as a Path; one that is no path (None, a number) is the folder's error, not
    the TypeError of ``Path(None)``."""
    if not isinstance(folder, (str, os.PathLike)):
        raise PraxiconError(f"a praxicon folder is a path, not {type(folder).__name__}")
    if os.fspath(folder) == "":  # Path("") is the current folder: dump wrote into it
        raise PraxiconError("a praxicon folder's name is empty ('' would be the current folder)")
    return Path(folder)


def dump(praxicon: Praxicon, folder: str | Path) -> None:
    """Write ``praxicon`` into ``folder``: every record and system, the index, the actuator
    matrix and the shared patterns (what :func:`load` reads back as an equal value).

    Raises :class:`~praxicon.records.PraxiconError` (before writing anything) when an
    action's name cannot be a file name, or a learnt record's ``mean_pose`` or
    ``component_names`` key is one :func:`load` refuses (what is written reads back).

    Examples
    --------
    >>> import tempfile
    >>> from praxicon.records import ActionRecord, Settings
    >>> px = Praxicon((ActionRecord("m.a", "m", "a", reason="no takes"),), Settings.make())
    >>> folder = Path(tempfile.mkdtemp()) / "px"
    >>> dump(px, folder)
    >>> load(folder) == px
    True
    """
    if not isinstance(praxicon, Praxicon):
        raise PraxiconError(f"dump writes a Praxicon, not {type(praxicon).__name__}")
    problems = [p for p in map(name_problem, praxicon.names) if p]
    problems += [f"action {a.name!r}: {p}" for a in praxicon.actions
                 if a.learnt and (p := lookup_problem(a))]
    if problems:
        raise PraxiconError(problems[0])
    folder = _folder(folder)
    for record in praxicon.actions:
        write_record(folder, record, praxicon.key(record.name))
    write_index(folder, praxicon)
    write_shared(folder, praxicon)
    if praxicon.descriptions is not None and praxicon.window_descriptions is not None:
        write_atomic(folder / FILE, descriptions_text(
            praxicon.descriptions, praxicon.window_descriptions, descriptions_key(praxicon)))


def load(folder: str | Path, *, descriptions: bool = True) -> Praxicon:
    """The praxicon in ``folder`` (made by ``psgs praxicon build``), every record in full.

    Parameters
    ----------
    folder : str or Path
        A praxicon folder.
    descriptions : bool, default True
        Also read ``descriptions.json`` (what recognition and parsing read). Without it the
        praxicon has no descriptions and the file is not read at all: generation and the
        pictures need only the records, so a folder whose descriptions are of another
        version (learnt by another psgs) still generates and draws.

    Returns
    -------
    Praxicon

    Raises
    ------
    PraxiconError
        One line naming the file: a path that does not exist, a folder that is not a
        praxicon, a praxicon of an earlier format version (the line names the command that
        rebuilds it) or of a later one (it says to upgrade psgs), a damaged index or record
        (a learnt record whose ``mean_pose`` or ``component_names`` key is no channel of its
        joints, or that lacks a channel of its morphemes, is one: generation would look the
        channel up in vain), or (unless ``descriptions=False``) a damaged
        ``descriptions.json`` (the line and column of what is not JSON; the field of a value
        out of its range), descriptions of another format, or descriptions learnt from other
        records than the folder's (left by an interrupted build); ``descriptions`` that is
        not True or False.

    Examples
    --------
    >>> import pathlib, tempfile
    >>> load(pathlib.Path(tempfile.mkdtemp()))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    praxicon.records.PraxiconError: ...: not a praxicon folder (no index.json; build one with 'psgs praxicon build DATASET... -o FOLDER')
    """
    folder = _folder(folder)
    if not is_flag(descriptions):
        raise PraxiconError(f"descriptions must be True or False, not {shown(descriptions)}")
    if not folder.exists():
        raise PraxiconError(f"{folder}: no such praxicon folder")
    if not folder.is_dir():
        raise PraxiconError(f"{folder}: not a praxicon folder (a file; a praxicon is a folder "
                            f"with index.json)")
    where = folder / "index.json"
    index = read_json(where, PraxiconError, f"{folder}: not a praxicon folder (no index.json; "
                                            f"build one with '{REBUILD}')")
    check_index(index, str(where))
    entries = index.get("actions")
    if not isinstance(entries, list) or not all(isinstance(e, dict) for e in entries):
        raise PraxiconError(f"{where}: 'actions' must be a list of records")
    datasets = index.get("datasets", [])
    if not isinstance(datasets, list) or not all(isinstance(d, str) for d in datasets):
        raise PraxiconError(f"{where}: 'datasets' must be a list of paths")
    names: set[str] = set()
    for i, entry in enumerate(entries):
        problem = name_problem(entry.get("name"))
        if problem:
            raise PraxiconError(f"{where}: action {i + 1}: {problem}")
        if entry["name"] in names:  # before any record is read: the index alone says so
            raise PraxiconError(f"{where}: action {entry['name']!r} is listed twice")
        names.add(entry["name"])
    settings = Settings.from_dict(index.get("settings"), f"{where}: settings")
    records, keys = [], []
    for name in sorted(names):
        key, record = _stored_record(folder / "records" / f"{name}.json", name)
        records.append(record)
        if key:  # "" is what dump writes for a record whose inputs are not known
            keys.append((name, key))
    praxicon = Praxicon(tuple(records), settings, tuple(datasets), tuple(keys))
    if not descriptions:
        return praxicon
    described = read_descriptions_file(folder)
    if described is None:
        return praxicon
    _check_described(praxicon, *described, folder / FILE)
    return replace(praxicon, descriptions=described[0], window_descriptions=described[1])


def _check_described(praxicon: Praxicon, takes, windows, key: str, path: Path) -> None:
    """A :class:`PraxiconError` unless the descriptions were learnt from ``praxicon``'s learnt
    actions: an answer names only an action the folder holds, as learnt from the records
    there (descriptions left by an interrupted build, or copied from another folder, would
    answer for other records)."""
    learnt = {a.name for a in praxicon.actions if a.learnt}
    for part, described in (("takes", takes), ("windows", windows)):
        stray = [n for n in described.names if n not in learnt]
        if stray:
            raise PraxiconError(f"{path}: {part}: describes {stray[0]!r}, which index.json "
                                f"does not list as a learnt action (learn the descriptions "
                                f"again: '{REBUILD}' resumes the build and describes its "
                                f"actions)")
    if key != descriptions_key(praxicon):
        raise PraxiconError(f"{path}: 'key' is not the key of this folder's learnt actions: "
                            f"the descriptions were learnt from other records (learn them "
                            f"again: '{REBUILD}' resumes the build and describes its actions)")


def read_descriptions(folder, *, windows: bool = False) -> Descriptions:
    """The descriptions a praxicon folder holds (whole takes, or ``windows`` for parsing).

    The folder is read by :func:`load` (one code path): its index, every record (each is an
    action an answer may name, and what the descriptions' key is checked against) and
    ``descriptions.json``, so a folder ``load`` refuses is refused here too, with the same
    line. Reading every record costs little beside a recognition (0.1 s for the shared
    data's 56 actions, whose descriptions alone take 0.05 s).

    Raises
    ------
    DescriptionError
        One line: the folder does not exist, is not a praxicon (or one of another version),
        is damaged, or has no descriptions or damaged ones (naming the command that learns
        them).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> read_descriptions(pathlib.Path(tempfile.mkdtemp()) / "none")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    praxicon.description.DescriptionError: .../none: no such praxicon folder
    """
    try:
        praxicon = load(folder)
    except PraxiconError as exc:
        raise DescriptionError(str(exc)) from None
    found = praxicon.window_descriptions if windows else praxicon.descriptions
    if found is None and not praxicon.counts["learnt"]:
        raise DescriptionError(f"{folder}: {_nothing_learnt(praxicon, windows)}")
    if found is None:
        raise DescriptionError(f"{Path(folder) / FILE}: no descriptions in this praxicon "
                               f"(learn them: '{REBUILD}' resumes the build and describes its "
                               f"actions)")
    return found


def _nothing_learnt(praxicon: Praxicon, windows: bool = False) -> str:
    """Why a praxicon that learnt no action has no descriptions: a build that resumes learns
    none either (it describes the learnt actions), so the descriptions' command is not named.

    >>> from praxicon.records import ActionRecord
    >>> print(_nothing_learnt(Praxicon((ActionRecord("m.a", "m", "a"),), Settings.make())))
    ... # doctest: +NORMALIZE_WHITESPACE
    no action of this praxicon was learnt (its 1 action failed; index.json says why):
    nothing to recognise with
    """
    count = praxicon.counts["actions"]
    why = (f"its {count} action{'' if count == 1 else 's'} failed; index.json says why"
           if count else "it has no action")
    return (f"no action of this praxicon was learnt ({why}): nothing to "
            f"{'parse' if windows else 'recognise'} with")
