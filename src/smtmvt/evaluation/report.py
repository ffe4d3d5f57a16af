"""Build the evaluation report of a run folder from stored results (nothing is re-run).

``build_report(RUN_DIR)`` reads ``RUN_DIR/results/<tracker>/<seq>.txt`` (1-based ``x,y,w,h``),
``times/<seq>_time.txt``, ``run.json`` and ``errors.json``, scores every (tracker, sequence)
pair with :mod:`.metrics` against the dataset's ground truth and writes ``RUN_DIR/report/``:

* ``summary.json``: every number (schema in ``build_report``);
* ``table.md`` / ``table.csv``: average overlap per sequence (rows) and tracker (columns),
  best of each row in bold, like the paper's table, plus average / AUC / precision / FPS rows;
* ``success.{png,svg}`` / ``precision.{png,svg}``: OTB success and precision plots (top
  trackers, legend sorted by score), and ``success_<ATTR>`` / ``precision_<ATTR>`` for each of
  the 11 attributes that at least one scored sequence has;
* ``index.html`` showing all of it, with the errors.

Published scores (the benchmark's JSON, averaged over *its* sequence set) are drawn beside
ours, labelled with their benchmark, and never enter the per-sequence table. Per-frame
published results imported into the run (``published.import_into_run``) are ordinary
trackers here: scored by our metrics on our sequences.

A result file that cannot be used (missing, malformed line, shorter or longer than its
sequence) becomes an error entry naming the file and the line counts; that pair is marked in
the table and the report goes on with the rest.
"""

from __future__ import annotations

import csv
import html
import io
import json
import os
import warnings
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .metrics import SequenceScore, _check_mode, aggregate, score_sequence
from .plots import Curve, plot_curves, select_curves
from .published import (
    ATTRIBUTE_NAMES,
    ATTRIBUTES,
    benchmark_label,
    canonical_name,
    load_attribute_table,
    load_published_scores,
    read_box_file,
)

__all__ = ["build_report", "load_groundtruth_source", "REPORT_DIR"]

REPORT_DIR = "report"


# --------------------------------------------------------------------------- ground truth


class _GroundTruth:
    """Ground truth (1-based, as in the files) of a dataset folder, looked up by any spelling.

    OTB folders (``<Seq>/img`` + ``groundtruth_rect*.txt``) are opened with
    :mod:`smtmvt.data` (which knows the OTB quirks: David's frame range, numbered targets);
    anything else (an ``anno/`` folder of ``<Seq>.txt``, folders without images) is read
    directly.
    """

    def __init__(self, root):
        self.root = Path(root)
        if not self.root.exists():
            raise FileNotFoundError(f"dataset not found: {self.root}")
        self._boxes: dict[str, np.ndarray] = {}
        self._names: dict[str, str] = {}
        self._errors: dict[str, str] = {}
        self._files: dict[str, Path] = {}
        self._data_layer = False
        self._scan()

    def _scan(self) -> None:
        try:
            from smtmvt.data import SequenceError, open_dataset
        except ImportError:  # pragma: no cover - the data layer is part of the package
            open_dataset = None
        if open_dataset is not None:
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    items = open_dataset(self.root, on_error="collect")
            except Exception:  # noqa: BLE001 - not an OTB folder of folders; read it ourselves
                items = []
            for item in items:
                if isinstance(item, SequenceError):
                    name = item.sequence or "?"
                    self._names.setdefault(canonical_name(name), name)
                    self._errors[canonical_name(name)] = str(item)
                    continue
                key = canonical_name(item.name)
                gt = item.groundtruth
                if gt is None:
                    self._errors[key] = f"sequence {item.name}: no ground truth"
                    continue
                self._names.setdefault(key, item.name)
                self._boxes[key] = np.asarray(gt, dtype=np.float64) + np.array([1.0, 1.0, 0.0, 0.0])
                self._data_layer = True
        # plain files: anno/<Seq>.txt, or sequence folders the data layer did not take
        for p in sorted(self.root.iterdir()) if self.root.is_dir() else []:
            if p.is_file() and p.suffix.lower() == ".txt":
                self._files.setdefault(canonical_name(p.stem), p)
                self._names.setdefault(canonical_name(p.stem), p.stem)
            elif p.is_dir():
                plain = p / "groundtruth_rect.txt"
                numbered = sorted(p.glob("groundtruth_rect.*.txt"))
                if plain.is_file():
                    self._files.setdefault(canonical_name(p.name), plain)
                    self._names.setdefault(canonical_name(p.name), p.name)
                for f in numbered:
                    k = f.name.split(".")[1]
                    if k.isdigit():
                        name = f"{p.name}-{k}"
                        self._files.setdefault(canonical_name(name), f)
                        self._names.setdefault(canonical_name(name), name)

    def names(self) -> list[str]:
        return list(self._names.values())

    def display_name(self, seq: str) -> str:
        return self._names.get(canonical_name(seq), seq)

    def load(self, seq: str) -> np.ndarray:
        key = canonical_name(seq)
        if key in self._boxes:
            return self._boxes[key]
        if key in self._files:
            boxes = read_box_file(self._files[key])
            self._boxes[key] = boxes
            return boxes
        if key in self._errors:
            raise ValueError(self._errors[key])
        raise ValueError(f"no ground truth for sequence {seq!r} in {self.root}")


