"""Actiongrams: construction, merging, text and JSON forms, errors with places."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import psgs
from psgs import Actiongram, FormatError


def test_from_strings_merges_equal_neighbours_and_adds_durations():
    ag = Actiongram.from_strings({"knee": ["a", "b", "b", "c"], "hip": "xy"},
                                 durations={"knee": [1, 2, 3, 0.5]})
    assert ag.string("knee") == ("a", "b", "c")
    assert ag.durations["knee"] == (1.0, 5.0, 0.5)
    assert ag.starts["knee"] == (0.0, 1.0, 6.0)
    assert len(ag) == 2 and ag.total_symbols == 5
    assert ag.names == ("knee", "hip")


def test_starts_follow_durations_and_origin():
    ag = Actiongram.from_strings({"a": "xyz"}, durations={"a": [2, 3, 4]}, starts={"a": 10})
    t, d = ag.starts["a"], ag.durations["a"]
    assert t == (10.0, 12.0, 15.0)
    assert all(t[j] + d[j] == t[j + 1] for j in range(len(t) - 1))


def test_text_form_reads_comments_durations_and_origins():
    text = "# header\n\nlknee: B G R@2.5 Y  # tail comment\nrknee@4: Y B@3\n"
    ag = Actiongram.from_text(text)
    assert ag.strings == {"lknee": ("B", "G", "R", "Y"), "rknee": ("Y", "B")}
    assert ag.durations["lknee"] == (1.0, 1.0, 2.5, 1.0)
    assert ag.starts["rknee"] == (4.0, 5.0)
    assert Actiongram.from_text(ag.to_text()) == ag


def test_subset_keeps_the_order_asked_for():
    ag = Actiongram.from_strings({"a": "xy", "b": "yz", "c": "zx"})
    sub = ag.subset(["c", "a"])
    assert sub.names == ("c", "a") and sub.string("c") == ("z", "x")
    with pytest.raises(KeyError):
        ag.string("nope")


@pytest.mark.parametrize("text, line, column, words", [
    ("a: x y@z\n", 1, 7, "unknown duration syntax"),
    ("a: x\nb: y@0\n", 2, 6, "must be positive"),
    ("a: x@-2\n", 1, 6, "must be positive"),
    (": x y\n", 1, 1, "non-empty"),
    ("a: x\n  a: y\n", 2, 3, "already given on line 1"),
    ("a: x y:z\n", 1, 6, "contains ':'"),
    ("a: x @2\n", 1, 6, "no symbol"),
    ("just words\n", 1, 1, "no ':'"),
    ("a@q: x\n", 1, 3, "start time"),
])
def test_bad_text_names_the_place(text, line, column, words):
    with pytest.raises(FormatError) as info:
        Actiongram.from_text(text, source="ag.txt")
    err = info.value
    assert (err.source, err.line, err.column) == ("ag.txt", line, column)
    assert words in err.message
    assert str(err).startswith(f"ag.txt:{line}:{column}: ")


def test_bad_values_in_python_are_format_errors():
    with pytest.raises(FormatError):
        Actiongram.from_strings({"a": "xy"}, durations={"a": [1, -1]})
    with pytest.raises(FormatError):
        Actiongram.from_strings({"a": ["x@1"]})
    with pytest.raises(FormatError):
        Actiongram.from_strings({"": "x"})
    with pytest.raises(FormatError):
        Actiongram.from_json('{"strings": [{"name": "a", "symbols": ["x"]}, '
                             '{"name": "a", "symbols": ["y"]}]}')
    with pytest.raises(FormatError) as info:
        Actiongram.from_json("{oops", source="x.json")
    assert info.value.line == 1 and info.value.source == "x.json"


def test_load_actiongram_by_suffix(tmp_path):
    ag = Actiongram.from_strings({"a": "xyx", "b": "q"}, durations={"b": [2.5]})
    (tmp_path / "ag.json").write_text(ag.to_json())
    (tmp_path / "ag.txt").write_text(ag.to_text())
    assert psgs.load_actiongram(tmp_path / "ag.json") == ag
    assert psgs.load_actiongram(str(tmp_path / "ag.txt")) == ag


symbols = st.text(alphabet="abcXYZ_01+-", min_size=1, max_size=3).filter(
    lambda s: not s.startswith("#"))
durations = st.one_of(st.integers(1, 50).map(float),
                      st.floats(1e-3, 1e3, allow_nan=False, allow_infinity=False))
strings = st.lists(st.tuples(symbols, durations), max_size=12)
names = st.text(alphabet="abcdefghij_0123456789.", min_size=1, max_size=8)


@st.composite
def actiongrams(draw):
    picked = draw(st.lists(names, min_size=1, max_size=5, unique=True))
    rows = {n: draw(strings) for n in picked}
    starts = {n: draw(st.sampled_from([0.0, 2.0, -1.5, 0.1])) for n in picked}
    return Actiongram.from_strings({n: [s for s, _ in r] for n, r in rows.items()},
                                   durations={n: [d for _, d in r] for n, r in rows.items()},
                                   starts=starts)


@settings(max_examples=150, deadline=None)
@given(actiongrams())
def test_round_trip_text_and_json(ag):
    assert Actiongram.from_text(ag.to_text()) == ag
    assert Actiongram.from_json(ag.to_json()) == ag
    for syms in ag.symbols:
        assert all(a != b for a, b in zip(syms, syms[1:]))


@pytest.mark.parametrize("page", ["actiongram.md", "pal.md"])
def test_documentation_examples_run(page):
    import doctest
    from pathlib import Path

    path = Path(__file__).resolve().parents[2] / "docs" / page
    result = doctest.testfile(str(path), module_relative=False, optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0


@pytest.mark.parametrize("name, content, words", [
    ("junk.txt", b"a: x\n\xff\xfe\x00garbage", "junk.txt:2:1: not UTF-8 text"),
    ("junk.json", b"\x89PNG\r\n", "junk.json:1:1: not UTF-8 text"),
    ("empty.txt", b"", "empty.txt:1:1: empty actiongram"),
    ("comments.txt", b"# only a comment\n\n", "comments.txt:1:1: empty actiongram"),
    ("empty.json", b'{"strings": []}', "empty.json:1:1: empty actiongram"),
    ("nested.json", b'{"strings": [{"name": "a", "symbols": [["x"]]}]}', "non-empty text"),
])
def test_unreadable_or_empty_files_are_one_format_error(tmp_path, name, content, words):
    path = tmp_path / name
    path.write_bytes(content)
    with pytest.raises(FormatError) as info:
        psgs.load_actiongram(path)
    assert words in str(info.value)


def test_a_huge_bad_token_gives_a_short_message():
    with pytest.raises(FormatError) as info:
        Actiongram.from_text("a: x@" + "q" * 100_000)
    assert "unknown duration syntax" in str(info.value) and len(str(info.value)) < 200
    with pytest.raises(FormatError) as info:
        Actiongram.from_strings({"n" * 100_000 + " ": "x"})
    assert "white space" in str(info.value) and len(str(info.value)) < 200


def test_a_byte_order_mark_is_not_part_of_the_first_name(tmp_path):
    path = tmp_path / "bom.txt"
    path.write_bytes("\ufeffhip: a b\n".encode("utf-8"))
    assert psgs.load_actiongram(path).names == ("hip",)
    path.write_bytes("\ufeffhip: a b\nknee: \xe9".encode("utf-8")[:-1] + b"\xff")
    with pytest.raises(FormatError, match=r"bom.txt:2:7: not UTF-8 text \(byte 0xc3\)"):
        psgs.load_actiongram(path)


@pytest.mark.parametrize("item", [
    '"durations": [1%s]' % ("0" * 400),
    '"start": 1%s' % ("0" * 400),
    '"durations": [1e308, 1e308]',
])
def test_numbers_too_large_for_a_float_are_format_errors(item):
    text = '{"strings": [{"name": "a", "symbols": ["x", "y"], %s}]}' % item
    if '"durations": [1' in item and "," not in item:
        text = text.replace('["x", "y"]', '["x"]')
    with pytest.raises(FormatError, match="finite|overflow"):
        Actiongram.from_json(text)


def test_unknown_names_in_durations_are_reported_in_the_order_given():
    import subprocess
    import sys

    code = ("from psgs import Actiongram\n"
            "try:\n"
            "    Actiongram.from_strings({'a': 'x'}, durations={'q1': [1], 'q2': [1], 'q3': [1],"
            " 'q4': [1]}, starts={'q5': 0})\n"
            "except Exception as exc:\n"
            "    print(exc.message)\n")
    seen = {subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                           env={**__import__("os").environ, "PYTHONHASHSEED": str(seed)},
                           check=True).stdout for seed in range(4)}
    assert seen == {"durations or starts given for unknown string 'q1'\n"}
