"""The descriptions a praxicon folder keeps: ``descriptions.json``, written and read.

One :class:`~praxicon.description.Descriptions` for whole takes (recognition) and one for the
windows of a recording (parsing), in one JSON file beside the folder's ``index.json``.
"""

from __future__ import annotations

import json
from pathlib import Path

from .description import FORMAT_VERSION, DescriptionError, Descriptions

__all__ = ["read_descriptions", "write_descriptions", "FILE"]

#: The file's name inside a praxicon folder.
FILE = "descriptions.json"


def write_descriptions(folder, takes, windows) -> Path:
    """Write ``descriptions.json`` into the praxicon ``folder``; returns its path."""
    from .store import write_atomic

    path = Path(folder) / FILE
    text = json.dumps({"format": "praxicon-descriptions-file", "version": FORMAT_VERSION,
                       "takes": takes.to_dict(), "windows": windows.to_dict()})
    write_atomic(path, text + "\n")
    return path


def read_descriptions(folder, *, windows: bool = False) -> Descriptions:
    """The descriptions a praxicon folder holds (whole takes, or ``windows`` for parsing).

    Raises
    ------
    DescriptionError
        One line: the folder does not exist, is not a praxicon, has no descriptions (naming
        the command that learns them) or holds another version's (naming the rebuild).
    """
    from .store import load_index

    folder = Path(folder)
    if not folder.exists():
        raise DescriptionError(f"{folder}: no such praxicon folder")
    try:
        load_index(folder)
    except ValueError as exc:
        raise DescriptionError(str(exc)) from None
    path = folder / FILE
    try:
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise DescriptionError(f"{path}: no descriptions in this praxicon (learn them with "
                               f"'psgs praxicon describe {folder}')") from None
    except ValueError as exc:
        raise DescriptionError(f"{path}: not JSON ({exc})") from None
    if not isinstance(data, dict) or data.get("format") != "praxicon-descriptions-file":
        raise DescriptionError(f"{path}: not a praxicon descriptions file")
    if data.get("version") != FORMAT_VERSION:
        raise DescriptionError(f"{path}: descriptions of version {data.get('version')!r}, "
                               f"this psgs reads version {FORMAT_VERSION} (learn them again "
                               f"with 'psgs praxicon describe {folder}')")
    try:
        return Descriptions.from_dict(data["windows" if windows else "takes"])
    except (KeyError, TypeError, DescriptionError) as exc:
        raise DescriptionError(f"{path}: {exc}") from None
