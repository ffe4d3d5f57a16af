"""Is ``TrackResult.lost`` right, and is ``TrackResult.confidence`` calibrated?

Usage::

    python bench/lost_calibration.py --data DIR [DIR ...] [--sequences NAME ...]
        [--seeds 0 1 2] [--max-frames N] [--config JSON] [--plot reliability.png]
        [--frames-out frames.csv]

Runs the tracker (``TrackerConfig(**config, seed=s)``, the defaults without
``--config``) on every OTB sequence of the ``--data`` folders (or only those
named by ``--sequences``) for each seed, and compares each frame's ``lost``
and ``confidence`` (the first frame, given, and frames without a valid
ground-truth box left out) with the ground truth, where a frame is *tracked*
when the box's overlap with it is at least ``LOST_OVERLAP`` (0.1). Prints:

- the precision and recall of ``lost`` against "not tracked";
- a reliability table of ``confidence``: ``BINS`` (10) equal bins over
  [0, 1], each with the mean confidence, the share of its frames tracked and
  its count, and the expected calibration error (the count-weighted mean of
  ``|share tracked - mean confidence|``): calibrated, the share tracked is
  about the mean confidence in every bin;

and saves the reliability diagram (``--plot``, PNG) and, with
``--frames-out``, one CSV line per frame (sequence, seed, frame, overlap,
confidence, lost and the evidence's features,
:meth:`smtmvt.confidence.Evidence.features`) from which a logistic
regression fits :class:`smtmvt.confidence.ConfidenceModel`'s constants.
Not a test: it measures.
"""

from __future__ import annotations

import argparse
import csv
import json
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from smtmvt import Tracker, TrackerConfig
from smtmvt.data import list_dataset, open_dataset
from smtmvt.evaluation.metrics import overlap_ratio

#: A frame is tracked when its box overlaps the ground truth's at least this much (else lost).
LOST_OVERLAP = 0.1
#: Equal-width confidence bins of the reliability table.
BINS = 10
#: The ``--frames-out`` columns of :meth:`smtmvt.confidence.Evidence.features`.
FEATURES = ("log_peak_ratio", "log_apce_ratio", "log_cost_ratio", "lost_frames", "drift")


@dataclass(frozen=True)
class Frames:
    """Per-frame outcomes, ``(m,)`` arrays each: ``confidence`` in [0, 1],
    ``lost`` (the tracker's) and ``tracked`` (overlap >= ``LOST_OVERLAP``)."""

    confidence: np.ndarray
    lost: np.ndarray
    tracked: np.ndarray


def precision_recall(lost: np.ndarray, tracked: np.ndarray) -> tuple[float, float]:
    """``(precision, recall)`` of ``lost`` ``(m,)`` bool as a detector of the
    frames not ``tracked`` ``(m,)`` bool; NaN where its denominator is 0 (no
    frame called lost, no frame truly lost)."""
    lost, truly = np.asarray(lost, dtype=bool), ~np.asarray(tracked, dtype=bool)
    hits = float(np.sum(lost & truly))
    precision = hits / lost.sum() if lost.any() else float("nan")
    recall = hits / truly.sum() if truly.any() else float("nan")
    return precision, recall


def reliability(confidence: np.ndarray, tracked: np.ndarray, bins: int = BINS) -> np.ndarray:
    """The reliability table, ``(bins, 3)`` float64: per equal-width bin of
    [0, 1] (bin ``k`` is ``[k / bins, (k + 1) / bins)``, the last one closed),
    the mean confidence, the share of its frames tracked (NaN for both in an
    empty bin) and its count."""
    c = np.asarray(confidence, dtype=np.float64)
    t = np.asarray(tracked, dtype=bool)
    if c.shape != t.shape:
        raise ValueError(f"confidence {c.shape} and tracked {t.shape} must have one value per frame")
    if np.any(~((c >= 0) & (c <= 1))):
        raise ValueError(f"confidence must lie in [0, 1], got values from {np.nanmin(c)} to {np.nanmax(c)}")
    which = np.minimum((c * bins).astype(np.intp), bins - 1)
    table = np.full((bins, 3), np.nan)
    for k in range(bins):
        inside = which == k
        table[k, 2] = inside.sum()
        if inside.any():
            table[k, 0], table[k, 1] = c[inside].mean(), t[inside].mean()
    return table


def calibration_error(table: np.ndarray) -> float:
    """Expected calibration error of a :func:`reliability` table: the mean of
    ``|share tracked - mean confidence|`` weighted by the bins' counts."""
    full = table[:, 2] > 0
    return float(np.sum(table[full, 2] * np.abs(table[full, 1] - table[full, 0])) / table[full, 2].sum())


def track(seq, config: dict, seed: int, max_frames: int | None) -> tuple[list, np.ndarray]:
    """``(results, overlaps)``: the ``TrackResult`` of each frame after the first
    and its overlap with the ground truth ``(m,)`` (NaN where it has no valid box)."""
    n = len(seq) if max_frames is None else min(len(seq), max_frames)
    tracker = Tracker(TrackerConfig(**config, seed=seed))
    tracker.init(seq[0], seq.first_box)
    results = [tracker.update(seq[i]) for i in range(1, n)]
    gt = np.asarray(seq.groundtruth[1:n], dtype=np.float64)
    valid = np.all(np.isfinite(gt), axis=1) & np.all(gt[:, 2:] > 0, axis=1)
    overlaps = np.full(len(results), np.nan)
    if valid.any():
        boxes = np.array([r.box for r in results])
        overlaps[valid] = overlap_ratio(boxes[valid], gt[valid])
    return results, overlaps


