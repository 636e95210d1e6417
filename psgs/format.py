"""Reading the psgs text format (see ``docs/format.md``), and every file psgs reads.

A file describes one PSGS or one PCGS::

    psgs Sync
    mode parallel
    component G1 start S
      p1: S -> "a" S
      p2: S -> "a"
    component G2 start T
      q1: T -> "b" T
      q2: T -> "b"
    sync
      (p1, q1)
      (p2, q2)

The text is split into lines by a Lark grammar shipped with the package
(``psgs/format.lark``) and read into the model's values by :mod:`psgs._format_reader`.
Every mistake, of syntax or of meaning, becomes one :class:`~psgs.errors.FormatError`
naming ``source:line:column``. :func:`load` is psgs's one file reader (grammar systems,
examples by name, actiongrams); writing is :mod:`psgs.writing`'s (``dump``).
"""

from __future__ import annotations

from importlib import resources
from os import PathLike
from pathlib import Path

from ._foundation.files import decode_utf8, read_text
from ._format_reader import read_system
from .errors import ValidationError
from .model import PCGS, PSGS

__all__ = ["loads", "load", "example_names", "example_path", "ACTIONGRAM_SUFFIXES"]


def loads(text: str | bytes, source: str = "<string>") -> PSGS | PCGS:
    """Read a PSGS or a PCGS from text in the psgs format.

    ``source`` names the text in error messages. Bytes are decoded as UTF-8.
    Parameters
    ----------
    text : str or bytes
        The system in the psgs text format (bytes are decoded as UTF-8).
    source : str, default "<string>"
        The name error messages give.

    Returns
    -------
    PSGS or PCGS
        Whichever the header line (``psgs NAME`` or ``pcgs NAME``) says.

    Raises
    ------
    FormatError
        For malformed text, as ``source:line:col: message``; also for a system that is not
        valid (a tuple of the wrong arity, ...), at the place it is written.

    Examples
    --------
    >>> system = loads('''
    ... psgs Copy
    ... component G1 start S
    ...   p1: S -> "a" S
    ...   p2: S -> "a"
    ... component G2 start T
    ...   q1: T -> "b" T
    ...   q2: T -> "b"
    ... sync
    ...   (p1, q1)
    ...   (p2, q2)
    ... ''')
    >>> system.name, len(system.sync), system.mode
    ('Copy', 2, 'parallel')

    >>> loads("psgs Broken", source="broken.psgs")
    Traceback (most recent call last):
    ...
    psgs.errors.FormatError: broken.psgs:1:...
    """
    if not isinstance(source, str):  # it was found out only by an error: a TypeError then
        raise ValidationError(f"source must be a str (the name errors give), not {source!r}")
    if isinstance(text, (bytes, bytearray)):
        text = decode_utf8(bytes(text), source)
    if not isinstance(text, str):
        raise TypeError(f"loads expects text, not {type(text).__name__}")
    if text.startswith("\ufeff"):
        text = text[1:]  # a byte-order mark is not content; columns of line 1 shift by one
    if not text.endswith("\n"):
        text += "\n"
    return read_system(text, source)


#: Suffixes of actiongram files (``psgs.load`` reads every other file as a grammar system).
ACTIONGRAM_SUFFIXES = (".actiongram", ".json")


def example_names() -> list[str]:
    """The example grammar systems shipped inside the package, loadable by name.

    Returns
    -------
    list of str
        Names such as ``"paper_example"`` (the files are ``psgs/grammars/NAME.psgs``).

    Examples
    --------
    >>> "paper_example" in example_names()
    True
    """
    folder = resources.files("psgs").joinpath("grammars")
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".psgs"))


def example_path(text: str | PathLike) -> str | PathLike:
    """``text`` itself when such a file exists, else the shipped example it names, else ``text``.

    ``paper_example`` (or ``paper_example.psgs``) names the example inside the package when
    there is no file of that name in the working directory, so a pip user can follow the tour.
    Text holding a path separator is always a path.

    Parameters
    ----------
    text : str or PathLike
        A path, or an example's name.

    Returns
    -------
    str or PathLike
        The path to read.

    Examples
    --------
    >>> example_path("paper_example").endswith("paper_example.psgs")
    True
    >>> example_path("no/such.psgs")
    'no/such.psgs'
    """
    name = str(text)
    if Path(name).exists() or any(sep in name for sep in ("/", "\\")):
        return text
    stem = name[:-5] if name.endswith(".psgs") else name
    if stem in example_names():
        return str(resources.files("psgs").joinpath("grammars", f"{stem}.psgs"))
    return text


def load(path: str | PathLike, *, kind: str | None = None):
    """Read a file: a grammar system (PSGS or PCGS), an example by name, or an actiongram.

    ``kind=None`` decides by the name: ``.actiongram`` and ``.json`` files are actiongrams
    (:class:`psgs.Actiongram`; JSON when the name ends in ``.json``, else the text form),
    every other file a grammar system in the text format, whose header line says PSGS or
    PCGS. A name with no such file, such as ``"paper_example"``, reads the example shipped
    in the package (:func:`example_names`). Errors name the file:
    ``grammars/x.psgs:3:7: missing arrow ...``.

    Parameters
    ----------
    path : str or PathLike
        The file, or an example's name.
    kind : {None, "system", "actiongram"}, default None
        What the file holds, when its name does not say (an actiongram named ``walk.txt``).

    Returns
    -------
    PSGS, PCGS or Actiongram

    Raises
    ------
    FormatError
        For malformed text or bytes that are not UTF-8, naming ``path:line:col``; for an
        actiongram file that holds no string.
    ValidationError
        For another ``kind``, or a ``path`` that is no str or os.PathLike.
    FileNotFoundError
        When the file does not exist (and is no example's name).

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("paper_example")
    >>> gamma.name, len(gamma.components), len(gamma.sync)
    ('Gamma', 4, 8)
    >>> psgs.load("grammars/paper_example.psgs") == gamma
    True
    """
    if kind not in (None, "system", "actiongram"):
        raise ValidationError(f"kind must be None, 'system' or 'actiongram', not {kind!r}")
    if not isinstance(path, (str, PathLike)):  # pathlib's TypeError would name no argument
        raise ValidationError(f"load reads a path (a str or os.PathLike), not {path!r}")
    if kind == "actiongram" or (kind is None
                                and Path(path).suffix.lower() in ACTIONGRAM_SUFFIXES):
        from .actiongram import _read_file

        return _read_file(path)
    path = example_path(path)
    return loads(read_text(path), source=str(path))

