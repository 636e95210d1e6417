"""Building a praxicon: every action learnt, on any executor, resumable.

:func:`build` hands one :func:`~praxicon.learn.learn_action` per action to a
``concurrent.futures.Executor`` (processes, threads, or a Dask cluster through
``dask.distributed.Client.get_executor()``; serial when none is given), and
writes each record as it arrives. What is already in the folder with the same
input key (same files' bytes, spans and settings) is not learnt again. After
every finished action the index is written anew (atomically), so an
interrupted build (Ctrl-C) leaves a valid praxicon of what was done, and the
next build picks up from there.
"""

from __future__ import annotations

import os
import sys
import time
from collections import Counter
from collections.abc import Iterable
from concurrent.futures import Executor, Future, ProcessPoolExecutor, as_completed
from dataclasses import dataclass, replace
from pathlib import Path

from psgs._foundation.files import read_text
from psgs.errors import MissingDependency, ValidationError

from ._pools import ignore_interrupts, interrupts_deferred, stop_pool
from ._record_checks import name_problem
from ._values import check_count, not_all, shown
from .datasets import Action, DatasetError
from .learn import Settings, input_key, learn_action
from .outputs import check_writable_folder
from .description import DescriptionError
from .description_store import (FILE, descriptions_in, descriptions_key, descriptions_text,
                                read_descriptions_file)
from .jsonvalues import read_json, written_by
from .records import ActionRecord, PerformanceRecord, Praxicon, PraxiconError
from .store import read_records, write_atomic, write_index, write_record, write_shared

__all__ = ["build", "BuildResult", "executor_for", "describe_praxicon", "ignore_interrupts",
           "stop_pool"]


@dataclass(frozen=True)
class BuildResult:
    """What a build did: the praxicon written, and which actions were learnt, skipped, failed.

    ``refused`` lists the actions whose name cannot be a file name (with the reason): they
    are not learnt and not stored.
    """

    praxicon: Praxicon
    learnt: tuple[str, ...]
    skipped: tuple[str, ...]
    failed: tuple[str, ...]
    refused: tuple[str, ...] = ()

    @property
    def index(self) -> dict:
        """The index written (``index.json``)."""
        return self.praxicon.index()

    def __repr__(self) -> str:  # a summary, not the dataclass dump of the whole praxicon
        refused = f", {len(self.refused)} refused" if self.refused else ""
        return (f"<BuildResult: {len(self.learnt)} learnt, {len(self.skipped)} already done, "
                f"{len(self.failed)} failed{refused}; {self.praxicon!r}>")


def executor_for(workers: int | None = None, scheduler=None):
    """An executor: a Dask client's (``scheduler`` an address or a Client), N processes, or None.

    Returns ``(executor, close)``; call ``close()`` when done (it shuts down only
    what this function started), ``close(stop=True)`` when the build was interrupted or
    failed: N processes then end at once, without finishing what they learn (they ignore
    Ctrl-C, which is this process's to handle: :func:`ignore_interrupts`). ``close()``
    called while an exception is being handled (in a ``finally`` after Ctrl-C) stops them
    too: a shutdown would wait for every action being learnt, and a second Ctrl-C could not
    end that wait.
    """
    if scheduler is not None:
        try:
            from dask.distributed import Client
        except ImportError:  # pragma: no cover - the dask extra is not installed
            raise MissingDependency("--scheduler needs dask.distributed (pip install "
                             "'psgs[dask]')") from None
        client = scheduler if isinstance(scheduler, Client) else Client(scheduler)
        executor = client.get_executor()
        return executor, ((lambda stop=False: None) if client is scheduler
                          else (lambda stop=False: client.close()))
    if workers is not None:  # "2" failed in a comparison, True was 1
        check_count(workers, "workers")
    if workers is not None and workers > 1:
        pool = ProcessPoolExecutor(max_workers=workers, initializer=ignore_interrupts)

        def close(stop: bool = False) -> None:
            if stop or sys.exc_info()[0] is not None:
                stop_pool(pool)
            else:
                pool.shutdown(cancel_futures=True)

        return pool, close
    return None, lambda stop=False: None


