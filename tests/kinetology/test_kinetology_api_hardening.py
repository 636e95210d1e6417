"""The public API refuses a wrong type or value with one ValidationError naming it.

A demanding caller's mistakes (a string for a number, a bool for a rate, complex or object
values, a huge count) must not reach numpy's own errors, a silent wrong answer or an
unbounded allocation.
"""

from __future__ import annotations

import numpy as np
import pytest

import kinetology
from kinetology import Motion
from psgs.errors import ValidationError

CHANNELS = ("a.rx", "b.rx")


def small() -> Motion:
    return kinetology.synthetic_motion(2, (0,), repetitions=2)


@pytest.mark.parametrize("values, what", [
    (np.zeros((5, 2)) + 1j, "complex"),                   # the imaginary part was dropped
    (np.array([["a", "b"]] * 5, dtype=object), "object"),
    ([["1", "2"]] * 5, "<U1"),                            # strings were read as numbers
    (np.zeros((5, 2), dtype=bool), "bool"),
    ([[1.0, 2.0], [3.0]], "array of numbers"),            # ragged
])
def test_motion_values_must_be_real_numbers(values, what):
    with pytest.raises(ValidationError, match=f"motion values must be .*{what}"):
        Motion(values, CHANNELS, 30.0)


@pytest.mark.parametrize("rate", ["30", None, True, 1j, np.array([30.0])])
def test_motion_frame_rate_must_be_a_number(rate):
    with pytest.raises(ValidationError, match="frame rate must be a number"):
        Motion(np.zeros((5, 2)), CHANNELS, rate)


@pytest.mark.parametrize("channels, match", [
    ("ab", "channels must be a sequence of names"),   # was split into 'a', 'b'
    (None, "channels must be a sequence of names"),
    ((1, 2), "channel names must be strings"),
])
def test_motion_channels_must_be_names(channels, match):
    with pytest.raises(ValidationError, match=match):
        Motion(np.zeros((5, 2)), channels, 30.0)


@pytest.mark.parametrize("extra, match", [
    (("skeleton",), "skeleton must be a Skeleton"),
    ((None, 5), "source must be a string"),
    ((None, "x", [1]), "meta must be a mapping"),
])
def test_motion_other_fields_have_their_types(extra, match):
    with pytest.raises(ValidationError, match=match):
        Motion(np.zeros((5, 2)), CHANNELS, 30.0, *extra)


def test_motion_meta_none_is_empty_and_int_values_are_numbers():
    motion = Motion(np.zeros((5, 2), dtype=int), CHANNELS, 30, None, "x", None)
    assert dict(motion.meta) == {} and motion.values.dtype == float


def test_motion_values_cannot_be_made_writeable_again():
    motion = Motion(np.zeros((5, 2)), CHANNELS, 30.0)
    with pytest.raises(ValueError):
        motion.values.setflags(write=True)
    with pytest.raises(ValueError):
        motion.values[0, 0] = 1.0
    assert motion.values.sum() == 0


@pytest.mark.parametrize("value", ["1", None, True, float("nan"), -1.0])
@pytest.mark.parametrize("name", ["smoothing", "velocity_deadband", "min_range"])
def test_segmentation_parameters_are_non_negative_numbers(name, value):
    with pytest.raises(ValidationError, match=name):
        kinetology.segments(small(), **{name: value})


def test_a_huge_smoothing_is_the_whole_take_not_an_overflow():
    motion = small()
    whole = kinetology.segments(motion, smoothing=1e308)
    assert [b.tolist() for b in whole.borders] == \
        [b.tolist() for b in kinetology.segments(motion, smoothing=1e6).borders]


@pytest.mark.parametrize("motion, channels, match", [
    (None, None, "motion must be a Motion"),
    (np.zeros((5, 2)), None, "motion must be a Motion"),
    ("self", "j0.rx", "channels must be a sequence of names"),
])
def test_segments_checks_its_motion_and_channels(motion, channels, match):
    with pytest.raises(ValidationError, match=match):
        kinetology.segments(small() if isinstance(motion, str) else motion, channels)


