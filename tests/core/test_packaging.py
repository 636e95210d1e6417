"""The distribution's metadata: the ``all`` extra is every feature extra, and the extras named in
messages exist. (What the built wheel holds is checked in test_cli_core.py, which builds it.)"""

from __future__ import annotations

import re
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
PROJECT = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]
EXTRAS = PROJECT["optional-dependencies"]
FEATURES = ("fast", "plot", "praxicon", "dask")  # what a user installs; not test, bench, docs


def test_all_is_the_union_of_the_feature_extras():
    union = {r for name in FEATURES for r in EXTRAS[name]}
    assert set(EXTRAS["all"]) == union and len(EXTRAS["all"]) == len(union)
    assert set(EXTRAS) == {*FEATURES, "all", "test", "bench", "peers", "docs"}  # a new one is placed


def test_every_extra_a_message_names_exists():
    named = set()
    for path in [*REPO.glob("psgs/**/*.py"), *REPO.glob("kinetology/**/*.py"),
                 *REPO.glob("praxicon/**/*.py"), REPO / "README.md", *REPO.glob("docs/*.md")]:
        named |= set(re.findall(r"psgs\[([a-z,]+)\]", path.read_text(encoding="utf-8")))
    used = {e for group in named for e in group.split(",")}
    assert used and used <= set(EXTRAS), used - set(EXTRAS)


def test_no_placeholder_address_and_the_package_says_it_is_typed():
    assert "urls" not in PROJECT  # no public home yet: no address rather than a false one
    assert "Typing :: Typed" in PROJECT["classifiers"]
    for package in ("psgs", "kinetology", "praxicon"):
        assert (REPO / package / "py.typed").is_file()


def test_every_command_reading_a_grammar_finds_the_shipped_examples_by_name(tmp_path, capsys):
    from psgs.cli import main

    pytest.importorskip("matplotlib", reason="psgs draw without Graphviz draws with matplotlib")
    commands = {"show": [], "derive": ["--seed", "1"], "export": ["-o", str(tmp_path / "lark")],
                "check": ["a", "b", "c", "d"],
                "draw": ["-o", str(tmp_path / "x.svg"), "--engine", "matplotlib"]}
    for command, rest in commands.items():
        status = main([command, "paper_example", *rest])
        err = capsys.readouterr().err
        assert status in (0, 1) and "No such file" not in err, (command, err)
    assert (tmp_path / "x.svg").read_text().startswith("<?xml")


# the modules the extras bring; None in sys.modules makes every import of one fail, as in a
# plain `pip install .`
_EXTRA_MODULES = ("matplotlib", "scipy", "numba", "graphviz", "tqdm", "dask", "PIL")


@pytest.fixture
def plain_install(monkeypatch):
    for name in list(sys.modules):
        if name.split(".")[0] in _EXTRA_MODULES:
            monkeypatch.delitem(sys.modules, name)
    for name in _EXTRA_MODULES:
        monkeypatch.setitem(sys.modules, name, None)


def _one_line_naming(capsys, extra: str) -> str:
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and f"pip install 'psgs[{extra}]'" in err, err
    return err


def test_without_the_extras_each_command_names_the_one_to_install(plain_install, tmp_path,
                                                                   capsys):
    from kinetology.bvh_writer import write_bvh
    from kinetology.cli import main as kinetology_main
    from psgs.cli import main as psgs_main
    from kinetology import Joint, Motion, Skeleton

    assert psgs_main(["draw", "paper_example", "-o", str(tmp_path / "x.png")]) == 2
    _one_line_naming(capsys, "plot")
    assert psgs_main(["draw", "paper_example", "-o", str(tmp_path / "x.svg"),
                      "--engine", "graphviz"]) == 2
    _one_line_naming(capsys, "praxicon")  # the graphviz package asked for by name
    arm = Skeleton((Joint("shoulder", None, (0, 0, 0), ("shoulder.rz",)),
                    Joint("shoulder.end", 0, (10, 0, 0), end_site=True)))
    take = tmp_path / "arm.bvh"
    write_bvh(Motion(np.linspace(0, 90, 30)[:, None], ("shoulder.rz",), 30, arm), take)
    for argv in (["plot", str(take), "--channel", "shoulder.rz", "-o", str(tmp_path / "p.png")],
                 ["view", str(take), "-o", str(tmp_path / "v.gif")]):
        assert kinetology_main(argv) == 2
        _one_line_naming(capsys, "plot")
    assert kinetology_main(["view", str(take), "-o", str(tmp_path / "v.html")]) == 0  # no extra


def test_generation_without_scipy_names_the_praxicon_extra(plain_install):
    from praxicon.shaping import shape
    from psgs.errors import PSGSError

    with pytest.raises(PSGSError, match=r"pip install 'psgs\[praxicon\]'"):
        shape(np.zeros(101), [0, 20, 40, 60, 80, 100], "RYRBR", 30.0, {})


def test_whole_body_generation_without_scipy_names_the_praxicon_extra(plain_install):
    # the body's rotations (a real take's root and its heading) are read through scipy
    from praxicon.body_motion import euler_angles
    from psgs.errors import PSGSError

    with pytest.raises(PSGSError, match=r"pip install 'psgs\[praxicon\]'"):
        euler_angles(np.eye(3)[None], "zxy")


def test_asking_for_the_compiled_engine_without_numba_names_the_fast_extra():
    # a fresh interpreter: in this one the engine may have been chosen and kept already
    code = ("import sys; sys.modules['numba'] = None; from psgs.cli import main; "
            "sys.exit(main(['induce', '--example', '--param', 'engine=numba']))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          timeout=60)
    err = done.stderr.strip()
    assert done.returncode == 2 and len(err.splitlines()) == 1, err[-500:]
    assert "pip install 'psgs[fast]'" in err


def test_the_graphviz_engine_without_dot_says_so(monkeypatch, tmp_path):
    pytest.importorskip("graphviz")
    import psgs
    import psgs.draw
    from psgs.errors import MissingDependency

    monkeypatch.setattr(psgs.draw.shutil, "which", lambda name: None)
    with pytest.raises(MissingDependency, match="dot program"):
        psgs.draw.draw(psgs.load("paper_example"), tmp_path / "x.svg", engine="graphviz")