def load_groundtruth_source(dataset) -> _GroundTruth:
    """Ground-truth look-up of a dataset folder (OTB sequence folders or an ``anno`` folder)."""
    return _GroundTruth(dataset)


# --------------------------------------------------------------------------- helpers


@dataclass
class _Pair:
    score: SequenceScore
    fps: float | None
    frames_timed: int
    seconds: float


def _read_json(path: Path, errors: list, what: str):
    if not path.is_file():
        return None
    try:
        return json.loads(path.read_text(encoding="utf-8"))
    except (OSError, ValueError) as exc:
        errors.append(
            {"tracker": None, "sequence": None, "error": f"{path}: unreadable {what} ({exc})", "stage": "report"}
        )
        return None


def _unique(seq: Iterable[str]) -> list[str]:
    out, seen = [], set()
    for s in seq:
        k = canonical_name(s)
        if k not in seen:
            seen.add(k)
            out.append(s)
    return out


def _tracker_files(tdir: Path) -> dict[str, Path]:
    if not tdir.is_dir():
        return {}
    return {canonical_name(p.stem): p for p in sorted(tdir.glob("*.txt"))}


def _read_times(path: Path) -> np.ndarray | None:
    if not path.is_file():
        return None
    try:
        t = np.loadtxt(path, ndmin=1, dtype=np.float64)
    except ValueError:
        return None
    return t.ravel()


def _rel(p: Path, base: Path) -> str:
    try:
        return str(p.relative_to(base))
    except ValueError:
        return str(p)


def _round(v):
    return None if v is None else float(v)


def _attribute_source(attributes, meta: dict, published, gt: _GroundTruth, errors: list):
    for cand in (attributes, meta.get("attributes"), published):
        if cand:
            try:
                return load_attribute_table(cand), str(cand)
            except (OSError, ValueError) as exc:
                if cand is attributes:
                    raise
                if cand is not published:
                    errors.append({"tracker": None, "sequence": None, "stage": "report", "error": f"attributes: {exc}"})
    # next to the dataset: anno/att or att/
    for cand in (gt.root / "anno" / "att", gt.root / "att", gt.root.parent / "anno" / "att"):
        if cand.is_dir():
            try:
                return load_attribute_table(cand), str(cand)
            except (OSError, ValueError):
                pass
    return {}, None


# --------------------------------------------------------------------------- main entry


