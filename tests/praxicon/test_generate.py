"""Generation: K synchronised copies, BVH written and read back, re-segmented to the morphemes."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from praxicon import build, read_dataset
from praxicon.generation import Generated, derive_copies, generate, generate_motion, \
    is_smooth_cycle
from praxicon_fixtures import CHANNELS, SHARED, needs_mocap, take


def _record(pattern, durations, displacements, rate=30.0, legs=None):
    from psgs import dumps
    from psgs.induce.base import build_system

    from praxicon.records import ActionRecord, ChannelMorpheme, JointRecord

    leg = legs or (pattern, durations, displacements)
    system = build_system([("arm_rx", tuple(pattern)), ("leg_rx", tuple(leg[0]))])
    morpheme = ChannelMorpheme(tuple(pattern), tuple(durations), tuple(displacements))
    other = ChannelMorpheme(tuple(leg[0]), tuple(leg[1]), tuple(leg[2]))
    return ActionRecord("t", "d", "t", status="ok", actuators=("arm", "leg"),
                        system=dumps(system), frame_rate=rate,
                        component_names=(("arm.rx", "arm_rx"), ("leg.rx", "leg_rx")),
                        joints=(JointRecord("arm", (("arm.rx", morpheme),)),
                                JointRecord("leg", (("leg.rx", other),))),
                        all_joints=tuple(dict.fromkeys(c.split(".")[0] for c in CHANNELS)),
                        mean_pose=tuple((c, 5.0) for c in sorted(CHANNELS)))


def _generated(record, repeat):
    motion, words, methods = generate_motion(record, repeat, source_motion=take(1))
    return Generated(motion, "t", repeat, ("arm", "leg"), tuple(words), words, {}, methods)


def _signs(pattern):
    return [1 if k in "BG" else -1 for k in pattern]


@st.composite
def morphemes(draw, smooth: bool):
    """A kineteme pattern the segmentation can emit (neighbours differ, read cyclically)."""
    if smooth:  # one or two swings B G R Y, from any phase
        start, swings = draw(st.integers(0, 3)), draw(st.integers(1, 2))
        return ("BGRY" * 3)[start:start + 4 * swings]
    pattern = [draw(st.sampled_from("BGRY"))]
    for _ in range(draw(st.integers(1, 4))):
        pattern.append(draw(st.sampled_from([k for k in "BGRY" if k != pattern[-1]])))
    if len(pattern) > 2 and pattern[0] == pattern[-1]:
        pattern.pop()  # the repeated copies would merge these two
    return "".join(pattern)


def test_derive_copies_repeats_every_component_k_times():
    import psgs

    words = derive_copies(psgs.load("grammars/paper_example.psgs"), 3)
    assert ["".join(w) for w in words] == [p * 3 for p in ("abcdbcad", "bcadabcd", "cdabcdab",
                                                            "abcdbcad")]


# a smooth cycle comes back whatever its durations (down to 2 frames a kineteme at 30 fps) and
# displacements (down to 0.05 degrees, under every dead band: the correction layer lifts them)
@settings(max_examples=25, deadline=None)
@given(pattern=morphemes(smooth=True), repeat=st.integers(1, 4), data=st.data())
def test_a_smooth_morpheme_comes_back_from_segmentation(pattern, repeat, data):
    n = len(pattern)
    frames = data.draw(st.lists(st.integers(2, 10), min_size=n, max_size=n))
    sizes = data.draw(st.lists(st.floats(0.05, 60.0), min_size=n, max_size=n))
    record = _record(pattern, [f / 30 for f in frames],
                     [s * x for s, x in zip(_signs(pattern), sizes)])
    generated = _generated(record, repeat)
    assert generated.words["arm.rx"] == tuple(pattern) * repeat
    assert generated.round_trip() == {"arm.rx": True, "leg.rx": True}
    assert generated.round_trip(by="actuator") == {"arm": True, "leg": True}
    # the still channels stay at the mean pose; the arm swings around its mean
    assert np.allclose(generated.motion.column("head.ry"), 5.0)
    assert abs(generated.motion.column("arm.rx").mean() - 5.0) < 1e-9


# any pattern, with changes no smooth angle makes (R -> B, G -> Y, B -> Y, ...): given time
# for them (2/3 s a kineteme) and at least two copies it comes back exactly, the arm and the
# leg in step (one copy of a two-kineteme pattern may not: the recording's ends leave it no
# frames to turn in)
@settings(max_examples=10, deadline=None)
@given(arm=morphemes(smooth=False), leg=morphemes(smooth=False), repeat=st.integers(2, 3),
       data=st.data())
def test_any_morpheme_comes_back_from_segmentation_given_time(arm, leg, repeat, data):
    def drawn(pattern):
        n = len(pattern)
        frames = data.draw(st.lists(st.integers(22, 30), min_size=n, max_size=n))
        sizes = data.draw(st.lists(st.floats(0.5, 5.0), min_size=n, max_size=n))
        return pattern, [f / 30 for f in frames], [s * x for s, x in
                                                  zip(_signs(pattern), sizes)]

    record = _record(*drawn(arm), legs=drawn(leg))
    generated = _generated(record, repeat)
    assert generated.round_trip() == {"arm.rx": True, "leg.rx": True}, generated.methods
    assert all(not m.kind.startswith("failed") for m in generated.methods.values())
    assert generated.motion.frames == round(repeat * np.median(
        [sum(m.durations) for m in record.morphemes().values()]) * 30) + 1


def test_the_correction_layer_makes_a_change_of_both_signs_in_one_frame():
    # R -> B: falling and braking, then rising and speeding up, in one frame; the quartic
    # base reads R Y B there (it must brake to turn), the corrected curve reads R B
    pattern, durations, sizes = "RYRB", [0.6, 0.6, 0.6, 0.6], [-3.0, 1.0, -3.0, 5.0]
    generated = _generated(_record(pattern, durations, sizes), 3)
    method = generated.methods["arm.rx"]
    assert method.kind == "corrected" and 0 < method.change < 30
    assert generated.resegmented()["arm.rx"] == tuple(pattern) * 3


def test_what_cannot_be_made_is_said_not_hidden():
    # B Y B Y in 1/10 s a kineteme: the velocity must fall through zero while the acceleration
    # stays inside its dead band, which takes longer than that: no curve does it
    generated = _generated(_record("BY", [0.1, 0.1], [1.0, -1.0]), 3)
    assert generated.methods["arm.rx"].kind.startswith("failed: ")
    assert generated.round_trip()["arm.rx"] is False
    with pytest.raises(ValueError, match="by must be"):
        generated.round_trip(by="joint")


def test_is_smooth_cycle():
    assert is_smooth_cycle("BGRY") and is_smooth_cycle("GRYRYB") and is_smooth_cycle("YBGRY")
    assert not is_smooth_cycle("RYB") and not is_smooth_cycle("B")


def test_generated_bvh_reads_back_with_kinetology_and_an_independent_reader(manifest, tmp_path):
    import bvh
    import kinetology

    build(read_dataset(manifest), tmp_path / "px", progress=False, log=lambda s: None)
    out = tmp_path / "wave.bvh"
    seen = []
    generated = generate(tmp_path / "px", "moves.wave", repeat=3, output=out,
                         plot=tmp_path / "wave.png", progress=lambda *a: seen.append(a))
    # one call per generated channel, counting up to all of them
    assert [c for _, _, c in seen] == list(generated.channels)
    assert [(d, t) for d, t, _ in seen] == [(k + 1, len(seen)) for k in range(len(seen))]
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
    for repeat in (3, 1):
        generated = generate(tmp_path / "px", "bye.byebye", repeat=repeat, output=out)
        back = kinetology.read(out)
        assert back.skeleton.names == kinetology.read(
            data / "dataset-1_byebye_normal_001.bvh").skeleton.names  # the source skeleton
        assert np.abs(back.values - generated.motion.values).max() < 0.01
        # the file, read back and segmented, gives what the motion in memory gives
        again = kinetology.segments(back, channels=list(generated.channels))
        assert {c: again.symbols(again.channels.index(c)) if c in again.channels else ()
                for c in generated.channels} == generated.resegmented()
        # re-segmented, every actuator channel is its morpheme K times, and so every actuator
        exact = generated.round_trip()
        assert exact and all(exact.values()), generated.methods
        assert all(generated.round_trip(by="actuator").values())
        assert not any(m.kind.startswith("failed") for m in generated.methods.values())


@needs_mocap()
def test_real_walk_comes_back_whole(tmp_path):
    # four takes of the sideways walk: with morphemes read off PAL's grid, Foot_R.ry carried a
    # change no take makes and did not come back; each morpheme is now a stretch of a take
    manifest = tmp_path / "walk.csv"
    data = SHARED / "bandai-namco-1" / "data"
    manifest.write_text("action,file\n" + "".join(
        f"walk-left,{data / f'dataset-1_walk-left_{s}_001.bvh'}\n"
        for s in ("normal", "active", "happy", "proud")))
    build(read_dataset(manifest), tmp_path / "px", progress=False, log=lambda s: None)
    generated = generate(tmp_path / "px", "walk.walk-left", repeat=3)
    exact = generated.round_trip()
    assert len(exact) >= 20 and all(exact.values()), {
        c: generated.methods[c] for c, ok in exact.items() if not ok}


def _gesture(seed: int, seconds: float, at: float, rate: float = 30.0):
    """One raise of the arm (two channels) held for half a second, at ``at`` s: no repetition."""
    from kinetology import Motion
    from kinetology.bvh_writer import star_skeleton

    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * rate)) / rate
    up = 1 / (1 + np.exp(-(t - at) * 10)) - 1 / (1 + np.exp(-(t - at - 0.5) * 10))
    values = np.column_stack([0.2 * rng.standard_normal(t.size), 70 * up + 5, 30 * up,
                              0.2 * rng.standard_normal(t.size),
                              0.2 * rng.standard_normal(t.size)])
    return Motion(values, CHANNELS, rate, star_skeleton(CHANNELS), f"point{seed}")


@pytest.fixture
def gestures(tmp_path):
    """A praxicon of one action, a gesture made once per take, early, late or midway."""
    from kinetology import write_bvh

    lines = ["action,file"]
    for seed, (seconds, at) in enumerate([(4.0, 0.5), (4.5, 2.8), (3.5, 1.5)]):
        write_bvh(_gesture(seed, seconds, at), tmp_path / f"point_{seed}.bvh")
        lines.append(f"point,point_{seed}.bvh")
    (tmp_path / "gestures.csv").write_text("\n".join(lines) + "\n")
    build(read_dataset(tmp_path / "gestures.csv"), tmp_path / "px", progress=False,
          log=lambda s: None)
    return tmp_path / "px"


def test_an_action_without_repetition_is_its_performances_course(gestures, tmp_path):
    import kinetology

    from praxicon import load
    from praxicon.acyclic import performed_motion

    record = load(gestures)["gestures.point"]
    assert record.learnt and not record.actuators
    assert record.verdict == "no synchronised repetition"
    generated = generate(gestures, "gestures.point", output=tmp_path / "point.bvh")
    assert generated.origin == "performances" and generated.performances == 3
    # played once by default, as long as the median take, every channel of the takes
    assert generated.repeat == 1 and generated.motion.frames == 120
    assert generated.motion.channels == CHANNELS
    assert generated.channels == () and generated.round_trip() == {}
    back = kinetology.read(tmp_path / "point.bvh")
    assert np.abs(back.values - generated.motion.values).max() < 0.01
    # warped onto one another, the three raises keep their height and their speed; the
    # plain mean of the takes resampled to one length is a lower, slower raise
    real = _gesture(0, 4.0, 0.5).column("arm.rx")
    linear, _ = performed_motion(record, 1, back, alignment="linear")
    for motion, fine in ((generated.motion, True), (linear, False)):
        arm = motion.column("arm.rx")
        tall = np.ptp(arm) >= 0.9 * np.ptp(real)
        quick = np.abs(np.diff(arm)).max() >= 0.8 * np.abs(np.diff(real)).max()
        assert (tall and quick) == fine, (np.ptp(arm), np.abs(np.diff(arm)).max())
    # still channels stay still: the mean of noise
    assert np.ptp(generated.motion.column("head.ry")) < 1.5


def test_an_action_without_repetition_played_several_times_joins_without_a_jump(gestures):
    once = generate(gestures, "gestures.point")
    three = generate(gestures, "gestures.point", repeat=3)
    assert three.repeat == 3 and three.motion.frames == 3 * (once.motion.frames - 1) + 1
    arm = three.motion.column("arm.rx")
    assert np.abs(np.diff(arm)).max() <= np.abs(np.diff(once.motion.column("arm.rx"))).max() + 1
    assert np.allclose(arm[:once.motion.frames], once.motion.column("arm.rx"))


def test_the_command_line_says_an_action_was_generated_from_its_performances(
        gestures, tmp_path, capsys):
    from praxicon.cli import main

    assert main(["generate", str(gestures), "gestures.point", "-o",
                 str(tmp_path / "p.bvh"), "--repeat", "2"]) == 0
    printed = capsys.readouterr().out.splitlines()
    assert printed[0] == (f"{tmp_path / 'p.bvh'}: 239 frames at 30 fps, the action played "
                          f"2 times, one after the other (120 frames each, a frame shared "
                          f"where one meets the next)")
    assert printed[1].startswith("generated from the course of 3 performances, not from a "
                                 "grammar: no synchronised repetition was found")
    assert printed[2] == "segmented again: no symbolic round trip (there is no morpheme to " \
                         "give back)"
    assert (tmp_path / "p.bvh").is_file()


@needs_mocap()
def test_a_real_gesture_without_repetition_generates_from_its_takes(tmp_path):
    # Bandai's guide (point the way once): PAL finds no synchronised repetition in it
    data = SHARED / "bandai-namco-1" / "data"
    styles = ("active", "angry", "childish", "chimpira")
    (tmp_path / "guide.csv").write_text("action,file\n" + "".join(
        f"guide,{data / f'dataset-1_guide_{s}_001.bvh'}\n" for s in styles))
    build(read_dataset(tmp_path / "guide.csv"), tmp_path / "px", progress=False,
          log=lambda s: None)
    generated = generate(tmp_path / "px", "guide.guide")
    assert generated.origin == "performances" and generated.performances == 4
    assert generated.motion.frames == 129  # the median of 110, 119, 140 and 186 frames
    arm = generated.motion.column("UpperArm_R.ry")
    assert 60 < np.ptp(arm) < 120  # the right arm points (the takes: 63-116 degrees)
    # one style: its one take, on its own clock
    angry = generate(tmp_path / "px", "guide.guide", style="angry")
    assert angry.performances == 1 and angry.motion.frames == 110
    with pytest.raises(ValueError, match="no performance of style 'sad'"):
        generate(tmp_path / "px", "guide.guide", style="sad")


def test_a_moved_performance_is_named_with_where_it_was_read_from(manifest, tmp_path):
    out = tmp_path / "px"
    build(read_dataset(manifest), out, progress=False, log=lambda s: None)
    for f in (tmp_path / "data").glob("*"):  # the takes move after the build
        f.rename(f.with_name("moved-" + f.name))
    with pytest.raises(ValueError, match=r"no such file: the skeleton of 'moves\.wave' .* rel"):
        generate(out, "moves.wave", repeat=1)
