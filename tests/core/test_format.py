"""The text format: reading, writing, round trips and one clear error per mistake."""

from __future__ import annotations

import dataclasses
import random
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import psgs
import psgs.strategies as pst
from psgs import (IDLE, PCGS, PSGS, FormatError, Grammar, Nonterminal, Query, Rule, Terminal,
                  ValidationError, dumps, load, loads)

REPO = Path(__file__).resolve().parents[2]
GRAMMAR_FILES = sorted((REPO / "grammars").glob("*.psgs"))

SMALL = """\
psgs Small
component G1 start S
  p1: S -> "a" S
  p2: S -> "a"
component G2 start T
  q1: T -> "b" T
  q2: T -> "b"
sync
  (p1, q1)
  (p2, q2)
"""


def small_system() -> PSGS:
    S, T = Nonterminal("S"), Nonterminal("T")
    a, b = Terminal("a"), Terminal("b")
    g1 = Grammar("G1", S, (Rule("p1", S, (a, S)), Rule("p2", S, (a,))))
    g2 = Grammar("G2", T, (Rule("q1", T, (b, T)), Rule("q2", T, (b,))))
    return PSGS((g1, g2), sync=[("p1", "q1"), ("p2", "q2")], name="Small")


# ---------------------------------------------------------------- reading
def test_loads_builds_the_system_it_describes():
    assert loads(SMALL) == small_system()


def test_defaults_are_parallel_and_free():
    system = loads(SMALL)
    assert (system.mode, system.unsynchronised) == ("parallel", "free")


def test_settings_are_read():
    text = SMALL.replace("psgs Small\n", "psgs Small\nmode single\nunsynchronised strict\n")
    system = loads(text)
    assert (system.mode, system.unsynchronised) == ("single", "strict")


def test_a_hash_after_text_is_not_a_comment():
    # '#' starts a comment only as the first non-blank character of a line
    with pytest.raises(FormatError) as info:
        loads('psgs E\ncomponent G start S   # trailing\n  p: S -> "a"\n')
    assert (info.value.line, info.value.column) == (2, 23)


def test_comments_blank_lines_unicode_arrow_and_epsilon():
    text = """
  # comment
psgs E   // trailing
component G start S
  p: S → "a" S B   // unicode arrow
  q: S -> ε
  r: B ->
sync
  (p)   // a tuple
  # a comment between tuples
  (q)
"""
    system = loads(text)
    g = system.components[0]
    assert g.rule("q").rhs == () and g.rule("r").rhs == ()
    assert g.rule("p").rhs == (Terminal("a"), Nonterminal("S"), Nonterminal("B"))
    assert [t[0].label for t in system.sync] == ["p", "q"]


def test_no_final_newline_and_crlf_are_accepted():
    assert loads(SMALL.rstrip("\n")) == small_system()
    assert loads(SMALL.replace("\n", "\r\n")) == small_system()


def test_idle_marker_in_tuples():
    text = SMALL.replace("(p2, q2)", "(p2, q2)\n  (#, q1)\n  (p1, #)")
    system = loads(text)
    assert system.sync[2] == (IDLE, system.components[1].rule("q1"))
    assert system.sync[3] == (system.components[0].rule("p1"), IDLE)


def test_terminals_are_quoted_with_json_escapes_and_may_be_long():
    text = ('psgs W\ncomponent G start S\n'
            '  p: S -> "up" "d\\u00f6wn" "q\\"uote" "back\\\\slash" "#" "//" "->"\n')
    rule = loads(text).components[0].rules[0]
    assert [t.name for t in rule.rhs] == ["up", "döwn", 'q"uote', "back\\slash", "#", "//",
                                          "->"]


def test_keywords_may_name_symbols_rules_and_components():
    text = """\
psgs component
component start start sync
  component: sync -> mode "x"
  sync: mode -> start
  mode: start -> "y"
sync
  (component)
"""
    system = loads(text)
    assert system.name == "component"
    g = system.components[0]
    assert g.name == "start" and g.start == Nonterminal("sync")
    assert [r.label for r in g.rules] == ["component", "sync", "mode"]
    assert loads(dumps(system)) == system


def test_pcgs_header_settings_and_queries():
    text = """\
pcgs P
returning no
master G2
component G1 start S1
  p: S1 -> "a" ?G2
component G2 start S2
  q: S2 -> "b" ?G1
  r: S2 -> "b"
"""
    system = loads(text)
    assert isinstance(system, PCGS)
    assert system.returning is False and system.master == "G2"
    assert system.components[0].rules[0].rhs == (Terminal("a"), Query("G2"))
    assert not system.centralised


