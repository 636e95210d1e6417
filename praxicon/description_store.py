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

from ._description_json import FieldError, check_named_alike
from .description import FORMAT_VERSION, LEARNING, DescriptionError, Descriptions
from .jsonvalues import read_json, written_by
from .records import REBUILD, Praxicon, PraxiconError

__all__ = ["FILE", "descriptions_key", "read_descriptions_file", "descriptions_in",
           "descriptions_text"]

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

    Every field is checked (:mod:`praxicon._description_json`); the whole-take descriptions
    must be of whole takes (``window`` 0), the window descriptions of windows, both of the
    same actions, the takes' families those of their actions
    (:func:`~praxicon._description_json.check_named_alike`).

    Raises
    ------
    PraxiconError
        One line naming the file (and the line and column of what is not JSON, or the field):
        the file is damaged, or holds descriptions of an earlier version (naming the command
        that rebuilds them) or of a later one (saying to upgrade psgs).
    """
    path = Path(folder) / FILE
    if not path.exists() and not path.is_symlink():
        return None
    return descriptions_in(read_json(path, PraxiconError), path)


def descriptions_in(data, path):
    """``(takes, windows, key)`` of the JSON value ``data`` read from ``path`` (a
    ``descriptions.json``), every field checked as :func:`read_descriptions_file` checks them
    (its errors name ``path``): for a reader that has read the file already.

    Examples
    --------
    >>> descriptions_in({"format": "praxicon-descriptions-file", "version": 10**6},
    ...                 "px/descriptions.json")
    Traceback (most recent call last):
    ...
    praxicon.records.PraxiconError: px/descriptions.json: descriptions of version 1000000, this psgs reads version ... (a later psgs wrote them; upgrade psgs to read them)
    """
    if not isinstance(data, dict) or data.get("format") != _FORMAT:
        raise PraxiconError(f"{path}: not a praxicon descriptions file")
    said = data.get("version")
    age = written_by(said, FORMAT_VERSION)
    if age:  # a later version's are not to be learnt again over
        raise PraxiconError(f"{path}: descriptions of version {said!r}, this psgs reads "
                            f"version {FORMAT_VERSION} " + ("(a later psgs wrote them; upgrade "
                            "psgs to read them)" if age == "later" else f"(learn them again: "
                            f"'{REBUILD}' resumes the build and describes its actions)"))
    key = data.get("key", "")
    if not isinstance(key, str):
        raise PraxiconError(f"{path}: 'key' must be text (what the descriptions were learnt "
                            f"from), not {type(key).__name__}")
    found = []
    for part, windowed in (("takes", False), ("windows", True)):
        try:
            if part not in data:
                raise DescriptionError(f"no {part!r}")
            described = Descriptions.from_dict(data[part])
        except (DescriptionError, RecursionError) as exc:
            text = str(exc) if isinstance(exc, DescriptionError) else "nests too deeply"
            raise PraxiconError(f"{path}: {part}: {text}") from None
        if bool(described.spread.window) != windowed:
            raise PraxiconError(f"{path}: {part}: spread: 'window' must be "
                                f"{'a window length' if windowed else '0 (whole takes)'}, "
                                f"not {described.spread.window!r}")
        found.append(described)
    try:
        check_named_alike(*found)
    except FieldError as exc:
        raise PraxiconError(f"{path}: {exc}") from None
    return found[0], found[1], key
