"""Published OTB results: the benchmark's OPE score files and per-frame result files.

Formats read here
-----------------
* **Score JSON** (the Python port of the OTB toolkit, ``tracker_benchmark``):
  ``OPE/<TRACKER>/scores_<benchmark>/<SUBSET>.json`` with ``seqs``, ``overlapScores``
  (average overlap per sequence, over the frames with valid ground truth),
  ``successRateList`` (21 thresholds, mean = AUC) and ``precisionList`` (0..50 px, index 20 =
  precision score). ``load_published_scores``. These curves are averaged over *their*
  benchmark's full sequence set (51 for ``cvpr13``, 50 for ``tb50``, 100 for ``tb100``); they
  are shown beside ours, never mixed into a per-sequence table.
* **Per-frame result JSON** of that port: ``OPE/<TRACKER>/<Seq>.json``, a one-element list with
  ``res`` (boxes), ``resType``, ``tmplsize``, ``startFrame``, ``fps``. ``read_otb_json``.
* **OTB toolkit ``.mat`` files** ``<seq>_<tracker>.mat``: a struct ``results`` (inside a 1x1
  cell) with ``res``, ``type`` (``rect`` or ``ivtAff``), ``tmplsize``, ``startFrame``,
  ``annoBegin``, ``len``, ``fps``; or a plain numeric array (MDNet's ``result``).
  ``read_otb_mat`` / ``load_otb_mat``.
* **Text results** (got10k, pysot, pytracking; the ``RUN_DIR/results`` layout): one
  ``x,y,w,h`` box per line, 1-based, separated by commas, tabs or spaces.
  ``read_box_file``.

``ivtAff`` (IVT, ASLA) conversion is the toolkit's ``calcRectCenter``: with the template size
``(w, h) = tmplsize`` and the affine ``M = [p1 p3 p4; p2 p5 p6]``, the template corners
``(-w/2, -h/2)`` and ``(w/2, h/2)`` are mapped, floored, and the box is
``[floor(c1x), floor(c1y), floor(c3x) - floor(c1x), floor(c3y) - floor(c1y)]`` (flooring is
what reproduces the published per-sequence figures exactly).

Sequence names differ in case and separator between sources (``BasketBall``, ``basketball``,
``Skating2-1``, ``Skating2.1``, ``Human4-2`` / ``Human4``): ``canonical_name`` is the key used
for matching everywhere.
"""

from __future__ import annotations

import json
import math
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..data.attributes import ATTRIBUTE_NAMES, ATTRIBUTES, load_attributes
from ..data.files import read_regular_bytes
from ..data.names import canonical_name

__all__ = [
    "ATTRIBUTES",
    "ATTRIBUTE_NAMES",
    "BENCHMARKS",
    "canonical_name",
    "benchmark_label",
    "read_box_file",
    "write_box_file",
    "load_published_scores",
    "published_trackers",
    "ImportedResult",
    "read_otb_mat",
    "load_otb_mat",
    "read_otb_json",
    "ivt_affine_to_rect",
    "import_results",
    "load_attribute_table",
]

#: benchmark key -> (directory suffix, label)
BENCHMARKS = {
    "cvpr13": ("cvpr13", "OTB-2013"),
    "tb50": ("tb50", "TB-50"),
    "tb100": ("tb100", "OTB-100"),
}
_BENCHMARK_ALIASES = {
    "cvpr13": "cvpr13",
    "cvpr2013": "cvpr13",
    "otb2013": "cvpr13",
    "otb-2013": "cvpr13",
    "otb13": "cvpr13",
    "tb50": "tb50",
    "otb50": "tb50",
    "tb-50": "tb50",
    "tb100": "tb100",
    "otb100": "tb100",
    "otb-100": "tb100",
    "otb2015": "tb100",
    "otb-2015": "tb100",
}


def _benchmark_key(benchmark: str) -> str:
    key = _BENCHMARK_ALIASES.get(str(benchmark).strip().lower())
    if key is None:
        raise ValueError(f"unknown benchmark {benchmark!r}: expected one of cvpr13, tb50, tb100")
    return key


