"""The first way of reading a frame block, for blocks the chunked reader does not take
(malformed ones, or ones with other white space): the lines split a piece at a time into one
array, about the text and the values in memory (splitting them all at once took 7 to 18 times
the file's size), with the same values and the same first error as splitting all at once.

An AMC file's errors come in the order splitting its lines met them: its layout (a bone of
frame 1 not in the skeleton among it), then bone by bone in frame 1's order (its first line
without its count of numbers, else its first value that is not finite), then the first value
too large in degrees.
Reading a piece at a time meets the lines in another order (frame by frame); each case is read
with pieces of a frame and with one piece for the whole block.
"""

from __future__ import annotations

import tracemalloc
from unittest import mock

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from kinetology import _frame_block
from kinetology import asf as asf_module
from kinetology import bvh as bvh_module
from kinetology.asf import parse_amc
from kinetology.bvh import parse_bvh
from kinetology.motion import MotionFormatError
from kinetology.textblocks import parse_rows
from psgs._foundation.text import decimal


def _split(parse, text, chunk):
    """``parse(text)`` the first way, in pieces of about ``chunk`` characters."""
    with mock.patch.object(bvh_module, "read_records", lambda *a: None), \
            mock.patch.object(asf_module, "read_at_once", lambda *a: None), \
            mock.patch.object(_frame_block, "CHUNK", chunk):
        return parse(text)


def _amc(rows, radians=False):
    """Frames of bones root (2 numbers), femur (1, its line indented) and tibia (2)."""
    lines = [":RADIANS" if radians else ":DEGREES"]
    for number, (root, femur, tibia) in enumerate(rows, 1):
        lines += [str(number), f"root {root}", f"  femur {femur}", f"tibia {tibia}"]
    return "\n".join(lines) + "\n"


_OK = ("1 2", "3", "4 5")
_DOFS = {"root": ("tx", "rx"), "tibia": ("rx", "ry")}  # no femur
_ORDER = [
    # root's bad line in frame 3 before femur's in frame 2: bone by bone, not line by line
    (_amc([_OK, ("1 2", "x", "4 5"), ("1", "3", "4 5")]), None,
     "o.amc:11:1: expected 2 numbers, found 1"),
    (_amc([_OK, ("1 2", "3 3", "4 5"), ("1 nan", "3", "4 5")]), None,
     "o.amc:11:8: value 2 is not finite (nan)"),
    # a bone's bad line before its value that is not finite, wherever they are
    (_amc([_OK, ("1 inf", "3", "4 5"), ("1 2 3", "3", "4 5")]), None,
     "o.amc:11:1: expected 2 numbers, found 3"),
    (_amc([_OK, ("1 2", "3", "4"), ("1 2", "-inf", "4 5")]), None,
     "o.amc:12:9: value 1 is not finite (-inf)"),
    # a bone of frame 1 not in the skeleton with the layout, before any bone's values
    (_amc([_OK, _OK, ("1 nan", "3", "4 5")]), _DOFS,
     "o.amc:4:3: bone 'femur' is not in the skeleton"),
    (_amc([_OK, ("1 2", "3", "4"), _OK]), _DOFS, "o.amc:4:3: bone 'femur' is not in the skeleton"),
    # a value too large in degrees after every other error, the first frame's first
    (_amc([("1 1e307", "3", "4 5"), _OK, ("1 2", "3", "x 5")], radians=True), None,
     "o.amc:13:7: not a number: 'x'"),
    (_amc([_OK, ("1 2", "1e307", "4 5"), ("1e307 1e307", "3", "4 5")], radians=True), None,
     "o.amc:8:9: femur.1: 1e+307 radians is too large to convert to degrees"),
    (_amc([_OK, ("1e307 2", "3", "4 1e307")], radians=True),
     {"root": ("tx", "rx"), "femur": ("rx",), "tibia": ("ty", "rz")},
     "o.amc:9:9: tibia.rz: 1e+307 radians is too large to convert to degrees"),
]


