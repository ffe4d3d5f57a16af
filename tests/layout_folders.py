"""The same frames of a real OTB sequence written in each benchmark layout (OTB, GOT-10k,
LaSOT, UAV123, VOT), shared by the layout tests.

Frames are the OTB JPEG files copied byte for byte; every layout's ground truth holds the
same 1-based ``x,y,w,h`` numbers (VOT's as the rectangle's four corners), and frames in
``absent`` are marked as each layout marks an absent target.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np

from smtmvt.data import read_boxes


def _fmt(row) -> str:
    return ",".join(np.format_float_positional(v, trim="-") for v in row)


def _copy_frames(files, folder: Path, digits: int) -> None:
    folder.mkdir(parents=True)
    for k, f in enumerate(files, start=1):
        shutil.copyfile(f, folder / f"{k:0{digits}d}.jpg")


def write_otb(root: Path, name: str, files, boxes) -> Path:
    _copy_frames(files, root / name / "img", 4)
    (root / name / "groundtruth_rect.txt").write_text("".join(_fmt(b) + "\n" for b in boxes))
    return root


def write_got10k(root: Path, name: str, files, boxes, absent=()) -> Path:
    seq = root / name
    _copy_frames(files, seq, 8)
    (seq / "groundtruth.txt").write_text("".join(_fmt(b) + "\n" for b in boxes))
    flags = [int(i in absent) for i in range(len(files))]
    (seq / "absence.label").write_text("".join(f"{a}\n" for a in flags))
    (seq / "cover.label").write_text("".join(f"{0 if a else 8}\n" for a in flags))
    (seq / "meta_info.ini").write_text("[METAINFO]\nobject_class: person\n")
    (root / "list.txt").write_text(name + "\n")
    return root


def write_lasot(root: Path, name: str, files, boxes, occluded=(), out_of_view=()) -> Path:
    seq = root / name / f"{name}-1"
    _copy_frames(files, seq / "img", 8)
    rows = [(0, 0, 0, 0) if i in occluded or i in out_of_view else b for i, b in enumerate(boxes)]
    (seq / "groundtruth.txt").write_text("".join(_fmt(b) + "\n" for b in rows))
    for fname, marked in (("full_occlusion.txt", occluded), ("out_of_view.txt", out_of_view)):
        (seq / fname).write_text(",".join(str(int(i in marked)) for i in range(len(files))) + "\n")
    return root


def write_uav123(root: Path, name: str, files, boxes, absent=(), first: int = 1) -> Path:
    """Frames numbered from ``first`` (``%06d.jpg``); NaN lines for the absent frames."""
    folder = root / "data_seq" / "UAV123" / name
    folder.mkdir(parents=True)
    for k, f in enumerate(files, start=first):
        shutil.copyfile(f, folder / f"{k:06d}.jpg")
    (root / "anno" / "UAV123").mkdir(parents=True)
    rows = ["NaN,NaN,NaN,NaN" if i in absent else _fmt(b) for i, b in enumerate(boxes)]
    (root / "anno" / "UAV123" / f"{name}.txt").write_text("".join(r + "\n" for r in rows))
    return root


def write_vot(root: Path, name: str, files, boxes, absent=(), color: bool = True) -> Path:
    """Polygon lines (the rectangle's corners, clockwise from the top left) in ``color/``, or
    rectangle lines beside the frames when ``color`` is False; NaN lines for ``absent``."""
    seq = root / name
    _copy_frames(files, seq / "color" if color else seq, 8)
    lines = []
    for i, (x, y, w, h) in enumerate(boxes):
        if i in absent:
            lines.append(",".join(["NaN"] * (8 if color else 4)))
        elif color:
            lines.append(_fmt([x, y, x + w, y, x + w, y + h, x, y + h]))
        else:
            lines.append(_fmt([x, y, w, h]))
    (seq / "groundtruth.txt").write_text("".join(line + "\n" for line in lines))
    (root / "list.txt").write_text(name + "\n")
    return root


def cut(otb_sequence: Path, n: int):
    """The first ``n`` frame files of an OTB sequence folder and their 1-based boxes."""
    files = sorted((otb_sequence / "img").glob("*.jpg"))[:n]
    return files, read_boxes(otb_sequence / "groundtruth_rect.txt", one_based=True)[:n]


def write_all(base: Path, otb_sequence: Path, n: int = 40, absent=()) -> dict:
    """``{layout: dataset folder}``: the first ``n`` frames in each layout under ``base``."""
    files, boxes = cut(otb_sequence, n)
    name = otb_sequence.name
    absent = set(absent)
    half = sorted(absent)[: len(absent) // 2]
    return {
        "otb": write_otb(base / "otb", name, files, boxes),
        "got10k": write_got10k(base / "got10k", name, files, boxes, absent),
        "lasot": write_lasot(base / "lasot", name.lower(), files, boxes, set(half), absent - set(half)),
        "uav123": write_uav123(base / "uav123", name.lower(), files, boxes, absent),
        "vot": write_vot(base / "vot", name.lower(), files, boxes, absent),
    }
