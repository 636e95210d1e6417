"""The descriptions a praxicon folder keeps: ``descriptions.json``, learnt, written and read.

One :class:`~praxicon.description.Descriptions` for whole takes (recognition) and one for the
windows of a recording (parsing), in one JSON file beside the folder's ``index.json``. The
build learns them after the actions, from the performances each
learnt action was learnt from, and keeps with them a key of what they were learnt from
(:func:`descriptions_key`): a resumed build that learns no action again reuses them.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

from .description import FORMAT_VERSION, LEARNING, DescriptionError, Descriptions
from .records import REBUILD, Praxicon, PraxiconError, check_index

__all__ = ["FILE", "descriptions_key", "read_descriptions",
           "read_descriptions_file", "descriptions_text"]

#: The file's name inside a praxicon folder.
FILE = "descriptions.json"
_FORMAT = "praxicon-descriptions-file"


def descriptions_key(praxicon: Praxicon) -> str:
    """What a praxicon's descriptions are learnt from: its learnt actions with their input
    keys, the descriptions' format version and how they are learnt (a change of any learns
    them again)."""
    learnt = [(a.name, praxicon.key(a.name)) for a in praxicon.actions if a.learnt]
    text = json.dumps({"version": FORMAT_VERSION, "learning": LEARNING, "actions": learnt})
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def descriptions_text(takes: Descriptions, windows: Descriptions, key: str = "") -> str:
    """What ``descriptions.json`` holds (written by :func:`praxicon.dump` and the build)."""
    return json.dumps({"format": _FORMAT, "version": FORMAT_VERSION, "key": key,
                       "takes": takes.to_dict(), "windows": windows.to_dict()}) + "\n"


def read_descriptions_file(folder):
    """``(takes, windows, key)`` from ``folder/descriptions.json``; ``None`` when it has none.

    Raises
    ------
    PraxiconError
        One line: the file is damaged, or holds descriptions of another version (naming the
        command that rebuilds them).
    """
    path = Path(folder) / FILE
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        return None
    except (OSError, UnicodeDecodeError, ValueError, RecursionError) as exc:
        raise PraxiconError(f"{path}: not JSON ({type(exc).__name__})") from None
    if not isinstance(data, dict) or data.get("format") != _FORMAT:
        raise PraxiconError(f"{path}: not a praxicon descriptions file")
    if data.get("version") != FORMAT_VERSION:
        raise PraxiconError(f"{path}: descriptions of version {data.get('version')!r}, this "
                            f"psgs reads version {FORMAT_VERSION} (learn them again: "
                            f"'{REBUILD}' resumes the build and describes its actions)")
    key = data.get("key", "")
    try:
        return (Descriptions.from_dict(data["takes"]), Descriptions.from_dict(data["windows"]),
                key if isinstance(key, str) else "")
    except (KeyError, TypeError, ValueError, RecursionError) as exc:
        raise PraxiconError(f"{path}: {str(exc).splitlines()[0] if str(exc) else exc!r}") \
            from None


def read_descriptions(folder, *, windows: bool = False) -> Descriptions:
    """The descriptions a praxicon folder holds (whole takes, or ``windows`` for parsing).

    Reads only the index's header and ``descriptions.json`` (not every record): what
    recognising from a folder needs.

    Raises
    ------
    DescriptionError
        One line: the folder does not exist, is not a praxicon (or one of another version),
        has no descriptions or damaged ones (naming the command that learns them).
    """
    folder = Path(folder)
    if not folder.exists():
        raise DescriptionError(f"{folder}: no such praxicon folder")
    where = folder / "index.json"
    try:
        index = json.loads(where.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise DescriptionError(f"{folder}: not a praxicon folder (no praxicon index "
                               f"index.json; build one with '{REBUILD}')") from None
    except (OSError, UnicodeDecodeError, ValueError, RecursionError) as exc:
        raise DescriptionError(f"{where}: not a praxicon index ({type(exc).__name__})") \
            from None
    try:
        check_index(index, str(where))
        found = read_descriptions_file(folder)
    except PraxiconError as exc:
        raise DescriptionError(str(exc)) from None
    if found is None:
        raise DescriptionError(f"{folder / FILE}: no descriptions in this praxicon (learn "
                               f"them: '{REBUILD}' resumes the build and describes its "
                               f"actions)")
    return found[1] if windows else found[0]
