"""Motion databases in, actions out: which performances make up each action.

An :class:`Action` is a name and its :class:`Performance` s (a file, and a time
span of it or the whole take). Three layouts are read out of the box:

* **Bandai Namco** (a folder with ``cfg/content_label.txt``, ``cfg/style_label.txt``
  and ``data/*.bvh`` with a ``.json`` beside each): one take per file, named
  ``dataset-N_{content}_{style}_{id}``; the JSON's content and style (read by
  :func:`kinetology.read_bandai_json`) must agree with the file name.
* **cmu-mocap6** (a folder with ``amc/`` and ``truelabels/``): each
  ``truelabels/T.txt`` gives one label per 1/10 s (label ``t`` covers AMC frames
  ``12t .. 12t+11``, read by :func:`kinetology.read_cmu_truelabels`); each run of
  one label lasting ``MIN_SPAN_SECONDS`` or more is one performance of that exercise.
* a **manifest**, CSV (columns ``action,file,start,stop``; start/stop in seconds,
  optional, empty = the whole take; an optional ``style`` column) or TOML
  (``[[performance]]`` tables with the same keys), for any other database. Relative
  file paths are relative to the manifest's folder; styles group as a Bandai folder's.

A problem found while reading (a label file that disagrees with its motion, an
unreadable label file) never stops the reading: it is kept in the action's
``problems`` and the performance is left out.
"""

from __future__ import annotations

import csv
import io
import math
import os
from numbers import Real
import re
import tomllib
from collections import Counter, defaultdict
from dataclasses import dataclass, field
from pathlib import Path

from psgs._foundation.files import decode_utf8, read_bytes
from psgs.errors import FormatError, PSGSError

from ._values import shown

__all__ = ["Performance", "Action", "read_dataset", "read_datasets", "DatasetError"]

_CMU_FRAME_RATE = 120.0  # the AMC files' rate; a label covers 12 frames (1/10 s)
#: Shortest labelled run of cmu-mocap6 taken as a performance (shorter runs are transitions).
MIN_SPAN_SECONDS = 2.0
_BANDAI_NAME = re.compile(r"^dataset-\d+_(?P<content>.+?)_(?P<style>[^_]+)_(?P<take>\d+)$")


class DatasetError(PSGSError, ValueError):
    """A dataset path that is not one of the known layouts, or a malformed manifest.

    Under :class:`psgs.PSGSError`, the root of the distribution's errors, so every command
    reports it in one line."""


@dataclass(frozen=True)
class Performance:
    """One performance of an action: ``file`` (a string; a ``pathlib.Path`` given is kept as
    its string), optionally cut to ``start``..``stop`` seconds.

    ``label`` says where the cut came from (e.g. ``truelabels/13_29.txt``), for the index.
    """

    file: str
    start: float | None = None
    stop: float | None = None
    label: str | None = None

    def __post_init__(self) -> None:
        # made in Python, not read from a manifest (whose reader says the same per line): a
        # path that is no string, a time that is a string or NaN, or a stop before the start
        # went on to the learner, or failed there with a TypeError. A pathlib.Path is kept as
        # the string the records, the index and the learner's cache keys hold.
        if isinstance(self.file, os.PathLike):
            object.__setattr__(self, "file", os.fspath(self.file))
        problem = _performance_problem(self)
        if problem:
            raise DatasetError(f"a performance's {problem}")

    def to_dict(self) -> dict:
        """The performance as plain JSON values (for index.json)."""
        return {"file": self.file, "start": self.start, "stop": self.stop, "label": self.label}