def build_report(
    run_dir,
    dataset=None,
    published=None,
    benchmark: str = "tb100",
    attributes=None,
    top: int = 10,
    invalid: str = "otb",
    *,
    trackers: Sequence[str] | None = None,
    sequences: Sequence[str] | None = None,
    formats: Sequence[str] = ("png", "svg"),
) -> dict:
    """Score the stored results of ``run_dir`` and write ``run_dir/report/``. Returns the summary.

    Parameters
    ----------
    run_dir : path
        The run folder (``results/``, optional ``run.json`` and ``errors.json``).
    dataset : path, optional
        OTB folder of sequences (or an ``anno`` folder of ``<Seq>.txt``); default
        ``run.json["dataset"]``.
    published : path, optional
        Folder holding the benchmark's ``OPE/`` score files (curves drawn beside ours) and,
        when present, ``anno/att`` (attributes); default ``run.json["published"]``. Pass
        ``False`` to leave published curves out even if ``run.json`` names a folder.
    benchmark : {"tb100", "cvpr13", "tb50"}
        Which published score set to draw.
    attributes : path or mapping, optional
        Attribute table (``attributes-tb100.txt``, an ``anno/att`` folder, ...); default
        ``run.json["attributes"]``, else the ``published`` folder's, else one next to the
        dataset.
    top : int
        Number of curves in each plot (our trackers first, published ones fill the rest).
    invalid : {"otb", "pytracking", "fail"}
        Handling of invalid ground-truth frames (see :mod:`.metrics`).
    trackers, sequences : optional
        Restrict the report (default: ``run.json``'s lists plus any tracker folder found).
    formats : plot formats.

    Returns
    -------
    dict
        The summary written to ``summary.json``::

            {"trackers": {NAME: {"auc", "precision20", "avg_overlap", "fps", "n_sequences",
                                 "success": [21], "precision": [51], "imported": bool,
                                 "sequences": {SEQ: {"avg_overlap", "auc", "precision20",
                                                     "fps", "n_frames", "n_valid"}},
                                 "attributes": {ATTR: {"auc", "precision20", "n_sequences",
                                                       "success", "precision"}},
                                 "errors": {SEQ: message}}},
             "sequences": [...], "attributes": {ATTR: {"name", "sequences"}},
             "published": {...} or None, "errors": [{"tracker", "sequence", "error", "stage"}],
             "settings": {...}, "files": [...]}

        ``fps`` is frames / total tracking time from the times files (None without them);
        a tracker's ``fps`` pools all its timed frames.
    """
    _check_mode(invalid)
    run_dir = Path(run_dir)
    if not run_dir.is_dir():
        raise FileNotFoundError(f"run folder not found: {run_dir}")
    out_dir = run_dir / REPORT_DIR
    out_dir.mkdir(parents=True, exist_ok=True)
    errors: list[dict] = []

    meta = _read_json(run_dir / "run.json", errors, "run.json") or {}
    if not isinstance(meta, dict):
        meta = {}
    dataset = dataset if dataset is not None else meta.get("dataset")
    if not dataset:
        raise ValueError(f"{run_dir}: no dataset given and run.json names none (pass dataset=...)")
    gt_source = _GroundTruth(dataset)
    if published is None:
        published = meta.get("published")
    published = published or None
    max_frames = meta.get("max_frames")

    run_errors = _read_json(run_dir / "errors.json", errors, "errors.json") or []
    run_error_pairs = set()
    for e in run_errors if isinstance(run_errors, list) else []:
        if isinstance(e, dict):
            entry = {
                "tracker": e.get("tracker"),
                "sequence": e.get("sequence"),
                "error": str(e.get("error", "")),
                "stage": "run",
            }
            errors.append(entry)
            run_error_pairs.add((str(entry["tracker"]), canonical_name(entry["sequence"] or "")))

    results_dir = run_dir / "results"
    found_trackers = (
        sorted((p.name for p in results_dir.iterdir() if p.is_dir()), key=str.lower) if results_dir.is_dir() else []
    )
    if trackers is None:
        trackers = _unique(list(meta.get("trackers") or []) + found_trackers)
    trackers = list(trackers)
    files = {t: _tracker_files(results_dir / t) for t in trackers}

    if sequences is None:
        sequences = meta.get("sequences") or None
    if sequences is None:
        names = [p.stem for t in trackers for p in files[t].values()]
        sequences = sorted(_unique(names), key=lambda s: canonical_name(s))
    sequences = [gt_source.display_name(s) for s in _unique(sequences)]

    # ---- score every pair
    pairs: dict[str, dict[str, _Pair]] = {t: {} for t in trackers}
    pair_errors: dict[str, dict[str, str]] = {t: {} for t in trackers}
    seq_ok: list[str] = []
    for seq in sequences:
        key = canonical_name(seq)
        try:
            gt_full = gt_source.load(seq)
        except (OSError, ValueError) as exc:
            errors.append({"tracker": None, "sequence": seq, "error": str(exc), "stage": "report"})
            for t in trackers:
                pair_errors[t][seq] = "no ground truth"
            continue
        seq_ok.append(seq)
        for t in trackers:
            tdir = results_dir / t
            path = files[t].get(key)
            if path is None:
                msg = f"missing result file {_rel(tdir / (seq + '.txt'), run_dir)}"
                pair_errors[t][seq] = msg if (t, key) not in run_error_pairs else "failed in the run (errors.json)"
                if (t, key) not in run_error_pairs:
                    errors.append({"tracker": t, "sequence": seq, "error": msg, "stage": "report"})
                continue
            try:
                boxes = read_box_file(path)
                gt = gt_full
                if max_frames:
                    gt = gt[: int(max_frames)]
                offset = _import_offset(tdir, seq)
                if len(boxes) != len(gt) and offset and len(gt) == offset + len(boxes):
                    gt = gt[offset:]
                if len(boxes) < len(gt):
                    raise ValueError(
                        f"{_rel(path, run_dir)}: result file shorter than its sequence: {len(boxes)} lines, "
                        f"sequence {seq} has {len(gt)} frames (no box from line {len(boxes) + 1} on)"
                    )
                if len(boxes) > len(gt):
                    raise ValueError(
                        f"{_rel(path, run_dir)}: result file longer than its sequence: {len(boxes)} lines, "
                        f"sequence {seq} has {len(gt)} frames (line {len(gt) + 1} and after have no frame)"
                    )
                score = score_sequence(boxes, gt, invalid=invalid)
            except (OSError, ValueError) as exc:
                msg = str(exc)
                if str(path) in msg:
                    msg = msg.replace(str(path), _rel(path, run_dir))
                pair_errors[t][seq] = msg
                errors.append({"tracker": t, "sequence": seq, "error": msg, "stage": "report"})
                continue
            times = _read_times(tdir / "times" / f"{path.stem}_time.txt")
            fps, n_timed, secs = None, 0, 0.0
            if times is not None and times.size and np.all(np.isfinite(times)) and times.sum() > 0:
                n_timed, secs = int(times.size), float(times.sum())
                fps = n_timed / secs
            pairs[t][seq] = _Pair(score, fps, n_timed, secs)

    # ---- attributes
    attr_table, attr_source = _attribute_source(attributes, meta, published, gt_source, errors)
    subsets: dict[str, list[str]] = {}
    if attr_table:
        for a in ATTRIBUTES:
            members = [s for s in seq_ok if a in attr_table.get(canonical_name(s), ())]
            if members and any(s in pairs[t] for t in trackers for s in members):
                subsets[a] = members

    # ---- per tracker
    summary_trackers: dict = {}
    for t in trackers:
        got = pairs[t]
        imported = (results_dir / t / "import.json").is_file()
        entry: dict = {
            "auc": None,
            "precision20": None,
            "avg_overlap": None,
            "fps": None,
            "n_sequences": len(got),
            "success": None,
            "precision": None,
            "imported": imported,
            "sequences": {},
            "attributes": {},
            "errors": dict(pair_errors[t]),
        }
        for seq, p in got.items():
            entry["sequences"][seq] = {
                "avg_overlap": float(p.score.avg_overlap),
                "auc": float(p.score.auc),
                "precision20": float(p.score.precision20),
                "fps": _round(p.fps),
                "n_frames": int(p.score.n_frames),
                "n_valid": int(p.score.n_valid),
            }
        if got:
            agg = aggregate([p.score for p in got.values()])
            entry.update(
                auc=agg.auc,
                precision20=agg.precision20,
                avg_overlap=float(np.mean([p.score.avg_overlap for p in got.values()])),
                success=agg.success.tolist(),
                precision=agg.precision.tolist(),
            )
            timed = [p for p in got.values() if p.fps is not None]
            if timed:
                entry["fps"] = sum(p.frames_timed for p in timed) / sum(p.seconds for p in timed)
            for a, members in subsets.items():
                sub = [got[s].score for s in members if s in got]
                if sub:
                    sa = aggregate(sub)
                    entry["attributes"][a] = {
                        "auc": sa.auc,
                        "precision20": sa.precision20,
                        "n_sequences": len(sub),
                        "success": sa.success.tolist(),
                        "precision": sa.precision.tolist(),
                    }
        summary_trackers[t] = entry

    # ---- published curves
    pub_summary = None
    pub_scores: dict[str, dict] = {}
    if published:
        try:
            label = benchmark_label(benchmark)
            pub_scores["ALL"] = load_published_scores(published, benchmark, "ALL")
            for a in subsets:
                pub_scores[a] = load_published_scores(published, benchmark, a)
            pub_summary = {
                "source": str(published),
                "benchmark": benchmark,
                "label": label,
                "note": f"published OPE scores computed by the benchmark on the {label} sequence set, "
                "not on this run's sequences",
                "trackers": {
                    n: {
                        "auc": d["auc"],
                        "precision20": d["precision20"],
                        "n_sequences": d["n_sequences"],
                        "success": d["success"].tolist(),
                        "precision": d["precision"].tolist(),
                    }
                    for n, d in pub_scores["ALL"].items()
                },
                "attributes": {
                    a: {
                        n: {"auc": d["auc"], "precision20": d["precision20"], "n_sequences": d["n_sequences"]}
                        for n, d in pub_scores[a].items()
                    }
                    for a in subsets
                },
            }
        except (OSError, ValueError) as exc:
            errors.append({"tracker": None, "sequence": None, "error": f"published scores: {exc}", "stage": "report"})
            pub_scores = {}

    # ---- plots
    written: list[Path] = []
    plots: list[dict] = []
    scored = [t for t in trackers if summary_trackers[t]["auc"] is not None]

    def _plot_pair(stem_suffix: str, subset: str | None, n_seq: int):
        for kind, curve_key, score_key in (("success", "success", "auc"), ("precision", "precision", "precision20")):
            ours = []
            for t in scored:
                src = summary_trackers[t] if subset is None else summary_trackers[t]["attributes"].get(subset)
                if src:
                    ours.append(Curve(t, np.asarray(src[curve_key]), src[score_key]))
            pub = []
            for n, d in pub_scores.get(subset or "ALL", {}).items():
                pub.append(Curve(n, d[curve_key], d[score_key], published=benchmark_label(benchmark)))
            chosen = select_curves(ours, pub, top=top)
            subtitle = None if subset is None else f"{ATTRIBUTE_NAMES[subset]} ({n_seq})"
            paths = plot_curves(kind, chosen, out_dir / f"{kind}{stem_suffix}", subtitle=subtitle, formats=formats)
            written.extend(paths)
            plots.append({"kind": kind, "subset": subset or "ALL", "files": [p.name for p in paths]})

    if scored:
        _plot_pair("", None, len(seq_ok))
        for a, members in subsets.items():
            _plot_pair(f"_{a}", a, len(members))

    # ---- tables
    table_md, table_csv = _tables(sequences, seq_ok, trackers, summary_trackers, invalid)
    (out_dir / "table.md").write_text(table_md, encoding="utf-8")
    (out_dir / "table.csv").write_text(table_csv, encoding="utf-8")
    written += [out_dir / "table.md", out_dir / "table.csv"]

    summary = {
        "trackers": summary_trackers,
        "sequences": seq_ok,
        "attributes": {a: {"name": ATTRIBUTE_NAMES[a], "sequences": m} for a, m in subsets.items()},
        "published": pub_summary,
        "errors": errors,
        "settings": {
            "run_dir": str(run_dir.resolve()),
            "dataset": str(dataset),
            "invalid": invalid,
            "benchmark": benchmark,
            "top": top,
            "attributes": attr_source,
            "max_frames": max_frames,
            "protocol": "OTB OPE: IoU with inclusive pixel extents, success = IoU > t for t in 0:0.05:1, "
            "AUC = mean, precision = centre error <= t px for t in 0..50, score at 20 px, "
            "curves averaged over sequences, frame 1 = ground truth",
        },
        "plots": plots,
        "files": sorted(p.name for p in written) + ["index.html", "summary.json"],
    }
    (out_dir / "index.html").write_text(_index_html(summary, table_md), encoding="utf-8")
    tmp = out_dir / "summary.json.tmp"
    tmp.write_text(json.dumps(_finite(summary), indent=1, allow_nan=False), encoding="utf-8")
    os.replace(tmp, out_dir / "summary.json")
    return summary