def test_pcgs_defaults():
    system = loads('pcgs P\ncomponent A start S\n  p: S -> "a"\n')
    assert system.returning is True and system.master == "A"


def test_load_reads_files_and_names_them_in_errors(tmp_path):
    path = tmp_path / "small.psgs"
    path.write_text(SMALL, encoding="utf-8")
    assert load(path) == small_system()
    assert load(str(path)) == small_system()
    bad = tmp_path / "bad.psgs"
    bad.write_text("psgs B\ncomponent G start S\n  p: S \"a\"\n", encoding="utf-8")
    with pytest.raises(FormatError) as info:
        load(bad)
    assert str(info.value).startswith(f"{bad}:3:8: ")


def test_loads_takes_utf8_bytes_and_locates_bad_ones():
    assert loads(SMALL.encode("utf-8")) == small_system()
    with pytest.raises(FormatError) as info:
        loads(b"psgs G\n\xc3(\n", source="b.psgs")
    assert str(info.value).startswith("b.psgs:2:1: not UTF-8")


def test_load_accepts_a_byte_order_mark(tmp_path):
    path = tmp_path / "bom.psgs"
    path.write_bytes(b"\xef\xbb\xbf" + SMALL.encode())
    assert load(path) == small_system()


# ---------------------------------------------------------------- errors
H = "psgs G\ncomponent A start S\n"
ERRORS = [
    # (name, text, line, column, words the message must hold)
    ("missing arrow", H + '  p: S "a"\n', 3, 8, "missing arrow"),
    ("missing arrow at end of line", H + "  p: S\n", 3, 7, "missing arrow"),
    ("unterminated string", H + '  p: S -> "a\n', 3, 11, "unterminated string"),
    ("unterminated line", H + "  p:\n", 3, 5, "unterminated line: expected a name"),
    ("label after the left side", H + '  S p -> "a"\n', 3, 7, "needs a label"),
    ("unterminated tuple", H + '  p: S -> "a"\nsync\n  (p\n', 5, 5, "unterminated tuple"),
    ("empty file", "", 1, 1, "empty file"),
    ("only comments", "# nothing\n\n// here\n", 1, 1, "empty file"),
    ("unknown label in a tuple", H + '  p: S -> "a"\nsync\n  (q)\n', 5, 4,
     "no rule labelled q"),
    ("tuple of wrong arity", H + '  p: S -> "a"\nsync\n  (p, #)\n', 5, 3,
     "2 entries but the system has 1 component"),
    ("terminal then nonterminal", H + '  p: S -> "a" a\n', 3, 15,
     "a is used as a nonterminal here but as a terminal"),
    ("nonterminal then terminal", H + '  p: S -> "S"\n', 3, 11,
     '"S" is used as a terminal here but as a nonterminal'),
    ("kinds across components",
     'psgs G\ncomponent A start S\n  p: S -> "X"\ncomponent B start X\n  q: X -> "b"\n', 4, 19,
     "used as a nonterminal here but as a terminal on line 3"),
    ("control character", "psgs G\x00\n", 1, 7,
     "unexpected character U+0000 NULL (control characters and binary data are not allowed)"),
    ("a character the format has no use for", H + '  p: S -> "a" %\n',
     3, 15, "unexpected character '%' (U+0025 PERCENT SIGN); expected one of"),
    ("a look-alike of a Latin letter", H + '  p: S -> "a" \u0430\n',
     3, 15, "unexpected character '\u0430' (U+0430 CYRILLIC SMALL LETTER A)"),
    ("a quoted text where a name goes", 'psgs G "a\x85"\n', 1, 8,
     "unexpected '\"a\\x85\"' (it holds U+0085 NEXT LINE); expected one of a name"),
    ("no header", 'component A start S\n  p: S -> "a"\n', 1, 1, "psgs NAME"),
    ("second header", "psgs G\npsgs H\n", 2, 1, "second header"),
    ("unknown mode", "psgs G\nmode sequential\n", 2, 6, "parallel or single"),
    ("pcgs setting in psgs", "psgs G\nreturning yes\n", 2, 1, "setting of a pcgs"),
    ("setting after a component", H + '  p: S -> "a"\nmode single\n', 4, 1,
     "before the first component"),
    ("setting twice", "psgs G\nmode single\nmode parallel\n", 3, 1, "set twice"),
    ("bad component line", "psgs G\ncomponent A S\n", 2, 1, "component NAME start SYMBOL"),
    ("duplicate component", H + '  p: S -> "a"\ncomponent A start S\n  q: S -> "b"\n', 4, 11,
     "second component named A"),
    ("rule before any component", 'psgs G\n  p: S -> "a"\n', 2, 3, "before any component"),
    ("rule after sync", H + '  p: S -> "a"\nsync\n  q: S -> "b"\n', 5, 3, "after 'sync'"),
    ("rule without label", H + '  S -> "a"\n', 3, 5, "needs a label"),
    ("duplicate label", H + '  p: S -> "a"\n  p: S -> "b"\n', 4, 3, "second rule labelled p"),
    ("repeated rule", H + '  p: S -> "a"\n  q: S -> "a"\n', 4, 3, "repeats rule p"),
    ("start symbol without rule", H + '  p: T -> "a"\n', 2, 1, "start symbol S has no rule"),
    ("component without rules", "psgs G\ncomponent A start S\n", 2, 1, "has no rules"),
    ("no component", "psgs G\nmode single\n", 1, 1, "at least one"),
    ("empty terminal", H + '  p: S -> ""\n', 3, 11, "non-empty"),
    ("bad escape", H + '  p: S -> "\\q"\n', 3, 11, "bad terminal"),
    # a raw control character inside quotes: the error outside quotes gives, at its column
    ("control character in a terminal", H + '  p: S -> "a\x1b[2J"\n', 3, 13,
     "unexpected character U+001B ESCAPE (control characters"),
    ("carriage return in a terminal", H + '  p: S -> "a\rb"\n', 3, 13,
     "unexpected character U+000D CARRIAGE RETURN (control characters"),
    ("bad escape beside a control character", H + '  p: S -> "\\q\x07"\n', 3, 11,
     'bad terminal "\\q\\x07" (it holds U+0007 ALERT): Invalid \\escape'),
    ("epsilon with symbols", H + '  p: S -> "a" ε\n', 3, 15, "ε stands alone"),
    ("query in a psgs", H + "  p: S -> ?A\n", 3, 11, "only a pcgs has queries"),
    ("query of no component", 'pcgs G\ncomponent A start S\n  p: S -> "a" ?C\n', 3, 3,
     "?C, which names no component"),
    ("unknown master", 'pcgs G\nmaster B\ncomponent A start S\n  p: S -> "a"\n', 2, 8,
     "master B is not a component"),
    ("sync in a pcgs", 'pcgs G\ncomponent A start S\n  p: S -> "a"\nsync\n', 4, 1,
     "no 'sync' section"),
    ("tuple before sync", H + '  p: S -> "a"\n  (p)\n', 4, 3, "outside the 'sync' section"),
    ("all-idle tuple", H + '  p: S -> "a"\nsync\n  (#)\n', 5, 3, "idles in every component"),
    ("repeated tuple", H + '  p: S -> "a"\nsync\n  (p)\n  (p)\n', 6, 3, "repeats the tuple"),
    ("second sync", H + '  p: S -> "a"\nsync\n  (p)\nsync\n', 6, 1, "second 'sync'"),
    ("stray word", H + '  p: S -> "a"\nhello world\n', 4, 1, "cannot read line"),
]


