"""The argument type of a grammar file: a path, or the name of an example shipped in psgs.

(The types every command shares, numbers and shares, are in :mod:`psgs._foundation.shell`.)
"""

from __future__ import annotations


def example_names() -> list[str]:
    """The example grammar systems shipped inside the package (``psgs/grammars/NAME.psgs``)."""
    from importlib import resources
    folder = resources.files("psgs").joinpath("grammars")
    return sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".psgs"))


def grammar_file(text: str) -> str:
    """A grammar file's path: ``text`` itself when such a file exists, else a shipped example.

    ``psgs show paper_example`` (or ``paper_example.psgs``) reads the example from inside the
    package when there is no file of that name in the working directory, so a pip user can
    follow the tour. Any other text is returned unchanged and fails to open with one line.
    """
    from importlib import resources
    from pathlib import Path
    if Path(text).exists() or any(sep in text for sep in ("/", "\\")):
        return text
    name = text[:-5] if text.endswith(".psgs") else text
    if name in example_names():
        return str(resources.files("psgs").joinpath("grammars", f"{name}.psgs"))
    return text
