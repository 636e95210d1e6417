"""Reading a motion file takes about twice its size, and reading the frames a chunk at a time
gives what splitting the lines gave: the same values bit for bit (each number as ``float``
reads it) and, on malformed frames, the same error at the same line and column.

The first way (splitting the frame block into lines and numbers, :func:`parse_rows`) is
reached by making the chunked reading give up; ``CHUNK`` is made tiny so that small texts
cross many chunk boundaries, and ``SMALL`` 0 so that they are read in chunks at all.
"""

from __future__ import annotations

import tracemalloc
from contextlib import ExitStack
from unittest import mock

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import kinetology
from fuzz_support import SEEDS, apply, mutations_strategy
from kinetology import _frame_block
from kinetology import asf as asf_module
from kinetology import bvh as bvh_module
from kinetology.asf import parse_amc, read_asf
from kinetology.bvh import parse_bvh
from kinetology.motion import Motion, MotionFormatError, _Owned

#: The bound stated in docs/kinetology.md: the peak of memory allocated while a file of a
#: megabyte or more is read, per byte of the file (the bytes and the text they decode to, then
#: the text and the values, which the motion keeps without copying them).
PEAK_PER_BYTE = 2.5


def _outcome(parse, text: str):
    try:
        motion = parse(text)
    except MotionFormatError as exc:
        return ("error", str(exc))
    return ("ok", motion.values.shape, motion.values.tobytes(), motion.channels)


def _both_ways(parse, text: str, chunk: int):
    """The outcome of reading ``text`` in chunks of ``chunk`` characters, whether the chunks
    read it (or it gave up), and the outcome of the first way; which splits the lines a piece
    at a time, and must read them as in one piece (the same values, the same error)."""
    read = []

    def spy(function):
        def spied(*args):
            answer = function(*args)
            read.append(answer is not None)
            return answer
        return spied

    with ExitStack() as stack:
        stack.enter_context(mock.patch.object(_frame_block, "CHUNK", chunk))
        stack.enter_context(mock.patch.object(_frame_block, "SMALL", 0))
        stack.enter_context(mock.patch.object(bvh_module, "read_records",
                                              spy(bvh_module.read_records)))
        stack.enter_context(mock.patch.object(asf_module, "read_at_once",
                                              spy(asf_module.read_at_once)))
        chunked = _outcome(parse, text)
    split = []
    for piece in (1 << 30, chunk):  # the whole block in one piece, then in pieces of chunk
        with ExitStack() as stack:  # the chunked reading gives up: the lines are split
            stack.enter_context(mock.patch.object(bvh_module, "read_records", lambda *a: None))
            stack.enter_context(mock.patch.object(asf_module, "read_at_once", lambda *a: None))
            stack.enter_context(mock.patch.object(_frame_block, "CHUNK", piece))
            split.append(_outcome(parse, text))
    assert split[0] == split[1]
    return chunked, any(read), split[0]


# numbers as files write them: every format a float of the file may be written in
_FORMATS = (repr, "{:.6f}".format, "{:.17g}".format, "{:.3e}".format, "{:E}".format,
            "{:+.2f}".format, lambda x: f"{x:.4f}".replace("0.", ".", 1), "{:.0f}.".format,
            lambda x: "00" + f"{abs(x):.5g}")
_values = st.floats(-1e6, 1e6, allow_subnormal=True) | st.sampled_from(
    [0.0, -0.0, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e308, 0.1, 1 / 3])
_chunks = st.sampled_from([8, 40, 1 << 16])


def _bvh(rows: list[list[str]], separator: str = " ", newline: str = "\n", tail: str = "\n") -> str:
    """A chain of joints of up to three rotations each, ``rows`` its frames."""
    width = len(rows[0])
    groups = [("Xrotation", "Yrotation", "Zrotation")[:min(3, width - k)]
              for k in range(0, width, 3)]
    head = "HIERARCHY\n" + "".join(
        f"{'JOINT' if k else 'ROOT'} j{k}\n{{ OFFSET 0 1 0\nCHANNELS {len(group)} "
        f"{' '.join(group)}\n" for k, group in enumerate(groups))
    head += "End Site\n{ OFFSET 0 1 0 }\n" + "}\n" * len(groups)
    body = newline.join(separator.join(row) for row in rows)
    return f"{head}MOTION\nFrames: {len(rows)}\nFrame Time: 0.01\n{body}{tail}"


