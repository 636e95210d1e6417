"""What psgs, kinetology and praxicon share, below all three of them.

One home for each piece every package of the distribution needs, so that no package keeps
a copy of another's:

* :mod:`psgs._foundation.shell`: the command-line shell (exit statuses, the help formatter,
  argument types, the error-handling ``run``, the version lookup);
* :mod:`psgs._foundation.lazy`: a package's names imported on first use;
* :mod:`psgs._foundation.engines`: choosing between numpy's array passes and numba's
  compiled loops;
* :mod:`psgs._foundation.files`: reading an input file whole (no device, a pipe to a limit, strict UTF-8);
* :mod:`psgs._foundation.text`: its lines as an editor counts them, its numbers as written;
* :mod:`psgs._foundation.pictures`: whether matplotlib writes a picture to a path (its suffix).

The error tree is :mod:`psgs.errors` (public: users catch its classes). These modules import
nothing of psgs but :mod:`psgs.errors`, so any layer may use them; kinetology and praxicon
may import them although they are private (tests/core/test_architecture.py lists what
kinetology may import).
"""

# the one place the version is written (pyproject.toml reads it; ``psgs.__version__`` is it)
__version__ = "0.1.0"
