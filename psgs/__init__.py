"""psgs: parallel grammar systems, and learning them from parallel symbol streams.

The formal core (``psgs.model``) holds immutable values: symbols, rules,
component grammars, :class:`PSGS` and :class:`PCGS`. Around it, plain
functions: reading and writing the text format, deriving, enumerating,
checking membership, exporting to Lark and networkx. Inducers
(``psgs.induce``) learn a PSGS from an :class:`Actiongram`.

Names are imported on first use, so ``import psgs`` stays cheap.
"""

from __future__ import annotations

import importlib

from .errors import BoundReached, FormatError, PSGSError, ValidationError
from .model import (IDLE, PCGS, PSGS, Grammar, Nonterminal, Query, Rule, Terminal, as_word,
                    word)

__version__ = "0.1.0"

# public name -> module that defines it (imported lazily)
_LAZY = {
    "loads": "format", "load": "format", "dumps": "format", "dump": "format",
    "to_lark": "lark_export", "from_lark_name": "lark_export",
    "to_networkx": "graph",
    "Configuration": "derivation", "Step": "derivation", "Derivation": "derivation",
    "initial_configuration": "derivation", "applicable_steps": "derivation",
    "apply_step": "derivation", "random_derivation": "derivation", "language": "derivation",
    "Language": "derivation",
    "accepts": "membership", "Acceptance": "membership",
    "Actiongram": "actiongram", "load_actiongram": "actiongram",
}
_SUBMODULES = {"induce", "synthetic", "strategies", "model", "errors", "format", "derivation",
               "membership", "actiongram", "lark_export", "graph"}

__all__ = [
    "PSGSError", "ValidationError", "FormatError", "BoundReached",
    "Terminal", "Nonterminal", "Query", "Rule", "Grammar", "PSGS", "PCGS", "IDLE", "word",
    "as_word", *_LAZY,
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
    return sorted(set(__all__) | _SUBMODULES | {"__version__"})
