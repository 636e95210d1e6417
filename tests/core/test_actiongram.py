"""Actiongrams: construction, merging, text and JSON forms, errors with places."""

from __future__ import annotations

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import psgs
from psgs import Actiongram, FormatError, ValidationError


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
    assert psgs.load(tmp_path / "ag.json") == ag
    assert psgs.load(str(tmp_path / "ag.txt"), kind="actiongram") == ag


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


@settings(max_examples=75, deadline=None)
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
        psgs.load(path, kind="actiongram")
    assert words in str(info.value)


def test_a_huge_bad_token_gives_a_short_message():
    with pytest.raises(FormatError) as info:
        Actiongram.from_text("a: x@" + "q" * 100_000)
    assert "unknown duration syntax" in str(info.value) and len(str(info.value)) < 200
    with pytest.raises(FormatError) as info:
        Actiongram.from_strings({"n" * 100_000 + " ": "x"})
    # (201 characters: the name cut to 40, the message naming its character, and the source
    # "Actiongram", which refused the value, before it)
    assert "white space" in str(info.value) and len(str(info.value)) < 210


def test_a_byte_order_mark_is_not_part_of_the_first_name(tmp_path):
    path = tmp_path / "bom.txt"
    path.write_bytes("\ufeffhip: a b\n".encode("utf-8"))
    assert psgs.load(path, kind="actiongram").names == ("hip",)
    path.write_bytes("\ufeffhip: a b\nknee: \xe9".encode("utf-8")[:-1] + b"\xff")
    with pytest.raises(FormatError, match=r"bom.txt:2:7: not UTF-8 text: byte 0xc3 "):
        psgs.load(path, kind="actiongram")


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


# -- the optional extras: displacements, actuator map, skeleton ------------------------------

def test_displacements_merge_with_their_segments_and_default_to_unknown():
    ag = Actiongram.from_strings({"knee.rx": "abbc", "knee.ry": "xy"},
                                 displacements={"knee.rx": [1.5, -2, 0.25, 3]})
    assert ag.string("knee.rx") == ("a", "b", "c")
    assert ag.displacements("knee.rx") == (1.5, -1.75, 3.0)
    assert ag.displacements("knee.ry") is None
    with pytest.raises(FormatError, match="3 symbols but 2 displacements"):
        Actiongram.from_strings({"a": "xyz"}, displacements={"a": [1, 2]})
    with pytest.raises(FormatError, match="finite"):
        Actiongram.from_strings({"a": "x"}, displacements={"a": [float("nan")]})
    with pytest.raises(FormatError, match="must be a number"):
        Actiongram.from_strings({"a": "x"}, displacements={"a": [True]})


def test_actuators_default_to_the_name_before_the_first_dot():
    ag = Actiongram.from_strings({"lfemur.rx": "ab", "lfemur.rz": "b", "root": "a",
                                  "rhand.x.y": "a"})
    assert ag.actuator_map == {"lfemur.rx": "lfemur", "lfemur.rz": "lfemur", "root": "root",
                               "rhand.x.y": "rhand"}
    assert ag.actuators == ("lfemur", "root", "rhand")
    assert ag.channels("lfemur") == ("lfemur.rx", "lfemur.rz")
    assert ag.skeleton == {} and ag.parent("lfemur") is None
    moved = Actiongram.from_strings({"a.x": "ab", "b": "a"}, actuators={"b": "arm"})
    assert moved.actuator("b") == "arm" and moved.actuators == ("a", "arm")


def test_skeleton_neighbours_and_validation():
    ag = Actiongram.from_strings({"lhumerus.rx": "ab"}, skeleton={
        "root": None, "lclavicle": "root", "lhumerus": "lclavicle", "lradius": "lhumerus"})
    assert ag.parent("lhumerus") == "lclavicle" and ag.parent("root") is None
    assert ag.neighbours("lhumerus") == ("lclavicle", "lradius")
    assert ag.neighbours("root") == ("lclavicle",)
    assert ag.subset(["lhumerus.rx"]).skeleton == ag.skeleton
    with pytest.raises(FormatError, match="cycle"):
        Actiongram.from_strings({"a": "x"}, skeleton={"a": "b", "b": "c", "c": "a"})
    with pytest.raises(FormatError, match="its own parent"):
        Actiongram.from_strings({"a": "x"}, skeleton={"a": "a"})
    with pytest.raises(FormatError, match="white space"):
        Actiongram.from_strings({"a": "x"}, skeleton={"a": "b c"})
    long_chain = {f"j{i}": f"j{i + 1}" for i in range(20_000)}  # linear-time cycle check
    assert len(Actiongram.from_strings({"a": "x"}, skeleton=long_chain).skeleton) == 20_000