def _finite(obj):
    """JSON-safe copy: non-finite floats become None (strict JSON has no NaN/inf)."""
    if isinstance(obj, dict):
        return {k: _finite(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_finite(v) for v in obj]
    if isinstance(obj, (float, np.floating)):
        return float(obj) if np.isfinite(obj) else None
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def _import_offset(tdir: Path, seq: str) -> int:
    path = tdir / "import.json"
    if not path.is_file():
        return 0
    try:
        meta = json.loads(path.read_text(encoding="utf-8"))
        info = meta.get("sequences", {})
        for name, rec in info.items():
            if canonical_name(name) == canonical_name(seq):
                return int(rec.get("anno_offset") or 0)
    except (OSError, ValueError, AttributeError, TypeError):
        return 0
    return 0


# --------------------------------------------------------------------------- tables


def _best(values: dict[str, float | None], digits: int) -> set[str]:
    shown = {k: round(v, digits) for k, v in values.items() if v is not None}
    if not shown:
        return set()
    top = max(shown.values())
    return {k for k, v in shown.items() if v == top}


def _tables(sequences, seq_ok, trackers, st, invalid) -> tuple[str, str]:
    digits = 2
    lines = [
        "# Average overlap per sequence (OTB one-pass evaluation)",
        "",
        f"Best of each row in **bold** (compared at the {digits} decimals shown). `error`: no usable "
        f"result (see below). Invalid ground-truth frames: `{invalid}` rule.",
        "",
        "| Sequence | " + " | ".join(trackers) + " |",
        "| --- | " + " | ".join("---:" for _ in trackers) + " |",
    ]

    def row(label, values: dict, fmt, bold=True):
        best = _best(values, digits) if bold else set()
        cells = []
        for t in trackers:
            v = values.get(t)
            if v is None:
                cells.append("error" if label in sequences else "–")
            else:
                s = fmt(v)
                cells.append(f"**{s}**" if t in best else s)
        return f"| {label} | " + " | ".join(cells) + " |"

    f2 = lambda v: f"{v:.{digits}f}"  # noqa: E731
    for seq in sequences:
        if seq not in seq_ok:
            lines.append(f"| {seq} | " + " | ".join("error" for _ in trackers) + " |")
            continue
        vals = {t: st[t]["sequences"].get(seq, {}).get("avg_overlap") for t in trackers}
        lines.append(row(seq, vals, f2))
    lines.append(row("**Average**", {t: st[t]["avg_overlap"] for t in trackers}, f2))
    lines.append(row("AUC (success)", {t: st[t]["auc"] for t in trackers}, lambda v: f"{v:.3f}"))
    lines.append(row("Precision (20 px)", {t: st[t]["precision20"] for t in trackers}, lambda v: f"{v:.3f}"))
    lines.append(row("FPS", {t: st[t]["fps"] for t in trackers}, lambda v: f"{v:.1f}", bold=False))
    lines.append("")
    n_seq = {t: st[t]["n_sequences"] for t in trackers}
    if len(set(n_seq.values())) > 1:
        lines.append(
            "Averages are over the sequences each tracker has results for: "
            + ", ".join(f"{t} {n}" for t, n in n_seq.items())
            + "."
        )
        lines.append("")
    errs = [(t, s, m) for t in trackers for s, m in st[t]["errors"].items()]
    if errs:
        lines.append("## Errors")
        lines.append("")
        for t, s, m in errs:
            lines.append(f"- {t} / {s}: {m}")
        lines.append("")
    md = "\n".join(lines)

    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["sequence", *trackers])
    for seq in sequences:
        w.writerow([seq, *[_csv(st[t]["sequences"].get(seq, {}).get("avg_overlap")) for t in trackers]])
    w.writerow(["average", *[_csv(st[t]["avg_overlap"]) for t in trackers]])
    w.writerow(["auc", *[_csv(st[t]["auc"]) for t in trackers]])
    w.writerow(["precision20", *[_csv(st[t]["precision20"]) for t in trackers]])
    w.writerow(["fps", *[_csv(st[t]["fps"]) for t in trackers]])
    return md, buf.getvalue()


