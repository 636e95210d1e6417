"""Inducers: learn a grammar system from an actiongram, or from several performances.

Every inducer is configured by keyword arguments and has one method,
``induce(performances) -> Induction``, taking one
:class:`~psgs.actiongram.Actiongram` or a sequence of them (each one
performance of the same action; see :mod:`psgs.induce.base` for the contract).
Built in: :class:`PAL` (``"pal"``) and the sequential baseline
:class:`Sequential` (``"sequential"``). Other packages add inducers through
the entry-point group ``psgs.inducers`` (``name = "package.module:Class"``);
:func:`get` and :func:`available` see them (:mod:`psgs.induce.registry`).

Beside the inducers, their evaluation: :mod:`psgs.induce.synthetic` (the
paper's synthetic protocol with ground truth, and ``success``) and
:mod:`psgs.induce.sweep` (success against noise over many seeds, in worker
processes).

>>> from psgs import Actiongram
>>> from psgs.induce import get
>>> get("sequential").induce(Actiongram.from_strings({"a": "abab"})).components
('a',)
"""

from __future__ import annotations

from .base import Inducer
from .pal import PAL
from .registry import available, get
from .results import ActuatorReport, Induction, Morpheme, StringReport
from .sequential import Sequential
from .locate import Located, locate  # noqa: E402  (after PAL: locate reads PAL's modules)

__all__ = ["Induction", "Inducer", "StringReport", "ActuatorReport", "Morpheme", "PAL",
           "Sequential", "get", "available", "locate", "Located"]
