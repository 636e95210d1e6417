"""parse checks each span against its action's feature-group test: a span whose windows
mostly fail it, or a long stretch of failing windows inside one, is none of these."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from praxicon.description import DescriptionError
from praxicon.parsing import _supported, describe_windows, parse
from praxicon_fixtures import refused


def _oracle(path, passes, none, support, stretch):
    """The rule spelt out window by window: each window's run of its action, the share of
    that run's windows that pass, and the failing stretch the window lies in."""
    out = list(path)
    n = len(path)
    for i in range(n):
        if path[i] == none:
            continue
        a = i
        while a > 0 and path[a - 1] == path[i]:
            a -= 1
        b = i
        while b + 1 < n and path[b + 1] == path[i]:
            b += 1
        share = sum(passes[a:b + 1]) / (b - a + 1)
        if share < support:
            out[i] = none
            continue
        if not passes[i]:
            c, d = i, i
            while c > a and not passes[c - 1]:
                c -= 1
            while d < b and not passes[d + 1]:
                d += 1
            if d - c + 1 >= stretch:
                out[i] = none
    return out


@settings(max_examples=150, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 3), st.booleans()), min_size=1, max_size=40),
       st.floats(0, 1), st.integers(1, 12))
def test_supported_agrees_with_the_rule_window_by_window(windows, support, stretch):
    path = np.array([a for a, _ in windows])
    passes = np.array([p for _, p in windows])
    found = _supported(path, passes, 3, support, stretch)
    assert found.tolist() == _oracle(path.tolist(), passes.tolist(), 3, support, stretch)
    # only ever none of these where an action was: never another action
    assert np.all((found == path) | (found == 3))


def _learnt():
    from kinetology import synthetic_motion

    a = [synthetic_motion(3, (0,), seed=1, noise=n) for n in (0.2, 0.5, 1.0)]
    b = [synthetic_motion(3, (2,), seed=2, noise=n) for n in (0.2, 0.5, 1.0)]
    return describe_windows({"a": a, "b": b}, window=1.0, hop=0.5)


def test_a_stretch_that_fits_no_action_is_none_of_these():
    """Action a with a joint it keeps near 0 held 20 degrees away: the windows' distance
    still reads some of it as a, the feature-group test does not."""
    from kinetology import Motion, synthetic_motion

    px = _learnt()
    base = synthetic_motion(3, (0,), seed=1, noise=0.7)
    values = base.values.copy()
    values[:, 2] += 20
    odd = Motion(values, base.channels, base.frame_rate)
    times = np.arange(0.05, odd.duration, 0.1)
    alone = parse(px, odd, support=0.0, unfit=math.inf).labels(times)
    checked = parse(px, odd).labels(times)
    # the check only ever answers none of these where the threshold alone named an action
    assert all(c == a or c is None for a, c in zip(alone, checked))
    assert sum(c is None for c in checked) > sum(a is None for a in alone)


def test_a_recording_of_learnt_actions_keeps_its_spans():
    from kinetology import Motion, synthetic_motion

    px = _learnt()
    a = synthetic_motion(3, (0,), seed=1, noise=0.5)
    b = synthetic_motion(3, (2,), seed=2, noise=0.5)
    joined = Motion(np.concatenate([a.values, b.values]), a.channels, 120.0)
    assert [s.action for s in parse(px, joined).spans if s.action] == ["a", "b"]


@pytest.mark.parametrize("name, value", [("support", -0.1), ("support", 1.5),
                                         ("support", math.nan), ("support", "half"),
                                         ("unfit", 0.0), ("unfit", -1.0), ("unfit", math.nan)])
def test_bad_support_or_unfit_is_refused(name, value):
    from kinetology import synthetic_motion

    with pytest.raises(DescriptionError, match=name):
        parse(_learnt(), synthetic_motion(3, (0,), seed=1), **{name: value})


@pytest.mark.parametrize("option, value", [("--support", "2"), ("--unfit", "0"),
                                           ("--support", "nan")])
def test_the_command_checks_support_and_unfit_before_reading(capsys, tmp_path, option, value):
    said = refused(capsys, ["parse", str(tmp_path / "no-praxicon"), str(tmp_path / "x.bvh"),
                            option, value])
    assert said.startswith(option) and "no-praxicon" not in said


def test_a_huge_unfit_is_never_and_unfit_counts_the_real_hop():
    """``unfit`` of 1e308 seconds overflowed the count of windows (a traceback); the count is
    of the windows' real hop, whole frames (a 0.25 s hop at 30 fps is 8 frames, 0.267 s)."""
    from kinetology import synthetic_motion

    from praxicon.parsing import _stretch

    px = _learnt()
    motion = synthetic_motion(3, (0,), seed=1, noise=0.7)
    assert parse(px, motion, unfit=1e308) == parse(px, motion, unfit=math.inf)
    assert _stretch(4.0, [0.0, 8 / 30], 100) == 15
    assert _stretch(4.0, [0.0, 0.25], 100) == 16