def _as_executor(executor):
    """A Dask client given where an executor is expected becomes its executor."""
    get = getattr(executor, "get_executor", None)
    return get() if callable(get) and not isinstance(executor, Executor) else executor


def build(actions: list[Action], out: str | Path, *, settings: Settings | None = None,
          executor=None, progress: bool = True, datasets: list[str] | None = None,
          log=None) -> BuildResult:
    """Learn every action into the praxicon folder ``out``.

    Parameters
    ----------
    actions : list of Action
        From :func:`praxicon.read_datasets`.
    out : str or Path
        The praxicon folder (made when missing).
    settings : Settings, optional
        Inducer, parameters and segmentation (default: PAL with its defaults).
    executor : concurrent.futures.Executor or dask.distributed.Client, optional
        Where to learn; serially in this process when None.
    progress : bool
        Show a tqdm progress bar on stderr.
    datasets : list of str, optional
        The dataset paths, recorded in the index.
    log : callable, optional
        Called with each one-line problem or failure (default: print to stderr).

    Returns
    -------
    BuildResult

    Raises
    ------
    DatasetError
        When two actions have the same name (one record would overwrite the other).
    ValueError
        (ValidationError) When ``actions`` are not :class:`~praxicon.datasets.Action` values
        or ``out`` is no path or a file.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> from praxicon import read_dataset
    >>> out = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (out / "m.csv").write_text("action,file\\nwave,missing.bvh\\n")
    >>> r = build(read_dataset(out / "m.csv"), out / "px", progress=False, log=lambda s: None)
    >>> r.failed, r.praxicon["m.wave"].problems[0].endswith("unreadable file (no such file)")
    (('m.wave',), True)
    """
    given, actions = actions, list(actions) if isinstance(actions, Iterable) else None
    if actions is None or not all(isinstance(a, Action) for a in actions):
        raise ValidationError(f"build learns a list of praxicon.Action (read_dataset makes one), "
                              f"{not_all(given, actions, Action)}")
    if not isinstance(out, (str, os.PathLike)):
        raise ValidationError(f"out must be a folder's path, not {type(out).__name__}")
    if isinstance(datasets, str):  # one dataset a letter
        raise ValidationError(f"datasets must be a list of names, not {shown(datasets)}")
    if not (settings is None or isinstance(settings, Settings)):  # a string failed in a worker
        raise ValidationError(f"settings must be a Settings, not {shown(settings)}")
    given, executor = executor, _as_executor(executor)
    if executor is not None and not callable(getattr(executor, "submit", None)):
        raise ValidationError(f"executor must be an Executor or a Dask client, not {given!r}")
    counts = Counter(a.name for a in actions)  # names.count per action was quadratic
    twice = sorted(n for n, count in counts.items() if count > 1)
    if twice:
        raise DatasetError(f"two actions are named {twice[0]!r}: one record would overwrite "
                           f"the other")
    if isinstance(out, (str, os.PathLike)) and os.fspath(out) == "":
        raise ValidationError("the praxicon folder's name is empty ('' would be the current "
                              "folder)")
    out = Path(out)
    try:  # a file in its place (else mkdir's bare "File exists"), or a folder that cannot be
        # written, which failed only once the first action was learnt
        check_writable_folder(out, "a praxicon folder")
    except ValueError as exc:
        raise ValidationError(str(exc)) from None
    seen = _not_of_a_later_psgs(out)
    out.mkdir(parents=True, exist_ok=True)
    settings = settings or Settings.make()
    bar = _bar(0, False)
    log = log or (lambda line: bar.write(f"praxicon: {line}"))
    refused = []
    for action in actions:
        problem = name_problem(action.name)
        if problem:
            refused.append(action.name)
            log(f"{problem}: not learnt (rename the action)")
    actions = [a for a in actions if a.name not in refused]
    done, damaged = read_records(out)
    records: dict[str, ActionRecord] = {}
    timings: dict[str, float] = {}
    keys = {a.name: input_key(a, settings) for a in actions}
    todo, skipped = [], []
    for action in actions:
        previous = done.get(action.name)
        if previous is not None and previous[0] == keys[action.name]:
            records[action.name] = previous[1]
            skipped.append(action.name)
            _repair(out, previous[1], keys[action.name])
        else:
            todo.append(action)
    for name, why in sorted(damaged.items()):
        if name in keys:
            log(f"{why}: learnt again")
    if todo:
        # the learnt actions may change: the old descriptions go before any learning, so that
        # a build interrupted at any moment leaves a folder without descriptions (which load
        # reads, and recognise names the command for), never one describing other records
        (out / FILE).unlink(missing_ok=True)
        seen.pop(FILE, None)  # not kept through the learning: they may be megabytes
    learnt, failed = [], [n for n in skipped if not records[n].learnt]
    dataset_list = tuple(str(d) for d in (datasets or sorted({a.dataset for a in actions})))

    def praxicon() -> Praxicon:
        return Praxicon(tuple(records[n] for n in sorted(records)), settings, dataset_list,
                        tuple((n, keys[n]) for n in sorted(records)))

    index_written = time.monotonic()

    def finish(action: Action, record: ActionRecord, seconds: float) -> None:
        nonlocal index_written
        write_record(out, record, keys[action.name])
        records[action.name] = record
        timings[action.name] = seconds
        (failed if not record.learnt else learnt).append(action.name)
        for problem in record.problems:
            log(f"{action.name}: {problem}")
        if not record.learnt:
            log(f"{action.name}: failed: {record.reason}")
        # the index is rewritten whole (3.7 s for the 56 rewrites of the shared data's build, in
        # the process that should leave the cores to the workers), so during the build at most
        # once a second: the records are on disk at once, resuming reads them, and the index is
        # written whole at the end, also after Ctrl-C
        if time.monotonic() - index_written >= 1.0:
            write_index(out, praxicon())
            index_written = time.monotonic()

    bar = _bar(len(todo), progress)
    try:
        if executor is None:
            for action in todo:
                finish(action, *learn_action(action, settings))
                bar.update(1)
        else:
            with interrupts_deferred():
                futures: dict[Future, Action] = {executor.submit(learn_action, a, settings): a
                                                 for a in schedule(todo)}
            try:
                for future in as_completed(futures):
                    action = futures[future]
                    try:
                        record, seconds = future.result()
                    except Exception as exc:  # a worker died: record it, go on
                        record, seconds = _crashed(action, exc), 0.0
                    finish(action, record, seconds)
                    bar.update(1)
            finally:
                for future in futures:
                    future.cancel()
    finally:
        bar.close()
        # always leave a consistent index of what is done (also after Ctrl-C)
        result = praxicon()
        write_index(out, result, timings={**_old_timings(out), **timings})
        # the patterns that recur across actions (Fig. 13)
        write_shared(out, result)
    # the build's last step: what recognition and parsing read, learnt from every learnt
    # action's performances together (the actions share one spread)
    # the descriptions as read before the build, unless it learnt an action (they were
    # removed then)
    result = _described(out, result, log, announce=progress,
                        read=_UNREAD if todo else seen.get(FILE, _UNREAD))
    return BuildResult(result, tuple(sorted(learnt)), tuple(sorted(skipped)),
                       tuple(sorted(failed)), tuple(refused))