def benchmark_label(benchmark: str) -> str:
    """``"cvpr13"`` -> ``"OTB-2013"``, ``"tb50"`` -> ``"TB-50"``, ``"tb100"`` -> ``"OTB-100"``."""
    return BENCHMARKS[_benchmark_key(benchmark)][1]


# --------------------------------------------------------------------------- text boxes

_SPLIT = re.compile(r"[,;\s]+")


def read_box_file(path, ncols: int = 4) -> np.ndarray:
    """Read a text box file (one ``x,y,w,h`` row per line; comma, tab, space or ``;``).

    Blank lines are skipped. ``NaN`` is accepted. A malformed line raises ``ValueError`` naming
    the file and the 1-based line number; a path that is not a regular file (a FIFO) raises
    ``OSError`` at once.
    """
    path = Path(path)
    rows = []
    text = read_regular_bytes(path).decode("utf-8", errors="replace")
    for lineno, line in enumerate(text.replace("\r\n", "\n").replace("\r", "\n").split("\n"), 1):
        line = line.strip()
        if not line:
            continue
        parts = [p for p in _SPLIT.split(line) if p]
        if len(parts) != ncols:
            raise ValueError(f"{path}:{lineno}: expected {ncols} numbers (x,y,w,h), got {len(parts)}: {line[:60]!r}")
        try:
            rows.append([float(p) for p in parts])
        except ValueError:
            raise ValueError(f"{path}:{lineno}: not a number in {line[:60]!r}") from None
    return np.asarray(rows, dtype=np.float64).reshape(-1, ncols)


