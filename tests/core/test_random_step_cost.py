"""random_step asks a tuple's rules whether it changes the form, not a configuration built for it.

A tuple changes nothing exactly when each rewriting entry is a rule A -> A, so the draw
builds one configuration per step (the step drawn), not one per applicable tuple; single
mode's occurrence choices are counted, and listed only for the tuple drawn. The steps drawn
are those of listing every applicable step and picking one with the same seed.
"""

from __future__ import annotations

import random
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import psgs
from psgs import steps
from psgs.derivation import applicable_steps
from psgs.model import PSGS
from psgs.strategies import psgs_systems

# the PSGS among them (a PCGS's draw rejects combinations of rules A -> A: its own stream)
GRAMMARS = [path for path in sorted((Path(psgs.__file__).parent / "grammars").glob("*.psgs"))
            if isinstance(psgs.load(path), PSGS)]


def _in_mode(system: PSGS, mode: str) -> PSGS:
    """``system`` with the rewriting mode ``mode``."""
    if system.mode == mode:
        return system
    return PSGS(system.components, system.sync, mode=mode, unsynchronised=system.unsynchronised)


def _walk_agrees_with_listing(system, seed: int, length: int) -> int:
    """Draw ``length`` steps both ways from the same seed; the steps taken."""
    drawn_rng, listed_rng = random.Random(seed), random.Random(seed)
    configuration = steps.initial_configuration(system)
    for taken in range(length):
        drawn = steps.random_step(system, configuration, drawn_rng)
        options = applicable_steps(system, configuration)
        listed = options[listed_rng.randrange(len(options))] if options else None
        assert drawn == listed
        if drawn is None or sum(map(len, drawn.after)) > 60:
            return taken
        configuration = drawn.after
    # the two consumed the random stream alike, so every later draw agrees too
    assert drawn_rng.random() == listed_rng.random()
    return length


@pytest.mark.parametrize("path", GRAMMARS, ids=lambda p: p.stem)
@pytest.mark.parametrize("mode", ["parallel", "single"])
def test_seeded_steps_on_the_shipped_grammars_are_those_of_the_listing(path, mode):
    system = _in_mode(psgs.load(path), mode)
    taken = sum(_walk_agrees_with_listing(system, seed, 25) for seed in range(20))
    assert taken > 20  # the walks went somewhere


@settings(max_examples=75, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(psgs_systems(max_components=3, max_nonterminals=2, max_rules=4), st.integers(0, 2**16))
def test_seeded_steps_on_drawn_systems_are_those_of_the_listing(system, seed):
    # drawn systems hold rules A -> A (unit rules are allowed), alone and beside others
    _walk_agrees_with_listing(system, seed, 12)


def test_a_tuple_of_rules_a_to_a_changes_nothing_and_is_never_drawn():
    system = psgs.loads('psgs Keep\nmode single\nunsynchronised strict\n'
                        'component G start S\n  k: S -> S\n  g: S -> "a" S\n  e: S -> "b"\n'
                        'component H start T\n  k2: T -> T\n  e2: T -> "c"\n'
                        'sync\n  (k, k2)\n  (k, #)\n  (g, k2)\n  (e, e2)\n')
    rng = random.Random(3)
    start = steps.initial_configuration(system)
    drawn = {str(steps.random_step(system, start, rng)) for _ in range(200)}
    assert drawn == {str(step) for step in applicable_steps(system, start)}
    assert drawn == {"(g, k2)", "(e, e2)"}


def test_one_configuration_is_built_per_step_whatever_the_tuples(monkeypatch):
    # 3,000 rules applicable at once: building the configuration after each of them to see
    # whether it changed anything made 1,000 steps take minutes
    rules = "".join(f'  r{i}: S -> "x{i}" S S\n' for i in range(3000))
    system = psgs.loads(f"psgs Many\nmode single\nunsynchronised free\ncomponent G start S\n"
                        f"{rules}  e: S -> \"e\"\n")
    built = []
    real = steps.rewritten

    def counted(*args):
        built.append(args)
        return real(*args)

    monkeypatch.setattr(steps, "rewritten", counted)
    rng = random.Random(0)
    configuration = steps.initial_configuration(system)
    for _ in range(20):
        step = steps.random_step(system, configuration, rng)
        configuration = step.after
    assert len(built) == 20
    assert sum(s.name == "S" for s in configuration[0]) > 10  # many occurrences to choose among
