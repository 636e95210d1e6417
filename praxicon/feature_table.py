"""The features a praxicon's descriptions share with many motions, as one matrix: a batch of
takes, or the windows of a recording (:func:`~praxicon.parsing.parse`).

Each motion's features are written into a block of rows as soon as they are read, a row of
numbers and a row of flags (which features it has), over the features the first motion has
(a praxicon of several skeletons describes others that no motion of this one has); the matrix
keeps the columns every motion has, known once the last motion is read. A recording's windows
are counted before they are read, so that their rows are one block made at once, which is the
answer itself when every window was read and has every feature (the usual case): no copy of
it is made.
"""

from __future__ import annotations

import numpy as np

from .description import Descriptions, feature_rows
from .features import feature_joint

__all__ = ["feature_matrix"]

#: rows of a block when the number of motions is not known beforehand
_BLOCK = 256


def feature_matrix(descriptions: Descriptions, motions, *, shape: bool = True,
                   count: int | None = None):
    """The features the descriptions share with every motion, as one matrix.

    Returns ``(columns, rows, missing)``: the indices of the descriptions' features kept, a
    motions x kept-features matrix, and per motion the joints of the descriptions' features
    it lacks (of every action: in a praxicon of several skeletons, the other skeletons' too;
    :class:`~praxicon.recognition.Recognition` names each action's).

    Parameters
    ----------
    descriptions : Descriptions
    motions : iterable of kinetology.Motion
        Read one at a time; each one's features are kept as numbers, not as the dict of them
        (the windows of an hour's recording are 14,400 motions, and a dict of features each
        held ten times more).
    shape : bool, default True
        Whole takes' features (False: a window's, :func:`~praxicon.features.motion_features`).
    count : int, optional
        At most this many motions (a recording's windows, counted before they are read): the
        rows are then one block of ``count`` rows, made at once.

    Examples
    --------
    >>> from kinetology import synthetic_motion
    >>> from praxicon.description import describe
    >>> d = describe({"a": [synthetic_motion(2, (0,), seed=s) for s in (1, 2)],
    ...               "b": [synthetic_motion(2, (1,), seed=s) for s in (3, 4)]})
    >>> takes = [synthetic_motion(2, (0,), seed=5), synthetic_motion(2, (1,), seed=6)]
    >>> columns, x, missing = feature_matrix(d, takes, count=2)
    >>> x.shape == (2, len(d.spread.features)), missing
    (True, ((), ()))
    >>> bool(np.array_equal(x, feature_matrix(d, takes)[1]))
    True
    """
    wanted = descriptions.spread.features
    size = _BLOCK if count is None else max(1, int(count))
    kept: list[int] = []  # the features of the first motion: the only ones every motion can have
    blocks: list[tuple[np.ndarray, np.ndarray]] = []
    # per motion the joints it lacks: one tuple (of one string a joint) per set of joints, as
    # each window of a recording on one skeleton lacks the same other skeletons' joints
    joint = {f: feature_joint(f) for f in wanted}
    lacking: dict[tuple, tuple] = {}
    missing = []
    n = 0
    for motion in motions:
        row = feature_rows([motion], shape=shape)[0]
        if not n:
            kept = [i for i, f in enumerate(wanted) if f in row]
        if n == len(blocks) * size:
            # column order (Fortran), as the kept columns of a matrix come (values[:, columns]):
            # the matrix answered is laid out as it was when it was one such copy
            blocks.append((np.full((size, len(kept)), np.nan, order="F"),
                           np.zeros((size, len(kept)), dtype=bool)))
        values, present = blocks[-1]
        present[n % size] = [wanted[i] in row for i in kept]
        values[n % size] = [row.get(wanted[i], np.nan) for i in kept]
        lacks = tuple(sorted({joint[f] for f in wanted if f not in row}))
        missing.append(lacking.setdefault(lacks, lacks))
        n += 1
    used = [(v[:n - k * size], p[:n - k * size]) for k, (v, p) in enumerate(blocks)]
    has = np.ones(len(kept), dtype=bool)
    for _, present in used:
        has &= present.all(axis=0)
    columns = np.array(kept, dtype=int)[has] if n else np.arange(len(wanted))
    if len(used) == 1 and n == size and has.all():
        return columns, used[0][0], tuple(missing)  # the block itself: every row and column
    x = np.empty((n, len(columns)), order="F")
    start = 0
    for values, _ in used:  # copied a column at a time: no second copy of a block is made
        for j, c in enumerate(np.flatnonzero(has)):
            x[start:start + len(values), j] = values[:, c]
        start += len(values)
    return columns, x, tuple(missing)
