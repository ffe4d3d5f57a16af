"""Build the evaluation report of a run folder from stored results (nothing is re-run).

``build_report(RUN_DIR)`` scores every (tracker, sequence, repeat) of the run
(:func:`.scoring.score_run`, the strict reader for our result files) against the dataset's
ground truth and writes ``RUN_DIR/report/``:

* ``summary.json``: every number (schema: :class:`.scoring.Summary`);
* ``table.md`` / ``table.csv``: average overlap per sequence (rows) and tracker (columns),
  best of each row in bold, like the paper's table, plus average / AUC / precision / FPS rows
  (:mod:`.tables`); with repeats ``mean ± std``;
* ``success.{png,svg}`` / ``precision.{png,svg}``: OTB success and precision plots (top
  trackers, legend sorted by score), and ``success_<ATTR>`` / ``precision_<ATTR>`` for each of
  the 11 attributes that at least one scored sequence has;
* ``index.html`` showing all of it, with the errors (:mod:`.page`).

A run that holds OTB's TRE or SRE runs (``run.json``'s ``protocols``, :mod:`.protocols`)
gets the same files for each of them in ``report/tre/`` and ``report/sre/`` (scored by
:func:`.scoring.score_run` with ``protocol=``; titles "Success plots of TRE", ...; no
published curves, which are OPE's), and ``report/summary.json`` has their summaries under
``protocols``. The OPE files are written only when the run holds OPE results; otherwise
``report/`` has just ``summary.json`` and an ``index.html`` linking the protocols' pages.
The top summary's ``errors`` are those of every protocol (each tagged ``protocol``).

Every file is written atomically inside the run (:meth:`RunDir.write_bytes`); a folder that
is not a run (no ``run.json``) is refused and nothing is created in it. Published scores (the
benchmark's JSON, averaged over *its* sequence set) are drawn beside ours, labelled with their
benchmark, and never enter the per-sequence table. Results imported into the run
(:func:`.imports.import_into_run`) are ordinary trackers here: scored by our metrics on our
sequences.

A result file that cannot be used (missing, malformed line, shorter or longer than its
sequence) becomes an error entry naming the file; that pair is marked in the table and the
report goes on with the rest. The report has gaps when ``summary["errors"]`` is not empty.
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import asdict
from pathlib import Path

import numpy as np

from ..data import canonical_name
from .groundtruth import GroundTruth, load_groundtruth_source
from .metrics import _check_mode
from .page import index_html
from .paper_table import paper_table_files
from .plots import Curve, render_curves, select_curves
from .published import ATTRIBUTE_NAMES, benchmark_label, load_attribute_table, load_published_scores
from .rundir import REPORT, REPORT_PAGE, REPORT_SUMMARY, REPORT_TABLE, REPORT_TABLE_CSV, RunDir, RunInfo
from .scoring import PROTOCOL_NOTES, Summary, score_run
from .tables import csv_table, markdown_table

__all__ = ["build_report", "load_groundtruth_source", "REPORT_DIR"]

REPORT_DIR = REPORT  # kept for callers of this module; the name is RunDir's


def build_report(
    run_dir,
    dataset=None,
    published=None,
    benchmark: str = "tb100",
    attributes=None,
    top: int = 10,
    invalid: str | None = None,
    *,
    trackers: Sequence[str] | None = None,
    sequences: Sequence[str] | None = None,
    formats: Sequence[str] = ("png", "svg"),
    repeat: int | None = None,
    paper_table: bool = False,
) -> dict:
    """Score the stored results of ``run_dir`` and write ``run_dir/report/``. Returns the summary.

    Parameters
    ----------
    run_dir : path or RunDir
        The run folder; it must have ``run.json`` (made by ``smtmvt evaluate``).
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
    invalid : {"otb", "pytracking", "fail"}, optional
        Handling of invalid ground-truth frames (see :mod:`.metrics`). Default: the rule
        of the dataset's layout (``"otb"`` for an OTB folder; GOT-10k and VOT
        ``"pytracking"``, LaSOT ``"fail"``, UAV123 ``"otb"``: :mod:`smtmvt.data.layouts`).
    trackers, sequences : optional
        Restrict the report (default: ``run.json``'s lists plus any tracker folder found).
    formats : plot formats.
    repeat : int, optional
        Repeats to score (default: all the run holds; fewer reports the first ones).
    paper_table : bool
        Write ``paper_table.md``/``.csv`` (:mod:`.paper_table`); they are written anyway
        when the run holds a sequence of the paper's table.

    Returns
    -------
    dict
        The summary written to ``summary.json`` (:class:`.scoring.Summary` as a dict; ``fps``
        is frames / total tracking time from the times files, None without them).

    Raises
    ------
    ValueError
        Not a run folder, no dataset, or no tracker to report (nothing is written then).
    """
    if invalid is not None:
        _check_mode(invalid)
    run = run_dir if isinstance(run_dir, RunDir) else RunDir(run_dir)
    with run.locked("smtmvt report"):
        info = run.info()
        repeat = _check_repeat(run, info, repeat)
        dataset, published, names = _sources(run, info, dataset, published, trackers)
        gt = GroundTruth(dataset)
        invalid = invalid or gt.absent_rule
        errors: list[dict] = []
        table, source = _attribute_table(attributes, info, published, gt, errors)
        settings = {
            "run_dir": str(run.root), "dataset": str(dataset), "invalid": invalid, "benchmark": benchmark,
            "top": top, "attributes": source, "max_frames": info.max_frames, "repeat": repeat,
        }  # fmt: skip
        scored = _score_protocols(run, info, gt, names, _sequences(run, info, gt, sequences), table, settings)
        summary = _top_summary(run, scored, errors, settings, top, formats)
        _write_top(run, info, summary, "ope" in scored, published, paper_table, formats)
    return _finite(asdict(summary))


def _sources(run: RunDir, info: RunInfo, dataset, published, trackers) -> tuple:
    """``(dataset, published or None, tracker names)`` of a report: the arguments, else
    ``run.json``'s (trackers: also every tracker folder); ValueError when there is no
    dataset or no tracker."""
    dataset = dataset if dataset is not None else info.dataset
    if not dataset:
        raise ValueError(f"{run.root}: no dataset given and run.json names none (pass dataset=...)")
    names = _trackers(run, info, trackers)
    if not names:
        raise ValueError(
            f"{run.root}: no tracker to report (run.json names none and results/ has no tracker folder); "
            "run smtmvt evaluate on it, or import results with smtmvt report --import"
        )
    return dataset, (info.published if published is None else published) or None, names


def _write_top(run: RunDir, info: RunInfo, summary: Summary, ope: bool, published, paper_table: bool, formats) -> None:
    """``report/``: OPE's report (``ope``: the run holds OPE results), with the published
    curves beside ours and the paper's table (when asked or when the run holds a sequence of
    it); else just the page linking the other protocols' reports."""
    if not ope:
        _write_index(run, summary)
        return
    settings = summary.settings
    curves = _published(summary, published, settings["benchmark"])
    extra = paper_table_files(summary.trackers, summary.sequences, published, info.max_frames)
    if paper_table and not extra:
        summary.errors.append({"error": "--paper-table: the run holds none of the paper's sequences"})
    _write(run, summary, curves, settings["top"], formats, extra, run.report_dir)