@pytest.mark.parametrize("name,text,line,column,words", ERRORS, ids=[e[0] for e in ERRORS])
def test_each_mistake_gives_one_located_error(name, text, line, column, words):
    with pytest.raises(FormatError) as info:
        loads(text, source="x.psgs")
    error = info.value
    assert (error.source, error.line, error.column) == ("x.psgs", line, column), str(error)
    assert words in error.message, str(error)
    message = str(error)
    assert message.startswith(f"x.psgs:{line}:{column}: ")
    assert "\n" not in message and "Traceback" not in message
    assert message.isprintable(), message  # no raw control character echoed from the text


@pytest.mark.parametrize("source", [None, 3, b"x.psgs"])
def test_loads_refuses_a_source_that_is_no_str(source):
    # it was used only to word an error, so a bad text raised a TypeError ("+=") instead
    with pytest.raises(psgs.ValidationError, match="source must be a str"):
        loads("psgs G\n", source=source)
    with pytest.raises(psgs.ValidationError, match="source must be a str"):
        loads(H + '  p: S -> "a"\n', source=source)


def test_binary_junk_is_one_located_error(tmp_path):
    path = tmp_path / "junk.psgs"
    path.write_bytes(b"psgs G\ncomp\xffonent\n")
    with pytest.raises(FormatError) as info:
        load(path)
    assert (info.value.line, info.value.column) == (2, 5)
    assert "not UTF-8" in str(info.value) and str(info.value).startswith(f"{path}:2:5:")


