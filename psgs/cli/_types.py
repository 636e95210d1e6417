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
