"""An action learnt from ASF/AMC takes is generated on their skeleton: the BVH file holds the
ASF's bones (its axes turned into the joints' angles), not a star of joints at offset 0."""

from __future__ import annotations

import numpy as np

import kinetology
from kinetology.kinematics import forward_kinematics
from praxicon import build, generate, read_dataset
from praxicon.records import Settings

from praxicon_fixtures import take

ASF = """:version 1.10
:name synthetic
:units
  mass 1.0
  length 1.0
  angle deg
:root
  order TX TY TZ RX RY RZ
  axis XYZ
  position 0 0 0
  orientation 0 0 0
:bonedata
  begin
    id 1
    name arm
    direction 1 0 0
    length 10
    axis 0 0 90 XYZ
    dof rx rz
  end
  begin
    id 2
    name leg
    direction 0 -1 0
    length 12
    axis 30 0 0 XYZ
    dof rx
  end
  begin
    id 3
    name head
    direction 0 1 0
    length 5
    axis 0 0 0 XYZ
    dof ry
  end
:hierarchy
  begin
    root arm leg head
  end
"""


def _amc(seed: int) -> str:
    """The synthetic take of the praxicon fixtures as AMC frames on the skeleton above."""
    motion = take(seed)
    column = dict(zip(motion.channels, motion.values.T))
    rows = [":FULLY-SPECIFIED", ":DEGREES"]
    for f in range(motion.frames):
        rows += [str(f + 1), f"root 0 0 0 0 0 {column['hips.rz'][f]:.5f}",
                 f"arm {column['arm.rx'][f]:.5f} {column['arm.rz'][f]:.5f}",
                 f"leg {column['leg.rx'][f]:.5f}", f"head {column['head.ry'][f]:.5f}"]
    return "\n".join(rows) + "\n"


def test_an_action_learnt_from_amc_takes_is_written_on_their_asf_skeleton(tmp_path):
    (tmp_path / "07.asf").write_text(ASF)
    for seed in (1, 2, 3):
        (tmp_path / f"07_0{seed}.amc").write_text(_amc(seed))
    (tmp_path / "m.csv").write_text("action,file\n" + "".join(
        f"wave,07_0{seed}.amc\n" for seed in (1, 2, 3)))
    build(read_dataset(tmp_path / "m.csv"), tmp_path / "px", progress=False,
          log=lambda s: None, settings=Settings.make(params={"min_copies": 3}))
    generated = generate(tmp_path / "px", "m.wave", repeat=1, output=tmp_path / "g.bvh")
    source = kinetology.read(tmp_path / "07_01.amc").skeleton
    assert generated.motion.skeleton == source  # the motion in memory: the ASF skeleton
    back = kinetology.read(tmp_path / "g.bvh")
    assert back.skeleton.names == source.names
    assert [j.offset for j in back.skeleton.joints] == [j.offset for j in source.joints]
    # the bones come back where the ASF puts them, frame by frame (six decimals written)
    error = np.abs(forward_kinematics(back) - forward_kinematics(generated.motion)).max()
    assert error < 1e-4, error
    assert all(generated.round_trip().values()), generated.methods


def test_takes_without_a_skeleton_are_generated_on_a_star_and_the_command_says_so(tmp_path,
                                                                                  capsys):
    from praxicon.cli import main

    # AMC takes whose channels a SkeletonJoints.key names, with no ASF (as cmu-mocap6 ships)
    (tmp_path / "SkeletonJoints.key").write_text("root tx ty tz rx ry rz\narm rx rz\nleg rx\n"
                                                 "head ry\n")
    for seed in (1, 2, 3):
        (tmp_path / f"07_0{seed}.amc").write_text(_amc(seed))
    (tmp_path / "m.csv").write_text("action,file\n" + "".join(
        f"wave,07_0{seed}.amc\n" for seed in (1, 2, 3)))
    assert main(["build", str(tmp_path / "m.csv"), "-o", str(tmp_path / "px"), "--no-progress",
                 "--param", "min_copies=3"]) == 0
    capsys.readouterr()
    out = tmp_path / "g.bvh"
    assert main(["generate", str(tmp_path / "px"), "m.wave", "--repeat", "1", "-o",
                 str(out)]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == (
        f"{out}: on a star skeleton (every joint on the root at offset 0, angles only): "
        f"{tmp_path / '07_01.amc'} has no skeleton (an AMC file without its ASF)")
    assert all(j.offset == (0.0, 0.0, 0.0) for j in kinetology.read(out).skeleton.joints)
    # the viewer says why the body is a dot
    from kinetology.cli import main as kinetology_main

    assert kinetology_main(["view", str(out), "-o", str(tmp_path / "g.html")]) == 0
    assert capsys.readouterr().out.splitlines()[-1] == (
        "g.bvh: every joint at one point (all offsets 0: a skeleton of angles only, as written "
        "for an AMC take without its ASF); the body is a dot")