@pytest.mark.parametrize("values, rate, options, match", [
    (np.array([0.0, 1.0, np.nan, 3.0, 4.0]), 30.0, {}, "values must be finite"),  # was: still
    (np.zeros(10) + 1j, 30.0, {}, "values must be real numbers"),
    (np.array(["a"] * 10, dtype=object), 30.0, {}, "values must be real numbers"),
    (np.arange(10.0), 0.0, {}, "frame_rate must be a positive"),                 # was: still
    (np.arange(10.0), float("nan"), {}, "frame_rate"),
    (np.arange(10.0), "30", {}, "frame_rate must be a number"),
    (np.arange(10.0), 30.0, {"smoothing": -1.0}, "smoothing"),                  # was accepted
])
def test_states_checks_its_input(values, rate, options, match):
    with pytest.raises(ValidationError, match=match):
        kinetology.states(values, rate, **options)


@pytest.mark.parametrize("values, period, match", [
    (np.arange(5.0), "360", "period must be a number"),
    (np.arange(5.0), float("nan"), "period must be a number"),     # was all NaN after frame 0
    (np.array(["a"] * 3, dtype=object), 360.0, "values must be real numbers"),
    (np.float64(3.0), 360.0, "time axis"),
])
def test_unwrap_checks_its_input(values, period, match):
    with pytest.raises(ValidationError, match=match):
        kinetology.unwrap(values, period)


@pytest.mark.parametrize("options, match", [
    ({"quantum": True}, "quantum must be a non-negative number"),    # was a 1-degree quantum
    ({"residual_step": True}, "residual_step"),
    ({"max_error": True}, "max_error must be a positive number"),    # was a 1-degree bound
])
def test_compress_refuses_a_bool_for_a_number(options, match):
    with pytest.raises(ValidationError, match=match):
        kinetology.compress(small(), **options)


@pytest.mark.parametrize("motion", [None, np.zeros((5, 2))])
def test_compress_refuses_what_is_not_a_motion(motion):
    with pytest.raises(ValidationError, match="motion must be a Motion"):
        kinetology.compress(motion)


def test_compress_with_a_huge_smoothing_decodes():
    motion = small()
    back = kinetology.decompress(kinetology.compress(motion, smoothing=1e308))
    assert back.frames == motion.frames


@pytest.mark.parametrize("options, match", [
    ({"joints": "6"}, "joints must be an integer"),
    ({"joints": True}, "joints must be an integer"),
    ({"repetitions": 1.5}, "repetitions must be an integer"),
    ({"seed": None}, "seed must be an integer"),              # was a new motion every call
    ({"seed": -1}, "seed not negative"),
    ({"period": float("nan")}, "period must be a positive number"),
    ({"period": "1"}, "period must be a number"),
    ({"frame_rate": "120"}, "frame_rate must be a number"),
    ({"noise": -1.0}, "noise must be a non-negative number"),
    ({"patterned": None}, "patterned must be joint indices"),
    ({"patterned": "01"}, "patterned must be joint indices"),  # was joints 0 and 1
    ({"patterned": (0, "a")}, "patterned joints must be integers"),
    ({"patterned": (1.7,)}, "patterned joints must be integers"),  # was joint 1
])
def test_synthetic_motion_checks_its_arguments(options, match):
    with pytest.raises(ValidationError, match=match):
        kinetology.synthetic_motion(**options)


@pytest.mark.parametrize("options", [{"repetitions": 10**9}, {"joints": 10**9},
                                     {"period": 1e9}, {"frame_rate": 1e9}])
def test_synthetic_motion_refuses_before_allocating_without_bound(options):
    with pytest.raises(ValidationError, match="samples"):
        kinetology.synthetic_motion(**options)