def test_random_bytes_never_escape_as_anything_but_format_error(tmp_path):
    rng = random.Random(7)
    path = tmp_path / "noise.psgs"
    for _ in range(30):
        path.write_bytes(bytes(rng.randrange(256) for _ in range(rng.randrange(1, 200))))
        with pytest.raises(FormatError):
            load(path)


@settings(max_examples=150, deadline=None)
@given(st.text(alphabet=st.sampled_from(list('psgcomnt SAB:->"()#,\n?ε→ab12_/')), max_size=80))
def test_arbitrary_text_parses_or_fails_with_a_located_format_error(text):
    try:
        system = loads(text, source="fuzz")
    except FormatError as error:
        assert str(error).startswith("fuzz:") and error.line is not None
    else:
        assert isinstance(system, (PSGS, PCGS))
        assert loads(dumps(system)) == system


def test_the_command_line_prints_one_line_and_no_traceback(tmp_path):
    path = tmp_path / "bad.psgs"
    path.write_text("psgs G\ncomponent A start S\n  p: S \"a\"\n", encoding="utf-8")
    done = subprocess.run([sys.executable, "-m", "psgs", "show", str(path)],
                          capture_output=True, text=True, cwd=tmp_path)
    assert done.returncode != 0
    lines = done.stderr.strip().splitlines()
    assert len(lines) == 1 and f"{path}:3:8:" in lines[0] and "missing arrow" in lines[0]
    assert "Traceback" not in done.stderr


# ---------------------------------------------------------------- writing
def test_dumps_is_canonical_and_readable():
    text = dumps(small_system())
    assert text.splitlines()[:3] == ["psgs Small", "mode parallel", "unsynchronised free"]
    assert "  p1: S -> \"a\" S" in text and "  (p2, q2)" in text
    assert dumps(loads(text)) == text


def test_dumps_writes_epsilon_and_idle():
    S = Nonterminal("S")
    g = Grammar("G", S, (Rule("e", S, ()), Rule("a", S, (Terminal("a"), S))))
    h = Grammar("H", S, (Rule("b", S, (Terminal("b"),)),))
    system = PSGS((g, h), sync=[("a", "#")], name="E")
    text = dumps(system)
    assert "  e: S -> ε" in text and "  (a, #)" in text
    assert loads(text) == system


def test_dump_writes_a_file_load_reads(tmp_path):
    path = tmp_path / "out.psgs"
    psgs.dump(small_system(), path)
    assert load(path) == small_system()


@pytest.mark.parametrize("path", GRAMMAR_FILES, ids=[p.name for p in GRAMMAR_FILES])
def test_round_trip_of_every_shipped_grammar(path):
    system = load(path)
    assert loads(dumps(system)) == system
    other = (dataclasses.replace(system, mode="single") if isinstance(system, PSGS)
             else dataclasses.replace(system, returning=not system.returning))
    assert loads(dumps(other)) == other


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(pst.psgs_systems(max_components=3))
def test_round_trip_of_generated_psgs(system):
    assert loads(dumps(system)) == system


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(pst.pcgs_systems(max_components=3))
def test_round_trip_of_generated_pcgs(system):
    assert loads(dumps(system)) == system


# Names and terminal texts the shared strategies never draw: keywords, odd text.
KEYWORDS = ["psgs", "pcgs", "mode", "unsynchronised", "returning", "master", "component",
            "start", "sync", "parallel", "single", "free", "strict", "yes", "no"]
identifiers = st.one_of(st.sampled_from(KEYWORDS),
                        st.from_regex(r"[A-Za-z_][A-Za-z0-9_]{0,6}", fullmatch=True))
# (no control or format character: a terminal refuses them, tests/core/test_format_invisible.py)
terminal_texts = st.text(st.characters(blacklist_categories=("Cs", "Zs", "Zl", "Zp", "Cc", "Cf")),
                         min_size=1, max_size=6).filter(lambda t: not any(c.isspace() for c in t))


