"""``smtmvt track`` on a live source: a camera, a stream, or a file played as one (``--live``).

Frames are tracked as they arrive and each frame's line is appended to ``--out`` (and
``--scores``) and flushed at once, so that a crash or Ctrl-C keeps every frame tracked
so far. ``--show`` displays each box with its confidence ("lost" when
``TrackResult.lost``); ``q`` or Esc in the window stops the run (exit 0). ``--select``
lets the user draw the first box on the first frame (``cv2.selectROI``). The run also
stops at ``--max-frames`` or when the source ends.
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import TextIO

import cv2
import numpy as np

from ..data.boxes import box_line
from ..data.live import LiveCapture, describe_source
from ..data.scores import SCORES_HEADER, scores_line

__all__ = ["run_live", "LiveWriter", "status_label", "annotate", "select_box", "WINDOW", "STOP_KEYS"]

#: The window ``--show`` and ``--select`` open.
WINDOW = "smtmvt"
#: Keys that stop a shown run: q, Q, Esc.
STOP_KEYS = (ord("q"), ord("Q"), 27)
#: RGB colours of the box: tracked, lost.
TRACKED_COLOR, LOST_COLOR = (0, 255, 0), (255, 0, 0)


class LiveWriter:
    """The result file (and scores file) written a line per frame, each flushed at once.

    The files are created (emptied) when the writer is made; :meth:`add` appends one
    frame; what was added is on disk whatever stops the process after.
    """

    def __init__(self, out, scores=None) -> None:
        self.count = 0
        self._files: list[TextIO] = []
        self._out = self._open(out)
        self._scores = self._open(scores) if scores else None
        if self._scores is not None:
            self._write(self._scores, SCORES_HEADER)

    def _open(self, path):
        path = Path(path)
        path.parent.mkdir(parents=True, exist_ok=True)
        f = open(path, "w", encoding="ascii")  # closed by close()
        self._files.append(f)
        return f

    @staticmethod
    def _write(f, line: str) -> None:
        f.write(line + "\n")
        f.flush()

    def add(self, box, confidence: float, lost: bool) -> None:
        """Append the next frame's 0-based ``box`` (and its confidence and lost flag)."""
        self.count += 1
        self._write(self._out, box_line(box))
        if self._scores is not None:
            self._write(self._scores, scores_line(self.count, box, confidence, lost))

    def close(self) -> None:
        for f in self._files:
            f.close()
        self._files = []


def status_label(confidence: float, lost: bool) -> str:
    """The text drawn beside a shown box: ``"0.93"``, or ``"lost 0.21"``."""
    return f"lost {confidence:.2f}" if lost else f"{confidence:.2f}"


def annotate(frame: np.ndarray, box, confidence: float, lost: bool) -> np.ndarray:
    """``frame`` (RGB) with ``box`` and its :func:`status_label`, as a BGR image for ``cv2.imshow``
    (green box, red when lost)."""
    from ..visualize import draw_box

    color = LOST_COLOR if lost else TRACKED_COLOR
    return np.ascontiguousarray(draw_box(frame, box, color, status_label(confidence, lost))[:, :, ::-1])


def _window_call(what: str, call, *args):
    """``call(*args)``, an OpenCV window function; an OpenCV built without windows
    (``opencv-python-headless``) raises an OSError that says so."""
    try:
        return call(*args)
    except cv2.error as exc:
        reason = str(getattr(exc, "err", None) or exc).strip().split(". ")[0]
        raise OSError(
            f"{what} needs a window, and this OpenCV cannot open one (one built without a GUI, "
            f"as opencv-python-headless, says: {reason})"
        ) from None


def select_box(frame: np.ndarray) -> tuple:
    """The box the user draws on ``frame`` (RGB) with ``cv2.selectROI``: 0-based ``(x, y, w, h)``
    floats. An empty selection (Esc, or a click without a drag) is a ValueError."""
    from ..visualize import to_display_rgb

    bgr = np.ascontiguousarray(to_display_rgb(frame)[:, :, ::-1])
    box = _window_call("--select", cv2.selectROI, WINDOW, bgr, True, False)
    x, y, w, h = (float(v) for v in box)
    if w <= 0 or h <= 0:
        raise ValueError(f"--select: no box was drawn (got {tuple(box)}); drag a box and press Enter or Space")
    return x, y, w, h