def _score_protocols(
    run: RunDir, info: RunInfo, gt: GroundTruth, names: list[str], seqs: list[str], table: dict, settings: dict
) -> dict[str, Summary]:
    """``{protocol: Summary}`` of each protocol the run holds (imported trackers: OPE only);
    ``settings`` (``repeat``, ``invalid``, ...) is what the report states it was made with."""
    scored = {}
    for protocol in info.protocols:
        ours = names if protocol == "ope" else [t for t in names if not run.is_imported(t)]
        scored[protocol] = score_run(
            run, info, gt, trackers=ours, sequences=seqs, repeat=settings["repeat"], invalid=settings["invalid"],
            attribute_table=table, protocol=protocol,
        )  # fmt: skip
        scored[protocol].settings = settings | {"protocol": PROTOCOL_NOTES[protocol]}
    return scored


def _check_repeat(run: RunDir, info: RunInfo, repeat: int | None) -> int:
    if repeat is None:
        return info.repeat
    if not isinstance(repeat, int) or not 1 <= repeat <= info.repeat:
        raise ValueError(f"repeat {repeat!r}: {run.root} holds {info.repeat} repeat(s); report 1 to {info.repeat}")
    return repeat


def _trackers(run: RunDir, info: RunInfo, trackers) -> list[str]:
    if trackers is not None:
        return list(trackers)
    return list(dict.fromkeys([*info.trackers, *run.tracker_folders()]))


