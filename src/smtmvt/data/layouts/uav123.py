"""UAV123 layout: ``<root>/data_seq/UAV123/<folder>/000001.jpg ...`` and
``<root>/anno/UAV123/<seq>.txt`` (1-based ``x,y,w,h``; ``NaN,NaN,NaN,NaN`` where the target
is absent).

Sequences
---------
One sequence per annotation file, named by its stem. As got10k's ``UAV123`` dataset class
does (``got10k/datasets/uav123.py``), a sequence listed in :data:`.uav123_ranges.UAV123_RANGES`
(``bird1_2``: frames 775-1477 of folder ``bird1``) reads that range of its folder; any other
sequence ``<seq>`` reads ``data_seq/UAV123/<seq>/000001.jpg`` on, one frame per annotation
line. A missing frame file is an error naming it; so is a line count other than the range's.

Absent frames
-------------
The NaN lines are kept as NaN rows. pytracking (``extract_results.py``,
``calc_seq_err_robust`` with ``dataset == 'uav'``) and pysot (``success_overlap``,
``success_error``: ``iou``/``dist`` start at -1 for frames without a positive-size box) score
them as OTB's MATLAB toolkit does: overlap -1 (a failure), centre error -1 (a hit at every
precision threshold), over **all** frames: the ``"otb"`` rule of
:mod:`smtmvt.evaluation.metrics`. (got10k's ``ExperimentUAV123._calc_metrics`` instead drops
them; we follow the two toolkits that agree with OTB's.)
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..boxes import read_boxes
from ..errors import SequenceError
from .common import sequence_from_files
from .uav123_ranges import UAV123_RANGES

__all__ = ["NAME", "ABSENT_RULE", "matches", "entries", "open_entry"]

NAME = "uav123"
ABSENT_RULE = "otb"
ANNO = Path("anno", "UAV123")
FRAMES = Path("data_seq", "UAV123")


def matches(root: Path) -> bool:
    """True when ``root`` has both ``anno/UAV123/`` and ``data_seq/UAV123/``."""
    return (root / ANNO).is_dir() and (root / FRAMES).is_dir()


def _range(name: str, n_lines: int) -> tuple[str, int, int]:
    return UAV123_RANGES.get(name, (name, 1, n_lines))


def entries(root: Path) -> list:
    """``[(name, frame folder, None), ...]``, one per ``anno/UAV123/*.txt``."""
    out = []
    for anno in (root / ANNO).glob("*.txt"):
        folder = UAV123_RANGES.get(anno.stem, (anno.stem,))[0]
        out.append((anno.stem, root / FRAMES / folder, None))
    return out


def open_entry(root: Path, name: str, folder: Path):
    """The sequence ``name``: the frames of its range in ``folder``, the boxes of its annotation file."""
    gt_file = root / ANNO / f"{name}.txt"
    boxes = read_boxes(gt_file, one_based=True)
    _, first, last = _range(name, len(boxes))
    if last - first + 1 != len(boxes):
        raise SequenceError(
            f"{gt_file}: {len(boxes)} lines, but {name} is frames {first}-{last} of {folder} "
            f"({last - first + 1} frames)",
            path=gt_file,
        )
    files = [folder / f"{k:06d}.jpg" for k in range(first, last + 1)]
    missing = next((f for f in files if not f.is_file()), None)
    if missing is not None:
        raise SequenceError(f"{name}: frame file {missing} not found (frames {first}-{last})", path=missing)
    return sequence_from_files(files, name, gt_file, source=folder, boxes=np.asarray(boxes))