def _show(frame, box, confidence: float, lost: bool) -> bool:
    """Display one tracked frame; True when a stop key (:data:`STOP_KEYS`) was pressed."""
    _window_call("--show", cv2.imshow, WINDOW, annotate(frame, box, confidence, lost))
    key = _window_call("--show", cv2.waitKey, 1)
    return key is not None and key != -1 and (key & 0xFF) in STOP_KEYS


def _close_windows() -> None:
    try:
        cv2.destroyAllWindows()
    except cv2.error:
        pass  # nothing was opened: an OpenCV without windows


def check_live_args(args) -> None:
    """Refuse, before the source is opened, a live run that cannot start."""
    if args.box is None and not args.select:
        raise ValueError(
            f"{describe_source(args.source)}: a live source needs a first box: give --box x,y,w,h or --select"
        )
    if args.groundtruth is not None:
        raise ValueError(f"--groundtruth {args.groundtruth}: a live source has no frames to match a ground truth to")


def _frames(capture: LiveCapture, first: np.ndarray):
    """``first``, then the capture's frames until it ends (the loop's ``limit`` stops it before
    a frame past ``--max-frames`` is read)."""
    yield first
    while True:
        frame = capture.read()
        if frame is None:
            return
        yield frame


def run_live(args, tracker, check_outputs) -> int:
    """Track a live source (see the module) with ``tracker`` (a :class:`smtmvt.Tracker`: its
    ``update`` gives confidence and lost); ``check_outputs(inputs)`` refuses outputs that
    cannot be written."""
    check_live_args(args)
    check_outputs([("live source", args.source)] if Path(args.source).exists() else [])
    try:
        with LiveCapture(args.source) as capture:
            first = capture.read()
            if first is None:
                raise OSError(f"{capture.name}: no frame could be read")
            box0 = select_box(first) if args.select else args.box
            writer = LiveWriter(args.out, args.scores)
            try:
                done, seconds, why = _track_live(tracker, capture, first, box0, writer, args)
            finally:
                writer.close()
    finally:
        if args.show or args.select:
            _close_windows()
    fps = done / max(seconds, 1e-9)
    print(f"{describe_source(args.source)}: {done} frames ({why}), {fps:.1f} fps (tracking only) -> {args.out}")
    return 0


def _track_live(tracker, capture, first, box0, writer, args) -> tuple[int, float, str]:
    """``(frames tracked, seconds of tracking, why it stopped)``; on a failure or an interrupt
    the lines written stay, and the error (or a line on stderr) says how many."""
    from tqdm import tqdm

    from ..interrupts import check_stop
    from ..loop import run_loop
    from .track import _sink

    sink = _sink(args.video)
    bar = tqdm(total=args.max_frames, unit="frame", disable=args.quiet, desc=capture.name)
    seconds, why = 0.0, "end of the source"
    try:
        for step in run_loop(tracker, _frames(capture, first), box0, limit=args.max_frames):
            frame, box, lost = step.frame, step.box, step.lost
            seconds += step.seconds
            confidence = float("nan") if step.confidence is None else step.confidence
            writer.add(box, confidence, lost)
            if sink is not None:
                sink.add(annotate(frame, box, confidence, lost)[:, :, ::-1])
            bar.update(1)
            if args.show and _show(frame, box, confidence, lost):
                why = "stopped by the key"
                break
            check_stop()  # a signal whose exception compiled code dropped
        else:
            if args.max_frames is not None and writer.count >= args.max_frames:
                why = "--max-frames"
    except BaseException as exc:
        try:
            _close_sink(sink, args)
        except OSError as video_exc:
            print(video_exc, file=sys.stderr)
        where = f"after {writer.count} frames; {writer.count} lines kept in {args.out}"
        if isinstance(exc, (ValueError, OSError)):
            raise type(exc)(f"{exc} ({where})") from exc
        print(f"{capture.name}: stopped {where}", file=sys.stderr)
        raise
    finally:
        bar.close()
    _close_sink(sink, args)
    return writer.count, seconds, why


def _close_sink(sink, args) -> None:
    """Write the annotated video of the frames tracked (all of them, or up to a stop)."""
    if sink is None:
        return
    try:
        sink.close()
    except OSError as exc:
        raise OSError(f"{args.out} written; the video {args.video} failed: {exc}") from exc
