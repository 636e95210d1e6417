"""What a new user's sweep of the kinetology command and API found: each test fails before
its fix (plot's --min-range, label files of another take, ...)."""

from __future__ import annotations

import numpy as np
import pytest

from kinetology.cli import main

from kinetology_fixtures import MOCAP, needs_mocap
from test_kinetology_review_fixes import _write_bvh


def _one_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("kinetology: error:"), err
    return err[0]


# -- plot --min-range -----------------------------------------------------------------------

def _drawn(monkeypatch):
    """The figures plot would have written, instead of writing them."""
    import kinetology.plotting

    figures = []
    monkeypatch.setattr(kinetology.plotting, "save", lambda fig, path: figures.append(fig))
    return figures


def test_plot_states_draws_a_channel_below_min_range_as_still(tmp_path, monkeypatch, capsys):
    pytest.importorskip("matplotlib")
    from kinetology.plotting import STILL_COLOUR

    take, out = str(_write_bvh(tmp_path / "take.bvh")), str(tmp_path / "p.png")
    figures = _drawn(monkeypatch)
    assert main(["plot", take, "--channel", "Knee.rx", "-o", out]) == 0
    assert main(["plot", take, "--channel", "Knee.rx", "--min-range", "1000", "-o", out]) == 0
    moving, still = (fig.axes[0] for fig in figures)
    assert "states" in moving.get_title() and len(moving.get_lines()) == 4
    assert still.get_title().startswith("Knee.rx: still (moves less than min_range 1000 deg")
    assert [line.get_color() for line in still.get_lines()] == [STILL_COLOUR]


@pytest.mark.parametrize("kind, says", [
    ("reconstruction", "the codec has no setting --min-range"),
    ("view", "--kind view: --min-range does not apply"),
])
def test_plot_refuses_min_range_where_it_means_nothing(tmp_path, capsys, kind, says):
    pytest.importorskip("matplotlib")
    out = tmp_path / "p.png"
    assert main(["plot", str(_write_bvh(tmp_path / "take.bvh")), "--channel", "lknee",
                 "--kind", kind, "--min-range", "5", "-o", str(out)]) == 2
    assert says in _one_line(capsys)
    assert not out.exists()
