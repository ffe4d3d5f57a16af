"""Tracker speed: frames per second and time per stage on a real sequence.

Usage::

    python bench/bench_tracker.py [SEQUENCE_DIR] [--frames 60] [--particles 400]

Default sequence: ../shared/data/otb/Crossing when present, else the built-in
demo sequence. Prints fps (tracking only, frames already in memory) and the
milliseconds per frame of each stage (preprocess = Tan-Triggs, warp, features,
solve, update). Nothing is asserted: speed is measured here, never in tests.
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from smtmvt import Tracker, TrackerConfig


def load_frames(source: str | None, n: int):
    default = Path(__file__).resolve().parents[1] / ".." / "shared" / "data" / "otb" / "Crossing"
    if source is None and default.exists():
        source = str(default)
    if source is None:
        from smtmvt.demo import make_demo_sequence

        seq = make_demo_sequence(n_frames=n)
        return "demo", list(seq.frames[:n]), seq.groundtruth[0]
    from smtmvt.data import open_sequence

    seq = open_sequence(source)
    n = min(n, len(seq))
    return seq.name, [seq[i] for i in range(n)], seq.first_box


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("source", nargs="?", default=None)
    ap.add_argument("--frames", type=int, default=60)
    ap.add_argument("--particles", type=int, default=400)
    args = ap.parse_args()

    name, frames, box0 = load_frames(args.source, args.frames)
    tracker = Tracker(TrackerConfig(n_particles=args.particles, seed=0))
    t0 = time.perf_counter()
    tracker.init(frames[0], box0)
    t_init = time.perf_counter() - t0
    tracker.timings.clear()
    t0 = time.perf_counter()
    for f in frames[1:]:
        tracker.update(f)
    total = time.perf_counter() - t0
    n = len(frames) - 1
    print(f"sequence {name}: {n} updates, n={args.particles} particles, frame {frames[0].shape}")
    print(f"init: {1000 * t_init:.1f} ms")
    print(f"fps (tracking only): {n / total:.2f}  ({1000 * total / n:.1f} ms/frame)")
    accounted = 0.0
    for stage in ("preprocess", "warp", "features", "solve", "update"):
        ms = 1000 * tracker.timings.get(stage, 0.0) / n
        accounted += ms
        print(f"  {stage:<10s} {ms:8.2f} ms/frame")
    print(f"  {'other':<10s} {1000 * total / n - accounted:8.2f} ms/frame (motion, likelihood, resampling)")


if __name__ == "__main__":
    np.set_printoptions(precision=3)
    main()