def test_text_form_of_the_extras_reads_and_round_trips():
    text = ("lfemur.rx: B@0.5~12.25 G@1~-3\nlfemur.ry: Y B\nhand: B@2~1e-05\n"
            "%actuator arm: hand\n%parent lfemur: root\n%parent root:\n%parent arm: lfemur\n")
    ag = Actiongram.from_text(text)
    assert ag.displacements("lfemur.rx") == (12.25, -3.0)
    assert ag.displacements("lfemur.ry") is None
    assert ag.actuator_map == {"lfemur.rx": "lfemur", "lfemur.ry": "lfemur", "hand": "arm"}
    assert ag.skeleton == {"lfemur": "root", "root": None, "arm": "lfemur"}
    assert ag.to_text() == text
    assert Actiongram.from_json(ag.to_json()) == ag
    old = Actiongram.from_text("lknee: B G@2\n")  # a file without extras reads as before
    assert old.displacements("lknee") is None and old.skeleton == {}
    assert "~" not in old.to_text() and "%" not in old.to_text()


@pytest.mark.parametrize("text, words", [
    ("a: B@1~x", "f.txt:1:7: unknown displacement syntax '~x'"),
    ("a: B@1~2 G", "f.txt:1:10: give a displacement (sym@D~X) for every symbol"),
    ("a: B@~2", "f.txt:1:5: unknown duration syntax"),
    ("%parent a: b c", "f.txt:1:1: %parent a: one parent, not 2"),
    ("%parent a: b\n%parent b: a", "f.txt:2:1: skeleton: the parents of 'a' form a cycle"),
    ("%actuator j: zz\na: x", "f.txt:1:1: %actuator names unknown string 'zz'"),
    ("%actuator j: a\n%actuator k: a\na: x", "f.txt:2:1: string 'a' is given an actuator twice"),
    ("%parent a:\n%parent a: b", "f.txt:2:1: skeleton: 'a' is given a parent twice"),
    ("%parent  : b", "f.txt:1:1: %parent: an actuator name must be non-empty text"),
])
def test_bad_extras_in_text_are_one_line_format_errors(text, words):
    with pytest.raises(FormatError) as info:
        Actiongram.from_text(text, source="f.txt")
    assert str(info.value).startswith(words) and "\n" not in str(info.value)


@pytest.mark.parametrize("doc, words", [
    ('{"strings": [{"name": "a", "symbols": ["x"], "displacements": 3}]}', "must be a list"),
    ('{"strings": [{"name": "a", "symbols": ["x"], "displacements": ["q"]}]}', "a number"),
    ('{"strings": [{"name": "a", "symbols": ["x"], "actuator": ""}]}', "non-empty"),
    ('{"strings": [{"name": "a", "symbols": ["x"]}], "skeleton": [1]}', "'skeleton' must be"),
    ('{"strings": [{"name": "a", "symbols": ["x"]}], "skeleton": {"a": 3}}', "non-empty text"),
])
def test_bad_extras_in_json_are_format_errors(doc, words):
    with pytest.raises(FormatError, match=words):
        Actiongram.from_json(doc, source="f.json")


joints = st.sampled_from(["root", "lfemur", "ltibia", "lhumerus", "arm"])


@st.composite
def actiongrams_with_extras(draw):
    base = draw(actiongrams())
    disps = draw(st.floats(-1e4, 1e4, allow_nan=False, allow_infinity=False))
    rows = {n: [disps * (j % 3 - 1) for j in range(len(s))] for n, s in base.strings.items()
            if draw(st.booleans())}
    owners = {n: draw(joints) for n in base.names if draw(st.booleans())}
    order = draw(st.permutations(["root", "lfemur", "ltibia", "lhumerus", "arm"]))
    skeleton = {j: (order[k - 1] if k else None) for k, j in enumerate(order)
                if draw(st.booleans())}
    return Actiongram.from_strings(base.strings, base.durations,
                                   {n: base.origins[base.index(n)] for n in base.names},
                                   displacements=rows, actuators=owners, skeleton=skeleton)


