"""Where the praxicon's commands write, checked before any work.

A file or folder that cannot be written was an error only once the work was done (a
timeline printed, an action learnt, a motion generated), and the work was lost:
:func:`check_folder` checks a file's place, :func:`check_writable_folder` a folder that is
written into or made. Each is one :class:`ValueError` line naming the path.
"""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["check_folder", "check_writable_folder"]


def check_folder(path, what: str = "the file") -> None:
    """ValueError (one line) unless ``path`` can be written: its folder exists, is a folder
    and is writable, and ``path`` itself is not a folder, nor a file that cannot be written.

    Examples
    --------
    >>> import tempfile
    >>> check_folder(tempfile.gettempdir())  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: ...: a folder, not the file
    >>> check_folder("/nonexistent/dir/walk.bvh", "the motion")
    Traceback (most recent call last):
    ...
    ValueError: /nonexistent/dir/walk.bvh: no folder /nonexistent/dir to write the motion into
    """
    if not isinstance(path, (str, os.PathLike)):  # Path(5) is a TypeError
        raise ValueError(f"{what} is written to a file's path, not {type(path).__name__}")
    path = Path(path)
    folder = path.parent
    if path.is_dir():
        raise ValueError(f"{path}: a folder, not {what}")
    if not folder.exists():
        raise ValueError(f"{path}: no folder {folder} to write {what} into")
    if not folder.is_dir():
        raise ValueError(f"{path}: {folder} is not a folder")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise ValueError(f"{path}: the folder {folder} is not writable")
    # a read-only file there: written over only after the work, which failed then
    if path.exists() and not os.access(path, os.W_OK):
        raise ValueError(f"{path}: the file is not writable (it is there, read-only)")


def check_writable_folder(path, what: str = "the folder") -> None:
    """ValueError (one line) unless files can be written into the folder ``path``: it is a
    writable folder, or it is not there and the nearest folder above it that is can be
    written into (it is made with its parents).

    Examples
    --------
    >>> import pathlib, tempfile
    >>> check_writable_folder(pathlib.Path(tempfile.mkdtemp()) / "new" / "px")
    >>> afile = pathlib.Path(tempfile.mkdtemp()) / "afile"
    >>> _ = afile.write_text("")
    >>> check_writable_folder(afile, "a praxicon folder")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: .../afile: a file, not a praxicon folder
    >>> check_writable_folder(afile / "px", "a praxicon folder")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    ValueError: .../afile/px: .../afile is not a folder to make a praxicon folder in
    """
    path = Path(path)
    there = path
    while not there.exists() and there.parent != there:  # what mkdir(parents=True) makes in
        there = there.parent
    if there == path:
        if not path.is_dir():
            raise ValueError(f"{path}: a file, not {what}")
        if not os.access(path, os.W_OK | os.X_OK):
            raise ValueError(f"{path}: the folder is not writable")
    elif not there.is_dir():
        raise ValueError(f"{path}: {there} is not a folder to make {what} in")
    elif not os.access(there, os.W_OK | os.X_OK):
        raise ValueError(f"{path}: the folder {there} is not writable (to make {what} in)")