@pytest.mark.parametrize("chunk", [1, 1 << 16])
@pytest.mark.parametrize("text, dofs, error", _ORDER)
def test_amc_errors_come_bone_by_bone_whatever_the_pieces(text, dofs, error, chunk):
    with pytest.raises(MotionFormatError) as caught:
        _split(lambda t: parse_amc(t, dofs=dofs, source="o.amc"), text, chunk)
    assert str(caught.value) == error


@pytest.mark.parametrize("chunk", [1, 7, 1 << 16])
def test_bvh_first_bad_line_then_first_value_not_finite(chunk):
    head = ("HIERARCHY\nROOT a\n{ OFFSET 0 0 0\nCHANNELS 2 Xrotation Yrotation\n"
            "End Site\n{ OFFSET 0 1 0 }\n}\nMOTION\nFrames: 4\nFrame Time: 0.01\n")
    rows = ["1 2", "3 inf", "5 6", "7 x"]  # line 14 not a number, after line 12's inf
    with pytest.raises(MotionFormatError, match=r"^b.bvh:14:3: not a number: 'x'$"):
        _split(lambda t: parse_bvh(t, "b.bvh"), head + "\n".join(rows) + "\n", chunk)
    rows[3] = "7 8"
    with pytest.raises(MotionFormatError, match=r"^b.bvh:12:3: value 2 is not finite \(inf\)$"):
        _split(lambda t: parse_bvh(t, "b.bvh"), head + "\n".join(rows) + "\n", chunk)
    rows[1] = "3\x0c4"  # a form feed: white space to split, not to the chunked reader
    values = _split(lambda t: parse_bvh(t, "b.bvh"), head + "\n".join(rows) + "\n\n \n",
                    chunk).values
    assert values.tolist() == [[1, 2], [3, 4], [5, 6], [7, 8]]


def _peak(function):
    tracemalloc.start()
    try:
        answer = function()
        return tracemalloc.get_traced_memory()[1], answer
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("kind", ["bvh", "amc"])
def test_a_block_the_chunks_do_not_take_is_read_in_about_twice_its_size(kind):
    rng = np.random.default_rng(2)
    values = np.round(rng.normal(0, 60, size=(3000, 45)), 6)
    if kind == "bvh":
        head = "HIERARCHY\n" + "".join(
            f"{'JOINT' if k else 'ROOT'} j{k}\n{{ OFFSET 0 1 0\n"
            f"CHANNELS 3 Xrotation Yrotation Zrotation\n" for k in range(15))
        head += "End Site\n{ OFFSET 0 1 0 }\n" + "}\n" * 15
        rows = [" ".join(f"{v:.6f}" for v in row) for row in values]
        rows[-1] = rows[-1].replace(" ", "\x0b", 1)  # a vertical tab: the first way reads it
        text = f"{head}MOTION\nFrames: {len(rows)}\nFrame Time: 0.01\n" + "\n".join(rows) + "\n"
        parse = parse_bvh
    else:
        lines = [":DEGREES"]
        for number, row in enumerate(values, 1):
            lines.append(str(number))
            # indented bone lines: the first way reads them
            lines += [f" b{k} " + " ".join(f"{v:.6f}" for v in row[3 * k:3 * k + 3])
                      for k in range(15)]
        text = "\n".join(lines) + "\n"
        parse = parse_amc
    answers = []

    def spy(function):
        def spied(*args):
            answers.append(function(*args))
            return answers[-1]
        return spied

    with mock.patch.object(bvh_module, "read_records", spy(bvh_module.read_records)), \
            mock.patch.object(asf_module, "read_at_once", spy(asf_module.read_at_once)):
        peak, motion = _peak(lambda: parse(text))
    assert answers == [None]  # the chunks gave up: read the first way
    assert np.array_equal(motion.values, values)
    size = len(text)
    # the text is not counted (made before): the values, and a piece's lines and numbers (or
    # the chunked reader's chunk before it gave up), whatever the block's size; splitting all
    # the lines at once took 6 to 11 times the text more
    assert motion.values.nbytes < 0.8 * size
    assert peak < motion.values.nbytes + 1_000_000, f"{peak / size:.2f} bytes a character"


