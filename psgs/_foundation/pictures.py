"""Whether matplotlib can write a picture to a path: its suffix checked before any work.

matplotlib chooses a picture's format by the file's suffix and refuses one it does not write
only once the figure is drawn, as a traceback after the work; a name without a suffix it
writes as ``NAME.png`` beside the file named. The commands of psgs, kinetology and praxicon
that draw check their output here first, with one wording.
"""

from __future__ import annotations

from pathlib import Path

from psgs.errors import MissingDependency, ValidationError

__all__ = ["picture_suffix"]

#: listed first in the refusal: the formats people ask for
_USUAL = ("png", "svg", "pdf")


def picture_suffix(path, *, needs: str = "pip install 'psgs[plot]'") -> str:
    """The suffix of ``path``, lower case, when matplotlib writes pictures of that format.

    Parameters
    ----------
    path : str or os.PathLike
        Where a picture is to be written.
    needs : str, optional
        What to install when matplotlib is missing (the extra of the package asking).

    Returns
    -------
    str
        The suffix with its dot (``".png"``).

    Raises
    ------
    ValidationError
        For a suffix matplotlib does not write, or none, naming the path and the formats.
    MissingDependency
        When matplotlib is not installed.

    Examples
    --------
    >>> picture_suffix("walk.PNG")
    '.png'
    >>> picture_suffix("walk.txt")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: walk.txt: matplotlib cannot write '.txt' pictures; give one of .png, .svg, .pdf, ...
    >>> picture_suffix("walk")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    psgs.errors.ValidationError: walk: matplotlib cannot write a picture without a suffix; give one of .png, ...
    """
    try:
        # the package first: a submodule imported before is found in sys.modules on its own,
        # even where the package cannot be imported now
        import matplotlib  # noqa: F401
        from matplotlib.backend_bases import FigureCanvasBase
    except ImportError:  # pragma: no cover - depends on the environment
        raise MissingDependency(f"pictures need matplotlib: {needs} "
                                f"(or pip install matplotlib)") from None
    suffix = Path(path).suffix.lower()
    known = FigureCanvasBase.get_supported_filetypes()
    if suffix[1:] not in known:
        names = ", ".join(f".{n}" for n in [*_USUAL, *sorted(set(known) - set(_USUAL))])
        what = f"{suffix!r} pictures" if suffix else "a picture without a suffix"
        raise ValidationError(f"{path}: matplotlib cannot write {what}; give one of {names}")
    return suffix
