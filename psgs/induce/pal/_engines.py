"""Which engine searches motifs: numpy's array passes or numba's compiled loops (same output).

``engine="auto"`` (PAL's default) takes the compiled engine when numba can be imported
(``pip install 'psgs[fast]'``) and numpy's otherwise; ``"numpy"`` and ``"numba"`` ask for one.
The choice is PAL's parameter, never a setting held anywhere.
"""

from __future__ import annotations

from functools import lru_cache

__all__: list[str] = []  # private: the PAL parameter ``engine`` is the interface

ENGINES = ("auto", "numpy", "numba")


@lru_cache(maxsize=1)
def _numba_missing() -> str:
    """Why numba cannot be had (its import error), or "" when it imports; looked up once."""
    try:
        import numba  # noqa: F401  (only to know whether it imports)
    except ImportError as error:
        return str(error) or "numba is not installed"
    return ""


def select(engine: str = "auto") -> str:
    """The engine that runs for ``engine`` (one of :data:`ENGINES`): "numpy" or "numba".

    Raises ``ValueError`` for another name and ``ImportError`` when ``"numba"`` is asked for
    and numba does not import.
    """
    if not isinstance(engine, str) or engine not in ENGINES:
        raise ValueError(f"engine must be one of {', '.join(map(repr, ENGINES))}, "
                         f"not {engine!r}")
    if engine == "numpy":
        return "numpy"
    missing = _numba_missing()
    if not missing:
        return "numba"
    if engine == "numba":
        raise ImportError(f"engine='numba' needs numba, which does not import here "
                          f"({missing}); install it with `pip install 'psgs[fast]'`, or use "
                          f"engine='numpy'")
    return "numpy"
