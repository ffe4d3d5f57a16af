"""GOT-10k layout: ``<root>/<seq>/00000001.jpg ...``, ``groundtruth.txt``, ``absence.label``,
``cover.label`` (and ``cut_by_image.label``, ``meta_info.ini``, unused here).

Absent frames
-------------
got10k's ``ExperimentGOT10k.report`` (got10k 0.1.3, ``experiments/got10k.py``) keeps "only
valid frames where targets are visible": ``ious[covers > 0]``, with ``cover`` read from
``cover.label`` (``datasets/got10k.py``, ``_fetch_meta``): frames with ``cover == 0`` are
left out of the numerator **and** the denominator. We read them the same way: a frame with
``cover == 0`` (or, without ``cover.label``, ``absence == 1``) has no box (NaN row), and
the layout's scoring rule is ``"pytracking"`` of :mod:`smtmvt.evaluation.metrics`
(invalid frames dropped). One difference: got10k also drops frame 1 from its average; we
keep it (replaced by the ground truth, as in OTB) so that the same frames score the same in
every layout.

Boxes in ``groundtruth.txt`` are read as OTB's: ``x,y,w,h``, 1-based in the file.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .common import groundtruth_entries, images_of, read_flags, sequence_from_files, visible_folders

__all__ = ["NAME", "ABSENT_RULE", "MARKERS", "matches", "entries", "open_entry"]

NAME = "got10k"
ABSENT_RULE = "pytracking"
#: Files that only GOT-10k's sequence folders have.
MARKERS = ("absence.label", "cover.label", "meta_info.ini")


def _is_sequence(folder: Path) -> bool:
    return (folder / "groundtruth.txt").is_file() and any((folder / m).is_file() for m in MARKERS)


def matches(root: Path) -> bool:
    """True when a sub-folder of ``root`` holds ``groundtruth.txt`` and a GOT-10k label file."""
    return any(_is_sequence(p) for p in visible_folders(root))


def entries(root: Path) -> list:
    """``[(name, folder, None), ...]``: sub-folders with ``groundtruth.txt`` (not hidden)."""
    return groundtruth_entries(root)


def absent_frames(folder: Path, n_frames: int) -> np.ndarray | None:
    """``(n_frames,) bool`` from ``cover.label`` (``== 0``), else ``absence.label`` (``== 1``); None without either."""
    if (folder / "cover.label").is_file():
        return read_flags(folder / "cover.label", n_frames) == 0
    if (folder / "absence.label").is_file():
        return read_flags(folder / "absence.label", n_frames) == 1
    return None


def open_entry(root: Path, name: str, folder: Path):
    """The sequence ``name`` in ``folder``: its images, boxes, absent frames as NaN rows."""
    files = images_of(folder)
    return sequence_from_files(
        files, name, folder / "groundtruth.txt", source=folder, absent=absent_frames(folder, len(files))
    )
