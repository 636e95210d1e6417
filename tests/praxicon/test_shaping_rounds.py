"""``praxicon.shaping.shape``'s rounds: the dead band the answer will have is assumed, checked
on the answer, and the programmes solved again with the answer's band, up to ten rounds. Where
the bands come back to a round's (a cycle of two, on a channel of cmu-subject02's walk at
120 fps), the rounds left would solve the same programmes again, none settling: they stop
there, with what the ten rounds give (status ``band``). Whether a round's conditions can hold
at all is asked before its nearest curve until some round's did, and after that only where the
nearest curve has no answer."""

from __future__ import annotations

import numpy as np

from kinetology.codec import reconstruct
from kinetology.segmentation import STATES
from praxicon import shaping

KNOTS, SYMBOLS = [0, 20, 40, 60, 80, 100], "RYRBR"


def _base():
    return reconstruct(KNOTS, [STATES.index(k) for k in SYMBOLS],
                       [0.0, -2.0, -3.0, -5.0, -2.0, -4.0])


def _counted(monkeypatch) -> list[int]:
    """The linear programmes shape solves, counted."""
    import scipy.optimize

    solved: list[int] = []
    real = scipy.optimize.linprog

    def linprog(*args, **kwargs):
        solved.append(1)
        return real(*args, **kwargs)

    monkeypatch.setattr(scipy.optimize, "linprog", linprog)
    return solved


def test_bands_that_come_back_stop_the_rounds(monkeypatch):
    solved = _counted(monkeypatch)
    # the base's two bands (velocity, acceleration) as shape first reads them, then every
    # band read is 1.2 times those or those in turn: the check never holds, and the rounds go
    # A, B, A, ...
    real = shaping._band
    read: list[float] = []

    def band(signal, floor, relative):
        k = len(read)
        read.append(real(signal, floor, relative) if k < 2 else
                    read[k % 2] * (1.2 if k // 2 % 2 else 1.0))
        return read[-1]

    monkeypatch.setattr(shaping, "_band", band)
    base = _base()
    shaped = shaping.shape(base, KNOTS, SYMBOLS, 30.0, {})
    assert shaped.status == "band" and np.array_equal(shaped.curve, base)
    # per placement of the peaks two rounds (A, B; A again is not solved, where the ten rounds
    # would solve ten), a programme a round, and in the very first round the conditions alone
    # before it (once they held, the nearest curve is asked at once)
    assert len(solved) == 3 * 2 + 1


def test_an_answer_is_what_it_was(monkeypatch):
    solved = _counted(monkeypatch)
    shaped = shaping.shape(_base(), KNOTS, SYMBOLS, 30.0, {})
    # one round per placement; the conditions alone asked in the first only
    assert shaped.status == "solved" and len(solved) == 3 + 1
    assert shaped.change < 5


def test_no_nearest_curve_keeps_the_conditions_curve(monkeypatch):
    """Where the nearest curve has no answer (its simplex iterations capped here at one), the
    conditions are asked alone in that round too, and their feasible curve is what is kept."""
    import scipy.optimize

    real = scipy.optimize.linprog
    asked: list[tuple[str, int]] = []
    feasible: list[np.ndarray] = []

    def linprog(c, *args, **kwargs):
        whole = bool(np.any(c))  # the conditions alone have no objective
        if whole:
            kwargs = {**kwargs, "options": {**kwargs["options"], "maxiter": 1}}
        answer = real(c, *args, **kwargs)
        asked.append(("whole" if whole else "conditions", answer.status))
        if not whole and answer.status == 0:
            feasible.append(answer.x)
        return answer

    monkeypatch.setattr(scipy.optimize, "linprog", linprog)
    shaped = shaping.shape(_base(), KNOTS, SYMBOLS, 30.0, {})
    # the first round: the conditions, then the whole programme at its cap; every later round:
    # the whole programme first, then (no answer) the conditions alone
    assert asked[:2] == [("conditions", 0), ("whole", 1)]
    rest = asked[2:]
    assert rest and len(rest) % 2 == 0
    assert all(rest[i:i + 2] == [("whole", 1), ("conditions", 0)] for i in range(0, len(rest), 2))
    assert shaped.status == "solved"
    assert any(np.array_equal(shaped.curve, x) for x in feasible)