def test_synthetic_motion_is_the_same_for_the_same_seed():
    a, b = kinetology.synthetic_motion(seed=3), kinetology.synthetic_motion(seed=3)
    assert a.values.tobytes() == b.values.tobytes() and a.meta == b.meta


@pytest.mark.parametrize("args, match", [
    ((None, 0.0, 1.0), "motion must be a Motion"),
    (("self", "0", "1"), "start must be a number"),           # was read as 0 and 1 seconds
    (("self", True, 1.5), "start must be a number"),
])
def test_cut_checks_its_arguments(args, match):
    motion, *times = args
    with pytest.raises(ValidationError, match=match):
        kinetology.cut(small() if isinstance(motion, str) else motion, *times)


@pytest.mark.parametrize("args, match", [
    (("x", "0", "1"), "start and stop must be numbers"),
    (("x", True, 2), "start and stop must be numbers"),
    ((None, 0, 1), "label and style must be strings"),
    (("x", 0, 1, 5), "label and style must be strings"),
])
def test_span_checks_its_fields(args, match):
    with pytest.raises(ValidationError, match=match):
        kinetology.Span(*args)


@pytest.mark.parametrize("options, match", [
    ({"spans": [1]}, "spans must hold Span values"),
    ({"spans": [kinetology.Span("a", 0, 1)], "min_seconds": float("nan")}, "min_seconds"),
    ({"spans": [kinetology.Span("a", 0, 1)], "min_seconds": "1"}, "min_seconds"),
])
def test_performances_checks_spans_and_min_seconds(options, match):
    with pytest.raises(ValidationError, match=match):
        kinetology.performances(small(), **options)


def test_performances_refuses_a_source_that_is_no_file_or_motion():
    with pytest.raises(ValidationError, match="a Motion or a file's path"):
        kinetology.performances(5)


@pytest.mark.parametrize("motions, match", [
    (None, "motions must be a sequence"),
    ("motion", "motions must be a sequence"),      # one Motion, not a sequence of them
    ([None], "motions must hold Motion values"),
])
def test_segment_performances_checks_its_motions(motions, match):
    motions = small() if motions == "motion" else motions
    with pytest.raises(ValidationError, match=match):
        kinetology.segment_performances(motions)


def with_skeleton() -> Motion:
    from kinetology.bvh_writer import star_skeleton
    m = kinetology.synthetic_motion(3, (0,), repetitions=2)
    return Motion(m.values, m.channels, m.frame_rate, star_skeleton(m.channels))


@pytest.mark.parametrize("positions, indices, match", [
    (np.zeros((3, 2, 3)), (0, 1, 5), "joint index c must be an integer below 2"),
    (np.zeros((3, 3, 3)), (0, 1, 1.5), "joint index c"),
    (np.zeros((3, 3, 3)), (True, 1, 2), "joint index a"),
    (np.zeros((3, 3)), (0, 1, 2), "positions must be frames x joints x 2 or 3"),
    (np.zeros((3, 3, 3), dtype=complex), (0, 1, 2), "positions must be real numbers"),
])
def test_joint_angle_checks_its_input(positions, indices, match):
    from kinetology import joint_angle
    with pytest.raises(ValidationError, match=match):
        joint_angle(positions, *indices)


def test_forward_kinematics_refuses_what_is_not_a_motion():
    with pytest.raises(ValidationError, match="motion must be a Motion"):
        kinetology.forward_kinematics(None)


