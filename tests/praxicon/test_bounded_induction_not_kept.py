"""An induction that stopped at its bound is no action learnt: the record says failed and why.

With ``--param max_seconds=...`` (PAL) or ``max_rules`` (sequential) reached, the components
found by then were stored with status ``ok``, and nothing in the record (whose params do not
keep the bound) said the action was learnt in part.
"""

from __future__ import annotations

import pytest

from praxicon import Settings, read_dataset
from praxicon.learn import learn_action
from praxicon_fixtures import write_manifest


@pytest.mark.parametrize("inducer, params, bound", [
    ("pal", {"max_seconds": 1e-9}, "max_seconds"),
    ("sequential", {"max_rules": 1}, "max_rules"),
])
def test_an_induction_stopped_at_its_bound_is_recorded_failed(tmp_path, inducer, params, bound):
    action = read_dataset(write_manifest(tmp_path, {"wave": [1, 2, 3]}))[0]
    record, _ = learn_action(action, Settings.make(inducer, params, {}, 2))
    assert record.status == "failed"
    assert f"stopped at its bound {bound}" in record.reason
    assert "\n" not in record.reason and not record.joints


def test_the_same_action_without_a_bound_is_learnt(tmp_path):
    action = read_dataset(write_manifest(tmp_path, {"wave": [1, 2, 3]}))[0]
    record, _ = learn_action(action, Settings.make("pal", {}, {}, 2))
    assert record.status == "ok" and record.joints
