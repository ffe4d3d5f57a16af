"""Where each cue puts the size: the true box's centre scored at several sizes.

Usage::

    python bench/size_probe.py --data DIR [DIR ...] [--sequences A B ...] [--seed 0]
                               [--every 3] [--spread 0.4] [--sizes 9] [--config JSON]

Not a speed benchmark and not a test: a diagnosis of the likelihood's size
(docs/experiments.md#n61). The tracker runs each sequence as usual; on every
``--every``-th frame the ground-truth box's centre is scored as probes
(:meth:`smtmvt.Tracker.update_detailed`: coded with the frame's templates, no part
in the choice) at ``--sizes`` sizes whose log area runs evenly from
``-spread`` to ``+spread`` about the true box's (the reported box's
``report_scale`` taken out). For each probed frame and each part of the cost
(the total ``-log(likelihood) / alpha``, the sparse residual, each other cue's
cost: :attr:`smtmvt.FrameDetail.cue_costs`) the size of least cost is found.

Prints per sequence and part the mean of that size's log area ratio to the
truth (signed: negative prefers smaller boxes), its mean absolute value and
the share of frames where it is the true size; then the same over all probed
frames, with how often each size was the least (a part whose counts pile up at
the ends has no size of its own there). A part whose cost is the same at every
size of a frame (the motion and correlation cues read the centre only) is left
out of that frame, and so is the total where every probe's likelihood
underflows to 0 (a total cost over about 24 at alpha 30: a lost track). The last column is the tracker's own mean log area ratio on
the probed frames.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

import numpy as np

from smtmvt import Tracker, TrackerConfig
from smtmvt.data import open_sequence


def probe_boxes(gt_box, logs: np.ndarray, report_scale: float) -> np.ndarray:
    """``(len(logs), 4)`` boxes at ``gt_box``'s centre whose areas are its area, over
    ``report_scale ** 2``, times ``exp(logs)``."""
    x, y, w, h = (float(v) for v in gt_box)
    cx, cy = x + w / 2, y + h / 2
    f = np.exp(logs / 2) / report_scale
    return np.stack([cx - w * f / 2, cy - h * f / 2, w * f, h * f], axis=1)


def least_sizes(path: Path, config: TrackerConfig, logs: np.ndarray, every: int) -> tuple[dict, list]:
    """``({part: [log area of its least-cost size, per probed frame]}, [tracker's log area ratio])``."""
    seq = open_sequence(str(path))
    gt = np.asarray(seq.groundtruth, dtype=np.float64)
    tracker = Tracker(config)
    tracker.init(seq[0], gt[0])
    parts: dict = {}
    own = []
    for i in range(1, len(seq)):
        g = gt[i] if i < len(gt) else None
        usable = g is not None and np.all(np.isfinite(g)) and g[2] > 0 and g[3] > 0
        probes = probe_boxes(g, logs, config.report_scale) if usable and i % every == 0 else None
        result, detail = tracker.update_detailed(seq[i], probes)
        if probes is None:
            continue
        n = len(detail.particles)
        with np.errstate(divide="ignore"):
            costs = {"total": -np.log(detail.observation.likelihood[n:]) / config.alpha}
        costs["sparse"] = detail.observation.residual[n:]
        costs.update({k: np.asarray(v)[n:] for k, v in detail.cue_costs.items() if v is not None})
        for part, c in costs.items():
            c = np.where(np.isfinite(c), c, np.inf)  # not coded or invalid: never the least
            finite = c[np.isfinite(c)]
            if finite.size and finite.max() - finite.min() > 1e-12:  # the same at every size: no size
                parts.setdefault(part, []).append(float(logs[int(np.argmin(c))]))
        b = result.box
        own.append(float(np.log(b[2] * b[3] / (g[2] * g[3]))))
    return parts, own


def summary(values) -> str:
    a = np.asarray(values)
    return f"{a.mean():+.3f}/{np.abs(a).mean():.3f}/{np.mean(a == 0):.2f}"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--data", nargs="+", required=True, help="dataset folders (OTB layout)")
    ap.add_argument("--sequences", nargs="*", default=None)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--every", type=int, default=3)
    ap.add_argument("--spread", type=float, default=0.4, help="largest |log area ratio| probed")
    ap.add_argument("--sizes", type=int, default=9, help="sizes probed (odd: the true one among them)")
    ap.add_argument("--config", default="{}", help="TrackerConfig fields as JSON")
    args = ap.parse_args()
    if args.sizes < 3 or args.sizes % 2 == 0:
        ap.error(f"--sizes must be odd and at least 3, got {args.sizes}")
    logs = np.linspace(-args.spread, args.spread, args.sizes)
    logs[args.sizes // 2] = 0.0
    config = TrackerConfig(**json.loads(args.config)).replace(seed=args.seed)
    folders = [p for d in args.data for p in sorted(Path(d).iterdir()) if p.is_dir()]
    if args.sequences:
        folders = [p for p in folders if p.name in set(args.sequences)]
    every: dict = {}
    print("per part: mean / mean absolute log area ratio of the least-cost size, share at the true size")
    for path in folders:
        parts, own = least_sizes(path, config, logs, args.every)
        if not own:
            continue
        for part, v in parts.items():
            every.setdefault(part, []).extend(v)
        cells = "  ".join(f"{part} {summary(v)}" for part, v in parts.items())
        print(f"{path.name:14s} {cells}  tracker {np.mean(own):+.2f}", flush=True)
    print("over every probed frame (counts per size, smallest first):")
    for part, v in every.items():
        counts = np.bincount(np.searchsorted(logs, v), minlength=len(logs))
        print(f"{part:12s} {summary(v)}  {' '.join(str(c) for c in counts)}")


if __name__ == "__main__":
    main()