@pytest.mark.parametrize("motions, options, match", [
    (None, {}, "motions must be a Motion, a sequence or a mapping"),
    ([None], {}, "is a NoneType, not a Motion"),
    ("self", {"max_rate": "30"}, "max_rate must be a positive number"),
    ("self", {"max_frames": 1.5}, "max_frames must be a whole number"),  # 2 frames were kept
    ("self", {"max_frames": True}, "max_frames must be a whole number"),
    ("self", {"max_frames": np.array([5, 6])}, "max_frames must be a whole number"),
    ("self", {"max_rate": float("nan")}, "max_rate must be a positive number"),
    ("self", {"actuators": 5}, "actuators must be a collection"),
    ("self", {"actuators": "j0"}, "actuators must be a collection"),   # was 'j', '0'
    ("self", {"kinetemes": "no"}, "^kinetology.view: kinetemes must be True or False, not 'no'$"),
    ("self", {"follow": 1}, "^kinetology.view: follow must be True or False, not 1$"),
    ("self", {"max_frames": "5"}, "^kinetology.view: max_frames must be a whole number of at "
     r"least 1 \(inf: no cap\), not '5'$"),
    ("self", {"output": 5}, "the output must be a file's path"),
])
def test_view_checks_its_arguments(motions, options, match):
    motions = with_skeleton() if isinstance(motions, str) else motions
    with pytest.raises(kinetology.ViewError, match=match):
        kinetology.view(motions, **options)


@pytest.mark.parametrize("path", [None, 5])
@pytest.mark.parametrize("reader", ["read", "read_bvh", "read_amc", "read_asf",
                                    "read_cmu_truelabels", "read_bandai_json"])
def test_readers_refuse_a_path_that_is_no_path(reader, path):
    with pytest.raises(ValidationError, match="path must be a file's path"):
        getattr(kinetology, reader)(path)


def test_write_bvh_checks_its_motion_and_path(tmp_path):
    with pytest.raises(ValidationError, match="path must be a file's path"):
        kinetology.write_bvh(with_skeleton(), None)
    with pytest.raises(ValidationError, match="motion must be a Motion"):
        kinetology.write_bvh(None, tmp_path / "x.bvh")


SMALL_AMC = "1\nroot 1 2 3 0 0 0\n2\nroot 1 2 4 0 0 0\n"


@pytest.mark.parametrize("rate", ["120", True])   # "120" was a TypeError, True 1 fps
def test_an_amc_frame_rate_must_be_a_number(tmp_path, rate):
    path = tmp_path / "t.amc"
    path.write_text(SMALL_AMC)
    with pytest.raises(ValidationError, match="frame rate must be a number"):
        kinetology.read_amc(path, asf=None, frame_rate=rate)


def test_read_amc_refuses_an_asf_of_the_wrong_type(tmp_path):
    path = tmp_path / "t.amc"
    path.write_text(SMALL_AMC)
    with pytest.raises(ValidationError, match="asf must be 'auto', a path, an AsfSkeleton"):
        kinetology.read_amc(path, asf=5)


@pytest.mark.parametrize("rate", ["120", True, float("inf")])
def test_a_truelabels_frame_rate_must_be_a_positive_number(tmp_path, rate):
    path = tmp_path / "t.txt"
    path.write_text("1 1 1 5 5\n")
    with pytest.raises(ValidationError, match="frame rate must be a"):
        kinetology.read_cmu_truelabels(path, frame_rate=rate)


@pytest.mark.parametrize("duration", ["3", -1.0, float("nan")])   # "3" was 3 seconds
def test_a_bandai_duration_must_be_a_positive_number(tmp_path, duration):
    cfg, data = tmp_path / "cfg", tmp_path / "data"
    cfg.mkdir(), data.mkdir()
    (cfg / "content_label.txt").write_text("bye\n")
    (cfg / "style_label.txt").write_text("sad\n")
    path = data / "dataset-1_bye_sad_001.json"
    path.write_text('{"content": 0, "style": 0}')
    with pytest.raises(ValidationError, match="duration must be a"):
        kinetology.read_bandai_json(path, duration=duration)


def test_actuator_map_and_skeleton_parents_refuse_one_string():
    motion = small()
    with pytest.raises(ValidationError, match="channels must be a collection"):
        kinetology.actuator_map(motion, "j0.rx")          # was {'j': 'j', '0': '0', ...}
    with pytest.raises(ValidationError, match="actuators must be a collection"):
        kinetology.skeleton_parents(motion, "j0")
    with pytest.raises(ValidationError, match="motion must be a Motion"):
        kinetology.actuator_map(None)


