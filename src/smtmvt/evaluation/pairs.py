"""One unit of work of a run: one tracker over one sequence (one repeat), OTB one-pass, or
over one segment of it (one TRE or SRE run: a start frame and a start box, :mod:`.protocols`).

:class:`PairTask` holds everything a worker needs (picklable: tracker factory, sequence
paths and ground truth, no pixels); :func:`run_pair` runs it and returns a
:class:`PairOutcome` (boxes and times, or an error naming tracker, sequence, frame and
file), never raising for bad data or a bad tracker.
"""

from __future__ import annotations

import contextlib
import time
import traceback
import zlib
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..data import Sequence
from ..interrupts import reraise_interruption
from ..loop import LoopPosition, run_loop
from .trackers import accepts_keyword

__all__ = ["PairTask", "PairOutcome", "run_pair", "sequence_seed", "describe"]


def sequence_seed(sequence: str, base: int = 0, repeat: int = 0) -> int:
    """Deterministic seed of a (sequence, repeat): ``crc32(name) xor base`` for repeat 0,
    ``crc32(f"{name}#{repeat}") xor base`` for the others; 31 bits."""
    text = sequence if repeat == 0 else f"{sequence}#{repeat}"
    return (zlib.crc32(text.encode("utf-8")) ^ int(base)) & 0x7FFFFFFF


@dataclass(frozen=True)
class PairTask:
    """Everything a worker needs for one (tracker, sequence, repeat); picklable.

    ``factory`` is the registry's factory (a module-level function or partial), resolved
    in the driver so that trackers registered at run time work in worker processes too.
    ``fresh_process``: run it in a new Python process (see :class:`~.trackers.TrackerSpec`).
    ``part``: ``(protocol, segment)`` of a TRE or SRE run, None for OPE; ``start``: its
    0-based first frame; ``init_box``: its 0-based start box (None: frame 0's ground
    truth). ``n_frames`` counts from ``start``. ``single_thread``: the pair runs among
    others (a pool or Dask worker): one OpenCV thread, and ``TrackerConfig.threads=None``
    means one thread (:func:`smtmvt.threads.set_default`).
    """

    tracker: str
    factory: Callable
    options: dict
    sequence: Sequence  # paths + ground truth, no pixels
    n_frames: int
    seed: int
    single_thread: bool = False
    repeat: int = 0
    fresh_process: bool = False
    part: tuple[str, str] | None = None
    start: int = 0
    init_box: tuple | None = None

    @property
    def key(self) -> tuple:
        if self.part is None:
            return (self.tracker, self.sequence.name, self.repeat)
        return (self.tracker, self.sequence.name, self.repeat, *self.part)

    @property
    def label(self) -> str:
        """``tracker / sequence`` (`` tre seg-03`` for a segment, ``#r`` for repeats after the
        first), for messages."""
        part = "" if self.part is None else f" {self.part[0]} {self.part[1]}"
        suffix = f" #{self.repeat}" if self.repeat else ""
        return f"{self.tracker} / {self.sequence.name}{part}{suffix}"


@dataclass
class PairOutcome:
    """What a worker sends back: boxes ``(n, 4)`` 0-based and seconds ``(n,)``, or an error."""

    tracker: str
    sequence: str
    n_frames: int
    boxes: np.ndarray | None = None
    times: np.ndarray | None = None
    error: str | None = None
    lost_frames: int | None = None
    wall: float = 0.0

    @property
    def ok(self) -> bool:
        return self.error is None


def describe(exc: BaseException) -> str:
    """``"TypeName: message"`` (just the type when the message is empty)."""
    text = str(exc).strip()
    return f"{type(exc).__name__}: {text}" if text else type(exc).__name__


class _Step:
    """Where :func:`run_pair` is, for its error message."""

    def __init__(self) -> None:
        self.what = "creating the tracker"
        self.frame: int | None = None


