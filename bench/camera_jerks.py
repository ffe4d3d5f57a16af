"""The demo sequence seen by a jerky or a following camera: ``camera_motion`` on and off.

Usage::

    python bench/camera_jerks.py [--seeds 8] [--frames 120] [--config JSON]

Not a speed benchmark and not a test: a synthetic third check of
``TrackerConfig.camera_motion`` (docs/experiments.md#n60), beside the two
halves of the measuring sequences. Each demo sequence (``smtmvt.demo``, seed
``s``) is seen through a camera whose window moves over it (the frame padded
by reflection and cropped again, the ground truth moved with it):

* ``jerks``: the window jumps at 4 frames drawn at random, each time by 25-45 px
  across and 10-25 px up or down (kept until the next jump): a hand-held camera;
* ``follow``: the window follows the target, which stays where it started
  while the background moves under it (a camera panning with a runner), the
  case where taking the camera's move out of the target's is wrong;
* ``follow+jerks``: both;
* ``background-jerks``: the jerks of ``jerks`` with the target's box pasted back
  where it was: only the background jumps (a camera that keeps a fast target
  in place), the case where following the camera is wrong and the filter must
  refuse it.

Prints the mean overlap per variant and configuration over the seeds, and
per seed, the configuration given by ``--config`` (default: the default
tracker) with ``camera_motion`` on and off.
"""

from __future__ import annotations

import argparse
import json

import cv2
import numpy as np
from scale_change import run  # a script beside this one: bench/ is on the path

from smtmvt import TrackerConfig
from smtmvt.demo import make_demo_sequence

VARIANTS = ("jerks", "follow", "follow+jerks", "background-jerks")


def camera_offsets(variant: str, centres: np.ndarray, rng: np.random.Generator) -> np.ndarray:
    """The window's offset ``(dx, dy)`` per frame, ``(T, 2)`` pixels: the content
    of frame ``i`` moves by ``-offset[i]``."""
    T = len(centres)
    offsets = np.zeros((T, 2))
    if "follow" in variant:
        offsets += centres - centres[0]
    if "jerks" in variant:
        jumps = np.zeros((T, 2))
        for at in rng.choice(np.arange(5, T), size=4, replace=False):
            jumps[at] = rng.uniform(25, 45) * rng.choice([-1, 1]), rng.uniform(10, 25) * rng.choice([-1, 1])
        offsets += np.cumsum(jumps, axis=0)
    return offsets


def seen(frames: np.ndarray, boxes: np.ndarray, offsets: np.ndarray, still: bool = False) -> tuple[list, np.ndarray]:
    """The frames seen through the moved window (reflected at the borders) and
    the boxes in them; with ``still`` the target's box is pasted back where it
    was (only the background moves) and the boxes stay."""
    out = []
    for f, (dx, dy), b in zip(frames, offsets, boxes):
        M = np.float32([[1, 0, -dx], [0, 1, -dy]])
        g = cv2.warpAffine(f, M, (f.shape[1], f.shape[0]), borderMode=cv2.BORDER_REFLECT)
        if still:
            x0, y0 = max(0, int(np.floor(b[0]))), max(0, int(np.floor(b[1])))
            x1, y1 = int(np.ceil(b[0] + b[2])), int(np.ceil(b[1] + b[3]))
            g[y0:y1, x0:x1] = f[y0:y1, x0:x1]
        out.append(g)
    if still:
        return out, boxes.copy()
    moved = boxes.copy()
    moved[:, :2] -= offsets
    return out, moved


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, default=8)
    ap.add_argument("--frames", type=int, default=120)
    ap.add_argument("--config", default="{}", help="TrackerConfig fields as JSON (camera_motion is set here)")
    args = ap.parse_args()
    base = TrackerConfig(**json.loads(args.config))
    scores: dict = {(v, on): [] for v in VARIANTS for on in (True, False)}
    for s in range(args.seeds):
        demo = make_demo_sequence(n_frames=args.frames, seed=s)
        gt = np.asarray(demo.groundtruth, dtype=np.float64)
        centres = gt[:, :2] + gt[:, 2:] / 2
        for v in VARIANTS:
            offsets = camera_offsets(v.replace("background-", ""), centres, np.random.default_rng(1000 + s))
            frames, truth = seen(demo.frames, gt, offsets, still=v.startswith("background"))
            for on in (True, False):
                scores[v, on].append(run(frames, truth, base.replace(camera_motion=on, seed=s))[0])
            print(f"seed {s} {v:16s} on {scores[v, True][-1]:.3f}  off {scores[v, False][-1]:.3f}", flush=True)
    print("variant           camera_motion on   off")
    for v in VARIANTS:
        print(f"{v:16s}  {np.mean(scores[v, True]):.3f}  {np.mean(scores[v, False]):.3f}")


if __name__ == "__main__":
    main()