def _sequences(run: RunDir, info: RunInfo, gt: GroundTruth, sequences) -> list[str]:
    names = list(sequences) if sequences is not None else list(info.sequences)
    if not names:  # a run folder made by hand: the sequences its result files name
        found = {p.stem for t in run.tracker_folders() for p in run.tracker_dir(t).glob("*.txt")}
        names = sorted(found, key=canonical_name)
    unique: dict[str, str] = {}
    for s in names:
        unique.setdefault(canonical_name(s), s)
    return [gt.display_name(s) for s in unique.values()]


def _attribute_table(attributes, info: RunInfo, published, gt: GroundTruth, errors: list):
    """``(table, source)``: the first usable attribute table (explicit, run.json's, the
    published folder's, next to the dataset); ``({}, None)`` when there is none."""
    for cand in (attributes, info.attributes, published):
        if cand:
            try:
                return load_attribute_table(cand), str(cand)
            except (OSError, ValueError) as exc:
                if cand is attributes:
                    raise
                if cand is not published:
                    errors.append({"tracker": None, "sequence": None, "stage": "report", "error": f"attributes: {exc}"})
    for cand in (gt.root / "anno" / "att", gt.root / "att", gt.root.parent / "anno" / "att"):
        if cand.is_dir():
            try:
                return load_attribute_table(cand), str(cand)
            except (OSError, ValueError):
                pass
    return {}, None


def _published(summary: Summary, published, benchmark: str) -> dict[str, dict]:
    """Fill ``summary.published``; return the curves ``{subset: {tracker: scores}}``."""
    if not published:
        return {}
    try:
        label = benchmark_label(benchmark)
        curves = {a: load_published_scores(published, benchmark, a) for a in ["ALL", *summary.attributes]}
    except (OSError, ValueError) as exc:
        summary.errors.append(
            {"tracker": None, "sequence": None, "error": f"published scores: {exc}", "stage": "report"}
        )
        return {}

    def entry(d, with_curves: bool) -> dict:
        out = {"auc": d["auc"], "precision20": d["precision20"], "n_sequences": d["n_sequences"]}
        if with_curves:
            out.update(success=d["success"].tolist(), precision=d["precision"].tolist())
        return out

    summary.published = {
        "source": str(published),
        "benchmark": benchmark,
        "label": label,
        "note": f"published OPE scores computed by the benchmark on the {label} sequence set, "
        "not on this run's sequences",
        "trackers": {n: entry(d, True) for n, d in curves["ALL"].items()},
        "attributes": {a: {n: entry(d, False) for n, d in curves[a].items()} for a in summary.attributes},
    }
    return curves


# --------------------------------------------------------------------------- writing


