"""Process pools under Ctrl-C: workers that leave it to their parent, and a parent that
neither loses an interrupt nor leaves a worker running.

The build's pool (:mod:`praxicon.builder`, forked workers) and the drawing's
(:mod:`praxicon.pictures`, spawned ones) share these; SIGINT goes to the whole process group,
so each worker would otherwise print a traceback of its own and the parent could stop in the
middle of starting one.
"""

from __future__ import annotations

import signal
import threading
from concurrent.futures import ProcessPoolExecutor
from contextlib import contextmanager

__all__ = ["ignore_interrupts", "interrupts_deferred", "spawned_ignoring_interrupts",
           "stop_pool"]


def ignore_interrupts() -> None:
    """A worker process's initializer: Ctrl-C (SIGINT, sent to the whole process group) is
    left to the process that started the pool, which cancels the work, leaves its files
    whole and stops the workers (:func:`stop_pool`); a worker waiting for work printed a
    traceback of its own before ``psgs: interrupted``."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


@contextmanager
def interrupts_deferred():
    """Ctrl-C held back until the block ends, then delivered as it would have been.

    A process pool forks its workers at the first submit; an interrupt that landed in the
    parent's after-fork handlers (logging's release of its lock) was swallowed there
    ("Exception ignored") and left that lock taken, so the build hung at its next fork, and one
    that landed between the workers' start and the pool's thread's left a thread that could not
    be joined. Python's handler can only be set from the main thread: elsewhere nothing is held.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    previous = signal.signal(signal.SIGINT, lambda signum, frame: caught.append(signum))
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)
        if caught:  # to the handler now in place: KeyboardInterrupt, or what the caller set
            signal.raise_signal(signal.SIGINT)


def stop_pool(pool: ProcessPoolExecutor) -> None:
    """Stop ``pool`` now: nothing more starts, and its workers end without finishing what
    they do (they ignore Ctrl-C, so a shutdown waited for every action being learnt)."""
    terminate = getattr(pool, "terminate_workers", None)  # Python 3.14
    if callable(terminate):
        terminate()
        return
    # before 3.14 the pool names its processes, and the thread that manages them, only in
    # private attributes (shutdown clears both)
    processes = list((getattr(pool, "_processes", None) or {}).values())
    manager = getattr(pool, "_executor_manager_thread", None)
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        process.terminate()
    # that thread reaps the workers it sees end and marks the work they held as failed: wait
    # for it first, so that the futures are done when this returns, and reap after it rather
    # than beside it (a process two threads wait for at once can keep reading as alive, its
    # exit code taken by the other thread)
    # Ctrl-C can land inside the pool's first submit, between its processes' start and its
    # thread's: that thread never ran, and joining it raised over the interrupt
    if manager is not None and manager.ident is not None:
        manager.join(timeout=10)
    for process in processes:
        process.join()


@contextmanager
def spawned_ignoring_interrupts():
    """SIGINT blocked in this thread while it spawns a pool's workers.

    A spawned worker is a fresh interpreter that takes Ctrl-C as KeyboardInterrupt until its
    initializer ignores it, a second or so of imports in which each worker printed a traceback
    before ``psgs: interrupted`` and died; the blocked mask is what it inherits, so the
    interrupt waits, and is dropped when the initializer ignores it. The pool must exist
    before: its queues start multiprocessing's resource tracker, which unblocks SIGINT after
    starting its own process. In this process the block only delays the interrupt until the
    submits are done (:func:`interrupts_deferred` holds it meanwhile).
    """
    block = getattr(signal, "pthread_sigmask", None)  # not on Windows
    if block is None:
        yield
        return
    previous = block(signal.SIG_BLOCK, {signal.SIGINT})
    try:
        yield
    finally:
        block(signal.SIG_SETMASK, previous)
