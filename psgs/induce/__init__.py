"""Inducers: learn a grammar system from an actiongram, or from several performances.

Every inducer is configured by keyword arguments and has one method,
``induce(performances) -> Induction``, taking one
:class:`~psgs.actiongram.Actiongram` or a sequence of them (each one
performance of the same action; see :mod:`psgs.induce.base` for the contract).
Built in: :class:`PAL` (``"pal"``), which hands one actiongram to the
paper's learner :class:`~psgs.induce.pal.ContentPAL` (``"pal_content"``) and
several performances to the real-motion learner
:class:`~psgs.induce.pal.MotionPAL` (``"pal_motion"``), and the sequential
baseline :class:`Sequential` (``"sequential"``). Each declares its parameters
once, in a frozen table (:mod:`psgs.induce.conf`);
:func:`psgs.induce.testing.check_inducer` checks that an inducer keeps the
contract (the suite runs it on every registered one). Other packages add inducers through
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
from .conf import Conf
from .pal import PAL, ContentPAL, MotionPAL
from .pal.motion import ActuatorReport, Located, Morpheme, locate
from .registry import available, get
from .results import Induction, StringReport
from .sequential import Sequential

__all__ = ["Induction", "Inducer", "Conf", "StringReport", "ActuatorReport", "Morpheme", "PAL",
           "ContentPAL", "MotionPAL", "Sequential", "get", "available", "locate", "Located"]