@dataclass(frozen=True)
class Action:
    """An action: its name, where it comes from, its performances and reading problems."""

    name: str
    dataset: str
    content: str
    style: str | None = None
    performances: tuple[Performance, ...] = ()
    problems: tuple[str, ...] = field(default=())

    def __post_init__(self) -> None:
        for name in ("performances", "problems"):  # a list given is copied: not shared, frozen
            value = getattr(self, name)
            if isinstance(value, list):
                object.__setattr__(self, name, tuple(value))
        for name in ("name", "dataset", "content", "style"):
            value = getattr(self, name)
            if not (isinstance(value, str) or (name == "style" and value is None)):
                raise DatasetError(f"an action's {name} must be a string, not {shown(value)}")
        if not (isinstance(self.performances, tuple)
                and all(isinstance(p, Performance) for p in self.performances)):
            raise DatasetError(f"an action's performances must be a tuple (or a list) of "
                               f"Performance values, not {shown(self.performances)}")
        if not isinstance(self.problems, tuple):
            raise DatasetError(f"an action's problems must be a tuple (or a list) of strings, "
                               f"not {shown(self.problems)}")


def _performance_problem(p: Performance) -> str | None:
    """What is wrong with a performance made in Python, after "a performance's" (or None)."""
    if not isinstance(p.file, str):
        return f"file must be a path (a string or a pathlib.Path), not {shown(p.file)}"
    if not isinstance(p.label, (str, type(None))):
        return f"label must be a string or None, not {shown(p.label)}"
    for name in ("start", "stop"):
        t = getattr(p, name)
        if t is not None and not (isinstance(t, Real) and not isinstance(t, bool)
                                  and 0 <= t < math.inf):
            return f"{name} must be a number of seconds, 0 or more, or None, not {shown(t)}"
    if p.start is not None and p.stop is not None and not p.start < p.stop:
        return f"start must come before its stop, not {shown(p.start)} and {shown(p.stop)}"
    return None


def _name_part(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9_.-]+", "-", text).strip("-") or "x"


def _shown_path(path: Path) -> str:
    return path.as_posix()


# -- Bandai Namco ------------------------------------------------------------------------------
def _unprefixed(name: str) -> str:
    return re.sub(r"^dataset-\d+_", "", name)


def _read_bandai(root: Path, group_by: tuple[str, ...] | None) -> list[Action]:
    data = root / "data"
    files = sorted(data.glob("*.bvh"))
    if not files:
        raise DatasetError(f"{_shown_path(root)}: no data/*.bvh files")
    takes: list[tuple[str, str, Performance | None, str | None]] = []
    for path in files:
        match = _BANDAI_NAME.match(path.stem)
        if not match:
            takes.append(("unnamed", "", None, f"{_shown_path(path)}: file name is not "
                          f"dataset-N_CONTENT_STYLE_ID"))
            continue
        content, style = match["content"], match["style"]
        problem = _bandai_label_problem(path, content, style)
        takes.append((content, style, None if problem else Performance(_shown_path(path)),
                      problem))
    group_by = _grouping([(content, style) for content, style, _, _ in takes], group_by)
    groups: dict[tuple[str, str | None], list] = defaultdict(list)
    for content, style, perf, problem in takes:
        key = (content, style if "style" in group_by else None)
        groups[key].append((perf, problem))
    actions = []
    for (content, style), members in sorted(groups.items(), key=lambda kv: (kv[0][0],
                                                                             kv[0][1] or "")):
        name = ".".join(_name_part(p) for p in (root.name, content, style) if p)
        actions.append(Action(name, root.name, content, style,
                              tuple(p for p, _ in members if p is not None),
                              tuple(q for _, q in members if q)))
    return actions


def _grouping(pairs, group_by: tuple[str, ...] | None) -> tuple[str, ...]:
    """``group_by``, or by default ``("content", "style")`` where most of the takes'
    (content, style) ``pairs`` have several takes, else ``("content",)`` (a pair of one take
    would be an action of a single performance)."""
    if group_by is not None:
        return group_by
    per_pair: dict[tuple, int] = defaultdict(int)
    for pair in pairs:
        per_pair[pair] += 1
    several = sum(n >= 2 for n in per_pair.values())
    return ("content", "style") if 2 * several > len(per_pair) else ("content",)


