"""PAL and its two learners: the same findings whichever name runs them, one table per learner,
every rule declared once."""

from __future__ import annotations

import dataclasses

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from psgs import ValidationError
from psgs.induce import PAL, ContentPAL, MotionPAL, get
from psgs.induce.pal import ContentConf, MotionConf, PALConf
from psgs.induce.synthetic import generate


def _findings(result):
    """An Induction without who made it (name, parameters, the system's name)."""
    return dataclasses.replace(result, inducer="", params={},
                               system=None if result.system is None
                               else dataclasses.replace(result.system, name="x"))


SMALL = dict(strings=8, patterned=3, copies=6)


def test_pal_finds_what_its_learners_find():
    one = generate(seed=5, noise=0.2, **SMALL).actiongram
    assert _findings(PAL(rounds=3).induce(one)) == _findings(ContentPAL(rounds=3).induce(one))
    takes = [generate(seed=k, noise=0.1, **SMALL).actiongram for k in (1, 2)]
    assert _findings(PAL(joint_share=0.3).induce(takes)) == \
        _findings(MotionPAL(joint_share=0.3).induce(takes))
    assert _findings(PAL(timing="performances").induce(one)) == \
        _findings(MotionPAL().induce(one))


def test_an_induction_says_who_made_it_with_which_parameters():
    one = generate(seed=5, **SMALL).actiongram
    result = PAL().induce(one)
    assert result.inducer == "pal" and result.system.name == "pal"
    # engine changes how it computes; max_seconds and max_bytes name the bound that stopped it
    unrecorded = {"engine", "max_seconds", "max_bytes"}
    assert set(result.params) == set(PALConf.names()) - unrecorded
    content = ContentPAL().induce(one)
    assert content.inducer == "pal_content" and set(content.params) == \
        set(ContentConf.names()) - unrecorded
    motion = MotionPAL().induce([one, one])
    assert motion.inducer == "pal_motion" and set(motion.params) == \
        set(MotionConf.names()) - unrecorded


def test_the_tables_are_frozen_and_pal_s_is_the_union():
    with pytest.raises(dataclasses.FrozenInstanceError):
        ContentConf().rounds = 3
    assert set(PALConf.names()) == set(ContentConf.names()) | set(MotionConf.names())
    assert PAL().get_params() == PALConf().as_dict()
    # a row both learners read is one declaration: the same rule object in every table
    for name in ("min_copies", "alpha", "max_seconds", "max_bytes"):
        rules = {id(f.metadata["rule"]) for table in (ContentConf, MotionConf, PALConf)
                 for f in dataclasses.fields(table) if f.name == name}
        assert len(rules) == 1, name


@pytest.mark.parametrize("make, bad, words", [
    (ContentPAL, dict(timing="performances"), "timing must be one of content, period, auto, "),
    (MotionPAL, dict(max_shift=0.6), "parameter max_shift must be <= 0.5"),
    (MotionPAL, dict(evidence="angles"), "evidence must be one of kinetemes, path"),
    (PAL, dict(timing="tempo"), "timing must be one of content, period, auto, performances"),
])
def test_each_learner_refuses_what_its_table_refuses(make, bad, words):
    with pytest.raises(ValidationError, match=words):
        make(**bad)
    with pytest.raises(ValidationError, match=words):
        get(make.name, **bad)


def test_the_paper_s_learner_refuses_several_performances():
    one = generate(seed=1).actiongram
    with pytest.raises(ValidationError, match="ContentPAL.induce learns from one actiongram, "
                                              "got 2 performances"):
        ContentPAL().induce([one, one])


@settings(max_examples=40)
@given(min_copies=st.integers(2, 9), alpha=st.floats(1e-6, 1.0),
       joint_share=st.floats(0.01, 1.0), rounds=st.integers(1, 4),
       timing=st.sampled_from(["content", "period", "auto", "performances"]))
def test_pal_hands_each_learner_its_own_values(min_copies, alpha, joint_share, rounds, timing):
    pal = PAL(min_copies=min_copies, alpha=alpha, joint_share=joint_share, rounds=rounds,
              timing=timing)
    motion = MotionConf.pick(pal.conf())
    assert (motion.min_copies, motion.alpha, motion.joint_share) == (min_copies, alpha,
                                                                      joint_share)
    assert motion == MotionPAL(**{k: v for k, v in pal.get_params().items()
                                  if k in MotionConf.names()}).conf()
    if timing != "performances":
        content = ContentConf.pick(pal.conf())
        assert (content.rounds, content.timing, content.min_copies) == (rounds, timing,
                                                                         min_copies)


def test_locate_reads_the_parameters_the_action_was_learnt_with():
    assert MotionConf.of("pal", {"min_cycle": 0.5, "rounds": 2}).min_cycle == 0.5
    assert MotionConf.of("pal_motion", {"min_cycle": 0.5}).min_cycle == 0.5
    assert MotionConf.of("sequential", {"alpha": 0.5}) == MotionConf()
