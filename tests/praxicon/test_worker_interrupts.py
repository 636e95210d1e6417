"""Ctrl-C with worker processes: the workers ignore SIGINT (the process that started them
handles it), so none prints a traceback, and they are stopped at once rather than waited for."""

from __future__ import annotations

import multiprocessing
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from praxicon_fixtures import write_manifest

#: The build, run as its own program: the wave takes a worker a minute and the step is quick
#: (a build starts no more workers than actions), so that at the interrupt one worker is busy
#: and the other waits for work (the one that printed a traceback), and a parent that waited
#: for its workers would not be done in time.
SCRIPT = textwrap.dedent("""
    import signal, sys, time

    import praxicon.builder
    from praxicon.learn import learn_action


    def slow(action, settings):
        if action.content == "wave":
            time.sleep(60)
        return learn_action(action, settings)


    if __name__ == "__main__":
        signal.signal(signal.SIGINT, signal.default_int_handler)  # not inherited as ignored
        praxicon.builder.learn_action = slow
        from psgs.cli import main

        sys.exit(main(["praxicon", "build", sys.argv[1], "-o", sys.argv[2], "--workers", "2",
                       "--no-progress"]))
""")


def _workers(pid: int) -> list[int]:
    """The processes forked from ``pid`` (its command line; not the resource tracker's)."""
    own = Path(f"/proc/{pid}/cmdline").read_bytes()
    found = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            parent = int(stat.read_text().rsplit(")", 1)[1].split()[1])
            if parent == pid and (stat.parent / "cmdline").read_bytes() == own:
                found.append(int(stat.parent.name))
        except (OSError, IndexError, ValueError):
            continue  # a process that ended meanwhile
    return found


def _ignores_sigint(pid: int) -> bool:
    try:
        status = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return False
    mask = next(line.split()[1] for line in status.splitlines() if line.startswith("SigIgn:"))
    return bool(int(mask, 16) & (1 << (signal.SIGINT - 1)))


def _group(pgid: int) -> list[str]:
    """The processes of process group ``pgid`` still there: pid, state and command line."""
    found = []
    for stat in Path("/proc").glob("[0-9]*/stat"):
        try:
            fields = stat.read_text().rsplit(")", 1)[1].split()
            if int(fields[2]) == pgid and fields[0] != "Z":
                command = (stat.parent / "cmdline").read_bytes().replace(b"\0", b" ")
                found.append(f"{stat.parent.name} {fields[0]} {command.decode(errors='replace')}")
        except (OSError, IndexError, ValueError):
            continue
    return found


def _alive(pids: list[int]) -> list[int]:
    """Those of ``pids`` that are still processes (not zombies: a worker whose parent ended
    is the init process's to reap)."""
    left = []
    for pid in pids:
        try:
            state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
        except OSError:
            continue
        if state != "Z":
            left.append(pid)
    return left


@pytest.mark.skipif(not sys.platform.startswith("linux")
                    or multiprocessing.get_start_method() != "fork",
                    reason="reads /proc; the workers are the build's forks")
def test_ctrl_c_prints_no_worker_traceback_and_stops_at_once(tmp_path):
    manifest = write_manifest(tmp_path, {"wave": [1, 2], "step": [3, 4]})
    script = tmp_path / "build.py"
    script.write_text(SCRIPT)
    out = tmp_path / "px"
    root = str(Path(__file__).resolve().parents[2])  # the praxicon under test, not an install
    env = {**os.environ, "PYTHONPATH": os.pathsep.join(
        [root, *filter(None, [os.environ.get("PYTHONPATH")])])}
    started = time.monotonic()
    # stderr to a file and the build's own exit awaited: a pipe would also wait for any
    # process that inherited it, and a failure would not say which process was still there
    err_file = tmp_path / "stderr"
    with err_file.open("w") as err_out:
        build = subprocess.Popen([sys.executable, str(script), str(manifest), str(out)],
                                 stderr=err_out, text=True, start_new_session=True,
                                 cwd=root, env=env)
    workers: list[int] = []
    try:
        deadline = time.monotonic() + 10
        while time.monotonic() < deadline:  # both workers up, past their initializer
            workers = _workers(build.pid)
            if len(workers) == 2 and all(map(_ignores_sigint, workers)):
                break
            time.sleep(0.02)
        else:  # an interrupt before the build started would test nothing of the pool
            pytest.fail("the build's two workers did not start within 10 s")
        os.killpg(build.pid, signal.SIGINT)  # what Ctrl-C sends: the whole process group
        try:
            build.wait(timeout=max(1.0, 14 - (time.monotonic() - started)))
        except subprocess.TimeoutExpired:
            pytest.fail(f"the build did not stop within 14 s of its start; its processes: "
                        f"{_group(build.pid)}; stderr: {err_file.read_text()!r}")
        # nothing it started is left running either (its workers were stopped, not orphaned)
        left = _alive(workers) or _group(build.pid)
        assert not left, f"left running after the build ended: {_group(build.pid)} {left}"
    finally:
        if _group(build.pid):
            os.killpg(build.pid, signal.SIGKILL)
        build.wait()
    err = err_file.read_text()
    assert "Traceback" not in err, err
    assert build.returncode == 130 and err.strip().splitlines()[-1] == "psgs: interrupted"
    assert (out / "index.json").is_file()  # the folder of what was done, as before


