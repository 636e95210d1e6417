"""``psgs praxicon build --workers N`` starts no more processes than there are actions: a
process pool forks all of its workers at once, and a count past a C int was a traceback."""

from __future__ import annotations

import praxicon.builder
from praxicon.cli import main


def test_workers_are_capped_at_the_number_of_actions(tmp_path, monkeypatch, capsys):
    manifest = tmp_path / "m.csv"
    manifest.write_text("action,file\nwave,a.bvh\nwave,b.bvh\nstep,c.bvh\nstep,d.bvh\n")
    asked = []
    real = praxicon.builder.executor_for

    def spy(workers=None, scheduler=None):
        asked.append(workers)
        return real(workers, scheduler)

    monkeypatch.setattr(praxicon.builder, "executor_for", spy)
    for workers in ("99999999999999999999", "5000", "1"):
        # no file can be read: every action fails (status 1), quickly, and nothing raises
        assert main(["build", str(manifest), "-o", str(tmp_path / "px"), "--no-progress",
                     "--workers", workers]) == 1
    assert asked == [2, 2, 1]
    assert "Traceback" not in capsys.readouterr().err