def run_pair(task: PairTask, on_frame: Callable[[int], None] | None = None) -> PairOutcome:
    """Run one tracker over one sequence (OPE). Never raises for bad data or a bad tracker:
    the failure is returned in ``PairOutcome.error``, naming tracker, sequence, frame and file.
    Ctrl-C and SIGTERM are raised, never returned as a failure, even when compiled code
    wrapped them in another exception (:mod:`smtmvt.interrupts`).

    ``on_frame(k)`` is called with the number of frames just done (for progress bars).
    """
    from ..data import SequenceError

    seq = task.sequence
    t_start = time.perf_counter()
    out = PairOutcome(task.tracker, seq.name, task.n_frames)
    if task.single_thread:
        from ..threads import set_default

        set_default(1)  # TrackerConfig.threads=None: one thread per worker (a tracker option may say more)
        with contextlib.suppress(Exception):
            import cv2

            cv2.setNumThreads(1)
    step = _Step()
    try:
        options = dict(task.options)
        if accepts_keyword(task.factory, "seed"):
            options["seed"] = task.seed
        else:
            options.pop("seed", None)
        tracker = task.factory(**options)
        out.boxes, out.times = _track(tracker, task, step, on_frame)
        out.lost_frames = getattr(tracker, "lost_frames", None)
    except SequenceError as exc:  # names the file and the frame/line itself
        reraise_interruption(exc)
        out.error = f"{task.tracker} on {out.sequence}: {exc}"
    except Exception as exc:  # noqa: BLE001 - one bad pair must never stop the run
        reraise_interruption(exc)  # Ctrl-C / SIGTERM inside compiled code: a stop, not a failure
        out.error = _error_message(task, step, exc)
    out.wall = time.perf_counter() - t_start
    return out


def _track(tracker, task: PairTask, step: _Step, on_frame) -> tuple[np.ndarray, np.ndarray]:
    """Boxes ``(n, 4)`` of frames ``start .. start + n - 1`` (the first: the start box) and
    seconds ``(n,)`` of the tracker's own calls (init, update), excluding reading the frames
    (:func:`smtmvt.loop.run_loop`)."""
    seq, n, start = task.sequence, task.n_frames, task.start
    step.what = "reading the first ground-truth box"
    first = tuple(float(v) for v in (seq.first_box if task.init_box is None else task.init_box))
    boxes = np.empty((n, 4), dtype=np.float64)
    times = np.empty(n, dtype=np.float64)
    position = LoopPosition()
    frames = (seq[start + i] for i in range(n))
    try:
        for frame_step in run_loop(tracker, frames, first, limit=n, position=position):
            boxes[frame_step.index] = frame_step.box
            times[frame_step.index] = frame_step.seconds
            if on_frame is not None:
                on_frame(1)
    except BaseException:
        if position.index is not None:  # for the error message: the frame and what failed on it
            step.frame, step.what = start + position.index, position.stage
        raise
    bad = ~np.isfinite(boxes).all(axis=1)
    if bad.any():
        step.frame, step.what = start + int(np.argmax(bad)), "checking the boxes"
        raise ValueError(f"non-finite box {boxes[step.frame - start].tolist()} returned")
    return boxes, times


def _error_message(task: PairTask, step: _Step, exc: Exception) -> str:
    seq = task.sequence
    head = f"{task.tracker} on {seq.name}"
    if task.part is not None:
        head += f" ({task.part[0]} {task.part[1]}, from frame {task.start})"
    if step.frame is None:
        msg = f"{head}: {step.what}: {describe(exc)}"
    else:
        files = getattr(seq, "files", None)
        names = seq.frame_names
        where = str(files[step.frame]) if files is not None else names[step.frame]
        msg = f"{head}: frame {step.frame} ({where}): {step.what}: {describe(exc)}"
    tb = traceback.extract_tb(exc.__traceback__)
    if tb:  # where in the code, for the tracker's author
        msg += f" [at {Path(tb[-1].filename).name}:{tb[-1].lineno}]"
    return msg
