"""``praxicon.shaping.shape``'s rounds: the dead band the answer will have is assumed, checked
on the answer, and the programmes solved again with the answer's band, up to ten rounds. Where
the bands come back to a round's (a cycle of two, on a channel of cmu-subject02's walk at
120 fps), the rounds left would solve the same programmes again, none settling: they stop
there, with what the ten rounds give (status ``band``)."""

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
    # per placement of the peaks two rounds of two programmes (A, B; A again is not solved),
    # where the ten rounds solved twenty
    assert len(solved) == 3 * 2 * 2


def test_an_answer_is_what_it_was(monkeypatch):
    solved = _counted(monkeypatch)
    shaped = shaping.shape(_base(), KNOTS, SYMBOLS, 30.0, {})
    assert shaped.status == "solved" and len(solved) == 3 * 2  # one round per placement
    assert shaped.change < 5