@pytest.mark.parametrize("options, match", [
    ({"views": 10**9}, "views must be a positive whole number, at most 3600"),  # gigabytes
    ({"views": True}, "views must be a positive whole number"),
    ({"views": "4"}, "views must be a positive whole number"),
    ({"triple": ("j0", "j1")}, "^triple must name three joints, not "),   # a TypeError before
    ({"up_axis": 5}, "^up_axis must be 0, 1 or 2, not 5$"),
    ({"up_axis": -2}, "^up_axis must be 0, 1 or 2, not -2$"),  # the up axis was horizontal
    ({"up_axis": 1.0}, "up_axis must be 0, 1 or 2"),           # an IndexError before
    ({"up_axis": True}, "up_axis must be 0, 1 or 2"),          # a boolean mask of no axis
    ({"views": 4.0}, "views must be a positive whole number"),  # a TypeError from numpy before
])
def test_view_invariance_checks_its_arguments(options, match):
    from kinetology.evaluation import view_invariance

    arguments = {"triple": ("j0", "j1", "j2"), **options}
    with pytest.raises(ValidationError, match=match):
        view_invariance(with_skeleton(), **arguments)


@pytest.mark.parametrize("knots, codes, values, match", [
    ([0, 10], [0, 1], [0.0, 1.0], "codes must be one state 0..3 for each of the 1"),  # was read
    ([0, 10], [7], [0.0, 1.0], "codes must be one state 0..3"),                     # was read
    ([10, 0], [0], [0.0, 1.0], "knots must be whole frames rising from 0"),
    ([0, 10.5], [0], [0.0, 1.0], "knots must be whole frames"),
    ([0, 10], [0], [0.0, np.nan], "values must be one finite number"),             # was all NaN
    ([0, 10], [0], [0.0, 1.0, 2.0], "values must be one finite number for each of the 2"),
])
def test_reconstruct_checks_its_arrays(knots, codes, values, match):
    with pytest.raises(ValidationError, match=match):
        kinetology.reconstruct(np.array(knots), np.array(codes), np.array(values))


def test_reconstruct_refuses_a_curve_past_max_frames_before_allocating_it():
    from kinetology.codec.quartic import MAX_FRAMES

    far = np.array([0, 10**12])  # a MemoryError (7 TiB asked) before
    with pytest.raises(ValidationError, match=f"asks for a curve of {10**12 + 1} frames, "
                                              f"more than max_frames={MAX_FRAMES}"):
        kinetology.reconstruct(far, np.array([0]), np.array([0.0, 1.0]))
    with pytest.raises(ValidationError, match="more than max_frames=10 "):
        kinetology.reconstruct([0, 5, 10], [0, 1], [0.0, 4.0, 10.0], max_frames=10)
    curve = kinetology.reconstruct([0, 5, 10], [0, 1], [0.0, 4.0, 10.0], max_frames=11)
    assert np.array_equal(curve, kinetology.reconstruct([0, 5, 10], [0, 1], [0.0, 4.0, 10.0],
                                                        max_frames=None))
    with pytest.raises(ValidationError, match="max_frames must be a whole number ≥ 1"):
        kinetology.reconstruct([0, 5, 10], [0, 1], [0.0, 4.0, 10.0], max_frames=1.5)


@pytest.mark.parametrize("most", [-1, "5", True, 1.5])
def test_decompress_max_samples_must_be_a_whole_number(most):
    with pytest.raises(ValidationError, match="max_samples must be a whole number of samples, "
                                              "0 or more, not "):
        kinetology.decompress(kinetology.compress(small()), max_samples=most)


@pytest.mark.parametrize("most", [1e6, np.int64(10**6), np.float64(1e6), 10.0**30])
def test_decompress_takes_a_whole_number_of_any_type(most):   # int() read them before
    data = kinetology.compress(small())
    assert kinetology.decompress(data, max_samples=most).frames == small().frames


