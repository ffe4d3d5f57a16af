"""Helpers shared by the dataset layouts: flag files, absent frames, image runs."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np

from ..boxes import read_boxes
from ..errors import SequenceError
from ..files import read_regular_bytes
from ..frames import list_images
from ..sequence import ImageSequence, align_groundtruth

__all__ = ["read_flags", "sequence_from_files", "images_of", "visible_folders", "groundtruth_entries"]

_FLAG_SEPARATOR = re.compile(r"\s*,\s*|\s+")


def visible_folders(root: Path) -> list:
    """The sub-folders of ``root`` whose names do not start with a dot."""
    return [p for p in root.iterdir() if p.is_dir() and not p.name.startswith(".")]


def groundtruth_entries(root: Path) -> list:
    """``[(name, folder, None), ...]``: the visible sub-folders holding ``groundtruth.txt``
    (the ``entries`` of the layouts with one folder per sequence)."""
    return [(p.name, p, None) for p in visible_folders(root) if (p / "groundtruth.txt").is_file()]


def read_flags(path, n_frames: int) -> np.ndarray:
    """Per-frame integer labels of ``path``: one per line (GOT-10k ``*.label``) or comma
    separated on one line (LaSOT ``full_occlusion.txt``).

    Returns ``(n_frames,) int64``. SequenceError naming the file (and line) for a missing
    file, a field that is not a whole number, or a count other than ``n_frames``.
    """
    path = Path(path)
    try:
        text = read_regular_bytes(path).decode("utf-8-sig")
    except (OSError, UnicodeDecodeError) as exc:
        raise SequenceError(f"cannot read label file {path}: {exc}", path=path) from None
    values: list[int] = []
    for i, line in enumerate(text.splitlines()):
        for field in (f for f in _FLAG_SEPARATOR.split(line.strip()) if f):
            try:
                values.append(int(field))
            except ValueError:
                raise SequenceError(f"{path}, line {i + 1}: not a number: {field!r}", path=path, line=i + 1) from None
    if len(values) != n_frames:
        raise SequenceError(f"{path}: {len(values)} labels for {n_frames} frames", path=path)
    return np.asarray(values, dtype=np.int64)


def images_of(folder: Path) -> list:
    """The image files of ``folder`` in natural order; SequenceError when there is none."""
    files = list_images(folder)
    if not files:
        raise SequenceError(f"no image files in {folder}", path=folder)
    return files


def sequence_from_files(files, name: str, gt_file: Path, *, source: Path, absent=None, boxes=None) -> ImageSequence:
    """An :class:`ImageSequence` of ``files`` with the 1-based boxes of ``gt_file``.

    ``boxes``: the file's boxes already read (1-based, ``(m, 4)``), else read with
    :func:`~smtmvt.data.boxes.read_boxes`. ``absent``: ``(len(files),) bool``, frames where
    the layout's labels say the target is not in view; their rows become NaN (not
    annotated), so that scoring applies the layout's rule to them.
    """
    gt = read_boxes(gt_file) if boxes is None else np.asarray(boxes, dtype=np.float64) - [1.0, 1.0, 0.0, 0.0]
    gt = np.array(align_groundtruth(gt, len(files), groundtruth_file=gt_file, sequence=name, source=source))
    if absent is not None:
        gt[np.asarray(absent, dtype=bool)] = np.nan
    return ImageSequence(files, name, gt, source=source, groundtruth_file=gt_file)
