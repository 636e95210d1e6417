"""The inducer contract: parameters, the registry and its plug-ins, performances as input."""

from __future__ import annotations

import ast
import importlib
import importlib.util
import os
import subprocess
import sys
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import psgs
import psgs.induce.registry as registry
from psgs import Actiongram, ValidationError
from psgs.cli import main
from psgs.induce import PAL, Induction, Inducer, Sequential, StringReport, available, get
from psgs.induce.base import as_performances
from psgs.induce.synthetic import generate

ROOT = Path(__file__).resolve().parents[2]


class FakeEntryPoint:
    """What importlib.metadata gives for one entry point, enough for the registry."""

    def __init__(self, name, target, value="fakepkg.learner:Learner", error=None):
        self.name, self.value, self._target, self._error = name, value, target, error

    def load(self):
        if self._error is not None:
            raise self._error
        return self._target


def plug_in(monkeypatch, *entry_points):
    monkeypatch.setattr(registry, "entry_points", lambda group: list(entry_points))


class Echo(Inducer):
    """A plug-in inducer: every string with at least ``least`` symbols is a component."""

    name = "echo"

    def __init__(self, *, least: int = 1, tags: list | None = None) -> None:
        if isinstance(least, bool) or not isinstance(least, int) or least < 1:
            raise ValidationError(f"parameter least must be an integer >= 1, not {least!r}")
        self.least = least
        self.tags = [] if tags is None else tags

    def induce(self, performances):
        takes = as_performances(performances, "Echo.induce")
        if len(takes) > 1:
            raise ValidationError("Echo.induce learns from one actiongram")
        ag = takes[0]
        patterns = {n: s for n, s in ag.strings.items() if len(s) >= self.least}
        reports = [StringReport(n, "component" if n in patterns else "too short")
                   for n in ag.names]
        return self.build_induction(ag.names, patterns, {n: ((0.0, 1.0),) for n in patterns},
                                    reports, synchronise=False)


class DuckTyped:
    """A plug-in that is not an Inducer but has ``induce``: accepted."""

    def __init__(self, colour="red"):
        self.colour = colour

    def induce(self, performances):
        return Induction(None, (), {}, {})


# -- parameters: get_params, set_params, clone -----------------------------------------------
def test_set_params_validates_and_changes_nothing_on_error():
    pal = PAL()
    before = pal.get_params()
    with pytest.raises(ValidationError, match="conserve must be <= 1"):
        pal.set_params(min_copies=5, conserve=2.0)
    assert pal.get_params() == before  # all or nothing: min_copies was not changed either
    with pytest.raises(ValidationError, match="inducer pal has no parameter 'colour' "
                                              "\\(its parameters: min_copies,"):
        pal.set_params(colour="red")
    assert pal.set_params(min_copies=5, timing="period") is pal
    assert (pal.min_copies, pal.timing) == (5, "period")
    with pytest.raises(ValidationError, match="timing must be one of content, period, auto"):
        pal.set_params(timing="tempo")


@pytest.mark.parametrize("make, bad", [
    (PAL, dict(min_copies=1)), (PAL, dict(alpha=float("nan"))), (PAL, dict(seeds=True)),
    (PAL, dict(timing=3)), (PAL, dict(conserve="high")),
    (Sequential, dict(min_count=1)), (Sequential, dict(max_rules=2.5)),
])
def test_every_parameter_error_is_a_validation_error(make, bad):
    with pytest.raises(ValidationError) as info:
        make(**bad)
    assert isinstance(info.value, ValueError) and isinstance(info.value, psgs.PSGSError)
    with pytest.raises(ValidationError):
        make().set_params(**bad)
    with pytest.raises(ValidationError):
        make().clone(**bad)
    with pytest.raises(ValidationError):
        get(make.name, **bad)


def test_clone_is_independent_and_equal_in_parameters():
    tags = ["wave"]
    a = Echo(least=2, tags=tags)
    b = a.clone()
    assert type(b) is Echo and b is not a and b.get_params() == a.get_params()
    b.tags.append("bow")  # a deep copy: the clone's mutable parameter is its own
    b.set_params(least=7)
    assert a.get_params() == {"least": 2, "tags": ["wave"]} and tags == ["wave"]
    c = a.clone(least=3)
    assert (c.least, a.least) == (3, 2)
    with pytest.raises(ValidationError, match="inducer echo has no parameter 'most'"):
        a.clone(most=3)


@settings(max_examples=40)
@given(min_copies=st.integers(2, 10), conserve=st.floats(0.01, 1.0),
       timing=st.sampled_from(["content", "period", "auto"]))
