"""Box files: OTB ground truth (``groundtruth_rect.txt``) and tracker result files.

On disk a box is one line ``x,y,w,h`` in **1-based** pixel coordinates (OTB's
convention: the top-left pixel is (1, 1)). In the Python API boxes are
**0-based**: ``api_box = file_box - (1, 1, 0, 0)``. The functions here say in
their names and docstrings which one they take or give:

- :func:`parse_boxes`: text -> boxes as written (1-based), no conversion.
- :func:`read_boxes`: file -> 0-based API boxes (``one_based=True`` for as written).
- :func:`write_boxes`: 0-based API boxes -> 1-based file, written atomically.

``read_boxes(write_boxes(p, b))`` gives back ``b`` up to the float rounding of
the +-1 shift (exactly for whole and half pixels).
"""

from __future__ import annotations

import os
import re
from pathlib import Path

import numpy as np

from .atomic import write_text_atomic
from .errors import SequenceError
from .files import read_regular_bytes

__all__ = ["parse_boxes", "read_boxes", "write_boxes", "box_line", "ONE_BASED_OFFSET"]

#: ``file_box = api_box + ONE_BASED_OFFSET``; ``api_box = file_box - ONE_BASED_OFFSET``.
ONE_BASED_OFFSET = np.array([1.0, 1.0, 0.0, 0.0])

# Separators seen in OTB files: ",", "\t", " ", and mixes ("1, 2\t3 4").
_SEPARATOR = re.compile(r"\s*,\s*|\s+")
# A plain decimal number (no "1_000", no "inf"), or NaN in any case.
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|[nN][aA][nN]")


def parse_boxes(text: str, source: str = "<text>") -> np.ndarray:
    """Parse box lines as written, **without** changing coordinates.

    Parameters
    ----------
    text : str
        One box per line, four numbers ``x y w h`` separated by commas, tabs,
        spaces or any mix of them. ``\\r\\n`` line ends are fine. ``NaN``
        (any case) is accepted for a missing box. Blank lines at the end are
        ignored; a blank line followed by more boxes is an error (it would
        shift every later box by one frame).
    source : str
        Name of the text's origin (usually the file path), used in errors.

    Returns
    -------
    ndarray, shape (m, 4), float64
        The numbers as written (1-based for OTB files). ``m`` is 0 for a text
        with no boxes.

    Raises
    ------
    SequenceError
        A malformed line; the message names ``source``, the 1-based line
        number and the line's text.
    """
    lines = text.splitlines()
    while lines and not lines[-1].strip():
        lines.pop()
    boxes = np.empty((len(lines), 4), dtype=np.float64)
    for i, line in enumerate(lines):
        stripped = line.strip()
        fields = _SEPARATOR.split(stripped) if stripped else []
        problem = None
        if not stripped:
            problem = "blank line before the last box"
        elif "" in fields:
            problem = "empty field (two separators in a row, or one at an end)"
        elif len(fields) != 4:
            problem = f"expected 4 numbers x,y,w,h, found {len(fields)} fields"
        else:
            bad = [f for f in fields if not _NUMBER.fullmatch(f)]
            if bad:
                problem = f"not a number: {bad[0]!r}"
        if problem:
            raise SequenceError(f"{source}, line {i + 1}: {problem}: {line!r}", path=source, line=i + 1)
        boxes[i] = [float(f) for f in fields]
    return boxes


def read_boxes(path, *, one_based: bool = False, allow_empty: bool = False) -> np.ndarray:
    """Read a box file (OTB ground truth or a result file).

    Parameters
    ----------
    path : str or os.PathLike
        File of 1-based ``x,y,w,h`` lines (see :func:`parse_boxes` for the format).
    one_based : bool, keyword-only
        False (default): return 0-based API boxes (``file - (1, 1, 0, 0)``).
        True: return the numbers as written in the file (1-based).
    allow_empty : bool, keyword-only
        A file with no boxes raises unless this is True (then shape ``(0, 4)``).

    Returns
    -------
    ndarray, shape (m, 4), float64
        Boxes as read: invalid boxes (NaN, zero or negative size) are kept as
        they are, for the caller to interpret.

    Raises
    ------
    SequenceError
        Missing/unreadable/empty file, not a regular file (a FIFO), or malformed
        line, naming the file (and line).
    """
    path = os.fspath(path)
    try:
        raw = read_regular_bytes(path)  # a FIFO in its place is an error, not a wait
    except FileNotFoundError:
        raise SequenceError(f"box file not found: {path}", path=path) from None
    except OSError as exc:
        raise SequenceError(f"cannot read box file {path}: {exc.strerror or exc}", path=path) from None
    try:
        text = raw.decode("utf-8-sig")  # tolerate a byte-order mark
    except UnicodeDecodeError as exc:
        line = raw[: exc.start].count(b"\n") + 1
        raise SequenceError(f"{path}, line {line}: not a text file (undecodable byte)", path=path, line=line) from None
    boxes = parse_boxes(text, source=path)
    if len(boxes) == 0 and not allow_empty:
        raise SequenceError(f"box file is empty: {path}", path=path)
    return boxes if one_based else boxes - ONE_BASED_OFFSET


def write_boxes(path, boxes) -> Path:
    """Write 0-based API boxes as a 1-based OTB box file, atomically.

    Parameters
    ----------
    path : str or os.PathLike
        Destination; missing parent folders are created.
    boxes : array_like, shape (m, 4)
        0-based ``(x, y, w, h)`` boxes. Written as ``x+1,y+1,w,h``, comma
        separated, one line per box, numbers in their shortest exact form
        (``198``, ``12.25``); NaN is written as ``NaN``.

    Returns
    -------
    Path
        ``path``.

    Notes
    -----
    Written with :func:`write_text_atomic`: a reader sees either the old file
    whole or the new one whole; a new file gets permissions ``0o644``, a
    replaced file keeps its permissions.
    """
    path = Path(path)
    arr = np.asarray(boxes, dtype=np.float64)
    if arr.ndim != 2 or arr.shape[1] != 4:
        raise ValueError(f"boxes for {path} must have shape (m, 4), got {arr.shape}")
    text = "".join(box_line(row) + "\n" for row in arr)
    return write_text_atomic(path, text, encoding="ascii")


def box_line(box) -> str:
    """One result-file line (no newline) for a 0-based ``(x, y, w, h)`` box: ``x+1,y+1,w,h``
    as :func:`write_boxes` writes it (for files written a line at a time, ``smtmvt track``
    on a live source)."""
    return ",".join(_format_number(v) for v in np.asarray(box, dtype=np.float64) + ONE_BASED_OFFSET)


def _format_number(value: float) -> str:
    """Shortest text that reads back as exactly ``value``; ``NaN`` for NaN."""
    if np.isnan(value):
        return "NaN"
    if not np.isfinite(value):
        raise ValueError(f"cannot write a non-finite box coordinate: {value}")
    return np.format_float_positional(value, trim="-")
