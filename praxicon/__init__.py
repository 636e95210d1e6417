"""praxicon: the morphology of every action in a motion database, and motion generated back.

Built on both ``psgs`` (grammar systems, inducers) and ``kinetology`` (motion
capture in, actiongrams out); ``psgs`` itself never imports either of them.
A praxicon is a folder (``docs/praxicon.md``): per action the joints that take
part, their morphemes, the grammar system, and the actuator-set matrix.

A praxicon of one action (the wave, two takes of the shared data named in a manifest);
``build(read_dataset("../shared/data/mocap/cmu-mocap6"), "out/px")`` learns a whole dataset:

>>> import pathlib, tempfile
>>> from praxicon import read_dataset, build
>>> data = pathlib.Path("../shared/data/mocap/bandai-namco-1/data").resolve()
>>> work = pathlib.Path(tempfile.mkdtemp())
>>> _ = (work / "m.csv").write_text("action,file\\n" + "".join(
...     f"bye,{data / f'dataset-1_bye_{style}_001.bvh'}\\n" for style in ("normal", "active")))
>>> result = build(read_dataset(work / "m.csv"), work / "px", progress=False)
>>> (entry,) = result.index["actions"]
>>> entry["name"], entry["status"], "LowerArm_R" in entry["actuators"]
('m.bye', 'ok', True)
"""

from __future__ import annotations

from psgs._foundation.lazy import lazy_names

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


__getattr__, __dir__ = lazy_names(__name__, _LAZY, listed=__all__)
