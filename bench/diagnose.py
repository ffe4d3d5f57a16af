"""Why does the tracker fail on a sequence? Frame-by-frame diagnosis against the ground truth.

Usage::

    python bench/diagnose.py SEQ_DIR [--seed S] [--out DIR] [--frames N] [--config JSON]

Tracks the sequence as usual and, at every frame, also scores the ground-truth
box as one more candidate (:meth:`smtmvt.Tracker.update_detailed` with a probe:
it is coded like the particles but cannot change the tracker's state). Per frame
it records:

- ``overlap``: IoU of the chosen box with the ground truth;
- ``best_particle_overlap``: the best IoU among the frame's sampled particles
  (their boxes as the tracker would report them, ``config.report_aspect``);
- ``gt_rank``: 1 + the number of particles whose likelihood beats the ground
  truth's (1: the ground truth would have been chosen);
- the residuals of the chosen box and of the ground truth under the current
  templates, and under the **first frame's** templates (``*_first``);
- their anchor terms (``*_anchor``, :mod:`smtmvt.anchor`: ``anchor_weight``
  times the residual over the first template alone, 0 when the term is off),
  the part of a candidate's score ``residual + anchor`` besides its residual;
- whether a template was replaced and whether the frame was flagged occluded.

A frame fails when its overlap is below 0.5 (OTB's success threshold). A
failing frame is classified as

- ``model`` when the ground truth scores below the chosen box: the views, the
  templates or the likelihood prefer a wrong box. Among these, ``drift`` marks
  the frames where the **first** templates would still have preferred the
  ground truth (the current templates have drifted);
- ``search`` when the ground truth would have won, but no particle came near
  it (best particle overlap below 0.5): the motion model is at fault;
- ``peak`` when the ground truth would have won and a particle did come near
  it, but that particle scored below the chosen box: the likelihood is too
  narrow around the target (the views change faster than the overlap).

Writes ``DIR/<sequence>_seed<S>.csv`` (one row per frame) and ``.png`` (overlap,
rank and residuals over time), and prints a summary line.
"""

from __future__ import annotations

import argparse
import csv
import json
import sys
from pathlib import Path

import numpy as np

from smtmvt import Tracker, TrackerConfig, open_sequence
from smtmvt.anchor import anchor_offsets
from smtmvt.evaluation.metrics import overlap_ratio
from smtmvt.geometry import box_to_affine
from smtmvt.preprocess import prepare_frame
from smtmvt.solvers import reconstruction_residual

FAIL = 0.5
FIELDS = [
    "frame",
    "overlap",
    "best_particle_overlap",
    "gt_rank",
    "gt_likelihood",
    "chosen_likelihood",
    "gt_residual",
    "chosen_residual",
    "gt_residual_first",
    "chosen_residual_first",
    "gt_anchor",
    "chosen_anchor",
    "replaced",
    "occluded",
    "cls",
]


def residuals_under(tracker: Tracker, frame, boxes, dictionaries) -> tuple[np.ndarray, np.ndarray]:
    """Residuals of ``boxes`` (m, 4) under ``dictionaries`` (the first frame's),
    and their anchor terms ``(m,)`` (over the first template, 0 when off).

    Uses the tracker's own views and observation model (private members: this
    is a diagnosis tool, it reads the tracker's internals without changing them).
    """
    prepared = prepare_frame(frame, "frame", tracker._channels)
    X = tracker._sampler.views(
        prepared, box_to_affine(np.asarray(boxes, dtype=np.float64)).reshape(-1, 6), 1.0, tracker._work_box
    )
    C, _ = tracker._sparse.code(X, dictionaries)
    anchor = np.zeros(len(boxes))
    if tracker.config.anchor_weight:
        first = tracker._sampler.terms_of([Dk[:, 0] for Dk in dictionaries])
        anchor = anchor_offsets(tracker._sampler.terms_of(X), first, tracker.config.anchor_weight)
    return reconstruction_residual(X, dictionaries, C), anchor


def classify(row: dict) -> str:
    if row["overlap"] >= FAIL:
        return ""
    if row["gt_likelihood"] < row["chosen_likelihood"]:
        return "drift" if row["gt_residual_first"] < row["chosen_residual_first"] else "model"
    return "search" if row["best_particle_overlap"] < FAIL else "peak"


