"""Which engine searches motifs: numpy's array passes or numba's compiled loops (same output).

``engine="auto"`` (PAL's default) takes the compiled engine when numba can be imported
(``pip install 'psgs[fast]'``) and numpy's otherwise; ``"numpy"`` and ``"numba"`` ask for one.
The choice is PAL's parameter, never a setting held anywhere; how it is made is
:mod:`psgs._foundation.engines`'s, shared with kinetology's segmentation.
"""

from __future__ import annotations

from ..._foundation.engines import ENGINES, resolve  # noqa: F401  (ENGINES: the learner's)

__all__: list[str] = []  # private: the PAL parameter ``engine`` is the interface


def select(engine: str = "auto") -> str:
    """The engine that runs for ``engine`` (one of :data:`ENGINES`): "numpy" or "numba".

    The phase modules still compare this name at their call sites; the shared design hands
    them a table of functions instead (``psgs._foundation.engines.select``).
    Raises ``ValidationError`` (a ``ValueError``) for another name and ``MissingDependency``
    (an ``ImportError``) when ``"numba"`` is asked for and numba does not import.
    """
    return resolve(engine)