def test_params_survive_clone_set_params_and_rebuild(min_copies, conserve, timing):
    pal = PAL(min_copies=min_copies, conserve=conserve, timing=timing)
    params = pal.get_params()
    assert PAL(**params).get_params() == params == pal.clone().get_params()
    assert PAL().set_params(**params).get_params() == params
    assert repr(pal) == repr(pal.clone())


def test_an_inducer_must_name_its_parameters():
    class Loose(Inducer):
        def __init__(self, **kwargs):
            self.kwargs = kwargs

    with pytest.raises(TypeError, match="must be named one by one"):
        Loose().get_params()

    class Forgetful(Inducer):
        def __init__(self, *, depth=1):
            self.level = depth

    with pytest.raises(TypeError, match="does not store its parameter 'depth'"):
        Forgetful().get_params()


# -- the registry and plug-ins ------------------------------------------------------------------
def test_a_plug_in_is_built_like_a_built_in(monkeypatch, tmp_path, capsys):
    plug_in(monkeypatch, FakeEntryPoint("echo", Echo))
    assert available() == ("pal", "sequential", "pal_content", "pal_motion", "echo")
    echo = get("echo", least=3)
    assert isinstance(echo, Echo) and echo.least == 3
    with pytest.raises(ValidationError, match="inducer echo has no parameter 'most' "
                                              "\\(its parameters: least, tags\\)"):
        get("echo", most=3)
    with pytest.raises(ValidationError, match="'echo' \\(a plug-in, fakepkg.learner:Learner\\): "
                                              "parameter least must be"):
        get("echo", least=0)
    path = tmp_path / "a.txt"
    path.write_text("x: a b c\ny: p\n")
    assert main(["induce", str(path), "--inducer", "echo", "--param", "least=2"]) == 0
    out = capsys.readouterr().out
    assert "echo: 1 component(s)" in out and "1 too short" in out


def test_a_duck_typed_plug_in_is_accepted(monkeypatch):
    plug_in(monkeypatch, FakeEntryPoint("duck", DuckTyped))
    assert get("duck", colour="blue").colour == "blue"
    with pytest.raises(ValidationError, match="inducer duck has no parameter 'size'"):
        get("duck", size=3)


