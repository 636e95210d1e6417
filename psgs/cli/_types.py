"""The argument type of a grammar file: a path, or the name of an example shipped in psgs.

(The types every command shares, numbers and shares, are in :mod:`psgs._foundation.shell`.)
"""

from __future__ import annotations

from ..format import example_names, example_path

__all__ = ["example_names", "grammar_file"]


def grammar_file(text: str) -> str:
    """A grammar file's path: ``text`` itself when such a file exists, else a shipped example.

    ``psgs show paper_example`` reads the example from inside the package (as ``psgs.load``
    does); any other text is returned unchanged and fails to open with one line.
    """
    return str(example_path(text))


grammar_file.names_a_file = True  # '' (which exists: the current folder) refused by the shell