def plot(table: np.ndarray, path: Path, title: str) -> None:
    """Save the reliability diagram of ``table`` (:func:`reliability`) as a PNG at ``path``."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    bins = len(table)
    edges = np.arange(bins) / bins
    fig, (ax, counts) = plt.subplots(2, 1, figsize=(5, 6), height_ratios=(3, 1), sharex=True)
    ax.plot([0, 1], [0, 1], "k--", lw=1, label="calibrated")
    ax.bar(edges, np.nan_to_num(table[:, 1]), width=1 / bins, align="edge", alpha=0.6, edgecolor="k", label="tracked")
    ax.plot(table[:, 0], table[:, 1], "o-", color="C3", label="share tracked at mean confidence")
    ax.set(ylabel=f"share tracked (overlap >= {LOST_OVERLAP})", xlim=(0, 1), ylim=(0, 1), title=title)
    ax.legend(loc="upper left", fontsize=8)
    counts.bar(edges, table[:, 2], width=1 / bins, align="edge", color="C0", edgecolor="k")
    counts.set(xlabel="confidence", ylabel="frames", yscale="log" if table[:, 2].max() > 0 else "linear")
    fig.tight_layout()
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=120)
    plt.close(fig)


def sequences_of(folders, names) -> list:
    """The sequences of the data ``folders``: all, or those whose name is in ``names``
    (case-insensitive; a name found in no folder is an error naming it)."""
    wanted = {n.lower() for n in names or ()}
    out, found = [], set()
    for folder in folders:
        keep = [name for name, _, _ in list_dataset(folder) if not wanted or name.lower() in wanted]
        found |= {n.lower() for n in keep}
        out += open_dataset(folder, keep) if keep else []
    missing = sorted(wanted - found)
    if missing:
        raise SystemExit(f"--sequences: {', '.join(missing)} not found in {', '.join(map(str, folders))}")
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", nargs="+", required=True, type=Path, help="folders of OTB sequences")
    ap.add_argument("--sequences", nargs="*", default=None, help="only these sequences (default: all)")
    ap.add_argument("--seeds", nargs="+", type=int, default=[0], help="seeds (default 0)")
    ap.add_argument("--max-frames", type=int, default=None, help="at most this many frames per sequence")
    ap.add_argument("--config", default="{}", help="TrackerConfig fields as JSON (default: the defaults)")
    ap.add_argument("--plot", type=Path, default=Path("reliability.png"), help="reliability diagram PNG")
    ap.add_argument("--frames-out", type=Path, default=None, help="per-frame CSV for fitting the constants")
    args = ap.parse_args()
    config = json.loads(args.config)
    rows = []
    for seq in sequences_of(args.data, args.sequences):
        for seed in args.seeds:
            results, overlaps = track(seq, config, seed, args.max_frames)
            for i, (r, o) in enumerate(zip(results, overlaps)):
                if np.isfinite(o):
                    rows.append((seq.name, seed, i + 2, float(o), r.confidence, r.lost, *r.evidence.features()))
            scored = np.isfinite(overlaps)
            lost = np.array([r.lost for r in results])[scored]
            print(
                f"{seq.name} seed {seed}: {scored.sum()} frames, {np.mean(overlaps[scored] < LOST_OVERLAP):.1%} "
                f"truly lost, {lost.mean():.1%} called lost, mean overlap {np.mean(overlaps[scored]):.3f}",
                flush=True,
            )
    if not rows:
        raise SystemExit("no frame with a valid ground-truth box")
    frames = Frames(
        confidence=np.array([r[4] for r in rows]),
        lost=np.array([r[5] for r in rows], dtype=bool),
        tracked=np.array([r[3] for r in rows]) >= LOST_OVERLAP,
    )
    report(frames, args.plot)
    if args.frames_out is not None:
        args.frames_out.parent.mkdir(parents=True, exist_ok=True)
        with open(args.frames_out, "w", newline="") as f:
            out = csv.writer(f)
            out.writerow(["sequence", "seed", "frame", "overlap", "confidence", "lost", *FEATURES])
            out.writerows(rows)
        print(f"per-frame features: {args.frames_out}")


def report(frames: Frames, plot_path: Path) -> None:
    """Print the precision and recall of ``lost`` and the reliability table; save the diagram."""
    precision, recall = precision_recall(frames.lost, frames.tracked)
    m = len(frames.tracked)
    print(
        f"\n{m} frames, {np.sum(~frames.tracked)} truly lost (overlap < {LOST_OVERLAP}), {frames.lost.sum()} called lost"
    )
    print(f"lost: precision {precision:.3f}, recall {recall:.3f}")
    table = reliability(frames.confidence, frames.tracked)
    print("\nconfidence bin   mean confidence   share tracked   count")
    for k, (mean, share, count) in enumerate(table):
        print(
            f"[{k / BINS:.1f}, {(k + 1) / BINS:.1f}{']' if k == BINS - 1 else ')'}       {mean:15.3f} {share:15.3f} {int(count):7d}"
        )
    print(f"expected calibration error {calibration_error(table):.3f}")
    plot(table, plot_path, f"confidence reliability ({m} frames)")
    print(f"reliability diagram: {plot_path}")


if __name__ == "__main__":
    main()
