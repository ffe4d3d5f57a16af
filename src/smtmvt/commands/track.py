"""``smtmvt track SOURCE --out RESULT.txt``: track one object through a sequence."""

from __future__ import annotations

import argparse

import numpy as np

__all__ = ["add_parser", "run_track", "parse_box"]


def parse_box(text: str) -> tuple:
    """Parse ``"x,y,w,h"`` (commas or spaces) into 4 floats.

    Raises ``argparse.ArgumentTypeError`` (a ValueError for argparse) naming the text.
    """
    parts = text.replace(",", " ").split()
    try:
        vals = tuple(float(p) for p in parts)
    except ValueError:
        vals = ()
    if len(vals) != 4 or not np.all(np.isfinite(vals)):
        raise argparse.ArgumentTypeError(f"--box must be four numbers x,y,w,h, got {text!r}")
    return vals


def add_parser(sub) -> None:
    p = sub.add_parser(
        "track",
        help="track an object through a sequence, write an OTB result file",
        description="Track one object. SOURCE is an OTB folder (img/ + groundtruth_rect.txt), a video "
        "file, a folder of images or a glob pattern. Writes one 1-based 'x,y,w,h' line per frame.",
    )
    p.add_argument("source", help="OTB folder, video file, image folder or glob pattern")
    p.add_argument("--out", required=True, help="result file (OTB format, 1-based x,y,w,h per line)")
    p.add_argument(
        "--box",
        type=parse_box,
        default=None,
        help="initial box x,y,w,h in 0-based pixels (as in the Python API); "
        "default: the first ground-truth box of SOURCE",
    )
    p.add_argument("--groundtruth", default=None, help="ground-truth file for SOURCE (OTB format)")
    p.add_argument("--seed", type=int, default=0, help="random seed (same seed, same boxes)")
    p.add_argument("--max-frames", type=int, default=None, help="stop after this many frames")
    p.add_argument("--particles", type=int, default=None, help="number of particles (default 400)")
    p.add_argument("--video", default=None, help="write an annotated video (.mp4, .avi or .gif)")
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run_track)


def run_track(args) -> int:
    from tqdm import tqdm

    from ..config import TrackerConfig
    from ..data import open_sequence, write_boxes
    from ..evaluation.metrics import overlap_ratio
    from ..tracker import Tracker, track_frames
    from ..visualize import VideoSink, draw_box

    seq = open_sequence(args.source, groundtruth=args.groundtruth)
    if args.box is not None:
        box0 = args.box
    elif seq.groundtruth is not None:
        box0 = tuple(seq.first_box)
    else:
        raise ValueError(f"{args.source}: no ground truth to start from; give --box x,y,w,h")
    n = len(seq) if args.max_frames is None else min(len(seq), args.max_frames)
    overrides = {"seed": args.seed}
    if args.particles:
        overrides["n_particles"] = args.particles
    tracker = Tracker(TrackerConfig(**overrides))

    boxes = np.full((n, 4), np.nan)
    done = 0
    sink = VideoSink(args.video) if args.video else None
    track_time = 0.0
    bar = tqdm(total=n, unit="frame", disable=args.quiet, desc=seq.name)
    try:
        for i, (frame, box, seconds) in enumerate(track_frames(tracker, (seq[i] for i in range(n)), box0)):
            boxes[i] = box
            done = i + 1
            track_time += seconds
            if sink is not None:
                img = frame
                if seq.groundtruth is not None and np.all(np.isfinite(seq.groundtruth[i])):
                    img = draw_box(img, seq.groundtruth[i], (0, 255, 0))
                sink.add(draw_box(img, box, (255, 0, 0), "smtmvt"))
            bar.update(1)
            bar.set_postfix(fps=f"{done / max(track_time, 1e-9):.1f}")
    finally:
        bar.close()
        if sink is not None:
            sink.close()
        if done:
            # Whatever was tracked is written, also after an interruption.
            write_boxes(args.out, boxes[:done])
    msg = f"{seq.name}: {n} frames, {n / max(track_time, 1e-9):.1f} fps (tracking only) -> {args.out}"
    if seq.groundtruth is not None:
        gt = seq.groundtruth[:n]
        ok = np.all(np.isfinite(gt), axis=1)
        if ok.any():
            msg += f", mean overlap {overlap_ratio(boxes[ok], gt[ok]).mean():.3f}"
    print(msg)
    return 0
