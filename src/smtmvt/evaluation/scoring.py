"""Scoring a run folder: stored results -> one plain summary (nothing is written here).

:func:`score_run` reads every (tracker, sequence, repeat) result of a :class:`~.rundir.RunDir`
with the strict reader, scores it with :mod:`.metrics` against the dataset's ground truth and
returns a :class:`Summary`; :mod:`.report` turns that into files.

Repeats
-------
A stochastic tracker of a run with ``repeat = N`` is scored on each of its N repeats; the
numbers reported are means over the repeats, beside their sample standard deviation
(``ddof=1``): per sequence ``avg_overlap`` / ``avg_overlap_std``, ``auc`` / ``auc_std``,
``precision20`` / ``precision20_std``; overall the same over each repeat's figure (its
curves averaged over the sequences, as OTB does); the curves are the means of the repeats'
curves. A deterministic tracker has one repeat and spread 0.0; an imported tracker one run
and spread None (unknown), as has a stochastic tracker of a run with ``repeat = 1``. A
sequence is scored only when all the repeats it needs are there and usable; otherwise it is a
gap (``errors``) naming the first missing or bad file.

Protocols
---------
``protocol="tre"`` or ``"sre"`` scores OTB's TRE or SRE runs (:mod:`.protocols`): a
sequence's runs (its segments, re-derived from the ground truth as the runner planned them)
are each scored as an OPE result on their own frames and pooled into one score of the
sequence (:func:`.protocols.pool_scores`, OTB's ``genPerfMat.m``); from there everything is
as for OPE (repeats, averages over sequences, attributes). A sequence is scored when every
one of its runs is there and usable.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..data import SequenceError, canonical_name
from .groundtruth import GroundTruth
from .metrics import SequenceScore, aggregate, score_sequence
from .protocols import init_omit, pool_scores, segments
from .rundir import RunDir, RunInfo
from .trackers import UnknownTrackerError, tracker_spec

__all__ = ["Summary", "score_run", "score_result", "PROTOCOL", "PROTOCOL_NOTES"]

PROTOCOL = (
    "OTB OPE: IoU with inclusive pixel extents, success = IoU > t for t in 0:0.05:1, "
    "AUC = mean, precision = centre error <= t px for t in 0..50, score at 20 px, "
    "curves averaged over sequences, frame 1 = ground truth"
)
#: what each protocol's numbers are, for the report's settings
PROTOCOL_NOTES = {
    "ope": PROTOCOL,
    "tre": "OTB TRE: 20 runs per sequence from start frames spread over it (OTB's splitSeqTRE), each to the "
    "end and scored as OPE on its own frames; success and precision counts pooled over a sequence's runs "
    "(genPerfMat), curves averaged over sequences",
    "sre": "OTB SRE: 12 runs per sequence from the first frame with the ground-truth box shifted (8) or "
    "scaled by 0.8, 0.9, 1.1, 1.2 (OTB's shiftInitBB), each scored as OPE (frame 1 = ground truth); "
    "counts pooled over a sequence's runs (genPerfMat), curves averaged over sequences",
}


@dataclass
class Summary:
    """Everything the report shows; ``asdict`` of it is ``summary.json``.

    ``trackers``: ``{name: entry}`` with ``auc``, ``auc_std``, ``precision20``,
    ``precision20_std``, ``avg_overlap``, ``avg_overlap_std``, ``fps`` (frames / tracking
    seconds, pooled), ``n_sequences``, ``n_runs``, ``deterministic``, ``imported``,
    ``success`` (21 values), ``precision`` (51), ``sequences`` (``{seq: {avg_overlap,
    avg_overlap_std, auc, auc_std, precision20, precision20_std, fps, n_frames, n_valid,
    n_runs}}``), ``attributes`` (``{ATTR: {auc, auc_std, precision20, n_sequences, success,
    precision}}``) and ``errors`` (``{seq: message}``). ``sequences``: the scored sequences;
    ``table_sequences``: every row of the table (scored or not). ``protocol``: ``"ope"``,
    ``"tre"`` or ``"sre"``; ``protocols``: in the top summary of a report, ``{protocol:
    summary dict}`` of the other protocols the run holds.
    """

    trackers: dict
    sequences: list
    table_sequences: list
    attributes: dict
    published: dict | None
    errors: list
    settings: dict
    plots: list = field(default_factory=list)
    files: list = field(default_factory=list)
    protocol: str = "ope"
    protocols: dict = field(default_factory=dict)


@dataclass
class _Runs:
    """One tracker's scores on one sequence, one per repeat."""

    scores: list[SequenceScore]
    frames_timed: int = 0
    seconds: float = 0.0

    @property
    def fps(self) -> float | None:
        return self.frames_timed / self.seconds if self.seconds > 0 else None


