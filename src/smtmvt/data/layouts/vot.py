"""VOT short-term layout: ``<root>/<seq>/color/00000001.jpg ...`` (VOT2017 on) or
``<root>/<seq>/00000001.jpg ...`` (earlier), with ``groundtruth.txt`` beside them: per line a
rectangle ``x,y,w,h`` (4 numbers) or a polygon ``x1,y1,...,x4,y4`` (8 numbers).

Polygons are made axis-aligned as the VOT toolkit does (vot-toolkit-python,
``Polygon.convert`` to a rectangle: ``left = min x``, ``top = min y``, ``width = max x - min
x``, ``height = max y - min y``), as pytracking's ``VOTDataset`` does too. (got10k's
``VOT._corner2rect`` instead keeps the polygon's area, centred on its mean corner.) Numbers
are read as 1-based, like OTB's.

Absent frames
-------------
A line of NaN (``NaN,NaN,NaN,NaN``) has no box. pytracking (``extract_results.py``) scores
a ``'vot'`` sequence's frames without a positive-size box as invalid and divides by the
number of valid frames only: they are dropped, the ``"pytracking"`` rule of
:mod:`smtmvt.evaluation.metrics`. Mask lines (``m...``, VOT2020 on) are refused.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ..errors import SequenceError
from ..files import read_regular_bytes
from ..frames import list_images
from .common import groundtruth_entries, images_of, sequence_from_files, visible_folders

__all__ = ["NAME", "ABSENT_RULE", "matches", "entries", "open_entry", "parse_regions"]

NAME = "vot"
ABSENT_RULE = "pytracking"
_SEPARATOR = re.compile(r"\s*,\s*|\s+")
_NUMBER = re.compile(r"[+-]?(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?|[nN][aA][nN]")


def _frames_folder(seq: Path) -> Path:
    return seq / "color" if (seq / "color").is_dir() else seq


def _is_sequence(seq: Path) -> bool:
    if not (seq / "groundtruth.txt").is_file():
        return False
    return (seq / "color").is_dir() or bool(list_images(seq))


def matches(root: Path) -> bool:
    """True when a sub-folder has ``groundtruth.txt`` and ``color/`` or images of its own."""
    return any(_is_sequence(p) for p in visible_folders(root))


def entries(root: Path) -> list:
    """``[(name, folder, None), ...]``: sub-folders with ``groundtruth.txt`` (not hidden)."""
    return groundtruth_entries(root)


def _region(fields: list) -> np.ndarray:
    values = np.array([float(f) for f in fields])
    if len(values) == 4:
        return values
    xs, ys = values[0::2], values[1::2]
    return np.array([xs.min(), ys.min(), xs.max() - xs.min(), ys.max() - ys.min()])


def parse_regions(text: str, source: str) -> np.ndarray:
    """VOT ground-truth lines -> ``(m, 4)`` float64 ``x,y,w,h`` as written (1-based); a NaN
    line gives a NaN row. SequenceError naming ``source`` and the 1-based line otherwise."""
    lines = text.splitlines()
    while lines and not lines[-1].strip():
        lines.pop()
    out = np.empty((len(lines), 4))
    for i, line in enumerate(lines):
        fields = [f for f in _SEPARATOR.split(line.strip()) if f] if line.strip() else []
        problem = None
        if line.lstrip().startswith("m"):
            problem = "a mask region (VOT2020 on) cannot be read, only rectangles and polygons"
        elif len(fields) not in (4, 8):
            problem = f"expected 4 numbers (x,y,w,h) or 8 (a polygon), found {len(fields)} fields"
        elif any(not _NUMBER.fullmatch(f) for f in fields):
            problem = f"not a number: {next(f for f in fields if not _NUMBER.fullmatch(f))!r}"
        if problem:
            raise SequenceError(f"{source}, line {i + 1}: {problem}: {line!r}", path=source, line=i + 1)
        out[i] = _region(fields)
    return out


def open_entry(root: Path, name: str, folder: Path):
    """The sequence ``name`` in ``folder``: ``color/*`` (or the folder's images) and its regions."""
    gt_file = folder / "groundtruth.txt"
    try:
        text = read_regular_bytes(gt_file).decode("utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        raise SequenceError(f"cannot read {gt_file}: {exc}", path=gt_file) from None
    boxes = parse_regions(text, str(gt_file))
    if len(boxes) == 0:
        raise SequenceError(f"box file is empty: {gt_file}", path=gt_file)
    files = images_of(_frames_folder(folder))
    return sequence_from_files(files, name, gt_file, source=folder, boxes=boxes)