@settings(max_examples=75, deadline=None)
@given(actiongrams_with_extras())
def test_round_trip_text_and_json_with_extras(ag):
    assert Actiongram.from_text(ag.to_text()) == ag
    assert Actiongram.from_json(ag.to_json()) == ag


# ---- inputs that once crashed with an undocumented exception
def test_deeply_nested_json_is_a_format_error():
    with pytest.raises(FormatError, match="nested too deeply"):
        Actiongram.from_json("[" * 100_000, source="deep.json")


def test_a_json_integer_of_thousands_of_digits_is_a_format_error():
    text = '{"strings": [{"name": "a", "symbols": ["x"], "durations": [' + "9" * 5000 + "]}]}"
    with pytest.raises(FormatError, match="not JSON that can be read") as err:
        Actiongram.from_json(text, source="long.json")
    assert err.value.source == "long.json"


def test_induce_on_unreadable_json_is_one_line_not_a_traceback(tmp_path, capsys):
    from psgs.cli import main
    path = tmp_path / "deep.json"
    path.write_text("[" * 100_000)
    assert main(["induce", str(path)]) == 2
    err = capsys.readouterr().err
    assert "nested too deeply" in err and "Traceback" not in err


@pytest.mark.parametrize("text", ["s@1e15: a@1e-9 b@1e-9", "s: a@1e20 b@1"])
def test_durations_that_vanish_beside_the_start_time_are_rejected(text):
    with pytest.raises(FormatError, match="vanishes beside its start time"):
        Actiongram.from_text(text)


def test_durations_that_vanish_are_rejected_from_python_too():
    with pytest.raises(FormatError, match="T \\+ D == T"):
        Actiongram.from_strings({"s": "ab"}, durations={"s": [1e-9, 1e-9]}, starts={"s": 1e15})
    # small durations beside a small start are fine
    assert Actiongram.from_strings({"s": "ab"}, durations={"s": [1e-9, 1e-9]}).starts["s"] == (
        0.0, 1e-9)


@pytest.mark.parametrize("text, place, words", [
    ("hip: a\ns@1e15: a@1e-9 b@1e-9\n", "2:9", "duration 1e-09 of symbol 1 vanishes"),
    ("hip: a\n  s@1e308: a@1e308\n", "2:3", "string 's': its times overflow"),
    ("hip: a\ns: a@1~1e308 a@1~1e308\n", "2:1", "its displacements overflow"),
    ("hip: a\n%parent x: y\nknee: b\n%parent x: z\n", "4:1", "'x' is given a parent twice"),
    ("%parent x: x\nhip: a\n", "1:1", "'x' is its own parent"),
    ("%parent a: b\n%parent b: c\n%parent c: a\nhip: a\n", "3:1", "form a cycle"),
    ("%parent a: b@c\nhip: a\n", "1:1", "actuator name 'b@c' must have no"),
    ("hip: a\n%actuator j: hip\n%actuator k: nope\n", "3:1", "unknown string 'nope'"),
])
def test_what_the_text_form_refuses_as_a_whole_is_named_at_its_line(text, place, words):
    # these were found once every line was read, and named the file alone
    with pytest.raises(FormatError) as caught:
        Actiongram.from_text(text, source="f.txt")
    assert str(caught.value).startswith(f"f.txt:{place}: ") and words in str(caught.value)


def test_displacements_that_overflow_when_equal_neighbours_merge_are_rejected():
    # each is finite, their sum is not: the actiongram loaded, and its text did not read back
    with pytest.raises(FormatError, match="string 's': its displacements overflow"):
        Actiongram.from_text("s: a@1~1e308 a@1~1e308 b@1~0\n", source="s.txt")
    with pytest.raises(FormatError, match="displacements overflow"):
        Actiongram.from_strings({"s": "aa"}, displacements={"s": [-1e308, -1e308]})
    kept = Actiongram.from_strings({"s": "aa"}, displacements={"s": [1e308, 1e308]},
                                   keep_repeats=True)
    assert Actiongram.from_text(kept.to_text()) == kept