def _bandai_label_problem(path: Path, content: str, style: str) -> str | None:
    """Why the JSON beside a take does not label it as its name says (None when it does)."""
    from kinetology.labels import read_bandai_json

    label = path.with_suffix(".json")
    try:
        (span,) = read_bandai_json(label)
    except FileNotFoundError:
        return f"{_shown_path(label)}: label file missing"
    except (OSError, ValueError) as exc:  # MotionFormatError is a ValueError
        return f"unreadable label file: {str(exc).splitlines()[0]}"
    if span.label != content or (span.style is not None and span.style != style):
        return (f"{_shown_path(label)}: label file says {span.label}/{span.style}, the file "
                f"name {content}/{style}: the label file does not match its motion")
    return None


# -- cmu-mocap6 --------------------------------------------------------------------------------
def _read_cmu_mocap6(root: Path, group_by: tuple[str, ...] | None) -> list[Action]:
    from kinetology.labels import read_cmu_truelabels

    groups: dict[str, list[Performance]] = defaultdict(list)
    general: list[str] = []
    for label_path in sorted((root / "truelabels").glob("*.txt")):
        amc = root / "amc" / f"{label_path.stem}.amc"
        try:
            spans = read_cmu_truelabels(label_path, _CMU_FRAME_RATE)
        except (OSError, ValueError) as exc:
            general.append(f"unreadable label file: {str(exc).splitlines()[0]}")
            continue
        for span in spans:
            if span.duration >= MIN_SPAN_SECONDS:
                groups[span.label].append(Performance(_shown_path(amc), round(span.start, 6),
                                                      round(span.stop, 6),
                                                      _shown_path(label_path)))
    return [Action(f"{_name_part(root.name)}.{_name_part(name)}", root.name, name, None,
                   tuple(groups[name]), tuple(general)) for name in sorted(groups)]


# -- manifests ---------------------------------------------------------------------------------
def _optional_seconds(value, where: str) -> float | None:
    if value is None or (isinstance(value, str) and not value.strip()):
        return None
    try:
        seconds = float(value)
    except (TypeError, ValueError, OverflowError):
        raise DatasetError(f"{where}: start/stop must be seconds, not {shown(value)}") from None
    if isinstance(value, bool) or not (seconds >= 0 and math.isfinite(seconds)):
        raise DatasetError(f"{where}: start/stop must be seconds >= 0, not {shown(value)}")
    return seconds


class _Lines:
    """The lines of a text, counted as the csv reader takes them (its own count lags behind
    on an error)."""

    def __init__(self, text: str):
        self._lines = iter(io.StringIO(text, newline=""))
        self.number = 0

    def __iter__(self):
        return self

    def __next__(self) -> str:
        line = next(self._lines)
        self.number += 1
        return line


def _manifest_text(path: Path) -> str:
    # read_bytes: a device named as a manifest is refused, not read without end;
    # decode_utf8: bytes that are not UTF-8 are named at their line and column
    try:
        # signature: a spreadsheet's "CSV UTF-8" starts with a byte-order mark
        return decode_utf8(read_bytes(path), _shown_path(path), signature=True)
    except FormatError as exc:
        raise DatasetError(str(exc)) from None
    except OSError as exc:
        raise DatasetError(f"{_shown_path(path)}: cannot be read ({exc.strerror or exc})") \
            from None


