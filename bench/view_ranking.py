"""Which view tells the target from its neighbours? An oracle check of the views.

Usage::

    python bench/view_ranking.py SEQ_DIR [SEQ_DIR ...] [--config JSON] [--frames 5:51:5]

For each listed frame of each sequence, the tracker's state is put on the ground
truth, 400 candidates are drawn around it with the tracker's own random walk, and
each candidate is scored, per view, by its nonnegative least-squares residual
over the **first frame's** dictionary (no template update, no tracking history).
Printed per sequence, and as the mean over sequences, for each view alone and
for the sum of the views (the paper's likelihood, up to the coding):

- ``iou``: the overlap with the ground truth of the candidate of least residual
  (what a tracker using only that score would choose);
- ``rho``: the Spearman correlation of ``-residual`` with the overlap over all
  candidates (how well the score ranks them).

It uses the tracker's internals (``_prepare``, ``_views``, ``_templates``): a
diagnosis tool, like ``diagnose.py``, not an API.
"""

from __future__ import annotations

import argparse
import json

import numpy as np
from scipy.stats import spearmanr

from smtmvt import Tracker, TrackerConfig, open_sequence
from smtmvt.evaluation.metrics import overlap_ratio
from smtmvt.geometry import affine_to_box, box_to_affine
from smtmvt.motion import propagate
from smtmvt.solvers.bounds import nonnegative_residuals


def rank_views(seq, config: TrackerConfig, frames: range, n: int = 400) -> np.ndarray:
    """(n_frames, K + 1, 2) float64: per frame, per view and for the sum of the views,
    (overlap of the least-residual candidate, Spearman rho of -residual with overlap)."""
    t = Tracker(config)
    t.init(seq[0], seq.first_box)
    rng = np.random.default_rng(0)
    rows = []
    for f in frames:
        if f >= len(seq):
            break
        gt = np.asarray(seq.groundtruth[f], dtype=np.float64)
        if not np.all(np.isfinite(gt)) or gt[2] <= 0 or gt[3] <= 0:
            continue
        t._state = box_to_affine(t._to_work(gt[None]))[0]
        plane_scale = t._plane_scale()
        prepared = t._prepare(seq[f], f"frame {f}", t._channels, plane_scale)
        start = np.repeat(t._state[None], n, axis=0)
        particles = propagate(start, config.affine_std, rng, None, None, config.translation_power)
        X = t._sampler.views(prepared, particles, plane_scale, t._work_box)
        D = t._sparse.templates.dictionaries
        boxes = t._from_work(np.array([affine_to_box(p) for p in particles]))
        iou = overlap_ratio(boxes, np.repeat(gt[None], n, axis=0))
        scores = [nonnegative_residuals([X[k]], [D[k]]) for k in range(len(X))]
        scores.append(np.sum(scores, axis=0))
        rows.append([(iou[np.argmin(r)], spearmanr(-r, iou)[0]) for r in scores])
    return np.array(rows, dtype=np.float64)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("sequences", nargs="+", help="OTB sequence folders")
    ap.add_argument("--config", default="{}", help="TrackerConfig fields as JSON")
    ap.add_argument("--frames", default="5:51:5", help="start:stop:step (default 5:51:5)")
    args = ap.parse_args(argv)
    config = TrackerConfig(**{"seed": 0, **json.loads(args.config)})
    frames = range(*(int(v) for v in args.frames.split(":")))
    names = [*config.views, "sum"]
    means = []
    for path in args.sequences:
        seq = open_sequence(path)
        m = rank_views(seq, config, frames).mean(axis=0)
        means.append(m)
        print(f"{seq.name:12s}" + "  ".join(f"{v}: iou {a:.2f} rho {b:+.2f}" for v, (a, b) in zip(names, m)))
    m = np.mean(means, axis=0)
    print(f"{'mean':12s}" + "  ".join(f"{v}: iou {a:.2f} rho {b:+.2f}" for v, (a, b) in zip(names, m)))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
