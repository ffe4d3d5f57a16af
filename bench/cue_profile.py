"""Per-cue cost of the default tracker: milliseconds per frame of each cue's steps.

Usage::

    python bench/cue_profile.py [SEQUENCE_DIR] [--frames 120] [--config JSON] [--threads T]

Wraps, on one tracker, each cue's :meth:`~smtmvt.cues.Cue.cost`,
:meth:`~smtmvt.cues.Cue.view_cost` and :meth:`~smtmvt.cues.Cue.learn`, the
correlation filter's response (and its judging) and the scale filter, and
prints the CPU time (``time.process_time``: other processes on the machine
do not count) of each per frame, beside the tracker's stage timings. The
wrapped calls are the tracker's own, so the boxes are unchanged. Speed is
measured here, never asserted by tests; see bench/README.md for the floors.
"""

from __future__ import annotations

import argparse
import json
import time
from collections import defaultdict
from pathlib import Path

import numpy as np

from smtmvt import Tracker, TrackerConfig

SPENT: defaultdict[str, float] = defaultdict(float)


def timed(name: str, fn):
    def wrapper(*args, **kwargs):
        t0 = time.process_time()
        try:
            return fn(*args, **kwargs)
        finally:
            SPENT[name] += time.process_time() - t0

    return wrapper


def instrument(tracker: Tracker) -> None:
    """Wrap the steps of the tracker's cues (after ``init``)."""
    for cue in tracker.cues:
        for step in ("cost", "view_cost", "learn"):
            setattr(cue, step, timed(f"{cue.name}.{step}", getattr(cue, step)))
        if cue.name == "correlation":
            cue.respond = timed("correlation.respond", cue.respond)
            cue.judge = timed("correlation.judge", cue.judge)
    scaler = tracker._scaler
    if scaler is not None:
        scaler.rescale = timed("scale_filter.rescale", scaler.rescale)
        scaler.update = timed("scale_filter.update", scaler.update)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("source", nargs="?", default=None)
    ap.add_argument("--frames", type=int, default=120)
    ap.add_argument("--config", default="{}", help="TrackerConfig fields as JSON")
    args = ap.parse_args()
    from bench_tracker import load_frames

    name, frames, box0 = load_frames(args.source, args.frames)
    config = TrackerConfig(**{"seed": 0, **json.loads(args.config)})
    tracker = Tracker(config)
    tracker.init(frames[0], box0)
    for f in frames[1:4]:  # compile the kernels
        tracker.update(f)
    tracker.init(frames[0], box0)
    instrument(tracker)
    SPENT.clear()
    tracker.timings.clear()
    t0 = time.process_time()
    for f in frames[1:]:
        tracker.update(f)
    total = time.process_time() - t0
    n = len(frames) - 1
    print(f"sequence {name}: {n} updates, {1000 * total / n:.2f} ms/frame CPU ({n / total:.2f} fps CPU)")
    print("stages (wall, nested stages counted in each):")
    for stage, seconds in sorted(tracker.timings.items()):
        print(f"  {stage:<12s} {1000 * seconds / n:8.2f} ms/frame")
    print("cue steps (CPU):")
    for step, seconds in sorted(SPENT.items(), key=lambda kv: -kv[1]):
        print(f"  {step:<24s} {1000 * seconds / n:8.3f} ms/frame")


if __name__ == "__main__":
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parent))
    np.set_printoptions(precision=3)
    main()