def diagnose(seq, config: TrackerConfig, max_frames: int | None = None) -> list[dict]:
    """Track ``seq`` with ``config``; one dict per frame from the second on (see module doc)."""
    gt = np.asarray(seq.groundtruth, dtype=np.float64)
    n = len(seq) if not max_frames else min(max_frames, len(seq))
    tracker = Tracker(config)
    tracker.init(seq[0], seq.first_box)
    first = [Dk.copy() for Dk in tracker._sparse.templates.dictionaries]
    rows = []
    for i in range(1, n):
        frame = seq[i]
        g = gt[i]
        has_gt = bool(np.all(np.isfinite(g)) and g[2] > 0 and g[3] > 0)
        result, detail = tracker.update_detailed(frame, probes=[g] if has_gt else None)
        if not has_gt:
            continue
        p = detail.observation.likelihood[: len(detail.particles)]
        p_gt = float(detail.probe_likelihood[0])
        r_gt = float(detail.observation.residual[len(detail.particles)])
        chosen = np.asarray(result.box)
        first_res, anchor = residuals_under(tracker, frame, [g, chosen], first)
        row = dict(
            frame=i + 1,
            overlap=float(overlap_ratio(chosen[None], g[None])[0]),
            best_particle_overlap=float(np.nanmax(overlap_ratio(detail.reported_boxes, np.repeat(g[None], len(p), 0)))),
            gt_rank=int(1 + np.sum(p > p_gt)),
            gt_likelihood=p_gt,
            chosen_likelihood=float(result.score),
            gt_residual=r_gt,
            chosen_residual=float(result.residual),
            gt_residual_first=float(first_res[0]),
            chosen_residual_first=float(first_res[1]),
            gt_anchor=float(anchor[0]),
            chosen_anchor=float(anchor[1]),
            replaced=result.template_replaced is not None,
            occluded=bool(result.occluded),
        )
        row["cls"] = classify(row)
        rows.append(row)
    return rows


def summarize(name: str, rows: list[dict]) -> str:
    ov = np.array([r["overlap"] for r in rows])
    classes = [r["cls"] for r in rows]
    failing = [c for c in classes if c]
    first_fail = next((r["frame"] for r in rows if r["cls"]), None)
    counts = {c: failing.count(c) for c in ("model", "drift", "search", "peak")}
    share = ", ".join(f"{c} {counts[c]}" for c in counts)
    repl = sum(r["replaced"] for r in rows)
    return (
        f"{name}: mean overlap {ov.mean():.3f}, {len(failing)}/{len(rows)} frames below {FAIL} "
        f"({share}); first failing frame {first_fail}; {repl} template replacements"
    )


def plot(rows: list[dict], path: Path, title: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    f = np.array([r["frame"] for r in rows])
    fig, ax = plt.subplots(3, 1, figsize=(10, 8), sharex=True)
    ax[0].plot(f, [r["overlap"] for r in rows], label="chosen box")
    ax[0].plot(f, [r["best_particle_overlap"] for r in rows], lw=0.8, alpha=0.7, label="best particle")
    colors = {"model": "tab:red", "drift": "tab:purple", "search": "tab:orange", "peak": "tab:green"}
    for c, col in colors.items():
        fr = [r["frame"] for r in rows if r["cls"] == c]
        ax[0].scatter(fr, [-0.05] * len(fr), s=6, color=col, label=c)
    ax[0].set_ylabel("IoU with ground truth")
    ax[0].legend(loc="upper right", fontsize=7, ncol=3)
    ax[1].semilogy(f, [r["gt_rank"] for r in rows])
    ax[1].set_ylabel("ground-truth rank")
    ax[2].plot(f, [r["chosen_residual"] for r in rows], label="chosen")
    ax[2].plot(f, [r["gt_residual"] for r in rows], label="ground truth")
    ax[2].plot(f, [r["gt_residual_first"] for r in rows], lw=0.8, label="ground truth, first templates")
    if any(r["gt_anchor"] or r["chosen_anchor"] for r in rows):
        ax[2].plot(f, [r["chosen_anchor"] for r in rows], lw=0.8, ls="--", label="chosen, anchor term")
        ax[2].plot(f, [r["gt_anchor"] for r in rows], lw=0.8, ls="--", label="ground truth, anchor term")
    ax[2].set_ylabel("residual")
    ax[2].set_xlabel("frame")
    ax[2].legend(fontsize=7)
    ax[0].set_title(title)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sequence")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--out", default="diagnosis")
    ap.add_argument("--frames", type=int, default=0, help="stop after N frames (0: all)")
    ap.add_argument("--config", default="{}", help="TrackerConfig fields as JSON, e.g. '{\"alpha\": 20}'")
    ap.add_argument("--paper", action="store_true", help="start from TrackerConfig.paper() instead of the defaults")
    args = ap.parse_args(argv)
    seq = open_sequence(args.sequence)
    fields = {**json.loads(args.config), "seed": args.seed}
    config = TrackerConfig.paper(**fields) if args.paper else TrackerConfig(**fields)
    rows = diagnose(seq, config, args.frames or None)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    stem = out / f"{seq.name}_seed{args.seed}"
    with open(stem.with_suffix(".csv"), "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=FIELDS)
        w.writeheader()
        w.writerows(rows)
    line = summarize(seq.name, rows)
    plot(rows, stem.with_suffix(".png"), line)
    print(line)
    return 0


if __name__ == "__main__":
    sys.exit(main())
