"""Generation: K synchronised copies, BVH written and read back, re-segmented to the morphemes."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from praxicon import build, read_dataset
from praxicon.generation import Generated, derive_copies, generate, generate_motion, \
    is_smooth_cycle
from praxicon_fixtures import CHANNELS, SHARED, needs_mocap, take


def _record(pattern, durations, displacements, rate=30.0):
    from psgs import dumps
    from psgs.induce.base import build_system

    system = build_system([("arm_rx", tuple(pattern)), ("leg_rx", tuple(pattern))])
    morpheme = {"kinetemes": list(pattern), "durations": list(durations),
                "displacements": list(displacements)}
    return {"name": "t", "status": "ok", "actuators": ["arm", "leg"], "system": dumps(system),
            "frame_rate": rate, "component_names": {"arm.rx": "arm_rx", "leg.rx": "leg_rx"},
            "joints": {"arm": {"channels": ["arm.rx"], "morphemes": {"arm.rx": morpheme}},
                       "leg": {"channels": ["leg.rx"], "morphemes": {"leg.rx": morpheme}}},
            "mean_pose": {c: 5.0 for c in CHANNELS}}


def test_derive_copies_repeats_every_component_k_times():
    import psgs

    words = derive_copies(psgs.load("grammars/paper_example.psgs"), 3)
    assert ["".join(w) for w in words] == [p * 3 for p in ("abcdbcad", "bcadabcd", "cdabcdab",
                                                            "abcdbcad")]


# kinetemes the default segmentation resolves at 30 fps: its acceleration dead band is
# 200 deg/s², and a 15° half-swing in 0.3 s accelerates at about 2 * 15 / 0.3² = 333 deg/s²
@settings(max_examples=40, deadline=None)
@given(start=st.integers(0, 3), repeat=st.integers(1, 4),
       durations=st.lists(st.floats(0.12, 0.3), min_size=4, max_size=4),
       sizes=st.lists(st.floats(15.0, 40.0), min_size=4, max_size=4))
def test_a_smooth_morpheme_comes_back_from_segmentation(start, repeat, durations, sizes):
    pattern = ("BGRY" * 2)[start:start + 4]
    signs = [1 if k in "BG" else -1 for k in pattern]
    record = _record(pattern, durations, [s * x for s, x in zip(signs, sizes)])
    motion, words, methods = generate_motion(record, repeat, source_motion=take(1))
    generated = Generated(motion, "t", repeat, ("arm", "leg"), tuple(words), words, {}, methods)
    assert words["arm.rx"] == tuple(pattern) * repeat
    assert generated.round_trip() == {"arm.rx": True, "leg.rx": True}
    # the still channels stay at the mean pose; the arm swings around its mean
    assert np.allclose(motion.column("head.ry"), 5.0)
    assert abs(motion.column("arm.rx").mean() - 5.0) < 1e-9


def test_is_smooth_cycle():
    assert is_smooth_cycle("BGRY") and is_smooth_cycle("GRYRYB") and is_smooth_cycle("YBGRY")
    assert not is_smooth_cycle("RYB") and not is_smooth_cycle("B")


def test_generated_bvh_reads_back_with_kinetology_and_an_independent_reader(manifest, tmp_path):
    import bvh
    import kinetology

    build(read_dataset(manifest), tmp_path / "px", progress=False, log=lambda s: None)
    out = tmp_path / "wave.bvh"
    generated = generate(tmp_path / "px", "moves.wave", repeat=3, output=out,
                         plot=tmp_path / "wave.png")
    back = kinetology.read(out)
    assert back.channels == generated.motion.channels
    assert np.abs(back.values - generated.motion.values).max() < 0.01
    tree = bvh.Bvh(out.read_text())
    assert tree.nframes == generated.motion.frames
    assert abs(tree.frame_time - 1 / 30) < 1e-6
    frames = np.array(tree.frames, dtype=float)
    assert np.abs(frames - generated.motion.values).max() < 0.01
    assert (tmp_path / "wave.png").stat().st_size > 1000
    # the morpheme of a smooth cycle comes back: K copies in the re-segmented string
    smooth = [c for c in generated.channels if is_smooth_cycle(generated.words[c])]
    assert smooth and all(generated.round_trip(interior=True)[c] for c in smooth)


def test_nothing_to_generate_is_a_clear_error(manifest, tmp_path):
    build(read_dataset(manifest), tmp_path / "px", progress=False, log=lambda s: None)
    with pytest.raises(ValueError, match="was not learnt: 1 usable performance"):
        generate(tmp_path / "px", "moves.alone")
    with pytest.raises(ValueError, match="no action 'moves.nope'"):
        generate(tmp_path / "px", "moves.nope")
    with pytest.raises(ValueError, match="repeat must be"):
        generate(tmp_path / "px", "moves.wave", repeat=0)


@needs_mocap()
def test_real_action_generates_and_reads_back(tmp_path):
    import kinetology

    manifest = tmp_path / "bye.csv"
    data = SHARED / "bandai-namco-1" / "data"
    styles = ("normal", "active", "happy", "proud")
    manifest.write_text("action,file\n" + "".join(
        f"byebye,{data / f'dataset-1_byebye_{s}_001.bvh'}\n" for s in styles))
    build(read_dataset(manifest), tmp_path / "px", progress=False, log=lambda s: None)
    out = tmp_path / "bye.bvh"
    generated = generate(tmp_path / "px", "bye.byebye", repeat=4, output=out)
    back = kinetology.read(out)
    assert back.skeleton.names == kinetology.read(data / "dataset-1_byebye_normal_001.bvh") \
        .skeleton.names  # the source skeleton
    assert np.abs(back.values - generated.motion.values).max() < 0.01
    assert generated.actuators and any(generated.round_trip(interior=True).values())