def test_decompress_takes_a_huge_max_samples():
    data = kinetology.compress(small())
    assert kinetology.decompress(data, max_samples=10**30).frames == small().frames  # overflowed


@pytest.mark.parametrize("size", [0, -5, "100", True])   # 0 was a ZeroDivisionError
def test_codec_point_checks_the_original_size(size):
    from kinetology.evaluation import codec_point

    with pytest.raises(ValidationError, match="original_size"):
        codec_point(small(), size)


@pytest.mark.parametrize("codes, signal", [
    (np.zeros((3, 3), dtype=int), np.zeros(3)),           # was "still"
    (np.zeros(3, dtype=int), np.arange(5.0) * 10),         # was read without a word
])
def test_evaluation_describe_wants_one_channel_of_one_length(codes, signal):
    from kinetology.evaluation import describe

    with pytest.raises(ValidationError, match="one channel each, of one length"):
        describe(codes, signal)


def test_player_checks_its_panels_rate_and_ticks():
    player = kinetology.view(with_skeleton())
    with pytest.raises(kinetology.ViewError, match=r"one or more Panel values, not \(\)"):
        kinetology.Player((), 30.0)                         # max() of nothing before
    with pytest.raises(kinetology.ViewError, match="one or more Panel values, not 5"):
        kinetology.Player(5, 30.0)
    with pytest.raises(ValidationError, match="frame_rate must be a"):
        kinetology.Player(player.panels, "30")
    with pytest.raises(ValidationError, match="frame_rate must be a"):
        kinetology.Player(player.panels, -1.0)                # was accepted
    with pytest.raises(kinetology.ViewError, match="tick must be a whole number from 0"):
        player.frame_of(0, -1)                              # was frame -1
    assert player.frame_of(0, 10**9) == player.panels[0].frames - 1


@pytest.mark.parametrize("channels", [None, "a.rx", 5])
def test_motion_select_wants_a_sequence_of_names(channels):
    with pytest.raises(ValidationError, match="channels must be a sequence of names"):
        Motion(np.zeros((5, 2)), CHANNELS, 30.0).select(channels)


def test_motion_select_reads_a_generator_once():
    motion = Motion(np.arange(10.0).reshape(5, 2), CHANNELS, 30.0)
    assert motion.select(c for c in ("b.rx",)).channels == ("b.rx",)


def test_view_reads_a_generator_of_actuators_once_for_every_panel():
    motion = with_skeleton()
    player = kinetology.view({"a": motion, "b": motion}, actuators=(j for j in ["j0"]))
    assert player.panels[0].actuators == player.panels[1].actuators   # the second had none


def test_view_takes_what_it_took_before_its_checks():
    motion, html = with_skeleton(), lambda player: player.to_html()
    every = html(kinetology.view(motion, max_rate=10**6, max_frames=10**6))
    assert html(kinetology.view(motion, max_rate=float("inf"))) == every  # no rate cap
    assert html(kinetology.view(motion, max_rate=float("inf"), max_frames=float("inf"))) == every
    assert html(kinetology.view(motion, max_frames=20.0)) == html(kinetology.view(motion,
                                                                                  max_frames=20))
    assert html(kinetology.view(motion, kinetemes=np.bool_(False), follow=np.bool_(False))) == \
        html(kinetology.view(motion, kinetemes=False, follow=False))  # follow was kept as np.bool_


def test_the_view_command_takes_an_infinite_max_rate(tmp_path):
    from kinetology.cli import main

    take = tmp_path / "t.bvh"
    kinetology.write_bvh(with_skeleton(), take)
    assert main(["view", str(take), "-o", str(tmp_path / "t.html"), "--max-rate", "inf"]) == 0


