"""Pictures: psgs draw (Graphviz and matplotlib), the praxicon's figures, shared sub-patterns."""

from __future__ import annotations

import pytest

import psgs
from praxicon import build, load, read_dataset, shared_patterns
from praxicon.pictures import draw_praxicon
from psgs.cli import main as psgs_main
from psgs.draw import draw, graphviz_available, parse_forest, sync_edges, to_svg

GAMMA = "grammars/paper_example.psgs"


def test_forest_leaves_are_the_derived_words():
    gamma = psgs.load(GAMMA)
    forest = parse_forest(gamma, seed=3)
    words = ["".join(forest.leaves(c)) for c in range(4)]
    k = len(words[0]) // 8
    assert forest.complete and k >= 1
    assert words == [w * k for w in ("abcdbcad", "bcadabcd", "cdabcdab", "abcdbcad")]


def test_sync_edges_follow_the_tuples():
    gamma = psgs.load(GAMMA)
    edges = sync_edges(gamma)
    assert (("G1", "N13"), ("G2", "N18"), 2) in edges or \
        any(a == ("G1", "N13") and b[0] == "G2" for a, b, _ in edges)
    assert all(t >= 0 for _, _, t in edges)


@pytest.mark.parametrize("engine", ["matplotlib", "graphviz"])
@pytest.mark.parametrize("suffix", ["svg", "png"])
def test_draw_both_engines(tmp_path, engine, suffix):
    if engine == "graphviz" and not graphviz_available():
        pytest.skip("Graphviz's dot is not installed (apt-get install graphviz)")
    out = draw(psgs.load(GAMMA), tmp_path / f"g.{suffix}", engine=engine)
    data = out.read_bytes()
    assert data.startswith(b"\x89PNG" if suffix == "png" else b"<?xml")
    if suffix == "svg":
        text = data.decode()
        assert "N13" in text and "G4" in text


def test_svg_is_deterministic():
    gamma = psgs.load(GAMMA)
    assert to_svg(gamma, engine="matplotlib") == to_svg(gamma, engine="matplotlib")


def test_psgs_draw_cli(tmp_path, capsys):
    assert psgs_main(["draw", GAMMA, "-o", str(tmp_path / "g.png"), "--seed", "2"]) == 0
    assert (tmp_path / "g.png").stat().st_size > 1000
    assert psgs_main(["draw", "grammars/pcgs_abc.psgs", "-o", str(tmp_path / "p.svg")]) == 0
    assert psgs_main(["draw", GAMMA, "-o", str(tmp_path / "g.txt")]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"psgs: error: {tmp_path / 'g.txt'}: draw writes .svg or .png, not '.txt'"]


def test_without_graphviz_worker_processes_draw_the_same_systems(manifest, tmp_path,
                                                                  monkeypatch):
    import psgs.draw

    monkeypatch.setattr(psgs.draw, "graphviz_available", lambda: False)
    build(read_dataset(manifest), tmp_path / "px", progress=False, log=lambda s: None)
    serial = draw_praxicon(tmp_path / "px", tmp_path / "one", workers=1)
    parallel = draw_praxicon(tmp_path / "px", tmp_path / "two", workers=2)
    assert [p.relative_to(tmp_path / "one") for p in serial] == \
        [p.relative_to(tmp_path / "two") for p in parallel]
    for a, b in zip(serial, parallel):  # SVG bytes: ids salted, no date
        assert a.read_bytes() == b.read_bytes(), a.name


def test_praxicon_pictures_and_shared_patterns(manifest, tmp_path):
    build(read_dataset(manifest), tmp_path / "px", progress=False, log=lambda s: None)
    told = []
    written = draw_praxicon(tmp_path / "px", tmp_path / "img", workers=1, fmt="png",
                            progress=lambda *call: told.append(call))
    # every per-action picture is told once, in order, morphemes first, then systems
    assert [(done, total) for done, total, _ in told] == [(k, 4) for k in range(4)]
    assert [what.split(" of ")[0] for *_, what in told] == ["morphemes"] * 2 + ["system"] * 2
    names = sorted(p.relative_to(tmp_path / "img").as_posix() for p in written)
    assert names == ["actuators.png", "morphemes/moves.step.png", "morphemes/moves.wave.png",
                     "shared.png", "systems/moves.step.png", "systems/moves.wave.png"]
    assert all(p.read_bytes().startswith(b"\x89PNG") for p in written)
    shared = shared_patterns(load(tmp_path / "px"))
    # both actions swing the arm through the same whole cycle
    arm = [p for p in shared if p.joint == "arm" and p.kinetemes == ("B", "G", "R", "Y")]
    assert arm and arm[0].actions == ("moves.step", "moves.wave")
    assert all(len(p.actions) >= 2 and len(p.kinetemes) >= 4 for p in shared)
    import json

    listed = json.loads((tmp_path / "px" / "shared.json").read_text())
    assert listed == [p.to_dict() for p in shared]


def _text_boxes(fig):
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    return [(t.get_text(), t.get_window_extent(renderer)) for ax in fig.axes for t in ax.texts]


def test_matplotlib_drawing_wraps_large_systems_and_tags_instead_of_lines():
    # a system wider than a row wraps: the picture's width stays that of PER_ROW cells
    # whatever the number of components, and synchronisation is tags, not crossing lines
    pytest.importorskip("matplotlib")
    import matplotlib.pyplot as plt

    from psgs.draw import PER_ROW, _matplotlib
    from psgs.model import PSGS, Grammar, Nonterminal, Rule, Terminal

    def component(i):
        start = Nonterminal(f"S{i}")
        return Grammar(f"G{i}", start, (Rule(f"p{i}", start, (Terminal("a"), start)),
                                        Rule(f"q{i}", start, ())))

    n = 3 * PER_ROW + 2
    grammars = tuple(component(i) for i in range(n))
    # tuple 1 skips every other component: those idle in it
    sync = [tuple(f"p{i}" if i % 2 == 0 else "#" for i in range(n)),
            tuple(f"q{i}" for i in range(n))]
    system = PSGS(grammars, sync=sync, name="wide")
    small = _matplotlib(PSGS(grammars[:PER_ROW], sync=[tuple(f"q{i}" for i in range(PER_ROW))]),
                        None)
    fig = _matplotlib(system, None)
    try:
        assert fig.get_figwidth() == small.get_figwidth()
        assert fig.get_figheight() > 3 * small.get_figheight() / 2
        assert not any(ax.lines for ax in fig.axes)  # no line can cross an idle component
        texts = [t for t, _ in _text_boxes(fig)]
        # p of an idle component carries no tag; q of every component carries M2
        assert texts.count("M1") == (n + 1) // 2 and texts.count("M2") == n
        assert any("tuple k of M" in t.get_text() for t in fig.texts)  # the legend
    finally:
        plt.close(fig)
        plt.close(small)
