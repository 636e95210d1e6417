"""``parse(max_seconds=...)`` and ``psgs praxicon parse --max-seconds``: past the bound no more
window is read, and the windows read are parsed: the timeline up to there, its ``bound`` and
``reason`` (as the library's searches report a bound in their result); the command prints it
and exits 3, naming the bound on stderr. parse had no bound: 0.9 s a minute of motion.

Where the clock stops is made exact by a budget that expires after a given number of windows
(or by a bound of a nanosecond, past which only the first window, always read, is)."""

from __future__ import annotations

import numpy as np
import pytest

from kinetology import Motion, synthetic_motion
from praxicon.description import DescriptionError
from praxicon.parsing import describe_windows, parse, windows
from praxicon_fixtures import run_praxicon


@pytest.fixture(scope="module")
def two_actions():
    """Window descriptions of a and b, and a recording of a then b (15.9 s, parsed in windows
    of 1 s every 0.25 s: 60 windows), as the module's example."""
    a = [synthetic_motion(3, (0,), seed=1, noise=n) for n in (0.2, 0.5, 1.0)]
    b = [synthetic_motion(3, (2,), seed=2, noise=n) for n in (0.2, 0.5, 1.0)]
    px = describe_windows({"a": a, "b": b}, window=1.0, hop=0.5)
    joined = Motion(np.concatenate([a[0].values, b[1].values]), a[0].channels, 120.0,
                    source="joined")
    return px, joined


def _expiring_after(monkeypatch, windows_read: int) -> None:
    """The budget's clock expires once ``windows_read`` windows were read (asked once a
    window from the second on)."""
    import psgs.budget

    asked = []

    def expired(self) -> bool:
        asked.append(1)
        return len(asked) >= windows_read

    monkeypatch.setattr(psgs.budget.Budget, "expired", expired)


def test_without_a_bound_the_timeline_is_whole(two_actions):
    px, joined = two_actions
    whole = parse(px, joined)
    assert whole.bound is None and whole.reason is None and whole.end == joined.duration
    assert parse(px, joined, max_seconds=1e9) == whole  # a bound not reached changes nothing


@pytest.mark.parametrize("read", [1, 12, 20])
def test_the_windows_read_are_parsed_up_to_the_bound(two_actions, monkeypatch, read):
    px, joined = two_actions
    whole = parse(px, joined)
    _expiring_after(monkeypatch, read)
    cut = parse(px, joined, max_seconds=5.0)
    starts, _ = windows(joined, 1.0, 0.25)
    assert cut.bound == "max_seconds" and cut.duration == whole.duration
    # it ends where the whole timeline's answer of the next window would begin
    end = (starts[read - 1] + starts[read]) / 2 + 0.5
    assert cut.end == pytest.approx(end, abs=1e-6) and cut.spans[0].start == 0.0
    assert cut.reason == (f"stopped after 5 seconds (max_seconds): parsed to {end:.2f} s of "
                          f"{joined.duration:.2f} s")
    # the spans end there, each the action the whole timeline has there
    times = np.linspace(0.0, end - 0.3, 25)
    assert cut.labels(times) == whole.labels(times)
    with pytest.raises(DescriptionError, match=rf"^a time of 15 s: the recording's times are 0 "
                                               rf"to 15\.8667 s, parsed to {end:g} s "
                                               rf"\(max_seconds\)$"):
        cut.labels([15.0])
    assert repr(cut).endswith(f", parsed to {end:.2f} s (max_seconds)>")


def test_the_first_window_is_always_read(two_actions):
    px, joined = two_actions
    cut = parse(px, joined, max_seconds=1e-9)  # past at once, on the real clock
    (span,) = cut.spans
    assert cut.bound == "max_seconds" and (span.start, span.stop) == (0.0, 0.625)
    assert span.action == "a"


@pytest.mark.parametrize("bad", [0, -1, float("nan"), "2", True])
def test_the_bound_is_a_positive_number_of_seconds(two_actions, bad):
    px, joined = two_actions
    with pytest.raises(DescriptionError, match=r"^max_seconds must be a positive number or "
                                               r"None, not "):
        parse(px, joined, max_seconds=bad)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    from praxicon_fixtures import build_wave_and_step

    return build_wave_and_step(tmp_path_factory.mktemp("data"))


def test_the_command_prints_what_was_parsed_and_exits_3(built, tmp_path, capsys):
    take = str(built.parent / "wave_1.bvh")
    status, whole, err = run_praxicon(capsys, ["parse", str(built), take])
    assert status == 0 and err == ""
    plot = tmp_path / "t.png"
    argv = ["parse", str(built), take, "--max-seconds", "1e-9", "--plot", str(plot)]
    status, out, err = run_praxicon(capsys, argv)
    assert status == 3
    # one window's span, then the picture's path; the bound named on stderr
    first, written = out.splitlines()
    assert first.split()[:3] == ["0.00", "1.13", "moves.wave"] and written == str(plot)
    assert plot.stat().st_size > 0
    assert err == ("psgs: the parse stopped at its bound max_seconds (1e-09 s): parsed to "
                   "1.13 s of 6.00 s; the timeline above ends there\n")
    assert whole.splitlines()[0].split()[2] == "moves.wave"
    # a bound that is no positive number: a usage error, before any work
    with pytest.raises(SystemExit) as usage:
        run_praxicon(capsys, ["parse", str(built), take, "--max-seconds", "0"])
    assert usage.value.code == 2
    assert "argument --max-seconds: must be positive" in capsys.readouterr().err


def test_the_commands_deadline_runs_from_its_start(built, monkeypatch, capsys):
    """The command's one deadline covers reading the praxicon; parse's windows are read until
    it (the first always): a praxicon read past it leaves one window, as a nanosecond does.
    A deadline started again for parse would parse the whole take; one handed on as seconds
    left, floored at a millisecond, read windows past it."""
    import time

    from praxicon import store

    real = store.read_descriptions

    def slow(*args, **kwargs):
        time.sleep(0.3)
        return real(*args, **kwargs)

    monkeypatch.setattr(store, "read_descriptions", slow)
    take = str(built.parent / "wave_1.bvh")
    status, out, err = run_praxicon(capsys, ["parse", str(built), take, "--max-seconds", "0.2"])
    assert status == 3
    (only,) = out.splitlines()
    assert only.split()[:3] == ["0.00", "1.13", "moves.wave"]
    assert err == ("psgs: the parse stopped at its bound max_seconds (0.2 s): parsed to "
                   "1.13 s of 6.00 s; the timeline above ends there\n")