@settings(max_examples=80)
@given(data=st.data(), frames=st.integers(1, 7), width=st.integers(1, 8), chunk=_chunks,
       separator=st.sampled_from([" ", "\t", "  ", " \t "]), newline=st.sampled_from(["\n", "\r\n"]),
       tail=st.sampled_from(["", "\n", "\n\n  \n", "\r\n"]))
def test_bvh_values_are_floats_of_the_numbers_bit_for_bit(data, frames, width, chunk, separator,
                                                           newline, tail):
    rows = [[data.draw(st.sampled_from(_FORMATS))(data.draw(_values)) for _ in range(width)]
            for _ in range(frames)]
    chunked, read, split = _both_ways(parse_bvh, _bvh(rows, separator, newline, tail), chunk)
    assert chunked == split
    expected = np.array([[float(token) for token in row] for row in rows])
    if np.isfinite(expected).all():  # ("{:.3e}" rounds the largest float up past it)
        assert read and chunked[0] == "ok" and chunked[2] == expected.tobytes()


def _amc(bones, frames, values, *, first=1, radians=False, newline="\n"):
    lines = [":FULLY-SPECIFIED", ":RADIANS" if radians else ":DEGREES"]
    for f in range(frames):
        lines.append(str(first + f))
        lines.extend(" ".join([bone] + values[f][b]) for b, bone in enumerate(bones))
    return newline.join(lines) + newline


_BONES = ["root", "lfemur", "ltibia", "fémur", "thorax", "r_hand"]


@settings(max_examples=80)
@given(data=st.data(), frames=st.integers(1, 6), count=st.integers(1, 4), chunk=_chunks,
       named=st.booleans(), radians=st.booleans(), first=st.sampled_from([0, 1, 7]),
       newline=st.sampled_from(["\n", "\r\n"]))
def test_amc_values_are_those_of_splitting_the_lines(data, frames, count, chunk, named, radians,
                                                     first, newline):
    bones = _BONES[:count]
    widths = [data.draw(st.integers(0 if b else 1, 6)) for b in range(count)]
    values = [[[data.draw(st.sampled_from(_FORMATS))(data.draw(_values)) for _ in range(w)]
               for w in widths] for _ in range(frames)]
    dofs = ({bone: ("rx", "ry", "rz", "tx", "ty", "tz")[:w] for bone, w in zip(bones, widths)}
            if named else None)
    text = _amc(bones, frames, values, first=first, radians=radians, newline=newline)
    chunked, read, split = _both_ways(lambda t: parse_amc(t, dofs=dofs), text, chunk)
    assert chunked == split
    expected = np.array([[float(v) for bone in frame for v in bone] for frame in values])
    if np.isfinite(expected).all() and not (radians and np.abs(expected).max() > 1e306):
        assert read and chunked[0] == "ok"
        if not radians:
            assert chunked[2] == expected.tobytes()


# what hand editing and bad exporters do to a frame block: every one either reads to the
# same values both ways, or is the same error at the same place
_EDITS = ["1-2", "1e5e5", "+2", "002", "2.0", "2e0", "inf", "-nan", "1_0", "١", "0x10", "1e999",
          ".", "-", "e5", "1.", ".5", "+.5", "1e+5", "", "  ", "\t", "\r", "\x0b", "\x0c",
          "\x1c", "\u00a0", "#", "root", "femur", "3", "1 2", "\n", "\n\n", "\r\n",
          "1e307", "\ufeff", "\x00", "  femur 1", "2\nroot 1 2"]


