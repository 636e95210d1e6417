"""The checks of names and numbers that the actiongram modules share (one job: say what is wrong).

Kept below both :mod:`psgs.actiongram` and :mod:`psgs._actiongram_extras` so that neither has to
import the other for them.
"""

from __future__ import annotations

import math

__all__: list[str] = []  # private helpers


def _shown(value: object, limit: int = 40) -> str:
    """``repr(value)``, cut to about ``limit`` characters so one bad token keeps errors one line."""
    text = repr(value)
    return text if len(text) <= limit else text[:limit - 5] + "...'" + f" ({len(str(value))} chars)"


def _not_unicode(text: str) -> bool:
    """True for text with a lone surrogate (JSON ``"\\ud800"``): it cannot be written as UTF-8."""
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:
        return True
    return False


def _bad_name(name: object) -> str | None:
    """Why ``name`` cannot name an actuator, or None when it can."""
    if not isinstance(name, str) or not name:
        return "an actuator name must be non-empty text"
    if _not_unicode(name):
        return f"actuator name {_shown(name)} is not valid Unicode (a lone surrogate)"
    if any(ch.isspace() for ch in name) or "@" in name or ":" in name or name.startswith("#"):
        return (f"actuator name {_shown(name)} must have no white space, '@' or ':' and not "
                f"start with '#'")
    return None


def _finite(value: int | float) -> bool:
    """``math.isfinite``, False for an int too large for a float (instead of OverflowError)."""
    try:
        return math.isfinite(value)
    except OverflowError:
        return False
