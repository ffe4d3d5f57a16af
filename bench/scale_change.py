"""The demo sequence seen by a zooming camera: how well the box's size follows the target.

Usage::

    python bench/scale_change.py [--seeds 3] [--frames 150] [--ends 0.25,3,1]
                                 [--configs '{"default": {}, "refine": {"scale_refine": 2}}']

Not a speed benchmark and not a test: a synthetic third check of the
tracker's scale (issue 48 item 3; docs/experiments.md#n61), beside the two
halves of the measuring sequences. Each demo sequence (``smtmvt.demo``, seed
``s``) is seen through a camera that zooms about the target, steadily in the
log: frame ``i`` of ``T`` is the demo's frame scaled by ``end ** (i / (T - 1))``
(``end`` 0.25: the target ends at a quarter of its first width and height, a
sixteenth of its area; 3: three times them) about the target's centre, which
moves toward the frame's centre by ``1 - factor`` of the way (the borders
reflected), and the ground truth with it. ``end`` 1 is the demo as it is.

Prints, per end, seed and configuration, the mean overlap, that of the last
third of the frames and the last frame's log area ratio (tracked over true),
then the mean overlap per end and configuration over the seeds.
"""

from __future__ import annotations

import argparse
import json

import cv2
import numpy as np

from smtmvt import Tracker, TrackerConfig
from smtmvt.demo import make_demo_sequence
from smtmvt.evaluation.metrics import overlap_ratio
from smtmvt.tracker import track_frames


def zoomed(frames, boxes: np.ndarray, end: float) -> tuple[list, np.ndarray]:
    """``frames`` (T of (H, W, 3)) and their 0-based ``boxes`` (T, 4) seen by a camera
    zooming by ``end ** (i / (T - 1))`` about the target's centre, which moves
    toward the frame's centre by ``1 - factor`` of the way: the frames and the
    boxes in them."""
    T = len(frames)
    out, moved = [], []
    for i, (f, b) in enumerate(zip(frames, boxes)):
        s = end ** (i / max(T - 1, 1))
        H, W = f.shape[:2]
        cx, cy = b[0] + b[2] / 2, b[1] + b[3] / 2
        to_x, to_y = cx * s + W / 2 * (1 - s), cy * s + H / 2 * (1 - s)
        M = np.float32([[s, 0, to_x - s * cx], [0, s, to_y - s * cy]])
        flags = cv2.INTER_AREA if s < 1 else cv2.INTER_LINEAR
        out.append(cv2.warpAffine(f, M, (W, H), flags=flags, borderMode=cv2.BORDER_REFLECT))
        moved.append([to_x - s * b[2] / 2, to_y - s * b[3] / 2, s * b[2], s * b[3]])
    return out, np.asarray(moved)


def run(frames, truth: np.ndarray, config: TrackerConfig) -> tuple[float, float, float]:
    """Mean overlap, mean overlap of the last third, last frame's log area ratio."""
    boxes = np.array([box for _, box, _ in track_frames(Tracker(config), frames, truth[0])])
    ov = overlap_ratio(boxes, truth)
    last = np.log(boxes[-1, 2] * boxes[-1, 3] / (truth[-1, 2] * truth[-1, 3]))
    return float(ov.mean()), float(ov[-max(1, len(ov) // 3) :].mean()), float(last)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=3)
    ap.add_argument("--frames", type=int, default=150)
    ap.add_argument("--ends", default="0.25,3,1", help="comma-separated zoom factors at the last frame")
    ap.add_argument(
        "--configs",
        default='{"default": {}, "refine": {"scale_refine": 2}}',
        help="JSON {name: TrackerConfig fields}",
    )
    args = ap.parse_args()
    configs = json.loads(args.configs)
    ends = [float(e) for e in args.ends.split(",")]
    means: dict = {(e, name): [] for e in ends for name in configs}
    for end in ends:
        for s in range(args.seeds):
            demo = make_demo_sequence(n_frames=args.frames, seed=s)
            frames, truth = zoomed(demo.frames, np.asarray(demo.groundtruth, dtype=np.float64), end)
            for name, fields in configs.items():
                ao, tail, last = run(frames, truth, TrackerConfig(**fields).replace(seed=s))
                means[end, name].append(ao)
                print(
                    f"end {end:g} seed {s} {name:12s} ao {ao:.3f}  last third {tail:.3f}  last log area {last:+.2f}",
                    flush=True,
                )
    print("end    " + "".join(f"{name:>14s}" for name in configs))
    for end in ends:
        print(f"{end:<6g} " + "".join(f"{np.mean(means[end, name]):14.3f}" for name in configs))


if __name__ == "__main__":
    main()
