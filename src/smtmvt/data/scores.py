"""Per-frame scores files (``smtmvt track --scores``): the box, its confidence and whether it is lost.

A CSV file with a header line, then one line per frame::

    frame,x,y,w,h,confidence,lost
    1,198,214,34,81,1,0
    2,197.5,214.25,34,81,0.9731,0

``frame`` is the 1-based frame number (the line of the result file), the box
is 1-based as in result files, ``confidence`` in [0, 1] and ``lost`` 0 or 1
(:class:`smtmvt.TrackResult`); numbers in their shortest exact form.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .atomic import write_text_atomic
from .boxes import ONE_BASED_OFFSET, _format_number

__all__ = ["SCORES_HEADER", "write_scores", "read_scores", "scores_line"]

#: The first line of a scores file.
SCORES_HEADER = "frame,x,y,w,h,confidence,lost"


def write_scores(path, boxes, confidence, lost) -> Path:
    """Write a scores file atomically (:func:`smtmvt.data.write_text_atomic`); return ``Path(path)``.

    ``boxes`` : (m, 4) 0-based ``(x, y, w, h)`` pixels (written 1-based);
    ``confidence`` : (m,) floats in [0, 1]; ``lost`` : (m,) booleans.
    """
    path = Path(path)
    b = np.asarray(boxes, dtype=np.float64)
    c = np.asarray(confidence, dtype=np.float64)
    lost_flags = np.asarray(lost, dtype=bool)
    if b.ndim != 2 or b.shape[1] != 4:
        raise ValueError(f"scores for {path}: boxes must have shape (m, 4), got {b.shape}")
    if c.shape != (len(b),) or lost_flags.shape != (len(b),):
        raise ValueError(
            f"scores for {path}: {len(b)} boxes but confidence of shape {c.shape} and lost of shape {lost_flags.shape}"
        )
    outside = np.flatnonzero(~((c >= 0) & (c <= 1)))
    if len(outside):
        raise ValueError(f"scores for {path}: confidence of frame {outside[0] + 1} is {c[outside[0]]}, not in [0, 1]")
    lines = [SCORES_HEADER] + [scores_line(i + 1, box, ci, li) for i, (box, ci, li) in enumerate(zip(b, c, lost_flags))]
    return write_text_atomic(path, "\n".join(lines) + "\n", encoding="ascii")


def scores_line(frame: int, box, confidence: float, lost: bool) -> str:
    """One line (no newline) of a scores file, as :func:`write_scores` writes it: the 1-based
    ``frame``, the 0-based ``box`` written 1-based, ``confidence`` and ``lost`` as 0 or 1."""
    b = np.asarray(box, dtype=np.float64) + ONE_BASED_OFFSET
    return ",".join([str(frame), *(_format_number(v) for v in b), _format_number(float(confidence)), str(int(lost))])


def read_scores(path) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(boxes (m, 4) 0-based, confidence (m,), lost (m,) bool)`` of a scores file.

    Raises ValueError naming the file and line of a header or line that is not as
    :func:`write_scores` writes them.
    """
    path = Path(path)
    lines = path.read_text(encoding="ascii").splitlines()
    if not lines or lines[0].strip() != SCORES_HEADER:
        first = lines[0] if lines else ""
        raise ValueError(f"{path}: line 1 must be the header {SCORES_HEADER!r}, got {first!r}")
    rows = []
    for n, line in enumerate(lines[1:], start=2):
        parts = line.split(",")
        try:
            values = [float(v) for v in parts]
        except ValueError:
            values = []
        if len(values) != 7 or values[0] != n - 1 or values[6] not in (0.0, 1.0):
            raise ValueError(f"{path}: line {n} is not 'frame,x,y,w,h,confidence,lost' for frame {n - 1}: {line!r}")
        rows.append(values)
    arr = np.array(rows, dtype=np.float64).reshape(-1, 7)
    return arr[:, 1:5] - ONE_BASED_OFFSET, arr[:, 5], arr[:, 6] == 1.0