def describe_praxicon(praxicon: Praxicon, *, log=print):
    """The whole-take and window descriptions of every learnt action of ``praxicon``.

    Each action is described from the performances it was learnt from, read as the build
    read them (cut to their span, angles unwrapped); one that cannot be read now is left out
    and named through ``log``. Returns ``(takes, windows)``, or ``None`` (and says why through
    ``log``) when no learnt action has a readable performance or they cannot be described.
    """
    from .datasets import Performance
    from .description import describe
    from .learn import _load_performance
    from .parsing import describe_windows

    takes: dict[str, list] = {}
    for action in praxicon.actions:
        if not action.learnt:
            continue
        motions = []
        for p in action.performances:
            if p.used is False:
                continue
            motion, problem = _load_performance(Performance(p.file, p.start, p.stop, p.label))
            if problem:
                log(f"{action.name}: not described from {p.file}: {problem}")
            else:
                motions.append(motion)
        if motions:
            takes[action.name] = motions
    for retry in (True, False):
        if not takes:
            log("no learnt action with a readable performance: nothing to recognise with")
            return None
        try:
            # the styles of one content (an action per content and style) form a family,
            # which decides "none of these" for its members
            families = {a.name: f"{a.dataset}.{a.content}" for a in praxicon.actions
                        if a.name in takes}
            return describe(takes, families=families), describe_windows(takes)
        except DescriptionError as exc:
            # a take whose features cannot be computed (a value too large to compute with)
            # is left out, as an unreadable one is, and the others described without it;
            # each take is read again only now, so a build that describes pays nothing more
            left_out = _undescribable(takes) if retry else {}
            if not left_out:
                log(f"descriptions not learnt: {exc}")
                return None
            for (name, k), problem in sorted(left_out.items(), reverse=True):
                log(f"{name}: not described from {problem}")  # the problem names the take
                del takes[name][k]
                if not takes[name]:
                    del takes[name]
    return None  # pragma: no cover - the second pass returns or says why


