"""A praxicon learnt from takes of two skeletons (joint names of CMU's ASF and of Bandai's BVH):
every action keeps its own joints, each take is recognised as its own action, a take lacking
some of an action's joints says which, and build -> load -> recognise equals memory."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from praxicon.description import describe
from praxicon.features import feature_joint
from praxicon.recognition import recognise, recognise_many
from praxicon.scoring import distances, precision_parts

#: per skeleton, its joints in the roles the synthetic takes move: hips, left arm (two
#: channels), right arm, left leg, head
SKELETONS = {"cmu": ("root", "lhumerus", "rhumerus", "lfemur", "head"),
             "bandai": ("Hips", "LeftArm", "RightArm", "LeftUpLeg", "Head")}
#: action -> (skeleton, moves the left arm, the right arm, the left leg)
ACTIONS = {"cmu-wave": ("cmu", True, False, False), "cmu-step": ("cmu", False, False, True),
           "bandai-wave": ("bandai", True, False, False),
           "bandai-reach": ("bandai", False, True, False)}
LEARNT, NEW = (1, 2, 3), (7, 8)


def _take(action: str, seed: int, seconds: float = 5.0, rate: float = 30.0):
    from kinetology import Motion
    from kinetology.bvh_writer import star_skeleton

    skeleton, left, right, leg = ACTIONS[action]
    hips, larm, rarm, lleg, head = SKELETONS[skeleton]
    rng = np.random.default_rng(seed)
    t = np.arange(int(seconds * rate)) / rate
    phase = 2 * np.pi * t / (1 + 0.05 * (seed % 3))
    noise = lambda: 0.3 * rng.standard_normal(t.size)  # noqa: E731
    channels = (f"{hips}.rz", f"{larm}.rx", f"{larm}.rz", f"{rarm}.rx", f"{lleg}.rx",
                f"{head}.ry")
    values = np.column_stack([
        noise(), (40 * np.sin(phase) if left else 0 * t) + noise(),
        (25 * np.sin(phase + 0.7) if left else 0 * t) + noise(),
        (35 * np.sin(phase + 1.3) if right else 0 * t) + noise(),
        (30 * np.sin(phase + 2) if leg else 0 * t) + noise(), noise()])
    return Motion(values, channels, rate, star_skeleton(channels), f"{action}{seed}")


@pytest.fixture(scope="module")
def px(tmp_path_factory) -> Path:
    """A praxicon folder built from one manifest of the four actions' BVH takes, two
    skeletons, and new takes of each action beside it."""
    from kinetology import write_bvh
    from praxicon import build, read_dataset

    folder = tmp_path_factory.mktemp("mixed")
    rows = ["action,file"]
    for action in ACTIONS:
        for seed in LEARNT:
            write_bvh(_take(action, seed), folder / f"{action}{seed}.bvh")
            rows.append(f"{action},{folder / f'{action}{seed}.bvh'}")
        for seed in NEW:
            write_bvh(_take(action, seed), folder / f"new-{action}{seed}.bvh")
    (folder / "m.csv").write_text("\n".join(rows) + "\n")
    result = build(read_dataset(folder / "m.csv"), folder, progress=False, log=lambda s: None)
    assert result.praxicon.descriptions is not None
    return folder


def _new(px: Path):
    import kinetology

    return [(action, kinetology.read(px / f"new-{action}{seed}.bvh"))
            for action in ACTIONS for seed in NEW]


def test_every_action_keeps_its_skeletons_joints(px):
    """Each action's description has its own skeleton's joints (not only the tempo that the
    takes of both skeletons share), and the shared spread covers both skeletons."""
    from praxicon import load

    for d in (load(px).descriptions, load(px).window_descriptions):
        for a in d.actions:
            joints = {feature_joint(f) for f in a.features} - {"*"}
            assert joints == set(SKELETONS[ACTIONS[a.name.split(".", 1)[1]][0]])
        assert {feature_joint(f) for f in d.spread.features} - {"*"} == \
            set(SKELETONS["cmu"]) | set(SKELETONS["bandai"])


def test_each_take_is_recognised_as_its_own_action(px):
    """New takes of every action, both skeletons in one call: each is its own action; the
    other skeleton's actions share no joint with it, are ranked last at probability 0 and
    named (in the explanation too), while the probabilities still sum to 1."""
    new = _new(px)
    found = recognise_many(px, [m for _, m in new])
    assert [r.action for r in found] == [f"m.{a}" for a, _ in new]
    for (action, _), r in zip(new, found):
        other = {f"m.{a}" for a, (s, *_) in ACTIONS.items() if s != ACTIONS[action][0]}
        assert set(r.unshared) == other
        assert {name for name, _ in r.ranking[-len(other):]} == other
        assert all(p == 0.0 for name, p in r.ranking if name in other)
        assert math.isclose(sum(p for _, p in r.ranking), 1.0)
        assert r.missing == () and r.penalty <= r.threshold
        assert "sharing no joint with the motion" in r.explain()


def test_a_take_lacking_some_joints_says_which(px):
    """A Bandai wave without its right arm and head: recognised over the joints it has, as
    the wave; the explanation names the joints the action has and the take lacks."""
    import kinetology

    full = kinetology.read(px / "new-bandai-wave7.bvh")
    fewer = full.select(tuple(c for c in full.channels
                              if not c.startswith(("RightArm.", "Head."))))
    found = recognise(px, fewer)
    assert found.action == "m.bandai-wave"
    assert found.missing == ("Head", "RightArm")
    lacking = dict(found.lacking)
    assert lacking["m.bandai-wave"] == ("Head", "RightArm")
    assert "lacks the action's joints: Head, RightArm" in found.explain()
    assert "missing joints (recognised without them): Head, RightArm" in found.explain()


def test_round_trip_build_load_recognise_equals_memory(px):
    """The descriptions the build wrote are those learnt in memory from the same takes, and
    the folder, the loaded praxicon and the in-memory descriptions give the same answers."""
    import kinetology
    from praxicon import load
    from praxicon.store import read_descriptions
    from praxicon.parsing import describe_windows, parse

    loaded = load(px)
    takes = {a.name: [kinetology.read(p.file) for p in a.performances if p.used]
             for a in loaded.actions if a.learnt}
    memory, windows = describe(takes), describe_windows(takes)
    assert read_descriptions(px) == memory == loaded.descriptions
    assert read_descriptions(px, windows=True) == windows == loaded.window_descriptions
    new = [m for _, m in _new(px)]
    assert recognise_many(px, new) == recognise_many(loaded, new) == recognise_many(memory, new)
    assert parse(px, new[0]) == parse(loaded, new[0]) == parse(windows, new[0])


def test_parse_never_chooses_the_other_skeletons_actions(px):
    """A recording of a CMU wave and then a CMU step, parsed in the mixed praxicon: the CMU
    actions in order, and none of the Bandai actions anywhere."""
    from kinetology import Motion
    from praxicon import load
    from praxicon.parsing import parse

    a, b = _take("cmu-wave", 7), _take("cmu-step", 8)
    joined = Motion(np.concatenate([a.values, b.values]), a.channels, a.frame_rate, a.skeleton)
    spans = parse(load(px), joined).spans
    assert [s.action for s in spans if s.action] == ["m.cmu-wave", "m.cmu-step"]


def test_an_action_compared_over_fewer_features_is_on_the_same_scale():
    """Oracle: an action learnt without one of the motion's joints is compared over the
    features it has; its distance per feature compared (the penalty the threshold reads) is
    its squared Mahalanobis distance over those features, in the shared spread's marginal,
    divided by their number, and the ranking distance is that times the motion's count."""
    from praxicon.description import score_model, scores
    from praxicon.recognition import feature_matrix

    full = [_take("bandai-wave", s) for s in LEARNT]
    px = describe({"wave": full,
                   "wave-no-head": [m.select(tuple(c for c in m.channels
                                                   if not c.startswith("Head.")))
                                    for m in full],
                   "reach": [_take("bandai-reach", s) for s in LEARNT]})
    motion = _take("bandai-wave", 7)
    columns, x, _ = feature_matrix(px, [motion])
    shared, _ = scores(px, x, columns)
    k = px.names.index("wave-no-head")
    mine = np.array([i for i, c in enumerate(columns)
                     if px.spread.features[c] in set(px.actions[k].features)])
    assert 0 < len(mine) < len(columns)
    mean = np.array(px.aligned()[k][columns[mine]])
    alone = distances(x[:, mine], mean[None], precision_parts(px.spread, columns[mine]))[0, 0]
    assert shared[0, k] == pytest.approx(alone / len(mine) * len(columns), rel=1e-9)
    found = recognise(px, motion)
    assert dict(found.lacking).get("wave-no-head", ()) == ()  # it lacks a joint, not the take
    assert found.ranking[0][0] in ("wave", "wave-no-head") and found.action is not None
    assert score_model(px, columns).compared.all()


