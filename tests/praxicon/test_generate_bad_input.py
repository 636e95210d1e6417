"""``psgs praxicon generate`` on bad input, one line and status 2 each: a record that failed
with no reason stored (``not learnt: None``)."""

from __future__ import annotations

from dataclasses import replace

import pytest

from fuzz_support import praxicon_seed
from praxicon import dump
from praxicon.generation import generate_motion
from praxicon.records import ActionRecord
from praxicon_fixtures import refused


def _with(px, name, **changes):
    """The praxicon with one action's record changed."""
    return replace(px, actions=tuple(replace(a, **changes) if a.name == name else a
                                     for a in px.actions))


def test_a_record_that_failed_without_a_reason_says_so(tmp_path, capsys):
    seed = praxicon_seed()
    dump(_with(seed, "moves.bow", reason=None), tmp_path / "px")
    out = tmp_path / "b.bvh"
    assert refused(capsys, ["generate", str(tmp_path / "px"), "moves.bow", "-o", str(out)]) == \
        "action 'moves.bow' was not learnt (no reason recorded)"
    assert not out.exists()
    with pytest.raises(ValueError, match=r"^action 'x' was not learnt \(no reason recorded\)$"):
        generate_motion(ActionRecord("x", "d", "x", reason=" "), 1)
    # a reason stored is given as it was
    with pytest.raises(ValueError, match=r"^action 'moves\.bow' was not learnt: 1 usable "
                                         r"performance \(at least 2 needed\)$"):
        generate_motion(seed["moves.bow"], 1)
