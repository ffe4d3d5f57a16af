"""SMTMVT against OpenCV's CSRT: frames per second on the same frames, one thread each.

Usage::

    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python bench/speed.py --sequence DIR [DIR ...] [--frames N] [--rounds R]
    OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1 python bench/speed.py --dataset DIR [--frames N] [--rounds R]

Loads the frames first (no I/O in the timing), then tracks them with ``smtmvt``
(the default :class:`smtmvt.TrackerConfig`, or ``--paper``: :meth:`~smtmvt.TrackerConfig.paper`;
with ``--config`` fields) and with ``opencv-csrt`` (OpenCV's
defaults, driven by the evaluation's adapter), alternately for ``--rounds``
rounds, with BLAS and OpenCV limited to one thread. Prints smtmvt's
milliseconds per frame for each stage (warp, features, solve, likelihood,
update, other), the fps of both (median over the rounds) and, as its last
line, ``ratio_vs_csrt=<fps_smtmvt / fps_csrt>``. The first init of each
tracker (numba compilation, OpenCV set-up) is done before timing.
With several sequences (``--sequence A B ...``, or ``--dataset DIR``: every
OTB sequence folder in it), each is measured in turn as above, then a table
of their ratios and, as the last line, their geometric mean,
``ratio_vs_csrt_geomean=``.
Nothing is asserted: speed is measured here, never in tests.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import cv2
import numpy as np
from threadpoolctl import threadpool_limits

from smtmvt import Tracker, TrackerConfig, open_sequence
from smtmvt.evaluation.trackers import make_tracker

STAGES = ("preprocess", "motion", "warp", "features", "solve", "likelihood", "update")


def run_smtmvt(frames, box, config: TrackerConfig):
    tracker = Tracker(config)
    t0 = time.perf_counter()
    tracker.init(frames[0], box)
    tracker.timings.clear()
    for f in frames[1:]:
        tracker.update(f)
    total = time.perf_counter() - t0
    return total, dict(tracker.timings)


def run_csrt(frames, box):
    tracker = make_tracker("opencv-csrt", seed=0)
    t0 = time.perf_counter()
    tracker.init(frames[0], box)
    for f in frames[1:]:
        tracker.update(f)
    return time.perf_counter() - t0


def measure(path: str, frames_max: int, rounds: int, config: TrackerConfig) -> float:
    """Print one sequence's stage table and fps; returns its ``ratio_vs_csrt``."""
    seq = open_sequence(path)
    n = min(frames_max, len(seq))
    frames = [seq[i] for i in range(n)]
    box = seq.first_box
    with threadpool_limits(limits=1):
        run_smtmvt(frames[:3], box, config)  # compile the numba kernels, warm the caches
        run_csrt(frames[:3], box)
        ours, theirs, stages = [], [], []
        for _ in range(rounds):
            total, timings = run_smtmvt(frames, box, config)
            ours.append(total)
            stages.append(timings)
            theirs.append(run_csrt(frames, box))
    updates = n - 1
    best = int(np.argsort(ours)[len(ours) // 2])  # the median round's stage split
    print(f"sequence {seq.name}: {n} frames {frames[0].shape}, {rounds} rounds, one thread")
    print("smtmvt ms/frame by stage (median round):")
    accounted = 0.0
    for stage in STAGES:
        ms = 1000 * stages[best].get(stage, 0.0) / updates
        accounted += ms
        print(f"  {stage:<11s} {ms:8.2f}")
    print(f"  {'other':<11s} {1000 * ours[best] / updates - accounted:8.2f}  (init, bookkeeping)")
    fps_ours = n / float(np.median(ours))
    fps_csrt = n / float(np.median(theirs))
    print(f"fps smtmvt {fps_ours:.2f}  (rounds: {', '.join(f'{n / t:.1f}' for t in ours)})")
    print(f"fps opencv-csrt {fps_csrt:.2f}  (rounds: {', '.join(f'{n / t:.1f}' for t in theirs)})")
    ratio = fps_ours / fps_csrt
    print(f"ratio_vs_csrt={ratio:.3f}", flush=True)
    return ratio


def sequence_folders(dataset: str) -> list[str]:
    """Every OTB sequence folder (one holding a ``groundtruth_rect*.txt``) in ``dataset``, by name."""
    root = Path(dataset)
    if not root.is_dir():
        raise SystemExit(f"speed: dataset folder {root} does not exist")
    found = sorted(str(p) for p in root.iterdir() if p.is_dir() and any(p.glob("groundtruth_rect*.txt")))
    if not found:
        raise SystemExit(f"speed: no OTB sequence folder in {root}")
    return found


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default = Path(__file__).resolve().parents[1] / ".." / "shared" / "data" / "otb" / "Crossing"
    where = ap.add_mutually_exclusive_group()
    where.add_argument("--sequence", nargs="+", default=[str(default)], help="one or more sequence folders")
    where.add_argument("--dataset", default=None, help="a folder of OTB sequences: each one is measured")
    ap.add_argument("--frames", type=int, default=120)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--config", default="{}", help="TrackerConfig fields as JSON (default: the defaults)")
    ap.add_argument("--paper", action="store_true", help="TrackerConfig.paper() (with the --config fields)")
    args = ap.parse_args()
    fields = {**json.loads(args.config), "seed": 0}
    config = TrackerConfig.paper(**fields) if args.paper else TrackerConfig(**fields)
    cv2.setNumThreads(1)
    paths = sequence_folders(args.dataset) if args.dataset else args.sequence
    ratios = {Path(p).name: measure(p, args.frames, args.rounds, config) for p in paths}
    if len(ratios) > 1:
        print("sequence      ratio_vs_csrt")
        for name, ratio in ratios.items():
            print(f"  {name:<12s} {ratio:6.3f}")
        geomean = float(np.exp(np.mean(np.log(list(ratios.values())))))
        print(f"slowest {min(ratios.values()):.3f} ({min(ratios, key=ratios.__getitem__)})")
        print(f"ratio_vs_csrt_geomean={geomean:.3f}")


if __name__ == "__main__":
    main()