@pytest.mark.parametrize("where", ["name", "symbol"])
def test_a_lone_surrogate_is_rejected_so_to_text_can_be_written(where):
    name, symbol = ("\\ud800", "a") if where == "name" else ("a", "\\ud800")
    text = '{"strings": [{"name": "%s", "symbols": ["%s"]}]}' % (name, symbol)
    with pytest.raises(FormatError, match="lone surrogate"):
        Actiongram.from_json(text)
    with pytest.raises(FormatError, match="lone surrogate"):
        Actiongram.from_strings({"\ud800" if where == "name" else "a":
                                 ["a" if where == "name" else "\ud800"]})


def test_a_control_character_is_an_error_at_its_line_and_column(tmp_path):
    path = tmp_path / "nul.txt"
    path.write_bytes(b"a: x y\nb: x\x00 y\n")
    with pytest.raises(FormatError, match=r"nul.txt:2:5: control character U\+0000"):
        psgs.load(path, kind="actiongram")
    with pytest.raises(FormatError, match="control character"):
        Actiongram.from_strings({"a": ["x\x07"]})


@pytest.mark.parametrize("strings", [["ab"], None, "ab"])
def test_strings_not_named_are_a_validation_error(strings):
    with pytest.raises(ValidationError, match="must map each string's name"):
        Actiongram.from_strings(strings)


@pytest.mark.parametrize("breaker", ["\x0b", "\x0c", "\x1c", "\x85", "\u2028", "\u2029", "\r"])
def test_a_character_splitlines_breaks_at_is_an_error_on_its_own_line(breaker):
    # str.splitlines would read the one line as two, and name a line the file does not have
    with pytest.raises(FormatError, match=r"t.txt:2:7: control character U\+"):
        Actiongram.from_text(f"a: x y\nb: p q{breaker}c: r s\n", source="t.txt")


def test_windows_line_ends_still_read():
    assert Actiongram.from_text("a: x y\r\nb: p q\r\n").names == ("a", "b")


@pytest.mark.parametrize("doc, words", [
    # json.loads keeps the last of two equal keys: the first list of strings was lost
    ('{"strings": [{"name": "a", "symbols": ["x"]}], "strings": [{"name": "b", "symbols": ["y"]}]}',
     "f.json:1:48: key 'strings' is given twice"),
    ('{"strings": [{"name": "a", "symbols": ["x"]}], "skeleton": {"a": null, "a": "b"}}',
     "f.json:1:72: key 'a' is given twice"),
    # a misspelt key was ignored: the durations read as 1 each, the skeleton as none
    ('{"strings": [{"name": "a", "symbols": ["x", "y"], "duration": [5, 6]}]}',
     (r"f.json:1:51: strings\[0\] has unknown key 'duration' \(its keys: name, start, symbols, "
      r"durations")),
    ('{"strings": [{"name": "a", "symbols": ["x"]}], "skeletn": {"a": null}}',
     "f.json:1:48: the document has unknown key 'skeletn'"),
    # another format, or a later version, was read as this one
    ('{"format": "psgs-grammar", "strings": [{"name": "a", "symbols": ["x"]}]}',
     "f.json:1:12: 'format' is 'psgs-grammar', not 'psgs-actiongram'"),
    ('{"format": "psgs-actiongram", "version": 2, "strings": [{"name": "a", "symbols": ["x"]}]}',
     "f.json:1:42: 'version' is 2: this reader knows version 1"),
])
def test_json_that_would_lose_data_is_a_format_error(doc, words):
    # each at the value, or the key, at fault (a key given twice: at the second)
    with pytest.raises(FormatError, match="^" + words) as info:
        Actiongram.from_json(doc, source="f.json")
    assert "\n" not in str(info.value)


def test_a_name_that_starts_with_a_byte_order_mark_is_refused(tmp_path):
    # it was kept, and written first in the file; psgs.load drops a leading U+FEFF, so the
    # file read back as another actiongram (string 'a' where 'U+FEFF a' was written)
    with pytest.raises(FormatError, match="starts with U\\+FEFF"):
        Actiongram.from_strings({"\ufeffa": "xy"})
    with pytest.raises(FormatError, match="starts with U\\+FEFF") as info:
        Actiongram.from_text("\ufeffa: x y\n", source="f.txt")
    assert (info.value.line, info.value.column) == (1, 1)
    ag = Actiongram.from_strings({"a\ufeff": "xy"})  # elsewhere in a name it is kept, and read
    psgs.dump(ag, tmp_path / "ok.actiongram")
    assert psgs.load(tmp_path / "ok.actiongram") == ag