def test_an_action_whose_takes_share_no_joint_is_a_clear_error():
    from praxicon.description import DescriptionError

    with pytest.raises(DescriptionError, match="'mixed': its takes share no joint"):
        describe({"mixed": [_take("cmu-wave", 1), _take("bandai-wave", 2)],
                  "wave": [_take("cmu-wave", s) for s in (3, 4)]})


def test_descriptions_of_the_old_format_are_learnt_again(px, tmp_path):
    """Descriptions of format 3 (which kept only the features every take of every action
    had: the tempo alone, here) are refused with the command that learns them again, and a
    resumed build into that folder learns them again."""
    import shutil

    from praxicon import build, read_dataset
    from praxicon.description import DescriptionError
    from praxicon.store import read_descriptions

    old = tmp_path / "old"
    shutil.copytree(px, old)
    data = json.loads((old / "descriptions.json").read_text())
    data["version"] = 3
    (old / "descriptions.json").write_text(json.dumps(data))
    with pytest.raises(DescriptionError, match="version 3.*psgs praxicon build"):
        recognise(old, _take("cmu-wave", 7))
    result = build(read_dataset(px / "m.csv"), old, progress=False, log=lambda s: None)
    assert result.learnt == () and read_descriptions(old) == read_descriptions(px)


def test_cli_recognises_takes_of_both_skeletons_in_one_call(px, capsys):
    """``psgs praxicon recognise PX FILE...`` with a CMU and a Bandai take: one line each,
    its own action; the take lacking a joint is named on stderr, exit status 0."""
    from kinetology import read, write_bvh
    from praxicon.recognition_cli import register_recognise
    from psgs.cli import main

    def register(subparsers) -> None:
        parser = subparsers.add_parser("praxicon")
        register_recognise(parser.add_subparsers(dest="praxicon_command", required=True))

    full = read(px / "new-bandai-reach8.bvh")
    write_bvh(full.select(tuple(c for c in full.channels if not c.startswith("Head."))),
              px / "headless.bvh")
    files = [px / "new-cmu-step7.bvh", px / "headless.bvh"]
    capsys.readouterr()
    assert main(["praxicon", "recognise", str(px), *map(str, files), "--explain"],
                commands={"praxicon": register}) == 0
    captured = capsys.readouterr()
    answers = [line for line in captured.out.splitlines() if line.startswith(str(px))
               and " p=" not in line and "(distance" not in line]
    assert answers[0].startswith(f"{files[0]}: m.cmu-step ")
    assert answers[1].startswith(f"{files[1]}: m.bandai-reach ")
    assert "sharing no joint with the motion" in captured.out
    assert f"{files[1]}: recognised without the joints it lacks: Head" in captured.err
