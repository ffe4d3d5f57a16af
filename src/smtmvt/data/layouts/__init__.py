"""Benchmark folder layouts, detected from the folder: OTB (the default), GOT-10k, LaSOT,
UAV123 and VOT short-term.

:func:`detect_layout` looks, in this order, for: UAV123's ``anno/UAV123`` + ``data_seq/UAV123``;
a sub-folder with ``img/`` or ``groundtruth_rect*.txt`` (OTB); a ``<class>/<class>-<n>/img``
(LaSOT); a sub-folder with ``groundtruth.txt`` and ``absence.label``, ``cover.label`` or
``meta_info.ini`` (GOT-10k); a sub-folder with ``groundtruth.txt`` and ``color/`` or images
(VOT). Anything else is read as OTB (whose reader says what is missing).

Each layout module has ``NAME``, ``ABSENT_RULE`` (how scoring treats frames without a box:
one of :data:`smtmvt.evaluation.metrics.INVALID_MODES`, with its source in the module's
docstring), ``matches(root)``, ``entries(root) -> [(name, folder, None)]`` and
``open_entry(root, name, folder) -> Sequence``. Boxes are 1-based in every layout's files
and 0-based in the sequences, as everywhere in :mod:`smtmvt.data`.
"""

from __future__ import annotations

from pathlib import Path

from ..otb import groundtruth_targets, is_otb_folder
from . import got10k, lasot, uav123, vot

__all__ = ["LAYOUTS", "OTB", "ABSENT_RULES", "detect_layout", "layout_module"]

OTB = "otb"
#: Layout name -> its module (OTB is read by :mod:`smtmvt.data.dataset` itself).
LAYOUTS = {m.NAME: m for m in (got10k, lasot, uav123, vot)}
#: Layout name -> scoring rule of frames without a box (``invalid=`` of the metrics).
ABSENT_RULES = {OTB: "otb", **{name: m.ABSENT_RULE for name, m in LAYOUTS.items()}}


def _has_otb_sequence(root: Path) -> bool:
    """A sub-folder with ``img/`` or a ``groundtruth_rect*.txt``."""
    for p in root.iterdir():
        if not p.is_dir() or p.name.startswith("."):
            continue
        if is_otb_folder(p) or any(
            f.name.lower().startswith("groundtruth_rect") for f in groundtruth_targets(p).values()
        ):
            return True
    return False


def detect_layout(root) -> str:
    """The layout name of the benchmark folder ``root``: ``"otb"``, ``"uav123"``, ``"lasot"``,
    ``"got10k"`` or ``"vot"`` (see the module docstring for the order of the tests)."""
    root = Path(root)
    if not root.is_dir():
        return OTB
    if uav123.matches(root):
        return uav123.NAME
    if _has_otb_sequence(root):
        return OTB
    for module in (lasot, got10k, vot):
        if module.matches(root):
            return module.NAME
    return OTB


def layout_module(name: str):
    """The module of layout ``name`` (None for OTB)."""
    return LAYOUTS.get(name)