def _read_manifest(path: Path, group_by: tuple[str, ...] | None = None) -> list[Action]:
    rows: list[tuple[str, dict]] = []
    text = _manifest_text(path)
    if path.suffix.lower() == ".toml":
        try:
            table = tomllib.loads(text)
        except (tomllib.TOMLDecodeError, ValueError) as exc:  # ValueError: e.g. a date out of range
            raise DatasetError(f"{_shown_path(path)}: {exc}") from None
        except RecursionError:
            raise DatasetError(f"{_shown_path(path)}: nests too deeply to be a manifest") \
                from None
        entries = table.get("performance", [])
        if not isinstance(entries, list):
            raise DatasetError(f"{_shown_path(path)}: [[performance]] tables expected")
        rows = [(f"{_shown_path(path)}: performance {i + 1}", e) for i, e in enumerate(entries)]
        for where, entry in rows:
            if not isinstance(entry, dict):
                raise DatasetError(f"{where}: a [[performance]] table expected, not "
                                   f"{shown(entry)}")
    else:
        lines = _Lines(text)
        reader = csv.DictReader(lines)
        try:
            missing = {"action", "file"} - set(reader.fieldnames or ())
            if missing:
                raise DatasetError(f"{_shown_path(path)}:1: manifest needs columns action,file "
                                   f"(missing {', '.join(sorted(missing))})")
            names = list(reader.fieldnames or ())
            counts = Counter(names)  # not names.count per column (quadratic)
            twice = sorted({n for n in names if n and n.strip() and counts[n] > 1})
            if twice:  # which of the two is meant cannot be known (blank ones pad a sheet's)
                raise DatasetError(f"{_shown_path(path)}:1: the header names column "
                                   f"{twice[0]!r} twice")
            rows = [(f"{_shown_path(path)}:{lines.number}", row) for row in reader]
        except csv.Error as exc:  # e.g. a field longer than the csv module's limit
            raise DatasetError(f"{_shown_path(path)}:{lines.number}: {exc}") from None
    takes: list[tuple[str, str | None, Performance]] = []
    seen: dict[tuple, str] = {}  # (action, style, file, start, stop) -> the row that gave it
    for where, row in rows:
        if any(str(cell).strip() for cell in row.get(None, ())):
            # cells past the header's, which would be dropped without a word (empty ones
            # pad a spreadsheet's rows)
            raise DatasetError(f"{where}: {len(row) - 1 + len(row[None])} cells, the header "
                               f"has {len(row) - 1}")
        action, file = row.get("action"), row.get("file")
        if not action or not file:
            raise DatasetError(f"{where}: action and file are required")
        if not isinstance(action, str) or not isinstance(file, str):
            raise DatasetError(f"{where}: action and file must be text, not "
                               f"{shown(action if not isinstance(action, str) else file)}")
        file_path = Path(file) if Path(file).is_absolute() else path.parent / file
        start = _optional_seconds(row.get("start"), where)
        stop = _optional_seconds(row.get("stop"), where)
        if start is not None and stop is not None and stop <= start:
            raise DatasetError(f"{where}: stop {stop} is not after start {start}")
        style = row.get("style")
        if style is not None and not isinstance(style, str):
            raise DatasetError(f"{where}: style must be text, not {shown(style)}")
        style = style.strip() or None if style else None
        performance = Performance(_shown_path(file_path), start, stop, _shown_path(path))
        # a row given twice would count as two performances: one take met the minimum of
        # two and was learnt as if it repeated across takes
        first = seen.setdefault((action, style, performance), where)
        if first != where:
            said = first.rsplit(":", 1)[-1].strip()  # a CSV row's line, a TOML table's place
            raise DatasetError(f"{where}: the same performance as "
                               f"{'line ' + said if said.isdigit() else said} (action, file "
                               f"and span): list each once")
        takes.append((str(action), style, performance))
    if not takes:  # an action is its rows: a build of none would be an empty folder
        raise DatasetError(f"{_shown_path(path)}: no actions in it (no "
                           + ("[[performance]] table)" if path.suffix.lower() == ".toml"
                              else "row under the header: one per performance)"))
    # a style column groups as a Bandai folder's styles do (one action per action and style
    # where most pairs have several performances); without one, an action a row names
    group_by = _grouping([(a, s) for a, s, _ in takes], group_by)
    groups: dict[tuple[str, str | None], list[Performance]] = defaultdict(list)
    for action, style, performance in takes:
        groups[action, style if "style" in group_by else None].append(performance)
    dataset = path.stem
    return [Action(".".join(_name_part(p) for p in (dataset, a, style) if p), dataset, a, style,
                   tuple(p))
            for (a, style), p in sorted(groups.items(), key=lambda kv: (kv[0][0],
                                                                        kv[0][1] or ""))]


