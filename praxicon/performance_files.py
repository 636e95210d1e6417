"""The performances an action was learnt from, read back from their files.

Generation reads them for the body around the actuators, the root's course and a style's
scales (:mod:`praxicon.body_motion`, :mod:`praxicon.acyclic`), at the paths the records keep
(as ``build`` was given them). A file that cannot be read there (moved, deleted, a relative
path read from another folder, damaged) is never left out without a word: the motion made
from the others would not be the one the praxicon gives. :func:`read_performances` returns
the motions and, per such file, the line saying why; :func:`performances_of` raises that.

A performance's style is a word of its file name (:func:`style_of`).
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["RELATIVE", "learnt_files", "missing_style", "performances_of", "read_performances",
           "style_of", "unreadable"]

#: Where a recorded path is read from (the records keep the paths build was given).
RELATIVE = ("a relative path is relative to the folder build ran in: run from there, or build "
            "from absolute paths")


def style_of(file) -> list[str]:
    """The words of a performance's file name, any of which can name its style.

    Bandai Namco's names are ``dataset-N_CONTENT_STYLE_TAKE``: their words are split at
    ``_``, so ``walk-turn-left`` stays one word.

    >>> style_of("data/dataset-2_walk-turn-left_elderly_003.bvh")
    ['dataset-2', 'walk-turn-left', 'elderly', '003']
    """
    return Path(str(file)).stem.split("_")


def missing_style(record, style: str, failed: dict[str, str] | None = None) -> ValueError:
    """The error for a style none of ``record``'s performances read gives.

    When performances of that style were learnt from but none could be read (a relative path
    read from another folder, a file moved), the error names one and why, not "no such
    style". Else it names the styles there are: the words that tell the performances' file
    names apart (take numbers aside), and the action's own style (an action of one style,
    whose file names differ by their take numbers only).

    ``failed`` holds, per file that could not be read, the line saying why, from a caller
    that has read the performances (:func:`read_performances`): a file of the style not among
    them was read (too short, or not on the channels of the others) and none is read again.
    Without it, the style's first file is read here to say why.

    Examples
    --------
    >>> from praxicon.records import ActionRecord, PerformanceRecord
    >>> record = ActionRecord("d.wave", "d", "wave", performances=(
    ...     PerformanceRecord("/x/d_wave_happy_1.bvh"), PerformanceRecord("/x/d_wave_angry_1.bvh")))
    >>> missing_style(record, "sad")
    ValueError("action 'd.wave' has no performance of style 'sad' (styles: angry, happy)")
    >>> missing_style(record, "happy")
    ValueError("action 'd.wave': its performances of style 'happy' cannot be read (/x/d_wave_happy_1.bvh: no such file)")
    >>> missing_style(record, "happy", {})  # read by the caller: too short
    ValueError("action 'd.wave': its performances of style 'happy' cannot be read (/x/d_wave_happy_1.bvh: too short, or not on the channels of the other performances)")
    """
    own = [record.performances[i] for i in record.learnt_from or range(len(record.performances))
           if style in style_of(record.performances[i].file)]
    if own:
        file = own[0].file
        if failed is None:
            failed = _unread(file)
        why = failed.get(file, f"{file}: too short, or not on the channels of the other "
                               f"performances")
        return ValueError(f"action {record.name!r}: its performances of style {style!r} "
                          f"cannot be read ({why})")
    names = [style_of(p.file) for p in record.performances]
    styles = {n[i] for n in names for i in range(len(n))
              if not n[i].isdigit() and any(len(o) <= i or o[i] != n[i] for o in names)}
    styles = sorted(styles | ({record.style} if record.style else set()))
    return ValueError(f"action {record.name!r} has no performance of style {style!r}"
                      + (f" (styles: {', '.join(styles)})" if styles else ""))


def learnt_files(record, style: str | None = None) -> list[str]:
    """The files of the performances ``record`` was learnt from (every one when the record
    does not say), in its order, a file once per performance; with ``style``, those whose
    file name holds it as a word.

    Examples
    --------
    >>> from praxicon.records import ActionRecord, PerformanceRecord
    >>> record = ActionRecord("d.wave", "d", "wave", learnt_from=(0, 2), performances=(
    ...     PerformanceRecord("d_wave_happy_1.bvh"), PerformanceRecord("d_wave_angry_1.bvh"),
    ...     PerformanceRecord("d_wave_angry_2.bvh")))
    >>> learnt_files(record), learnt_files(record, "angry")
    (['d_wave_happy_1.bvh', 'd_wave_angry_2.bvh'], ['d_wave_angry_2.bvh'])
    """
    files = [record.performances[i].file
             for i in record.learnt_from or range(len(record.performances))]
    return files if style is None else [f for f in files if style in style_of(f)]


def _why(file: str, exc: Exception) -> str:
    """The line saying why ``file`` cannot be read, naming it once."""
    if isinstance(exc, FileNotFoundError):
        return f"{file}: no such file" + ("" if Path(file).is_absolute() else f"; {RELATIVE}")
    # what kinetology says, on one line (it names the file)
    why = str(exc).splitlines()[0] if str(exc).strip() else type(exc).__name__
    return why if why.startswith(file) else f"{file}: {why}"


def _unread(file: str) -> dict[str, str]:
    """``{file: the line saying why it cannot be read}``, or ``{}`` when it reads."""
    import kinetology

    try:
        kinetology.read(file)
    except Exception as exc:  # not a motion it reads: what kinetology says, on one line
        return {file: _why(file, exc)}
    return {}


def read_performances(record, style: str | None = None) -> tuple[list, dict[str, str]]:
    """The motions of the performances ``record`` was learnt from, each cut to its span, and
    per file that cannot be read the line saying why (in the record's order).

    With ``style``, only those whose file name holds it as a word (:func:`style_of`). A
    performance of fewer than 2 frames (its span cut short) is left out: it reads, but holds
    no motion.

    Examples
    --------
    >>> from praxicon.records import ActionRecord, PerformanceRecord
    >>> record = ActionRecord("d.a", "d", "a", performances=(
    ...     PerformanceRecord("/nowhere/a_1.bvh"),))
    >>> read_performances(record)
    ([], {'/nowhere/a_1.bvh': '/nowhere/a_1.bvh: no such file'})
    """
    import kinetology

    out, failed = [], {}
    for i in record.learnt_from or range(len(record.performances)):
        p = record.performances[i]
        if style is not None and style not in style_of(p.file):
            continue
        try:
            m = kinetology.read(p.file)
        except Exception as exc:  # a moved or unreadable file: said, never left out silently
            failed.setdefault(p.file, _why(p.file, exc))
            continue
        if p.start is not None or p.stop is not None:
            a = int(round((p.start or 0.0) * m.frame_rate))
            b = m.frames if p.stop is None else int(round(p.stop * m.frame_rate))
            m = kinetology.Motion(m.values[a:b], m.channels, m.frame_rate, m.skeleton, m.source)
        if m.frames >= 2:
            out.append(m)
    return out, failed


def unreadable(record, failed: dict[str, str], style: str | None = None) -> str | None:
    """The error line for the files in ``failed`` (:func:`read_performances`) of the
    performances ``record`` was learnt from (of ``style``), else None: how many cannot be
    read, and the first one and why.

    Examples
    --------
    >>> from praxicon.records import ActionRecord, PerformanceRecord
    >>> record = ActionRecord("d.a", "d", "a", performances=(
    ...     PerformanceRecord("/x/a_1.bvh"), PerformanceRecord("/x/a_2.bvh")))
    >>> unreadable(record, {"/x/a_2.bvh": "/x/a_2.bvh: no such file"})
    "action 'd.a': 1 of the 2 performances it was learnt from cannot be read (/x/a_2.bvh: no such file)"
    """
    if not failed:
        return None
    files = learnt_files(record, style)
    lost = sum(f in failed for f in files)
    of = "" if style is None else f" of style {style!r}"
    which = (f"the one performance{of} it was learnt from cannot be read" if len(files) == 1
             else f"none of the {len(files)} performances{of} it was learnt from can be read"
             if lost == len(files) else
             f"{lost} of the {len(files)} performances{of} it was learnt from cannot be read")
    return f"action {record.name!r}: {which} ({next(iter(failed.values()))})"


def performances_of(record, style: str | None = None) -> list:
    """The motions of the performances an action was learnt from, cut to their spans (of
    ``style`` only, when given: :func:`style_of`).

    Raises
    ------
    ValueError
        One line, when one of them cannot be read (:func:`unreadable`): the body, the course
        or the scales made from the others would not be the action's, and were, without a
        word.

    Examples
    --------
    >>> from praxicon.records import ActionRecord, PerformanceRecord
    >>> performances_of(ActionRecord("d.a", "d", "a", performances=(
    ...     PerformanceRecord("/nowhere/a_1.bvh"),)))
    Traceback (most recent call last):
    ...
    ValueError: action 'd.a': the one performance it was learnt from cannot be read (/nowhere/a_1.bvh: no such file)
    """
    motions, failed = read_performances(record, style)
    if failed:
        raise ValueError(unreadable(record, failed, style))
    return motions
