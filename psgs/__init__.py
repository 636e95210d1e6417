"""psgs: parallel grammar systems, and learning them from parallel symbol streams.

The formal core (``psgs.model``) holds immutable values: symbols, rules,
component grammars, :class:`PSGS` and :class:`PCGS`. Around it, plain
functions: reading and writing files (``load``/``dump``; examples by name:
``psgs.load("paper_example")``), deriving, enumerating, checking membership,
exporting to Lark and networkx. Inducers (``psgs.induce``) learn a PSGS from
an :class:`Actiongram`. How the modules are layered is pictured in
``docs/architecture.md``.

Names are imported on first use, so ``import psgs`` stays cheap.
"""

from __future__ import annotations

from ._foundation import __version__
from ._foundation.lazy import lazy_names
from .errors import BoundReached, FormatError, PSGSError, ValidationError
from .model import IDLE, PCGS, PSGS, Grammar, Nonterminal, Query, Rule, Terminal, as_word

from . import _display  # noqa: F401  (gives systems and actiongrams their notebook pictures)


# module -> the public names it defines (or re-exports); each is in that module's __all__
# (tests/core/test_architecture.py checks it), and is imported on first use
_PUBLIC = {
    "format": ("loads", "load"),
    "writing": ("dumps", "dump"),
    "lark_export": ("to_lark", "from_lark_name"),
    "graph": ("to_networkx",),
    # the step engine's own values (Configuration, Step, apply_tuple) stay in their modules
    "derivation": ("Derivation", "initial_configuration", "applicable_steps",
                   "random_derivation"),
    "enumeration": ("language", "Language"),
    "membership": ("accepts", "Acceptance"),
    "actiongram": ("Actiongram",),
}
_LAZY = {name: module for module, names in _PUBLIC.items() for name in names}
# modules reachable as attributes (``psgs.strategies`` needs hypothesis, the test extra)
_SUBMODULES = {"induce", "strategies", "model", "errors", "format", "writing", "derivation",
               "membership", "actiongram", "lark_export", "graph", "analysis", "steps",
               "enumeration", "notation", "search", "budget"}

__all__ = [
    "PSGSError", "ValidationError", "FormatError", "BoundReached",
    "Terminal", "Nonterminal", "Query", "Rule", "Grammar", "PSGS", "PCGS", "IDLE", "as_word",
    *_LAZY,
]


# help(psgs) and tab completion look at every name dir() lists, and listing the submodules
# would import them all (strategies needs hypothesis): the public names only
__getattr__, __dir__ = lazy_names(__name__, _LAZY, submodules=_SUBMODULES,
                                  listed=[*__all__, "__version__"])