@pytest.mark.parametrize("text, dofs", [
    # 300 channels claimed, a number a line: no 300 x 20,000 array for the lines' claim
    ("HIERARCHY\nROOT a\n{ OFFSET 0 0 0\nCHANNELS 3 Xrotation Yrotation Zrotation\n"
     + "".join(f"JOINT b{k}\n{{ OFFSET 0 0 0\nCHANNELS 3 Xrotation Yrotation Zrotation\n"
               for k in range(99))
     + "End Site\n{ OFFSET 0 1 0 }\n" + "}\n" * 100
     + "MOTION\nFrames: 20000\nFrame Time: 0.01\n" + "1\n" * 20000, None),
    (":DEGREES\n" + "".join(f"{n}\nroot 1\n" for n in range(1, 20001)), {"root": ("rx",) * 300}),
])
def test_a_block_too_short_for_its_numbers_allocates_nothing_for_them(text, dofs):
    parse = parse_bvh if text.startswith("HIERARCHY") else (lambda t: parse_amc(t, dofs=dofs))
    peak, _ = _peak(lambda: pytest.raises(MotionFormatError, parse, text))
    with pytest.raises(MotionFormatError, match="expected 300 numbers, found 1"):
        parse(text)
    assert peak < 5_000_000  # 300 x 20,000 floats are 48 MB


def test_parse_rows_reads_and_fails_as_before():
    assert parse_rows(["1 2", "3\u00a04.5"], 2, source="w.amc").tolist() == [[1, 2], [3, 4.5]]
    with pytest.raises(MotionFormatError, match=r"^w.amc:11:5: not a number: '١'$"):
        parse_rows(["1 2", "3 \u0661"], 2, source="w.amc", first_line=10,
                   indent_of=lambda i: 2)
    with pytest.raises(MotionFormatError, match=r"^w.amc:10:1: expected 2 numbers, found 1$"):
        parse_rows(["1", "2 3 4 5 6 7 8 9"], 2, source="w.amc", first_line=10)


# a row's numbers: mostly good, now and then one that is no number or not finite, and now and
# then a number too few or too many
_GOOD = st.sampled_from(["0", "1.5", "-2", "1e3", "+.5", "7."])
_BAD = st.sampled_from(["x", "1_0", "inf", "-nan", "1e999", "Infinity", "1e5e5", "\u0661"])
_TOKEN = st.one_of(_GOOD, _GOOD, _GOOD, _GOOD, _GOOD, _GOOD, _BAD)


def _row(width):
    return st.integers(-1, 1).map(lambda d: d if d else 0).flatmap(
        lambda d: st.lists(_TOKEN, min_size=max(0, width + d), max_size=max(0, width + d)))


def _first_error(rows, width, where):
    """What splitting every row at once answers: the first row without ``width`` decimal
    numbers, else the first value that is not finite; ``where(j, k)``: (line, column)."""
    for j, tokens in enumerate(rows):
        if len(tokens) != width:
            return f"{where(j, 0)[0]}:1: expected {width} number{'s' * (width != 1)}, " \
                   f"found {len(tokens)}"
        for k, token in enumerate(tokens):
            if decimal(token) is None:
                return "%d:%d: not a number: %r" % (*where(j, k), token)
    for j, tokens in enumerate(rows):
        for k, token in enumerate(tokens):
            if not math.isfinite(float(token)):
                return "%d:%d: value %d is not finite (%s)" % (*where(j, k), k + 1, token)
    return None


def _column(prefix, tokens, k):  # of token k, on a line of prefix and tokens joined by spaces
    return len(prefix) + sum(len(t) + 1 for t in tokens[:k]) + 1