# -- entry points ------------------------------------------------------------------------------
def _parse_group_by(group_by: str | None) -> tuple[str, ...] | None:
    if group_by is None:
        return None
    if not isinstance(group_by, str):  # an AttributeError on .split before
        raise DatasetError(f"--group-by must be 'content' or 'content,style', not {group_by!r}")
    parts = tuple(p.strip() for p in group_by.split(","))
    if parts not in (("content",), ("content", "style")):
        raise DatasetError(f"--group-by must be 'content' or 'content,style', not {group_by!r}")
    return parts


def read_dataset(path: str | Path, group_by: str | None = None) -> list[Action]:
    """The actions of one dataset (layout recognised from what is in ``path``).

    Parameters
    ----------
    path : str or Path
        A Bandai-style folder, a cmu-mocap6 folder, or a ``.csv``/``.toml`` manifest.
    group_by : {"content", "content,style"}, optional
        For datasets with styles (a Bandai folder's file names, a manifest's ``style``
        column): one action per content, or per content and style.
        Default: ``"content,style"`` when most (content, style) pairs have several
        takes (Bandai dataset 2), else ``"content"`` (Bandai dataset 1 has one take
        of most pairs, so a (content, style) action would be a single performance).

    Returns
    -------
    list of Action
        Sorted by name.

    Raises
    ------
    DatasetError
        When ``path`` is none of the layouts, or a manifest is malformed or lists no
        performance.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> d = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (d / "m.csv").write_text("action,file,start,stop\\nwave,a.bvh,0,2\\nwave,b.bvh,,\\n")
    >>> [(a.name, len(a.performances)) for a in read_dataset(d / "m.csv")]
    [('m.wave', 2)]
    """
    if not isinstance(path, (str, os.PathLike)):
        raise DatasetError(f"a dataset is a folder's or a manifest's path, not "
                           f"{type(path).__name__}")
    path = Path(path)
    parts = _parse_group_by(group_by)
    if path.is_dir() and (path / "cfg" / "content_label.txt").is_file():
        return _checked_names(_read_bandai(path, parts), path)
    if path.is_dir() and (path / "amc").is_dir() and (path / "truelabels").is_dir():
        return _checked_names(_read_cmu_mocap6(path, parts), path)
    if path.is_file() and path.suffix.lower() in (".csv", ".toml"):
        return _checked_names(_read_manifest(path, parts), path)
    if not path.exists():
        raise DatasetError(f"{_shown_path(path)}: no such file or folder")
    raise DatasetError(f"{_shown_path(path)}: not a known dataset layout (a Bandai folder with "
                       f"cfg/content_label.txt, a cmu-mocap6 folder with amc/ and truelabels/, "
                       f"or a .csv/.toml manifest)")


def _checked_names(actions: list[Action], path: Path) -> list[Action]:
    """``actions``, or a DatasetError when two of them get one name (one record would
    overwrite the other) or a name cannot name the action's files."""
    from ._record_checks import name_problem

    first: dict[str, Action] = {}
    for action in actions:
        problem = name_problem(action.name)
        if problem:
            raise DatasetError(f"{_shown_path(path)}: {problem}")
        other = first.setdefault(action.name, action)
        if other is not action:
            said = [" ".join(p for p in (a.content, a.style) if p) for a in (other, action)]
            raise DatasetError(f"{_shown_path(path)}: actions {said[0]!r} and {said[1]!r} are "
                               f"both named {action.name!r} (names keep letters, digits and "
                               f"_.-): rename one")
    return actions


def read_datasets(paths, group_by: str | None = None) -> list[Action]:
    """The actions of several datasets, sorted by name (a name used twice is an error)."""
    actions: list[Action] = []
    for path in paths:
        actions.extend(read_dataset(path, group_by))
    counts = Counter(a.name for a in actions)  # not names.count per action (quadratic)
    twice = sorted(n for n, count in counts.items() if count > 1)
    if twice:
        raise DatasetError(f"action names given by two datasets: {', '.join(twice[:5])}")
    return sorted(actions, key=lambda a: a.name)
