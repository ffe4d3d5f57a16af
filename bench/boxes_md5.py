"""md5 of the boxes the tracker gives, to show that a refactoring changed nothing.

For each sequence (OTB folders, and ``demo``: the demo's built-in sequence), each
seed and each configuration (``default``: ``TrackerConfig()``; ``paper``:
``TrackerConfig.paper()``), the tracker runs over the whole sequence from its
first ground-truth box and the boxes are written as ``smtmvt track`` writes them
(:func:`smtmvt.data.write_boxes`); the md5 of that text is printed, one line per
run: ``config sequence seed md5``. Run it before and after a change and ``diff``
the two outputs::

    python bench/boxes_md5.py --data ../shared/data/otb --seeds 0-2 > before.txt
    # ... change ...
    python bench/boxes_md5.py --data ../shared/data/otb --seeds 0-2 > after.txt
    diff before.txt after.txt && echo unchanged

``--configs paper`` or ``--max-frames N`` shorten it (the paper's tracker codes
all 400 candidates each frame: minutes per sequence).
"""

from __future__ import annotations

import argparse
import hashlib
import os
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from smtmvt import Tracker, TrackerConfig
from smtmvt.data import open_sequence
from smtmvt.data.boxes import box_line
from smtmvt.demo import make_demo_sequence
from smtmvt.tracker import track_frames


def parse_seeds(text: str) -> list[int]:
    """``"0-2"`` -> ``[0, 1, 2]``; ``"0,4"`` -> ``[0, 4]``."""
    if "-" in text:
        lo, hi = (int(v) for v in text.split("-", 1))
        return list(range(lo, hi + 1))
    return [int(v) for v in text.split(",")]


def config_of(name: str, seed: int) -> TrackerConfig:
    """The configuration named ``name`` (``default`` or ``paper``) with ``seed``."""
    if name == "paper":
        return TrackerConfig.paper(seed=seed)
    if name == "default":
        return TrackerConfig(seed=seed)
    raise ValueError(f"unknown configuration {name!r}: default or paper")


def boxes_md5(config: str, source: str, seed: int, max_frames: int | None) -> str:
    """One line ``config sequence seed md5`` for one run."""
    if source == "demo":
        seq = make_demo_sequence()
        frames, box, name = seq.frames, tuple(seq.groundtruth[0]), "demo"
    else:
        seq = open_sequence(source)
        frames, box, name = seq, tuple(seq.first_box), Path(source).name
    if max_frames is not None:
        frames = (f for i, f in enumerate(frames) if i < max_frames)
    tracker = Tracker(config_of(config, seed))
    text = "".join(box_line(b) + "\n" for _, b, _ in track_frames(tracker, frames, box))
    return f"{config} {name} {seed} {hashlib.md5(text.encode('ascii')).hexdigest()}"


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--data", nargs="*", default=[], help="folders of OTB sequences (each sub-folder one sequence)")
    p.add_argument("--seeds", default="0-2")
    p.add_argument("--configs", default="default,paper")
    p.add_argument("--sequences", default=None, help="comma-separated names to keep")
    p.add_argument("--no-demo", action="store_true", help="leave out the demo's sequence")
    p.add_argument("--max-frames", type=int, default=None)
    p.add_argument("--workers", type=int, default=1)
    args = p.parse_args(argv)
    sources = [] if args.no_demo else ["demo"]
    keep = None if args.sequences is None else set(args.sequences.split(","))
    for folder in args.data:
        for d in sorted(Path(folder).iterdir()):
            if d.is_dir() and (keep is None or d.name in keep):
                sources.append(str(d))
    jobs = [
        (c, s, seed, args.max_frames)
        for c in args.configs.split(",")
        for s in sources
        for seed in parse_seeds(args.seeds)
    ]
    with ProcessPoolExecutor(max_workers=max(1, args.workers)) as pool:
        for line in pool.map(boxes_md5, *zip(*jobs)):
            print(line, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
