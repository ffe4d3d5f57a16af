"""The one loop that drives a tracker over a sequence: ``init`` on the first frame with the
start box, ``update`` on each of the rest.

``smtmvt track`` (a sequence or a live source), ``smtmvt evaluate`` (each pair of
:mod:`smtmvt.evaluation.pairs`, and so the bench's sweep) and :func:`smtmvt.tracker.track_frames`
all run it; what differs between them is what they do with each :class:`FrameStep`
(write a line, draw a frame, advance a progress bar), which stays with them.

The tracker is anything with ``init(frame, box)`` and ``update(frame)``; ``update`` may
return a :class:`~smtmvt.results.TrackResult` (its ``box``, ``confidence`` and ``lost``
are used) or the box itself (four numbers: the adapters of :mod:`smtmvt.evaluation.trackers`).
"""

from __future__ import annotations

import time
from collections.abc import Iterable, Iterator
from dataclasses import dataclass

import numpy as np

from .interrupts import check_stop

__all__ = ["FrameStep", "LoopPosition", "run_loop"]


@dataclass(frozen=True)
class FrameStep:
    """One frame of :func:`run_loop`.

    index : 0-based position of the frame in the frames given (not in the file's sequence).
    frame : the frame as read, ``(H, W)`` or ``(H, W, 3)``.
    box : ``(4,)`` float64, 0-based ``(x, y, w, h)`` pixels; on the first frame the start box.
    seconds : wall seconds spent in ``init`` / ``update`` only (reading the frame is not counted).
    confidence : ``TrackResult.confidence`` in [0, 1]; 1.0 on the first frame; None when
        the tracker's ``update`` returns a bare box.
    lost : ``TrackResult.lost``; False on the first frame and for a bare box.
    """

    index: int
    frame: np.ndarray
    box: np.ndarray
    seconds: float
    confidence: float | None
    lost: bool


class LoopPosition:
    """Where :func:`run_loop` is, for the caller's error messages: ``index`` (0-based, as
    :attr:`FrameStep.index`; None before the first frame) and ``stage``: ``"reading"`` the
    frame or ``"tracking"`` it."""

    def __init__(self) -> None:
        self.index: int | None = None
        self.stage = "starting"


def run_loop(
    tracker,
    frames: Iterable[np.ndarray],
    box,
    *,
    limit: int | None = None,
    position: LoopPosition | None = None,
) -> Iterator[FrameStep]:
    """Run ``tracker`` over ``frames``, yielding one :class:`FrameStep` per frame.

    Parameters
    ----------
    tracker : an object with ``init(frame, box)`` and ``update(frame)`` (see the module).
    frames : iterable of frames, read lazily one at a time (a reading error is raised with
        ``position.stage == "reading"``).
    box : 0-based ``(x, y, w, h)`` pixels, the target in the first frame (four finite numbers).
    limit : stop after this many frames (None: all of them).
    position : updated before each frame is read and tracked, so that a caller catching an
        error knows the frame and the stage it failed in.

    Raises
    ------
    ValueError
        ``update`` returned something other than four numbers (``position`` names the frame).

    A Ctrl-C or SIGTERM whose exception compiled code dropped is raised before each frame
    (:func:`smtmvt.interrupts.check_stop`).
    """
    where = position if position is not None else LoopPosition()
    first = np.array([float(v) for v in box], dtype=np.float64)
    if first.shape != (4,):
        raise ValueError(f"start box {box!r}: expected four numbers x, y, w, h")
    it = iter(frames)
    i = 0
    while limit is None or i < limit:
        check_stop()
        where.index, where.stage = i, "reading"
        try:
            frame = next(it)
        except StopIteration:
            return
        where.stage = "tracking"
        t0 = time.perf_counter()
        if i == 0:
            tracker.init(frame, tuple(float(v) for v in first))
            seconds = time.perf_counter() - t0
            yield FrameStep(0, frame, first.copy(), seconds, 1.0, False)
        else:
            result = tracker.update(frame)
            seconds = time.perf_counter() - t0
            yield _step(i, frame, result, seconds)
        i += 1


def _step(i: int, frame: np.ndarray, result, seconds: float) -> FrameStep:
    """The :class:`FrameStep` of what ``update`` returned: a TrackResult or a bare box."""
    raw = getattr(result, "box", result)
    out = np.asarray(raw, dtype=np.float64).reshape(-1)
    if out.shape != (4,):
        raise ValueError(f"update() returned {out.size} numbers, expected x, y, w, h")
    confidence = getattr(result, "confidence", None)
    lost = bool(getattr(result, "lost", False))
    return FrameStep(i, frame, out, seconds, None if confidence is None else float(confidence), lost)
