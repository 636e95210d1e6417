"""A flag set at a deadline, for the compiled loops that read no clock.

numba's compiled motif search (:mod:`psgs.induce.pal._motifs_jit`) cannot read the wall
clock, and one of its units of work, a seed grown in one long string, can take minutes (one
pass over the string for each column of each growth step). :func:`alarm` hands it a one-byte
array that a timer thread sets when the deadline of a :class:`~psgs.budget.Budget` comes;
the loops read it between passes and stop. Without a deadline the flag is never set, and
nothing changes.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ...budget import Budget

__all__: list[str] = []  # private: motifs.py is the caller


@contextmanager
def alarm(clock: Budget) -> Iterator[np.ndarray]:
    """A flag (a one-byte array, 0) that turns 1 when ``clock``'s deadline comes, while the
    ``with`` block runs; never, when ``clock`` has no deadline or one farther off than a
    timer can wait (``threading.TIMEOUT_MAX``, some 292 years).

    Examples
    --------
    >>> import time
    >>> from psgs.budget import Budget
    >>> with alarm(Budget(seconds=0.01)) as flag:
    ...     time.sleep(0.2)
    ...     print(flag[0])
    1
    >>> with alarm(Budget()) as flag:
    ...     print(flag[0])
    0
    >>> with alarm(Budget(seconds=1e10)) as flag:  # past TIMEOUT_MAX: no timer
    ...     print(flag[0])
    0
    """
    flag = np.zeros(1, dtype=np.uint8)
    # (the seconds left by the clock's own reading: the same deadline as its check())
    left = clock.left()
    if left is None or left >= threading.TIMEOUT_MAX:
        # a wait that long makes the timer's thread die of OverflowError; it would never
        # ring anyway
        yield flag
        return
    timer = threading.Timer(left, flag.fill, (1,))
    timer.daemon = True  # a timer left waiting never keeps the interpreter alive
    timer.start()
    try:
        yield flag
    finally:
        timer.cancel()