def _spread(values, n_runs: int, deterministic: bool) -> float | None:
    if n_runs >= 2:
        return float(np.std(values, ddof=1))
    return 0.0 if deterministic else None


def score_run(
    run: RunDir,
    info: RunInfo,
    gt: GroundTruth,
    *,
    trackers: list[str],
    sequences: list[str],
    repeat: int,
    invalid: str = "otb",
    attribute_table: dict | None = None,
    protocol: str = "ope",
) -> Summary:
    """Score ``trackers`` x ``sequences`` of ``run`` (first ``repeat`` repeats) for
    ``protocol`` (module notes).

    ``attribute_table``: ``{canonical name: {codes}}`` for the per-attribute figures.
    Errors of the run (``errors.json``) and every unusable result become ``errors`` entries
    ``{"tracker", "sequence", "error", "stage"}`` (stage ``run`` or ``report``).
    """
    errors = _run_errors(run, protocol)
    failed_in_run = {(e["tracker"], canonical_name(e["sequence"] or "")) for e in errors}
    scored_seqs, gts, gt_problems = [], {}, {}
    for seq in sequences:
        try:
            gts[seq] = gt.load(seq)
            scored_seqs.append(seq)
        except (OSError, ValueError) as exc:
            gt_problems[seq] = str(exc)  # what is wrong (missing, a name clash, ...), said per pair too
            errors.append({"tracker": None, "sequence": seq, "error": str(exc), "stage": "report"})
    entries, all_runs = {}, {}
    for t in trackers:
        how = (invalid, protocol, gt.layout)
        all_runs[t], pair_errors = _score_tracker(run, info, t, scored_seqs, gts, repeat, how)
        for seq, msg in pair_errors.items():
            if (t, canonical_name(seq)) in failed_in_run:
                pair_errors[seq] = "failed in the run (errors.json)"
            else:
                errors.append({"tracker": t, "sequence": seq, "error": msg, "stage": "report"})
        for seq, problem in gt_problems.items():
            pair_errors[seq] = problem
        entries[t] = _tracker_entry(run, t, all_runs[t], pair_errors, repeat)
    subsets = _attribute_subsets(attribute_table, scored_seqs, all_runs)
    for t, entry in entries.items():
        entry["attributes"] = _attribute_entries(all_runs[t], subsets, entry)
    return Summary(
        trackers=entries,
        sequences=scored_seqs,
        table_sequences=list(sequences),
        attributes=subsets,
        published=None,
        errors=errors,
        settings={},
        protocol=protocol,
    )


def _run_errors(run: RunDir, protocol: str) -> list[dict]:
    """The run's errors (``errors.json``) of ``protocol`` (an entry's ``part`` names it; none
    for OPE) and of whole trackers (sequence None)."""
    out = []
    for e in run.errors().as_list():
        if e["sequence"] is not None and (e.get("part") or "ope").split("/")[0] != protocol:
            continue
        where = "" if not e["repeat"] else f" (repeat {e['repeat']})"
        out.append({"tracker": e["tracker"], "sequence": e["sequence"], "error": e["error"] + where, "stage": "run"})
    return out


def _is_deterministic(run: RunDir, tracker: str) -> bool:
    try:
        return tracker_spec(tracker).deterministic
    except UnknownTrackerError:
        return False


def _runs_needed(run: RunDir, tracker: str, repeat: int) -> int:
    if run.is_imported(tracker) or _is_deterministic(run, tracker):
        return 1
    return repeat