def test_a_plug_in_named_like_a_built_in_is_refused_loudly(monkeypatch, capsys):
    plug_in(monkeypatch, FakeEntryPoint("pal", Echo, value="impostor.mod:PAL"))
    with pytest.raises(ValidationError, match="inducer 'pal' is built in, and the plug-in "
                                              "'pal' \\(a plug-in, impostor.mod:PAL\\) has the "
                                              "same name: rename the plug-in"):
        get("pal")
    assert available() == ("pal", "sequential", "pal_content", "pal_motion")  # listed once
    assert isinstance(get("sequential"), Sequential)  # other names are unaffected
    assert main(["induce", "--example"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "impostor.mod:PAL" in err


def test_two_plug_ins_of_one_name_are_refused(monkeypatch):
    plug_in(monkeypatch, FakeEntryPoint("echo", Echo, value="a.mod:Echo"),
            FakeEntryPoint("echo", Echo, value="b.mod:Echo"))
    with pytest.raises(ValidationError, match="given by 2 plug-ins: .*a.mod:Echo.*b.mod:Echo"):
        get("echo")


@pytest.mark.parametrize("entry, words", [
    (FakeEntryPoint("bad", None, error=ImportError("No module named 'nowhere'")),
     "inducer 'bad' (a plug-in, fakepkg.learner:Learner) could not be loaded: ImportError: "
     "No module named 'nowhere'"),
    (FakeEntryPoint("bad", 42), "inducer 'bad' (a plug-in, fakepkg.learner:Learner) is an int, "
                                "not a class or function that builds an inducer"),
    (FakeEntryPoint("bad", lambda: "not an inducer"),
     "inducer 'bad' (a plug-in, fakepkg.learner:Learner) gave a str, which has no induce method "
     "(an inducer subclasses psgs.induce.Inducer or has one)"),
    (FakeEntryPoint("bad", lambda: 1 / 0),
     "inducer 'bad' (a plug-in, fakepkg.learner:Learner) could not be built: "
     "ZeroDivisionError: division by zero"),
])
def test_a_bad_plug_in_is_one_error_naming_it(monkeypatch, capsys, entry, words):
    plug_in(monkeypatch, entry)
    with pytest.raises(ValidationError) as info:
        get("bad")
    assert str(info.value) == words
    assert main(["induce", "--example", "--inducer", "bad"]) == 2
    err = capsys.readouterr().err
    assert err == f"psgs: error: {words}\n"


def test_an_unknown_name_lists_what_there_is(monkeypatch):
    plug_in(monkeypatch, FakeEntryPoint("echo", Echo))
    with pytest.raises(ValidationError, match="unknown inducer 'nope'; available: pal, "
                                              "sequential, pal_content, pal_motion, echo"):
        get("nope")


# -- performances as input ---------------------------------------------------------------------
def test_one_actiongram_or_a_sequence_of_one_give_the_same_induction():
    ag = generate(seed=3, noise=0.1).actiongram
    for inducer in (PAL(), Sequential()):
        one = inducer.induce(ag)
        assert inducer.induce([ag]) == one == inducer.induce((ag,))
        assert one.performances == 1


def test_bad_performances_are_clear_errors():
    a = Actiongram.from_strings({"knee": "abab", "hip": "xyxy"})
    b = Actiongram.from_strings({"knee": "abab", "elbow": "xyxy"})
    for inducer in (PAL(), Sequential(), Echo()):
        with pytest.raises(ValidationError, match="needs at least one performance"):
            inducer.induce([])
        if not isinstance(inducer, PAL):  # PAL gives a string a take lacks as empty
            with pytest.raises(ValidationError, match="performance 1 does not have the actuators "
                                                      "of performance 0: it lacks 'hip' and has "
                                                      "'elbow' too"):
                inducer.induce([a, b])
        with pytest.raises(TypeError, match="performance 1 is a str"):
            inducer.induce([a, "abab"])
        for wrong in ("abab", {"knee": "abab"}, 3):
            with pytest.raises(TypeError, match="needs an Actiongram or a sequence of them"):
                inducer.induce(wrong)


def test_performances_in_another_string_order_are_reordered():
    a = Actiongram.from_strings({"knee": "abab", "hip": "xy"})
    b = Actiongram.from_strings({"hip": "yxy", "knee": "cdc"})
    takes = as_performances(iter([a, b]))
    assert [t.names for t in takes] == [("knee", "hip")] * 2
    assert takes[1].string("knee") == ("c", "d", "c")


def test_pal_learns_from_several_performances_without_joining_them():
    # several performances go to PAL's real-motion learner, each kept apart
    ag = generate(seed=1).actiongram
    result = PAL().induce([ag, ag])
    assert result.performances == 2
    for name in result.components:
        assert set(result.occurrence_performance[name]) <= {0, 1}


def test_sequential_counts_digrams_over_performances_but_never_across_them():
    # 'a b' occurs once in each performance: twice in all, so it is a rule
    two = [Actiongram.from_strings({"x": "abc"}), Actiongram.from_strings({"x": "dab"})]
    result = Sequential().induce(two)
    assert result.performances == 2 and result.patterns["x"] == ("a", "b")
    assert result.occurrence_performance["x"] == (0, 1)
    assert result.occurrences["x"] == ((0.0, 2.0), (1.0, 3.0))  # each in its own time
    assert result.to_dict()["occurrence_performance"] == {"x": [0, 1]}
    # 'c d' would repeat only across the joins of the performances: it is no rule
    three = [Actiongram.from_strings({"x": s}) for s in ("abc", "dxc", "dyz")]
    assert Sequential().induce(three).report("x").status == "no repetition"
    joined = Actiongram.from_strings({"x": "abcdxcdyz"})
    assert Sequential().induce(joined).patterns["x"] == ("c", "d")


@settings(max_examples=60)
@given(st.lists(st.text(alphabet="abc", max_size=15), min_size=1, max_size=4))
def test_sequential_occurrences_lie_where_the_pattern_is(texts):
    takes = [Actiongram.from_strings({"x": t}, starts={"x": 10.0 * k})
             for k, t in enumerate(texts)]
    result = Sequential().induce(takes)
    if "x" not in result.patterns:
        return
    pattern = result.patterns["x"]
    for (start, end), k in zip(result.occurrences["x"], result.occurrence_performance["x"]):
        take = takes[k]
        begins = take.starts["x"]
        p = begins.index(start)
        assert take.string("x")[p:p + len(pattern)] == pattern
        assert end - start == sum(take.durations["x"][p:p + len(pattern)])


def test_an_induction_checks_its_performance_indices():
    with pytest.raises(ValidationError, match="has 1 entries for 2 occurrences"):
        Induction(None, ("x",), {"x": ("a",)}, {"x": ((0, 1), (1, 2))},
                  occurrence_performance={"x": (0,)})
    with pytest.raises(ValidationError, match="outside 0..0"):
        Induction(None, ("x",), {"x": ("a",)}, {"x": ((0, 1),)},
                  occurrence_performance={"x": (1,)})
    with pytest.raises(ValidationError, match="performances must be a positive integer"):
        Induction(None, (), {}, {}, performances=0)


# -- where things live ---------------------------------------------------------------------------
def _calls(path: Path) -> set[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    return {node.func.id if isinstance(node.func, ast.Name) else node.func.attr
            for node in ast.walk(tree) if isinstance(node, ast.Call)
            and isinstance(node.func, (ast.Name, ast.Attribute))}


def test_the_shared_ending_lives_once_in_base():
    induce_dir = ROOT / "psgs" / "induce"
    learners = [p for p in induce_dir.rglob("*.py") if p.name not in ("base.py", "results.py")]
    assert any(p.name.startswith("pal") or p.parent.name == "pal" for p in learners)
    for path in learners:
        made_here = _calls(path) & {"Induction", "build_system", "component_name"}
        assert not made_here, f"{path.relative_to(ROOT)} builds {made_here} itself"


def test_the_synthetic_protocol_imports_without_a_warning():
    # in a fresh interpreter: nothing cached
    done = subprocess.run([sys.executable, "-W", "error", "-c",
                           "import psgs.induce.synthetic, psgs.induce.sweep, psgs.cli"],
                          env=dict(os.environ, PYTHONPATH=str(ROOT)), capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert importlib.util.find_spec("psgs.synthetic") is None  # the deprecated alias is gone


def test_bench_and_synth_live_in_their_own_cli_module():
    import psgs.cli.bench as bench
    import psgs.cli.induce as induce

    assert hasattr(bench, "run_bench_noise") and hasattr(bench, "run_synth")
    assert not hasattr(induce, "run_bench_noise") and not hasattr(induce, "run_synth")


# -- the examples in the docstrings run ------------------------------------------------------------
@pytest.mark.parametrize("module", ["psgs.induce", "psgs.induce.base", "psgs.induce.results",
                                    "psgs.induce.registry", "psgs.induce.sequential",
                                    "psgs.induce.synthetic", "psgs.induce.sweep",
                                    "psgs.cli.bench", "psgs.cli.induce"])
@pytest.mark.usefixtures("examples_tempdir")
def test_docstring_examples_run(module):
    import doctest

    result = doctest.testmod(importlib.import_module(module), optionflags=doctest.ELLIPSIS)
    assert result.attempted > 0 and result.failed == 0


# -- the benchmarks share one helper and measure the installed package ------------------------------
def _load_common():
    spec = importlib.util.spec_from_file_location("_common", ROOT / "benchmarks" / "_common.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_benchmarks_share_one_helper_and_never_edit_sys_path():
    shared = {"replace_section", "write_csv", "best_of", "slope", "loglog_slope"}
    scripts = sorted((ROOT / "benchmarks").glob("*.py"))
    assert len(scripts) >= 7
    for path in scripts:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        touches_path = [node.lineno for node in ast.walk(tree) if isinstance(node, ast.Attribute)
                        and node.attr == "path" and isinstance(node.value, ast.Name)
                        and node.value.id == "sys"]
        assert not touches_path, f"{path.name} uses sys.path (line {touches_path[0]})"
        if path.name == "_common.py":
            assert not any(isinstance(n, (ast.Import, ast.ImportFrom)) and "psgs" in ast.dump(n)
                           for n in ast.walk(tree))
            continue
        copies = {n.name for n in ast.walk(tree) if isinstance(n, ast.FunctionDef)} & shared
        assert not copies, f"{path.name} has its own {copies}"
        assert any(isinstance(n, ast.ImportFrom) and n.module == "_common" for n in tree.body)


def test_replace_section_keeps_the_rest_of_the_page(tmp_path):
    common = _load_common()
    page = tmp_path / "page.md"
    page.write_text("# Title\n\n<!-- x:start -->\nold\n<!-- x:end -->\ntail ü\n", encoding="utf-8")
    common.replace_section(page, "x", "\nnew table\n\n")
    assert page.read_text(encoding="utf-8") == ("# Title\n\n<!-- x:start -->\nnew table\n"
                                                "<!-- x:end -->\ntail ü\n")
    with pytest.raises(SystemExit, match="no <!-- y:start --> ... <!-- y:end --> markers"):
        common.replace_section(page, "y", "text")
    seconds, value = common.best_of(3, lambda: 7)
    assert value == 7 and 0 <= seconds < 1
    assert abs(common.loglog_slope([1, 10, 100], [2, 200, 20000]) - 2.0) < 1e-9
    out = tmp_path / "sub" / "t.csv"
    common.write_csv(out, ["a", "b"], [[1, "x"]])
    assert out.read_text(encoding="utf-8").splitlines() == ["a,b", "1,x"]
