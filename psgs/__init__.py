"""psgs: parallel grammar systems, and learning them from parallel symbol streams.

The formal core (``psgs.model``) holds immutable values: symbols, rules,
component grammars, :class:`PSGS` and :class:`PCGS`. Around it, plain
functions: reading and writing the text format, deriving, enumerating,
checking membership, exporting to Lark and networkx. Inducers
(``psgs.induce``) learn a PSGS from an :class:`Actiongram`. How the modules
are layered is pictured in ``docs/index.md``.

Names are imported on first use, so ``import psgs`` stays cheap.
"""

from __future__ import annotations

import importlib

from .errors import BoundReached, FormatError, PSGSError, ValidationError
from .model import IDLE, PCGS, PSGS, Grammar, Nonterminal, Query, Rule, Terminal, as_word

__version__ = "0.1.0"

# module -> the public names it defines (or re-exports); each is in that module's __all__
# (tests/core/test_architecture.py checks it), and is imported on first use
_PUBLIC = {
    "format": ("loads", "load", "dumps", "dump"),
    "lark_export": ("to_lark", "from_lark_name"),
    "graph": ("to_networkx",),
    "derivation": ("Configuration", "Step", "Derivation", "initial_configuration",
                   "applicable_steps", "apply_tuple", "random_derivation"),
    "enumeration": ("language", "Language"),
    "membership": ("accepts", "Acceptance", "nearest", "Nearest"),
    "actiongram": ("Actiongram", "load_actiongram"),
}
_LAZY = {name: module for module, names in _PUBLIC.items() for name in names}
# modules reachable as attributes (``psgs.strategies`` needs hypothesis, the test extra)
_SUBMODULES = {"induce", "synthetic", "strategies", "model", "errors", "format", "derivation",
               "membership", "actiongram", "lark_export", "graph", "analysis", "steps",
               "enumeration", "notation", "search", "budget"}

__all__ = [
    "PSGSError", "ValidationError", "FormatError", "BoundReached",
    "Terminal", "Nonterminal", "Query", "Rule", "Grammar", "PSGS", "PCGS", "IDLE", "as_word",
    *_LAZY,
]


def __getattr__(name: str):
    if name in _LAZY:
        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    if name in _SUBMODULES:
        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'psgs' has no attribute {name!r}")


def __dir__():
    # the public names only: help(psgs) and tab completion look at every name listed here,
    # and listing the submodules would import them all (strategies needs hypothesis)
    return sorted(set(__all__) | {"__version__"})