def write_box_file(path, boxes) -> None:
    """Write ``(n, 4)`` boxes as comma-separated lines (got10k layout), creating folders."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    boxes = np.asarray(boxes, dtype=np.float64).reshape(-1, 4)
    with open(path, "w", encoding="utf-8") as fh:
        for row in boxes:
            fh.write(",".join(_fmt(v) for v in row) + "\n")


def _fmt(v: float) -> str:
    if not np.isfinite(v):
        return "NaN"
    if float(v).is_integer():
        return str(int(v))
    return repr(float(v))


# --------------------------------------------------------------------------- score JSON


def _ope_dir(otb_results_dir) -> Path:
    root = Path(otb_results_dir)
    if (root / "OPE").is_dir():
        return root / "OPE"
    if root.name.upper() == "OPE" and root.is_dir():
        return root
    raise FileNotFoundError(f"{root}: no OPE/ folder of published scores (tracker_benchmark JSON layout)")


def published_trackers(otb_results_dir, benchmark: str = "tb100") -> list[str]:
    """Names of the trackers with a ``scores_<benchmark>`` folder, sorted."""
    ope = _ope_dir(otb_results_dir)
    sub = "scores_" + BENCHMARKS[_benchmark_key(benchmark)][0]
    return sorted((p.name for p in ope.iterdir() if (p / sub).is_dir()), key=str.lower)


def load_published_scores(
    otb_results_dir, benchmark: str = "tb100", subset: str = "ALL", trackers: Iterable[str] | None = None
) -> dict:
    """Published OPE scores of every tracker (or ``trackers``) on ``benchmark`` / ``subset``.

    Returns ``{tracker: {"success": (21,), "precision": (51,), "auc": float,
    "precision20": float, "sequences": {seq: avg_overlap}, "n_sequences": int,
    "benchmark": key, "label": "OTB-2013"|..., "subset": subset}}``. Trackers without that
    subset file are left out. ``otb_results_dir`` is the folder holding ``OPE/`` (or ``OPE``
    itself).
    """
    ope = _ope_dir(otb_results_dir)
    key = _benchmark_key(benchmark)
    sub, label = BENCHMARKS[key]
    wanted = None if trackers is None else {t.lower() for t in trackers}
    out: dict = {}
    for name in published_trackers(ope, key):
        if wanted is not None and name.lower() not in wanted:
            continue
        path = ope / name / f"scores_{sub}" / f"{subset}.json"
        if not path.is_file():
            continue
        try:
            with open(path, encoding="utf-8") as fh:
                data = json.load(fh)
            success = np.asarray(data["successRateList"], dtype=np.float64)
            precision = np.asarray(data["precisionList"], dtype=np.float64)
            seqs = list(data.get("seqs", []))
            overlaps = list(data.get("overlapScores", []))
        except (OSError, ValueError, KeyError, TypeError) as exc:
            raise ValueError(f"{path}: not a tracker_benchmark score file ({exc})") from None
        if success.shape != (21,) or precision.shape != (51,):
            raise ValueError(
                f"{path}: expected 21 success and 51 precision values, got {success.shape} and {precision.shape}"
            )
        out[name] = {
            "success": success,
            "precision": precision,
            "auc": float(success.mean()),
            "precision20": float(precision[20]),
            "sequences": {s: float(o) for s, o in zip(seqs, overlaps)},
            "n_sequences": len(seqs),
            "benchmark": key,
            "label": label,
            "subset": subset,
        }
    return out


# --------------------------------------------------------------------------- per-frame results


@dataclass
class ImportedResult:
    """Per-frame boxes of one tracker on one sequence, read from a published/foreign file."""

    tracker: str
    sequence: str  #: the name as the source spells it
    boxes: np.ndarray  #: (n, 4) x, y, w, h, 1-based, float64
    source: str  #: file it came from
    format: str  #: "otb-mat", "otb-json" or "text"
    result_type: str = "rect"  #: the source's type before conversion ("rect", "ivtAff")
    start_frame: int | None = None  #: first frame tracked (1-based, source's numbering)
    anno_begin: int | None = None  #: frame number of the annotation file's first row
    fps: float | None = None
    times: np.ndarray | None = field(default=None, repr=False)  #: per-frame seconds, if known

    @property
    def anno_offset(self) -> int:
        """Row of the annotation file that the first box belongs to (0 when unknown).

        The toolkit scores frame ``i`` of the result against annotation row
        ``startFrame - annoBegin + i`` (e.g. Tiger1: start 6, annoBegin 1 -> offset 5)."""
        if self.start_frame is None:
            return 0
        begin = 1 if self.anno_begin is None else self.anno_begin
        return max(0, int(self.start_frame) - int(begin))


def ivt_affine_to_rect(params, tmplsize) -> np.ndarray:
    """Convert IVT affine rows (``affparam2mat`` output ``[tx ty a11 a12 a21 a22]``) to boxes,
    exactly as the OTB toolkit's ``calcRectCenter`` (corners 1 and 3 of the template, floored).
    """
    p = np.asarray(params, dtype=np.float64).reshape(-1, 6)
    w, h = (float(v) for v in np.asarray(tmplsize, dtype=np.float64).ravel()[:2])

    # M = [p1 p3 p4; p2 p5 p6] applied to (1, u, v)
    def corner(u, v):
        return p[:, 0] + p[:, 2] * u + p[:, 3] * v, p[:, 1] + p[:, 4] * u + p[:, 5] * v

    x1, y1 = corner(-w / 2, -h / 2)
    x3, y3 = corner(w / 2, h / 2)
    x1, y1, x3, y3 = np.floor(x1), np.floor(y1), np.floor(x3), np.floor(y3)
    return np.stack([x1, y1, x3 - x1, y3 - y1], axis=1)


def _unwrap(x):
    while isinstance(x, np.ndarray) and x.dtype == object and x.size >= 1:
        x = x.ravel()[0]
    return x


def _scalar(x, cast=float):
    x = _unwrap(x)
    arr = np.asarray(x).ravel()
    if arr.size == 0:
        return None
    try:
        return cast(arr[0])
    except (TypeError, ValueError):
        return None


def _split_mat_name(path: Path) -> tuple[str, str]:
    stem = path.stem
    if "_" not in stem:
        return stem, ""
    seq, tracker = stem.split("_", 1)
    return seq, tracker


def read_otb_mat(path, tracker: str | None = None, sequence: str | None = None) -> ImportedResult:
    """Read an OTB toolkit result file ``<seq>_<tracker>.mat`` (types ``rect`` and ``ivtAff``,
    or a plain numeric box array such as MDNet's ``result``). Boxes come back 1-based."""
    from scipy.io import loadmat

    path = Path(path)
    seq_guess, trk_guess = _split_mat_name(path)
    tracker = tracker or trk_guess or path.stem
    sequence = sequence or seq_guess
    try:
        mat = loadmat(str(path))
    except Exception as exc:  # noqa: BLE001 - scipy raises several types for corrupt files
        raise ValueError(f"{path}: cannot read MATLAB file ({exc})") from None
    keys = [k for k in mat if not k.startswith("__")]
    common: dict[str, Any] = dict(tracker=tracker, sequence=sequence, source=str(path), format="otb-mat")
    if "results" in mat:
        rec = mat["results"]
        # a cell array (1 x runs; OPE has one run) of 1x1 structs
        while rec.dtype.names is None:
            if rec.dtype != object or rec.size == 0:
                raise ValueError(f"{path}: 'results' is neither a struct nor a cell of structs")
            rec = rec.ravel()[0]
        rec = rec.ravel()[0]
        fields = {n: rec[n] for n in rec.dtype.names}
        if "res" not in fields:
            raise ValueError(f"{path}: results struct has no 'res' field")
        rtype = (
            str(np.asarray(_unwrap(fields.get("type", np.array(["rect"])))).ravel()[0]) if "type" in fields else "rect"
        )
        tmpl = _unwrap(fields.get("tmplsize"))
        return ImportedResult(
            boxes=_result_boxes(_unwrap(fields["res"]), rtype, tmpl, path),
            result_type=rtype,
            start_frame=_scalar(fields.get("startFrame"), int) if "startFrame" in fields else None,
            anno_begin=_scalar(fields.get("annoBegin"), int) if "annoBegin" in fields else None,
            fps=_fps(_scalar(fields["fps"], lambda v: v), path) if "fps" in fields else None,
            **common,
        )
    numeric = [
        k
        for k in keys
        if isinstance(mat[k], np.ndarray) and mat[k].dtype != object and mat[k].ndim == 2 and mat[k].shape[1] == 4
    ]
    if len(numeric) == 1:
        return ImportedResult(boxes=np.asarray(mat[numeric[0]], dtype=np.float64), **common)
    raise ValueError(f"{path}: no 'results' struct and no single (n, 4) array (variables: {', '.join(keys) or 'none'})")


def _result_boxes(res, rtype, tmplsize, path) -> np.ndarray:
    """1-based ``(n, 4)`` boxes of a result's ``res`` of type ``rtype`` (``rect`` rows, or
    ``ivtAff`` affine rows with the template size ``tmplsize``). NaN (no box) is kept;
    anything else that is not a finite number is a ValueError naming ``path``."""
    try:
        arr = np.asarray(res, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{path}: 'res' is not an array of numbers ({exc})") from None
    if rtype not in ("rect", "ivtAff"):
        raise ValueError(f"{path}: unsupported result type {rtype!r} (supported: rect, ivtAff)")
    per_row = 4 if rtype == "rect" else 6
    if arr.size % per_row:
        raise ValueError(f"{path}: 'res' holds {arr.size} numbers, not rows of {per_row} ({rtype})")
    if rtype == "rect":
        boxes = arr.reshape(-1, 4)
    else:
        try:
            tmpl = np.asarray(tmplsize, dtype=np.float64).ravel()
        except (TypeError, ValueError):
            tmpl = np.zeros(0)
        if tmpl.size < 2 or not np.isfinite(tmpl[:2]).all():
            raise ValueError(f"{path}: ivtAff result without a valid tmplsize (got {tmplsize!r})")
        boxes = ivt_affine_to_rect(arr, tmpl)
    bad = np.isinf(boxes).any(axis=1)
    if bad.any():
        i = int(np.argmax(bad))
        raise ValueError(f"{path}: 'res' row {i + 1} is not finite: {boxes[i].tolist()}")
    return boxes


def _fps(value, path) -> float | None:
    """A result's frames per second: None when absent, else a finite number >= 0
    (ValueError naming ``path`` otherwise)."""
    if value is None:
        return None
    try:
        fps = float(value) if not isinstance(value, (bool, np.bool_)) else math.nan
    except (TypeError, ValueError):
        fps = math.nan
    if not (math.isfinite(fps) and fps >= 0):
        raise ValueError(f"{path}: 'fps' must be a number of frames per second >= 0, got {_plain(value)!r}")
    return fps


def _frame_number(value, key: str, path) -> int | None:
    """A 1-based frame number (``startFrame``): None when absent; ValueError naming ``path``
    unless a whole number >= 1."""
    if value is None:
        return None
    try:
        number = float(value) if not isinstance(value, (bool, np.bool_)) else math.nan
    except (TypeError, ValueError):
        number = math.nan
    if not (math.isfinite(number) and number.is_integer() and number >= 1):
        raise ValueError(f"{path}: {key!r} must be a frame number >= 1, got {_plain(value)!r}")
    return int(number)


def _plain(value):
    """``value`` as Python shows it (a numpy scalar read from a ``.mat`` file made plain)."""
    return value.item() if isinstance(value, np.generic) else value


def load_otb_mat(path) -> np.ndarray:
    """Boxes ``(m, 4)`` (1-based ``x, y, w, h``) of an OTB toolkit ``.mat`` result file."""
    return read_otb_mat(path).boxes


def read_otb_json(path, tracker: str | None = None) -> ImportedResult:
    """Read a tracker_benchmark per-frame result JSON (``OPE/<TRACKER>/<Seq>.json``)."""
    path = Path(path)
    try:
        data = json.loads(read_regular_bytes(path).decode("utf-8"))
    except (OSError, ValueError) as exc:  # a FIFO is refused, not waited on
        raise ValueError(f"{path}: not a JSON result file ({exc})") from None
    rec = data[0] if isinstance(data, list) and data else data
    if not isinstance(rec, dict) or "res" not in rec:
        raise ValueError(f"{path}: no 'res' in this JSON (not a tracker_benchmark result file)")
    for key in ("seqName", "tracker", "resType"):
        if rec.get(key) is not None and not isinstance(rec[key], str):
            raise ValueError(f"{path}: {key!r} must be a text, got {rec[key]!r}")
    rtype = rec.get("resType") or "rect"
    return ImportedResult(
        tracker=tracker or rec.get("tracker") or path.parent.name,
        sequence=rec.get("seqName") or path.stem,
        boxes=_result_boxes(rec["res"], rtype, rec.get("tmplsize", [32, 32]), path),
        source=str(path),
        format="otb-json",
        result_type=rtype,
        start_frame=_frame_number(rec.get("startFrame"), "startFrame", path),
        anno_begin=None,  # unknown in this format; resolved against the annotation length
        fps=_fps(rec.get("fps"), path),
    )


def _read_text_result(path: Path, tracker: str) -> ImportedResult:
    boxes = read_box_file(path)
    times = None
    tfile = path.parent / "times" / f"{path.stem}_time.txt"
    if tfile.is_file():
        try:
            times = np.loadtxt(tfile, ndmin=1, dtype=np.float64)
        except ValueError:
            times = None
    return ImportedResult(
        tracker=tracker, sequence=path.stem, boxes=boxes, source=str(path), format="text", times=times
    )


def _detect_format(path: Path) -> str:
    if path.is_file():
        if path.suffix.lower() == ".mat":
            return "otb-mat"
        if path.suffix.lower() == ".json":
            return "otb-json"
        return "text"
    if not path.is_dir():
        raise FileNotFoundError(f"{path}: no such file or folder")
    if any(path.glob("*.mat")):
        return "otb-mat"
    if any(path.glob("*.txt")):
        return "text"
    if any(p.suffix == ".json" and not p.name.startswith("scores") for p in path.glob("*.json")):
        return "otb-json"
    for sub in sorted(p for p in path.iterdir() if p.is_dir()):
        if any(sub.glob("*.mat")):
            return "otb-mat"
        if any(sub.glob("*.txt")):
            return "text"
        if any(sub.glob("*.json")):
            return "otb-json"
    raise ValueError(f"{path}: found no .mat, .json or .txt result files")


def import_results(
    path,
    fmt: str = "auto",
    tracker_name: str | None = None,
    trackers: Iterable[str] | None = None,
    sequences: Iterable[str] | None = None,
) -> dict[str, dict[str, ImportedResult]]:
    """Read foreign per-frame results into ``{tracker: {sequence: ImportedResult}}``.

    ``path`` may be:

    * ``fmt="otb-mat"``: one ``<seq>_<tracker>.mat`` file or a folder of them (the toolkit's
      ``results_OPE``); the tracker name comes from the file name.
    * ``fmt="otb-json"``: one per-frame JSON or a folder ``<TRACKER>/`` of ``<Seq>.json``
      (``scores_*`` folders are ignored).
    * ``fmt="got10k"`` / ``"pysot"`` / ``"text"``: a tracker folder of ``<seq>.txt`` (times
      in ``times/<seq>_time.txt`` when present), or a root holding several tracker folders.

    ``fmt="auto"`` picks by the files found. ``tracker_name`` renames the (single) tracker;
    ``trackers`` / ``sequences`` filter case-insensitively. Unreadable files raise
    ``ValueError`` naming the file (and line, for text).
    """
    path = Path(path)
    fmt = _import_format(path, fmt)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such file or folder")
    want_trk = None if trackers is None else {t.lower() for t in trackers}
    want_seq = None if sequences is None else {canonical_name(s) for s in sequences}
    items = _read_imports(path, fmt, want_trk, want_seq)

    out: dict[str, dict[str, ImportedResult]] = {}
    for item in items:
        out.setdefault(item.tracker, {})[item.sequence] = item
    if tracker_name is not None:
        if len(out) > 1:
            raise ValueError(
                f"{path}: holds {len(out)} trackers ({', '.join(sorted(out))}); "
                "pick one with trackers=[...] before renaming it"
            )
        only = next(iter(out.values()), {})
        out = {tracker_name: {s: _renamed(r, tracker_name) for s, r in only.items()}} if out else {}
    return out


def _import_format(path: Path, fmt: str) -> str:
    """``"otb-mat"``, ``"otb-json"`` or ``"text"``: ``fmt`` or one of its other names
    (``got10k``, ``pysot``, ``mat``, ``json``, ...), or what the files at ``path`` are for
    ``"auto"``; ValueError for another name."""
    fmt = fmt.lower()
    if fmt in ("got10k", "pysot", "pytracking", "txt"):
        fmt = "text"
    if fmt in ("mat", "otb"):
        fmt = "otb-mat"
    if fmt == "json":
        fmt = "otb-json"
    if fmt == "auto":
        fmt = _detect_format(path)
    if fmt not in ("otb-mat", "otb-json", "text"):
        raise ValueError(f"unknown import format {fmt!r}: expected auto, otb-mat, otb-json, got10k, pysot")
    return fmt


def _read_imports(path: Path, fmt: str, want_trk: set | None, want_seq: set | None) -> list[ImportedResult]:
    """Every result of format ``fmt`` at ``path`` whose tracker (lower case) is in ``want_trk``
    and sequence (:func:`canonical_name`) in ``want_seq`` (None: all)."""
    items: list[ImportedResult] = []
    if fmt == "otb-mat":
        files = [path] if path.is_file() else sorted(path.rglob("*.mat"))
        for f in files:
            seq, trk = _split_mat_name(f)
            if want_trk is not None and trk.lower() not in want_trk:
                continue
            if want_seq is not None and canonical_name(seq) not in want_seq:
                continue
            items.append(read_otb_mat(f))
    elif fmt == "otb-json":
        files = (
            [path]
            if path.is_file()
            else sorted(f for f in path.rglob("*.json") if not any(part.startswith("scores_") for part in f.parts))
        )
        for f in files:
            trk = f.parent.name
            if want_trk is not None and trk.lower() not in want_trk:
                continue
            if want_seq is not None and canonical_name(f.stem) not in want_seq:
                continue
            items.append(read_otb_json(f, tracker=trk))
    else:
        if path.is_file():
            groups = {path.parent.name: [path]}
        elif any(path.glob("*.txt")):
            groups = {path.name: sorted(path.glob("*.txt"))}
        else:
            groups = {d.name: sorted(d.glob("*.txt")) for d in sorted(path.iterdir()) if d.is_dir()}
        for trk, files in groups.items():
            if want_trk is not None and trk.lower() not in want_trk:
                continue
            for f in files:
                if want_seq is not None and canonical_name(f.stem) not in want_seq:
                    continue
                items.append(_read_text_result(f, trk))

    return items


def _renamed(r: ImportedResult, name: str) -> ImportedResult:
    r.tracker = name
    return r


# --------------------------------------------------------------------------- attributes


def load_attribute_table(source) -> dict[str, set[str]]:
    """Sequence attributes as ``{canonical_name: {"IV", ...}}``.

    ``source`` may be: a text file of ``<Seq>\\t<ATTR>, <ATTR>...`` lines (``attributes-tb100
    .txt``); a folder of ``<Seq>.txt`` files holding the toolkit's 11 0/1 flags (``anno/att``,
    flag order IV, OPR, SV, OCC, DEF, MB, FM, IPR, OV, BC, LR); the otb-results folder (its
    ``attributes-tb100.txt`` is preferred, else ``anno/att``); a JSON file ``{seq: [attrs]}``;
    or a mapping. Files and folders are read by :func:`smtmvt.data.load_attributes` (errors:
    :class:`~smtmvt.data.SequenceError`, a ``ValueError``); a missing path raises
    ``FileNotFoundError``.

    The two tables of the shared otb-results folder disagree on 7 sequences (Box, Car1, Car2,
    Coke, Crossing, Human4, Jump; e.g. Crossing's flags lack FM and OPR). The text table matches
    the benchmark's own per-attribute score files better (FM and MB: exactly), hence the
    preference.
    """
    if isinstance(source, Mapping):
        return _attribute_mapping(source, "attribute table")
    path = Path(source)
    if not path.exists():
        raise FileNotFoundError(f"{path}: no such attribute file or folder")
    if not path.is_dir() and path.suffix.lower() == ".json":
        try:
            data = json.loads(read_regular_bytes(path).decode("utf-8-sig"))
        except (OSError, ValueError) as exc:  # a FIFO is refused, not waited on
            raise ValueError(f"{path}: not a JSON attribute table ({exc})") from None
        return _attribute_mapping(data, str(path))
    return {canonical_name(name): set(codes) for name, codes in load_attributes(path).items()}


def _attribute_mapping(data, where: str) -> dict[str, set[str]]:
    """``{canonical name: {codes}}`` of a mapping ``{sequence: [codes]}``; ValueError naming
    ``where`` for anything else (a code list that is not a list of texts)."""
    if not isinstance(data, Mapping):
        raise ValueError(f"{where}: expected an object {{sequence: [attribute codes]}}, got {type(data).__name__}")
    for name, codes in data.items():
        if not isinstance(name, str) or isinstance(codes, str) or not isinstance(codes, (list, tuple, set, frozenset)):
            raise ValueError(f"{where}: sequence {name!r}: expected a list of attribute codes, got {codes!r}")
        if not all(isinstance(c, str) for c in codes):
            raise ValueError(f"{where}: sequence {name!r}: attribute codes must be texts, got {codes!r}")
    return {canonical_name(k): {a.strip().upper() for a in v} for k, v in data.items()}