def _score_tracker(run, info, tracker, seqs, gts, repeat, how) -> tuple[dict[str, _Runs], dict[str, str]]:
    """``how``: ``(invalid rule, protocol, dataset layout)``."""
    invalid, protocol, layout = how
    runs: dict[str, _Runs] = {}
    problems: dict[str, str] = {}
    offsets = _import_offsets(run, tracker)
    for seq in seqs:
        gt = gts[seq] if info.max_frames is None else gts[seq][: info.max_frames]
        got = _Runs([])
        try:
            for r in range(_runs_needed(run, tracker, repeat)):
                if protocol == "ope":
                    got.scores.append(
                        _score_one(run, tracker, seq, r, gt, offsets.get(canonical_name(seq), 0), invalid)
                    )
                    parts: list = [None]
                else:
                    score, parts = _score_segments(run, tracker, seq, r, gt, invalid, (protocol, layout))
                    got.scores.append(score)
                for part in parts:
                    times = run.read_times(tracker, seq, r, part=part)
                    if times is not None:
                        got.frames_timed += times.size
                        got.seconds += float(times.sum())
        except (OSError, ValueError) as exc:
            problems[seq] = str(exc)
            continue
        runs[seq] = got
    return runs, problems


def score_result(run: RunDir, tracker: str, sequence: str, repeat: int, gt: np.ndarray, invalid: str = "otb"):
    """The :class:`~.metrics.SequenceScore` of one stored OPE result (``repeat`` 0-based), as
    the report scores it. ``gt``: ``(n, 4)`` 0-based ground truth of the frames the run
    covers (cut to ``run.json``'s ``max_frames``); ``invalid``: :func:`.metrics.score_sequence`'s
    rule. ValueError naming the result file when it is missing, malformed or of another length."""
    return _score_one(run, tracker, sequence, repeat, gt, 0, invalid)


def _score_one(run: RunDir, tracker: str, seq: str, r: int, gt: np.ndarray, offset: int, invalid: str):
    boxes, rel = _read_boxes(run, tracker, seq, r)
    if len(boxes) != len(gt) and offset and len(gt) == offset + len(boxes):
        gt = gt[offset:]  # the toolkit's files start later (Tiger1 from frame 6)
    if len(boxes) != len(gt):
        side = "shorter" if len(boxes) < len(gt) else "longer"
        raise ValueError(
            f"{rel}: result file {side} than its sequence: {len(boxes)} lines, sequence {seq} has {len(gt)} frames"
        )
    return score_sequence(boxes, gt, invalid=invalid)


def _read_boxes(run: RunDir, tracker: str, seq: str, r: int, part=None) -> tuple[np.ndarray, Path]:
    """The boxes of one result file and its path relative to the run; ValueError naming
    the file when it is missing or malformed."""
    rel = run.result_path(tracker, seq, r, part=part).relative_to(run.root)
    if not (run.root / rel).exists():
        raise ValueError(f"missing result file {rel}")
    try:
        return run.read_result(tracker, seq, r, part=part), rel
    except SequenceError as exc:
        raise ValueError(str(exc).replace(str(run.root / rel), str(rel))) from None


def _score_segments(run: RunDir, tracker: str, seq: str, r: int, gt: np.ndarray, invalid: str, which):
    """``(pooled score, parts)`` of ``seq``'s TRE or SRE runs (module notes; ``which``:
    ``(protocol, dataset layout)``); ValueError naming the first missing or unusable file, or
    why the protocol has no run there."""
    protocol, layout = which
    try:
        runs = segments(protocol, gt, init_omit(seq, layout))
    except ValueError as exc:
        raise ValueError(f"{seq}: no {protocol.upper()} run: {exc}") from None
    scores, parts = [], []
    for segment in runs:
        part = (protocol, segment.name)
        boxes, rel = _read_boxes(run, tracker, seq, r, part)
        n = len(gt) - segment.start
        if len(boxes) != n:
            side = "shorter" if len(boxes) < n else "longer"
            raise ValueError(
                f"{rel}: result file {side} than its run: {len(boxes)} lines, {segment.label} of {seq} has {n} frames"
            )
        scores.append(score_sequence(boxes, gt[segment.start :], invalid=invalid))
        parts.append(part)
    return pool_scores(scores, invalid), parts


