"""Ctrl-C while the drawing pool starts: its spawned workers take the work inside the submits
(a worker started, then the pool's thread), and an interrupt there stops the pool as one later
does, rather than leaving its workers to the interpreter's exit; a worker still starting
prints no traceback of its own."""

from __future__ import annotations

import concurrent.futures
import os
import signal
import time

import pytest

import psgs.draw
from fuzz_support import praxicon_seed
from praxicon import dump
from praxicon.builder import stop_pool
from praxicon.pictures import draw_praxicon


@pytest.fixture
def pools(monkeypatch, tmp_path):
    """The process pools the drawing makes (spawned workers, no Graphviz), each with the pids
    of the workers it started; whatever a test leaves running is stopped after it."""
    made: list = []

    class Pool(concurrent.futures.ProcessPoolExecutor):
        submitted = 0
        pids: set

        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            self.pids = set()
            made.append(self)

        def submit(self, *args, **kwargs):
            try:
                return super().submit(*args, **kwargs)
            finally:  # the workers are started inside the submit, also when it is interrupted
                self.pids.update(self._processes or {})
                Pool.submitted += 1
                self.after_submit()

        def after_submit(self):
            pass

    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", Pool)
    monkeypatch.setattr(psgs.draw, "graphviz_available", lambda: False)
    dump(praxicon_seed(), tmp_path / "px")  # two actions with systems: two workers
    yield Pool, made
    for pool in made:  # a pool left running would be the interpreter's to wait for at exit
        stop_pool(pool)


def _running(pid: int) -> bool:
    """Whether ``pid`` is a process not yet reaped (a zombie counts: no one waited for it)."""
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    return True


def _draw(tmp_path):
    return draw_praxicon(tmp_path / "px", tmp_path / "img", workers=2)


def test_ctrl_c_between_a_worker_s_start_and_the_pool_s_thread_stops_the_worker(
        pools, tmp_path, monkeypatch):
    # raised before the drawing's try, it left a spawned worker waiting for work that no
    # thread would send, and the exit of `psgs praxicon draw` waited for it for good
    import concurrent.futures.process as process

    def interrupted(thread):
        raise KeyboardInterrupt

    monkeypatch.setattr(process._ExecutorManagerThread, "start", interrupted)
    _, made = pools
    started = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        _draw(tmp_path)
    assert len(made) == 1 and made[0].pids, "no worker was started: nothing was tested"
    assert not [pid for pid in made[0].pids if _running(pid)]
    assert time.monotonic() - started < 10
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_ctrl_c_in_a_later_submit_stops_the_workers_instead_of_drawing_on(pools, tmp_path):
    # raised before the drawing's try, the pool was left to the interpreter's exit, which
    # waited for every system submitted to be drawn
    Pool, made = pools

    def interrupt(pool):
        if Pool.submitted == 2:
            raise KeyboardInterrupt

    Pool.after_submit = interrupt
    with pytest.raises(KeyboardInterrupt):
        _draw(tmp_path)
    assert len(made) == 1 and made[0].pids
    assert not [pid for pid in made[0].pids if _running(pid)]
    assert not (tmp_path / "img" / "systems").exists() or \
        not list((tmp_path / "img" / "systems").iterdir())


def test_ctrl_c_during_the_submits_is_held_until_they_are_done(pools, tmp_path):
    # as in the build: the signal waits for the submits, then stops the pool
    Pool, made = pools

    def ctrl_c(pool):
        if Pool.submitted == 1:
            signal.raise_signal(signal.SIGINT)

    Pool.after_submit = ctrl_c
    with pytest.raises(KeyboardInterrupt):
        _draw(tmp_path)
    assert Pool.submitted == 2  # both systems were submitted before the interrupt
    assert len(made) == 1 and len(made[0].pids) == 2
    assert not [pid for pid in made[0].pids if _running(pid)]
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    assert not signal.pthread_sigmask(signal.SIG_BLOCK, set())  # nothing left blocked


def test_a_worker_interrupted_while_it_starts_prints_nothing_and_draws(pools, tmp_path, capfd):
    # Ctrl-C reaches the whole process group: a spawned worker still importing (a second or
    # so before its initializer ignores SIGINT) printed a KeyboardInterrupt traceback and died,
    # and the drawing failed with a broken pool
    Pool, made = pools

    def ctrl_c_to_the_new_workers(pool):
        for pid in pool.pids - getattr(pool, "told", set()):
            os.kill(pid, signal.SIGINT)  # just spawned: far from its initializer
        pool.told = set(pool.pids)

    Pool.after_submit = ctrl_c_to_the_new_workers
    written = _draw(tmp_path)
    assert len(made[0].pids) == 2
    systems = sorted(p.name for p in written if p.parent.name == "systems")
    assert systems == ["moves.step.svg", "moves.wave.svg"]
    err = capfd.readouterr().err
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err