def test_a_player_takes_a_list_of_panels_and_a_whole_float_tick():
    player = kinetology.view(with_skeleton())
    again = kinetology.Player(list(player.panels), player.frame_rate)
    assert again.panels == player.panels and isinstance(again.panels, tuple)
    assert again.frame_of(0, 3.0) == player.frame_of(0, 3) == player.frame_of(0, np.int64(3))
    with pytest.raises(kinetology.ViewError, match="tick must be a whole number from 0, not 3.5"):
        player.frame_of(0, 3.5)


def test_view_invariance_reads_a_generator_once_and_takes_up_axis_minus_one():
    from kinetology.evaluation import view_invariance

    motion, names = with_skeleton(), ("j0", "j1", "j2")
    listed = view_invariance(motion, names, views=4)
    once = view_invariance(motion, (n for n in names), views=4)   # a TypeError before
    assert np.array_equal(once.agreement_per_view, listed.agreement_per_view)
    last = view_invariance(motion, names, views=4, up_axis=-1)    # axis 2, as it was
    assert np.array_equal(last.agreement_per_view,
                          view_invariance(motion, names, views=4, up_axis=2).agreement_per_view)


def test_joint_angle_keeps_float32():
    from kinetology import joint_angle

    rng = np.random.default_rng(1)
    positions = rng.normal(size=(50, 3, 3)).astype(np.float32)
    angles = joint_angle(positions, 0, 1, 2)
    assert angles.dtype == np.float32                           # float64 after the check
    u, v = positions[:, 0] - positions[:, 1], positions[:, 2] - positions[:, 1]
    cos = np.einsum("fi,fi->f", u, v) / np.maximum(
        np.linalg.norm(u, axis=1) * np.linalg.norm(v, axis=1), 1e-12)
    assert np.array_equal(angles, np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))))


def test_joint_angle_of_unsigned_integer_positions_does_not_wrap_around():
    from kinetology import joint_angle

    positions = np.array([[[20, 20, 0], [20, 21, 0], [21, 22, 0]]])  # a bend of 135 degrees
    expected = joint_angle(positions.astype(float), 0, 1, 2)
    assert np.allclose(joint_angle(positions.astype(np.uint8), 0, 1, 2), expected)
    assert np.allclose(expected, [135.0])


@pytest.mark.parametrize("rate", [1e300, 1e180])
def test_a_frame_rate_whose_accelerations_overflow_is_named_not_one_still_segment(rate):
    from kinetology.segmentation import segments, states

    values = 30 * np.sin(np.arange(400) * 0.5)[:, None]
    motion = Motion(values, ("j.rx",), rate)   # 1e300: one segment, inf and NaN read as still
    for run in (lambda: segments(motion), lambda: states(values[:, 0], rate),
                lambda: kinetology.segment(motion)):
        with pytest.raises(ValidationError, match="accelerations overflow"):
            run()
    # a megahertz signal, far from it, segments as before; so do still values at any rate,
    # and small angles as fast as their accelerations stay finite
    fast = segments(Motion(values, ("j.rx",), 3e6), smoothing=0.0)
    assert fast.segment_count > 100
    assert (states(np.zeros(50), 1e160) == 0).all() and states(np.zeros(0), 1e160).size == 0
    assert len(set(states(1e-3 * np.sin(np.arange(50)), 2e153).tolist())) > 1


def test_select_of_many_channels_looks_each_up_once():
    """Motion.index searched the channel tuple per name, so selecting every one of 80,000
    channels took half a minute (quadratic); the columns are looked up in a table built once."""
    import numpy as np
    from kinetology import Motion

    n = 80_000
    channels = tuple(f"j{k}.rx" for k in range(n))
    motion = Motion(np.arange(3 * n, dtype=float).reshape(3, n), channels, 30.0)
    picked = motion.select(list(reversed(channels)))
    assert picked.channels == channels[::-1]
    assert picked.values[:, 0].tolist() == motion.values[:, -1].tolist()
    assert motion.index("j79999.rx") == n - 1
