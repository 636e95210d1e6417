"""The argument type of a grammar file: a path, or the name of an example shipped in psgs.

(The types every command shares, numbers and shares, are in :mod:`psgs._foundation.shell`.)
"""

from __future__ import annotations

__all__ = ["example_names", "grammar_file"]


def example_names() -> list[str]:
    """The names of the examples shipped in psgs (:func:`psgs.format.example_names`).

    Returns
    -------
    list of str
        The names, each usable where a grammar file is asked for.

    Examples
    --------
    >>> "paper_example" in example_names()
    True
    """
    # psgs.format imports the file reader and its parser (lark): read when asked, so that
    # building the command's parser (--help, --version) does not
    from ..format import example_names as shipped

    return shipped()


def grammar_file(text: str) -> str:
    """A grammar file's path: ``text`` itself when such a file exists, else a shipped example.

    ``psgs show paper_example`` reads the example from inside the package (as ``psgs.load``
    does); any other text is returned unchanged and fails to open with one line.

    Parameters
    ----------
    text : str
        The argument's text.

    Returns
    -------
    str
        The path to open.

    Examples
    --------
    >>> grammar_file("paper_example").endswith("paper_example.psgs")
    True
    >>> grammar_file("no/such.psgs")
    'no/such.psgs'
    """
    from ..format import example_path  # when an argument is read, not when the parser is made

    return str(example_path(text))


grammar_file.names_a_file = True  # '' (which exists: the current folder) refused by the shell
