"""praxicon: the morphology of every action in a motion database, and motion generated back.

Built on both ``psgs`` (grammar systems, inducers) and ``kinetology`` (motion
capture in, actiongrams out); ``psgs`` itself never imports either of them.
A praxicon is a folder (``docs/praxicon.md``): per action the joints that take
part, their morphemes, the grammar system, and the actuator-set matrix.
``load(folder)`` reads it as a :class:`~praxicon.records.Praxicon` of typed
:class:`~praxicon.records.ActionRecord` s; ``dump(praxicon, folder)`` writes one.

A praxicon of one action (the wave, two takes of the shared data named in a manifest);
``build(read_dataset("../shared/data/mocap/cmu-mocap6"), "out/px")`` learns a whole dataset:

>>> import pathlib, tempfile
>>> from praxicon import read_dataset, build
>>> data = pathlib.Path("../shared/data/mocap/bandai-namco-1/data").resolve()
>>> work = pathlib.Path(tempfile.mkdtemp())
>>> _ = (work / "m.csv").write_text("action,file\\n" + "".join(
...     f"bye,{data / f'dataset-1_bye_{style}_001.bvh'}\\n" for style in ("normal", "active")))
>>> result = build(read_dataset(work / "m.csv"), work / "px", progress=False)
>>> from praxicon import load
>>> px = load(work / "px")
>>> px.names, px["m.bye"].status, "LowerArm_R" in px["m.bye"].actuators
(('m.bye',), 'ok', True)
>>> px == result.praxicon
True
"""

from __future__ import annotations

from psgs._foundation.lazy import lazy_names

# public name -> module (imported on first use: matplotlib and dask stay unloaded until needed)
_LAZY = {
    "Performance": "datasets", "Action": "datasets", "read_dataset": "datasets",
    "read_datasets": "datasets", "DatasetError": "datasets",
    "Settings": "records", "learn_action": "learn",
    "build": "builder", "BuildResult": "builder", "executor_for": "builder",
    "load": "store", "dump": "store", "actuator_matrix": "store",
    "verify": "integrity", "repair": "integrity", "Verification": "integrity",
    "Praxicon": "records", "ActionRecord": "records", "JointRecord": "records",
    "ChannelMorpheme": "records", "PerformanceRecord": "records", "PraxiconError": "records",
    "shared_patterns": "shared",
    "generate": "generation", "generate_motion": "generation",
    "draw_actuator_matrix": "pictures", "draw_morphemes": "pictures",
    "draw_shared_patterns": "pictures", "draw_praxicon": "pictures",
    "recognise": "recognition", "recognise_many": "recognition", "Recognition": "recognition",
    "parse": "parsing", "Timeline": "parsing", "Span": "parsing",
    "describe": "description", "Descriptions": "description", "DescriptionError": "description",
}

__all__ = list(_LAZY)


__getattr__, __dir__ = lazy_names(__name__, _LAZY, listed=__all__)
