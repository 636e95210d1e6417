"""The option values of ``kinetology segment``, ``compress`` and ``plot``, checked before any
file is read (kept apart from the commands, :mod:`kinetology._commands`: it loads the
segmentation and numpy, which the commands import when a handler runs).

A bad value is then one line at once, not after reading a large take, nor after the error of a
missing file; the words are those the work itself would refuse the value in, so a message
does not depend on whether the file could be read.
"""

from __future__ import annotations

from .motion import check_number
from .segmentation import DEFAULTS
from .segmentation import _check as check_parameters

__all__ = ["check_segment_options", "check_codec_options"]


def check_segment_options(args) -> None:
    """``segment``'s values: the segmentation settings, ``--min-seconds`` and ``--start`` /
    ``--stop`` (those :func:`kinetology.cut` refuses whatever the take; with ``--labels`` they
    are refused as such, and later).

    Examples
    --------
    >>> from argparse import Namespace
    >>> check_segment_options(Namespace(unwrap=0.5, min_seconds=None, labels=None, start=None,
    ...                                 stop=None))
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: unwrap must be 0 (off) or a period of at least 1 degree, not 0.5: a step of more than half the period between two frames is taken for a wrap and folded back
    """
    from .performances import check_window

    check_parameters({n: getattr(args, n) for n in DEFAULTS if getattr(args, n, None) is not None})
    if args.min_seconds is not None:  # as from_spans checks it
        check_number(args.min_seconds, "min_seconds")
    if not args.labels:
        check_window(args.start, args.stop)


def check_codec_options(params: dict, max_error: float | None = None) -> None:
    """The codec's settings ``params``, or ``max_error`` (rate control, which takes none), as
    :func:`kinetology.compress` checks them.

    Examples
    --------
    >>> check_codec_options({"quantum": 0.0})
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: quantum must be positive, not 0.0
    >>> check_codec_options({}, max_error=float("nan"))
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: max_error must be a positive number of degrees, not nan
    """
    from .codec.encoder import _settings
    from .codec.rate import check_max_error

    if max_error is not None:
        check_max_error(max_error)
    else:
        _settings(params)
