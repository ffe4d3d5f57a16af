"""``smtmvt track SOURCE --out RESULT.txt``: track one object through a sequence."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from .args import check_writable, positive_int, same_file

__all__ = ["add_parser", "run_track", "parse_box", "check_outputs", "check_output_paths"]


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
        "file, a folder of images or a glob pattern: one 1-based 'x,y,w,h' line per frame is written "
        "once every frame is tracked (an interrupted or failed run writes nothing). SOURCE may also be "
        "live: a camera index (0), a stream URL (rtsp://, http://) or, with --live, anything "
        "cv2.VideoCapture opens; a live run appends each frame's line as it is tracked.",
    )
    p.add_argument("source", help="OTB folder, video file, image folder, glob pattern, camera index or stream URL")
    p.add_argument("--out", required=True, help="result file (OTB format, 1-based x,y,w,h per line)")
    p.add_argument(
        "--live",
        action="store_true",
        help="read SOURCE as a live source (frames as cv2.VideoCapture gives them, lines written as they "
        "are tracked), even when it is a file",
    )
    p.add_argument("--show", action="store_true", help="live source: show each box and its confidence; q or Esc stops")
    first = p.add_mutually_exclusive_group()
    first.add_argument(
        "--select", action="store_true", help="live source: draw the first box on the first frame with the mouse"
    )
    first.add_argument(
        "--box",
        type=parse_box,
        default=None,
        help="initial box x,y,w,h in 0-based pixels (as in the Python API); "
        "default: the first ground-truth box of SOURCE",
    )
    p.add_argument("--groundtruth", default=None, help="ground-truth file for SOURCE (OTB format)")
    p.add_argument("--seed", type=int, default=0, help="random seed (same seed, same boxes)")
    p.add_argument("--max-frames", type=positive_int, default=None, help="stop after this many frames")
    p.add_argument("--particles", type=positive_int, default=None, help="number of particles (default 400)")
    p.add_argument("--video", default=None, help="write an annotated video (.mp4, .avi or .gif)")
    p.add_argument(
        "--scores",
        default=None,
        help="also write a CSV file with a header and one 'frame,x,y,w,h,confidence,lost' line per frame "
        "(1-based frame and box; confidence in [0, 1], lost 0 or 1; the first frame's: 1, 0)",
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=run_track)


def check_outputs(args, seq) -> None:
    """Refuse, before any tracking, outputs that cannot be written or would destroy inputs.

    ``--out`` and ``--video`` must be creatable, differ from each other and from the
    sequence's ground truth and frame files; ``--video`` must be a type we write.
    """
    inputs = [("ground truth", f) for f in (seq.groundtruth_file, args.groundtruth) if f is not None]
    inputs += [("frame file", f) for f in getattr(seq, "files", [seq.source])]
    check_output_paths(args, inputs)


def check_output_paths(args, inputs) -> None:
    """:func:`check_outputs` against ``inputs``, ``[(what, path)]`` that no output may be."""
    from ..visualize import VIDEO_OUTPUTS

    outputs = [("--out", args.out)] + [(option, path) for option, path in _extra_outputs(args) if path]
    for option, path in outputs:
        check_writable(path, option)
        for kind, source in inputs:
            if same_file(path, source):
                raise ValueError(f"{option} {path} is the sequence's {kind}: refusing to write over it")
    if args.video and Path(args.video).suffix.lower() not in VIDEO_OUTPUTS:
        raise ValueError(f"--video {args.video}: unsupported type (use {', '.join(VIDEO_OUTPUTS)})")
    for i, (option, path) in enumerate(outputs):
        for other, other_path in outputs[:i]:
            if same_file(path, other_path):
                raise ValueError(f"{option} and {other} are the same file: {path}")


def _extra_outputs(args) -> list[tuple[str, str | None]]:
    """``[(option, path or None)]`` of the outputs besides ``--out``."""
    return [("--video", args.video), ("--scores", getattr(args, "scores", None))]


def _tracker(args):
    """The tracker the options ask for (``--seed``, ``--particles``)."""
    from ..config import TrackerConfig
    from ..tracker import Tracker

    overrides = {"seed": args.seed}
    if args.particles:
        overrides["n_particles"] = args.particles
    return Tracker(TrackerConfig(**overrides))


def run_track(args) -> int:
    """``smtmvt track``: a live source (:mod:`smtmvt.commands.live`), or a sequence tracked whole."""
    from ..data.live import is_live_source
    from .live import run_live

    if args.live or is_live_source(args.source):
        return run_live(args, _tracker(args), lambda inputs: check_output_paths(args, inputs))
    for option in ("show", "select"):
        if getattr(args, option, False):
            raise ValueError(
                f"--{option} works on a live source (a camera index, a stream URL); "
                f"add --live to play {args.source} as one"
            )
    return _track_sequence(args)


def _track_sequence(args) -> int:
    from ..data import open_sequence, write_boxes
    from ..data.scores import write_scores

    seq = open_sequence(args.source, groundtruth=args.groundtruth)
    if args.box is not None:
        box0 = args.box
    elif seq.groundtruth is not None:
        box0 = tuple(seq.first_box)
    else:
        raise ValueError(f"{args.source}: no ground truth to start from; give --box x,y,w,h")
    check_outputs(args, seq)
    n = len(seq) if args.max_frames is None else min(len(seq), args.max_frames)
    tracker = _tracker(args)
    sink = _sink(args.video)
    boxes, confidence, lost, track_time = _track_all(tracker, seq, n, box0, sink, args)
    write_boxes(args.out, boxes)  # complete: every frame has its box
    if args.scores:
        try:
            write_scores(args.scores, boxes, confidence, lost)
        except OSError as exc:
            raise OSError(f"{args.out} written; the scores file {args.scores} failed: {exc}") from exc
    if sink is not None:
        try:
            sink.close()
        except OSError as exc:
            raise OSError(f"{args.out} written; the video {args.video} failed: {exc}") from exc
    print(_summary(seq, n, boxes, track_time, args.out))
    return 0


def _sink(path):
    from ..visualize import VideoSink

    return VideoSink(path) if path else None


def _track_all(tracker, seq, n, box0, sink, args):
    """``(boxes (n, 4) 0-based, confidence (n,), lost (n,), seconds of tracking)`` (the first
    frame's confidence and lost: 1.0, False); on any failure nothing is kept and the error says
    how far it got and that ``--out`` was not written."""
    from tqdm import tqdm

    from ..interrupts import check_stop
    from ..loop import run_loop
    from ..visualize import draw_box

    boxes = np.full((n, 4), np.nan)
    confidence = np.full(n, np.nan)
    lost = np.zeros(n, dtype=bool)
    done, track_time = 0, 0.0
    bar = tqdm(total=n, unit="frame", disable=args.quiet, desc=seq.name)
    try:
        for step in run_loop(tracker, (seq[i] for i in range(n)), box0, limit=n):
            i = step.index
            boxes[i], lost[i] = step.box, step.lost
            confidence[i] = np.nan if step.confidence is None else step.confidence
            done, track_time = i + 1, track_time + step.seconds
            if sink is not None:
                img = step.frame
                if seq.groundtruth is not None and np.all(np.isfinite(seq.groundtruth[i])):
                    img = draw_box(img, seq.groundtruth[i], (0, 255, 0))
                sink.add(draw_box(img, step.box, (255, 0, 0), "smtmvt"))
            bar.update(1)
            bar.set_postfix(fps=f"{done / max(track_time, 1e-9):.1f}")
            check_stop()  # a signal whose exception compiled code dropped
    except BaseException as exc:
        if sink is not None:
            sink.discard()
        where = f"after {done} of {n} frames; nothing written to {args.out}"
        if isinstance(exc, (ValueError, OSError)):
            raise type(exc)(f"{exc} ({where})") from exc
        print(f"{seq.name}: stopped {where}", file=sys.stderr)
        raise
    finally:
        bar.close()
    return boxes, confidence, lost, track_time


def _summary(seq, n, boxes, track_time, out) -> str:
    from ..evaluation.metrics import overlap_ratio

    msg = f"{seq.name}: {n} frames, {n / max(track_time, 1e-9):.1f} fps (tracking only) -> {out}"
    if seq.groundtruth is not None:
        gt = seq.groundtruth[:n]
        ok = np.all(np.isfinite(gt), axis=1)
        if ok.any():
            msg += f", mean overlap {overlap_ratio(boxes[ok], gt[ok]).mean():.3f}"
    return msg
