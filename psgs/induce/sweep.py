"""Success against noise: the synthetic protocol over many seeds, in worker processes.

:func:`noise_sweep` runs ``trials`` seeded actiongrams of
:func:`psgs.induce.synthetic.generate` per noise level through each inducer
and counts :func:`~psgs.induce.synthetic.success`; ``psgs bench noise`` and
``benchmarks/noise.py`` are built on it. Each (inducer, level) cell is one
job, so ``jobs`` worker processes share the work cell by cell.
"""

from __future__ import annotations

import numbers
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass

from ..errors import ValidationError
from .conf import check_number, plain_number
from .registry import get
from .synthetic import generate, success

__all__ = ["SweepRow", "noise_sweep"]


@dataclass(frozen=True)
class SweepRow:
    """Success of one inducer at one noise level over ``trials`` actiongrams.

    Parameters
    ----------
    inducer : str
        The inducer's name.
    noise : float
        The noise level.
    trials : int
        Actiongrams run.
    successes : int
        How many of them :func:`~psgs.induce.synthetic.success` accepted.
    seconds : float
        Wall time of the cell.
    cpu_seconds : float, optional
        CPU time of the cell (in its worker process).

    Examples
    --------
    >>> SweepRow("pal", 0.1, 4, 3, 1.0).rate
    0.75
    """

    inducer: str
    noise: float
    trials: int
    successes: int
    seconds: float
    cpu_seconds: float = 0.0

    @property
    def rate(self) -> float:
        """Successes over trials (0 when there were no trials)."""
        return self.successes / self.trials if self.trials else 0.0


def _trial_batch(job):
    """Run one (inducer, noise) cell; module level so worker processes can import it."""
    inducer_name, params, noise, seeds, variant = job
    inducer = get(inducer_name, **params)
    began, cpu = time.perf_counter(), time.process_time()
    wins = 0
    for seed in seeds:
        case = generate(seed=seed, noise=noise, **variant)
        wins += success(inducer.induce(case.actiongram), case)
    return (inducer_name, noise, len(seeds), wins, time.perf_counter() - began,
            time.process_time() - cpu)


def noise_sweep(levels: Iterable[float], trials: int, *, inducers: Sequence[str] = ("pal",),
                params: Mapping[str, Mapping[str, object]] | None = None, seed: int = 0,
                variant: Mapping[str, object] | None = None, jobs: int = 1,
                progress: Callable[[int, int], object] | None = None) -> list[SweepRow]:
    """Success rate of each inducer at each noise level over ``trials`` seeded actiongrams.

    Trial ``t`` at every level uses seed ``seed + t`` (the same templates and
    strings, different noise), so levels are comparable.

    Parameters
    ----------
    levels : iterable of float
        Noise levels (0 to 1).
    trials : int
        Actiongrams per level.
    inducers : sequence of str, optional
        Inducer names (:func:`psgs.induce.get`), each once; default ``("pal",)``.
    params : mapping, optional
        Inducer name -> its keyword parameters.
    seed : int, optional
        The first seed (default 0).
    variant : mapping, optional
        Extra keyword arguments of :func:`~psgs.induce.synthetic.generate`
        (e.g. ``{"durations": "random"}``).
    jobs : int, optional
        Worker processes; 1 (the default) runs in this process.
    progress : callable, optional
        Called as ``progress(done, total)`` after each cell.

    Returns
    -------
    list of SweepRow
        One per (inducer, level), inducers outermost, in the order given.

    Raises
    ------
    ValidationError
        For an unknown inducer or parameter, arguments ``generate`` refuses, a level that is
        no number from 0 to 1, ``trials`` or ``jobs`` that is not a whole number ≥ 1, an
        inducer named twice (its parameters are those of its name, so it would run the same
        trials again), or an argument of the wrong kind (``inducers`` a single string,
        ``params`` no mapping).

    Examples
    --------
    >>> rows = noise_sweep([0.0], 2, inducers=("pal", "sequential"))
    >>> [(r.inducer, r.successes) for r in rows]
    [('pal', 2), ('sequential', 0)]
    """
    levels, inducers, params, variant = _checked(levels, trials, inducers, params, seed,
                                                 variant, jobs, progress)
    seeds = range(seed, seed + int(trials))  # not a list: the trials are not all held at once
    cells = [(name, dict(params.get(name, {})), float(level), seeds, variant)
             for name in inducers for level in levels]
    results = []
    if jobs > 1 and len(cells) > 1:
        # a worker per cell at most: the pool forks all its workers at once
        with ProcessPoolExecutor(max_workers=min(jobs, len(cells))) as pool:
            for k, out in enumerate(pool.map(_trial_batch, cells), start=1):
                results.append(out)
                if progress:
                    progress(k, len(cells))
    else:
        for k, cell in enumerate(cells, start=1):
            results.append(_trial_batch(cell))
            if progress:
                progress(k, len(cells))
    return [SweepRow(*cell) for cell in results]


def _checked(levels, trials, inducers, params, seed, variant, jobs, progress):
    """noise_sweep's arguments checked before any trial runs (a bad one found after hours of
    trials would lose them): the levels, inducer names and mappings, as tuples and dicts."""
    check_number("trials", plain_number(trials), low=1, integer=True)  # np.int64 as before
    check_number("jobs", plain_number(jobs), low=1, integer=True)
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral) or seed < 0:
        raise ValidationError(f"seed must be a non-negative integer, not {seed!r}")
    if isinstance(levels, (str, bytes)) or not isinstance(levels, Iterable):
        raise ValidationError(f"levels must be a sequence of noise levels, not {levels!r}")
    levels = tuple(levels)
    for level in levels:  # numpy's float32 and integers are numbers too, as float() read them
        check_number("noise level", plain_number(level), low=0, high=1)
    if isinstance(inducers, (str, bytes)) or not isinstance(inducers, Iterable):
        raise ValidationError(f"inducers must be a sequence of inducer names, not {inducers!r}")
    inducers = tuple(inducers)
    for k, name in enumerate(inducers):
        # params are keyed by name, so a second run of a name is the first one again
        if name in inducers[:k]:
            raise ValidationError(f"inducers names {name!r} twice: give each inducer once")
    read = {}
    for name, given in (("params", params), ("variant", variant)):
        try:  # a mapping, or (name, value) pairs as dict() reads them, read once (an iterator)
            read[name] = dict(given or {})
        except (TypeError, ValueError):
            raise ValidationError(f"{name} must be a mapping, not {given!r}") from None
    params = read["params"]
    for name, given in params.items():
        if not isinstance(given, Mapping):
            raise ValidationError(f"params[{name!r}] must map parameter names to values, "
                                  f"not {given!r}")
    if progress is not None and not callable(progress):
        raise ValidationError(f"progress must be callable, not {progress!r}")
    return levels, inducers, params, read["variant"]