@settings(max_examples=150)
@given(rows=st.lists(_row(3), min_size=1, max_size=8), chunk=st.sampled_from([1, 12, 1 << 16]))
def test_bvh_lines_read_a_piece_at_a_time_fail_as_all_at_once(rows, chunk):
    head = ("HIERARCHY\nROOT a\n{ OFFSET 0 0 0\nCHANNELS 3 Xrotation Yrotation Zrotation\n"
            "End Site\n{ OFFSET 0 1 0 }\n}\nMOTION\n"
            f"Frames: {len(rows)}\nFrame Time: 0.01\n")
    text = head + "\n".join(" ".join(tokens) for tokens in rows) + "\n"
    expected = _first_error(rows, 3, lambda j, k: (11 + j, _column("", rows[j], k)))
    try:
        answer = _split(lambda t: parse_bvh(t, "b.bvh"), text, chunk).values.tolist()
    except MotionFormatError as exc:
        answer = str(exc)
    if expected is None:
        assert answer == [[float(t) for t in tokens] for tokens in rows]
    else:
        assert answer == "b.bvh:" + expected


@settings(max_examples=75)
@given(data=st.data(), frames=st.integers(1, 5), chunk=st.sampled_from([1, 30, 1 << 16]))
def test_amc_lines_read_a_piece_at_a_time_fail_as_all_at_once(data, frames, chunk):
    bones, widths = ("root", "femur", "tibia"), (2, 1, 2)
    rows = [[data.draw(_row(w)) for w in widths] for _ in range(frames)]
    lines = [":DEGREES"]
    for number, frame in enumerate(rows, 1):
        lines.append(str(number))
        lines.extend(" ".join([bone, *tokens]) for bone, tokens in zip(bones, frame))
    text = "\n".join(lines) + "\n"
    dofs = {"root": ("tx", "rx"), "femur": ("rx",), "tibia": ("rx", "ry")}
    expected = None
    for b, (bone, width) in enumerate(zip(bones, widths)):  # bone by bone, as split
        mine = [frame[b] for frame in rows]
        expected = _first_error(mine, width, lambda j, k, b=b, bone=bone, mine=mine: (
            3 + b + 4 * j, _column(bone + " ", mine[j], k)))
        if expected is not None:
            break
    try:
        answer = _split(lambda t: parse_amc(t, dofs=dofs, source="a.amc"), text,
                        chunk).values.tolist()
    except MotionFormatError as exc:
        answer = str(exc)
    if expected is None:
        assert answer == [[float(t) for tokens in frame for t in tokens] for frame in rows]
    else:
        assert answer == "a.amc:" + expected


@settings(max_examples=150)
@given(parts=st.lists(st.sampled_from(["a", " ", "\r", "\n", "\r\n", "b1", "\t"]), max_size=40),
       data=st.data(), chunk=st.sampled_from([1, 3, 7, 1 << 16]), per=st.integers(1, 3))
def test_line_pieces_are_the_lines_of_the_block_in_whole_records(parts, data, chunk, per):
    text = "".join(parts) + "\n"
    start = data.draw(st.sampled_from([0] + [i + 1 for i, c in enumerate(text) if c == "\n"]))
    # a block ends after a character that is not white space (or is empty)
    end = data.draw(st.sampled_from([start] + [i + 1 for i in range(start, len(text))
                                               if not text[i].isspace()]))
    expected = text[start:end].split("\n") if end > start else []
    expected = [line[:-1] if line.endswith("\r") else line for line in expected]
    with mock.patch.object(_frame_block, "CHUNK", chunk):
        pieces = list(_frame_block.line_pieces(text, start, end, per))
    assert [line for _, lines in pieces for line in lines] == expected
    sizes = [len(lines) for _, lines in pieces]
    assert [first for first, _ in pieces] == [sum(sizes[:k]) for k in range(len(sizes))]
    assert all(size % per == 0 for size in sizes[:-1])