def _undescribable(takes: dict[str, list]) -> dict[tuple[str, int], str]:
    """Per take (its action and place) whose own or whose windows' features cannot be
    computed, why: found take by take, since takes cut from one file share its name."""
    from .description import feature_rows
    from .parsing import learning_windows

    out = {}
    for name, motions in takes.items():
        for k, motion in enumerate(motions):
            try:
                feature_rows([motion])
                feature_rows(list(learning_windows(motion)))
            except DescriptionError as exc:
                out[name, k] = str(exc)
    return out


def _not_of_a_later_psgs(out: Path) -> dict:
    """Refuse to build into a folder whose index or descriptions a later psgs wrote: learnt
    again here, they would be written over at this version (an earlier version's are).

    Returns what it read: per file its JSON value, or the :class:`PraxiconError` reading it
    raised, so that the build's last step (:func:`_described`) does not read the descriptions
    (megabytes) a second time."""
    from .description import FORMAT_VERSION as DESCRIBED
    from .records import FORMAT_VERSION as RECORDED
    read: dict = {}
    for name, version in (("index.json", RECORDED), (FILE, DESCRIBED)):
        if not (out / name).is_file():
            continue
        try:
            said = read[name] = read_json(out / name, PraxiconError)
        except PraxiconError as exc:
            read[name] = exc
            continue  # damaged: read, refused and rebuilt as before
        said = said.get("version") if isinstance(said, dict) else None
        if written_by(said, version) == "later":
            raise PraxiconError(f"{out / name}: of version {said}, written by a later psgs "
                                f"(this one writes {version}); building here would write over "
                                f"it: upgrade psgs, or build into another folder")
    return read


#: :func:`_described`'s ``read`` when the build has not read the descriptions file
_UNREAD = object()


def _described(out: Path, praxicon: Praxicon, log, announce: bool = False,
               read=_UNREAD) -> Praxicon:
    """``praxicon`` with its descriptions: the folder's when they were learnt from the same
    actions, else learnt now and written (``descriptions.json``); ``announce``: say so on
    stderr first (after the progress bar it is the build's one silent step, 15 s on the
    shared data). ``read``: the file's JSON value (or the error reading it raised) when the
    build has read it already, else it is read here."""
    key = descriptions_key(praxicon)
    try:
        if isinstance(read, PraxiconError):
            raise read
        found = read_descriptions_file(out) if read is _UNREAD else \
            descriptions_in(read, out / FILE)
    except PraxiconError as exc:  # damaged or of another version: learnt again
        log(f"{exc}: learnt again")
        found = None
    if found is not None and found[2] == key:
        takes, windows = found[0], found[1]
    else:
        # not left in place while they are learnt anew: an interruption then leaves none
        (out / FILE).unlink(missing_ok=True)
        if announce:
            count = sum(a.learnt for a in praxicon.actions)
            print(f"praxicon: describing the {count} learnt action(s) for recognise and "
                  f"parse ...", file=sys.stderr, flush=True)
        learnt = describe_praxicon(praxicon, log=log)
        if learnt is None:  # and none that would describe other actions
            return praxicon
        takes, windows = learnt
        write_atomic(out / FILE, descriptions_text(takes, windows, key))
    return replace(praxicon, descriptions=takes, window_descriptions=windows)