def _top_summary(run: RunDir, scored: dict[str, Summary], errors: list, settings: dict, top: int, formats) -> Summary:
    """Write the TRE and SRE reports (``report/<protocol>/``); return the top summary: OPE's
    (or an empty one), with the others' summaries in ``protocols`` and every error, once."""
    for protocol, other in scored.items():
        if protocol != "ope":
            _write(run, other, {}, top, formats, {}, run.protocol_report_dir(protocol))
    summary = scored.get("ope") or _empty_summary(settings)
    summary.errors[:0] = errors
    summary.protocols = {p: _finite(asdict(other)) for p, other in scored.items() if p != "ope"}
    seen = {(e.get("tracker"), e.get("sequence"), e.get("error")) for e in summary.errors}
    for p, other in scored.items():
        for e in other.errors if p != "ope" else ():
            if (key := (e.get("tracker"), e.get("sequence"), e.get("error"))) not in seen:
                seen.add(key)
                summary.errors.append(e | {"protocol": p})
    return summary


def _empty_summary(settings: dict) -> Summary:
    """The top summary of a run without OPE results (its protocols' summaries go in it)."""
    return Summary(
        {},
        [],
        [],
        {},
        None,
        [],
        settings | {"protocol": "No OPE results in this run; its other protocols are linked below"},
    )


def _write_index(run: RunDir, summary: Summary) -> None:
    """``index.html`` (links to the protocols' pages) and ``summary.json`` of a run without OPE."""
    summary.files = [REPORT_PAGE, REPORT_SUMMARY]
    run.write_text(run.report_page(), index_html(summary))
    run.write_text(run.report_summary(), json.dumps(_finite(asdict(summary)), indent=1, allow_nan=False))


def _write(run: RunDir, summary: Summary, published: dict, top: int, formats, extra: dict, out: Path) -> None:
    """Every file of one protocol's report in ``out`` (``report/`` for OPE, ``report/tre``, ...)."""
    written = _write_plots(run, summary, published, top, formats, out)
    tables = {REPORT_TABLE: markdown_table(summary), REPORT_TABLE_CSV: csv_table(summary), **extra}
    for name, text in tables.items():
        written.append(run.write_text(out / name, text))
    summary.files = sorted(p.name for p in written) + [REPORT_PAGE, REPORT_SUMMARY]
    run.write_text(out / REPORT_PAGE, index_html(summary))
    run.write_text(out / REPORT_SUMMARY, json.dumps(_finite(asdict(summary)), indent=1, allow_nan=False))


def _write_plots(run: RunDir, summary: Summary, published: dict, top: int, formats, out: Path) -> list[Path]:
    scored = {t: e for t, e in summary.trackers.items() if e["auc"] is not None}
    if not scored:
        return []
    written: list[Path] = []
    label = benchmark_label(summary.settings["benchmark"]) if published else None
    subsets: list[tuple[str | None, int]] = [(None, len(summary.sequences))]
    subsets += [(a, len(info["sequences"])) for a, info in summary.attributes.items()]
    for subset, n_seq in subsets:
        for kind, score_key in (("success", "auc"), ("precision", "precision20")):
            ours = []
            for t, e in scored.items():
                src = e if subset is None else e["attributes"].get(subset)
                if src:
                    ours.append(Curve(t, np.asarray(src[kind]), src[score_key]))
            pub = [
                Curve(n, d[kind], d[score_key], published=label) for n, d in published.get(subset or "ALL", {}).items()
            ]
            subtitle = None if subset is None else f"{ATTRIBUTE_NAMES[subset]} ({n_seq})"
            stem = kind if subset is None else f"{kind}_{subset}"
            files = []
            chosen = select_curves(ours, pub, top=top)
            for fmt, data in render_curves(kind, chosen, subtitle, formats, protocol=summary.protocol).items():
                files.append(run.write_bytes(out / f"{stem}.{fmt}", data))
            written += files
            summary.plots.append({"kind": kind, "subset": subset or "ALL", "files": [p.name for p in files]})
    return written


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
