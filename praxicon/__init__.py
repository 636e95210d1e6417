"""praxicon: the morphology of every action in a motion database, and motion generated back.

Built on both ``psgs`` (grammar systems, inducers) and ``kinetology`` (motion
capture in, actiongrams out); ``psgs`` itself never imports either of them.
A praxicon is a folder (``docs/praxicon.md``): per action the joints that take
part, their morphemes, the grammar system, and the actuator-set matrix.

>>> from praxicon import read_dataset, build, Settings  # doctest: +SKIP
>>> build(read_dataset("../shared/data/mocap/cmu-mocap6"), "out/px")  # doctest: +SKIP
"""

from __future__ import annotations

import importlib

# public name -> module (imported on first use: matplotlib and dask stay unloaded until needed)
_LAZY = {
    "Performance": "datasets", "Action": "datasets", "read_dataset": "datasets",
    "read_datasets": "datasets", "DatasetError": "datasets",
    "Settings": "learn", "learn_action": "learn",
    "build": "builder", "BuildResult": "builder", "executor_for": "builder",
    "load_index": "store", "load_record": "store", "actuator_matrix": "store",
    "shared_patterns": "shared",
    "generate": "generation", "generate_motion": "generation",
    "draw_actuator_matrix": "pictures", "draw_morphemes": "pictures",
    "draw_shared_patterns": "pictures", "draw_praxicon": "pictures",
}

__all__ = list(_LAZY)


def __getattr__(name: str):
    if name in _LAZY:
        value = getattr(importlib.import_module(f".{_LAZY[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'praxicon' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