def _repair(out: Path, record: ActionRecord, key: str) -> None:
    """Rewrite what the record says is on disk where it is not (a deleted ``ACTION.psgs``)."""
    psgs_path = out / f"{record.name}.psgs"
    try:  # read_text refuses a device in its place: rewritten, not read without end
        intact = (read_text(psgs_path) == record.system) if record.system \
            else not psgs_path.exists()
    except (OSError, ValueError):  # ValueError: not UTF-8, not a regular file
        intact = False
    if not intact:
        write_record(out, record, key)


def schedule(actions: list[Action]) -> list[Action]:
    """The order actions are handed to the workers: costliest block of shared files first.

    A block is a set of actions that read the same files (cmu-mocap6's labelled spans share
    its AMC takes); within a block the listing order is kept, because a worker's small
    cache of read motions helps only when one file's spans come together (the biggest
    action first scattered them: 13.4-14.6 s wall instead of 11.1-11.7 s with 2 workers on
    the shared data). Between blocks, the one whose files are the most bytes goes first
    (longest processing time first), so that the last actions to finish are short ones and
    no worker waits long on the other at the end. The order only changes when each action
    is learnt, never what is written.

    Parameters
    ----------
    actions : list of Action
        In listing order.

    Returns
    -------
    list of Action
        The same actions, reordered.

    Examples
    --------
    >>> from praxicon.datasets import Action, Performance
    >>> a = Action("a", "d", "a", performances=(Performance("x.amc", 0.0, 1.0),))
    >>> b = Action("b", "d", "b", performances=(Performance("y.bvh"),))
    >>> c = Action("c", "d", "c", performances=(Performance("x.amc", 2.0, 3.0),))
    >>> [x.name for x in schedule([a, b, c])]  # no file exists: every block weighs 0
    ['a', 'c', 'b']
    """
    import os

    from psgs.analysis import reachable

    readers: dict[str, list[int]] = {}
    for i, action in enumerate(actions):
        for perf in action.performances:
            readers.setdefault(perf.file, []).append(i)

    def sharing(i: int) -> set[int]:  # the actions reading a file action i reads
        return {j for perf in actions[i].performances for j in readers[perf.file]}

    blocks: list[list[int]] = []  # connected by shared files, in listing order
    seen: set[int] = set()
    for i in range(len(actions)):
        if i not in seen:
            block = sorted(reachable(sharing, [i]))  # the core's one graph walk
            seen.update(block)
            blocks.append(block)

    def size(path: str) -> int:
        try:
            return os.path.getsize(path)
        except OSError:
            return 0

    weight = [sum(size(f) for f in {p.file for i in block for p in actions[i].performances})
              for block in blocks]
    order = sorted(range(len(blocks)), key=lambda b: (-weight[b], blocks[b][0]))
    return [actions[i] for b in order for i in blocks[b]]


def _crashed(action: Action, exc: BaseException) -> ActionRecord:
    text = str(exc).splitlines()[0] if str(exc) else ""
    return ActionRecord(action.name, action.dataset, action.content, action.style,
                        status="failed", reason=f"worker failed: {type(exc).__name__}: {text}",
                        problems=tuple(action.problems),
                        performances=tuple(PerformanceRecord(p.file, p.start, p.stop, p.label)
                                           for p in action.performances))


def _old_timings(out: Path) -> dict[str, float]:
    """The timings of earlier builds, when ``timings.json`` holds what it should."""
    try:
        old = read_json(out / "timings.json", ValueError)
    except ValueError:  # missing or damaged: the timings start again
        return {}
    if not isinstance(old, dict):
        return {}
    return {k: v for k, v in old.items()
            if isinstance(v, (int, float)) and not isinstance(v, bool)}


class _NoBar:
    def update(self, n: int) -> None:
        pass

    def write(self, line: str) -> None:
        print(line, file=sys.stderr)

    def close(self) -> None:
        pass


def _bar(total: int, show: bool):
    if not show:
        return _NoBar()
    try:
        from tqdm import tqdm
    except ImportError:  # tqdm is in the praxicon extra; without it, no bar
        return _NoBar()
    bar = tqdm(total=total, unit="action", desc="praxicon", file=sys.stderr)
    bar.write = lambda line: tqdm.write(line, file=sys.stderr)  # above the bar, not through it
    return bar