def _import_offsets(run: RunDir, tracker: str) -> dict[str, int]:
    """``{canonical sequence: annotation offset}`` from an imported tracker's ``import.json``."""
    try:
        records = run.import_meta(tracker).get("sequences", {})
        return {canonical_name(s): int(rec.get("anno_offset") or 0) for s, rec in records.items()}
    except (ValueError, AttributeError, TypeError):
        return {}


def _tracker_entry(run: RunDir, tracker: str, runs: dict[str, _Runs], errors: dict[str, str], repeat: int) -> dict:
    n_runs = _runs_needed(run, tracker, repeat)
    det = _is_deterministic(run, tracker)
    entry: dict = {
        "auc": None,
        "auc_std": None,
        "precision20": None,
        "precision20_std": None,
        "avg_overlap": None,
        "avg_overlap_std": None,
        "fps": None,
        "n_sequences": len(runs),
        "n_runs": n_runs,
        "deterministic": det,
        "imported": run.is_imported(tracker),
        "success": None,
        "precision": None,
        "sequences": {},
        "errors": dict(errors),
    }
    for seq, got in runs.items():
        entry["sequences"][seq] = _stats(got.scores, n_runs, det) | {
            "fps": got.fps,
            "n_frames": int(got.scores[0].n_frames),
            "n_valid": int(got.scores[0].n_valid),
            "n_runs": n_runs,
        }
    if runs:
        per_run = [aggregate([got.scores[r] for got in runs.values()]) for r in range(n_runs)]
        overlaps = [float(np.mean([got.scores[r].avg_overlap for got in runs.values()])) for r in range(n_runs)]
        entry.update(
            auc=float(np.mean([a.auc for a in per_run])),
            auc_std=_spread([a.auc for a in per_run], n_runs, det),
            precision20=float(np.mean([a.precision20 for a in per_run])),
            precision20_std=_spread([a.precision20 for a in per_run], n_runs, det),
            avg_overlap=float(np.mean(overlaps)),
            avg_overlap_std=_spread(overlaps, n_runs, det),
            success=np.mean([a.success for a in per_run], axis=0).tolist(),
            precision=np.mean([a.precision for a in per_run], axis=0).tolist(),
        )
        timed = [got for got in runs.values() if got.seconds > 0]
        if timed:
            entry["fps"] = sum(g.frames_timed for g in timed) / sum(g.seconds for g in timed)
    return entry


def _stats(scores: list[SequenceScore], n_runs: int, det: bool) -> dict:
    out: dict[str, float | None] = {}
    for key in ("avg_overlap", "auc", "precision20"):
        values = [float(getattr(s, key)) for s in scores]
        out[key] = float(np.mean(values))
        out[f"{key}_std"] = _spread(values, n_runs, det)
    return out


def _attribute_subsets(table: dict | None, seqs: list[str], all_runs: dict[str, dict]) -> dict[str, dict]:
    """``{ATTR: {"name", "sequences"}}`` for the attributes that a scored pair has."""
    from ..data.attributes import ATTRIBUTE_NAMES, ATTRIBUTES

    if not table:
        return {}
    out = {}
    for a in ATTRIBUTES:
        members = [s for s in seqs if a in table.get(canonical_name(s), ())]
        if members and any(s in runs for runs in all_runs.values() for s in members):
            out[a] = {"name": ATTRIBUTE_NAMES[a], "sequences": members}
    return out


def _attribute_entries(runs: dict[str, _Runs], subsets: dict, entry: dict) -> dict:
    out = {}
    for a, subset in subsets.items():
        got = [runs[s] for s in subset["sequences"] if s in runs]
        if not got:
            continue
        n_runs = entry["n_runs"]
        per_run = [aggregate([g.scores[r] for g in got]) for r in range(n_runs)]
        out[a] = {
            "auc": float(np.mean([p.auc for p in per_run])),
            "auc_std": _spread([p.auc for p in per_run], n_runs, entry["deterministic"]),
            "precision20": float(np.mean([p.precision20 for p in per_run])),
            "n_sequences": len(got),
            "success": np.mean([p.success for p in per_run], axis=0).tolist(),
            "precision": np.mean([p.precision for p in per_run], axis=0).tolist(),
        }
    return out