def test_the_build_pool_workers_ignore_sigint():
    from praxicon.builder import executor_for

    pool, close = executor_for(2)
    try:
        assert pool.submit(signal.getsignal, signal.SIGINT).result() == signal.SIG_IGN
    finally:
        close()


def test_the_drawing_pool_ignores_sigint_and_is_stopped_when_interrupted(tmp_path,
                                                                         monkeypatch):
    import concurrent.futures

    import psgs.draw
    from fuzz_support import praxicon_seed
    from praxicon import dump
    from praxicon.builder import ignore_interrupts
    from praxicon.pictures import draw_praxicon

    made, pids = [], set()

    class Pool(concurrent.futures.ProcessPoolExecutor):
        def __init__(self, *args, **kwargs):
            made.append(kwargs.get("initializer"))
            super().__init__(*args, **kwargs)

        def submit(self, *args, **kwargs):
            future = super().submit(*args, **kwargs)
            pids.update(self._processes)  # spawned as work is submitted
            return future

    monkeypatch.setattr(concurrent.futures, "ProcessPoolExecutor", Pool)
    monkeypatch.setattr(psgs.draw, "graphviz_available", lambda: False)
    dump(praxicon_seed(), tmp_path / "px")

    def interrupt(done, total, what):  # Ctrl-C while the workers draw the systems
        raise KeyboardInterrupt

    started = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        draw_praxicon(tmp_path / "px", tmp_path / "img", workers=2, progress=interrupt)
    assert made == [ignore_interrupts] and len(pids) == 2
    for pid in pids:  # stopped and reaped, not left drawing (active_children() can still list
        with pytest.raises(ProcessLookupError):  # one the pool's own thread reaped)
            os.kill(pid, 0)
    assert time.monotonic() - started < 10


def test_closing_the_pool_while_an_exception_is_handled_does_not_wait_for_the_work():
    # library code closes the pool in a finally after Ctrl-C: a shutdown waited for every
    # action being learnt, the workers ignoring SIGINT, and a second Ctrl-C hung for good
    from praxicon.builder import executor_for

    pool, close = executor_for(2)
    busy = pool.submit(time.sleep, 60)
    workers = list(pool._processes.values())  # noqa: SLF001 - the processes to check
    started = time.monotonic()
    with pytest.raises(KeyboardInterrupt):
        try:
            raise KeyboardInterrupt
        finally:
            close()
    assert time.monotonic() - started < 10 and busy.done()
    assert workers and not any(w.is_alive() for w in workers)


@pytest.mark.skipif(sys.version_info >= (3, 14), reason="3.14's pool stops its own workers")
def test_ctrl_c_before_the_pool_s_thread_starts_stops_it_without_a_new_error(monkeypatch):
    # the interrupt once landed in the first submit after the workers had started and before
    # the pool's managing thread had: stopping the pool then tried to join that thread
    import concurrent.futures.process as process

    from praxicon.builder import executor_for

    def interrupted(thread):
        raise KeyboardInterrupt

    monkeypatch.setattr(process._ExecutorManagerThread, "start", interrupted)
    pool, close = executor_for(2)
    with pytest.raises(KeyboardInterrupt):
        try:
            pool.submit(time.sleep, 60)
        finally:
            workers = list(pool._processes.values())  # noqa: SLF001 - the processes to check
            close(stop=True)
    assert workers and not any(w.is_alive() for w in workers)


def test_ctrl_c_during_the_submits_waits_for_them_then_interrupts_the_build(tmp_path):
    # a pool forks its workers inside the first submit: an interrupt raised there could land in
    # the parent's after-fork handlers (logging's lock release), where it was swallowed and left
    # the lock taken; held until the submits are done, it interrupts the build as Ctrl-C does
    from concurrent.futures import Executor, Future

    from praxicon.builder import build
    from praxicon.datasets import read_datasets

    finished: list[str] = []

    class Forking(Executor):
        def submit(self, fn, /, *args, **kwargs):
            signal.raise_signal(signal.SIGINT)  # Ctrl-C while the "fork" runs
            finished.append(args[0].name)  # what the after-fork handlers still had to do
            return Future()

    actions = read_datasets([str(write_manifest(tmp_path, {"wave": [1, 2], "step": [3, 4]}))])
    with pytest.raises(KeyboardInterrupt):
        build(actions, tmp_path / "px", executor=Forking(), progress=False)
    assert sorted(finished) == sorted(a.name for a in actions)
    assert (tmp_path / "px" / "index.json").is_file()
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