@settings(max_examples=100)
@given(kind=st.sampled_from(["bvh", "amc"]), data=st.data(), chunk=_chunks)
def test_an_edited_frame_block_reads_or_fails_the_same_both_ways(kind, data, chunk):
    if kind == "bvh":
        text = _bvh([["0", "1.5", "-2"], ["3", "4", "5e-3"], ["6", "7", "8"]])
        parse = parse_bvh
    else:
        text = _amc(["root", "femur"], 3, [[["1", "2"], ["3"]]] * 3,
                    radians=data.draw(st.booleans()))
        dofs = data.draw(st.sampled_from([None, {"root": ("tx", "rx"), "femur": ("rx",)}]))
        parse = lambda t: parse_amc(t, dofs=dofs)  # noqa: E731
    block = text.index("0.01\n") + 5 if kind == "bvh" else text.index("\n1\n") + 1
    for _ in range(data.draw(st.integers(1, 3))):
        at = data.draw(st.integers(block, len(text)))
        cut = data.draw(st.integers(0, 4))
        text = text[:at] + data.draw(st.sampled_from(_EDITS)) + text[at + cut:]
    chunked, _, split = _both_ways(parse, text, chunk)
    assert chunked == split


@settings(max_examples=100)
@given(name=st.sampled_from(["small.bvh", "small_1.amc"]), mutations=mutations_strategy(),
       chunk=_chunks)
def test_a_mutated_file_reads_or_fails_the_same_both_ways(name, mutations, chunk):
    data = apply((SEEDS / name).read_bytes(), mutations)
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError:  # refused before the frames are read, the same both ways
        return
    if name.endswith(".bvh"):
        parse = parse_bvh
    else:
        dofs = read_asf(SEEDS / "small.asf").dofs
        parse = lambda t: parse_amc(t, dofs=dofs)  # noqa: E731
    chunked, _, split = _both_ways(parse, text, chunk)
    assert chunked == split


def _peak(path) -> int:
    tracemalloc.start()
    try:
        motion = kinetology.read(path)
        return tracemalloc.get_traced_memory()[1], motion
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("kind", ["bvh", "amc"])
def test_reading_takes_at_most_two_and_a_half_times_the_file(kind, tmp_path):
    rng = np.random.default_rng(0)
    values = np.round(rng.normal(0, 60, size=(6000, 45)), 6)
    rows = [" ".join(f"{v:.6f}" for v in row) for row in values]
    if kind == "bvh":
        path = tmp_path / "long.bvh"
        path.write_text(_bvh([row.split() for row in rows]), encoding="utf-8")
    else:
        bones = [f"bone{k}" for k in range(15)]  # 15 bones of 3 values
        frames = [[row.split()[3 * b:3 * b + 3] for b in range(15)] for row in rows]
        path = tmp_path / "long.amc"
        path.write_text(_amc(bones, len(rows), frames), encoding="utf-8")
    size = path.stat().st_size
    assert size > 2_000_000
    peak, motion = _peak(path)
    assert np.array_equal(motion.values, values)
    # splitting the lines took 7 (AMC) to 11 (BVH) times the file's size
    assert peak <= PEAK_PER_BYTE * size, f"{peak / size:.2f} bytes per byte of the file"


@pytest.mark.parametrize("claim, error", [
    (("Frames: 3", "Frames: 1000000000000"), "header says 1000000000000 frames but 3 frame "
                                             "lines follow"),
    (("CHANNELS 3", "CHANNELS 1000000000000"), "unknown channel 'End'"),
])
def test_a_header_claiming_a_trillion_frames_or_channels_allocates_nothing_for_them(
        claim, error, tmp_path):
    path = tmp_path / "claims.bvh"
    path.write_text(_bvh([["1", "2", "3"]] * 3).replace(*claim), encoding="utf-8")
    tracemalloc.start()
    try:
        with pytest.raises(MotionFormatError, match=error):
            kinetology.read(path)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 1_000_000


