"""Deprecated: the synthetic protocol moved to :mod:`psgs.induce.synthetic`, the sweep to
:mod:`psgs.induce.sweep`.

This module only re-exports their names (importing it warns) so that older
code keeps working; new code imports from the new modules.

>>> import warnings
>>> with warnings.catch_warnings():
...     warnings.simplefilter("ignore", DeprecationWarning)
...     from psgs.synthetic import generate
>>> generate.__module__
'psgs.induce.synthetic'
"""

from __future__ import annotations

import warnings

from .induce.sweep import SweepRow, noise_sweep
from .induce.synthetic import PAPER_POINTS, Synthetic, generate, success

__all__ = ["Synthetic", "generate", "success", "PAPER_POINTS", "SweepRow", "noise_sweep"]

warnings.warn("psgs.synthetic is deprecated: import generate, success, Synthetic and "
              "PAPER_POINTS from psgs.induce.synthetic, and noise_sweep and SweepRow from "
              "psgs.induce.sweep", DeprecationWarning, stacklevel=2)