def _csv(v) -> str:
    return "" if v is None else f"{v:.6f}"


# --------------------------------------------------------------------------- html


def _md_table_to_html(md: str) -> str:
    rows = [l for l in md.splitlines() if l.startswith("| ") and not l.startswith("| ---")]
    out = ["<table>"]
    for i, line in enumerate(rows):
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        tag = "th" if i == 0 else "td"
        tds = []
        for c in cells:
            text = html.escape(c.replace("**", ""))
            if c.startswith("**") and c.endswith("**"):
                text = f"<b>{text}</b>"
            tds.append(f"<{tag}>{text}</{tag}>")
        out.append("<tr>" + "".join(tds) + "</tr>")
    out.append("</table>")
    return "\n".join(out)


def _index_html(summary: dict, table_md: str) -> str:
    e = html.escape
    s = summary["settings"]
    parts = [
        "<!DOCTYPE html>",
        "<html><head><meta charset='utf-8'><title>OTB evaluation report</title>",
        "<style>body{font-family:sans-serif;margin:2em;max-width:1400px}table{border-collapse:collapse}"
        "td,th{border:1px solid #bbb;padding:3px 8px;text-align:right}td:first-child,th:first-child{text-align:left}"
        ".plots{display:flex;flex-wrap:wrap;gap:1em}.plots figure{margin:0}.plots img{max-width:640px}"
        ".err{color:#a00}</style></head><body>",
        "<h1>OTB one-pass evaluation</h1>",
        f"<p>Run: <code>{e(s['run_dir'])}</code><br>Dataset: <code>{e(s['dataset'])}</code><br>"
        f"Invalid ground-truth rule: <code>{e(s['invalid'])}</code>. {e(s['protocol'])}.</p>",
    ]
    if s.get("max_frames"):
        parts.append(
            f"<p class='err'>Sequences were cut to {int(s['max_frames'])} frames (max_frames): "
            "these numbers are not OTB-compliant.</p>"
        )
    parts.append(
        "<p>Files: <a href='summary.json'>summary.json</a>, <a href='table.md'>table.md</a>, "
        "<a href='table.csv'>table.csv</a></p>"
    )
    parts.append("<h2>Average overlap per sequence</h2>")
    parts.append(_md_table_to_html(table_md))
    pub = summary.get("published")
    if pub:
        parts.append(f"<p>Dashed curves: {e(pub['note'])} (<code>{e(pub['source'])}</code>).</p>")

    def figs(subset):
        items = [p for p in summary["plots"] if p["subset"] == subset]
        html_items = []
        for p in items:
            png = next((f for f in p["files"] if f.endswith(".png")), p["files"][0])
            links = " ".join(f"<a href='{e(f)}'>{e(f.rsplit('.', 1)[1].upper())}</a>" for f in p["files"])
            if png.endswith(".png"):
                img = f"<img src='{e(png)}' alt='{e(p['kind'])} {e(subset)}'>"
            else:
                img = f"<object data='{e(png)}' type='image/svg+xml'></object>"
            html_items.append(f"<figure>{img}<figcaption>{links}</figcaption></figure>")
        return "<div class='plots'>" + "".join(html_items) + "</div>"

    if summary["plots"]:
        parts.append(f"<h2>All sequences ({len(summary['sequences'])})</h2>")
        parts.append(figs("ALL"))
        for a, info in summary["attributes"].items():
            parts.append(f"<h2>{e(a)}: {e(info['name'])} ({len(info['sequences'])} sequences)</h2>")
            parts.append(f"<p>{e(', '.join(info['sequences']))}</p>")
            parts.append(figs(a))
    else:
        parts.append("<p class='err'>No tracker has a usable result: no plots.</p>")
    if summary["errors"]:
        parts.append(f"<h2 class='err'>Errors ({len(summary['errors'])})</h2><ul>")
        for err in summary["errors"]:
            who = " / ".join(x for x in (err.get("tracker"), err.get("sequence")) if x)
            parts.append(
                f"<li><b>{e(who or 'general')}</b> [{e(err.get('stage', ''))}]: <code>{e(err['error'])}</code></li>"
            )
        parts.append("</ul>")
    parts.append("</body></html>")
    return "\n".join(parts) + "\n"