def test_a_number_moved_to_the_next_line_is_an_error_not_shifted_values():
    # the right count of numbers in all, but not on every line: read as frames, every value
    # after the moved one landed in the next channel's column
    text = _bvh([["1", "2", "3"], ["4", "5", "6"]])
    first = text.splitlines().index("1 2 3") + 1
    with pytest.raises(MotionFormatError, match=f"<bvh>:{first}:1: expected 3 numbers, found 4"):
        parse_bvh(text.replace("1 2 3\n4 5 6", "1 2 3 4\n5 6"))
    amc = ":DEGREES\n1\nroot 1 2\nfemur 1 2\n2\nroot 1 2\nfemur\n"
    with pytest.raises(MotionFormatError, match="<amc>:4:1: expected 1 number, found 2"):
        parse_amc(amc, dofs={"root": ("tx", "ty"), "femur": ("rx",)})


def _digits_bvh(tmp_path, frames=20000, width=60):
    """A BVH file of one-digit numbers: a number per two characters, so that its floats are
    four times the file's size."""
    rng = np.random.default_rng(1)
    values = rng.integers(0, 10, size=(frames, width)).astype(float)
    path = tmp_path / "digits.bvh"
    path.write_text(_bvh([[f"{v:.0f}" for v in row] for row in values]), encoding="utf-8")
    return path, values


def test_a_file_of_one_digit_numbers_is_read_without_copying_its_values(tmp_path):
    path, values = _digits_bvh(tmp_path)
    size = path.stat().st_size
    peak, motion = _peak(path)
    assert np.array_equal(motion.values, values) and not motion.values.flags.writeable
    # the text (a byte a character) and the values (four times the text); copying the values
    # into the motion took four times more again: 8.5 bytes a byte of the file
    assert motion.values.nbytes > 3.9 * size
    assert peak <= 5.5 * size, f"{peak / size:.2f} bytes per byte of the file"


def test_a_motion_copies_every_array_but_one_handed_over_to_it():
    given = np.zeros((3, 2))
    motion = Motion(given, ("a.rx", "b.rx"), 30.0)
    given[0, 0] = 5.0  # the caller still holds its array: the motion's does not change
    assert motion.values[0, 0] == 0.0 and given.flags.writeable
    frozen = np.zeros((3, 2))
    frozen.setflags(write=False)  # read-only, but its owner can make it writeable again
    motion = Motion(frozen, ("a.rx", "b.rx"), 30.0)
    frozen.setflags(write=True)
    frozen[0, 0] = 5.0
    assert motion.values[0, 0] == 0.0
    # handed over: kept (read-only in place) if it is a new float array of its own
    owned = np.zeros((3, 2))
    motion = Motion(_Owned(owned), ("a.rx", "b.rx"), 30.0)
    assert np.shares_memory(motion.values, owned) and not owned.flags.writeable
    with pytest.raises(ValueError):
        motion.values.setflags(write=True)
    # a view of another array, another type or a non-float array is copied even so
    base = np.zeros((4, 2))  # (its first rows: contiguous, but a view of it)
    for other in (base[:3], np.zeros((3, 2), dtype=np.float32), [[0, 0]] * 3,
                  np.asfortranarray(np.zeros((3, 2)))):
        motion = Motion(_Owned(other), ("a.rx", "b.rx"), 30.0)
        assert not np.shares_memory(motion.values, np.asarray(other))
    assert base.flags.writeable


def test_select_keeps_the_columns_it_takes_and_a_pickled_motion_copies():
    import pickle
    motion = Motion(np.arange(6.0).reshape(3, 2), ("a.rx", "b.rx"), 30.0)
    chosen = motion.select(["b.rx"])
    assert chosen.values.tolist() == [[1.0], [3.0], [5.0]]
    assert not chosen.values.flags.writeable and not np.shares_memory(chosen.values,
                                                                      motion.values)
    again = pickle.loads(pickle.dumps(chosen))
    assert np.array_equal(again.values, chosen.values) and not again.values.flags.writeable
