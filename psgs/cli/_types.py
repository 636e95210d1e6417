"""argparse value types shared by the subcommands: each refuses bad text with one clear line."""

from __future__ import annotations

import argparse
import math


def _whole(text: str, minimum: int) -> int:
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a whole number") from None
    if value < minimum:
        raise argparse.ArgumentTypeError(
            f"{value} is negative" if minimum == 0 else f"must be at least {minimum}")
    return value


def natural(text: str) -> int:
    """A whole number ≥ 0 (lengths, seeds)."""
    return _whole(text, 0)


def positive_int(text: str) -> int:
    """A whole number ≥ 1 (budgets, counts, workers)."""
    return _whole(text, 1)


def _number(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"{text!r} is not a finite number")
    return value


def positive_float(text: str) -> float:
    """A finite number > 0 (seconds)."""
    value = _number(text)
    if not value > 0:
        raise argparse.ArgumentTypeError("must be positive")
    return value


def share(text: str) -> float:
    """A number from 0 to 1 (noise levels, fractions)."""
    value = _number(text)
    if not 0 <= value <= 1:
        raise argparse.ArgumentTypeError(f"{text} is not between 0 and 1")
    return value


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
