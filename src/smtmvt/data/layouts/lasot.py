"""LaSOT layout: ``<root>/<class>/<class>-<n>/img/00000001.jpg ...`` with ``groundtruth.txt``,
``full_occlusion.txt`` and ``out_of_view.txt`` (one comma-separated line of 0/1 per frame)
beside ``img/``.

Absent frames
-------------
pytracking (``pytracking/analysis/extract_results.py``, ``calc_seq_err_robust`` with
``dataset == 'lasot'``; ``target_visible = ~(full_occlusion | out_of_view)`` in its LaSOT
dataset) marks a frame whose target is not visible as invalid: overlap -1 (a failure at
every success threshold) and centre error +inf (a failure at every precision threshold),
and divides by **all** frames of the sequence. That is the ``"fail"`` rule of
:mod:`smtmvt.evaluation.metrics`; a frame flagged in either file has no box (NaN row).
(got10k 0.1.3 has no LaSOT experiment; its ``LaSOT`` dataset only returns the flags.)

Boxes in ``groundtruth.txt`` are 1-based ``x,y,w,h`` (as OTB's). Sequences are named by
their folder, ``<class>-<n>``.
"""

from __future__ import annotations

import re
from pathlib import Path

from .common import images_of, read_flags, sequence_from_files

__all__ = ["NAME", "ABSENT_RULE", "matches", "entries", "open_entry"]

NAME = "lasot"
ABSENT_RULE = "fail"
FLAG_FILES = ("full_occlusion.txt", "out_of_view.txt")


def _sequence_folders(root: Path):
    for cls in root.iterdir():
        if not cls.is_dir() or cls.name.startswith("."):
            continue
        pattern = re.compile(re.escape(cls.name) + r"-\d+")
        for seq in cls.iterdir():
            if seq.is_dir() and pattern.fullmatch(seq.name) and (seq / "img").is_dir():
                yield seq


def matches(root: Path) -> bool:
    """True when ``root`` has a ``<class>/<class>-<n>/img`` folder."""
    return next(_sequence_folders(root), None) is not None


def entries(root: Path) -> list:
    """``[(name, folder, None), ...]`` for every ``<class>/<class>-<n>`` with ``img/``."""
    return [(seq.name, seq, None) for seq in _sequence_folders(root)]


def open_entry(root: Path, name: str, folder: Path):
    """The sequence ``name`` in ``folder``: ``img/*``, its boxes, flagged frames as NaN rows."""
    files = images_of(folder / "img")
    absent = None
    for flag in FLAG_FILES:
        if (folder / flag).is_file():
            hit = read_flags(folder / flag, len(files)) != 0
            absent = hit if absent is None else absent | hit
    return sequence_from_files(files, name, folder / "groundtruth.txt", source=folder, absent=absent)