@st.composite
def odd_psgs(draw):
    n = draw(st.integers(1, 3))
    component_names = draw(st.lists(identifiers, min_size=n, max_size=n, unique=True))
    texts = draw(st.lists(terminal_texts, min_size=1, max_size=4, unique=True))
    nt_names = draw(st.lists(identifiers, min_size=1, max_size=4, unique=True)
                    .filter(lambda names: not set(names) & set(texts)))
    components = []
    for name in component_names:
        rules = {}
        for lhs in nt_names[:draw(st.integers(1, len(nt_names)))]:
            rhs = tuple(draw(st.lists(st.one_of(st.sampled_from(texts).map(Terminal),
                                                st.sampled_from(nt_names).map(Nonterminal)),
                                      max_size=3)))
            rules.setdefault((lhs, rhs), draw(identifiers))
        labels, out = set(), []
        for (lhs, rhs), label in rules.items():
            if label in labels:
                continue
            labels.add(label)
            out.append(Rule(label, Nonterminal(lhs), rhs))
        components.append(Grammar(name, Nonterminal(nt_names[0]), tuple(out)))
    tuples = []
    for _ in range(draw(st.integers(0, 3))):
        entry = tuple(draw(st.one_of(st.none(), st.sampled_from(g.rules))) for g in components)
        if any(e is not None for e in entry) and entry not in tuples:
            tuples.append(entry)
    return PSGS(tuple(components), sync=tuples, name=draw(identifiers),
                mode=draw(st.sampled_from(["parallel", "single"])),
                unsynchronised=draw(st.sampled_from(["free", "strict"])))


@settings(max_examples=75, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                  HealthCheck.filter_too_much])
@given(odd_psgs())
def test_round_trip_with_keywords_as_names_and_odd_terminal_text(system):
    assert loads(dumps(system)) == system


# ---------------------------------------------------------------- docs/format.md
DOC = REPO / "docs" / "format.md"


def doc_blocks(kind: str) -> list[str]:
    import re
    return re.findall(rf"```{kind}\n(.*?)```", DOC.read_text(encoding="utf-8"), re.S)


def test_every_psgs_block_of_the_format_page_parses():
    blocks = doc_blocks("psgs")
    assert len(blocks) >= 3
    for block in blocks:
        system = loads(block, source="docs")
        assert loads(dumps(system)) == system
    assert loads(blocks[0]) == load(REPO / "grammars" / "paper_example.psgs")


def test_every_error_example_of_the_format_page_gives_its_message():
    import re
    text = DOC.read_text(encoding="utf-8")
    pairs = re.findall(r"```psgs-error\n(.*?)```\s*```text\n(.*?)\n```", text, re.S)
    assert len(pairs) >= 9
    for source, message in pairs:
        with pytest.raises(FormatError) as info:
            loads(source, source="example.psgs")
        assert str(info.value) == message


@pytest.mark.usefixtures("examples_tempdir")
def test_the_python_blocks_of_the_format_page_run(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(REPO)
    blocks = doc_blocks("python")
    assert len(blocks) >= 2
    for block in blocks:
        exec(compile(block, str(DOC), "exec"), {})
    printed = capsys.readouterr().out
    assert printed.rstrip("\n") == doc_blocks("text")[0].rstrip("\n")


@settings(max_examples=80, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                 HealthCheck.filter_too_much])
@given(odd_psgs(), st.booleans(), st.data())
def test_pcgs_round_trip_with_keywords_as_names(shape, returning, data):
    components = list(shape.components)
    asking = components[0]
    target = data.draw(st.sampled_from([g.name for g in components]))
    rule = asking.rules[0]
    labels = {r.label for r in asking.rules}
    label = next(f"ask{k}" for k in range(len(labels) + 1) if f"ask{k}" not in labels)
    extra = Rule(label, rule.lhs, rule.rhs + (Query(target),))
    components[0] = Grammar(asking.name, asking.start, asking.rules + (extra,))
    master = data.draw(st.sampled_from([g.name for g in components]))
    system = PCGS(tuple(components), returning=returning, master=master, name=shape.name)
    assert loads(dumps(system)) == system


@pytest.mark.parametrize("path", [None, 3, ["a.psgs"], b"a.psgs"])
def test_load_refuses_what_is_no_path_naming_it(path):
    with pytest.raises(ValidationError, match="load reads a path"):
        load(path)
