"""Reading the words argument of :func:`psgs.accepts` and :func:`psgs.nearest` for a PSGS."""

from __future__ import annotations

from ..errors import ValidationError
from ..model import PSGS, Terminal, Word, as_word

__all__ = ["coerce_words"]


def coerce_words(system: PSGS, words) -> tuple[Word, ...]:
    """One word per component, as tuples of terminals; a one-component system takes a word.

    Parameters
    ----------
    system : PSGS
        The system the words are for.
    words : sequence of words, or a word
        A word is a ``str`` of one-character terminals or a sequence of names or Terminals.

    Returns
    -------
    tuple of Word

    Raises
    ------
    ValidationError
        The wrong number of words, or something that is not a word.

    Examples
    --------
    >>> import psgs
    >>> gamma = psgs.load("grammars/paper_example.psgs")
    >>> [len(w) for w in coerce_words(gamma, ["ab", "", "c", "d"])]
    [2, 0, 1, 1]
    """
    n = len(system.components)
    if isinstance(words, str):
        if n != 1:
            raise ValidationError(f"give one word per component ({n}), not one string")
        words = (words,)
    try:
        words = tuple(words)
    except TypeError:
        raise ValidationError(f"words must be a sequence of words, not {words!r}") from None
    if n == 1 and words and all(isinstance(w, Terminal) for w in words):
        words = (words,)
    if len(words) != n:
        raise ValidationError(f"the system has {n} components but {len(words)} words were given")
    return tuple(_word(w) for w in words)


def _word(value) -> Word:
    """:func:`~psgs.model.as_word`, making one Terminal per distinct character of a str."""
    if isinstance(value, str):
        terminal = {ch: as_word(ch)[0] for ch in set(value)}
        return tuple(map(terminal.__getitem__, value))
    return as_word(value)
